#include "mpmshock/transfer.hpp"

namespace mpmshock {

namespace {

// Calls f(i) for every node i of the given rows, the nodes shared among the threads.
template <int D, class F>
void for_each_node_of_rows(const GridGeometry<D>& geo, RowRange rows, F&& f) {
  const auto b = static_cast<std::ptrdiff_t>(geo.row_start(rows.begin));
  const auto e = static_cast<std::ptrdiff_t>(geo.row_start(rows.end));
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::ptrdiff_t i = b; i < e; ++i) f(static_cast<std::size_t>(i));
}

}  // namespace

template <int D>
void update_grid_momentum(Grid<D>& g, RowRange rows, double dt) {
  for_each_node_of_rows(g.geo, rows, [&](std::size_t i) {
    const double m = g.m[i];
    if (m > 0.0) {
      const double inv_m = 1.0 / m;
      for (int d = 0; d < D; ++d) {
        g.v[i][d] = (g.mv[i][d] + dt * g.f[i][d]) * inv_m;
        g.a[i][d] = g.f[i][d] * inv_m;
      }
    } else {
      g.v[i] = g.a[i] = Vec<D>{};
    }
    g.mv[i] = Vec<D>{};
  });
}

template <int D>
void remap_grid_velocity(Grid<D>& g, RowRange rows) {
  for_each_node_of_rows(g.geo, rows, [&](std::size_t i) {
    const double m = g.m[i];
    const double inv_m = m > 0.0 ? 1.0 / m : 0.0;
    for (int d = 0; d < D; ++d) g.v_remap[i][d] = g.mv[i][d] * inv_m;
  });
}

template <int D>
void sum_step_velocities(Grid<D>& g, RowRange rows, const std::vector<Vec<D>>& u, double dt) {
  for_each_node_of_rows(g.geo, rows, [&](std::size_t i) {
    for (int d = 0; d < D; ++d) g.v_sum[i][d] = g.v[i][d] - dt * g.a[i][d] + u[i][d];
  });
}

template void update_grid_momentum<2>(Grid<2>&, RowRange, double);
template void update_grid_momentum<3>(Grid<3>&, RowRange, double);
template void remap_grid_velocity<2>(Grid<2>&, RowRange);
template void remap_grid_velocity<3>(Grid<3>&, RowRange);
template void sum_step_velocities<2>(Grid<2>&, RowRange, const std::vector<Vec<2>>&, double);
template void sum_step_velocities<3>(Grid<3>&, RowRange, const std::vector<Vec<3>>&, double);

}  // namespace mpmshock
