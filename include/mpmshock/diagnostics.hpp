// Conserved totals of the material points, summed in a fixed order so that the numbers do not
// depend on the thread count.
#pragma once

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

template <int D>
Totals compute_totals(const Particles<D>& p);

}  // namespace mpmshock
