// Running a scene: set-up or restart, the time loop with its outputs, progress and the summary.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mpmshock/scene.hpp"

namespace mpmshock {

// Exit codes of the mpmshock program.
enum ExitCode : int {
  kExitOk = 0,
  kExitBadInput = 2,   // bad command line, scene or restart request
  kExitNumerical = 3,  // the run stopped on a non-physical state or material leaving the grid
  kExitIo = 4,         // output could not be written
  // Stopped by a signal (SIGINT, SIGTERM): 128 + the signal number, as shells report it, after the
  // current step finished and a final snapshot and the summary were written.
};

struct RunOptions {
  bool quiet = false;  // no progress line
  bool force = false;  // replace the outputs of an earlier run (or, on restart, its later outputs)
  bool fixed_threads = false;  // every step on all threads; otherwise the thread tuner chooses
};

struct RunResult {
  int exit_code = kExitOk;
  std::string failure;  // what went wrong, if exit_code != 0
  std::int64_t steps = 0;
  double start_time = 0.0;  // 0, or the time restarted from
  double end_time = 0.0;
  double wall_seconds = 0.0;
  std::size_t points = 0;   // simulated: with symmetry = on the target's, half the outputs' points
  bool symmetry = false;    // symmetry = on: the flyer is the target's mirror image
  int dimension = 2;
  double point_steps_per_second = 0.0;  // of the simulated points
  int threads = 1;                           // the most threads the run used (per rank)
  int ranks = 1;                             // MPI ranks (decomposition.hpp)
  double imbalance = 1.0;                    // MPI: the largest rank's work over the mean, at the end
  double mpi_bytes_per_step = 0.0;           // MPI: bytes all ranks sent per step (halos, moving points, sums)
  double mpi_messages_per_step = 0.0;        // MPI: messages (and collective calls) of all ranks per step
  double mpi_seconds = 0.0;                  // MPI: the most wall time a rank spent in MPI calls, waits included
  double mpi_seconds_least = 0.0;            // MPI: the least (about the cost of communicating itself)
  std::int64_t steps_with_fewer_threads = 0;  // steps the thread tuner ran with fewer (thread_tuner.hpp)
  // The steps' mean length over the mean step cfl allowed: 1 but for the steps cut to land on an
  // output time, well below 1 where the sample or snapshot interval is shorter than the step.
  double step_share = 1.0;
  double mass_error = 0.0, momentum_error = 0.0, energy_error = 0.0;  // relative, since t = 0
  double porosity = 1.0;                                             // from the material points
  std::size_t voids = 0;
  // The most simulated points compressed past the equation of state's fit (eos.hpp) at any sample.
  std::size_t beyond_eos_fit = 0;
  double beyond_eos_fit_J = 0.0;  // the J = V/V0 the fit ends at
  std::string output_dir;
};

// Runs the scene from t = 0, writing into scene.output_dir: scene.txt, voids.csv, regions.csv,
// conservation.csv, snapshot_NNNNN.h5, snapshots.xdmf and summary.json. Scene errors (voids that
// cannot fit, an output_dir holding an earlier run) throw SceneError; I/O errors std::runtime_error.
RunResult run_scene(const Scene& scene, const RunOptions& options);

// Continues the run a snapshot belongs to, from the snapshot's state, to end_time. `overrides`
// may change output and numerical keys (end_time, intervals, cfl, viscosity, ...), not the bodies,
// grid or material. The outputs go on in the snapshot's directory (or a new output_dir if one is
// set); rows and snapshots after the snapshot's time are discarded, which needs --force.
RunResult restart_run(const std::string& snapshot, const std::vector<std::string>& overrides,
                      const RunOptions& options);

// The overrides a snapshot's scene text needs to run as the mpmshock that wrote it did (keys it
// predates), after `overrides`; restart_run applies them.
std::vector<std::string> with_old_defaults(const std::string& scene_text, std::vector<std::string> overrides);

// --restart SNAPSHOT --check: reads and validates the snapshot (checksum, every value, the bodies
// against the scene) without running; SceneError says what is wrong.
std::string check_restart(const std::string& snapshot, const std::vector<std::string>& overrides);

// The --check report: builds the initial state and describes it (bodies, grid, material points,
// voids, time step, steps, memory).
std::string check_report(const Scene& scene);

// The summary block printed at the end of a run.
std::string describe_result(const RunResult& r);

// Every warning about the scene (scene_warnings, and the size of probes.csv at the first time step
// `first_step`), one per line on stderr; rank 0 alone calls it.
void print_scene_warnings(const Scene& scene, double first_step);

}  // namespace mpmshock
