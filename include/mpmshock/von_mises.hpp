// Von Mises plasticity with linear mixed hardening and a Jaumann (objective) stress rate,
// plane strain (physics-notes sections 1 and 2).
//
// Deviators are trace-free 3x3 tensors; in plane strain only xx, yy, xy and zz are non-zero and
// zz = -(xx + yy), so three numbers carry each one.
#pragma once

#include <cmath>

#include "mpmshock/material.hpp"

namespace mpmshock {

struct Deviator {
  double xx = 0.0, yy = 0.0, xy = 0.0;
  double zz() const { return -(xx + yy); }
  // ||a||^2 = a:a over the full 3x3 tensor.
  double norm2() const { return xx * xx + yy * yy + zz() * zz() + 2.0 * xy * xy; }
};

inline Deviator operator+(Deviator a, const Deviator& b) { return {a.xx + b.xx, a.yy + b.yy, a.xy + b.xy}; }
inline Deviator operator-(Deviator a, const Deviator& b) { return {a.xx - b.xx, a.yy - b.yy, a.xy - b.xy}; }
inline Deviator operator*(double k, const Deviator& a) { return {k * a.xx, k * a.yy, k * a.xy}; }

// Velocity gradient L = grad v split into what the stress update needs.
struct StrainRate {
  double xx, yy, xy;  // D = sym(L); D_zz = 0 in plane strain
  double spin;        // W_xy = (L_xy - L_yx)/2, the one independent component of W = skew(L)
  double trace() const { return xx + yy; }
  Deviator deviator() const {
    const double third = trace() / 3.0;
    return {xx - third, yy - third, xy};  // zz = -trD/3, consistent with Deviator::zz()
  }
};

inline StrainRate strain_rate(double Lxx, double Lxy, double Lyx, double Lyy) {
  return {Lxx, Lyy, 0.5 * (Lxy + Lyx), 0.5 * (Lxy - Lyx)};
}

// W a - a W for a deviator a and spin W = [[0, w], [-w, 0]]: the rotation part of the Jaumann rate,
// so that a_dot = a_jaumann + (W a - a W). Stays trace-free, zz untouched.
inline Deviator spin_rate(const Deviator& a, double w) {
  return {2.0 * w * a.xy, -2.0 * w * a.xy, w * (a.yy - a.xx)};
}

// s : D, the deviatoric stress power per unit volume (D_zz = 0 drops the zz term).
inline double stress_power(const Deviator& s, const StrainRate& D) {
  return s.xx * D.xx + s.yy * D.yy + 2.0 * s.xy * D.xy;
}

// Equivalent (von Mises) stress sqrt(3/2) ||a||.
inline double equivalent_stress(const Deviator& a) { return std::sqrt(1.5 * a.norm2()); }

struct VonMises {
  double shear_modulus;    // G
  double plastic_modulus;  // H = E E_tan / (E - E_tan)
  double beta;             // share of hardening that is isotropic
  double initial_yield;    // sigma_Y0

  explicit VonMises(const Material& mat)
      : shear_modulus(mat.shear_modulus()), plastic_modulus(mat.plastic_modulus()), beta(mat.hardening_beta),
        initial_yield(mat.yield_stress) {}

  // The yield radius only ever grows by beta H d eps_p, so it is a function of the effective
  // plastic strain and need not be stored.
  double yield_radius(double eps_p) const { return initial_yield + beta * plastic_modulus * eps_p; }

  // Radial return of a trial deviatoric stress onto sqrt(3/2)||s - alpha|| = sigma_Y(eps_p).
  // Updates s, alpha and eps_p in place; returns the effective plastic strain increment
  // d eps_p = (sigma_eq_trial - sigma_Y) / (3 G + H), zero if the trial state is elastic.
  // The yield radius grows by beta H d eps_p; the back stress by (1 - beta) (2/3) H d e_p with
  // d e_p = sqrt(3/2) d eps_p n the plastic strain increment along n = xi/||xi||. With beta = 1
  // alpha stays zero, which is why callers may pass a scratch zero for it.
  double return_map(Deviator& s, Deviator& alpha, double& eps_p) const {
    const Deviator xi = s - alpha;
    const double q_trial = equivalent_stress(xi);
    const double f = q_trial - yield_radius(eps_p);
    if (f <= 0.0) return 0.0;
    const double G = shear_modulus, H = plastic_modulus;
    const double deps_p = f / (3.0 * G + H);
    // n = xi / ||xi||, ||xi|| = sqrt(2/3) q_trial; plastic strain increment d e_p = sqrt(3/2) deps_p n.
    const double to_unit = 1.0 / (std::sqrt(2.0 / 3.0) * q_trial);
    const double dgamma = std::sqrt(1.5) * deps_p;  // ||d e_p||
    const Deviator n = to_unit * xi;
    s = s - (2.0 * G * dgamma) * n;
    alpha = alpha + ((1.0 - beta) * (2.0 / 3.0) * H * dgamma) * n;
    eps_p += deps_p;
    return deps_p;
  }
};

}  // namespace mpmshock
