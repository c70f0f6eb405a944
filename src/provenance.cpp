#include "mpmshock/provenance.hpp"

#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <system_error>

#include "openmp_wait.hpp"

namespace mpmshock {

namespace {

// A word as a POSIX shell reads it back: bare when it is plain, else in single quotes.
std::string shell_quoted(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789_-+=/.,:@%") == std::string::npos;
  if (plain) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

Invocation& the_invocation() {
  static Invocation inv = [] {
    Invocation i;
    char host[256] = {0};
    i.host = ::gethostname(host, sizeof host - 1) == 0 ? host : "unknown";
    std::error_code ec;
    i.working_directory = std::filesystem::current_path(ec).string();
    i.started = utc_now();
    i.openmp_wait = openmp_wait();
    return i;
  }();
  return inv;
}

}  // namespace

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

void record_invocation(int argc, char** argv, int ranks) {
  Invocation& inv = the_invocation();
  inv.command_line.clear();
  for (int i = 0; i < argc; ++i) inv.command_line += (i ? " " : "") + shell_quoted(argv[i]);
  inv.ranks = ranks;
}

const Invocation& invocation() { return the_invocation(); }

std::string version_text(bool with_mpi) {
  const BuildInfo& b = build_info();
  return std::string("mpmshock ") + b.version + (with_mpi ? " (with MPI)" : "") + "\ncommit: " + b.commit +
         "\ncompiler: " + b.compiler + "\nflags: " + b.flags + " (" + b.build_type + ")\n";
}

}  // namespace mpmshock
