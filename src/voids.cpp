#include "mpmshock/voids.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mpmshock {
namespace {

// The distance between two coordinates on a periodic axis of the given period.
double periodic_distance(double a, double b, double period) {
  const double d = std::abs(a - b);
  return std::min(d, period - d);
}

// Up to three distinct neighbouring buckets of bucket c on a periodic axis of n buckets (fewer
// than 3 buckets: every bucket is a neighbour); returns how many.
int periodic_neighbours(int c, int n, int out[3]) {
  if (n < 3) {
    for (int k = 0; k < n; ++k) out[k] = k;
    return n;
  }
  out[0] = c, out[1] = (c + 1) % n, out[2] = (c + n - 1) % n;
  return 3;
}

// Buckets of voids for the overlap test, periodic in x (and z). A bucket is at least as wide as
// the largest centre distance that can still overlap, so only the 3 x 3 (x 3) neighbourhood is
// searched.
class VoidBuckets {
 public:
  VoidBuckets(const Lattice& lat, double reach)
      : width_(lat.width()), depth_(lat.depth()), y0_(lat.y0), periodic_z_(lat.dimension == 3) {
    nx_ = std::max(1, static_cast<int>(std::floor(width_ / reach)));
    ny_ = std::max(1, static_cast<int>(std::floor(lat.height() / reach)));
    nz_ = periodic_z_ ? std::max(1, static_cast<int>(std::floor(depth_ / reach))) : 1;
    bx_ = width_ / nx_;
    by_ = lat.height() / ny_;
    bz_ = depth_ / nz_;
    buckets_.resize(static_cast<std::size_t>(nx_) * ny_ * nz_);
  }

  void insert(const Void& v, std::size_t index) { buckets_[bucket(v.x, v.y, v.z)].push_back(index); }

  // True if a void `v` stays at least `gap` away from every stored one.
  bool clear_of(const std::vector<Void>& voids, const Void& v, double gap) const {
    int columns[3], layers[3];
    const int ncol = periodic_neighbours(column(v.x), nx_, columns);
    const int nlay = periodic_neighbours(layer(v.z), nz_, layers);
    const int cy = row(v.y);
    for (int dy = -1; dy <= 1; ++dy) {
      const int ry = cy + dy;
      if (ry < 0 || ry >= ny_) continue;
      for (int l = 0; l < nlay; ++l)
        for (int k = 0; k < ncol; ++k) {
          for (std::size_t index : buckets_[key(columns[k], ry, layers[l])]) {
            const Void& o = voids[index];
            const double dx = periodic_distance(o.x, v.x, width_);
            const double dz = periodic_z_ ? periodic_distance(o.z, v.z, depth_) : 0.0;
            const double dyv = o.y - v.y;
            const double reach = v.r + o.r + gap;
            if (dx * dx + dyv * dyv + dz * dz < reach * reach) return false;
          }
        }
    }
    return true;
  }

 private:
  int column(double x) const { return std::min(nx_ - 1, std::max(0, static_cast<int>(x / bx_))); }
  int row(double y) const { return std::min(ny_ - 1, std::max(0, static_cast<int>((y - y0_) / by_))); }
  int layer(double z) const { return std::min(nz_ - 1, std::max(0, static_cast<int>(z / bz_))); }
  std::size_t key(int cx, int cy, int cz) const {
    return (static_cast<std::size_t>(cy) * nz_ + static_cast<std::size_t>(cz)) * nx_ + static_cast<std::size_t>(cx);
  }
  std::size_t bucket(double x, double y, double z) const { return key(column(x), row(y), layer(z)); }

  double width_, depth_, y0_, bx_ = 0, by_ = 0, bz_ = 0;
  bool periodic_z_;
  int nx_ = 1, ny_ = 1, nz_ = 1;
  std::vector<std::vector<std::size_t>> buckets_;
};

// The lattice indices [lo, lo + span) a void covers on a periodic axis of n points (wrapped by the
// caller); a void never wraps onto itself.
struct AxisSpan {
  int lo, span;
};
AxisSpan axis_span(double centre, double r, double origin, double a, int n) {
  const int lo = static_cast<int>(std::floor((centre - r - origin) / a - 0.5));
  const int hi = static_cast<int>(std::ceil((centre + r - origin) / a - 0.5));
  return {lo, std::min(hi - lo + 1, n)};
}

// Lattice points inside a void (periodic in x and z), as indices.
std::vector<std::size_t> points_inside(const Lattice& lat, const Void& v) {
  std::vector<std::size_t> out;
  const double a = lat.spacing;
  const int j_lo = std::max(0, static_cast<int>(std::floor((v.y - v.r - lat.y0) / a - 0.5)));
  const int j_hi = std::min(lat.rows - 1, static_cast<int>(std::ceil((v.y + v.r - lat.y0) / a - 0.5)));
  const AxisSpan xs = axis_span(v.x, v.r, lat.x0, a, lat.columns);
  const AxisSpan zs = lat.dimension == 3 ? axis_span(v.z, v.r, 0.0, a, lat.layers) : AxisSpan{0, 1};
  auto wrap = [](int i, int n) { return (i % n + n) % n; };
  for (int j = j_lo; j <= j_hi; ++j) {
    const double py = lat.y0 + (j + 0.5) * a;
    for (int l = 0; l < zs.span; ++l) {
      const int k = wrap(zs.lo + l, lat.layers);
      const double dz = lat.dimension == 3 ? periodic_distance((k + 0.5) * a, v.z, lat.depth()) : 0.0;
      for (int m = 0; m < xs.span; ++m) {
        const int i = wrap(xs.lo + m, lat.columns);
        const double dx = periodic_distance(lat.x0 + (i + 0.5) * a, v.x, lat.width());
        const double dy = py - v.y;
        if (dx * dx + dy * dy + dz * dz < v.r * v.r) out.push_back(lat.index(i, j, k));
      }
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
    const double z = lat.dimension == 3 ? lat.depth() * uniform01(rng) : 0.0;
    const Void v{x, y, r, z};
    if (!req.overlap && !buckets.clear_of(out.voids, v, req.min_gap)) {
      if (++misses > kMaxConsecutiveMisses)
        throw VoidSeedingError("voids that cannot fit: " + describe(out.porosity(), out.voids.size()) +
                               " and then found no free place in " + std::to_string(kMaxConsecutiveMisses) +
                               " tries; lower the porosity, void_radius or void_min_gap, or allow void_overlap");
      continue;
    }
    misses = 0;
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
    for (int k = 0; k < lat.layers; ++k)
      for (int i = 0; i < lat.columns; ++i)
        out.removed[lat.index(i, lat.rows - 1 - j, k)] = layout.removed[lat.index(i, j, k)];
  return out;
}

}  // namespace mpmshock
