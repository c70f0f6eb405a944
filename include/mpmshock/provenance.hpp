// Where a run's numbers came from: the build (version, commit, compiler, flags) and the
// invocation (command line, start time, host, directory). summary.json, log.txt and every
// snapshot record them.
#pragma once

#include <string>

namespace mpmshock {

struct BuildInfo {
  const char* version;     // scripts/mpmshock_post/_version.py, shared with the Python package
  const char* commit;      // git describe --always --dirty at build time
  const char* compiler;    // "GNU 12.2.0 (/usr/bin/c++)"
  const char* flags;       // the compile flags of the core library, -march=native included
  const char* build_type;  // Release, Debug, ...
};
const BuildInfo& build_info();  // build_info.cpp, generated

struct Invocation {
  std::string command_line;       // argv, quoted as a shell would need it
  std::string started;            // UTC, ISO 8601: 2026-12-03T17:48:19Z
  std::string host;
  std::string working_directory;
  int ranks = 1;
  std::string openmp_wait;        // how waiting threads wait (src/openmp_wait.hpp)
};

// main() records the command line once; until then invocation() has only host, time and directory.
void record_invocation(int argc, char** argv, int ranks);
const Invocation& invocation();

// The UTC time now, ISO 8601.
std::string utc_now();

// "mpmshock 0.2.0 (with MPI)\ncommit ...\ncompiler ...\nflags ...\n" for --version.
std::string version_text(bool with_mpi);

}  // namespace mpmshock
