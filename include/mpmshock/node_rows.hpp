// Four consecutive nodes of a stencil row in the lanes of one vector register (AVX2 width; two SSE2
// halves on a baseline x86-64 build), for the gathers of 2D stencils of four columns (the default
// bspline2_domain): a nodal vector field stored as interleaved (x, y) pairs gives a row's eight
// values in two vectors, [x0 y0 x1 y1] and [x2 y2 x3 y3], and the columns' weights repeat in the
// same pattern, [w0 w0 w1 w1] and [w2 w2 w3 w3]. A row whose columns wrap around the periodic x
// boundary is not consecutive: its nodes are loaded and stored one by one into the same lanes, so
// every point computes the same numbers whichever way. A scatter adds to each node what the scalar
// loop added, in the same order of points; a gather's sum over the stencil is grouped by lanes,
// which moves it at round-off from the scalar loop's. Both stay bitwise independent of thread and
// rank counts.
#pragma once

#include <cstring>

#include "mpmshock/shape.hpp"
#include "mpmshock/tensor.hpp"

// Without AVX (a portable x86-64 build) the vectors are two SSE2 halves; the helpers take and give
// them by reference, since by value their ABI would change with AVX (GCC's -Wpsabi note).
namespace mpmshock {

typedef double Lanes __attribute__((vector_size(32)));

static_assert(sizeof(Vec<2>) == 2 * sizeof(double), "a row of Vec<2> is interleaved (x, y) pairs");

[[gnu::always_inline]] inline void load_lanes(Lanes& v, const double* p) { std::memcpy(&v, p, sizeof v); }

// Whether a stencil's four columns are consecutive (no periodic wrap inside it): then a row's nodes
// load and store as two vectors, else node by node into the same lanes (the same numbers).
[[gnu::always_inline]] inline bool consecutive_columns(const Stencil<4, 2>& st) {
  return st.column[3] == st.column[0] + 3;
}

// The interleaved (x, y) values of a stencil row's four nodes; `row` points at the row's node 0.
struct RowPairs {
  Lanes low, high;  // nodes 0, 1 and 2, 3
};
[[gnu::always_inline]] inline void load_row(RowPairs& v, const Vec<2>* row, const int* column, bool consecutive) {
  if (consecutive) {
    const double* p = row[column[0]].c;
    load_lanes(v.low, p);
    load_lanes(v.high, p + 4);
    return;
  }
  const Vec<2>&n0 = row[column[0]], &n1 = row[column[1]], &n2 = row[column[2]], &n3 = row[column[3]];
  v.low = Lanes{n0.c[0], n0.c[1], n1.c[0], n1.c[1]};
  v.high = Lanes{n2.c[0], n2.c[1], n3.c[0], n3.c[1]};
}
// The four values of a scalar row (mass), one node per lane.
[[gnu::always_inline]] inline void load_scalar_row(Lanes& v, const double* row, const int* column, bool consecutive) {
  if (consecutive)
    load_lanes(v, row + column[0]);
  else
    v = Lanes{row[column[0]], row[column[1]], row[column[2]], row[column[3]]};
}
// Stores back what load_row and load_scalar_row read.
[[gnu::always_inline]] inline void store_row(Vec<2>* row, const int* column, bool consecutive, const RowPairs& v) {
  if (consecutive) {
    double* p = row[column[0]].c;
    std::memcpy(p, &v.low, sizeof v.low);
    std::memcpy(p + 4, &v.high, sizeof v.high);
    return;
  }
  row[column[0]] = Vec<2>{{v.low[0], v.low[1]}};
  row[column[1]] = Vec<2>{{v.low[2], v.low[3]}};
  row[column[2]] = Vec<2>{{v.high[0], v.high[1]}};
  row[column[3]] = Vec<2>{{v.high[2], v.high[3]}};
}
[[gnu::always_inline]] inline void store_scalar_row(double* row, const int* column, bool consecutive, const Lanes& v) {
  if (consecutive) {
    std::memcpy(row + column[0], &v, sizeof v);
    return;
  }
  for (int a = 0; a < 4; ++a) row[column[a]] = v[a];
}

// A column weight per node, repeated for the two components of each: [c0 c0 c1 c1], [c2 c2 c3 c3].
struct ColumnPairs {
  Lanes low, high;
  explicit ColumnPairs(const double* c) : low{c[0], c[0], c[1], c[1]}, high{c[2], c[2], c[3], c[3]} {}
};


// The sum of a vector's even lanes (x components) and of its odd lanes (y components).
[[gnu::always_inline]] inline Vec<2> sum_pairs(const Lanes& a) { return Vec<2>{{a[0] + a[2], a[1] + a[3]}}; }

}  // namespace mpmshock
