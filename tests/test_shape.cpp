// Shape functions: partition of unity, gradients summing to zero, linear reproduction, gradients
// matching finite differences, and periodic wrap at the seam, for every shape type.
#include <random>

#include "check.hpp"
#include "mpmshock/shape.hpp"

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

int main() {
  GridGeometry<2> g;
  g.nx = 7;
  g.ny = 12;
  g.h = 2.5e-6;
  g.inv_h = 1.0 / g.h;
  g.y_min = -1.0e-5;
  g.lp = 0.25;
  std::mt19937_64 rng(42);
  check_shape<BilinearShape>(g, rng);
  check_shape<GimpShape>(g, rng);
  check_shape<QuadraticBSplineShape>(g, rng);

  // Periodic seam: a point just left of x = width touches column 0 as its right neighbour.
  const auto st = BilinearShape::at(Vec<2>{{g.width() * (1 - 1e-9), 0.0}}, g);
  CHECK(st.column[0] == g.nx - 1 && st.column[1] == 0);
  const auto sb = QuadraticBSplineShape::at(Vec<2>{{1e-9 * g.h, 0.0}}, g);
  CHECK(sb.column[0] == g.nx - 1 && sb.column[1] == 0 && sb.column[2] == 1);
  return check::result();
}
