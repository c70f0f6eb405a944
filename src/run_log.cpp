#include "mpmshock/run_log.hpp"


#include "mpmshock/comm.hpp"
#include "mpmshock/provenance.hpp"

namespace mpmshock {

namespace {

struct Log {
  std::FILE* file = nullptr;  // open from open_run_log to the end of the process
  std::string before;         // what was said before it opened
};

Log& the_log() {
  static Log log;
  return log;
}

void keep(const std::string& text) {
  Log& log = the_log();
  if (!log.file) {
    log.before += text;
    return;
  }
  // A full disk loses the log, never the run: log.txt is a record, the outputs are the results.
  std::fputs(text.c_str(), log.file);
  std::fflush(log.file);
}

}  // namespace

void say(std::FILE* stream, const std::string& text) {
  std::fputs(text.c_str(), stream);
  std::fflush(stream);
  keep(text);
}

void log_only(const std::string& text) { keep(text); }

void open_run_log(const std::filesystem::path& dir, bool continued) {
  Log& log = the_log();
  if (log.file) std::fclose(log.file);
  log.file = std::fopen((dir / "log.txt").c_str(), continued ? "a" : "w");
  if (!log.file) return;  // the outputs themselves are checked for writability; the log is a record
  const BuildInfo& b = build_info();
  const Invocation& inv = invocation();
  std::fprintf(log.file, "%s# mpmshock %s%s, commit %s\n# built by %s with %s (%s)\n", continued ? "\n" : "",
               b.version, Comm::built_with_mpi() ? " (with MPI)" : "", b.commit, b.compiler, b.flags, b.build_type);
  std::fprintf(log.file, "# %s %s on %s in %s, %d rank%s\n# command: %s\n# OpenMP waits: %s\n",
               continued ? "restarted" : "started", inv.started.c_str(), inv.host.c_str(),
               inv.working_directory.c_str(), inv.ranks, inv.ranks == 1 ? "" : "s", inv.command_line.c_str(),
               inv.openmp_wait.c_str());
  std::fputs(log.before.c_str(), log.file);
  std::fflush(log.file);
  log.before.clear();
}

}  // namespace mpmshock
