// Thermal softening and melting (thermal_softening = on): Steinberg-Guinan's factor on the shear
// modulus and the yield stress (Steinberg, Cochran and Guinan, J. Appl. Phys. 51, 1498, 1980),
//
//   f(P, T, J) = 1 + A P eta^(-1/3) - B (T - T_r)   for T below the melt temperature T_m(J), else 0
//   T_m(J)     = T_m0 exp(2 a (1 - J)) J^(-2 (gamma0 - a - 1/3))   (Lindemann's law)
//
// with eta = rho / rho0 = 1/J, T_r = 300 K, B = 1 / (T_s - T_r) (T_s: where the thermal term alone
// would reach zero) and A = 1 / P_s (pressure_hardening_scale); f is never below 0. The
// work-hardened yield stress is capped at Y_max (yield_stress_max) before f scales it, as in
// Steinberg-Guinan. The parameters are each body's material's (material.hpp); the defaults, the
// library's aluminium, are 6061-T6's in Steinberg's table (LLNL UCRL-MA-106439, 1996): A = 6.52 /Mbar
// (P_s = 15.34 GPa), B = 6.16e-4 /K (T_s = 1923 K), Y_max = 0.68 GPa, T_m0 = 1220 K, a = 1.5 (gamma0
// is the material's gruneisen_gamma, 1.96 against their 1.97); the initial yield and the hardening
// stay the paper's. Copper and LiF take theirs from the same table (material_library.cpp). Melting takes the latent heat
// L (latent_heat) at T_m before the temperature rises further (temperature.hpp). The pressure is
// the point's pressure at the start of the step (the update is explicit).
#pragma once

#include <algorithm>
#include <cmath>

namespace mpmshock {

struct MeltCurve {
  double T_m0 = 1220.0, a = 1.5, gamma0 = 1.96;
  double at(double J) const { return T_m0 * std::exp(2.0 * a * (1.0 - J)) * std::pow(J, -2.0 * (gamma0 - a - 1.0 / 3.0)); }
};

struct ThermalSoftening {
  MeltCurve melt;
  double T_r = 300.0, T_s = 1923.0;
  double pressure_hardening = 1.0 / 15.337e9;                      // A = 1 / P_s [1/Pa]
  double yield_max = 0.68e9;                                       // Y_max [Pa]
  double latent_heat = 397e3;                                      // L [J/kg], taken at T_m
  // The factor on G and sigma_Y at pressure P, temperature T and volume ratio J.
  double factor(double P, double T, double J) const {
    if (T >= melt.at(J)) return 0.0;
    return std::max(0.0, 1.0 + pressure_hardening * P * std::cbrt(J) - (T - T_r) / (T_s - T_r));
  }
};

}  // namespace mpmshock
