#include "mpmshock/unreached.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mpmshock/constitutive.hpp"
#include "mpmshock/decomposition.hpp"
#include "mpmshock/parallel.hpp"

namespace mpmshock {

template <int D>
UnreachedMaterial<D>::UnreachedMaterial(const Scene& scene, const Particles<D>& pts, const Comm& comm)
    : comm_(&comm), on_(true), flyer_velocity_(scene.velocity_of(Body::flyer)), target_velocity_(scene.velocity_of(Body::target)),
      margin_(kMarginCells * scene.cell_size), speed_tolerance_(1e-9 * std::max(scene.fastest_body_speed(), 1.0)),
      energy_tolerance_(1e-12 * 0.5 * std::max(scene.fastest_body_speed(), 1.0) * std::max(scene.fastest_body_speed(), 1.0)) {
  // Every rank's points; the flyer's are the ids below the first target point's.
  std::int64_t counts[2] = {static_cast<std::int64_t>(pts.size()),
                            static_cast<std::int64_t>(std::count(pts.body.begin(), pts.body.end(), Body::flyer))};
  comm.sum(counts, 2);
  points_ = static_cast<std::size_t>(counts[0]);
  flyer_ = static_cast<std::size_t>(counts[1]);
  head_ = tail_ = flyer_;
  // The points of 2 margins of lattice rows: the band next to a boundary that follow() examines.
  const double a = scene.particle_spacing();
  band_ = static_cast<std::size_t>(2.0 * std::ceil(margin_ / a) * std::pow(std::round(scene.width / a), D - 1));
}

template <int D>
UnreachedMaterial<D>::UnreachedMaterial(const Scene& scene, const Model& model, const Particles<D>& pts,
                                        const Comm& comm)
    : UnreachedMaterial(scene, pts, comm) {
  // The impact plane is where the bodies are first reached, unless a point has left its initial
  // state already (a state set up by hand).
  const double inf = std::numeric_limits<double>::infinity();
  double found[4] = {0.0, 0.0, -inf, -inf};  // top, -bottom, -(lowest reached flyer id), highest reached target id + 1
  for (std::size_t p = 0; p < pts.size(); ++p) {
    if (!reached(pts, p)) continue;
    if (pts.id[p] < flyer_) {
      found[1] = std::max(found[1], -pts.x[p][1]);
      found[2] = std::max(found[2], -static_cast<double>(pts.id[p]));
    } else {
      found[0] = std::max(found[0], pts.x[p][1]);
      found[3] = std::max(found[3], static_cast<double>(pts.id[p]) + 1.0);
    }
  }
  comm.max(found, 4);
  if (found[2] > -inf) head_ = static_cast<std::size_t>(-found[2]);
  if (found[3] > -inf) tail_ = static_cast<std::size_t>(found[3]);
  extend(pts, found[0], -found[1]);
  measure_signal(model, pts);
}

template <int D>
UnreachedMaterial<D>::UnreachedMaterial(const Scene& scene, const Model& model, const Particles<D>& pts,
                                        std::size_t head, std::size_t tail, const Comm& comm)
    : UnreachedMaterial(scene, pts, comm) {
  if (head > flyer_ || tail < flyer_ || tail > points_)
    throw SceneError("its unreached material [0, " + std::to_string(head) + ") and [" + std::to_string(tail) + ", " +
                     std::to_string(points_) + ") does not fit its " + std::to_string(flyer_) +
                     " flyer points before the target's");
  double wrong = -std::numeric_limits<double>::infinity();  // -(lowest id saved unreached that is reached)
  for (std::size_t p = 0; p < pts.size(); ++p)
    if ((pts.id[p] < head || pts.id[p] >= tail) && reached(pts, p)) wrong = std::max(wrong, -static_cast<double>(pts.id[p]));
  wrong = comm.max(wrong);
  if (wrong > -std::numeric_limits<double>::infinity())
    throw SceneError("its material point " + std::to_string(static_cast<std::size_t>(-wrong)) +
                     " is saved as unreached but has left its initial state");
  head_ = head;
  tail_ = tail;
  measure_signal(model, pts);
}

template <int D>
PointRange UnreachedMaterial<D>::computed(const Particles<D>& pts) const {
  if (!on_) return {0, pts.size()};
  return {first_at_or_after(pts, head_), first_at_or_after(pts, tail_)};
}

template <int D>
void UnreachedMaterial<D>::measure_signal(const Model& model, const Particles<D>& pts) {
  // Every unreached point of a body has the same state (its body's material at its speed): the
  // signal of one of each (the first flyer point, the first unreached target point, the window's
  // last point), from the rank that holds it.
  double signal = 0.0;
  for (const std::size_t id : {head_ > 0 ? std::size_t{0} : points_, tail_, tail_ < points_ ? points_ - 1 : points_}) {
    const std::size_t sample = id < points_ ? index_of_id(pts, static_cast<std::uint32_t>(id)) : pts.size();
    if (sample >= pts.size()) continue;
    Particles<D> one;
    one.enable_fields_of(pts);
    one.append_copy(pts, sample);
    signal = std::max(signal, initial_signal_speed(one, model));
  }
  signal_ = std::max(comm_->max(signal), 0.0);
}

template <int D>
bool UnreachedMaterial<D>::reached(const Particles<D>& pts, std::size_t p) const {
  if (!(std::abs(pts.E[p]) <= energy_tolerance_)) return true;  // a state set by hand (NaN too), or heat conducted
  const Vec<D>& v = pts.v[p];
  const double v0 = pts.body[p] == Body::flyer ? flyer_velocity_ : target_velocity_;
  for (int d = 0; d < D; ++d)
    if (std::abs(v[d] - (d == 1 ? v0 : 0.0)) > speed_tolerance_) return true;
  const Mat<D>& F = pts.F[p];
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j)
      if (std::abs(F(i, j) - (i == j ? 1.0 : 0.0)) > 1e-12) return true;
  return false;
}

