// Material nothing has reached yet (skip_unreached = on, the default). Until the fastest signal
// arrives, a body translates rigidly at its initial velocity, stress free: F = I, E = 0, v = v0.
// Those points are advanced in closed form, x += v0 dt, and left out of every transfer and update;
// in the paper's base case they are a third of the point-steps, in the speed scene 45 %.
//
// The points are stored flyer first, then target, each bottom row first, and never reordered, so
// the unreached material is the flyer's first points [0, head) and the target's last [tail, n); the
// step computes [head, tail). After each step the boundaries move past every point within
// kMarginCells cells of the highest (in the flyer: lowest) point that has been reached: moved off
// v0 by more than 1e-9 of the impact speed, F off I by more than 1e-12, or E off 0 by more than
// 1e-12 of v0^2/2. Beyond the margin the whole-domain computation moves the material rigidly too,
// up to round-off (it sums N m v0 over N m, and turns that round-off into strains of 1e-18; here
// the translation is exact): in one step a disturbance spreads over at most four stencil radii
// (P2G, G2P, the re-map P2G and the gradient G2P; a radius is 1.5 cells for bspline2 and gimp, 1
// for bilinear, 2 for bspline2_domain), 6 cells (8), plus the step's motion (under a cell), so no
// point the disturbance can reach within a step, and no node such a point reads, lacks the share
// of a skipped point; the margin is twice that (1.3 times with bspline2_domain). Only the points
// within 2 margins of a boundary are examined.
// Material once computed stays computed. Before the impact (t = 0) the reached points are those at
// the impact plane y = 0.
//
// The boundaries are point ids. On MPI ranks (decomposition.hpp) each rank holds some of the points,
// in id order, so its unreached points are still its first and last ones; the boundaries move as
// one process moves them (the first id past the margin, in id order), found by a maximum and a
// minimum over the ranks (comm.hpp).
#pragma once

#include <cstddef>

#include "mpmshock/comm.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"

namespace mpmshock {

template <int D>
class UnreachedMaterial {
 public:
  static constexpr double kMarginCells = 12.0;

  // Off (or nothing known): every one of `points` (of all ranks) is computed.
  explicit UnreachedMaterial(std::size_t points = 0) : points_(points), tail_(points) {}
  // A new run's points (this rank's, of all ranks of comm), all in their initial state: everything
  // farther than the margin from the impact plane is unreached.
  UnreachedMaterial(const Scene& scene, const Model& model, const Particles<D>& pts,
                    const Comm& comm = Comm::world());
  // A run resumed with the boundaries it saved (Clock). Throws SceneError (on every rank) if they do
  // not fit the points, or a point they leave out has left its initial state.
  UnreachedMaterial(const Scene& scene, const Model& model, const Particles<D>& pts, std::size_t head,
                    std::size_t tail, const Comm& comm = Comm::world());

  // The points of `pts` (this rank's, in id order) a step computes: those with ids in [head, tail).
  PointRange computed(const Particles<D>& pts) const;
  bool any() const { return head_ > 0 || tail_ < points_; }
  std::size_t head() const { return head_; }
  std::size_t tail() const { return tail_; }
  // The fastest signal of an unreached point (|v0| + its sound speed), 0 when there is none.
  double signal() const { return any() ? signal_ : 0.0; }

  // Advances the unreached points by dt in closed form.
  void advance(Particles<D>& pts, double dt) const;
  // After a step: computes every point within the margin of what has been reached.
  void follow(const Particles<D>& pts);
  // The weights of a rank's work (decomposition.hpp) count unreached points apart.
  bool unreached(const Particles<D>& pts, std::size_t p) const {
    return on_ && (pts.id[p] < head_ || pts.id[p] >= tail_);
  }

  // A point that has left its initial state (velocity or deformation); unreached points never have.
  bool reached(const Particles<D>& pts, std::size_t p) const;

 private:
  // The constants of a scene's unreached material, nothing unreached yet.
  UnreachedMaterial(const Scene& scene, const Particles<D>& pts, const Comm& comm);
  // Moves the boundaries past every point within the margin of the reached points' highest y in
  // the target (`top`) and lowest in the flyer (`bottom`), as a scan in id order would.
  void extend(const Particles<D>& pts, double top, double bottom);
  const Comm* comm_ = &Comm::world();
  bool on_ = false;
  std::size_t points_ = 0, flyer_ = 0;  // all points; the flyer's [0, flyer_)
  std::size_t head_ = 0, tail_ = 0;     // computed: [head_, tail_)
  double flyer_velocity_ = 0.0, target_velocity_ = 0.0;  // v0_y of each body
  double margin_ = 0.0;                 // [m]
  std::size_t band_ = 0;                // points examined next to a boundary
  void measure_signal(const Model& model, const Particles<D>& pts);
  double signal_ = 0.0;
  double speed_tolerance_ = 0.0, energy_tolerance_ = 0.0;
};

extern template class UnreachedMaterial<2>;
extern template class UnreachedMaterial<3>;

}  // namespace mpmshock
