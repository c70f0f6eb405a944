// Johnson-Cook strength (strength_model = johnson_cook): von Mises plasticity whose flow stress
// depends on plastic strain, strain rate and temperature (Johnson and Cook, 7th Int. Symp. on
// Ballistics, 1983):
//
//   sigma_Y = (A + B eps_p^n) (1 + C ln(rate*)) (1 - T*^m),   rate* = max(rate / (1 /s), 1),
//   T* = (T - T_r) / (T_m - T_r) in [0, 1];  at T >= T_m the material is molten (s = 0).
//
// `rate` is the equivalent strain rate of the step, sqrt(2/3 D':D'), and T the energy model's
// temperature at the step's new volume and energy (its work added, before its own plastic heat);
// both are held over the step's return map. The shear
// modulus is the material's constant G. The return map solves the consistency condition
//   q_trial - 3 G d eps_p = sigma_Y(eps_p + d eps_p)
// to round-off by Newton's method kept inside the bracket [0, (q_trial - sigma_Y(eps_p)) / 3G]
// (the hardening slope B n eps_p^(n-1) is unbounded at eps_p = 0 for n < 1, so a single linearised
// step would not do). Isotropic hardening only (no back stress). Returns, as every strength law,
// the step's plastic work per unit volume, sigma_Y d eps_p.
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

#include "mpmshock/material.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/tensor.hpp"

namespace mpmshock {

struct MaterialLaw;

// A material's Johnson-Cook constants (its jc_* keys, src/laws/johnson_cook.cpp). The defaults are
// 6061-T6's as commonly tabulated after Johnson and Holmquist (1989); A = 0 marks a material without
// them (material_library.cpp).
struct JohnsonCookConstants {
  double yield_stress = 324e6;     // A [Pa]
  double hardening = 114e6;        // B [Pa]
  double hardening_exponent = 0.42;  // n
  double rate_coefficient = 0.002;   // C, per e-fold of the equivalent strain rate above 1 /s
  double thermal_exponent = 1.34;    // m
  double melt_temperature = 925.0;   // T_m [K]
  double room_temperature = 298.0;   // T_r [K], where T* = 0
  bool present() const { return yield_stress > 0.0; }
};

struct JohnsonCook {
  using Constants = JohnsonCookConstants;
  // Its keys, checks and --check lines (src/laws/johnson_cook.cpp), and the word strength_model
  // takes for it.
  static MaterialLaw law();
  static constexpr std::string_view kName = "johnson_cook";
  static constexpr bool has_stress = true;
  static constexpr bool has_back_stress = false;

  double shear_modulus;  // G
  double A, B, n, C, m;  // the Johnson-Cook constants
  double T_m, T_r;       // melt and room temperature [K]
  HugoniotTemperature thermal;

  explicit JohnsonCook(const Material& mat) : JohnsonCook(mat, mat.law_constants<Constants>()) {}
  JohnsonCook(const Material& mat, const Constants& c)
      : shear_modulus(mat.shear_modulus()), A(c.yield_stress), B(c.hardening), n(c.hardening_exponent),
        C(c.rate_coefficient), m(c.thermal_exponent), T_m(c.melt_temperature), T_r(c.room_temperature), thermal(mat) {}

  // The rate and temperature factors, (1 + C ln rate*) and (1 - T*^m); the second 0 in the melt.
  double rate_factor(double rate) const { return 1.0 + C * std::log(std::max(rate, 1.0)); }
  double thermal_factor(double T) const {
    if (T >= T_m) return 0.0;
    const double T_star = std::max(0.0, (T - T_r) / (T_m - T_r));
    return 1.0 - std::pow(T_star, m);
  }
  // The strain-hardening part A + B eps_p^n and its slope B n eps_p^(n-1).
  double hardened(double eps_p) const { return A + B * std::pow(eps_p, n); }
  double hardening_slope(double eps_p) const { return B * n * std::pow(eps_p, n - 1.0); }

  // The flow stress at a plastic strain, equivalent strain rate [1/s] and temperature [K].
  double flow_stress(double eps_p, double rate, double T) const {
    return hardened(eps_p) * rate_factor(rate) * thermal_factor(T);
  }

  // Radial return of a trial deviator onto sqrt(3/2)||s|| = sigma_Y(eps_p + d eps_p) with the
  // factor k = (1 + C ln rate*)(1 - T*^m) of the step. Updates s and eps_p; returns d eps_p.
  template <int D>
  double return_map(Deviator<D>& s, double& eps_p, double k) const {
    const double q_trial = equivalent_stress(s);
    const double f = q_trial - k * hardened(eps_p);
    if (f <= 0.0) return 0.0;
    const double G3 = 3.0 * shear_modulus;
    // g(x) = q_trial - 3 G x - k (A + B (eps_p + x)^n) falls from f > 0 at x = 0 to <= 0 at f / 3G.
    // Each pass at least halves the bracket, so 60 passes reach its round-off from any start.
    double lo = 0.0, hi = f / G3, x = hi;
    for (int it = 0; it < 60; ++it) {
      const double g = q_trial - G3 * x - k * hardened(eps_p + x);
      if (g > 0.0) lo = x;
      else hi = x;
      if (std::abs(g) <= 1e-13 * q_trial || hi - lo <= 1e-15 * hi) break;
      const double newton = x + g / (G3 + k * hardening_slope(eps_p + x));
      x = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    }
    const double deps_p = x;
    // The deviator shrinks radially to the new yield radius.
    s = ((q_trial - G3 * deps_p) / q_trial) * s;
    eps_p += deps_p;
    return deps_p;
  }

  // One step: the Jaumann rotation and elastic trial increment s_trial = R s R^T + 2 G D' dt, then
  // the return map at the step's rate and the temperature of J and the thermal part of the specific
  // internal energy (update_point passes the new ones). alpha and P are unused (no back stress, no
  // pressure term).
  template <int D>
  double update(Deviator<D>& s, [[maybe_unused]] Deviator<D>& alpha, double& eps_p, const StrainRate<D>& rate,
                double dt, double J, double E_thermal, [[maybe_unused]] double P) const {
    const double k_T = thermal_factor(thermal.temperature(J, E_thermal));
    if (k_T == 0.0) {  // molten: a fluid
      s = {};
      return 0.0;
    }
    const Deviator<D> d = rate.deviator();
    const double equivalent_rate = std::sqrt((2.0 / 3.0) * d.norm2());
    const double k = k_T * rate_factor(equivalent_rate);
    s = rotate(s, spin_rotation(rate, dt)) + (dt * 2.0 * shear_modulus) * d;
    const double deps_p = return_map(s, eps_p, k);
    return k * hardened(eps_p) * deps_p;
  }
};

}  // namespace mpmshock
