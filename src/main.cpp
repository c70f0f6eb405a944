// mpmshock: shock waves in porous metals by the material-point method. The program is a thin
// shell around the library: read the command line, load the scene, run or check it.
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "mpmshock/comm.hpp"

#include "mpmshock/hdf5_io.hpp"
#include "mpmshock/provenance.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/run_directory.hpp"
#include "mpmshock/run_log.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/signals.hpp"
#include "mpmshock/version.hpp"
#include "openmp_wait.hpp"

namespace {

constexpr const char* kUsage = R"(usage: mpmshock SCENE [--set key=value]... [--check] [--quiet] [--force] [--threads N [--fixed-threads]]
       mpmshock --restart SNAPSHOT [--set key=value]... [--check] [--quiet] [--force] [--threads N [--fixed-threads]]
       mpmshock --resolve SCENE [--set key=value]...
       mpmshock --help | --version | --keys | --materials | --laws

Runs the material-point simulation of the impact that SCENE (a key = value file) describes and
writes regions.csv, conservation.csv, HDF5 snapshots (with snapshots.xdmf for ParaView) and
summary.json into its output_dir.

  --set key=value  override a key of the scene (repeatable; for parameter sweeps)
  --check          validate the scene, print the set-up (bodies, cells, material points, voids,
                   time step, steps, memory) and exit without running
  --quiet          no progress line on stderr
  --force          replace the outputs of an earlier run in output_dir
  --restart SNAP   continue the run that snapshot SNAP belongs to, from its state, in its
                   directory (--set end_time=... to run longer; later outputs need --force);
                   with --check, only validate SNAP
  --threads N      use at most N threads (default: OMP_NUM_THREADS or all cores); the run
                   measures its steps and uses fewer where that is faster (a busy machine)
  --fixed-threads  use all the threads for every step, even where fewer would be faster
  --resolve        print the scene as a run would resolve it (every key, in SI, with the
                   --set overrides and the defaults: the scene.txt the run would write) and exit
  --keys           print the table of scene keys (unit, default, meaning) and exit
  --materials      print the built-in materials (every constant and its source) and exit
  --laws           print the laws a material is built from (equations of state, strength laws,
                   softening), which built-in materials carry their constants, and their keys
  --help           this text
  --version        the version, the commit it was built from, the compiler and its flags

On several MPI ranks (mpirun -np N mpmshock SCENE ...) each rank simulates a slab of the column
and the outputs are the same, bit for bit, as those of one process; rank 0 writes them.

Exit codes: 0 done, 2 bad command line or scene, 3 the run hit a non-physical state (a final
snapshot is written), 4 output could not be written, 130 / 143 stopped by SIGINT / SIGTERM
after the current step (a final snapshot to restart from and the summary are written).
)";

// Rank 0 speaks for all the ranks (each parses the same command line and scene).
bool speaks() { return mpmshock::Comm::world().root(); }

[[noreturn]] void finish(int code) {
  mpmshock::Comm::finalize();
  std::exit(code);
}

struct Args {
  std::string scene;
  std::string restart;
  std::vector<std::string> overrides;
  bool check = false, resolve = false, quiet = false, force = false, fixed_threads = false;
  int threads = 0;
};

[[noreturn]] void usage_error(const std::string& message) {
  if (speaks()) std::fprintf(stderr, "mpmshock: %s\n(see mpmshock --help)\n", message.c_str());
  finish(mpmshock::kExitBadInput);
}

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) {
      if (i + 1 >= argc) usage_error(std::string(flag) + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "--help" || arg == "-h") {
      if (speaks()) std::fputs(kUsage, stdout);
      finish(0);
    } else if (arg == "--version") {
      if (speaks()) std::fputs(mpmshock::version_text(mpmshock::Comm::built_with_mpi()).c_str(), stdout);
      finish(0);
    } else if (arg == "--keys") {
      if (speaks()) std::fputs(mpmshock::key_reference_markdown().c_str(), stdout);
      finish(0);
    } else if (arg == "--materials") {
      if (speaks()) std::fputs(mpmshock::material_library_text().c_str(), stdout);
      finish(0);
    } else if (arg == "--laws") {
      if (speaks()) std::fputs(mpmshock::material_laws_text().c_str(), stdout);
      finish(0);
    } else if (arg == "--set") {
      a.overrides.push_back(value("--set"));
    } else if (arg.rfind("--set=", 0) == 0) {
      a.overrides.push_back(arg.substr(6));
    } else if (arg == "--restart") {
      a.restart = value("--restart");
    } else if (arg == "--resolve") {
      a.resolve = true;
    } else if (arg == "--check") {
      a.check = true;
    } else if (arg == "--quiet" || arg == "-q") {
      a.quiet = true;
    } else if (arg == "--force") {
      a.force = true;
    } else if (arg == "--fixed-threads") {
      a.fixed_threads = true;
    } else if (arg == "--threads") {
      const std::string v = value("--threads");
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 4096) usage_error("--threads needs a whole number from 1 to 4096");
      a.threads = static_cast<int>(n);
    } else if (!arg.empty() && arg[0] == '-') {
      usage_error("unknown option '" + arg + "'");
    } else if (a.scene.empty()) {
      a.scene = arg;
    } else {
      usage_error("more than one scene file given ('" + a.scene + "' and '" + arg + "')");
    }
  }
  if (!a.restart.empty() && !a.scene.empty()) usage_error("give a scene file or --restart SNAPSHOT, not both");
  if (a.scene.empty() && a.restart.empty()) usage_error("no scene file given");
  if (a.resolve && !a.restart.empty()) usage_error("--resolve takes a scene file (a run's resolved scene is its scene.txt)");
  if (a.resolve && a.check) usage_error("give --resolve or --check, not both");
  return a;
}

