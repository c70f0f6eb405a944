// The linear polynomial equation of state (as LS-DYNA's *EOS_LINEAR_POLYNOMIAL and AUTODYN's
// polynomial), with mu = rho/rho0 - 1 = 1/J - 1 and E the specific internal energy relative to the
// reference state [J/kg]:
//   P = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) rho0 E,
// where in expansion (mu < 0) C2 and C6 are taken as zero, as those codes do. Their E is the energy per
// initial volume, rho0 E here, so their constants are these. Tabulated decks carry it for windows,
// polymers and gases: C4 = C5 = gamma - 1 (the others 0) is the ideal gas P = (gamma - 1) rho E, and
// C1 = rho0 c0^2, C2 = C1 (2 s - 1 - gamma0 / 2), C3 = C1 (s - 1)(3 s - 1 - gamma0), C4 = gamma0 is
// the Mie-Grüneisen law on the linear Us-up Hugoniot to third order in mu
// (tests/laws/test_polynomial.cpp). The sound speed is the isentropic
// c^2 = (dP/drho)_E + (P / rho^2) (dP/dE)_rho in closed form.
//
// Limits, stated rather than hidden: it has no constants of the library's materials (C1 = 0 marks
// none: a scene gives them); its temperature is referenced to its isentrope (temperature.hpp
// tabulates it); J at or below limiting_compression() is refused like the Us-up pole.
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

#include "mpmshock/material.hpp"
#include "mpmshock/pressure_terms.hpp"
#include "mpmshock/rankine_hugoniot.hpp"

namespace mpmshock {

struct MaterialLaw;

// A material's polynomial constants (its polynomial_* keys, src/laws/polynomial.cpp): none by
// default (C1 = 0).
struct PolynomialConstants {
  double c0 = 0.0, c1 = 0.0, c2 = 0.0, c3 = 0.0;  // [Pa]
  double c4 = 0.0, c5 = 0.0, c6 = 0.0;            // dimensionless
  bool present() const { return c1 > 0.0; }
};

class Polynomial : public FromPressureTerms<Polynomial> {
 public:
  using Constants = PolynomialConstants;
  // Its keys and checks (src/laws/polynomial.cpp), the word equation_of_state takes for it, and its
  // temperature's reference: the isentrope (tabulated).
  static MaterialLaw law();
  static constexpr std::string_view kName = "polynomial";
  static constexpr bool kHugoniotReference = false;
  // The reference bulk sound speed, c^2 = (C1 + C0 C4) / rho0, from the constants alone (scene checks).
  static double sound_speed_of(const Material& mat) {
    const Constants& c = mat.law_constants<Constants>();
    return std::sqrt(std::max(0.0, c.c1 + c.c0 * c.c4) / mat.density);
  }

  Polynomial() = default;
  explicit Polynomial(const Material& mat) : rho0_(mat.density), c_(mat.law_constants<Constants>()) {
    J_fit_ = shock_from_rest(*this, mat.fit_particle_velocity).J;
  }

  double rho0() const { return rho0_; }
  // The smallest J admitted: a fivefold compression.
  double limiting_compression() const { return kLimitingCompression; }
  // J of the Hugoniot state at the material's fit_particle_velocity.
  double fit_limit() const { return J_fit_; }
  double reference_sound_speed() const { return std::sqrt(std::max(0.0, c_.c1 + c_.c0 * c_.c4) / rho0_); }

  static constexpr double kLimitingCompression = 0.2;

  // P, (dP/drho)_E and (dP/dE)_rho of a state (pressure_terms.hpp derives the rest).
  PressureTerms terms(double J, double E) const {
    const double mu = 1.0 / J - 1.0;
    const bool compressed = mu >= 0.0;
    const double c2 = compressed ? c_.c2 : 0.0, c6 = compressed ? c_.c6 : 0.0;
    const double energy_factor = c_.c4 + c_.c5 * mu + c6 * mu * mu;
    const double P = c_.c0 + mu * (c_.c1 + mu * (c2 + mu * c_.c3)) + energy_factor * rho0_ * E;
    // d/drho = (1 / rho0) d/dmu.
    const double dP_dmu = c_.c1 + mu * (2.0 * c2 + 3.0 * c_.c3 * mu) + (c_.c5 + 2.0 * c6 * mu) * rho0_ * E;
    return {P, dP_dmu / rho0_, energy_factor * rho0_};
  }

 private:
  double rho0_ = 2700.0;
  Constants c_;
  double J_fit_ = kLimitingCompression;
};

}  // namespace mpmshock
