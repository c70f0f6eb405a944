// Tillotson's equation of state (Tillotson 1962, GA-3216; the form of Melosh 1989, appendix II):
// a metal from its cold solid through compressed, expanded, liquid and vapour states, with
// P(rho, E) in closed form. J = V/V0, eta = rho/rho0 = 1/J, mu = eta - 1, E the specific internal
// energy relative to the reference state [J/kg], omega = E / (E0 eta^2) + 1:
//   compressed (J <= 1) and cold expanded (E <= E_iv):
//     P_c = (a + b / omega) rho E + A mu + B mu^2;
//   hot expanded (J > 1, E >= E_cv), z = J - 1:
//     P_e = a rho E + (b rho E / omega + A mu e^(-beta z)) e^(-alpha z^2),
//     which tends to the ideal gas a rho E as the vapour expands;
//   between (J > 1, E_iv < E < E_cv): P = ((E - E_iv) P_e + (E_cv - E) P_c) / (E_cv - E_iv).
// The sound speed is the isentropic c^2 = (dP/drho)_E + (P / rho^2) (dP/dE)_rho, each branch's
// derivatives in closed form (tests/laws/test_tillotson.cpp checks them against differences).
//
// Limits, stated rather than hidden: the cold expanded branch bounds the tension at A^2 / (4 B)
// where B >= A / 2 (21.75 GPa for aluminium, at mu = -A / (2 B); with a smaller B the bound is A - B,
// at full expansion) and keeps -A + B at full expansion; a state with
// omega <= 0 (E below -E0 eta^2, far colder than 0 K) has no pressure (NaN, a bad state); J at or
// below limiting_compression() is refused like the Us-up pole (Tillotson has no pole).
#pragma once

#include <cmath>
#include <limits>
#include <string_view>

#include "mpmshock/material.hpp"
#include "mpmshock/pressure_terms.hpp"
#include "mpmshock/rankine_hugoniot.hpp"

namespace mpmshock {

struct MaterialLaw;

// A material's Tillotson constants (its tillotson_* keys, src/laws/tillotson.cpp). The defaults are
// aluminium's (Tillotson 1962, as tabulated in Spheral's material library); A = 0 marks a material
// without them (material_library.cpp).
struct TillotsonConstants {
  double a = 0.5;
  double b = 1.63;
  double bulk_modulus = 75.2e9;              // A [Pa]
  double nonlinear_modulus = 65.0e9;         // B [Pa]
  double energy = 5.0e6;                     // E0 [J/kg]
  double incipient_vaporisation = 2.7e6;     // E_iv [J/kg]
  double complete_vaporisation = 14.1e6;     // E_cv [J/kg]
  double alpha = 5.0;
  double beta = 5.0;
  bool present() const { return bulk_modulus > 0.0; }
};

class Tillotson : public FromPressureTerms<Tillotson> {
 public:
  using Constants = TillotsonConstants;
  // Its keys and checks (src/laws/tillotson.cpp), and the word equation_of_state takes for it; its
  // temperature is referenced to its isentrope (Tillotson has no Hugoniot in closed form;
  // temperature.hpp tabulates it).
  static MaterialLaw law();
  static constexpr std::string_view kName = "tillotson";
  static constexpr bool kHugoniotReference = false;
  // The reference bulk sound speed sqrt(A / rho0) from the constants alone (scene checks).
  static double sound_speed_of(const Material& mat) {
    return std::sqrt(mat.law_constants<Constants>().bulk_modulus / mat.density);
  }

  Tillotson() = default;
  explicit Tillotson(const Material& mat) : Tillotson(mat.density, mat.law_constants<Constants>()) {
    J_fit_ = shock_from_rest(*this, mat.fit_particle_velocity).J;
  }
  Tillotson(double rho0, const Constants& c)
      : rho0_(rho0), a_(c.a), b_(c.b), A_(c.bulk_modulus), B_(c.nonlinear_modulus), E0_(c.energy),
        E_iv_(c.incipient_vaporisation), E_cv_(c.complete_vaporisation), alpha_(c.alpha), beta_(c.beta) {}

  double rho0() const { return rho0_; }
  // The smallest J admitted: a fivefold compression (aluminium: 1.3 TPa on the cold branch).
  double limiting_compression() const { return kLimitingCompression; }
  // J of the Hugoniot state at the material's fit_particle_velocity.
  double fit_limit() const { return J_fit_; }
  // The bulk sound speed of the reference state, sqrt(A / rho0).
  double reference_sound_speed() const { return std::sqrt(A_ / rho0_); }

  static constexpr double kLimitingCompression = 0.2;

  // P, (dP/drho)_E and (dP/dE)_rho of a state (pressure_terms.hpp derives the rest).
  PressureTerms terms(double J, double E) const {
    if (J <= 1.0 || E <= E_iv_) return compressed(J, E);
    if (E >= E_cv_) return expanded(J, E);
    const PressureTerms c = compressed(J, E), e = expanded(J, E);
    const double w = (E - E_iv_) / (E_cv_ - E_iv_);
    return {w * e.P + (1.0 - w) * c.P, w * e.dP_drho + (1.0 - w) * c.dP_drho,
            w * e.dP_dE + (1.0 - w) * c.dP_dE + (e.P - c.P) / (E_cv_ - E_iv_)};
  }

 private:
  // omega and the derivative of b rho E / omega along rho at fixed E:
  // d/drho (b rho E / omega) = b E / omega + 2 b E (omega - 1) / omega^2.
  PressureTerms compressed(double J, double E) const {
    const double eta = 1.0 / J, rho = rho0_ * eta, mu = eta - 1.0;
    const double omega = E / (E0_ * eta * eta) + 1.0;
    if (!(omega > 0.0)) return nan_terms();
    const double inv_w = 1.0 / omega;
    return {(a_ + b_ * inv_w) * rho * E + A_ * mu + B_ * mu * mu,
            E * (a_ + b_ * inv_w + 2.0 * b_ * (omega - 1.0) * inv_w * inv_w) + (A_ + 2.0 * B_ * mu) / rho0_,
            rho * (a_ + b_ * inv_w * inv_w)};
  }
  PressureTerms expanded(double J, double E) const {
    const double eta = 1.0 / J, rho = rho0_ * eta, mu = eta - 1.0, z = J - 1.0;
    const double omega = E / (E0_ * eta * eta) + 1.0;
    if (!(omega > 0.0)) return nan_terms();
    const double inv_w = 1.0 / omega;
    const double X = std::exp(-alpha_ * z * z), Y = std::exp(-beta_ * z);
    const double G = b_ * rho * E * inv_w, H = A_ * mu * Y;
    const double dz_drho = -J * J / rho0_;
    const double dG = E * (b_ * inv_w + 2.0 * b_ * (omega - 1.0) * inv_w * inv_w);
    const double dH = A_ * Y * (1.0 / rho0_ - beta_ * mu * dz_drho);
    const double dX = -2.0 * alpha_ * z * dz_drho * X;
    return {a_ * rho * E + (G + H) * X, a_ * E + X * (dG + dH) + (G + H) * dX, rho * (a_ + X * b_ * inv_w * inv_w)};
  }
  static PressureTerms nan_terms() {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }

  // Aluminium's constants (material_library.cpp).
  double rho0_ = 2700.0, a_ = 0.5, b_ = 1.63, A_ = 75.2e9, B_ = 65.0e9, E0_ = 5.0e6, E_iv_ = 2.7e6, E_cv_ = 14.1e6;
  double alpha_ = 5.0, beta_ = 5.0;
  double J_fit_ = kLimitingCompression;
};

}  // namespace mpmshock
