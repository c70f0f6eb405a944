// Running a scene: set-up, the time loop with its outputs, progress and the closing summary.
#pragma once

#include <cstdint>
#include <string>

#include "mpmshock/scene.hpp"
#include "mpmshock/setup.hpp"

namespace mpmshock {

// Exit codes of the mpmshock program.
enum ExitCode : int {
  kExitOk = 0,
  kExitBadInput = 2,   // bad command line or scene
  kExitNumerical = 3,  // the run stopped on a non-physical state or material leaving the grid
  kExitIo = 4,         // output could not be written
};

struct RunOptions {
  bool quiet = false;  // no progress line
  bool force = false;  // replace the outputs of an earlier run in output_dir
};

struct RunResult {
  int exit_code = kExitOk;
  std::string failure;  // what went wrong, if exit_code != 0
  std::int64_t steps = 0;
  double end_time = 0.0;
  double wall_seconds = 0.0;
  std::size_t points = 0;
  double point_steps_per_second = 0.0;
  double mass_error = 0.0, momentum_error = 0.0, energy_error = 0.0;  // relative
  double porosity = 1.0;                                             // from the material points
  std::size_t voids = 0;
};

// Runs the scene, writing into scene.output_dir: scene.txt, voids.csv, regions.csv,
// conservation.csv, snapshot_NNNNN.h5 and summary.json. Setup errors throw SceneError; I/O errors std::runtime_error.
RunResult run_scene(const Scene& scene, const RunOptions& options);

// The --check report: bodies, grid, material points, voids, time step, steps, memory.
std::string describe_setup(const Scene& scene, const InitialState& state);

// The summary block printed at the end of a run.
std::string describe_result(const RunResult& r);

}  // namespace mpmshock