template <int D>
void UnreachedMaterial<D>::advance(Particles<D>& pts, double dt) const {
  if (!on_) return;
  const double flyer_step = flyer_velocity_ * dt, target_step = target_velocity_ * dt;
  const PointRange c = computed(pts);
  const auto head = static_cast<std::ptrdiff_t>(c.begin), tail = static_cast<std::ptrdiff_t>(c.end);
  const auto count = head + static_cast<std::ptrdiff_t>(pts.size()) - tail;  // [0, head) then [tail, n)
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    if (k < head) pts.x[k][1] += flyer_step;
    else pts.x[tail + (k - head)][1] += target_step;
  }
}

template <int D>
void UnreachedMaterial<D>::extend(const Particles<D>& pts, double top, double bottom) {
  // One process scans up from the tail while points lie within the margin of `top`, and down from
  // the head alike; the new boundary is the first point in id order that does not, which each rank
  // finds among its own (in id order), and the ranks agree on the lowest (highest).
  const double inf = std::numeric_limits<double>::infinity();
  const PointRange c = computed(pts);
  double next[2] = {-static_cast<double>(points_), 0.0};  // -(new tail), new head
  if (tail_ < points_)
    for (std::size_t p = c.end; p < pts.size(); ++p)
      if (!(pts.x[p][1] <= top + margin_)) {
        next[0] = -static_cast<double>(pts.id[p]);
        break;
      }
  if (head_ > 0)
    for (std::size_t p = c.begin; p-- > 0;)
      if (!(pts.x[p][1] >= bottom - margin_)) {
        next[1] = static_cast<double>(pts.id[p]) + 1.0;
        break;
      }
  (void)inf;
  comm_->max(next, 2);
  if (tail_ < points_) tail_ = std::max(tail_, static_cast<std::size_t>(-next[0]));
  if (head_ > 0) head_ = std::min(head_, static_cast<std::size_t>(next[1]));
}

template <int D>
void UnreachedMaterial<D>::follow(const Particles<D>& pts) {
  if (!on_ || !any()) return;
  // The highest reached target point and the lowest reached flyer point next to the boundaries.
  const double inf = std::numeric_limits<double>::infinity();
  double found[2] = {-inf, -inf};  // top, -bottom
  const PointRange c = computed(pts);
  if (tail_ < points_) {
    const std::size_t lo = std::max({head_, flyer_, tail_ > band_ ? tail_ - band_ : std::size_t{0}});
    for (std::size_t p = first_at_or_after(pts, lo); p < c.end; ++p)
      if (reached(pts, p)) found[0] = std::max(found[0], pts.x[p][1]);
  }
  if (head_ > 0) {
    const std::size_t hi = std::min({tail_, flyer_, head_ + band_});
    for (std::size_t p = c.begin; p < pts.size() && pts.id[p] < hi; ++p)
      if (reached(pts, p)) found[1] = std::max(found[1], -pts.x[p][1]);
  }
  comm_->max(found, 2);
  extend(pts, found[0], -found[1]);
}

template class UnreachedMaterial<2>;
template class UnreachedMaterial<3>;

}  // namespace mpmshock
