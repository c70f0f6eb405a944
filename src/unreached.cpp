#include "mpmshock/unreached.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mpmshock/constitutive.hpp"
#include "mpmshock/parallel.hpp"

namespace mpmshock {

template <int D>
UnreachedMaterial<D>::UnreachedMaterial(const Scene& scene, std::size_t points, std::size_t flyer)
    : on_(true), points_(points), flyer_(flyer), head_(flyer), tail_(flyer), flyer_velocity_(scene.velocity),
      target_velocity_(-scene.velocity), margin_(kMarginCells * scene.cell_size),
      speed_tolerance_(1e-9 * std::max(scene.velocity, 1.0)),
      energy_tolerance_(1e-12 * 0.5 * std::max(scene.velocity, 1.0) * std::max(scene.velocity, 1.0)) {
  // The points of 2 margins of lattice rows: the band next to a boundary that follow() examines.
  const double a = scene.particle_spacing();
  band_ = static_cast<std::size_t>(2.0 * std::ceil(margin_ / a) * std::pow(std::round(scene.width / a), D - 1));
}

template <int D>
UnreachedMaterial<D>::UnreachedMaterial(const Scene& scene, const Model& model, const Particles<D>& pts)
    : UnreachedMaterial(scene, pts.size(), flyer_points(pts)) {
  // The impact plane is where the bodies are first reached, unless a point has left its initial
  // state already (a state set up by hand).
  double top = 0.0, bottom = 0.0;
  for (std::size_t p = 0; p < points_; ++p) {
    if (!reached(pts, p)) continue;
    if (p < flyer_) {
      bottom = std::min(bottom, pts.x[p][1]);
      head_ = std::min(head_, p);
    } else {
      top = std::max(top, pts.x[p][1]);
      tail_ = p + 1;
    }
  }
  while (head_ > 0 && pts.x[head_ - 1][1] >= bottom - margin_) --head_;
  while (tail_ < points_ && pts.x[tail_][1] <= top + margin_) ++tail_;
  measure_signal(model, pts);
}

template <int D>
UnreachedMaterial<D>::UnreachedMaterial(const Scene& scene, const Model& model, const Particles<D>& pts,
                                        std::size_t head, std::size_t tail)
    : UnreachedMaterial(scene, pts.size(), flyer_points(pts)) {
  if (head > flyer_ || tail < flyer_ || tail > points_)
    throw SceneError("its unreached material [0, " + std::to_string(head) + ") and [" + std::to_string(tail) + ", " +
                     std::to_string(points_) + ") does not fit its " + std::to_string(flyer_) +
                     " flyer points before the target's");
  for (std::size_t p = 0; p < points_; ++p) {
    if (p == head) p = tail;
    if (p < points_ && reached(pts, p))
      throw SceneError("its material point " + std::to_string(pts.id[p]) +
                       " is saved as unreached but has left its initial state");
  }
  head_ = head;
  tail_ = tail;
  measure_signal(model, pts);
}

template <int D>
void UnreachedMaterial<D>::measure_signal(const Model& model, const Particles<D>& pts) {
  const std::size_t sample = head_ > 0 ? 0 : tail_;
  signal_ = 0.0;
  if (sample >= points_) return;
  Particles<D> one;  // every unreached point has the same state: the signal of one
  one.enable_fields_of(pts);
  one.append_copy(pts, sample);
  signal_ = initial_signal_speed(one, model);
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
  const auto head = static_cast<std::ptrdiff_t>(head_), tail = static_cast<std::ptrdiff_t>(tail_);
  const auto count = head + static_cast<std::ptrdiff_t>(points_) - tail;  // [0, head) then [tail, n)
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    if (k < head) pts.x[k][1] += flyer_step;
    else pts.x[tail + (k - head)][1] += target_step;
  }
}

template <int D>
void UnreachedMaterial<D>::follow(const Particles<D>& pts) {
  if (!on_) return;
  if (tail_ < points_) {  // the target: the highest reached point next to the boundary
    const std::size_t lo = std::max({head_, flyer_, tail_ > band_ ? tail_ - band_ : std::size_t{0}});
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t p = lo; p < tail_; ++p)
      if (reached(pts, p)) top = std::max(top, pts.x[p][1]);
    while (tail_ < points_ && pts.x[tail_][1] <= top + margin_) ++tail_;
  }
  if (head_ > 0) {  // the flyer: the lowest reached point next to the boundary
    const std::size_t hi = std::min({tail_, flyer_, head_ + band_});
    double bottom = std::numeric_limits<double>::infinity();
    for (std::size_t p = head_; p < hi; ++p)
      if (reached(pts, p)) bottom = std::min(bottom, pts.x[p][1]);
    while (head_ > 0 && pts.x[head_ - 1][1] >= bottom - margin_) --head_;
  }
}

template class UnreachedMaterial<2>;
template class UnreachedMaterial<3>;

}  // namespace mpmshock
