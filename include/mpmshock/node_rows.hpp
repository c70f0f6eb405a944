// The four nodes of a stencil row in the lanes of vector registers (lanes.hpp), for the
// passes of the default four-column stencils (bspline2_domain) in 2D and 3D. A nodal vector field
// is stored as (x, y) pairs or (x, y, z) triples, so a row's four nodes are D vectors:
//   2D  [x0 y0 x1 y1] [x2 y2 x3 y3]
//   3D  [x0 y0 z0 x1] [y1 z1 x2 y2] [z2 x3 y3 z3]
// and a column weight repeats in the same pattern (2D [w0 w0 w1 w1] [w2 w2 w3 w3]). A scalar field
// (mass) is one vector [m0 m1 m2 m3]. A row whose columns wrap round the periodic x boundary lies
// in two runs of memory, the row's last nodes and its first: each vector inside one run is still
// one load or store, and the one across the seam is taken as halves (column_split, RowRuns). How a
// stencil's columns lie is decided once per point and the pass's row loop compiled for each of the
// four ways (RowNodes): the same formulas, but the compiler may contract a*b + c into FMAs
// differently in the copies, so a point beside the seam can differ at round-off from the same
// point elsewhere. The shape is factored into columns and rows (Columns, RowFactors below), so a
// node's contribution differs at round-off from for_each_node's (shape.hpp), which the other
// stencils use. Whether a stencil wraps depends only on the point's x, and every node sums its
// points in the same order, so results stay bitwise independent of thread and rank counts.
#pragma once

#include <cassert>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "mpmshock/grid.hpp"
#include "mpmshock/lanes.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/tensor.hpp"

