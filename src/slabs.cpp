// The slabs of the MPI ranks (decomposition.hpp) as the integrator keeps them: each rank's grid
// rows and halo, the points moving to the rank whose slab holds them (one hop per step, or many
// after new slabs), and new slabs when the measured work has drifted. Outside step(), which calls
// rebalance() before and migrate() after the algorithm (simulation.cpp); one process never calls
// them.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "mpmshock/simulation.hpp"
#include "slab_rows.hpp"

namespace mpmshock {

template <int D>
int Simulation<D>::first_strip_end_needed() const {
  return mpmshock::first_strip_end_needed(whole_geo_, model_.symmetry_plane, kernels_.support);
}

template <int D>
int Simulation<D>::first_row_held() const {
  // With a symmetry plane no point goes below y = 0, so no stencil reaches below its support's rows
  // under the plane: the ghost rows further down are never used, and not held.
  if (!model_.symmetry_plane) return 0;
  const int plane_row = static_cast<int>(std::lround(-whole_geo_.y_min * whole_geo_.inv_h));
  return std::max(0, plane_row - kernels_.support);
}

template <int D>
int Simulation<D>::strip_of(double y) const {
  const int last_row = whole_geo_.ny - kernels_.support;  // as StripBins clamps a point off the grid
  const int row = std::clamp(kernels_.first_row(y, whole_geo_), 0, last_row);
  return row / StripBins::kRowsPerStrip;
}

template <int D>
void Simulation<D>::take_slab(const Decomposition& slabs) {
  slabs_ = slabs;
  const int rank = comm_->rank(), first = slabs.first_strip(rank), end = slabs.end_strip(rank);
  const int rows0 = std::max(first * StripBins::kRowsPerStrip, first_row_held());
  const int rows1 = std::min(whole_geo_.ny, end * StripBins::kRowsPerStrip + kernels_.support - 1);
  grid_ = Grid<D>(whole_geo_.holding(rows0, rows1));
  halo_ = Halo<D>(*comm_, grid_.geo, first, end, StripBins::kRowsPerStrip, kernels_.support, rank > 0,
                  rank + 1 < comm_->size());
}

template <int D>
bool Simulation<D>::hop(std::size_t most) {
  const int rank = comm_->rank(), size = comm_->size();
  const int below = rank > 0 ? rank - 1 : -1, above = rank + 1 < size ? rank + 1 : -1;
  std::vector<std::size_t> down, up;
  std::vector<char> keep(points_.size(), 1);
  // Points two cells inside the slab are home whatever the shape function's first row: only those
  // near its edges need their strip.
  const double inf = std::numeric_limits<double>::infinity(), h = whole_geo_.h;
  const double inside_from = rank > 0 ? whole_geo_.y_min + (slabs_.first_strip(rank) * StripBins::kRowsPerStrip + 2) * h : -inf;
  const double inside_to = above >= 0 ? whole_geo_.y_min + (slabs_.end_strip(rank) * StripBins::kRowsPerStrip - 2) * h : inf;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const double y = points_.x[p][1];
    if (y > inside_from && y < inside_to) continue;
    const int owner = slabs_.owner(strip_of(y));
    if (owner == rank) continue;
    std::vector<std::size_t>& way = owner < rank ? down : up;
    if (way.size() == most) continue;  // in a later hop
    way.push_back(p);
    keep[p] = 0;
  }
  // Sizes first, then the points, each in one round with both neighbours.
  const std::vector<char> to_up = up.empty() ? std::vector<char>{} : pack_points(points_, up);
  const std::vector<char> to_down = down.empty() ? std::vector<char>{} : pack_points(points_, down);
  std::vector<char> n_up(sizeof(std::uint64_t)), n_down(sizeof(std::uint64_t));
  std::vector<char> from_up(sizeof(std::uint64_t)), from_down(sizeof(std::uint64_t));
  const std::uint64_t sizes[2] = {to_up.size(), to_down.size()};
  std::memcpy(n_up.data(), &sizes[0], sizeof(std::uint64_t));
  std::memcpy(n_down.data(), &sizes[1], sizeof(std::uint64_t));
  comm_->swap(above, n_up, from_up, below, n_down, from_down);
  std::uint64_t incoming[2] = {0, 0};
  if (above >= 0) std::memcpy(&incoming[0], from_up.data(), sizeof(std::uint64_t));
  if (below >= 0) std::memcpy(&incoming[1], from_down.data(), sizeof(std::uint64_t));
  from_up.assign(incoming[0], 0);
  from_down.assign(incoming[1], 0);
  comm_->swap(above, to_up, from_up, below, to_down, from_down);
  const bool sent = !up.empty() || !down.empty();
  if (sent || !from_up.empty() || !from_down.empty()) merge_points(points_, keep, {from_up, from_down});
  return sent;
}

template <int D>
void Simulation<D>::migrate() {
  // A point moves under a cell per step and a slab is at least two strips, so a point that left its
  // slab is in a neighbour's: one hop.
  hop();
}

