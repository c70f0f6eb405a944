// The explicit MPM integrator. step() is the algorithm, one phase per line; output, sampling and
// bookkeeping live outside it (run.hpp).
//
// On several MPI ranks each rank simulates the material points of its slab of the grid
// (decomposition.hpp) on the node rows it holds; the scatters pass the shared rows' sums on between
// their colours (halo.hpp), the step's maxima and sums are agreed across the ranks, and points
// that cross into a neighbour's slab move there after the step. Every rank then holds exactly the
// numbers one process would, for its points: the outputs are the same bits on any number of ranks.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "mpmshock/comm.hpp"
#include "mpmshock/constitutive.hpp"
#include "mpmshock/decomposition.hpp"
#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
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
  int support;  // stencil nodes per axis
  int (*first_row)(double y, const GridGeometry<D>&);  // the node row a point's stencil starts at
  bool (*bin)(StripBins&, const Particles<D>&, PointRange, const GridGeometry<D>&);
  void (*stencils)(const Particles<D>&, PointRange, const GridGeometry<D>&, StencilStore<D>&);
  void (*to_grid)(const Particles<D>&, const StripBins&, Grid<D>&, const StencilStore<D>&, const Halo<D>&,
                  const HeatFluxRider*);
  void (*velocity_to_points)(Particles<D>&, PointRange, const StripBins&, Grid<D>&, const StencilStore<D>&,
                             const Halo<D>&, double dt, double flip_fraction, std::vector<Vec<D>>& v_pic);
  std::size_t (*gradient_work_and_move)(Particles<D>&, PointRange, const Grid<D>&, const StencilStore<D>&,
                                        const std::vector<Vec<D>>& u, const std::vector<Vec<D>>& v_pic, double dt);
  StressUpdateResult (*update_points)(Particles<D>&, PointRange, const Model&, double dt, const double* volume_rate);
};

// Where the integrator stands: all it needs, besides the points, to take the next step.
struct Clock {
  double time = 0.0;
  std::int64_t steps = 0;
  double max_signal = 0.0;  // fastest signal of the last step; sets the next time step
  // Running sum over steps and points of m (work - own trapezoid work): the internal energy the
  // points hold beyond what their own deformation did on them [J] (constitutive.hpp). The exact sum
  // of the points' own sums (Particles::work_mismatch), taken by Simulation::settle(), plus
  // work_mismatch_before.
  double work_mismatch = 0.0;
  // What a snapshot that kept no per-point sums (an older mpmshock's) held of work_mismatch; else 0.
  double work_mismatch_before = 0.0;
  // The points not reached yet: [0, unreached_head) and [unreached_tail, n) (unreached.hpp);
  // kNoneSaved in unreached_tail: not known (a snapshot of an older mpmshock), all computed.
  static constexpr std::size_t kNoneSaved = ~std::size_t{0};
  std::size_t unreached_head = 0, unreached_tail = kNoneSaved;
};

