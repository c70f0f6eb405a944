#include "mpmshock/grid.hpp"

#include <algorithm>

namespace mpmshock {

Grid::Grid(const GridGeometry& g)
    : geo(g), m(g.nodes()), px(g.nodes()), py(g.nodes()), fx(g.nodes()), fy(g.nodes()), vx(g.nodes()),
      vy(g.nodes()) {}

void Grid::reset(int row_begin, int row_end) {
  const std::size_t b = geo.node(0, row_begin), e = geo.node(0, row_end);
  for (std::vector<double>* field : {&m, &px, &py, &fx, &fy}) std::fill(field->begin() + b, field->begin() + e, 0.0);
}

}  // namespace mpmshock
