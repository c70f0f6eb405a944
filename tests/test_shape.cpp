// Shape functions: partition of unity, gradients summing to zero, linear reproduction, gradients
// matching finite differences, and periodic wrap at the seam, for every shape type; and the
// quadrature of a uniformly compressed lattice of points: sum_p V_p grad N_i(x_p) = 0 at every
// interior node for any offset from the grid where the points' domains tile the material (gimp,
// bspline2_domain), which bspline2 at points does not give; the domain B-spline's weights against
// its integral written out piece by piece, and its stencils computed four points at a time equal to
// the bytes of those computed one at a time, in 2D and 3D; the first node's index against std::floor;
// the strip bins' rows against the stencils'.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/strip_bins.hpp"

using namespace mpmshock;

template <class Shape>
void check_shape(const GridGeometry<2>& g, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ux(0.0, g.width()), uy(g.y_min + 3 * g.h, g.y_max() - 3 * g.h);
  for (int trial = 0; trial < 2000; ++trial) {
    const double x = ux(rng), y = uy(rng);
    const auto st = Shape::at(Vec<2>{{x, y}}, g);
    double sum = 0, gx = 0, gy = 0, xs = 0, ys = 0, dxs_dx = 0, dys_dy = 0;
    for (int b = 0; b < Shape::support; ++b)
      for (int a = 0; a < Shape::support; ++a) {
        const double N = st.w[0][a] * st.w[1][b];
        CHECK(N >= -1e-15);
        sum += N;
        gx += st.g[0][a] * st.w[1][b];
        gy += st.w[0][a] * st.g[1][b];
        // Node coordinates, unwrapped to the point's side of the seam.
        double xi = st.column[a] * g.h;
        if (xi - x > 0.5 * g.width()) xi -= g.width();
        if (x - xi > 0.5 * g.width()) xi += g.width();
        const double yi = g.y_min + (st.row0 + b) * g.h;
        xs += N * xi;
        ys += N * yi;
        dxs_dx += st.g[0][a] * st.w[1][b] * xi;
        dys_dy += st.w[0][a] * st.g[1][b] * yi;
      }
    CHECK_NEAR(sum, 1.0, 1e-12);                    // partition of unity
    CHECK_NEAR(gx * g.h, 0.0, 1e-12);               // gradients sum to zero
    CHECK_NEAR(gy * g.h, 0.0, 1e-12);
    CHECK_NEAR(xs, x, 1e-12 * g.width());           // reproduces x and y ...
    CHECK_NEAR(ys, y, 1e-12 * g.width());
    CHECK_NEAR(dxs_dx, 1.0, 1e-10);                 // ... and their gradients
    CHECK_NEAR(dys_dy, 1.0, 1e-10);
    CHECK(Shape::first_row(y, g) == st.row0);
  }
  // Gradients against central differences of the weights, away from kinks.
  for (int trial = 0; trial < 200; ++trial) {
    const double x = ux(rng), y = uy(rng), e = 1e-7 * g.h;
    const auto st = Shape::at(Vec<2>{{x, y}}, g), sx = Shape::at(Vec<2>{{x + e, y}}, g), sxm = Shape::at(Vec<2>{{x - e, y}}, g);
    if (sx.column[0] != sxm.column[0] || sx.row0 != sxm.row0) continue;
    for (int a = 0; a < Shape::support; ++a) {
      const double fd = (sx.w[0][a] - sxm.w[0][a]) / (2 * e);
      CHECK_NEAR(st.g[0][a] * g.h, fd * g.h, 1e-5);
    }
  }
}

