#include "mpmshock/run_directory.hpp"

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
  const std::string name = p.filename().string();
  int k = -1;
  char tail[8] = {0};
  if (std::sscanf(name.c_str(), "snapshot_%d.%7s", &k, tail) == 2 && std::string(tail) == "h5") return k;
  return -1;
}

bool is_run_output(const fs::path& p) {
  const std::string name = p.filename().string();
  for (const char* own : {"regions.csv", "conservation.csv", "summary.json", "scene.txt", "voids.csv", kXdmfName})
    if (name == own) return true;
  return name.rfind("snapshot_", 0) == 0 && (p.extension() == ".h5" || p.extension() == ".tmp");
}

void prepare_output_dir(const Scene& scene, bool force) {
  const std::string& dir = scene.output_dir;
  const std::string key = scene.where("output_dir") + ": key 'output_dir': ";
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw SceneError(key + "'" + dir + "' exists and is not a directory");
    std::vector<fs::path> earlier;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (is_run_output(entry.path())) earlier.push_back(entry.path());
    if (!earlier.empty() && !force)
      throw SceneError(key + "'" + dir + "' holds the outputs of an earlier run; pass --force to replace them, or " +
                       "choose another output_dir");
    for (const fs::path& p : earlier) fs::remove(p, ec);
  } else {
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create output_dir '" + dir + "': " + ec.message());
  }
  // Fail now, not after an hour of computing, if the directory cannot be written.
  const fs::path probe = fs::path(dir) / ".mpmshock-write-test";
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) throw std::runtime_error("output_dir '" + dir + "' is not writable");
  std::fclose(f);
  fs::remove(probe, ec);
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

void write_voids(const fs::path& path, const BodySummary& flyer, const BodySummary& target) {
  File f = open_output(path);
  std::fprintf(f.get(), "body,x,y,radius\n");
  for (const BodySummary* b : {&flyer, &target})
    for (const Void& v : b->voids) std::fprintf(f.get(), "%s,%.17g,%.17g,%.17g\n", b->name.c_str(), v.x, v.y, v.r);
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
