// Shape functions behind one interface. A shape type gives, for a point, the tensor-product stencil
// of the nodes it touches: their columns (and layers in 3D, wrapped for the periodic axes), the
// first row, and 1D weights and derivatives on each axis. Transfers are templates on the shape
// type and the choice is made once at setup, so a new shape function is a new type here; the
// physics never sees which one runs.
//
//   bilinear  4-node cells, N_i = (1 + xi xi_i)(1 + eta eta_i)/4 (8-node in 3D): the paper's
//             choice. Its gradient jumps where a point crosses a grid line, which puts grid-crossing
//             noise into shocked material (README, "Method").
//   gimp      contiguous-particle GIMP (cpGIMP): each point is a rectangle convolved with the hat,
//             its half-width on each axis the initial lp stretched by that diagonal entry of F
//             (at most half a cell), so points that are compressed keep tiling the material; the
//             gradient is continuous, 3 x 3 nodes. (Uniform GIMP, with lp fixed, makes a
//             compressed block heat as it crosses the grid: README, "Method".)
//   bspline2  quadratic B-spline at the points, C1 on the grid, 3 x 3 nodes (the default until
//             2026-12-05); a compressed lattice of points does not integrate a uniform stress with it.
//   bspline2_domain  the quadratic B-spline averaged over each point's domain (half-widths as
//             cpGIMP's), 4 x 4 nodes, the default: the least noise (a fifth of bspline2's
//             point pressure scatter) and the strength state right where material crosses the grid.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "mpmshock/grid.hpp"

namespace mpmshock {

// The nodes a point touches and their weights, per axis: N_i = w[0][a] w[1][b] (w[2][c] in 3D),
// grad N_i = (g[0][a] w[1][b], w[0][a] g[1][b]) (and so on in 3D). Axis 0 is x, 1 is y, 2 is z.
template <int S, int D>
struct Stencil {
  static constexpr int support = S;
  int column[S];    // node columns (x), already wrapped into [0, nx)
  int row0;         // first node row (y); rows row0 .. row0 + S - 1
  int layer[D == 3 ? S : 1];  // node layers (z), wrapped into [0, nz); 3D only
  double w[D][S];   // 1D weights
  double g[D][S];   // 1D derivatives [1/m]
};

// The stencils of a step's points, one per point by storage index: P2G computes each once, and the
// passes after it in the same step (heat conduction, G2P, the velocity gradient) read it again, since
// a point's x and F do not change until the step moves and updates it.
template <int D>
struct StencilStore {
  std::vector<Stencil<2, D>> linear;     // bilinear (trilinear) cells
  std::vector<Stencil<3, D>> quadratic;  // gimp, bspline2
  std::vector<Stencil<4, D>> wide;       // bspline2_domain

