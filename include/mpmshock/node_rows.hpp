// Four consecutive nodes of a stencil row in the lanes of vector registers (lanes.hpp), for the
// passes of the default four-column stencils (bspline2_domain) in 2D and 3D. A nodal vector field
// is stored as (x, y) pairs or (x, y, z) triples, so a row's four nodes are D vectors:
//   2D  [x0 y0 x1 y1] [x2 y2 x3 y3]
//   3D  [x0 y0 z0 x1] [y1 z1 x2 y2] [z2 x3 y3 z3]
// and a column weight repeats in the same pattern (2D [w0 w0 w1 w1] [w2 w2 w3 w3]). A scalar field
// (mass) is one vector [m0 m1 m2 m3]. A row whose columns wrap round the periodic x boundary is not
// consecutive: its nodes are loaded and stored one by one (the components of a node that share a
// vector's half as that half) into the same lanes, so every point computes the same numbers
// whichever way. Each lane computes a node's weights as for_each_node does (shape.hpp), so a
// scatter adds to each node what the scalar loop added, in the same order of points; a gather's sum
// over the stencil is grouped by lanes, which moves it at round-off from the scalar loop's. Both
// stay bitwise independent of thread and rank counts.
#pragma once

#include <cstddef>
#include <cstring>

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
// The sum over the lanes of each component.
template <int D>
[[gnu::always_inline]] inline Vec<D> sum_components(const RowLanes<D>& a) {
  if constexpr (D == 2) {
    const Lanes s = a.v[0] + a.v[1];
    return Vec<2>{{s[0] + s[2], s[1] + s[3]}};
  } else {
    return Vec<3>{{a.v[0][0] + a.v[0][3] + a.v[1][2] + a.v[2][1], a.v[0][1] + a.v[1][0] + a.v[1][3] + a.v[2][2],
                   a.v[0][2] + a.v[1][1] + a.v[2][0] + a.v[2][3]}};
  }
}

// Whether a stencil's four columns are consecutive (no periodic wrap inside it): then a row's nodes
// load and store as whole vectors, else node by node into the same lanes (the same numbers).
template <int D>
[[gnu::always_inline]] inline bool consecutive_columns(const Stencil<4, D>& st) {
  return st.column[3] == st.column[0] + 3;
}

// Loads and stores a row of a D-vector field; `row` points at the row's node of column 0.
template <int D>
[[gnu::always_inline]] inline void load_row(RowLanes<D>& out, const Vec<D>* row, const int* column, bool consecutive) {
  if (consecutive) {
    const double* p = row[column[0]].c;
    for (int k = 0; k < D; ++k) load_lanes(out.v[k], p + 4 * k);
    return;
  }
  if constexpr (D == 2) {  // a vector is two whole nodes
    for (int k = 0; k < 2; ++k) load_halves(out.v[k], row[column[2 * k]].c, row[column[2 * k + 1]].c);
  } else {  // [x0 y0 | z0 x1] [y1 z1 | x2 y2] [z2 x3 | y3 z3]: pairs that lie together load as halves
    const double *n0 = row[column[0]].c, *n1 = row[column[1]].c, *n2 = row[column[2]].c, *n3 = row[column[3]].c;
    HalfLanes x0y0, y1z1, x2y2, y3z3;
    load_half(x0y0, n0);
    load_half(y1z1, n1 + 1);
    load_half(x2y2, n2);
    load_half(y3z3, n3 + 1);
    join_halves(out.v[0], x0y0, HalfLanes{n0[2], n1[0]});
    join_halves(out.v[1], y1z1, x2y2);
    join_halves(out.v[2], HalfLanes{n2[2], n3[0]}, y3z3);
  }
}
template <int D>
[[gnu::always_inline]] inline void store_row(Vec<D>* row, const int* column, bool consecutive, const RowLanes<D>& v) {
  if (consecutive) {
    double* p = row[column[0]].c;
    for (int k = 0; k < D; ++k) store_lanes(p + 4 * k, v.v[k]);
    return;
  }
  if constexpr (D == 2) {
    for (int k = 0; k < 2; ++k) store_halves(row[column[2 * k]].c, row[column[2 * k + 1]].c, v.v[k]);
  } else {
    double *n0 = row[column[0]].c, *n1 = row[column[1]].c, *n2 = row[column[2]].c, *n3 = row[column[3]].c;
    HalfLanes x0y0, z0x1, z2x3, y3z3;
    split_halves(x0y0, z0x1, v.v[0]);
    store_halves(n1 + 1, n2, v.v[1]);
    split_halves(z2x3, y3z3, v.v[2]);
    store_half(n0, x0y0);
    store_half(n3 + 1, y3z3);
    n0[2] = z0x1[0];
    n1[0] = z0x1[1];
    n2[2] = z2x3[0];
    n3[0] = z2x3[1];
  }
}
// ... and of a scalar field, one node per lane.
[[gnu::always_inline]] inline void load_scalar_row(Lanes& v, const double* row, const int* column, bool consecutive) {
  if (consecutive)
    load_lanes(v, row + column[0]);
  else
    v = Lanes{row[column[0]], row[column[1]], row[column[2]], row[column[3]]};
}
[[gnu::always_inline]] inline void store_scalar_row(double* row, const int* column, bool consecutive, const Lanes& v) {
  if (consecutive) {
    store_lanes(row + column[0], v);
    return;
  }
  for (int a = 0; a < 4; ++a) row[column[a]] = v[a];
}

// The shape of one row of a four-column stencil, as for_each_node computes it per node: the weights
// N (one per node, `scalar`, and repeated per component, `N`) and the gradient dN[j].
template <int D>
struct RowShape {
  Lanes scalar;
  RowLanes<D> N;
  RowLanes<D> dN[D];
};

// Visits each row of a four-column stencil: f(first node of the row, its shape), rows in
// for_each_node's order (y outermost, then z).
template <int D, class F>
[[gnu::always_inline]] inline void for_each_row(const Stencil<4, D>& st, const GridGeometry<D>& g, F&& f) {
  RowLanes<D> wx, gx;
  column_lanes<D>(wx, st.w[0]);
  column_lanes<D>(gx, st.g[0]);
  Lanes w_columns;
  load_lanes(w_columns, st.w[0]);
  RowShape<D> shape;
  for (int b = 0; b < 4; ++b) {
    const double wy = st.w[1][b], gy = st.g[1][b];
    if constexpr (D == 2) {
      shape.scalar = w_columns * wy;
      for (int k = 0; k < 2; ++k) {
        shape.N.v[k] = wx.v[k] * wy;
        shape.dN[0].v[k] = gx.v[k] * wy;
        shape.dN[1].v[k] = wx.v[k] * gy;
      }
      f(g.row_start(st.row0 + b), shape);
    } else {
      for (int c = 0; c < 4; ++c) {
        const double wz = st.w[2][c], gz = st.g[2][c];
        shape.scalar = (w_columns * wy) * wz;
        for (int k = 0; k < 3; ++k) {
          const Lanes wxy = wx.v[k] * wy;
          shape.N.v[k] = wxy * wz;
          shape.dN[0].v[k] = (gx.v[k] * wy) * wz;
          shape.dN[1].v[k] = (wx.v[k] * gy) * wz;
          shape.dN[2].v[k] = wxy * gz;
        }
        f(g.row_start(st.row0 + b) + static_cast<std::size_t>(st.layer[c]) * static_cast<std::size_t>(g.nx), shape);
      }
    }
  }
}

}  // namespace mpmshock
