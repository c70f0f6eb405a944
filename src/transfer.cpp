#include "mpmshock/transfer.hpp"

#include "mpmshock/parallel.hpp"

namespace mpmshock {

void update_grid_momentum(Grid& g, int row_begin, int row_end, double dt) {
  const auto b = static_cast<std::ptrdiff_t>(g.geo.node(0, row_begin));
  const auto e = static_cast<std::ptrdiff_t>(g.geo.node(0, row_end));
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::ptrdiff_t i = b; i < e; ++i) {
    const double m = g.m[i];
    if (m > 0.0) {
      const double inv_m = 1.0 / m;
      g.vx[i] = (g.px[i] + dt * g.fx[i]) * inv_m;
      g.vy[i] = (g.py[i] + dt * g.fy[i]) * inv_m;
      g.fx[i] *= inv_m;
      g.fy[i] *= inv_m;
    } else {
      g.vx[i] = g.vy[i] = g.fx[i] = g.fy[i] = 0.0;
    }
    g.px[i] = g.py[i] = 0.0;
  }
}

void remap_grid_velocity(Grid& g, int row_begin, int row_end) {
  const auto b = static_cast<std::ptrdiff_t>(g.geo.node(0, row_begin));
  const auto e = static_cast<std::ptrdiff_t>(g.geo.node(0, row_end));
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::ptrdiff_t i = b; i < e; ++i) {
    const double m = g.m[i];
    const double inv_m = m > 0.0 ? 1.0 / m : 0.0;
    g.px[i] *= inv_m;
    g.py[i] *= inv_m;
  }
}

}  // namespace mpmshock