// The largest |sum_p a dN_i/dy (x_p)| over the interior rows, for a column of points of spacing
// a = J h / 2 (2 points per cell compressed to J) with F_yy = J, over offsets from the grid.
template <class Shape>
double compressed_lattice_error(const GridGeometry<2>& g, double J) {
  Mat<2> F = Mat<2>::identity();
  F(1, 1) = J;
  const double a = 0.5 * J * g.h;
  double worst = 0.0;
  for (int k = 0; k < 40; ++k) {
    const double offset = g.y_min + 3.0 * g.h + k * g.h / 40.0;
    std::vector<double> sum(static_cast<std::size_t>(g.ny), 0.0);
    for (double y = offset; y < g.y_max() - 3.0 * g.h; y += a) {
      const auto st = Shape::at(Vec<2>{{0.3 * g.h, y}}, g, F);
      for (int b = 0; b < Shape::support; ++b) sum[static_cast<std::size_t>(st.row0 + b)] += a * st.g[1][b];
    }
    for (int r = 6; r < g.ny - 6; ++r) worst = std::max(worst, std::abs(sum[static_cast<std::size_t>(r)]));
  }
  return worst;
}

// The domain B-spline written out piece by piece, independently of shape.hpp's form: the quadratic
// B-spline B and its integral M from -3/2, N(r) = (M(r + lp) - M(r - lp)) / (2 lp) and
// dN/dr = (B(r + lp) - B(r - lp)) / (2 lp), r the point's distance from the node in cells.
double reference_B(double s) {
  const double a = std::abs(s);
  return a < 0.5 ? 0.75 - s * s : (a < 1.5 ? 0.5 * (1.5 - a) * (1.5 - a) : 0.0);
}
double reference_M(double s) {
  if (s <= -1.5) return 0.0;
  if (s <= -0.5) return std::pow(s + 1.5, 3) / 6.0;
  if (s <= 0.5) return 1.0 / 6.0 + 0.75 * (s + 0.5) - (s * s * s + 0.125) / 3.0;
  if (s < 1.5) return 1.0 - std::pow(1.5 - s, 3) / 6.0;
  return 1.0;
}

// The stencils of four points at a time against each point's alone, byte for byte, in D dimensions.
template <int D>
void check_four_at_once(const GridGeometry<D>& g, const std::vector<Vec<D>>& xs, const std::vector<Mat<D>>& Fs) {
  using Domain = QuadraticBSplineDomainShape;
  for (std::size_t k = 0; k + 4 <= xs.size(); k += 4) {
    const Vec<D>* x[4] = {&xs[k], &xs[k + 1], &xs[k + 2], &xs[k + 3]};
    const Mat<D>* F[4] = {&Fs[k], &Fs[k + 1], &Fs[k + 2], &Fs[k + 3]};
    Stencil<4, D> four[4];
    Stencil<4, D>* out[4] = {&four[0], &four[1], &four[2], &four[3]};
    Domain::at_four(x, F, g, out);
    for (int l = 0; l < 4; ++l) {
      const Stencil<4, D> alone = Domain::at(*x[l], g, *F[l]);
      bool same = std::equal(alone.column, alone.column + 4, four[l].column) && alone.row0 == four[l].row0;
      if constexpr (D == 3) same = same && std::equal(alone.layer, alone.layer + 4, four[l].layer);
      for (int axis = 0; axis < D; ++axis)
        for (int a = 0; a < 4; ++a) {
          same = same && std::memcmp(&alone.w[axis][a], &four[l].w[axis][a], sizeof(double)) == 0;
          same = same && std::memcmp(&alone.g[axis][a], &four[l].g[axis][a], sizeof(double)) == 0;
        }
      CHECK(same);
    }
  }
}

// The test grid: nx columns (and nz layers in 3D) of 2.5 um cells, 12 node rows from y = -10 um,
// points of half a cell.
template <int D>
GridGeometry<D> test_grid(int nx, int nz = 1) {
  GridGeometry<D> g;
  g.nx = nx;
  g.ny = 12;
  g.nz = nz;
  g.h = 2.5e-6;
  g.inv_h = 1.0 / g.h;
  g.y_min = -1.0e-5;
  g.lp = 0.25;
  return g;
}

