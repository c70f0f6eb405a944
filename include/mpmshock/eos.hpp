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
      : rho0_(mat.density), c0_(mat.sound_speed), s_(mat.hugoniot_slope), gamma0_(mat.gruneisen_gamma),
        K0_(mat.density * mat.sound_speed * mat.sound_speed) {}

  double rho0() const { return rho0_; }
  double c0() const { return c0_; }
  double slope() const { return s_; }
  double gamma0() const { return gamma0_; }

  // Smallest J the Us-up Hugoniot reaches: P_H diverges at eta = 1/s.
  double limiting_compression() const { return 1.0 - 1.0 / s_; }

  // P_H = rho0 c0^2 eta / (1 - s eta)^2 in compression; rho0 c0^2 eta in tension (errata row 3).
  double hugoniot_pressure(double J) const {
    const double eta = 1.0 - J;
    if (eta <= 0.0) return K0_ * eta;
    const double d = 1.0 - s_ * eta;
    return K0_ * eta / (d * d);
  }

  // dP_H/deta, for the sound speed.
  double hugoniot_pressure_slope(double J) const {
    const double eta = 1.0 - J;
    if (eta <= 0.0) return K0_;
    const double d = 1.0 - s_ * eta;
    return K0_ * (1.0 + s_ * eta) / (d * d * d);
  }

  // E_H = P_H (V0 - V) / 2 per unit mass: eta P_H / (2 rho0).
  double hugoniot_energy(double J) const { return 0.5 * hugoniot_pressure(J) * (1.0 - J) / rho0_; }

  // (dP/dE)_V = gamma(V)/V = gamma0 rho0, constant because gamma*rho is.
  double gamma_rho() const { return gamma0_ * rho0_; }

  // P = P_H(V) + (gamma/V) (E - E_H(V)).
  double pressure(double J, double E) const {
    const double P_H = hugoniot_pressure(J);
    return P_H + gamma_rho() * (E - 0.5 * P_H * (1.0 - J) / rho0_);
  }

  // Pressure and squared bulk sound speed of a state together, sharing the Hugoniot terms (one
  // division instead of four): the constitutive update needs both every step.
  struct State {
    double pressure, sound_speed_squared;
  };
  State state(double J, double E) const {
    const double eta = 1.0 - J;
    double P_H, slope;
    if (eta <= 0.0) {
      P_H = K0_ * eta;
      slope = K0_;
    } else {
      const double inv_d = 1.0 / (1.0 - s_ * eta);
      P_H = K0_ * eta * inv_d * inv_d;
      slope = K0_ * (1.0 + s_ * eta) * inv_d * inv_d * inv_d;
    }
    const double P = P_H + gamma_rho() * (E - 0.5 * P_H * eta / rho0_);
    const double c2 = (J * J / rho0_) * (slope * (1.0 - 0.5 * gamma0_ * eta) - 0.5 * gamma0_ * P_H + gamma0_ * P);
    return {P, c2};
  }

  // Isentropic bulk sound speed squared, c^2 = V^2 [ -(dP/dV)_E + P (dP/dE)_V ], written in eta:
  // c^2 = (J^2/rho0) [ P_H' (1 - gamma0 eta / 2) - gamma0 P_H / 2 + gamma0 P ].
  // Can turn negative in strong tension; callers use it only for time steps and viscosity.
  double sound_speed_squared(double J, double P) const {
    const double eta = 1.0 - J;
    const double c2 = (J * J / rho0_) *
                      (hugoniot_pressure_slope(J) * (1.0 - 0.5 * gamma0_ * eta) -
                       0.5 * gamma0_ * hugoniot_pressure(J) + gamma0_ * P);
    return c2;
  }

 private:
  double rho0_ = 2700.0, c0_ = 5350.0, s_ = 1.34, gamma0_ = 1.96, K0_ = 2700.0 * 5350.0 * 5350.0;
};

}  // namespace mpmshock
