// The Rankine-Hugoniot jump state of a steady shock into material at rest in its reference state
// (J = 1, E = 0, P = 0), for any equation of state with rho0() and pressure(J, E): mass and
// momentum give P = rho0 Us up with Us = up / (1 - J), and energy gives E = up^2 / 2, so for a
// particle velocity up the state is the root in J of
//   f(J) = P_eos(J, up^2 / 2) - rho0 up^2 / (1 - J),
// which runs from -infinity at J -> 1 to positive values in strong compression; bisection finds it
// to round-off. For the linear Us-up Hugoniot of Mie-Grüneisen it returns Us = c0 + s up (tested).
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
  const double J_limit = eos.limiting_compression();
  double lo = J_limit + 1e-9 * (1.0 - J_limit), hi = 1.0;  // f(hi) < 0 < f(lo)
  if (!(f(lo) > 0.0)) return {lo, eos.pressure(lo, E), E, up / (1.0 - lo)};
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  const double J = 0.5 * (lo + hi);
  return {J, rho0 * up * up / (1.0 - J), E, up / (1.0 - J)};
}

}  // namespace mpmshock
