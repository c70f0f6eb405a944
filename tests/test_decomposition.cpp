// Decomposition::balanced: slabs of even work, rank 0 holding the symmetry plane's strips, and no
// rank holding more than kMaxPointShare times the mean number of points even where the work
// alone would give one rank most of them (the material nothing has reached weighs little).
#include <cstdint>
#include <vector>

#include "check.hpp"
#include "mpmshock/decomposition.hpp"
#include "mpmshock/scene.hpp"

using mpmshock::Decomposition;
using Loads = std::vector<std::int64_t>;

namespace {

std::int64_t held(const Decomposition& d, const Loads& per_strip, int rank) {
  std::int64_t n = 0;
  for (int s = d.first_strip(rank); s < d.end_strip(rank); ++s) n += per_strip[static_cast<std::size_t>(s)];
  return n;
}

void even_work_even_slabs() {
  const Loads work(40, 7);
  const Decomposition d = Decomposition::balanced(work, 4);
  CHECK(d.ranks() == 4 && d.strips() == 40);
  for (int r = 0; r < 4; ++r) CHECK(d.end_strip(r) - d.first_strip(r) == 10);
  CHECK_NEAR(d.imbalance(work), 1.0, 1e-12);
  for (int s = 0; s < 40; ++s) CHECK(d.owner(s) == s / 10);
}

void rank_zero_reaches_the_plane() {
  const Loads work(40, 1);
  const Decomposition d = Decomposition::balanced(work, 4, 25);
  CHECK(d.end_strip(0) >= 25);
  for (int r = 1; r < 4; ++r) CHECK(d.end_strip(r) - d.first_strip(r) >= Decomposition::kMinStrips);
}

void too_few_strips_refused() {
  CHECK_THROWS_WITH(Decomposition::balanced(Loads(7, 1), 4), "too few for 4 MPI ranks");
  CHECK_THROWS_WITH(Decomposition::balanced(Loads(7, 1), 4), "at most 3 ranks");
}

// A young front: 8 strips of computed points (weight 50 each) at the bottom, 72 of points nothing
// has reached (weight 1) above, 100 points per strip.
void memory_bounded_where_work_is_not() {
  Loads work(80, 100), points(80, 100);
  for (int s = 0; s < 8; ++s) work[static_cast<std::size_t>(s)] = 100 * Decomposition::kComputedWeight;
  const int ranks = 4;
  const std::int64_t mean = 8000 / ranks, cap = Decomposition::kMaxPointShare * mean;
  // By the work alone the top rank holds most of the points ...
  const Decomposition by_work = Decomposition::balanced(work, ranks);
  CHECK(held(by_work, points, ranks - 1) > cap);
  CHECK(by_work.crowded(points));
  // ... with the points counted none holds more than the cap, every strip is someone's, and the
  // work is as even as that allows: the computed strips still split between the lower ranks.
  const Decomposition d = Decomposition::balanced(work, ranks, 0, points);
  CHECK(!d.crowded(points));
  std::int64_t total = 0;
  for (int r = 0; r < ranks; ++r) {
    CHECK(held(d, points, r) <= cap);
    total += held(d, points, r);
  }
  CHECK(total == 8000 && d.first_strip(0) == 0 && d.end_strip(ranks - 1) == 80);
  // The cap costs only what it must: the ranks below keep the work's slabs, the top rank holds the
  // cap exactly (any less would load its neighbour more), and the work is 1.54 x even (18200 of a
  // mean 11800 on rank 2) against 1.27 by the work alone.
  CHECK(d.end_strip(0) == by_work.end_strip(0) && d.end_strip(1) == by_work.end_strip(1));
  CHECK(held(d, points, ranks - 1) == cap);
  CHECK_NEAR(d.imbalance(work), 18200.0 / 11800.0, 1e-12);
  CHECK_NEAR(by_work.imbalance(work), 15000.0 / 11800.0, 1e-12);
  // Where the work is even the cap changes nothing.
  CHECK(Decomposition::balanced(points, ranks, 0, points) == Decomposition::balanced(points, ranks));
}

}  // namespace

int main() {
  even_work_even_slabs();
  rank_zero_reaches_the_plane();
  too_few_strips_refused();
  memory_bounded_where_work_is_not();
  return check::result();
}