// The strip bins' rows are those of the points' own stencils, for a point alone and for four at a
// time (StripBins::build takes their first rows four at a time): at every quarter cell and the
// doubles beside it. (At a half cell bspline2's u - 1/2 is rounded once where the compiler fuses it
// with the product, in its scalar stencil, and twice in lanes: y = 4.5 h was binned a row too high.)
template <class Shape>
void check_bins_match_stencils() {
  GridGeometry<2> g = test_grid<2>(7);
  g.h = 1e-5;
  g.inv_h = 1.0 / g.h;
  g.y_min = 0.0;
  g.ny = 64;
  std::vector<Vec<2>> x;
  for (int k = 3; k < 56; ++k)
    for (int quarter = 0; quarter < 4; ++quarter) {
      const double y = (k + 0.25 * quarter) * g.h;
      for (const double at : {std::nextafter(y, 0.0), y, std::nextafter(y, 1.0)}) x.push_back(Vec<2>{{0.3 * g.h, at}});
    }
  StripBins bins;
  int differ = 0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    const std::vector<Vec<2>> one = {x[p]};
    CHECK(bins.build<Shape>(one, {0, 1}, g));
    differ += bins.rows().begin != Shape::at(x[p], g).row0;
  }
  for (std::size_t p = 0; p + 4 <= x.size(); p += 4) {
    int lo = g.ny, hi = -1;
    for (std::size_t q = p; q < p + 4; ++q) {
      lo = std::min(lo, Shape::at(x[q], g).row0);
      hi = std::max(hi, Shape::at(x[q], g).row0);
    }
    CHECK(bins.build<Shape>(x, {p, p + 4}, g));
    differ += bins.rows().begin != lo || bins.rows().end != hi + Shape::support;
  }
  if (differ) check::fail(__FILE__, __LINE__, std::to_string(differ) + " bins' rows differ from their stencils'");
}