namespace mpmshock {

static_assert(sizeof(Vec<2>) == 2 * sizeof(double) && sizeof(Vec<3>) == 3 * sizeof(double),
              "a row of Vec<D> is D-tuples of doubles, one after another");

// A row's four nodes of a D-vector field (or D per-node values in the same pattern).
template <int D>
struct RowLanes {
  Lanes v[D];
};

// The component (x 0, y 1, z 2) and the node (0-3) of lane l of vector k.
template <int D>
constexpr int component_of(int k, int l) {
  return (4 * k + l) % D;
}
template <int D>
constexpr int node_of(int k, int l) {
  return (4 * k + l) / D;
}

// A column weight per node, repeated for each node's D components.
template <int D>
[[gnu::always_inline]] inline void column_lanes(RowLanes<D>& out, const double* c) {
  for (int k = 0; k < D; ++k)
    out.v[k] = Lanes{c[node_of<D>(k, 0)], c[node_of<D>(k, 1)], c[node_of<D>(k, 2)], c[node_of<D>(k, 3)]};
}
// A per-point D-vector repeated at each node: 2D [a b a b], 3D [a b c a] [b c a b] [c a b c].
template <int D>
[[gnu::always_inline]] inline void component_lanes(RowLanes<D>& out, const double* a) {
  for (int k = 0; k < D; ++k)
    out.v[k] = Lanes{a[component_of<D>(k, 0)], a[component_of<D>(k, 1)], a[component_of<D>(k, 2)],
                     a[component_of<D>(k, 3)]};
}
// The sum over the lanes of each component: 2D (n0 + n2) + (n1 + n3), 3D ((n0 + n1) + n2) + n3,
// with the nodes' components aligned by shuffles so that the components add in vector lanes (the
// same sums as lane by lane, in fewer instructions).
template <int D>
[[gnu::always_inline]] inline Vec<D> sum_components(const RowLanes<D>& a) {
  if constexpr (D == 2) {
    HalfLanes low, high;
    split_halves(low, high, a.v[0] + a.v[1]);
    const HalfLanes s = low + high;
    return Vec<2>{{s[0], s[1]}};
  } else {  // node k's (x, y, z) into lanes 0-2; lane 3 is not used
    const Lanes n1 = __builtin_shufflevector(a.v[0], a.v[1], 3, 4, 5, 5);
    const Lanes n2 = __builtin_shufflevector(a.v[1], a.v[2], 2, 3, 4, 4);
    const Lanes n3 = __builtin_shufflevector(a.v[2], a.v[2], 1, 2, 3, 3);
    const Lanes s = ((a.v[0] + n1) + n2) + n3;
    return Vec<3>{{s[0], s[1], s[2]}};
  }
}

// Where a stencil row's four nodes lie in the grid's row. Split 0: at columns c0 .. c0 + 3, one run
// of memory (run A). Split s = 1, 2 or 3: wrapped round the periodic seam after s nodes, which are run A,
// the columns nx - s .. nx - 1 (from the stencil's first column), and then run B, the columns
// 0 .. 3 - s (from the row's first node). A grid is at least four cells wide (scene.cpp), so a
// stencil's columns are one of these.
template <int D>
[[gnu::always_inline]] inline int column_split(const Stencil<4, D>& st, int nx) {
  return st.column[3] == st.column[0] + 3 ? 0 : nx - st.column[0];
}

// A row's four nodes of W doubles each (W = D for a vector field, 1 for a scalar one) are 4 W
// doubles in order, W vectors of four; double d lies in run A if d < W * Split (every double with
// Split 0), else in run B.
template <int W, int Split>
struct RowRuns {
  static constexpr bool in_a(int d) { return Split == 0 || d < W * Split; }
  // Doubles d .. d + n - 1 lie in one run, so one after another in memory.
  static constexpr bool together(int d, int n) { return in_a(d) == in_a(d + n - 1); }
  template <class P>
  static P at(P a, P b, int d) {
    return in_a(d) ? a + d : b + (d - W * Split);
  }
};

// Vector K of a row's doubles: one load where its four doubles lie in one run, else its halves,
// each one load where its two lie in one run, else two doubles (only the vector across the seam).
template <int W, int Split, int K>
[[gnu::always_inline]] inline void load_run_vector(Lanes& v, const double* a, const double* b) {
  using R = RowRuns<W, Split>;
  constexpr int d = 4 * K;
  if constexpr (R::together(d, 4)) {
    load_lanes(v, R::at(a, b, d));
  } else {
    HalfLanes low, high;
    if constexpr (R::together(d, 2)) load_half(low, R::at(a, b, d));
    else low = HalfLanes{*R::at(a, b, d), *R::at(a, b, d + 1)};
    if constexpr (R::together(d + 2, 2)) load_half(high, R::at(a, b, d + 2));
    else high = HalfLanes{*R::at(a, b, d + 2), *R::at(a, b, d + 3)};
    join_halves(v, low, high);
  }
}
template <int W, int Split, int K>
[[gnu::always_inline]] inline void store_run_vector(double* a, double* b, const Lanes& v) {
  using R = RowRuns<W, Split>;
  constexpr int d = 4 * K;
  if constexpr (R::together(d, 4)) {
    store_lanes(R::at(a, b, d), v);
  } else {
    HalfLanes low, high;
    split_halves(low, high, v);
    if constexpr (R::together(d, 2)) {
      store_half(R::at(a, b, d), low);
    } else {
      *R::at(a, b, d) = low[0];
      *R::at(a, b, d + 1) = low[1];
    }
    if constexpr (R::together(d + 2, 2)) {
      store_half(R::at(a, b, d + 2), high);
    } else {
      *R::at(a, b, d + 2) = high[0];
      *R::at(a, b, d + 3) = high[1];
    }
  }
}
template <int W, int Split, std::size_t... K>
[[gnu::always_inline]] inline void load_run_vectors(Lanes* v, const double* a, const double* b,
                                                    std::index_sequence<K...>) {
  (load_run_vector<W, Split, static_cast<int>(K)>(v[K], a, b), ...);
}
template <int W, int Split, std::size_t... K>
[[gnu::always_inline]] inline void store_run_vectors(double* a, double* b, const Lanes* v, std::index_sequence<K...>) {
  (store_run_vector<W, Split, static_cast<int>(K)>(a, b, v[K]), ...);
}

// A four-column stencil's shape, factored. The node of column c in a row has
//   N = w_c * row.weight,   dN/dx = g_c * row.weight,   dN/dx_j = w_c * row.gradient[j] (j = y, z)
// with w_c and g_c the x weight and derivative of column c (Columns, once per point) and the row's
// factors the products of its y (and z) weights and derivatives (RowFactors: once per row, in 3D
// for a y row's four z layers at once). So a
// scatter weighs a point's values by the columns once and adds them to each row with a row factor,
// and a gather sums a row's nodes with the row factors and weighs the sums by the columns once at the
// end (RowSums): the node weights are never formed (issue 32: they were 6 products a row in 2D,
// 16 in 3D, for every pass).
template <int D>
struct Columns {
  Lanes weight;    // [w0 w1 w2 w3], for a scalar field
  RowLanes<D> w;   // the weights repeated per component (column_lanes)
  RowLanes<D> g;   // the derivatives repeated per component
};
template <int D>
[[gnu::always_inline]] inline Columns<D> columns_of(const Stencil<4, D>& st) {
  Columns<D> c;
  load_lanes(c.weight, st.w[0]);
  column_lanes<D>(c.w, st.w[0]);
  column_lanes<D>(c.g, st.g[0]);
  return c;
}

// In 2D the stencil's y weight and derivative, which the passes broadcast from memory; in
// 3D products of y and z factors, found for the four layers at once and each spread over four
// lanes (for_each_row: x86-64-v3, 3D narrow column 3,973 -> 3,631 instructions per point-step).
template <int D>
struct RowFactors {
  using Factor = std::conditional_t<D == 3, Lanes, double>;
  Factor weight;       // the product of the row's y (and z) weights
  Factor gradient[D];  // [j] for j = 1 .. D-1: the same product with axis j's derivative; [0] unused
};

// Lane C of v in all four lanes: one permute.
template <int C>
[[gnu::always_inline]] inline Lanes lane_in_all(const Lanes& v) {
  return __builtin_shufflevector(v, v, C, C, C, C);
}

// A stencil row's four nodes in a nodal field, with how they lie (column_split) known when compiled,
// so that a pass decides it once per point and not at every load and store. `row` points at the
// row's node of column 0 (the first node of run B); run A starts at the stencil's first column.
template <int Split>
struct RowNodes {
  const int* column;
  template <int D>
  [[gnu::always_inline]] void load(RowLanes<D>& out, const Vec<D>* row) const {
    load_run_vectors<D, Split>(out.v, row[column[0]].c, row[0].c, std::make_index_sequence<D>{});
  }
  template <int D>
  [[gnu::always_inline]] void store(Vec<D>* row, const RowLanes<D>& v) const {
    store_run_vectors<D, Split>(row[column[0]].c, row[0].c, v.v, std::make_index_sequence<D>{});
  }
  [[gnu::always_inline]] void load(Lanes& out, const double* row) const {
    load_run_vector<1, Split, 0>(out, row + column[0], row);
  }
  [[gnu::always_inline]] void store(double* row, const Lanes& v) const {
    store_run_vector<1, Split, 0>(row + column[0], row, v);
  }
};

// Visits each row of a four-column stencil: f(first node of the row, its factors, its RowNodes),
// rows in for_each_node's order (y outermost, then z).
template <int D, class F>
[[gnu::always_inline]] inline void for_each_row(const Stencil<4, D>& st, const GridGeometry<D>& g, F&& f) {
  auto rows = [&](const auto& nodes) __attribute__((always_inline)) {
    const std::size_t first = g.row_start(st.row0), stride = g.nodes_per_row();
    RowFactors<D> r{};
    [[maybe_unused]] Lanes wz, gz;  // 3D: the four layers' z weights and derivatives
    if constexpr (D == 3) {
      load_lanes(wz, st.w[2]);
      load_lanes(gz, st.g[2]);
    }
    for (int b = 0; b < 4; ++b) {
      const double wy = st.w[1][b], gy = st.g[1][b];
      const std::size_t row = first + static_cast<std::size_t>(b) * stride;
      if constexpr (D == 2) {
        r.weight = wy;
        r.gradient[1] = gy;
        f(row, r, nodes);
      } else {  // the four layers' products at once, each then spread from its lane
        const Lanes weights = wy * wz, y_gradients = gy * wz, z_gradients = wy * gz;
        auto layer = [&](auto c) __attribute__((always_inline)) {
          r.weight = lane_in_all<c>(weights);
          r.gradient[1] = lane_in_all<c>(y_gradients);
          r.gradient[2] = lane_in_all<c>(z_gradients);
          f(row + static_cast<std::size_t>(st.layer[c]) * static_cast<std::size_t>(g.nx), r, nodes);
        };
        layer(std::integral_constant<int, 0>{});
        layer(std::integral_constant<int, 1>{});
        layer(std::integral_constant<int, 2>{});
        layer(std::integral_constant<int, 3>{});
      }
    }
  };
  const int split = column_split(st, g.nx);
  assert(split >= 0 && split <= 3);  // a grid at least four cells wide (scene.cpp)
  switch (split) {
    case 0: rows(RowNodes<0>{st.column}); break;
    case 1: rows(RowNodes<1>{st.column}); break;
    case 2: rows(RowNodes<2>{st.column}); break;
    default: rows(RowNodes<3>{st.column}); break;
  }
}

// A gather's row sums of a D-vector field x over a stencil: sum_rows weight x_row and, With gradient,
// sum_rows gradient[j] x_row; then the field at the point, sum_i N_i x_i, and its gradient,
// sum_i x_i (x) grad N_i.
template <int D, bool WithGradient>
struct RowSums {
  RowLanes<D> weight{};
  RowLanes<D> gradient[D]{};  // [j] for j = 1 .. D-1

