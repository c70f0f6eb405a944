// Spall: material that fails in tension (spall = on). One type per choice, a slot of the model:
//
//   NoFailure  the material holds any tension (the EOS's linear branch in expansion)
//   Spall      a point whose largest principal stress, of sigma = s - P I (q is zero in tension),
//              exceeds the spall strength fails, once and for good: from then on it carries no
//              tension and no deviatoric stress (P = max(P, 0), s = 0), so the material around it
//              separates and voids open. It can be compressed again: it remembers the volume
//              ratio J_f at which it failed, and its equation of state and temperature see the
//              material's own volume, min(J, J_f); expansion beyond J_f is opened space, which must
//              close before the point carries pressure again.
//
// A fixed failure threshold (a "spall cutoff", as in most hydrocodes) rather than a rate-dependent
// damage law (Tuler-Butcher, Cochran-Banner): the threshold is the one number the free-surface
// pullback measures, sigma = rho0 c0 du / 2, so a scene can be checked against the experiment it
// models; the rate dependence of measured spall strengths (1.0-1.6 GPa for aluminium alloys at
// 1e4-1e6 /s) is left to the choice of spall_strength.
#pragma once

#include <algorithm>
#include <cmath>

#include "mpmshock/tensor.hpp"

namespace mpmshock {

// The largest principal value of sigma = s - P I.
inline double max_principal_stress(const Deviator<2>& s, double P) {
  // In plane: mean +- radius of Mohr's circle; out of plane s_zz.
  const double mean = 0.5 * (s.xx + s.yy), half = 0.5 * (s.xx - s.yy);
  return std::max(mean + std::sqrt(half * half + s.xy * s.xy), s.zz()) - P;
}
inline double max_principal_stress(const Deviator<3>& s, double P) {
  // A trace-free symmetric tensor's eigenvalues are 2 sqrt(J2/3) cos(theta - 2 pi k/3) with
  // cos(3 theta) = (3 sqrt(3)/2) J3 / J2^(3/2); the largest has k = 0, theta in [0, pi/3].
  const double J2 = 0.5 * s.norm2();
  if (!(J2 > 0.0)) return -P;
  const double J3 = s.xx * (s.yy * s.zz() - s.yz() * s.yz()) - s.xy * (s.xy * s.zz() - s.yz() * s.zx()) +
                    s.zx() * (s.xy * s.yz() - s.yy * s.zx());
  const double c = std::clamp(1.5 * std::sqrt(3.0) * J3 / (J2 * std::sqrt(J2)), -1.0, 1.0);
  return 2.0 * std::sqrt(J2 / 3.0) * std::cos(std::acos(c) / 3.0) - P;
}

struct NoFailure {
  static constexpr bool active = false;
};

struct Spall {
  static constexpr bool active = true;
  double strength;  // [Pa]

  template <int D>
  bool exceeded(const Deviator<D>& s, double P) const {
    return max_principal_stress(s, P) > strength;
  }
};

}  // namespace mpmshock
