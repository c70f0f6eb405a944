// Strength laws: how the deviatoric stress s responds, one type each, chosen once at set-up
// (model.hpp). Physics-notes sections 1 and 2.
//
//   NoStrength      hydrodynamics: s = 0, no deviatoric fields are stored
//   VonMises<false> von Mises plasticity with linear isotropic hardening (hardening_beta = 1)
//   VonMises<true>  mixed isotropic/kinematic hardening (hardening_beta < 1): a back stress alpha
//   VonMises<B, true>  the same with Steinberg-Guinan softening: G and sigma_Y scaled by
//                   f(P, T, J), zero in the melt, sigma_Y capped at Y_max (thermal_softening.hpp)
//
// Every law returns the step's plastic work per unit volume, sigma_Y d eps_p, of which the share
// taylor_quinney becomes heat and the rest is stored as cold work (constitutive.hpp).
//
// The stress rate is the Jaumann rate (objective); the plastic correction is a radial return.
#pragma once

#include <algorithm>
#include <cmath>

#include "mpmshock/material.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/tensor.hpp"
#include "mpmshock/thermal_softening.hpp"

namespace mpmshock {

struct NoStrength {
  static constexpr bool has_stress = false;
  static constexpr bool has_back_stress = false;
};

template <bool BackStress, bool Softening = false>
struct VonMises {
  static constexpr bool has_stress = true;
  static constexpr bool has_back_stress = BackStress;
  static constexpr bool softens = Softening;

  double shear_modulus;    // G
  double plastic_modulus;  // H = E E_tan / (E - E_tan)
  double beta;             // share of hardening that is isotropic
  double initial_yield;    // sigma_Y0

  // With Softening: the temperature model and the softening law.
  HugoniotTemperature thermal;
  ThermalSoftening softening;

  explicit VonMises(const Material& mat)
      : shear_modulus(mat.shear_modulus()), plastic_modulus(mat.plastic_modulus()), beta(mat.hardening_beta),
        initial_yield(mat.yield_stress) {}
  VonMises(const Material& mat, const ThermalSoftening& soft) : VonMises(mat) {
    thermal = HugoniotTemperature(mat);
    thermal.set_melting(soft.melt, soft.latent_heat);
    softening = soft;
  }

  // The yield radius only ever grows by beta H d eps_p, so it is a function of the effective
  // plastic strain and need not be stored. With Softening it stops at Steinberg-Guinan's Y_max.
  double yield_radius(double eps_p) const {
    if constexpr (Softening) return std::min(hardened_yield(eps_p), softening.yield_max);
    return hardened_yield(eps_p);
  }
  // The hardening modulus at eps_p: none once the yield radius has reached Y_max.
  double hardening_at(double eps_p) const {
    if constexpr (Softening)
      if (hardened_yield(eps_p) >= softening.yield_max) return 0.0;
    return plastic_modulus;
  }
  // sigma_Y0 + beta H eps_p, the linear hardening law before any cap.
  double hardened_yield(double eps_p) const { return initial_yield + beta * plastic_modulus * eps_p; }

  // Radial return of a trial deviatoric stress onto sqrt(3/2)||s - alpha|| = sigma_Y(eps_p).
  // Updates s, alpha and eps_p in place; returns the effective plastic strain increment
  // d eps_p = (sigma_eq_trial - sigma_Y) / (3 G + H), zero if the trial state is elastic.
  // The yield radius grows by beta H d eps_p; the back stress by (1 - beta) (2/3) H d e_p with
  // d e_p = sqrt(3/2) d eps_p n the plastic strain increment along n = xi/||xi||. With beta = 1
  // alpha stays zero, which is why callers may pass a scratch zero for it.
  // With a softening factor k, G, H and the yield radius are k times theirs.
  template <int D>
  double return_map(Deviator<D>& s, Deviator<D>& alpha, double& eps_p, double k = 1.0) const {
    const Deviator<D> xi = s - alpha;
    const double q_trial = equivalent_stress(xi);
    const double f = q_trial - k * yield_radius(eps_p);
    if (f <= 0.0) return 0.0;
    // A step that crosses Y_max hardens at H up to its end; the next steps do not harden.
    const double G = k * shear_modulus, H = k * hardening_at(eps_p);
    const double deps_p = f / (3.0 * G + H);
    // n = xi / ||xi||, ||xi|| = sqrt(2/3) q_trial; plastic strain increment d e_p = sqrt(3/2) deps_p n.
    const double to_unit = 1.0 / (std::sqrt(2.0 / 3.0) * q_trial);
    const double dgamma = std::sqrt(1.5) * deps_p;  // ||d e_p||
    const Deviator<D> n = to_unit * xi;
    s = s - (2.0 * G * dgamma) * n;
    alpha = alpha + ((1.0 - beta) * (2.0 / 3.0) * H * dgamma) * n;
    eps_p += deps_p;
    return deps_p;
  }

  // One step of the deviatoric stress by the Jaumann rate s_dot = 2 G D' + (W s - s W): the stress
  // is rotated with the material by the step's rotation R (tensor.hpp, Hughes-Winget), then the
  // elastic increment added, s_trial = R s R^T + 2 G D' dt; the back stress rotates too; then the
  // radial return.
  // Returns the plastic work per unit volume, sigma_Y d eps_p. J and the thermal part of the
  // specific internal energy give the temperature, and P the pressure of the Steinberg-Guinan
  // factor, with Softening only.
  template <int D>
  double update(Deviator<D>& s, Deviator<D>& alpha, double& eps_p, const StrainRate<D>& rate, double dt,
                [[maybe_unused]] double J, [[maybe_unused]] double E_thermal, [[maybe_unused]] double P) const {
    double k = 1.0;
    if constexpr (Softening) {
      k = softening.factor(P, thermal.temperature(J, E_thermal), J);
      if (k == 0.0) {  // molten: a fluid
        s = {};
        alpha = {};
        return 0.0;
      }
    }
    const Rotation<D> R = spin_rotation(rate, dt);
    s = rotate(s, R) + (dt * 2.0 * k * shear_modulus) * rate.deviator();
    if constexpr (BackStress) alpha = rotate(alpha, R);
    const double deps_p = return_map(s, alpha, eps_p, k);
    return k * yield_radius(eps_p) * deps_p;
  }
};

}  // namespace mpmshock
