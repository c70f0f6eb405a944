// Mie-Grüneisen equation of state referenced to the linear Us-up Hugoniot in compression
// (physics-notes section 2) and to a bounded cold curve in expansion, with gamma*rho constant:
// P = P_r(J) + gamma0 rho0 (E - E_r(J)).
//
// State variables: J = V/V0 (specific volume over reference specific volume; for a material
// point J = det F) and E, specific internal energy [J/kg] relative to the reference state.
// eta = 1 - J is the compression.
//
// Compression (J < 1): P_r = P_H = rho0 c0^2 eta / (1 - s eta)^2, E_r = E_H = P_H eta / (2 rho0).
// The linear Us-up line is a fit to data up to some particle velocity (fit_particle_velocity): a
// point compressed past that Hugoniot state, J < fit_limit(), is outside what the fit knows
// (the runs count such points: summary.json "beyond_eos_fit"). Past limiting_compression(), 2 % of
// the way from the pole eta = 1/s toward J = 1 (for aluminium J = 0.269, P_H = 1.2e5 GPa), the
// state is refused (a bad state): the temperature is tabulated down to there, not to the pole
// where it diverges, so every admitted state has a finite temperature.
//
// Expansion (J > 1): the universal binding-energy relation of Rose, Smith, Guinea and Ferrante
// (1984) on the Wigner-Seitz radius r = r0 J^(1/3), a = (r - r0)/l:
//   E_r = E_coh [1 - (1 + a) e^(-a)],  P_r = -rho0 dE_r/dJ = -rho0 c0^2 x0 a e^(-a) J^(-2/3),
//   a = 3 (J^(1/3) - 1) / x0,  x0 = sqrt(E_coh) / c0,
// with l fixed by the bulk modulus: P_r = -rho0 c0^2 (J - 1) + O((J - 1)^2), the slope of the
// compression branch at J = 1. The tension is bounded (for aluminium, E_coh = 12.1 MJ/kg: at most
// 13.2 GPa, at J = 1.55) and returns to zero as the material expands toward its cohesive energy;
// the linear branch P = rho0 c0^2 (1 - J) it replaces gave -49 GPa at J = 1.6 and more beyond.
// Past the tension's peak the bulk modulus (dP/dJ at fixed E) is negative: the material cavitates
// (mechanically unstable), as real metals do well before it (spall = on models that).
#pragma once

#include <cmath>
#include <string_view>
#include <type_traits>

#include "mpmshock/material.hpp"
#include "mpmshock/number.hpp"

namespace mpmshock {

struct MaterialLaw;

class MieGruneisen {
 public:
  // The word equation_of_state takes for it, and whether its temperature's reference curve is its
  // Hugoniot in closed form (temperature.hpp; false: the isentrope, tabulated).
  static MaterialLaw law();  // its keys and checks (src/laws/mie_gruneisen.cpp)
  static constexpr std::string_view kName = "mie_gruneisen";
  static constexpr bool kHugoniotReference = true;
  static constexpr bool in_lanes = true;  // its points may be updated four at a time (constitutive.hpp)
  // The reference bulk sound speed from the constants alone (scene checks, before they are checked).
  static double sound_speed_of(const Material& mat) { return mat.sound_speed; }

  MieGruneisen() = default;
  explicit MieGruneisen(const Material& mat)
      : rho0_(mat.density), c0_(mat.sound_speed), s_(mat.hugoniot_slope), gamma0_(mat.gruneisen_gamma),
        K0_(mat.density * mat.sound_speed * mat.sound_speed), E_coh_(mat.cohesive_energy),
        x0_(std::sqrt(mat.cohesive_energy) / mat.sound_speed), rose_(mat.bound_expansion),
        J_fit_(1.0 - mat.fit_particle_velocity / (mat.sound_speed + mat.hugoniot_slope * mat.fit_particle_velocity)) {}

  double rho0() const { return rho0_; }

  // The Us-up Hugoniot's pole, J = 1 - 1/s, where P_H and T_H diverge.
  double pole() const { return 1.0 - 1.0 / s_; }
  // The smallest J admitted: kPoleMargin of the way from the pole toward J = 1.
  static constexpr double kPoleMargin = 0.02;
  double limiting_compression() const { return pole() + kPoleMargin * (1.0 - pole()); }
  // J of the Hugoniot state at the fit's largest particle velocity u: 1 - u / (c0 + s u).
  double fit_limit() const { return J_fit_; }

  // The reference pressure P_r: the Hugoniot's in compression, Rose's cold curve in expansion.
  double hugoniot_pressure(double J) const { return hugoniot(J).pressure; }

  // dP_r/deta, for the sound speed.
  double hugoniot_pressure_slope(double J) const { return hugoniot(J).slope; }

  // The reference energy E_r: E_H = eta P_H / (2 rho0) in compression, Rose's in expansion.
  template <class T>
  T hugoniot_energy(const T& J) const { return hugoniot(J).energy; }

  // (dP/dE)_V = gamma(V)/V = gamma0 rho0, constant because gamma*rho is.
  double gamma_rho() const { return gamma0_ * rho0_; }

  // Pressure and squared bulk sound speed of a state, sharing the Hugoniot terms (one division):
  // the constitutive update needs both every step. T: a double, or four points' Lanes (number.hpp).
  template <class T>
  struct StateOf {
    T pressure, sound_speed_squared;
  };
  using State = StateOf<double>;
  template <class T>
  [[gnu::always_inline]] StateOf<T> state(const T& J, const T& E) const {
    const HugoniotOf<T> h = hugoniot(J);
    const T P = mie_gruneisen(h, J, E);
    return {P, bulk_sound_speed_squared(h, J, P)};
  }