template <int D>
void Simulation<D>::redistribute() {
  // After new slabs points may be farther from home, and many: they hop, at most an eighth of the
  // rank's points (64 Ki at least) each way at a time, so that what is in flight stays a fraction of
  // a share and the hops few, until every rank has only its own.
  const std::size_t batch = std::max<std::size_t>(65536, points_.size() / 8);
  while (comm_->sum(static_cast<std::int64_t>(hop(batch))) > 0) {
  }
}

template <int D>
typename Simulation<D>::StripLoads Simulation<D>::strip_loads() const {
  const std::size_t strips = static_cast<std::size_t>(slabs_.strips());
  std::vector<std::int64_t> both(2 * strips, 0);  // the weights, then the points
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const auto s = static_cast<std::size_t>(strip_of(points_.x[p][1]));
    both[s] += unreached_.unreached(points_, p) ? 1 : Decomposition::kComputedWeight;
    ++both[strips + s];
  }
  comm_->sum(both.data(), static_cast<int>(both.size()));
  return {{both.begin(), both.begin() + static_cast<std::ptrdiff_t>(strips)},
          {both.begin() + static_cast<std::ptrdiff_t>(strips), both.end()}};
}

template <int D>
void Simulation<D>::rebalance() {
  // Every kBalanceSteps steps the slabs follow the work, when that evens it out by 5 % or more.
  // The work of a strip is its points' weights (decomposition.hpp) times the time a weight took on
  // the rank that holds it since the last balance: the weights say where the points are, the times
  // what they cost there (plastic flow, compressed cells, a busy core). The slabs then depend on the
  // machine, the results do not (halo.hpp).
  constexpr std::int64_t kBalanceSteps = 20;
  if (balanced_once_ && clock_.steps - last_balance_step_ < kBalanceSteps) return;
  // The first balance (before the first step) goes by the weights alone; later ones by the time the
  // steps since took, outside MPI calls (outputs are not steps: they do not count).
  const double busy = busy_seconds_;
  const bool measured = balanced_once_ && busy > 0.0;
  balanced_once_ = true;
  busy_seconds_ = 0.0;
  last_balance_step_ = clock_.steps;
  const StripLoads loads = strip_loads();
  const std::vector<std::int64_t>& weights = loads.weights;
  const int ranks = comm_->size(), rank = comm_->rank();
  std::int64_t mine = 0;
  for (int s = slabs_.first_strip(rank); s < slabs_.end_strip(rank); ++s) mine += weights[static_cast<std::size_t>(s)];
  std::vector<double> seconds_per_weight(static_cast<std::size_t>(ranks), 0.0);
  seconds_per_weight[static_cast<std::size_t>(rank)] = measured && mine > 0 ? std::max(busy, 0.0) / static_cast<double>(mine) : 0.0;
  comm_->max(seconds_per_weight.data(), ranks);
  double typical = 0.0;  // ranks that measured nothing take the mean of those that did
  int counted = 0;
  for (double f : seconds_per_weight)
    if (f > 0.0) typical += f, ++counted;
  typical = counted > 0 ? typical / counted : 1.0;
  std::vector<std::int64_t> work(weights.size());
  for (std::size_t s = 0; s < weights.size(); ++s) {
    const double f = seconds_per_weight[static_cast<std::size_t>(slabs_.owner(static_cast<int>(s)))];
    work[s] = static_cast<std::int64_t>(std::llround(static_cast<double>(weights[s]) * (f > 0.0 ? f : typical) / typical * 64.0));
  }
  const Decomposition better = Decomposition::balanced(work, ranks, first_strip_end_needed(), loads.points);
  imbalance_ = slabs_.imbalance(work);
  if (better == slabs_) return;
  // New slabs for a rank holding too many points, or for work 5 % more even.
  const bool relieves = slabs_.crowded(loads.points) && !better.crowded(loads.points);
  if (!relieves && imbalance_ < better.imbalance(work) + 0.05) return;
  take_slab(better);
  redistribute();
  imbalance_ = better.imbalance(work);
}

#define MPMSHOCK_SLABS(D)                                                                 \
  template int Simulation<D>::first_strip_end_needed() const;                             \
  template int Simulation<D>::first_row_held() const;                                     \
  template int Simulation<D>::strip_of(double) const;                                     \
  template void Simulation<D>::take_slab(const Decomposition&);                           \
  template bool Simulation<D>::hop(std::size_t);                                          \
  template void Simulation<D>::migrate();                                                 \
  template void Simulation<D>::redistribute();                                            \
  template typename Simulation<D>::StripLoads Simulation<D>::strip_loads() const;         \
  template void Simulation<D>::rebalance();
MPMSHOCK_SLABS(2)
MPMSHOCK_SLABS(3)
#undef MPMSHOCK_SLABS

}  // namespace mpmshock
