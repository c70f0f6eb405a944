// Conserved totals of the material points, summed exactly (exact_sum.hpp) so that the numbers do
// not depend on the thread count or on how the points are shared between MPI ranks.
#pragma once

#include "mpmshock/comm.hpp"
#include "mpmshock/exact_sum.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

struct Totals {
  double mass = 0.0;
  double momentum[3] = {0.0, 0.0, 0.0};
  double momentum_magnitude = 0.0;  // sum m |v|: the scale against which momentum is judged
  double kinetic = 0.0;             // sum m v^2 / 2
  double internal = 0.0;            // sum m E
  double total_energy() const { return kinetic + internal; }
};

// The totals of the points on every rank of `comm` (each rank passes its own points).
template <int D>
Totals compute_totals(const Particles<D>& p, const Comm& comm = Comm::world());

}  // namespace mpmshock