  // P = P_H(V) + (gamma/V) (E - E_H(V)).
  double pressure(double J, double E) const { return mie_gruneisen(hugoniot(J), J, E); }

  // Isentropic bulk sound speed squared, c^2 = V^2 [ -(dP/dV)_E + P (dP/dE)_V ] =
  // (J^2/rho0) [ P_r' + gamma0 rho0 dE_r/deta + gamma0 P ], P_r' = dP_r/deta: on the Hugoniot
  // (J^2/rho0) [ P_H' (1 - gamma0 eta / 2) - gamma0 P_H / 2 + gamma0 P ], on the cold curve
  // (dE_r/deta = P_r/rho0) (J^2/rho0) [ P_r' - gamma0 P_r + gamma0 P ].
  // Negative past the cold curve's peak tension; callers use it only for time steps and viscosity.
  double sound_speed_squared(double J, double P) const { return bulk_sound_speed_squared(hugoniot(J), J, P); }
  // The same, in the form every equation of state offers (Tillotson's needs E).
  double sound_speed_squared(double J, double /*E*/, double P) const { return sound_speed_squared(J, P); }
  // The bulk sound speed of the reference state, c0.
  double reference_sound_speed() const { return c0_; }

 private:
  template <class T>
  struct HugoniotOf {
    T pressure, slope, energy;  // P_r, dP_r/deta, E_r
    T stiffness;                // P_r' + gamma0 rho0 dE_r/deta, the sound speed's bracket less gamma0 P
  };
  using Hugoniot = HugoniotOf<double>;
  // In Lanes the compressed branch is computed for every lane and the expanded one, where a lane
  // expands, chosen for it; Rose's curve (a cube root and an exponential) point by point.
  template <class T>
  HugoniotOf<T> hugoniot(const T& J) const {
    const T eta = 1.0 - J;
    if constexpr (std::is_same_v<T, double>) {
      if (eta < 0.0) return rose_ ? cold_expansion(J) : linear_expansion(eta);
      return compressed(eta);
    } else {
      HugoniotOf<T> h = compressed(eta);
      const auto expanded = eta < 0.0;
      if (!any(expanded)) return h;
      if (rose_) {
        for (int l = 0; l < 4; ++l)
          if (eta[l] < 0.0) {
            const Hugoniot c = cold_expansion(J[l]);
            h.pressure[l] = c.pressure;
            h.slope[l] = c.slope;
            h.energy[l] = c.energy;
            h.stiffness[l] = c.stiffness;
          }
        return h;
      }
      const HugoniotOf<T> e = linear_expansion(eta);
      return {expanded ? e.pressure : h.pressure, expanded ? e.slope : h.slope, expanded ? e.energy : h.energy,
              expanded ? e.stiffness : h.stiffness};
    }
  }
  // The Us-up Hugoniot (eta >= 0).
  template <class T>
  HugoniotOf<T> compressed(const T& eta) const {
    const T inv_d = 1.0 / (1.0 - s_ * eta);
    const T P = K0_ * eta * inv_d * inv_d, slope = K0_ * (1.0 + s_ * eta) * inv_d * inv_d * inv_d;
    return {P, slope, 0.5 * P * eta / rho0_, slope * (1.0 - 0.5 * gamma0_ * eta) - 0.5 * gamma0_ * P};
  }
  // The linear expanded branch (errata row 3).
  template <class T>
  HugoniotOf<T> linear_expansion(const T& eta) const {
    const T P = K0_ * eta;
    return {P, constant<T>(K0_), 0.5 * P * eta / rho0_, K0_ * (1.0 - 0.5 * gamma0_ * eta) - 0.5 * gamma0_ * P};
  }
  // Rose's universal binding curve (see the top of the file).
  Hugoniot cold_expansion(double J) const {
    const double cbrt_J = std::cbrt(J), a = 3.0 * (cbrt_J - 1.0) / x0_, decay = std::exp(-a);
    const double inv_J23 = 1.0 / (cbrt_J * cbrt_J);
    const double P = -K0_ * x0_ * a * decay * inv_J23;
    // dP/deta = -dP/dJ = K0 e^(-a) [ (1 - a) J^(-4/3) - (2/3) x0 a J^(-5/3) ]
    const double slope = K0_ * decay * inv_J23 * inv_J23 * ((1.0 - a) - (2.0 / 3.0) * x0_ * a / cbrt_J);
    const double E = E_coh_ * (1.0 - (1.0 + a) * decay);
    return {P, slope, E, slope - gamma0_ * P};
  }
  template <class T>
  T mie_gruneisen(const HugoniotOf<T>& h, const T&, const T& E) const { return h.pressure + gamma_rho() * (E - h.energy); }
  template <class T>
  T bulk_sound_speed_squared(const HugoniotOf<T>& h, const T& J, const T& P) const {
    return (J * J / rho0_) * (h.stiffness + gamma0_ * P);
  }

  double rho0_ = 2700.0, c0_ = 5350.0, s_ = 1.34, gamma0_ = 1.96, K0_ = 2700.0 * 5350.0 * 5350.0;
  double E_coh_ = 12.1e6, x0_ = std::sqrt(12.1e6) / 5350.0;
  bool rose_ = false;
  double J_fit_ = 1.0 - 6000.0 / (5350.0 + 1.34 * 6000.0);
};

}  // namespace mpmshock
