#include "mpmshock/mirror_image.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mpmshock {
namespace {

// The lattice cell of a point's initial position, with y reflected to the target's side.
template <int D>
std::size_t lattice_cell(const Vec<D>& x, double a, std::size_t columns, std::size_t rows) {
  const auto i = static_cast<std::size_t>(std::lround(x[0] / a - 0.5));
  const auto j = static_cast<std::size_t>(std::lround(std::abs(x[1]) / a - 0.5));
  std::size_t k = 0;
  if constexpr (D == 3) k = static_cast<std::size_t>(std::lround(x[2] / a - 0.5));
  return (k * rows + j) * columns + i;
}

}  // namespace

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
MirrorImage<D>::MirrorImage(const Particles<D>& whole) : on_(true) {
  auto fail = [](const std::string& why) {
    throw std::logic_error("symmetry = on: the flyer is not the target's mirror image: " + why);
  };
  const std::size_t flyer = mpmshock::flyer_points(whole);
  const std::size_t target = whole.size() - flyer;
  if (flyer != target)
    fail(std::to_string(flyer) + " flyer points against " + std::to_string(target) + " target points");
  if (target == 0) return;

  // The target's points on their lattice, by cell.
  const double a = std::pow(whole.V0[flyer], 1.0 / D);
  std::size_t columns = 0, rows = 0, layers = 0;
  for (std::size_t p = flyer; p < whole.size(); ++p) {
    const Vec<D>& x = whole.x[p];
    columns = std::max(columns, static_cast<std::size_t>(std::lround(x[0] / a - 0.5)) + 1);
    rows = std::max(rows, static_cast<std::size_t>(std::lround(x[1] / a - 0.5)) + 1);
    layers = D == 3 ? std::max(layers, static_cast<std::size_t>(std::lround(x[D - 1] / a - 0.5)) + 1) : 1;
  }
  constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::vector<std::uint32_t> at(columns * rows * layers, kNone);
  for (std::size_t p = flyer; p < whole.size(); ++p)
    at[lattice_cell(whole.x[p], a, columns, rows)] = static_cast<std::uint32_t>(p - flyer);

  mirror_of_.resize(flyer);
  std::vector<bool> used(target, false);
  for (std::size_t f = 0; f < flyer; ++f) {
    const Vec<D>& x = whole.x[f];
    const std::size_t cell = x[1] < 0.0 ? lattice_cell(x, a, columns, rows) : at.size();
    const std::uint32_t t = cell < at.size() ? at[cell] : kNone;
    const std::string which = "flyer point " + std::to_string(f);
    if (t == kNone || used[t]) fail(which + " has no target point at its mirror position");
    const std::size_t q = flyer + t;
    const Vec<D> image = reflected(whole.x[q]), velocity = reflected(whole.v[q]);
    for (int d = 0; d < D; ++d)
      if (std::abs(x[d] - image[d]) > 1e-9 * a || whole.v[f][d] != velocity[d])
        fail(which + " is not the mirror image of target point " + std::to_string(t) + " in position or velocity");
    if (whole.m[f] != whole.m[q] || whole.V0[f] != whole.V0[q])
      fail(which + " differs from target point " + std::to_string(t) + " in mass or volume");
    used[t] = true;
    mirror_of_[f] = t;
  }
}

template <int D>
Particles<D> MirrorImage<D>::half(const Particles<D>& whole) const {
  Particles<D> out;
  out.enable_fields_of(whole);
  const std::size_t flyer = mirror_of_.size();
  out.reserve(whole.size() - flyer);
  for (std::size_t p = flyer; p < whole.size(); ++p) {
    out.append_copy(whole, p);
    out.id.back() = static_cast<std::uint32_t>(p - flyer);
  }
  return out;
}

template <int D>
Particles<D> MirrorImage<D>::whole(const Particles<D>& half) const {
  Particles<D> out;
  out.enable_fields_of(half);
  const std::size_t n = mirror_of_.size() + half.size();
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