void report(const mpmshock::RunResult& result) {
  if (!speaks()) return;
  using mpmshock::say;
  if (result.exit_code == mpmshock::kExitNumerical)
    say(stderr, "mpmshock: the run stopped: " + result.failure + "\nmpmshock: the last state is in the newest snapshot\n");
  else if (result.exit_code != mpmshock::kExitOk)
    say(stderr, "mpmshock: " + result.failure + "\n");
  say(stdout, mpmshock::describe_result(result));
}

}  // namespace

namespace {

// An error every rank meets alike (the scene, the snapshot: each rank reads them) ends each rank
// with its code; one that a rank may meet alone (memory, the disk) stops every rank at once.
[[noreturn]] void fail(const char* message, int code, bool every_rank_alike) {
  const mpmshock::Comm& comm = mpmshock::Comm::world();
  if (speaks() || (comm.parallel() && !every_rank_alike)) {
    // One line per error (a scene with several errors reports them all).
    const std::string rank = comm.parallel() && !every_rank_alike ? " (rank " + std::to_string(comm.rank()) + ")" : "";
    std::string all = message;
    for (std::size_t start = 0; start <= all.size();) {
      const std::size_t end = std::min(all.find('\n', start), all.size());
      mpmshock::say(stderr, "mpmshock: error: " + all.substr(start, end - start) + rank + "\n");
      start = end + 1;
    }
  }
  if (comm.parallel() && !every_rank_alike) comm.abort(code);
  finish(code);
}

int run(const Args& args) {
  if (!args.restart.empty() && args.check) {
    const std::string text = mpmshock::check_restart(args.restart, args.overrides);
    if (speaks()) std::fputs(text.c_str(), stdout);
    return mpmshock::kExitOk;
  }
  if (!args.restart.empty()) {
    const mpmshock::RunOptions options{args.quiet, args.force, args.fixed_threads};
    const mpmshock::RunResult result = mpmshock::restart_run(args.restart, args.overrides, options);
    report(result);
    return result.exit_code;
  }
  const mpmshock::Scene scene = mpmshock::load_scene(args.scene, args.overrides);
  if (args.resolve) {
    if (speaks()) std::fputs(mpmshock::resolved_scene(scene).c_str(), stdout);
    return mpmshock::kExitOk;
  }
  if (args.check) {
    const std::string text = mpmshock::check_report(scene);
    if (speaks()) std::fputs(text.c_str(), stdout);
    return mpmshock::kExitOk;
  }
  const mpmshock::RunResult result = mpmshock::run_scene(scene, {args.quiet, args.force, args.fixed_threads});
  report(result);
  return result.exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  mpmshock::prefer_short_waits(argv);  // may start this program again, before anything else: openmp_wait.hpp
  mpmshock::Comm::init(&argc, &argv);
  mpmshock::h5::prepare_library();
  const Args args = parse_args(argc, argv);
  mpmshock::record_invocation(argc, argv, mpmshock::Comm::world().size());
  if (args.threads > 0) omp_set_num_threads(args.threads);
  mpmshock::install_stop_handlers();
  try {
    finish(run(args));
  } catch (const std::bad_alloc&) {
    fail("out of memory: the run needs more memory than this machine can give it; use a coarser cell_size, "
         "smaller bodies or a smaller grid_margin (--check estimates it)",
         mpmshock::kExitBadInput, false);
  } catch (const mpmshock::SceneError& e) {
    fail(e.what(), mpmshock::kExitBadInput, true);
  } catch (const mpmshock::AgreedIoError& e) {
    fail(e.what(), mpmshock::kExitIo, true);
  } catch (const std::exception& e) {
    fail(e.what(), mpmshock::kExitIo, false);
  }
}
