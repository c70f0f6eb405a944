#include "mpmshock/grid.hpp"

#include <cstddef>

#include "mpmshock/parallel.hpp"

namespace mpmshock {

Grid::Grid(const GridGeometry& g)
    : geo(g), m(g.nodes()), px(g.nodes()), py(g.nodes()), fx(g.nodes()), fy(g.nodes()), vx(g.nodes()),
      vy(g.nodes()) {}

void Grid::reset(int row_begin, int row_end) {
  const auto b = static_cast<std::ptrdiff_t>(geo.node(0, row_begin));
  const auto e = static_cast<std::ptrdiff_t>(geo.node(0, row_end));
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::ptrdiff_t i = b; i < e; ++i) m[i] = px[i] = py[i] = fx[i] = fy[i] = 0.0;
}

}  // namespace mpmshock
