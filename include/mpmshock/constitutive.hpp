// The constitutive update of every material point from its velocity gradient L and the work the
// step's nodal forces did on it (see velocity_gradient_work_and_move): internal energy E += work
// (compression, plastic and viscous work alike, exactly what the kinetic energy lost);
// F <- (I + dt L) F; deviatoric stress by the Jaumann rate and radial return (plasticity);
// Mie-Grüneisen pressure from the new volume and energy; artificial viscosity q (compression only).
#pragma once

#include <cstddef>

#include "mpmshock/model.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

// Which strength model runs, resolved at setup: none (hydrodynamic), von Mises with isotropic
// hardening only (hardening_beta = 1: no back stress to store), or mixed hardening.
enum class Strength { none, isotropic, mixed };

struct PointState {
  // In: the velocity gradient and the work of the step's forces [J/kg]. In/out: everything else.
  double Lxx, Lxy, Lyx, Lyy;
  double work;
  double Fxx, Fxy, Fyx, Fyy;
  double E, P, q;
  Deviator s, alpha;
  double eps_p;
};

// One point, one step. Pure and grid-free, so tests can drive it directly.
// Returns the point's signal speed (for the next time step), or a negative number if the new
// state is not physical (J <= the EOS limit, or a non-finite result).
template <Strength S, bool Viscous>
double update_point(PointState& st, const Model& model, double dt);

struct StressUpdateResult {
  double max_signal = 0.0;           // fastest |v| + sound (+ viscous) speed, for the next dt
  std::size_t first_bad = ~std::size_t{0};  // lowest index of a point in a bad state, if any
};

using StressUpdate = StressUpdateResult (*)(Particles&, const Model&, double dt);

// The update for a set of effects, chosen once at setup.
StressUpdate select_stress_update(Strength strength, bool artificial_viscosity);

// The strength model a scene asks for.
Strength strength_of(const Scene& scene);

// The signal speed of a point in its current state (|v| + longitudinal sound speed), for the
// first time step.
double initial_signal_speed(const Particles& p, const Model& model);

}  // namespace mpmshock
