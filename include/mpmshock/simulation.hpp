// The explicit MPM integrator. step() is the algorithm, one phase per line; output, sampling and
// bookkeeping live outside it (run.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mpmshock/constitutive.hpp"
#include "mpmshock/grid.hpp"
#include "mpmshock/heat_conduction.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/step_effect.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/symmetry_plane.hpp"
#include "mpmshock/unreached.hpp"

namespace mpmshock {

// The transfer and point-update kernels for one dimension, shape function and set of laws,
// instantiated for the model's choices at set-up (simulation.cpp).
template <int D>
struct Kernels {
  bool (*bin)(StripBins&, const Particles<D>&, PointRange, const GridGeometry<D>&);
  void (*to_grid)(const Particles<D>&, const StripBins&, Grid<D>&, StencilStore<D>&);
  void (*velocity_to_points)(Particles<D>&, PointRange, const StripBins&, Grid<D>&, const StencilStore<D>&, double dt,
                             double flip_fraction);
  std::size_t (*gradient_work_and_move)(Particles<D>&, PointRange, const Grid<D>&, const StencilStore<D>&,
                                        const std::vector<Vec<D>>& u, double dt);
  StressUpdateResult (*update_points)(Particles<D>&, PointRange, const Model&, double dt);
  // Heat conduction, or null when the scene has none.
  void (*conduct)(Particles<D>&, PointRange, const StripBins&, const Grid<D>&, const StencilStore<D>&,
                  const HugoniotTemperature&, HeatConduction&, const SymmetryPlane<D>*, double dt);
};

// Where the integrator stands: all it needs, besides the points, to take the next step.
struct Clock {
  double time = 0.0;
  std::int64_t steps = 0;
  double max_signal = 0.0;  // fastest signal of the last step; sets the next time step
  // Running sum over steps and points of m (work - own trapezoid work): the internal energy the
  // points hold beyond what their own deformation did on them [J] (constitutive.hpp).
  double work_mismatch = 0.0;
  // The points not reached yet: [0, unreached_head) and [unreached_tail, n) (unreached.hpp);
  // kNoneSaved in unreached_tail: not known (a snapshot of an older mpmshock), all computed.
  static constexpr std::size_t kNoneSaved = ~std::size_t{0};
  std::size_t unreached_head = 0, unreached_tail = kNoneSaved;
};

template <int D>
class Simulation {
 public:
  // A new run from its initial points (time 0, first time step from their state).
  Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points);
  // A run resumed from a snapshot's points and clock.
  Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points, const Clock& clock);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Advances by dt (which the caller takes from stable_time_step() or smaller).
  StepStatus step(double dt);
  // The checks of the step effects that run at sample times (the 0 K check).
  StepStatus check_at_sample();

  // cfl h / fastest signal of the last step.
  double stable_time_step() const { return model_.time_step(clock_.max_signal); }

  double time() const { return clock_.time; }
  std::int64_t steps() const { return clock_.steps; }
  const Clock& clock() const { return clock_; }
  const Particles<D>& particles() const { return points_; }
  Particles<D>& particles_for_testing() { return points_; }
  const Grid<D>& grid() const { return grid_; }
  const Model& model() const { return model_; }
  // Node rows the last step used; the grid's fields outside them are stale.
  RowRange active_rows() const { return bins_.rows(); }
  // The points the steps compute; the others nothing has reached yet (unreached.hpp).
  PointRange computed_points() const { return unreached_.computed(); }

  // A readable account of a failed step or check: the point, its position and its state.
  std::string describe(const StepStatus& status) const;

 private:
  void remember_unreached();  // the unreached boundaries into the clock, for snapshots
  Model model_;
  Particles<D> points_;
  Grid<D> grid_;
  StripBins bins_;
  StencilStore<D> stencils_;  // the step's shape weights, computed once by P2G
  Kernels<D> kernels_;
  HeatConduction heat_;
  std::vector<std::unique_ptr<StepEffect<D>>> effects_;
  const SymmetryPlane<D>* plane_ = nullptr;  // the symmetry plane among effects_ (symmetry = on), for conduction
  UnreachedMaterial<D> unreached_;
  Clock clock_;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

}  // namespace mpmshock
