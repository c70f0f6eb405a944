// The background grid: regular square cells of size h, periodic in x, free (unconstrained) in y.
#pragma once

#include <cstddef>
#include <vector>

namespace mpmshock {

struct GridGeometry {
  int nx = 0;          // node columns = cell columns (periodic: column nx is column 0)
  int ny = 0;          // node rows; cell rows are ny - 1
  double h = 0.0;      // cell size
  double inv_h = 0.0;
  double y_min = 0.0;  // y of node row 0
  double lp = 0.0;     // uGIMP: half-width of a material point's domain, in cells

  double width() const { return nx * h; }
  double y_max() const { return y_min + (ny - 1) * h; }
  std::size_t nodes() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  std::size_t node(int column, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(column);
  }
};

// Nodal fields, one array each. After the momentum update (fx, fy) hold the accelerations f/m and
// (vx, vy) the updated velocities; (px, py) are reused for the re-mapped momentum and velocity.
struct Grid {
  GridGeometry geo;
  std::vector<double> m;       // nodal mass m_i
  std::vector<double> px, py;  // nodal momentum p_i
  std::vector<double> fx, fy;  // nodal force f_i, then acceleration f_i / m_i
  std::vector<double> vx, vy;  // nodal velocity v_i^{n+1}

  explicit Grid(const GridGeometry& g = {});
  // Zeroes mass, momentum and force on node rows [row_begin, row_end).
  void reset(int row_begin, int row_end);
  static constexpr std::size_t bytes_per_node() { return 7 * sizeof(double); }
};

}  // namespace mpmshock
