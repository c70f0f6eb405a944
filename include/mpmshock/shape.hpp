// Shape functions behind one interface. A shape type gives, for a point, the tensor-product stencil
// of the nodes it touches: their columns (wrapped for periodic x), the first row, and 1D weights
// and derivatives in x and y. Transfers are templates on the shape type and the choice is made once
// at setup, so a new shape function is a new type here; the physics never sees which one runs.
//
//   bilinear  4-node cells, N_i = (1 + xi xi_i)(1 + eta eta_i)/4: the paper's choice. Its gradient
//             jumps where a point crosses a grid line, which puts grid-crossing noise into shocked
//             material (see docs/accuracy.md).
//   gimp      uniform GIMP: each point is a square of half-width lp convolved with the hat; the
//             gradient is continuous, 3 x 3 nodes.
//   bspline2  quadratic B-spline, C1 on the grid, 3 x 3 nodes: the least noise.
#pragma once

#include <algorithm>
#include <cmath>

#include "mpmshock/grid.hpp"

namespace mpmshock {

template <int S>
struct Stencil {
  static constexpr int support = S;
  int column[S];        // node columns, already wrapped into [0, nx)
  int row0;             // first node row; rows row0 .. row0 + S - 1
  double wx[S], wy[S];  // 1D weights; N_i = wx[a] wy[b]
  double gx[S], gy[S];  // 1D derivatives [1/m]; grad N_i = (gx[a] wy[b], wx[a] gy[b])
};

namespace detail {

// Wraps a column index that is at most one period out of range (stencils reach one cell past the
// seam); comparisons, not the integer division of %, which dominated the stencil's cost.
inline int wrap(int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); }

// Fills a stencil from a 1D rule applied in x (periodic) and y. Rule::base(u) is the first node
// touched at grid coordinate u; Rule::weights(d, lp, w, dw) the weights at d = u - base.
template <class Rule, int S>
[[gnu::always_inline]] inline Stencil<S> tensor_stencil(double x, double y, const GridGeometry& g) {
  Stencil<S> st;
  const double u = x * g.inv_h;
  const int i0 = Rule::base(u);
  Rule::weights(u - i0, g.lp, st.wx, st.gx);
  for (int a = 0; a < S; ++a) {
    st.column[a] = wrap(i0 + a, g.nx);
    st.gx[a] *= g.inv_h;
  }
  const double v = (y - g.y_min) * g.inv_h;
  st.row0 = Rule::base(v);
  Rule::weights(v - st.row0, g.lp, st.wy, st.gy);
  for (int b = 0; b < S; ++b) st.gy[b] *= g.inv_h;
  return st;
}

struct LinearRule {
  static int base(double u) { return static_cast<int>(std::floor(u)); }
  static void weights(double d, double, double* w, double* dw) {  // d in [0, 1)
    w[0] = 1.0 - d;
    w[1] = d;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
};

struct GimpRule {
  static int base(double u) { return static_cast<int>(std::floor(u + 0.5)) - 1; }
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

struct QuadraticBSplineRule {
  static int base(double u) { return static_cast<int>(std::floor(u - 0.5)); }
  static void weights(double d, double, double* w, double* dw) {  // d in [0.5, 1.5)
    w[0] = 0.5 * (1.5 - d) * (1.5 - d);
    w[1] = 0.75 - (d - 1.0) * (d - 1.0);
    w[2] = 0.5 * (d - 0.5) * (d - 0.5);
    dw[0] = d - 1.5;
    dw[1] = -2.0 * (d - 1.0);
    dw[2] = d - 0.5;
  }
};

}  // namespace detail

template <class Rule, int S, const char* Name>
struct TensorShape {
  static constexpr int support = S;
  static constexpr const char* name = Name;
  // The first node row a point at height y touches; a point is on the grid while this row is in
  // [0, ny - support].
  static int first_row(double y, const GridGeometry& g) { return Rule::base((y - g.y_min) * g.inv_h); }
  [[gnu::always_inline]] static Stencil<S> at(double x, double y, const GridGeometry& g) {
    return detail::tensor_stencil<Rule, S>(x, y, g);
  }
};

inline constexpr char kBilinearName[] = "bilinear";
inline constexpr char kGimpName[] = "gimp";
inline constexpr char kBSpline2Name[] = "bspline2";

using BilinearShape = TensorShape<detail::LinearRule, 2, kBilinearName>;
using GimpShape = TensorShape<detail::GimpRule, 3, kGimpName>;
using QuadraticBSplineShape = TensorShape<detail::QuadraticBSplineRule, 3, kBSpline2Name>;

// Visits every node of a stencil: f(node index, N_i, dN_i/dx, dN_i/dy).
template <int S, class F>
inline void for_each_node(const Stencil<S>& st, const GridGeometry& g, F&& f) {
  for (int b = 0; b < S; ++b) {
    const std::size_t row = static_cast<std::size_t>(st.row0 + b) * static_cast<std::size_t>(g.nx);
    for (int a = 0; a < S; ++a) {
      f(row + static_cast<std::size_t>(st.column[a]), st.wx[a] * st.wy[b], st.gx[a] * st.wy[b], st.wx[a] * st.gy[b]);
    }
  }
}

}  // namespace mpmshock
