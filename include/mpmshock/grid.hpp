// The background grid: regular cubic (square) cells of size h; periodic in x (and z in 3D), free
// (unconstrained) in y. Node (i, j, k) sits at (i h, y_min + j h, k h). Nodes are stored with y
// slowest, so the nodes of a range of y rows are one contiguous range. A process holds the rows
// [row0, row0 + rows_held()) of the ny (all of them on one rank; its slab's on an MPI rank:
// decomposition.hpp); rows keep their global numbers, and row_start() finds a held row's nodes.
#pragma once

#include <cstddef>
#include <vector>

#include "mpmshock/tensor.hpp"

namespace mpmshock {

template <int D>
struct GridGeometry {
  int nx = 0;          // node columns = cell columns (periodic: column nx is column 0)
  int ny = 0;          // node rows; cell rows are ny - 1
  int nz = 1;          // node layers in z (periodic); 1 in 2D
  double h = 0.0;      // cell size
  double inv_h = 0.0;
  double y_min = 0.0;  // y of node row 0
  double lp = 0.0;     // GIMP: initial half-width of a material point's domain, in cells
  int row0 = 0;        // the first node row held here
  int held_rows = -1;  // node rows held from row0; -1: all of them

  double width() const { return nx * h; }
  double depth() const { return nz * h; }
  // The area (3D) or width (2D, per metre of depth) of a horizontal section of the column.
  double cross_section() const { return D == 2 ? width() : width() * depth(); }
  double y_max() const { return y_min + (ny - 1) * h; }
  // The period of a periodic axis (x, and z in 3D).
  double period(int axis) const { return axis == 0 ? width() : depth(); }
  std::size_t nodes_per_row() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(nz); }
  int rows_held() const { return held_rows < 0 ? ny - row0 : held_rows; }
  // The nodes held here (all of the grid's on one rank).
  std::size_t nodes() const { return nodes_per_row() * static_cast<std::size_t>(rows_held()); }
  // The first node of held row j (the nodes of rows [a, b) are [row_start(a), row_start(b))).
  std::size_t row_start(int row) const { return static_cast<std::size_t>(row - row0) * nodes_per_row(); }
  // The same grid holding only the rows [first, end).
  GridGeometry holding(int first, int end) const {
    GridGeometry g = *this;
    g.row0 = first;
    g.held_rows = end - first;
    return g;
  }
  // The same grid holding every row.
  GridGeometry whole() const { return holding(0, ny); }
};

// A range of node rows [begin, end): the rows a step's points touch.
struct RowRange {
  int begin = 0, end = 0;
};

// Nodal fields, one array each, each with one meaning for the whole step:
//   m        nodal mass m_i (P2G)
//   mv       nodal momentum p_i (P2G); in MUSL then the re-mapped momentum sum N m_p v_p^{n+1}
//   f        nodal force f_i (P2G)
//   a        acceleration a_i = f_i / m_i
//   v        velocity v_i^{n+1} = (p_i + dt f_i) / m_i
//   v_remap  MUSL: the re-mapped velocity v~_i = sum N m_p v_p^{n+1} / m_i
//   v_sum    v^n_i + u_i, the step's start velocity v^n = v^{n+1} - dt a plus the one the points
//            move by (u: v^{n+1}, or v~ in MUSL): twice the velocity the work is taken from
template <int D>
struct Grid {
  GridGeometry<D> geo;
  std::vector<double> m;
  std::vector<Vec<D>> mv, f, a, v, v_remap, v_sum;

  explicit Grid(const GridGeometry<D>& g = {});
  // Zeroes mass, momentum and force on the given rows.
  void reset(RowRange rows);
  // Memory per node, for --check and the benchmarks.
  static std::size_t bytes_per_node() {
    std::size_t bytes = 0;
    Grid<D>{}.for_each_field([&bytes](const auto& field) { bytes += sizeof(field[0]); });
    return bytes;
  }

  // Every nodal field, for the operations that must not forget one.
  template <class F>
  void for_each_field(F&& f) {
    f(m), f(mv), f(this->f), f(a), f(v), f(v_remap), f(v_sum);
  }
};

extern template struct Grid<2>;
extern template struct Grid<3>;

}  // namespace mpmshock
