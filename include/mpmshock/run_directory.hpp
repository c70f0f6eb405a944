// The files of a run directory: their names, which of them are ours, creating and clearing the
// directory, and the small text files (scene.txt, voids.csv) and CSV edits a restart needs.
// Failures of the disk throw std::runtime_error (exit code 4); refusals the user fixes in the
// scene throw SceneError naming the output_dir key (exit code 2).
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "mpmshock/comm.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/setup.hpp"

namespace mpmshock {

namespace fs = std::filesystem;

inline constexpr const char* kXdmfName = "snapshots.xdmf";

// snapshot_NNNNN.h5
std::string snapshot_name(int index);
// The number of a snapshot file name, or -1.
int snapshot_number(const fs::path& p);
// The files a run writes; --force removes exactly these, never anything else in the directory.
bool is_run_output(const fs::path& p);

// An exclusive lock on a run directory (flock on its .mpmshock.lock), held while the object
// lives: a second run, or a restart, into a directory that a running mpmshock writes is refused
// (exit 2). The kernel releases the lock when the process ends, however it ends, so no lock is
// ever stale.
class DirectoryLock {
 public:
  DirectoryLock() = default;
  // Takes the lock or throws SceneError naming `where` ("scene:3: key 'output_dir'") and the pid
  // of the run that holds it.
  DirectoryLock(const fs::path& dir, const std::string& where);
  DirectoryLock(DirectoryLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  DirectoryLock& operator=(DirectoryLock&& other) noexcept;
  ~DirectoryLock();

 private:
  int fd_ = -1;
};

// Creates output_dir and locks it; if it holds an earlier run's outputs, removes them (with force)
// or refuses; then checks that the directory can be written.
DirectoryLock prepare_output_dir(const Scene& scene, bool force);

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_output(const fs::path& path, const char* mode = "w");
void flush_or_throw(std::FILE* f, const std::string& what);
void write_text(const fs::path& path, const std::string& text);
// Writes PATH.tmp and renames it over PATH.
void write_text_atomically(const fs::path& path, const std::string& text);
// voids.csv: body, x, y, radius per void (body, x, y, z, radius per sphere in 3D).
void write_voids(const fs::path& path, const BodySummary& flyer, const BodySummary& target, int dimension);

// An error of the disk that every rank knows of (on_root): each ends with exit 4, none aborts the others.
struct AgreedIoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs f on rank 0 alone (the run directory is rank 0's to write); an error it throws there is thrown
// on every rank, SceneError as SceneError and any other as AgreedIoError, so that no rank waits for
// one that gave up.
template <class F>
void on_root(const Comm& comm, F&& f) {
  std::string failure;  // "S" or "R", then the message
  if (comm.root()) {
    try {
      f();
    } catch (const SceneError& e) {
      failure = std::string("S") + e.what();
    } catch (const std::exception& e) {
      failure = std::string("R") + e.what();
    }
  }
  comm.broadcast(failure);
  if (failure.empty()) return;
  if (failure[0] == 'S') throw SceneError(failure.substr(1));
  throw AgreedIoError(failure.substr(1));
}

// Runs f on every rank, each on its own share (its points, its machine); a SceneError it throws on
// any rank is thrown on every rank, with the lowest such rank's message, so that no rank waits for
// one that gave up.
template <class F>
void on_every_rank(const Comm& comm, F&& f) {
  if (!comm.parallel()) {
    f();
    return;
  }
  std::string complaint;
  try {
    f();
  } catch (const SceneError& e) {
    complaint = e.what();
  }
  if (comm.max(complaint.empty() ? 0.0 : 1.0) == 0.0) return;
  std::string first;
  for (const std::vector<char>& why : comm.gather(std::vector<char>(complaint.begin(), complaint.end())))
    if (first.empty()) first.assign(why.begin(), why.end());
  comm.broadcast(first);
  throw SceneError(first);
}

// The rows of a CSV (the header is not a row) whose time, the first column, is after t.
std::size_t count_rows_after(const fs::path& path, double t);
// Keeps the header and the rows that are not after t; rewrites the file atomically. Returns the
// number of rows dropped.
std::size_t truncate_rows_after(const fs::path& path, double t);

}  // namespace mpmshock
