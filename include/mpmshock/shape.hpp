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
#include <cstring>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/lanes.hpp"

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

// The stencils of a step's points, one per point by storage index: computed once at the step's start
// (compute_stencils, transfer.hpp) from the x and F the step starts from, and read by every pass of
// the step: those before the points move (P2G, heat conduction, the heat flux, G2P, the velocity
// gradient), and by design two after it, volumetric smoothing's rate and spall's neighbourhood,
// which weigh the step's nodal sums with the weights the step began with.
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
// Truncated, and one less where that rounded a negative u up: exact, without a call to libm's floor
// (which GCC does not inline), as floor_lanes (lanes.hpp) does for four.
inline int floor_index(double u) {
  if (!(u >= -1e9)) u = -1e9;
  if (u > 1e9) u = 1e9;
  const int truncated = static_cast<int>(u);
  return static_cast<double>(truncated) > u ? truncated - 1 : truncated;
}

// u as the double it was rounded to: a barrier to FMA contraction for the rules whose first node
// adds to u (u + 1/2, u - 1/2). Fused with the product that made u, that sum is rounded once in one
// place and twice in another (the compiler decides per call site), and a point at a half cell took
// one row in its stencil and the next in the strip bins (test_shape). As a register it costs nothing.
[[gnu::always_inline]] inline double as_rounded(double u) {
#if defined(__x86_64__) || defined(__i386__)
  asm("" : "+x"(u));
#else
  volatile double held = u;
  u = held;
#endif
  return u;
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
  static constexpr bool kLanes = false;
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
  static constexpr bool kLanes = false;
  static int base(double u) { return floor_index(as_rounded(u) + 0.5) - 1; }
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
  static int base(double u) { return floor_index(as_rounded(u) - 0.5); }
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
// material moving across the grid turns that into noise). 4 nodes per axis. Computed for four points
// at once, one per lane (lanes.hpp; lane_stencils below), selects in place of branches.
struct QuadraticBSplineDomainRule {
  static constexpr bool kLanes = true;
  static int base(double u) { return floor_index(u) - 1; }
  [[gnu::always_inline]] static void base(LaneInts& first, const Lanes& u) {
    floor_lanes(first, u);
    first -= 1;
  }
  // As cpGIMP's: lp0 |F_aa|, which tiles the material where F is diagonal (the uniaxial strain of
  // a plane shock), not under shear or rotation; held within [1e-3, 1/2] cells, so that a point
  // rotated a quarter turn (F_aa = 0) takes the B-spline at a point (the weights divide by lp; at
  // 1e-3 they differ from the B-spline's by 2e-7 and lose 13 digits to none). As std::clamp.
  [[gnu::always_inline]] static void half_width(Lanes& lp, double lp0, const Lanes& F_aa) {
    Lanes magnitude;
    abs_lanes(magnitude, F_aa);
    const Lanes stretched = lp0 * magnitude;
    lp = stretched < 1e-3 ? Lanes{} + 1e-3 : (0.5 < stretched ? Lanes{} + 0.5 : stretched);
  }
  // With d in [1, 2) and lp <= 1/2 the outer nodes' domain ends lie on the spline's outer pieces
  // (node 0: r +- lp in [1/2, 5/2); node 3: in (-5/2, -1/2]), where it is 0.5 max(0, 3/2 - |s|)^2;
  // node 1 takes the general form, node 2 the partition of unity.
  [[gnu::always_inline]] static void weights(const Lanes& d, const Lanes& lp, Lanes* w, Lanes* dw) {  // d in [1, 2)
    const Lanes inv = 0.5 / lp;
    // 3/2 - |s| on the outer piece (s >= 1/2), as std::max(0.0, 1.5 - s). (The helpers give their
    // result through a reference: by value a vector's ABI would change with AVX, GCC's -Wpsabi.)
    auto tail = [](Lanes& out, const Lanes& s) __attribute__((always_inline)) {
      const Lanes t = 1.5 - s;
      out = 0.0 < t ? t : Lanes{};
    };
    // The B-spline at s and its integral from -3/2, both from t = |s| (the spline is even, the
    // integral 1/2 + sign(s) times the one from 0).
    auto spline = [](Lanes& out, const Lanes& s) __attribute__((always_inline)) {
      Lanes t;
      abs_lanes(t, s);
      const Lanes u = 1.5 - t;
      const Lanes v = t < 0.5 ? 0.75 - t * t : 0.5 * u * u;
      out = t < 1.5 ? v : Lanes{};
    };
    auto integral = [](Lanes& out, const Lanes& s) __attribute__((always_inline)) {
      Lanes t, signed_half;
      abs_lanes(t, s);
      const Lanes u = 1.5 - t;
      const Lanes half = t < 0.5 ? t * (0.75 - t * t * (1.0 / 3.0)) : 0.5 - u * u * u * (1.0 / 6.0);
      copysign_lanes(signed_half, t < 1.5 ? half : Lanes{} + 0.5, s);
      out = 0.5 + signed_half;
    };
    Lanes p0, q0, p3, q3, upper, lower;
    tail(p0, d - lp);  // node 0 at r = d
    tail(q0, d + lp);
    w[0] = (p0 * p0 * p0 - q0 * q0 * q0) * (1.0 / 6.0) * inv;
    dw[0] = 0.5 * (q0 * q0 - p0 * p0) * inv;
    // node 3 at r = d - 3 < 0, by symmetry: M(s) = tail(-s)^3 / 6 and B(s) = tail(-s)^2 / 2 there
    tail(p3, 3.0 - d + lp);  // tail(-(r - lp))
    tail(q3, 3.0 - d - lp);  // tail(-(r + lp))
    w[3] = (q3 * q3 * q3 - p3 * p3 * p3) * (1.0 / 6.0) * inv;
    dw[3] = 0.5 * (q3 * q3 - p3 * p3) * inv;
    const Lanes r1 = d - 1.0;
    integral(upper, r1 + lp);
    integral(lower, r1 - lp);
    w[1] = (upper - lower) * inv;
    spline(upper, r1 + lp);
    spline(lower, r1 - lp);
    dw[1] = (upper - lower) * inv;
    w[2] = 1.0 - w[0] - w[1] - w[3];
    dw[2] = -(dw[0] + dw[1] + dw[3]);
  }
};

// Four points' stencils at once, point l in lane l of each weight (Rule::kLanes rules): every lane
// computes its point's weights by the same operations, so a point's stencil is the same whichever
// points share its vector (lanes.hpp).
template <class Rule, int D>
[[gnu::always_inline]] inline void lane_stencils(const Vec<D>* const* x, const Mat<D>* const* F, const GridGeometry<D>& g,
                                                 Stencil<4, D>* const* out) {
  for (int axis = 0; axis < D; ++axis) {
    Lanes u{x[0]->c[axis], x[1]->c[axis], x[2]->c[axis], x[3]->c[axis]};
    u = (axis == 1 ? u - g.y_min : u) * g.inv_h;
    const Lanes stretch{(*F[0])(axis, axis), (*F[1])(axis, axis), (*F[2])(axis, axis), (*F[3])(axis, axis)};
    LaneInts first;
    Rule::base(first, u);
    Lanes lp, w[4], dw[4];
    Rule::half_width(lp, g.lp, stretch);
    Rule::weights(u - __builtin_convertvector(first, Lanes), lp, w, dw);
    for (int a = 0; a < 4; ++a) dw[a] *= g.inv_h;
    transpose_lanes(w);
    transpose_lanes(dw);
    for (int l = 0; l < 4; ++l) {
      store_lanes(out[l]->w[axis], w[l]);
      store_lanes(out[l]->g[axis], dw[l]);
    }
    if (axis == 1) {
      for (int l = 0; l < 4; ++l) out[l]->row0 = first[l];
      continue;
    }
    // The periodic axes' node indices, wrapped into [0, n) as wrap() does.
    const int n = axis == 0 ? g.nx : g.nz;
    LaneInts index[4];
    for (int a = 0; a < 4; ++a) {
      const LaneInts i = first + a;
      index[a] = i < 0 ? i + n : (i >= n ? i - n : i);
    }
    transpose_lanes(index);
    for (int l = 0; l < 4; ++l) {
      if (axis == 0) std::memcpy(out[l]->column, &index[l], sizeof index[l]);
      if constexpr (D == 3)
        if (axis == 2) std::memcpy(out[l]->layer, &index[l], sizeof index[l]);
    }
  }
}

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
  // ... of four points at heights y, lane by lane: what first_row gives each. In lanes for the lane
  // rules, whose stencils take their rows the same way (lane_stencils); the others point by point,
  // as their stencils do.
  template <int D>
  [[gnu::always_inline]] static void first_rows(LaneInts& rows, const Lanes& y, const GridGeometry<D>& g) {
    if constexpr (Rule::kLanes) {
      Rule::base(rows, (y - g.y_min) * g.inv_h);
    } else {
      for (int l = 0; l < 4; ++l) rows[l] = first_row(y[l], g);
    }
  }
  // The stencil of a point at x with deformation gradient F (only the point domains use F).
  template <int D>
  [[gnu::always_inline]] static Stencil<S, D> at(const Vec<D>& x, const GridGeometry<D>& g, const Mat<D>& F) {
    if constexpr (Rule::kLanes) {  // the point in every lane
      Stencil<S, D> st;
      const Vec<D>* xs[4] = {&x, &x, &x, &x};
      const Mat<D>* Fs[4] = {&F, &F, &F, &F};
      Stencil<S, D>* outs[4] = {&st, &st, &st, &st};
      detail::lane_stencils<Rule, D>(xs, Fs, g, outs);
      return st;
    } else {
      return detail::tensor_stencil<Rule, S, D>(x, g, F);
    }
  }
  // ... of an undeformed point.
  template <int D>
  static Stencil<S, D> at(const Vec<D>& x, const GridGeometry<D>& g) {
    return at<D>(x, g, Mat<D>::identity());
  }
  // ... of four points, out[l] that of x[l] with F[l] (the same stencils as at() gives each).
  template <int D>
  [[gnu::always_inline]] static void at_four(const Vec<D>* const* x, const Mat<D>* const* F, const GridGeometry<D>& g,
                                             Stencil<S, D>* const* out) {
    if constexpr (Rule::kLanes) {
      detail::lane_stencils<Rule, D>(x, F, g, out);
    } else {
      for (int l = 0; l < 4; ++l) *out[l] = detail::tensor_stencil<Rule, S, D>(*x[l], g, *F[l]);
    }
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
