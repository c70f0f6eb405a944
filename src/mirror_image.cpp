#include "mpmshock/mirror_image.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mpmshock {
template <int D>
void reflect_point(Particles<D>& pts, std::size_t p) {
  pts.x[p] = reflected(pts.x[p]);
  pts.v[p] = reflected(pts.v[p]);
  pts.F[p] = reflected(pts.F[p]);
  pts.L[p] = reflected(pts.L[p]);
  if (pts.has_strength()) pts.s[p] = reflected(pts.s[p]);
  if (pts.has_back_stress()) pts.alpha[p] = reflected(pts.alpha[p]);
}

template <int D>
MirrorImage<D>::MirrorImage(const std::vector<std::size_t>& flyer_rows, const std::vector<std::size_t>& target_rows)
    : on_(true) {
  const std::size_t rows = flyer_rows.size();
  if (target_rows.size() != rows)
    throw std::logic_error("symmetry = on: the flyer is not the target's mirror image: " + std::to_string(rows) +
                           " flyer rows against " + std::to_string(target_rows.size()));
  for (std::size_t j = 0; j < rows; ++j) {
    if (flyer_rows[j] != target_rows[rows - 1 - j])
      throw std::logic_error("symmetry = on: the flyer is not the target's mirror image: flyer row " +
                             std::to_string(j) + " holds " + std::to_string(flyer_rows[j]) +
                             " points, its mirror row " + std::to_string(target_rows[rows - 1 - j]));
    flyer_start_.push_back(flyer_start_.back() + flyer_rows[j]);
    target_start_.push_back(target_start_.back() + target_rows[j]);
  }
}

template <int D>
Particles<D> MirrorImage<D>::half(const Particles<D>& whole, std::size_t first) const {
  Particles<D> out;
  out.enable_fields_of(whole);
  const std::size_t flyer = flyer_points();
  const std::size_t from = std::min(whole.size(), flyer > first ? flyer - first : 0);
  out.reserve(whole.size() - from);
  for (std::size_t p = from; p < whole.size(); ++p) {
    out.append_copy(whole, p);
    out.id.back() = static_cast<std::uint32_t>(first + p - flyer);
  }
  return out;
}

template <int D>
Particles<D> MirrorImage<D>::whole(const Particles<D>& half) const {
  Particles<D> out;
  out.enable_fields_of(half);
  const std::size_t n = flyer_points() + half.size();
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto [q, mirrored] = source_of(static_cast<std::uint32_t>(k));
    out.append_copy(half, q);
    out.id[k] = static_cast<std::uint32_t>(k);
    if (!mirrored) continue;
    reflect_point(out, k);
    out.body[k] = Body::flyer;
  }
  return out;
}

template <int D>
Particles<D> MirrorImage<D>::with_images(const Particles<D>& half) const {
  Particles<D> out;
  out.enable_fields_of(half);
  out.reserve(2 * half.size());
  for (std::size_t q = 0; q < half.size(); ++q) out.append_copy(half, q);
  for (std::size_t q = 0; q < half.size(); ++q) {  // every target point has its image: the mirror is a bijection
    out.append_copy(half, q);
    reflect_point(out, out.size() - 1);
    out.body.back() = Body::flyer;
  }
  return out;
}

template <int D>
Totals MirrorImage<D>::whole(const Totals& half) const {
  if (!on_) return half;
  Totals t;
  t.mass = whole_sum(half.mass);
  t.momentum[0] = whole_sum(half.momentum[0]);
  t.momentum[1] = 0.0;  // the flyer's is the target's, reversed
  t.momentum[2] = whole_sum(half.momentum[2]);
  t.momentum_magnitude = whole_sum(half.momentum_magnitude);
  t.kinetic = whole_sum(half.kinetic);
  t.internal = whole_sum(half.internal);
  return t;
}

template void reflect_point<2>(Particles<2>&, std::size_t);
template void reflect_point<3>(Particles<3>&, std::size_t);
template class MirrorImage<2>;
template class MirrorImage<3>;

}  // namespace mpmshock
