// Race-free particle-to-grid scatter. Points are grouped by the first node row (y) they touch into
// strips of kRowsPerStrip cell rows (slabs in 3D). Two strips of the same colour (even or odd index) touch
// disjoint node rows, so each colour is scattered in parallel with no atomics and no per-thread
// copies of the grid. Every node then sums its contributions in a fixed order (even strip, then
// odd strip, points in storage order), so results do not depend on the number of threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/lanes.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

class StripBins {
 public:
  static constexpr int kRowsPerStrip = 4;  // must be >= shape support - 1
  // Memory per point (order_ and strip_of_), for the --check estimate.
  static constexpr std::size_t kBytesPerPoint = sizeof(std::uint32_t) + sizeof(int);

  // Groups the points of `range` by strip (a stable counting sort of their indices). Returns false
  // if one lies outside the rows [0, ny - support], which the caller reports; the bins are then invalid.
  template <class Shape, int D>
  bool build(const std::vector<Vec<D>>& x, PointRange range, const GridGeometry<D>& g);

  // Node rows the points touch.
  RowRange rows() const { return rows_; }

  // Calls f(point) for every point: strips of colour 0, then colour 1, each colour in parallel.
  // Between the colours and after the second, `between()` and `after()` run (on an MPI rank they
  // pass the sums of the rows it shares with its neighbours on: halo.hpp).
  template <class F, class Between, class After>
  void scatter(F&& f, Between&& between, After&& after) const {
    for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1)
      for (int k = colour; k < strips_; k += 2) {
        for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i) f(static_cast<std::size_t>(order_[i]));
      }
      if (colour == 0) between();
    }
    after();
  }
  template <class F>
  void scatter(F&& f) const {
    scatter(f, [] {}, [] {});
  }

 private:
  int strips_ = 0;
  RowRange rows_;
  std::vector<std::uint32_t> start_;  // strips_ + 1 offsets into order_
  std::vector<std::uint32_t> order_;  // point indices grouped by strip
  std::vector<int> strip_of_;         // scratch: strip of each point
};

template <class Shape, int D>
bool StripBins::build(const std::vector<Vec<D>>& x, PointRange range, const GridGeometry<D>& g) {
  static_assert(kRowsPerStrip >= Shape::support - 1, "strips too thin for this shape function");
  const std::size_t n = x.size(), first = range.begin, end = range.end;
  const int last_row = g.ny - Shape::support;  // highest first row that stays on the grid
  strips_ = (g.ny - 1) / kRowsPerStrip + 1;
  start_.assign(static_cast<std::size_t>(strips_) + 1, 0);
  strip_of_.resize(n);
  order_.resize(end - first);

  int lo = last_row, hi = 0;
  bool inside = true;
  // Four points at a time (the rows of the last group's spare lanes are its last point's).
  const std::size_t groups = (end - first + 3) / 4;
#pragma omp parallel for schedule(dynamic, kChunk / 4) reduction(min : lo) reduction(max : hi) reduction(&& : inside)
  for (std::size_t k = 0; k < groups; ++k) {
    const std::size_t p = first + 4 * k, n = std::min<std::size_t>(4, end - p);
    Lanes y;
    for (std::size_t l = 0; l < 4; ++l) y[l] = x[p + std::min(l, n - 1)][1];
    LaneInts row;
    Shape::first_rows(row, y, g);
    const LaneInts r = row < 0 ? LaneInts{} : (row > last_row ? LaneInts{} + last_row : row);
    const LaneInts strip = r / kRowsPerStrip;
    const LaneInts out = (row < 0) | (row > last_row);  // -1 where outside
    const int lo4 = std::min(std::min(r[0], r[1]), std::min(r[2], r[3]));
    const int hi4 = std::max(std::max(r[0], r[1]), std::max(r[2], r[3]));
    lo = lo4 < lo ? lo4 : lo;
    hi = hi4 > hi ? hi4 : hi;
    inside = inside && ((out[0] | out[1]) | (out[2] | out[3])) == 0;
    if (n == 4) std::memcpy(&strip_of_[p], &strip, sizeof strip);
    else for (std::size_t l = 0; l < n; ++l) strip_of_[p + l] = strip[l];
  }
  if (!inside) return false;
  for (std::size_t p = first; p < end; ++p) ++start_[static_cast<std::size_t>(strip_of_[p]) + 1];
  for (int k = 0; k < strips_; ++k) start_[k + 1] += start_[k];
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t p = first; p < end; ++p)
    order_[next[static_cast<std::size_t>(strip_of_[p])]++] = static_cast<std::uint32_t>(p);
  rows_ = end > first ? RowRange{lo, hi + Shape::support} : RowRange{};
  return true;
}

}  // namespace mpmshock
