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
  static constexpr bool in_lanes = true;  // its points may be updated four at a time (constitutive.hpp)
};

template <bool BackStress, bool Softening = false>
struct VonMises {
  static constexpr bool has_stress = true;
  static constexpr bool has_back_stress = BackStress;
  static constexpr bool softens = Softening;
  static constexpr bool in_lanes = !Softening;  // softening is computed point by point

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
  // T: a double, or four points' Lanes (number.hpp) without Softening.
  template <class T>
  T yield_radius(const T& eps_p) const {
    if constexpr (Softening) return minimum(hardened_yield(eps_p), constant<T>(softening.yield_max));
    return hardened_yield(eps_p);
  }
  // The hardening modulus at eps_p: none once the yield radius has reached Y_max.
  template <class T>
  T hardening_at(const T& eps_p) const {
    if constexpr (Softening) return hardened_yield(eps_p) >= softening.yield_max ? T{} : constant<T>(plastic_modulus);
    return constant<T>(plastic_modulus);
  }
  // sigma_Y0 + beta H eps_p, the linear hardening law before any cap.
  template <class T>
  T hardened_yield(const T& eps_p) const { return initial_yield + beta * plastic_modulus * eps_p; }

  // Radial return of a trial deviatoric stress onto sqrt(3/2)||s - alpha|| = sigma_Y(eps_p).
  // Updates s, alpha and eps_p in place; returns the effective plastic strain increment
  // d eps_p = (sigma_eq_trial - sigma_Y) / (3 G + H), zero if the trial state is elastic.
  // The yield radius grows by beta H d eps_p; the back stress by (1 - beta) (2/3) H d e_p with
  // d e_p = sqrt(3/2) d eps_p n the plastic strain increment along n = xi/||xi||. With beta = 1
  // alpha stays zero, which is why callers may pass a scratch zero for it.
  // With a softening factor k, G, H and the yield radius are k times theirs. In Lanes, the lanes
  // that do not yield keep s, alpha and eps_p as they were.
  template <int D, class T = double>
  T return_map(Deviator<D, T>& s, Deviator<D, T>& alpha, T& eps_p, const T& k = constant<T>(1.0)) const {
    const Deviator<D, T> xi = s - alpha;
    const T q_trial = equivalent_stress(xi);
    const T f = q_trial - k * yield_radius(eps_p);
    const auto yields = !(f <= 0.0);  // a NaN goes on, as it always has
    if (!any(yields)) return T{};
    // A step that crosses Y_max hardens at H up to its end; the next steps do not harden.
    const T G = k * shear_modulus, H = k * hardening_at(eps_p);
    const T deps_p = yields ? f / (3.0 * G + H) : T{};
    // n = xi / ||xi||, ||xi|| = sqrt(2/3) q_trial; plastic strain increment d e_p = sqrt(3/2) deps_p n.
    const T to_unit = 1.0 / (std::sqrt(2.0 / 3.0) * q_trial);
    const T dgamma = std::sqrt(1.5) * deps_p;  // ||d e_p||
    const Deviator<D, T> n = to_unit * xi;
    s = choose(yields, s - (2.0 * G * dgamma) * n, s);
    alpha = choose(yields, alpha + ((1.0 - beta) * (2.0 / 3.0) * H * dgamma) * n, alpha);
    eps_p = yields ? eps_p + deps_p : eps_p;
    return deps_p;
  }

  // One step of the deviatoric stress by the Jaumann rate s_dot = 2 G D' + (W s - s W): the stress
  // is rotated with the material by the step's rotation R (tensor.hpp, Hughes-Winget), then the
  // elastic increment added, s_trial = R s R^T + 2 G D' dt; the back stress rotates too; then the
  // radial return.
  // Returns the plastic work per unit volume, sigma_Y d eps_p. J and the thermal part of the
  // specific internal energy give the temperature, and P the pressure of the Steinberg-Guinan
  // factor, with Softening only (a double: softening is computed point by point).
  template <int D, class T>
  T update(Deviator<D, T>& s, Deviator<D, T>& alpha, T& eps_p, const StrainRate<D, T>& rate, double dt,
           [[maybe_unused]] const T& J, [[maybe_unused]] const T& E_thermal, [[maybe_unused]] const T& P) const {
    T k = constant<T>(1.0);
    if constexpr (Softening) {
      k = softening.factor(P, thermal.temperature(J, E_thermal), J);
      if (k == 0.0) {  // molten: a fluid
        s = {};
        alpha = {};
        return 0.0;
      }
    }
    const Rotation<D, T> R = spin_rotation(rate, dt);
    s = rotate(s, R) + (dt * 2.0 * k * shear_modulus) * rate.deviator();
    if constexpr (BackStress) alpha = rotate(alpha, R);
    const T deps_p = return_map(s, alpha, eps_p, k);
    return k * yield_radius(eps_p) * deps_p;
  }
};

}  // namespace mpmshock
