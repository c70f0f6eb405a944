#include "mpmshock/run_directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <vector>

namespace mpmshock {

std::string snapshot_name(int index) {
  char name[64];
  std::snprintf(name, sizeof name, "snapshot_%05d.h5", index);
  return name;
}

int snapshot_number(const fs::path& p) {
  // Exactly snapshot_ + at least five digits + .h5, as snapshot_name writes them.
  const std::string name = p.filename().string();
  const std::string prefix = "snapshot_", suffix = ".h5";
  if (name.size() < prefix.size() + 5 + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stoi(digits);
}

bool is_run_output(const fs::path& p) {
  std::string name = p.filename().string();
  // Our temporary files are our names plus .tmp.
  if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) name.erase(name.size() - 4);
  for (const char* own : {"regions.csv", "conservation.csv", "probes.csv", "summary.json", "scene.txt", "voids.csv",
                          "log.txt", kXdmfName})
    if (name == own) return true;
  return snapshot_number(name) >= 0;
}

DirectoryLock::DirectoryLock(const fs::path& dir, const std::string& where) {
  const fs::path path = dir / ".mpmshock.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot create " + path.string() + " (is the directory writable?)");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char pid[32] = {0};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    ::close(fd_);
    fd_ = -1;
    throw SceneError(where + "'" + dir.string() + "' is in use by another mpmshock run" +
                     (n > 0 ? " (pid " + std::string(pid, static_cast<std::size_t>(n)) + ")" : std::string()) +
                     "; wait for it to finish, or choose another output_dir");
  }
  const std::string me = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
    // The pid is only for the message of a run that is refused; the lock itself holds.
  }
}

DirectoryLock& DirectoryLock::operator=(DirectoryLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

DirectoryLock prepare_output_dir(const Scene& scene, bool force) {
  const std::string& dir = scene.output_dir;
  const std::string key = scene.where("output_dir") + ": key 'output_dir': ";
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw SceneError(key + "'" + dir + "' exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create output_dir '" + dir + "': " + ec.message());
  DirectoryLock lock(dir, key);
  std::vector<fs::path> earlier;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (is_run_output(entry.path())) earlier.push_back(entry.path());
  if (!earlier.empty() && !force)
    throw SceneError(key + "'" + dir + "' holds the outputs of an earlier run; pass --force to replace them, or " +
                     "choose another output_dir");
  for (const fs::path& p : earlier) fs::remove(p, ec);
  // Fail now, not after an hour of computing, if the directory cannot be written.
  const fs::path probe = fs::path(dir) / ".mpmshock-write-test";
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) throw std::runtime_error("output_dir '" + dir + "' is not writable");
  std::fclose(f);
  fs::remove(probe, ec);
  return lock;
}

File open_output(const fs::path& path, const char* mode) {
  File f(std::fopen(path.c_str(), mode));
  if (!f) throw std::runtime_error("cannot open " + path.string() + " for writing");
  return f;
}

void flush_or_throw(std::FILE* f, const std::string& what) {
  if (std::fflush(f) != 0 || std::ferror(f)) throw std::runtime_error("cannot write " + what + " (disk full?)");
}

void write_text(const fs::path& path, const std::string& text) {
  File f = open_output(path);
  std::fputs(text.c_str(), f.get());
  flush_or_throw(f.get(), path.string());
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  write_text(tmp, text);
  fs::rename(tmp, path);
}

void write_voids(const fs::path& path, const BodySummary& flyer, const BodySummary& target, int dimension) {
  File f = open_output(path);
  std::fprintf(f.get(), dimension == 3 ? "body,x,y,z,radius\n" : "body,x,y,radius\n");
  for (const BodySummary* b : {&flyer, &target})
    for (const Void& v : b->voids) {
      if (dimension == 3) std::fprintf(f.get(), "%s,%.17g,%.17g,%.17g,%.17g\n", b->name.c_str(), v.x, v.y, v.z, v.r);
      else std::fprintf(f.get(), "%s,%.17g,%.17g,%.17g\n", b->name.c_str(), v.x, v.y, v.r);
    }
  flush_or_throw(f.get(), path.string());
}

namespace {

// A CSV row whose time (first column) is after t; rows carry 10 significant digits of time.
bool row_after(const std::string& line, double t) { return std::strtod(line.c_str(), nullptr) > t * (1.0 + 1e-9); }

}  // namespace

std::size_t count_rows_after(const fs::path& path, double t) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::size_t n = 0;
  while (std::getline(in, line)) n += row_after(line, t);
  return n;
}

std::size_t truncate_rows_after(const fs::path& path, double t) {
  std::ifstream in(path);
  if (!in) return 0;
  std::string line, kept;
  std::size_t dropped = 0;
  bool header = true;
  while (std::getline(in, line)) {
    if (header) {
      kept += line + "\n";
      header = false;
      continue;
    }
    if (!row_after(line, t)) kept += line + "\n";
    else ++dropped;
  }
  in.close();
  if (dropped > 0) write_text_atomically(path, kept);
  return dropped;
}

}  // namespace mpmshock
