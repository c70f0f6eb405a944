#include "mpmshock/grid.hpp"

#include "mpmshock/parallel.hpp"

namespace mpmshock {

template <int D>
Grid<D>::Grid(const GridGeometry<D>& g) : geo(g) {
  for_each_field([n = g.nodes()](auto& field) { field.resize(n); });
}

template <int D>
void Grid<D>::reset(RowRange rows) {
  const auto b = static_cast<std::ptrdiff_t>(geo.row_start(rows.begin));
  const auto e = static_cast<std::ptrdiff_t>(geo.row_start(rows.end));
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::ptrdiff_t i = b; i < e; ++i) {
    m[i] = 0.0;
    mv[i] = Vec<D>{};
    f[i] = Vec<D>{};
  }
}

template struct Grid<2>;
template struct Grid<3>;

}  // namespace mpmshock
