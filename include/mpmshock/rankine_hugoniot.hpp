// The Rankine-Hugoniot jump state of a steady shock into material at rest in its reference state
// (J = 1, E = 0, P = 0), for any equation of state with rho0() and pressure(J, E): mass and
// momentum give P = rho0 Us up with Us = up / (1 - J), and energy gives E = up^2 / 2, so for a
// particle velocity up the state is the root in J of
//   f(J) = P_eos(J, up^2 / 2) - rho0 up^2 / (1 - J),
// which runs from -infinity at J -> 1 to positive values in compression. It need not stay positive
// toward the limiting compression (Mie-Grüneisen with gamma0 > 2 s turns to -infinity at the pole),
// so the root taken is the first sign change met coming down from J = 1 (the weakest shock), found
// by a scan in 1000 steps and bisected to round-off. For the linear Us-up Hugoniot of Mie-Grüneisen
// it returns Us = c0 + s up (tested, also with gamma0 > 2 s).
#pragma once

namespace mpmshock {

struct ShockState {
  double J, pressure, energy, shock_speed;
};

// The shock state at particle velocity up > 0; J is at most the EOS's limiting compression (with a
// pressure that does not match) where the root lies beyond it.
template <class Eos>
ShockState shock_from_rest(const Eos& eos, double up) {
  const double E = 0.5 * up * up, rho0 = eos.rho0();
  auto f = [&](double J) { return eos.pressure(J, E) - rho0 * up * up / (1.0 - J); };
  if (!(up > 0.0)) return {1.0, 0.0, 0.0, 0.0};
  const double J_limit = eos.limiting_compression() + 1e-9 * (1.0 - eos.limiting_compression());
  constexpr int kScan = 1000;
  double lo = 1.0, hi = 1.0;  // f(hi) < 0 < f(lo)
  for (int k = 1; k <= kScan; ++k) {
    hi = lo;
    lo = 1.0 - (1.0 - J_limit) * k / kScan;
    if (f(lo) > 0.0) break;
    if (k == kScan) return {lo, eos.pressure(lo, E), E, up / (1.0 - lo)};  // beyond the limit
  }
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  const double J = 0.5 * (lo + hi);
  return {J, rho0 * up * up / (1.0 - J), E, up / (1.0 - J)};
}

}  // namespace mpmshock