int main() {
  const GridGeometry<2> g = test_grid<2>(7);
  check_bins_match_stencils<BilinearShape>();
  check_bins_match_stencils<GimpShape>();
  check_bins_match_stencils<QuadraticBSplineShape>();
  check_bins_match_stencils<QuadraticBSplineDomainShape>();
  std::mt19937_64 rng(42);
  check_shape<BilinearShape>(g, rng);
  check_shape<GimpShape>(g, rng);
  check_shape<QuadraticBSplineShape>(g, rng);
  check_shape<QuadraticBSplineDomainShape>(g, rng);
  {
    // The domain shapes at the ends of their half-width range: stretched past the cap (F_aa = 2.5,
    // lp 1/2), compressed to nearly nothing and rotated a quarter turn (F_aa = 0: the floor).
    std::uniform_real_distribution<double> ux(0.0, g.width()), uy(g.y_min + 3 * g.h, g.y_max() - 3 * g.h);
    for (double f : {2.5, 1e-9, 0.0}) {
      Mat<2> F{};
      F(0, 0) = F(1, 1) = f;
      for (int trial = 0; trial < 500; ++trial) {
        const double x = ux(rng), y = uy(rng);
        const auto st = QuadraticBSplineDomainShape::at(Vec<2>{{x, y}}, g, F);
        double sum = 0, gy = 0, ys = 0, dys = 0;
        for (int b = 0; b < 4; ++b)
          for (int a = 0; a < 4; ++a) {
            const double N = st.w[0][a] * st.w[1][b], yi = g.y_min + (st.row0 + b) * g.h;
            CHECK(std::isfinite(N) && N >= -1e-15);
            sum += N;
            gy += st.w[0][a] * st.g[1][b];
            ys += N * yi;
            dys += st.w[0][a] * st.g[1][b] * yi;
          }
        CHECK_NEAR(sum, 1.0, 1e-12);
        CHECK_NEAR(gy * g.h, 0.0, 1e-12);
        CHECK_NEAR(ys, y, 1e-12 * g.width());
        CHECK_NEAR(dys, 1.0, 1e-10);
      }
    }
  }
  {
    // A compressed lattice: the domain shapes integrate a uniform stress exactly; the B-spline at
    // points errs by several per cent of it at J = 0.87 (the shocked state at 8 GPa).
    GridGeometry<2> tall = g;
    tall.ny = 40;
    for (double J : {1.0, 0.95, 0.87, 0.7}) {
      const double bspline = compressed_lattice_error<QuadraticBSplineShape>(tall, J);
      const double gimp = compressed_lattice_error<GimpShape>(tall, J);
      const double domain = compressed_lattice_error<QuadraticBSplineDomainShape>(tall, J);
      std::printf("J = %.2f: |sum_p V_p dN_i/dy| / h^(D-1): bspline2 %.3g, gimp %.3g, bspline2_domain %.3g\n", J, bspline,
                  gimp, domain);
      CHECK(domain < 1e-12);
      CHECK(gimp < 1e-12);
      if (J == 1.0) CHECK(bspline < 1e-12);
      if (J == 0.87) CHECK(bspline > 0.01);  // the error bspline2_domain exists to remove
    }
  }

  {
    // Four points at a time (the step's compute_stencils) give each point the bytes at() gives it
    // alone, whatever shares its vector: points at the seams, a NaN, a far point, and their mix.
    std::uniform_real_distribution<double> ux(0.0, g.width()), uy(g.y_min + 3 * g.h, g.y_max() - 3 * g.h),
        uf(0.3, 1.6);
    std::vector<Vec<2>> xs;
    std::vector<Mat<2>> Fs;
    for (int k = 0; k < 400; ++k) {
      Mat<2> F{};
      F(0, 0) = uf(rng);
      F(1, 1) = uf(rng);
      F(0, 1) = 0.1;
      xs.push_back(Vec<2>{{ux(rng), uy(rng)}});
      Fs.push_back(F);
    }
    xs[1] = Vec<2>{{1e-9 * g.h, 0.0}};
    xs[2] = Vec<2>{{g.width() * (1 - 1e-9), 0.0}};
    xs[5] = Vec<2>{{std::nan(""), 0.0}};
    xs[6] = Vec<2>{{0.0, 1e9}};
    check_four_at_once<2>(g, xs, Fs);
    using Domain = QuadraticBSplineDomainShape;
    // ... and the first row it gives is the one the bins and the left-grid check use.
    for (std::size_t k = 0; k < xs.size(); ++k)
      if (k != 5) CHECK(Domain::at(xs[k], g, Fs[k]).row0 == Domain::first_row(xs[k][1], g));
    // The weights and derivatives against the piecewise reference above, on both axes.
    double worst_w = 0.0, worst_g = 0.0;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      if (k == 5 || k == 6) continue;  // the NaN and the far point
      const auto st = Domain::at(xs[k], g, Fs[k]);
      for (int axis = 0; axis < 2; ++axis) {
        const double u = (axis == 0 ? xs[k][0] : xs[k][1] - g.y_min) * g.inv_h;
        const double lp = std::clamp(g.lp * std::abs(Fs[k](axis, axis)), 1e-3, 0.5);
        const int base = static_cast<int>(std::floor(u)) - 1;
        CHECK((axis == 0 ? (st.column[0] - base) % g.nx : st.row0 - base) == 0);
        for (int a = 0; a < 4; ++a) {
          const double r = u - (base + a);
          const double w = (reference_M(r + lp) - reference_M(r - lp)) / (2.0 * lp);
          const double dw = (reference_B(r + lp) - reference_B(r - lp)) / (2.0 * lp);
          worst_w = std::max(worst_w, std::abs(st.w[axis][a] - w));
          worst_g = std::max(worst_g, std::abs(st.g[axis][a] * g.h - dw));
        }
      }
    }
    std::printf("bspline2_domain against the piecewise reference: weights within %.2g, gradients within %.2g (cells)\n",
                worst_w, worst_g);
    CHECK(worst_w < 2e-14);
    CHECK(worst_g < 2e-14);
  }
  {
    // The same in 3D, where z is periodic too (layers wrapped at both seams).
    const GridGeometry<3> g3 = test_grid<3>(5, 6);
    std::uniform_real_distribution<double> ux(0.0, g3.width()), uy(g3.y_min + 3 * g3.h, g3.y_max() - 3 * g3.h),
        uz(0.0, g3.depth()), uf(0.3, 1.6);
    std::vector<Vec<3>> xs;
    std::vector<Mat<3>> Fs;
    for (int k = 0; k < 400; ++k) {
      Mat<3> F{};
      for (int d = 0; d < 3; ++d) F(d, d) = uf(rng);
      xs.push_back(Vec<3>{{ux(rng), uy(rng), uz(rng)}});
      Fs.push_back(F);
    }
    xs[1] = Vec<3>{{1e-9 * g3.h, 0.0, g3.depth() * (1 - 1e-9)}};
    xs[2] = Vec<3>{{g3.width() * (1 - 1e-9), 0.0, 1e-9 * g3.h}};
    check_four_at_once<3>(g3, xs, Fs);
    const auto seam = QuadraticBSplineDomainShape::at(xs[1], g3, Fs[1]);
    CHECK(seam.column[0] == g3.nx - 1 && seam.column[1] == 0 && seam.layer[0] == g3.nz - 2 && seam.layer[2] == 0);
  }

  // Periodic seam: a point just left of x = width touches column 0 as its right neighbour.
  const auto st = BilinearShape::at(Vec<2>{{g.width() * (1 - 1e-9), 0.0}}, g);
  CHECK(st.column[0] == g.nx - 1 && st.column[1] == 0);
  const auto sb = QuadraticBSplineShape::at(Vec<2>{{1e-9 * g.h, 0.0}}, g);
  CHECK(sb.column[0] == g.nx - 1 && sb.column[1] == 0 && sb.column[2] == 1);
  const auto sd = QuadraticBSplineDomainShape::at(Vec<2>{{1e-9 * g.h, 0.0}}, g);
  CHECK(sd.column[0] == g.nx - 1 && sd.column[1] == 0 && sd.column[2] == 1 && sd.column[3] == 2);
  const auto se = QuadraticBSplineDomainShape::at(Vec<2>{{g.width() * (1 - 1e-9), 0.0}}, g);
  CHECK(se.column[0] == g.nx - 2 && se.column[1] == g.nx - 1 && se.column[2] == 0 && se.column[3] == 1);

  // floor_index (every stencil's first node) and floor_lanes (four points' stencils) against
  // std::floor: integers and their neighbours either side, both signs, halves, the clamps at
  // +-1e9 and NaN (to -1e9), and random values over the grid's range and far beyond it.
  {
    std::vector<double> us = {0.0, -0.0, 0.5, -0.5, 1e9, -1e9, 2e9, -2e9, 1e300, -1e300,
                              std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::denorm_min(),
                              -std::numeric_limits<double>::denorm_min()};
    for (int i = -70; i <= 70; ++i)
      for (double u : {static_cast<double>(i), std::nextafter(static_cast<double>(i), -1e300),
                       std::nextafter(static_cast<double>(i), 1e300)})
        us.push_back(u);
    std::uniform_real_distribution<double> near(-200.0, 200.0), far(-3e9, 3e9);
    for (int k = 0; k < 20000; ++k) us.push_back(k % 2 ? near(rng) : far(rng));
    int wrong = 0;
    for (std::size_t k = 0; k < us.size(); ++k) {
      const double u = us[k], held = std::isnan(u) ? -1e9 : std::clamp(u, -1e9, 1e9);
      const int expected = static_cast<int>(std::floor(held));
      if (detail::floor_index(u) != expected) ++wrong;
      LaneInts four;
      floor_lanes(four, Lanes{u, us[(k + 1) % us.size()], u, u});
      if (four[0] != expected || four[2] != expected) ++wrong;
    }
    CHECK(wrong == 0);
  }
  return check::result();
}
