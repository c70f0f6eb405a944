// Domain decomposition over MPI ranks: slabs of whole strips along y, the direction the shock runs.
//
// The grid's node rows are cut into strips of StripBins::kRowsPerStrip rows; rank r owns the strips
// [first_strip(r), end_strip(r)) and the material points whose first node row lies in them (the row
// StripBins sorts them by). A rank holds its slab's node rows and the S - 1 rows above it that its
// top strip's points also touch (halo.hpp). Slabs are chosen so that the ranks' work is even: each
// strip weighs its computed points (kComputedWeight each) and the points nothing has reached yet
// (1 each: they are only moved), and the slabs are re-chosen as the material moves and compresses
// (Simulation::step, every 20 steps when that evens the work by 5 % or more). Even work is not even
// memory: the points nothing has reached weigh little, so the rank whose slab holds them would
// hold most of the points; no rank is given more than kMaxPointShare times the mean number of
// points where the strips allow it, at the cost of less even work while the front is young.
// Results do not depend on the slabs: every sum of the step is one process's
// (halo.hpp, exact_sum.hpp), so the slabs are free to follow the load.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mpmshock/comm.hpp"
#include "mpmshock/grid.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

class Decomposition {
 public:
  // A computed point-step costs 100-150 ns; an unreached point's (its closed-form move and the
  // check that it stays in its slab) about 2 ns.
  static constexpr std::int64_t kComputedWeight = 50;
  static constexpr int kMinStrips = 2;  // per rank: a point moves under a cell per step, so only to a neighbour
  static constexpr std::int64_t kMaxPointShare = 2;  // the most points a rank holds, over the mean

  // One rank holding all `strips`.
  explicit Decomposition(int strips = 0) : bounds_{0, strips} {}
  // Slabs of even work for `ranks`, from each strip's work; rank 0's slab reaches at least to strip
  // `first_end_min` (it must hold the symmetry plane's rows). With `points` (per strip) no rank holds
  // more than kMaxPointShare times the mean where the strips allow it. Throws SceneError when the
  // grid has too few strips for that many ranks.
  static Decomposition balanced(const std::vector<std::int64_t>& work, int ranks, int first_end_min = 0,
                                const std::vector<std::int64_t>& points = {});
  // The most ranks `strips` strips take when rank 0's slab must reach strip `first_end_min`.
  static int most_ranks(int strips, int first_end_min);
  // Throws SceneError, saying why and how many ranks fit, where `strips` are too few for `ranks`.
  static void check_ranks(int strips, int ranks, int first_end_min);
  // Whether some rank holds more points than balanced() allows.
  bool crowded(const std::vector<std::int64_t>& points) const;

  int ranks() const { return static_cast<int>(bounds_.size()) - 1; }
  int strips() const { return bounds_.back(); }
  int first_strip(int rank) const { return bounds_[static_cast<std::size_t>(rank)]; }
  int end_strip(int rank) const { return bounds_[static_cast<std::size_t>(rank) + 1]; }
  int owner(int strip) const;
  // The largest rank's work over the mean (1: even).
  double imbalance(const std::vector<std::int64_t>& work) const;
  const std::vector<int>& bounds() const { return bounds_; }
  bool operator==(const Decomposition& o) const { return bounds_ == o.bounds_; }
  bool operator!=(const Decomposition& o) const { return bounds_ != o.bounds_; }

 private:
  std::vector<int> bounds_;  // ranks + 1 strip indices
};

// Moving material points between ranks. Each rank keeps its points in id order (the order one
// process stores them in, which StripBins' sums follow), so points that arrive are merged in.

// The bytes of the points `which` (every field the layout holds).
template <int D>
std::vector<char> pack_points(const Particles<D>& p, const std::vector<std::size_t>& which);
// Appends the points of `bytes` (made by pack_points from the same layout).
template <int D>
void unpack_points(Particles<D>& p, const std::vector<char>& bytes);
// The points (in id order) that stay (their flag set) and those that arrive (each batch made by
// pack_points from points in id order), merged into id order in one pass over each field.
template <int D>
void merge_points(Particles<D>& p, const std::vector<char>& keep, const std::vector<std::vector<char>>& arrivals);
// Puts the points in id order (a no-op for points already in it).
template <int D>
void sort_by_id(Particles<D>& p);
// The storage index of the point with this id, or p.size() (the points in id order).
template <int D>
std::size_t index_of_id(const Particles<D>& p, std::uint32_t id);
// The first storage index whose id is at least `id`.
template <int D>
std::size_t first_at_or_after(const Particles<D>& p, std::size_t id);

// Every rank's points at rank 0, in id order (empty elsewhere): the whole set, for a snapshot.
template <int D>
Particles<D> gather_points(const Particles<D>& mine, const Comm& comm);

}  // namespace mpmshock
