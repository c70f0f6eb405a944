// The flyer as the mirror image of the target (symmetry = on). A symmetric scene (the flyer the
// target's mirror image about y = 0, moving the other way) stays symmetric, so the run simulates the
// target's points alone (symmetry_plane.hpp keeps the plane) and every output shows the whole
// impact: the flyer's points are the target's reflected, y -> -y, with v_y, the xy (and yz)
// components of F, L, s and alpha negated, and the ids a whole-domain run gives them.
//
//   snapshots   the whole set of points, as a whole-domain run writes them (same layout and ids)
//   regions     the target's regions from the simulated points; a band reaching within a cell of
//               y = 0 from the whole set (built at each sample)
//   conservation  whole-domain totals: twice the target's mass, x momentum and energies, y momentum 0
//   probes      a flyer point is read as the mirror of its target point
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

template <int D>
class MirrorImage {
 public:
  // Off: the points simulated are the whole.
  MirrorImage() = default;
  // From the points set-up makes in each lattice row (the flyer's bottom row first, then the
  // target's, each row's points in the same order across it): flyer row j mirrors target row
  // rows - 1 - j point for point. Throws std::logic_error if the rows do not mirror.
  MirrorImage(const std::vector<std::size_t>& flyer_rows, const std::vector<std::size_t>& target_rows);

  bool on() const { return on_; }
  std::size_t flyer_points() const { return on_ ? flyer_start_.back() : 0; }

  // The points to simulate: the target's, numbered from 0 in their whole-run order. `whole` may
  // be the points of ids [first, first + whole.size()) of the whole alone.
  Particles<D> half(const Particles<D>& whole, std::size_t first = 0) const;
  // The whole set from the simulated points: the mirrored flyer, then the target, in id order.
  Particles<D> whole(const Particles<D>& half) const;
  // Some of the simulated points (an MPI rank's) and the flyer points that mirror them, for sums
  // over the whole (region statistics; the ids of the images are not kept).
  Particles<D> with_images(const Particles<D>& half) const;
  // The totals of the whole from those of the simulated points.
  Totals whole(const Totals& half) const;
  // A sum over the whole (of a quantity the mirror image does not change sign) from its sum over
  // the simulated points.
  double whole_sum(double half) const { return on_ ? 2.0 * half : half; }

  // A point of the whole run (by id) as the simulated point it is or mirrors.
  struct Source {
    std::uint32_t point;
    bool mirrored;
  };
  Source source_of(std::uint32_t whole_id) const {
    if (!on_) return {whole_id, false};
    const std::size_t n = flyer_start_.back();
    if (whole_id >= n) return {static_cast<std::uint32_t>(whole_id - n), false};
    const std::size_t row = row_of(flyer_start_, whole_id), rows = flyer_start_.size() - 1;
    return {static_cast<std::uint32_t>(target_start_[rows - 1 - row] + (whole_id - flyer_start_[row])), true};
  }
  // The whole run's id of the flyer point that mirrors simulated (target) point `id`.
  std::uint32_t image_of(std::uint32_t id) const {
    const std::size_t row = row_of(target_start_, id), rows = target_start_.size() - 1;
    return static_cast<std::uint32_t>(flyer_start_[rows - 1 - row] + (id - target_start_[row]));
  }

 private:
  bool on_ = false;
  // The first point of each lattice row (and one past the last row): flyer ids, target ids from 0.
  std::vector<std::size_t> flyer_start_{0}, target_start_{0};
  static std::size_t row_of(const std::vector<std::size_t>& start, std::size_t id) {
    return static_cast<std::size_t>(std::upper_bound(start.begin(), start.end(), id) - start.begin()) - 1;
  }
};

// Reflects point p in place about y = 0.
template <int D>
void reflect_point(Particles<D>& pts, std::size_t p);

// The reflections about y = 0 of a point's fields: y negated; in a tensor, the components that
// couple y with another axis.
template <int D>
Vec<D> reflected(Vec<D> u) {
  u[1] = -u[1];
  return u;
}
template <int D>
Mat<D> reflected(const Mat<D>& a) {
  Mat<D> r = a;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j)
      if ((i == 1) != (j == 1)) r(i, j) = -a(i, j);
  return r;
}
inline Deviator<2> reflected(const Deviator<2>& s) { return {s.xx, s.yy, -s.xy}; }
inline Deviator<3> reflected(const Deviator<3>& s) { return {s.xx, s.yy, -s.xy, -s.yz_, s.zx_}; }

extern template class MirrorImage<2>;
extern template class MirrorImage<3>;

}  // namespace mpmshock
