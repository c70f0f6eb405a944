// The strips of a grid and the strip rank 0's slab must reach: shared by the integrator
// (simulation.cpp) and its slabs (slabs.cpp).
#pragma once

#include <cmath>

#include "mpmshock/grid.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {

// The strips StripBins cuts a grid into.
template <int D>
int strip_count(const GridGeometry<D>& g) {
  return (g.ny - 1) / StripBins::kRowsPerStrip + 1;
}

// The strip rank 0's slab must reach: the symmetry plane folds the rows within a stencil of y = 0
// onto each other on rank 0, which must own them all, not share them.
template <int D>
int first_strip_end_needed(const GridGeometry<D>& whole, bool symmetry_plane, int support) {
  if (!symmetry_plane) return 0;
  const int plane_row = static_cast<int>(std::lround(-whole.y_min * whole.inv_h));
  return (plane_row + support) / StripBins::kRowsPerStrip + 2;
}

}  // namespace mpmshock