  [[gnu::always_inline]] void add(const RowFactors<D>& r, const RowLanes<D>& x) {
    for (int k = 0; k < D; ++k) {
      weight.v[k] += r.weight * x.v[k];
      if constexpr (WithGradient)
        for (int j = 1; j < D; ++j) gradient[j].v[k] += r.gradient[j] * x.v[k];
    }
  }
  // sum_c factor_c sums(c, d), per component d.
  [[gnu::always_inline]] static Vec<D> weigh(const RowLanes<D>& factor, const RowLanes<D>& sums) {
    RowLanes<D> product;
    for (int k = 0; k < D; ++k) product.v[k] = factor.v[k] * sums.v[k];
    return sum_components(product);
  }
  [[gnu::always_inline]] Vec<D> value(const Columns<D>& c) const { return weigh(c.w, weight); }
  // G(d, j) = sum_i x_i[d] dN_i/dx_j.
  [[gnu::always_inline]] Mat<D> gradient_of(const Columns<D>& c) const {
    Mat<D> G;
    for (int j = 0; j < D; ++j) {
      const Vec<D> column = j == 0 ? weigh(c.g, weight) : weigh(c.w, gradient[j]);
      for (int d = 0; d < D; ++d) G(d, j) = column[d];
    }
    return G;
  }
};

}  // namespace mpmshock
