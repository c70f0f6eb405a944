#include "mpmshock/decomposition.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "mpmshock/scene.hpp"

namespace mpmshock {

namespace {

std::vector<std::int64_t> prefix_sums(const std::vector<std::int64_t>& v) {
  std::vector<std::int64_t> prefix(v.size() + 1, 0);
  for (std::size_t s = 0; s < v.size(); ++s) prefix[s + 1] = prefix[s] + v[s];
  return prefix;
}

// The most points a rank may hold: kMaxPointShare times the mean, rounded up.
std::int64_t point_cap(std::int64_t total, int ranks) {
  return (Decomposition::kMaxPointShare * total + ranks - 1) / ranks;
}

}  // namespace

Decomposition Decomposition::balanced(const std::vector<std::int64_t>& work, int ranks, int first_end_min,
                                      const std::vector<std::int64_t>& points) {
  const int strips = static_cast<int>(work.size());
  Decomposition d(strips);
  if (ranks <= 1) return d;
  check_ranks(strips, ranks, first_end_min);
  first_end_min = std::max(first_end_min, kMinStrips);
  const std::vector<std::int64_t> prefix = prefix_sums(work);
  const std::int64_t total = prefix.back();
  const bool capped = points.size() == work.size();
  const std::vector<std::int64_t> held = capped ? prefix_sums(points) : std::vector<std::int64_t>{};
  const std::int64_t cap = capped ? point_cap(held.back(), ranks) : 0;
  auto at = [](const std::vector<std::int64_t>& v, int k) { return v[static_cast<std::size_t>(k)]; };
  d.bounds_.assign(static_cast<std::size_t>(ranks) + 1, 0);
  d.bounds_.back() = strips;
  for (int r = 0; r + 1 < ranks; ++r) {
    const int start = d.bounds_[static_cast<std::size_t>(r)];
    const int lowest = std::max(start + kMinStrips, r == 0 ? first_end_min : 0);
    const int highest = strips - (ranks - 1 - r) * kMinStrips;
    // The first strip boundary at which ranks 0..r hold (r + 1) / ranks of the work (integers: the
    // same on every rank).
    int end = lowest;
    while (end < highest && at(prefix, end) * ranks < (r + 1) * total) ++end;
    if (capped) {
      // No more than the cap here, and no more than the cap each for the ranks after this one.
      while (end > lowest && at(held, end) - at(held, start) > cap) --end;
      while (end < highest && at(held, strips) - at(held, end) > (ranks - 1 - r) * cap) ++end;
    }
    d.bounds_[static_cast<std::size_t>(r) + 1] = end;
  }
  return d;
}

int Decomposition::most_ranks(int strips, int first_end_min) {
  const int first = std::max(first_end_min, kMinStrips);
  return strips < first ? 0 : 1 + (strips - first) / kMinStrips;
}

void Decomposition::check_ranks(int strips, int ranks, int first_end_min) {
  if (ranks <= 1 || ranks <= most_ranks(strips, first_end_min)) return;
  const int most = most_ranks(strips, first_end_min);
  std::string why = "the grid has " + std::to_string(strips) + " strips of 4 cell rows, too few for " +
                    std::to_string(ranks) + " MPI ranks: each rank needs " + std::to_string(kMinStrips) + " strips";
  if (first_end_min > kMinStrips)
    why += ", and with symmetry = on rank 0 needs the " + std::to_string(first_end_min) +
           " strips up to the symmetry plane and a stencil past it";
  throw SceneError(why + ", so this grid takes at most " + std::to_string(most) + " ranks; use at most " +
                   std::to_string(most) + " ranks, or finer cells");
}

bool Decomposition::crowded(const std::vector<std::int64_t>& points) const {
  const std::vector<std::int64_t> held = prefix_sums(points);
  const std::int64_t cap = point_cap(held.back(), ranks());
  for (int r = 0; r < ranks(); ++r)
    if (held[static_cast<std::size_t>(end_strip(r))] - held[static_cast<std::size_t>(first_strip(r))] > cap) return true;
  return false;
}

int Decomposition::owner(int strip) const {
  const auto it = std::upper_bound(bounds_.begin() + 1, bounds_.end() - 1, strip);
  return static_cast<int>(it - (bounds_.begin() + 1));
}

double Decomposition::imbalance(const std::vector<std::int64_t>& work) const {
  std::int64_t total = 0, largest = 0;
  for (int r = 0; r < ranks(); ++r) {
    std::int64_t w = 0;
    for (int s = first_strip(r); s < end_strip(r); ++s) w += work[static_cast<std::size_t>(s)];
    total += w;
    largest = std::max(largest, w);
  }
  return total > 0 ? static_cast<double>(largest) * ranks() / static_cast<double>(total) : 1.0;
}

template <int D>
std::vector<char> pack_points(const Particles<D>& p, const std::vector<std::size_t>& which) {
  std::vector<char> out(sizeof(std::uint64_t));
  const std::uint64_t count = which.size();
  std::memcpy(out.data(), &count, sizeof count);
  out.reserve(sizeof count + which.size() * p.bytes_per_point());
  p.for_each_member([&](auto field) {
    const auto& values = p.*field;
    using T = typename std::decay_t<decltype(values)>::value_type;
    const std::size_t at = out.size();
    out.resize(at + which.size() * sizeof(T));
    char* to = out.data() + at;
    for (std::size_t q : which) {
      std::memcpy(to, &values[q], sizeof(T));
      to += sizeof(T);
    }
  });
  return out;
}

template <int D>
void unpack_points(Particles<D>& p, const std::vector<char>& bytes) {
  if (bytes.size() < sizeof(std::uint64_t)) return;
  std::uint64_t count = 0;
  std::memcpy(&count, bytes.data(), sizeof count);
  if (count == 0) return;
  std::size_t at = sizeof count;
  p.for_each_member([&](auto field) {
    auto& values = p.*field;
    using T = typename std::decay_t<decltype(values)>::value_type;
    const std::size_t old = values.size();
    values.resize(old + count);
    std::memcpy(static_cast<void*>(values.data() + old), bytes.data() + at, count * sizeof(T));
    at += count * sizeof(T);
  });
}

template <int D>
void merge_points(Particles<D>& p, const std::vector<char>& keep, const std::vector<std::vector<char>>& arrivals) {
  const std::size_t before = p.size();
  std::vector<std::size_t> bounds{before};  // the sorted runs: the kept points, then each batch
  for (const std::vector<char>& batch : arrivals) {
    unpack_points(p, batch);
    bounds.push_back(p.size());
  }
  std::vector<std::size_t> order;
  order.reserve(p.size());
  for (std::size_t q = 0; q < before; ++q)
    if (keep[q]) order.push_back(q);
  for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {  // merge each batch in
    if (bounds[b] == bounds[b + 1]) continue;
    std::vector<std::size_t> merged;
    merged.reserve(order.size() + bounds[b + 1] - bounds[b]);
    std::size_t i = 0, j = bounds[b];
    while (i < order.size() || j < bounds[b + 1]) {
      if (j == bounds[b + 1] || (i < order.size() && p.id[order[i]] < p.id[j])) merged.push_back(order[i++]);
      else merged.push_back(j++);
    }
    order.swap(merged);
  }
  bool identity = true;
  for (std::size_t k = 0; k < order.size() && identity; ++k) identity = order[k] == k;
  if (identity && order.size() == p.size()) return;  // nothing left and every arrival after the rest
  p.for_each_member([&](auto field) {
    auto& values = p.*field;
    std::decay_t<decltype(values)> merged(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) merged[k] = values[order[k]];
    values.swap(merged);
  });
}

template <int D>
void sort_by_id(Particles<D>& p) {
  if (std::is_sorted(p.id.begin(), p.id.end())) return;
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  p.for_each_member([&](auto field) {
    auto& values = p.*field;
    std::decay_t<decltype(values)> sorted;
    sorted.reserve(values.size());
    for (std::size_t q : order) sorted.push_back(values[q]);
    values.swap(sorted);
  });
}

template <int D>
std::size_t index_of_id(const Particles<D>& p, std::uint32_t id) {
  const auto it = std::lower_bound(p.id.begin(), p.id.end(), id);
  return it != p.id.end() && *it == id ? static_cast<std::size_t>(it - p.id.begin()) : p.size();
}

template <int D>
std::size_t first_at_or_after(const Particles<D>& p, std::size_t id) {
  if (id > 0xffffffffu) return p.size();
  return static_cast<std::size_t>(std::lower_bound(p.id.begin(), p.id.end(), static_cast<std::uint32_t>(id)) -
                                  p.id.begin());
}

template <int D>
Particles<D> gather_points(const Particles<D>& mine, const Comm& comm) {
  if (!comm.parallel()) return mine;
  std::vector<std::size_t> all(mine.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  const std::vector<std::vector<char>> parts = comm.gather(pack_points(mine, all));
  Particles<D> whole;
  whole.enable_fields_of(mine);
  for (const std::vector<char>& part : parts) unpack_points(whole, part);
  sort_by_id(whole);
  return whole;
}

#define MPMSHOCK_INSTANTIATE(D)                                                                     \
  template std::vector<char> pack_points<D>(const Particles<D>&, const std::vector<std::size_t>&); \
  template void unpack_points<D>(Particles<D>&, const std::vector<char>&);                       \
  template void merge_points<D>(Particles<D>&, const std::vector<char>&, const std::vector<std::vector<char>>&); \
  template void sort_by_id<D>(Particles<D>&);                                                    \
  template std::size_t index_of_id<D>(const Particles<D>&, std::uint32_t);                       \
  template std::size_t first_at_or_after<D>(const Particles<D>&, std::size_t);                   \
  template Particles<D> gather_points<D>(const Particles<D>&, const Comm&);
MPMSHOCK_INSTANTIATE(2)
MPMSHOCK_INSTANTIATE(3)
#undef MPMSHOCK_INSTANTIATE

}  // namespace mpmshock
