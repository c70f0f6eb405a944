#include "mpmshock/voids.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mpmshock {
namespace {

// Buckets of voids for the overlap test, periodic in x. A bucket is at least as wide as the
// largest centre distance that can still overlap, so only the 3x3 neighbourhood is searched.
class VoidBuckets {
 public:
  VoidBuckets(const Lattice& lat, double reach) : width_(lat.width()), y0_(lat.y0) {
    nx_ = std::max(1, static_cast<int>(std::floor(width_ / reach)));
    ny_ = std::max(1, static_cast<int>(std::floor(lat.height() / reach)));
    bx_ = width_ / nx_;
    by_ = lat.height() / ny_;
    buckets_.resize(static_cast<std::size_t>(nx_) * ny_);
  }

  void insert(const Void& v, std::size_t index) { buckets_[bucket(v.x, v.y)].push_back(index); }

  // True if a void at (x, y, r) stays at least `gap` away from every stored one.
  bool clear_of(const std::vector<Void>& voids, double x, double y, double r, double gap) const {
    const int cx = column(x), cy = row(y);
    int columns[3] = {cx, (cx + 1) % nx_, (cx + nx_ - 1) % nx_};
    const int ncol = nx_ >= 3 ? 3 : nx_;  // fewer than 3 columns: every column is a neighbour
    if (nx_ < 3) for (int k = 0; k < nx_; ++k) columns[k] = k;
    for (int dy = -1; dy <= 1; ++dy) {
      const int ry = cy + dy;
      if (ry < 0 || ry >= ny_) continue;
      for (int k = 0; k < ncol; ++k) {
        for (std::size_t index : buckets_[static_cast<std::size_t>(ry) * nx_ + columns[k]]) {
          const Void& o = voids[index];
          double dx = std::abs(o.x - x);
          dx = std::min(dx, width_ - dx);
          const double dyv = o.y - y;
          const double reach = r + o.r + gap;
          if (dx * dx + dyv * dyv < reach * reach) return false;
        }
      }
    }
    return true;
  }

 private:
  int column(double x) const { return std::min(nx_ - 1, std::max(0, static_cast<int>(x / bx_))); }
  int row(double y) const { return std::min(ny_ - 1, std::max(0, static_cast<int>((y - y0_) / by_))); }
  std::size_t bucket(double x, double y) const { return static_cast<std::size_t>(row(y)) * nx_ + column(x); }

  double width_, y0_, bx_ = 0, by_ = 0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> buckets_;
};

// Lattice points inside a void (periodic in x), as indices.
std::vector<std::size_t> points_inside(const Lattice& lat, const Void& v) {
  std::vector<std::size_t> out;
  const double a = lat.spacing;
  const int j_lo = std::max(0, static_cast<int>(std::floor((v.y - v.r - lat.y0) / a - 0.5)));
  const int j_hi = std::min(lat.rows - 1, static_cast<int>(std::ceil((v.y + v.r - lat.y0) / a - 0.5)));
  const int i_lo = static_cast<int>(std::floor((v.x - v.r - lat.x0) / a - 0.5));
  const int i_hi = static_cast<int>(std::ceil((v.x + v.r - lat.x0) / a - 0.5));
  const int span = std::min(i_hi - i_lo + 1, lat.columns);  // a void never wraps onto itself
  for (int j = j_lo; j <= j_hi; ++j) {
    const double py = lat.y0 + (j + 0.5) * a;
    for (int k = 0; k < span; ++k) {
      const int i = ((i_lo + k) % lat.columns + lat.columns) % lat.columns;
      const double px = lat.x0 + (i + 0.5) * a;
      double dx = std::abs(px - v.x);
      dx = std::min(dx, lat.width() - dx);
      const double dy = py - v.y;
      if (dx * dx + dy * dy < v.r * v.r) out.push_back(lat.index(i, j));
    }
  }
  return out;
}

std::string describe(double porosity, std::size_t voids) {
  std::ostringstream s;
  s << "reached porosity " << porosity << " with " << voids << " voids";
  return s.str();
}

}  // namespace

VoidLayout seed_voids(const Lattice& lat, const VoidRequest& req, std::mt19937_64& rng, double tolerance) {
  VoidLayout out;
  out.lattice_points = lat.size();
  out.removed.assign(lat.size(), 0);
  if (req.porosity <= 1.0) return out;

  const double target_removed = static_cast<double>(lat.size()) * (1.0 - 1.0 / req.porosity);
  const double r_max = req.radius + req.radius_spread;
  VoidBuckets buckets(lat, 2.0 * r_max + req.min_gap);
  // Random sequential addition jams near 55 % coverage; far fewer successes than this many
  // consecutive failures means the voids do not fit.
  constexpr std::size_t kMaxConsecutiveMisses = 200000;
  std::size_t misses = 0;
  std::vector<std::size_t> last_cut;

  while (static_cast<double>(out.removed_count) < target_removed) {
    const double r = req.radius + req.radius_spread * (2.0 * uniform01(rng) - 1.0);
    const double x = lat.x0 + lat.width() * uniform01(rng);
    const double y = lat.y0 + r + (lat.height() - 2.0 * r) * uniform01(rng);
    if (!req.overlap && !buckets.clear_of(out.voids, x, y, r, req.min_gap)) {
      if (++misses > kMaxConsecutiveMisses)
        throw VoidSeedingError("voids that cannot fit: " + describe(out.porosity(), out.voids.size()) +
                               " and then found no free place in " + std::to_string(kMaxConsecutiveMisses) +
                               " tries; lower the porosity, void_radius or void_min_gap, or allow void_overlap");
      continue;
    }
    misses = 0;
    const Void v{x, y, r};
    last_cut.clear();
    for (std::size_t k : points_inside(lat, v)) {
      if (out.removed[k]) continue;
      out.removed[k] = 1;
      last_cut.push_back(k);
    }
    out.removed_count += last_cut.size();
    buckets.insert(v, out.voids.size());
    out.voids.push_back(v);
  }
  // Keep the last void only if it brings the point porosity closer to the request.
  if (!last_cut.empty()) {
    const double with = static_cast<double>(out.removed_count) - target_removed;
    const double without = target_removed - static_cast<double>(out.removed_count - last_cut.size());
    if (without < with) {
      for (std::size_t k : last_cut) out.removed[k] = 0;
      out.removed_count -= last_cut.size();
      out.voids.pop_back();
    }
  }
  if (out.removed_count >= out.lattice_points)
    throw VoidSeedingError("voids that cannot fit: they would remove every material point");
  const double achieved = out.porosity();
  if (std::abs(achieved - req.porosity) > tolerance * req.porosity) {
    std::ostringstream msg;
    msg << "cannot reach the requested porosity within " << tolerance * 100 << " %: " << describe(achieved, out.voids.size())
        << "; each void removes too large a share of the body, use smaller voids or a larger body";
    throw VoidSeedingError(msg.str());
  }
  return out;
}

VoidLayout mirror_layout(const VoidLayout& layout, const Lattice& lat) {
  VoidLayout out = layout;
  for (Void& v : out.voids) v.y = -v.y;
  // Row j of the body sits at the mirror height of row rows - 1 - j of its image.
  for (int j = 0; j < lat.rows; ++j)
    for (int i = 0; i < lat.columns; ++i) out.removed[lat.index(i, lat.rows - 1 - j)] = layout.removed[lat.index(i, j)];
  return out;
}

}  // namespace mpmshock
