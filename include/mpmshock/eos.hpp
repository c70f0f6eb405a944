// Mie-Grüneisen equation of state referenced to the linear Us-up Hugoniot
// (physics-notes section 2), with gamma*rho constant.
//
// State variables: J = V/V0 (specific volume over reference specific volume; for a material
// point J = det F) and E, specific internal energy [J/kg] relative to the reference state.
// eta = 1 - J is the compression.
#pragma once

#include <cmath>

#include "mpmshock/material.hpp"

namespace mpmshock {

class MieGruneisen {
 public:
  MieGruneisen() = default;
  explicit MieGruneisen(const Material& mat)
      : rho0_(mat.density), s_(mat.hugoniot_slope), gamma0_(mat.gruneisen_gamma),
        K0_(mat.density * mat.sound_speed * mat.sound_speed) {}

  double rho0() const { return rho0_; }

  // Smallest J the Us-up Hugoniot reaches: P_H diverges at eta = 1/s.
  double limiting_compression() const { return 1.0 - 1.0 / s_; }

  // P_H = rho0 c0^2 eta / (1 - s eta)^2 in compression; rho0 c0^2 eta in tension (errata row 3).
  double hugoniot_pressure(double J) const { return hugoniot(J).pressure; }

  // dP_H/deta, for the sound speed.
  double hugoniot_pressure_slope(double J) const { return hugoniot(J).slope; }

  // E_H = P_H (V0 - V) / 2 per unit mass: eta P_H / (2 rho0).
  double hugoniot_energy(double J) const { return 0.5 * hugoniot_pressure(J) * (1.0 - J) / rho0_; }

  // (dP/dE)_V = gamma(V)/V = gamma0 rho0, constant because gamma*rho is.
  double gamma_rho() const { return gamma0_ * rho0_; }

  // Pressure and squared bulk sound speed of a state, sharing the Hugoniot terms (one division):
  // the constitutive update needs both every step.
  struct State {
    double pressure, sound_speed_squared;
  };
  State state(double J, double E) const {
    const Hugoniot h = hugoniot(J);
    const double P = mie_gruneisen(h, J, E);
    return {P, bulk_sound_speed_squared(h, J, P)};
  }

  // P = P_H(V) + (gamma/V) (E - E_H(V)).
  double pressure(double J, double E) const { return mie_gruneisen(hugoniot(J), J, E); }

  // Isentropic bulk sound speed squared, c^2 = V^2 [ -(dP/dV)_E + P (dP/dE)_V ], written in eta:
  // c^2 = (J^2/rho0) [ P_H' (1 - gamma0 eta / 2) - gamma0 P_H / 2 + gamma0 P ].
  // Can turn negative in strong tension; callers use it only for time steps and viscosity.
  double sound_speed_squared(double J, double P) const { return bulk_sound_speed_squared(hugoniot(J), J, P); }

 private:
  struct Hugoniot {
    double pressure, slope;  // P_H and dP_H/deta
  };
  Hugoniot hugoniot(double J) const {
    const double eta = 1.0 - J;
    if (eta <= 0.0) return {K0_ * eta, K0_};
    const double inv_d = 1.0 / (1.0 - s_ * eta);
    return {K0_ * eta * inv_d * inv_d, K0_ * (1.0 + s_ * eta) * inv_d * inv_d * inv_d};
  }
  double mie_gruneisen(const Hugoniot& h, double J, double E) const {
    return h.pressure + gamma_rho() * (E - 0.5 * h.pressure * (1.0 - J) / rho0_);
  }
  double bulk_sound_speed_squared(const Hugoniot& h, double J, double P) const {
    const double eta = 1.0 - J;
    return (J * J / rho0_) * (h.slope * (1.0 - 0.5 * gamma0_ * eta) - 0.5 * gamma0_ * h.pressure + gamma0_ * P);
  }

  double rho0_ = 2700.0, s_ = 1.34, gamma0_ = 1.96, K0_ = 2700.0 * 5350.0 * 5350.0;
};

}  // namespace mpmshock