  template <int S>
  std::vector<Stencil<S, D>>& of() {
    if constexpr (S == 2) return linear;
    else if constexpr (S == 3) return quadratic;
    else return wide;
  }
  template <int S>
  const std::vector<Stencil<S, D>>& of() const {
    if constexpr (S == 2) return linear;
    else if constexpr (S == 3) return quadratic;
    else return wide;
  }
  // Bytes per point for a shape function of `support` nodes per axis (the --check estimate).
  static constexpr std::size_t bytes_per_point(int support) {
    return support == 2 ? sizeof(Stencil<2, D>) : support == 3 ? sizeof(Stencil<3, D>) : sizeof(Stencil<4, D>);
  }
};

namespace detail {

// Wraps a node index that is at most one period out of range (stencils reach one cell past the
// seam); comparisons, not the integer division of %, which dominated the stencil's cost.
inline int wrap(int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); }

// floor(u) as an int, for any u: a point far off the grid (or NaN) gets a node index far outside
// it, which the callers report, instead of an int conversion out of range (undefined behaviour).
inline int floor_index(double u) {
  if (!(u >= -1e9)) u = -1e9;
  if (u > 1e9) u = 1e9;
  return static_cast<int>(std::floor(u));
}

// Fills a stencil from a 1D rule applied on each axis, periodic in x and z. Rule::base(u) is the
// first node touched at grid coordinate u; Rule::weights(d, lp, w, dw) the weights at d = u - base
// for a point of half-width lp = Rule::half_width(g.lp, F_aa) on that axis.
template <class Rule, int S, int D>
[[gnu::always_inline]] inline Stencil<S, D> tensor_stencil(const Vec<D>& x, const GridGeometry<D>& g, const Mat<D>& F) {
  Stencil<S, D> st;
  const double u = x[0] * g.inv_h;
  const int i0 = Rule::base(u);
  Rule::weights(u - i0, Rule::half_width(g.lp, F(0, 0)), st.w[0], st.g[0]);
  for (int a = 0; a < S; ++a) {
    st.column[a] = wrap(i0 + a, g.nx);
    st.g[0][a] *= g.inv_h;
  }
  const double v = (x[1] - g.y_min) * g.inv_h;
  st.row0 = Rule::base(v);
  Rule::weights(v - st.row0, Rule::half_width(g.lp, F(1, 1)), st.w[1], st.g[1]);
  for (int b = 0; b < S; ++b) st.g[1][b] *= g.inv_h;
  if constexpr (D == 3) {
    const double z = x[2] * g.inv_h;
    const int k0 = Rule::base(z);
    Rule::weights(z - k0, Rule::half_width(g.lp, F(2, 2)), st.w[2], st.g[2]);
    for (int c = 0; c < S; ++c) {
      st.layer[c] = wrap(k0 + c, g.nz);
      st.g[2][c] *= g.inv_h;
    }
  }
  return st;
}

// Rules without a point domain ignore its half-width.
struct PointRule {
  static double half_width(double, double) { return 0.0; }
};

struct LinearRule : PointRule {
  static int base(double u) { return floor_index(u); }
  static void weights(double d, double, double* w, double* dw) {  // d in [0, 1)
    w[0] = 1.0 - d;
    w[1] = d;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
};

struct GimpRule {
  static int base(double u) { return floor_index(u + 0.5) - 1; }
  // cpGIMP: the initial half-width lp0 (cells) stretched by F_aa, at most 1/2 so that the domain
  // stays within the 3 nodes (a point stretched past twice its size is held at half a cell).
  static double half_width(double lp0, double F_aa) { return std::min(0.5, lp0 * std::abs(F_aa)); }
  // The uGIMP weight of a node at distance r (cells) from a point of half-width lp <= 1/2.
  static void node(double r, double lp, double& w, double& dw) {
    const double a = std::abs(r), sign = r < 0.0 ? -1.0 : 1.0;
    if (a < lp) {
      w = 1.0 - (r * r + lp * lp) / (2.0 * lp);
      dw = -r / lp;
    } else if (a < 1.0 - lp) {
      w = 1.0 - a;
      dw = -sign;
    } else if (a < 1.0 + lp) {
      const double b = 1.0 + lp - a;
      w = b * b / (4.0 * lp);
      dw = -sign * b / (2.0 * lp);
    } else {
      w = 0.0;
      dw = 0.0;
    }
  }
  static void weights(double d, double lp, double* w, double* dw) {  // d in [0.5, 1.5)
    // r is the point's position relative to node a; d/dx of N(x - x_a) is dN/dr.
    for (int a = 0; a < 3; ++a) node(d - a, lp, w[a], dw[a]);
  }
};

struct QuadraticBSplineRule : PointRule {
  static int base(double u) { return floor_index(u - 0.5); }
  static void weights(double d, double, double* w, double* dw) {  // d in [0.5, 1.5)
    w[0] = 0.5 * (1.5 - d) * (1.5 - d);
    w[1] = 0.75 - (d - 1.0) * (d - 1.0);
    w[2] = 0.5 * (d - 0.5) * (d - 0.5);
    dw[0] = d - 1.5;
    dw[1] = -2.0 * (d - 1.0);
    dw[2] = d - 0.5;
  }
};

// The quadratic B-spline integrated over the point's domain (bspline2_domain): the point is a
// segment of half-width lp on each axis, the initial half-width stretched by F_aa as in cpGIMP (at
// most half a cell), and its weight is the B-spline's mean over it,
//   N(r) = (M(r + lp) - M(r - lp)) / (2 lp),  dN/dr = (B(r + lp) - B(r - lp)) / (2 lp),
// B the quadratic B-spline and M its integral from -3/2. Points whose domains tile the material
// (a uniformly compressed lattice) then integrate a uniform stress exactly: sum_p V_p grad N_i = 0
// for any offset from the grid, which a lattice of points compressed to J h / 2 does not do with
// the B-spline at points (at J = 0.87 the nodal force of a uniform stress errs by 5.7 % of it, and
// material moving across the grid turns that into noise). 4 nodes per axis.
struct QuadraticBSplineDomainRule {
  static int base(double u) { return floor_index(u) - 1; }
  // As cpGIMP's: lp0 |F_aa|, which tiles the material where F is diagonal (the uniaxial strain of
  // a plane shock), not under shear or rotation; held within [1e-3, 1/2] cells, so that a point
  // rotated a quarter turn (F_aa = 0) takes the B-spline at a point (the weights divide by lp; at
  // 1e-3 they differ from the B-spline's by 2e-7 and lose 13 digits to none).
  static double half_width(double lp0, double F_aa) { return std::clamp(lp0 * std::abs(F_aa), 1e-3, 0.5); }
  // The B-spline at s and its integral from -3/2, both from t = |s| (the spline is even, the
  // integral 1/2 + sign(s) times the one from 0): selects, not a chain of branches.
  [[gnu::always_inline]] static double spline(double s) {
    const double t = std::abs(s), u = 1.5 - t;
    const double v = t < 0.5 ? 0.75 - t * t : 0.5 * u * u;
    return t < 1.5 ? v : 0.0;
  }
  [[gnu::always_inline]] static double integral(double s) {
    const double t = std::abs(s), u = 1.5 - t;
    const double half = t < 0.5 ? t * (0.75 - t * t * (1.0 / 3.0)) : 0.5 - u * u * u * (1.0 / 6.0);
    return 0.5 + std::copysign(t < 1.5 ? half : 0.5, s);
  }
  // With d in [1, 2) and lp <= 1/2 the outer nodes' domain ends lie on the spline's outer pieces
  // (node 0: r +- lp in [1/2, 5/2); node 3: in (-5/2, -1/2]), where it is 0.5 max(0, 3/2 - |s|)^2;
  // node 1 takes the general form, node 2 the partition of unity.
  [[gnu::always_inline]] static void weights(double d, double lp, double* w, double* dw) {  // d in [1, 2)
    const double inv = 0.5 / lp;
    auto tail = [](double s) { return std::max(0.0, 1.5 - s); };  // 3/2 - |s| on the outer piece, s >= 1/2
    const double p0 = tail(d - lp), q0 = tail(d + lp);            // node 0 at r = d
    w[0] = (p0 * p0 * p0 - q0 * q0 * q0) * (1.0 / 6.0) * inv;
    dw[0] = 0.5 * (q0 * q0 - p0 * p0) * inv;
    // node 3 at r = d - 3 < 0, by symmetry: M(s) = tail(-s)^3 / 6 and B(s) = tail(-s)^2 / 2 there
    const double p3 = tail(3.0 - d + lp), q3 = tail(3.0 - d - lp);  // tail(-(r - lp)), tail(-(r + lp))
    w[3] = (q3 * q3 * q3 - p3 * p3 * p3) * (1.0 / 6.0) * inv;
    dw[3] = 0.5 * (q3 * q3 - p3 * p3) * inv;
    const double r1 = d - 1.0;
    w[1] = (integral(r1 + lp) - integral(r1 - lp)) * inv;
    dw[1] = (spline(r1 + lp) - spline(r1 - lp)) * inv;
    w[2] = 1.0 - w[0] - w[1] - w[3];
    dw[2] = -(dw[0] + dw[1] + dw[3]);
  }
};

}  // namespace detail

template <class Rule, int S>
struct TensorShape {
  static constexpr int support = S;
  // The first node row a point at height y touches; a point is on the grid while this row is in
  // [0, ny - support].
  template <int D>
  static int first_row(double y, const GridGeometry<D>& g) {
    return Rule::base((y - g.y_min) * g.inv_h);
  }
  // The stencil of a point at x with deformation gradient F (only GIMP's domain uses F).
  template <int D>
  [[gnu::always_inline]] static Stencil<S, D> at(const Vec<D>& x, const GridGeometry<D>& g, const Mat<D>& F) {
    return detail::tensor_stencil<Rule, S, D>(x, g, F);
  }
  // ... of an undeformed point.
  template <int D>
  static Stencil<S, D> at(const Vec<D>& x, const GridGeometry<D>& g) {
    return detail::tensor_stencil<Rule, S, D>(x, g, Mat<D>::identity());
  }
};

using BilinearShape = TensorShape<detail::LinearRule, 2>;  // trilinear in 3D: the paper's 8-node cells
using GimpShape = TensorShape<detail::GimpRule, 3>;
using QuadraticBSplineShape = TensorShape<detail::QuadraticBSplineRule, 3>;
using QuadraticBSplineDomainShape = TensorShape<detail::QuadraticBSplineDomainRule, 4>;

// Visits every node of a stencil: f(node index, N_i, grad N_i), rows (y) outermost.
template <int S, int D, class F>
[[gnu::always_inline]] inline void for_each_node(const Stencil<S, D>& st, const GridGeometry<D>& g, F&& f) {
  for (int b = 0; b < S; ++b) {
    if constexpr (D == 2) {
      const std::size_t row = g.row_start(st.row0 + b);
      for (int a = 0; a < S; ++a)
        f(row + static_cast<std::size_t>(st.column[a]), st.w[0][a] * st.w[1][b],
          Vec<2>{{st.g[0][a] * st.w[1][b], st.w[0][a] * st.g[1][b]}});
    } else {
      for (int c = 0; c < S; ++c) {
        const std::size_t start = g.row_start(st.row0 + b) + static_cast<std::size_t>(st.layer[c]) * static_cast<std::size_t>(g.nx);
        for (int a = 0; a < S; ++a) {
          const double wxy = st.w[0][a] * st.w[1][b];
          f(start + static_cast<std::size_t>(st.column[a]), wxy * st.w[2][c],
            Vec<3>{{st.g[0][a] * st.w[1][b] * st.w[2][c], st.w[0][a] * st.g[1][b] * st.w[2][c], wxy * st.g[2][c]}});
        }
      }
    }
  }
}

}  // namespace mpmshock
