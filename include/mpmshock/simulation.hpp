// The explicit MPM integrator. step() is the algorithm, one phase per line; output, sampling
// and bookkeeping live outside it (see run.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "mpmshock/constitutive.hpp"
#include "mpmshock/grid.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {

// What a step found. Numerical trouble is a status, not an exception: the caller decides to stop,
// writes a final snapshot and reports.
struct StepStatus {
  enum class Code { ok, bad_state, left_grid };
  Code code = Code::ok;
  std::size_t point = 0;  // storage index of the offending material point
  bool ok() const { return code == Code::ok; }
};

// Transfer kernels for one shape function and set of choices, picked at setup.
struct TransferKernels {
  bool (*bin)(StripBins&, const Particles&, const GridGeometry&);
  void (*to_grid)(const Particles&, const StripBins&, Grid&);
  void (*velocity_to_points)(Particles&, const StripBins&, Grid&, double dt);
  std::size_t (*gradient_work_and_move)(Particles&, const Grid&, const std::vector<double>& ux,
                                        const std::vector<double>& uy, double dt);
};

// Where the integrator stands: all it needs, besides the points, to take the next step.
struct Clock {
  double time = 0.0;
  std::int64_t steps = 0;
  double max_signal = 0.0;  // fastest signal of the last step; sets the next time step
};

class Simulation {
 public:
  // A new run from its initial points (time 0, first time step from their state).
  Simulation(const Scene& scene, const GridGeometry& grid, Particles points);
  // A run resumed from a snapshot's points and clock.
  Simulation(const Scene& scene, const GridGeometry& grid, Particles points, const Clock& clock);

  // Advances by dt (which the caller takes from stable_time_step() or smaller).
  StepStatus step(double dt);

  // cfl h / fastest signal of the last step.
  double stable_time_step() const { return cfl_ * model_.cell_size / clock_.max_signal; }

  double time() const { return clock_.time; }
  std::int64_t steps() const { return clock_.steps; }
  const Clock& clock() const { return clock_; }
  const Particles& particles() const { return points_; }
  const Grid& grid() const { return grid_; }
  const Model& model() const { return model_; }
  // Node rows the last step used; the grid's fields outside them are stale.
  int active_row_begin() const { return bins_.row_begin(); }
  int active_row_end() const { return bins_.row_end(); }

  // A readable account of a bad step: the point, its position and its state.
  std::string describe(const StepStatus& status) const;

 private:
  Model model_;
  Particles points_;
  Grid grid_;
  StripBins bins_;
  TransferKernels kernels_;
  StressUpdate update_stress_;
  UpdateScheme scheme_;
  double cfl_;
  Clock clock_;
};

}  // namespace mpmshock
