// The symmetry plane y = 0 (symmetry = on): the boundary a mirror-image flyer puts on the target.
// Only the target's points are simulated; the grid keeps its rows below the plane as ghost rows.
//
// The mirror image of a point at (x, y) with velocity (v_x, v_y) and stress sigma sits at (x, -y)
// with (v_x, -v_y) and sigma_xy negated; its share at node (i, j) is exactly the point's own share at
// the mirror node (i, -j), with the y components of momentum and force negated. So after P2G each
// ghost row is folded onto its mirror row above the plane (m += m', p_x += p'_x, p_y -= p'_y, and f
// alike), the plane's own row counts twice with no normal momentum or force, and the ghost rows are
// then set to the mirror of the rows above. The momentum update keeps that symmetry exactly (v_y = 0
// on the plane: no normal velocity; the tangential velocity is free: no shear traction), and every
// point reads the same nodal values the whole-domain run would give it. The MUSL re-map scatter
// is folded the same way. A point never crosses the plane: the nodal v_y is odd in y, so the
// velocity interpolated at a point vanishes as its y does.
//
// A nodal scalar that is even in y (a mass-weighted temperature, a heat rate: heat conduction's
// sums) folds as the mass does (fold_scalar): the ghost's share is added to its mirror node, the
// plane's row counts twice, and the ghost then holds its mirror's value.
#pragma once

#include <cmath>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/mirror_image.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/step_effect.hpp"

namespace mpmshock {

template <int D>
class SymmetryPlane final : public StepEffect<D> {
 public:
  explicit SymmetryPlane(const GridGeometry<D>& g) : plane_row_(static_cast<int>(std::lround(-g.y_min * g.inv_h))) {}
  const char* name() const override { return "symmetry plane"; }
  unsigned slots() const override { return slot_bit(StepSlot::after_to_grid) | slot_bit(StepSlot::before_remap); }

  // Each ghost node is the only one folded onto its mirror node, so one pass folds it and sets it.
  void after_to_grid(StepContext<D>& c) override {
    Grid<D>& g = c.grid;
    fold(g, c.rows, [&g](std::size_t ghost, std::size_t image, bool on_plane) {
      if (on_plane) {  // its own mirror image: twice the share, no normal component
        g.m[image] *= 2.0;
        twice_tangential(g.mv[image]);
        twice_tangential(g.f[image]);
        return;
      }
      g.m[ghost] = g.m[image] += g.m[ghost];
      g.mv[ghost] = reflected(add_reflected(g.mv[image], g.mv[ghost]));
      g.f[ghost] = reflected(add_reflected(g.f[image], g.f[ghost]));
    });
  }

  // The mirror's share of a nodal scalar even in y, scattered by the step's points on `rows`.
  void fold_scalar(const Grid<D>& g, std::vector<double>& field, RowRange rows) const {
    fold(g, rows, [&field](std::size_t ghost, std::size_t image, bool on_plane) {
      if (on_plane) field[image] *= 2.0;
      else field[ghost] = field[image] += field[ghost];
    });
  }

  void before_remap(StepContext<D>& c) override {
    Grid<D>& g = c.grid;
    fold(g, c.rows, [&g](std::size_t ghost, std::size_t image, bool on_plane) {
      if (on_plane) twice_tangential(g.mv[image]);
      else g.mv[ghost] = reflected(add_reflected(g.mv[image], g.mv[ghost]));
    });
  }

 private:
  int plane_row_;  // the node row on y = 0

  static const Vec<D>& add_reflected(Vec<D>& to, const Vec<D>& u) {
    for (int d = 0; d < D; ++d) to[d] += d == 1 ? -u[d] : u[d];
    return to;
  }
  static void twice_tangential(Vec<D>& u) {
    for (int d = 0; d < D; ++d) u[d] = d == 1 ? 0.0 : 2.0 * u[d];
  }

  // Calls f(ghost node, its mirror node, on the plane) for every node of the step's rows on or
  // below the plane whose mirror row the step also uses; on the plane both nodes are the same.
  template <class F>
  void fold(const Grid<D>& g, RowRange rows, F&& f) const {
    const GridGeometry<D>& geo = g.geo;
    const int first = std::max(rows.begin, 2 * plane_row_ - (rows.end - 1));
    if (first > plane_row_) return;
    const std::size_t per_row = geo.nodes_per_row();
    const auto ghosts = static_cast<std::ptrdiff_t>(static_cast<std::size_t>(plane_row_ - first + 1) * per_row);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < ghosts; ++k) {
      const int row = first + static_cast<int>(static_cast<std::size_t>(k) / per_row);
      const std::size_t column = static_cast<std::size_t>(k) % per_row;
      f(geo.row_start(row) + column, geo.row_start(2 * plane_row_ - row) + column, row == plane_row_);
    }
  }
};

}  // namespace mpmshock