template <int D>
class Simulation {
 public:
  // A new run from its initial points (time 0, first time step from their state). On several ranks
  // of `comm` each rank passes a share of the points, in id order (every point on one rank; any
  // split: the points then move to the ranks whose slabs hold them); on one, all of them.
  Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points, const Comm& comm = Comm::world());
  // A run resumed from a snapshot's points (shared out as above) and clock.
  Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points, const Clock& clock,
             const Comm& comm = Comm::world());
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
  // The clock's work mismatch is the one settle() last took: the exact sum of the points' own sums
  // (one pass and one collective per sample, none per step).
  const Clock& clock() const { return clock_; }
  void settle();
  // MPI: the stop signal any rank got, agreed in the last step (0: none).
  int agreed_stop_signal() const { return stop_signal_; }
  // This rank's points, in id order (all of them on one rank).
  const Particles<D>& particles() const { return points_; }
  Particles<D>& particles_for_testing() { return points_; }
  // The points of every rank (all of them at rank 0 only: a snapshot's).
  Particles<D> all_particles() const { return gather_points(points_, *comm_); }
  // The points simulated on all ranks together.
  std::size_t total_points() const { return total_points_; }
  // This rank's grid rows (on one rank all of them, but for the unused ghost rows below a symmetry
  // plane).
  const Grid<D>& grid() const { return grid_; }
  const GridGeometry<D>& whole_grid() const { return whole_geo_; }
  const Model& model() const { return model_; }
  const Comm& comm() const { return *comm_; }
  const Decomposition& decomposition() const { return slabs_; }
  // Node rows the last step used here; the grid's fields outside them are stale.
  RowRange active_rows() const { return bins_.rows(); }
  // The nodal mass and velocity of every rank's active rows in one whole grid at rank 0, and in
  // `rows` the rows they span (for a snapshot's /grid).
  Grid<D> gathered_grid(RowRange& rows) const;
  // The points of every rank compressed past the equation of state's fit (a collective).
  std::size_t points_beyond_eos_fit() const;
  // This rank's points the steps compute; the others nothing has reached yet (unreached.hpp).
  PointRange computed_points() const { return unreached_.computed(points_); }

  // A readable account of a failed step or check: the point, its position and its state (at rank
  // 0, which gets it from the rank that holds the point; empty elsewhere). Every rank calls it.
  std::string describe(const StepStatus& status) const;

  // The largest rank's work over the mean, by the times the ranks measured at the last balance.
  double imbalance() const { return imbalance_; }

 private:
  void remember_unreached();  // the unreached boundaries into the clock, for snapshots
  // MPI: this rank's slab of `slabs`: its grid rows and halo (its points move there by hops).
  void take_slab(const Decomposition& slabs);
  int strip_of(double y) const;
  void migrate();     // points that crossed into a neighbour's slab move there
  // One move towards home of every point not home (of at most `most` each way); whether this rank
  // sent any.
  bool hop(std::size_t most = static_cast<std::size_t>(-1));
  void redistribute();  // after new slabs: every point home, however far
  void rebalance();   // new slabs when the work has drifted
  // Per strip, over every rank: the points' weights (decomposition.hpp) and their number.
  struct StripLoads {
    std::vector<std::int64_t> weights, points;
  };
  StripLoads strip_loads() const;
  StepStatus agree(const StepStatus& mine) const;  // the same status on every rank: the lowest id's
  // The step's maximum signal over every rank, and its failure (a bad state before a point off the
  // grid, each of the lowest id).
  StepStatus agree_on(StressUpdateResult& update, std::size_t left, const StepStatus& effect);
  bool bins_within_slab() const;  // the step's points touch only the rows held here
  int first_strip_end_needed() const;
  int first_row_held() const;  // the lowest node row any point can touch
  StepStatus with_id(StepStatus s) const;  // an effect's storage index as the point's id
  void describe_point(std::ostream& out, StepStatus::Code code, std::size_t p, std::size_t id) const;  // rank 0's slab must reach this strip (symmetry_plane.hpp)
  const Comm* comm_;
  GridGeometry<D> whole_geo_;
  Decomposition slabs_;
  Halo<D> halo_;
  std::size_t total_points_ = 0;
  std::int64_t last_balance_step_ = 0;
  bool balanced_once_ = false;
  double busy_seconds_ = 0.0;  // the steps' time since the last balance, outside MPI calls
  double imbalance_ = 1.0;           // by the last balance's measured work
  int stop_signal_ = 0;
  Model model_;
  Particles<D> points_;
  Grid<D> grid_;
  StripBins bins_;
  StencilStore<D> stencils_;  // the step's shape weights, computed once at its start
  std::vector<Vec<D>> v_pic_;  // the step's sum_i N_ip v_i^{n+1} by point, from G2P to the move
  Kernels<D> kernels_;
  // The step effects the scene calls for (simulation.cpp: effects_for), each slot's in the order made.
  std::vector<std::unique_ptr<StepEffect<D>>> effects_;
  std::array<std::vector<StepEffect<D>*>, kStepSlots> slot_effects_;
  const std::vector<StepEffect<D>*>& in_slot(StepSlot slot) const { return slot_effects_[static_cast<std::size_t>(slot)]; }
  const SymmetryPlane<D>* plane_ = nullptr;  // the symmetry plane among effects_ (symmetry = on), else null
  UnreachedMaterial<D> unreached_;
  Clock clock_;
};

// Refuses (SceneError) a rank count the scene's grid has too few strips for, before anything is
// built or written: the limits the Simulation's slabs obey (decomposition.hpp).
template <int D>
void check_rank_count(const Scene& scene, const GridGeometry<D>& grid, int ranks);

extern template class Simulation<2>;
extern template class Simulation<3>;

}  // namespace mpmshock
