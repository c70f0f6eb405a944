// Spall: material that fails in tension (spall = on). One type per choice, a slot of the model:
//
//   NoFailure  the material holds any tension (the EOS's linear branch in expansion)
//   Spall      a point in tension whose neighbourhood's mean largest principal stress, of
//              sigma = s - P I (q is zero in tension), reaches the spall strength (spall_criterion =
//              neighbourhood, spall_neighbourhood.hpp; or its own reaches spall_point_ceiling times
//              the strength), or whose own does (spall_criterion = point), starts to open: from then
//              on it carries no deviatoric
//              stress, and its tension is held at the strength (P >= -strength) while its own
//              material keeps the volume ratio J_f it opened at and the space around it grows (a
//              void fraction f = 1 - J_f / J). Its damage D = max over time of f / f_c rises from 0
//              to 1; at D = 1 (f reaches spall_void_fraction, f_c) it has separated, for good: no
//              tension at all (P >= 0). It can be compressed again at any stage: its equation of
//              state and temperature see the material's own volume, min(J, J_f), so the opened
//              space must close before it carries pressure again.
//
// A rate-independent tension cap ("pressure cutoff") followed by separation at a critical void
// fraction, rather than a rate-dependent damage law (Tuler-Butcher, Cochran-Banner): the strength is
// the one number the free-surface pullback measures, sigma = rho0 du c_L c_b / (c_L + c_b) with
// strength (rho0 c0 du / 2 without), so a scene can be checked against the experiment it models;
// the rate dependence of measured spall strengths (1.0-1.6 GPa for aluminium alloys at 1e4-1e6 /s)
// is left to the choice of spall_strength. A rate-dependent law would need its incubation
// parameters fitted to one alloy's pullback data at several strain rates, which the scenes here do
// not have; and its time integral of the tension would also answer the points' noise, which the
// neighbourhood criterion removes without a time scale.
// Why the cap: under a flyer's square pulse the releases from the two free surfaces meet and the
// tension where they overlap rises at twice the rate the free surface sees. A point that dropped
// to zero tension the moment it reached the strength (f_c = 0, still available) fails there before
// the tension the free surface feeds has grown to the strength, and the pullback reads 0.5-0.7 GPa
// for 1.2 GPa set; holding the strength while the point opens lets the tension behind the spall
// plane reach it, as the acoustic relation assumes. The default f_c = 0.15 is the void fraction at
// which voids coalesce in ductile metals (Tvergaard and Needleman 1984).
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
  double strength;       // [Pa]
  double void_fraction;  // f_c: the opened void fraction at which a point separates
  bool by_neighbourhood = false;  // the criterion reads the neighbourhood's stress (spall_neighbourhood.hpp)
  double point_ceiling = 1.0;     // with by_neighbourhood: the point's own tension that opens it regardless,
                                  // as a multiple of the strength

  // The point's own criterion: its tension beyond the strength (spall_criterion = point), or beyond
  // point_ceiling times it (neighbourhood; the opening by the neighbourhood's tension is
  // spall_neighbourhood.hpp's).
  template <int D>
  bool exceeded(const Deviator<D>& s, double P) const {
    return max_principal_stress(s, P) > (by_neighbourhood ? point_ceiling * strength : strength);
  }
  // The damage of a point that opened at J_f and now has J, given its damage so far.
  double damage(double J_f, double J, double damage_before) const {
    const double opened = J > J_f ? 1.0 - J_f / J : 0.0;
    const double d = void_fraction > 0.0 ? opened / void_fraction : 1.0;
    return std::min(1.0, std::max(damage_before, d));
  }
  // The pressure a failed point carries: its tension held at the strength while it opens, none
  // once it has separated.
  double pressure(double P, double damage) const { return std::max(P, damage < 1.0 ? -strength : 0.0); }
};

}  // namespace mpmshock
