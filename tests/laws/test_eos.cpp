// Mie-Grüneisen on the linear Us-up Hugoniot: reference curve, continuity at V0, the jump states of
// physics-notes section 3, gamma rho constant, and the sound speed.
#include "check.hpp"
#include "mpmshock/eos.hpp"

using namespace mpmshock;

int main() {
  const Material al;  // the paper's aluminium
  const MieGruneisen eos(al);
  Material bounded_al = al;
  bounded_al.bound_expansion = true;
  const MieGruneisen bounded(bounded_al);
  const double rho0 = 2700, c0 = 5350, s = 1.34, K0 = rho0 * c0 * c0;

  // P_H = rho0 c0^2 eta / (1 - s eta)^2, written out independently.
  for (double eta : {0.01, 0.1, 0.2, 0.3}) {
    const double expect = K0 * eta / ((1 - s * eta) * (1 - s * eta));
    CHECK_REL(eos.hugoniot_pressure(1 - eta), expect, 1e-14);
    CHECK_REL(eos.hugoniot_energy(1 - eta), 0.5 * expect * eta / rho0, 1e-14);
  }
  // The linear branch (bounded_expansion = off, the default): P_H = rho0 c0^2 (1 - V/V0).
  CHECK_REL(eos.hugoniot_pressure(1.02), -0.02 * K0, 1e-12);
  // Expansion: Rose's universal binding curve, written out independently,
  // E_r = E_coh [1 - (1 + a) e^-a], a = 3 (J^(1/3) - 1) / x0, x0 = sqrt(E_coh) / c0.
  const double E_coh = al.cohesive_energy, x0 = std::sqrt(E_coh) / c0;
  auto rose_energy = [&](double J) {
    const double a = 3 * (std::cbrt(J) - 1) / x0;
    return E_coh * (1 - (1 + a) * std::exp(-a));
  };
  for (double J : {1.001, 1.1, 1.5, 2.0, 4.0}) {
    CHECK_REL(bounded.hugoniot_energy(J), rose_energy(J), 1e-12);
    // An isentrope of the cold material: P_r = -rho0 dE_r/dJ (central difference).
    const double dJ = 1e-6 * J;
    CHECK_REL(bounded.hugoniot_pressure(J), -rho0 * (rose_energy(J + dJ) - rose_energy(J - dJ)) / (2 * dJ), 1e-6);
    const double h = 1e-6;  // and its slope dP_r/deta
    CHECK_REL(bounded.hugoniot_pressure_slope(J),
              -(bounded.hugoniot_pressure(J + h) - bounded.hugoniot_pressure(J - h)) / (2 * h), 1e-5);
  }
  // Near J = 1 it is the linear branch P = rho0 c0^2 (1 - V/V0) of the errata (second order).
  CHECK_REL(bounded.hugoniot_pressure(1.0001), -0.0001 * K0, 3e-4);
  // Bounded: the tension peaks at 13.2 GPa near J = 1.55 and returns to zero as the energy
  // approaches the cohesive energy (the linear branch gave -49 GPa at J = 1.63 and grew without end).
  double most_tension = 0, J_peak = 1;
  for (double J = 1.0; J < 20.0; J += 1e-3)
    if (bounded.hugoniot_pressure(J) < most_tension) most_tension = bounded.hugoniot_pressure(J), J_peak = J;
  CHECK(most_tension > -13.5e9 && most_tension < -12.5e9);
  CHECK(J_peak > 1.45 && J_peak < 1.65);
  CHECK(bounded.hugoniot_pressure(50.0) < 0.0 && bounded.hugoniot_pressure(50.0) > 0.01 * most_tension);
  CHECK_REL(bounded.hugoniot_energy(1e4), E_coh, 1e-6);
  // The fit's range: the Hugoniot state at fit_particle_velocity.
  CHECK_REL(eos.fit_limit(), 1 - 6000.0 / (c0 + s * 6000.0), 1e-14);

  // Continuity at V0: value and slope of both branches agree.
  const double e = 1e-8;
  CHECK_NEAR(eos.hugoniot_pressure(1.0), 0.0, 0.0);
  CHECK_REL(eos.hugoniot_pressure(1 - e) / e, -eos.hugoniot_pressure(1 + e) / e, 1e-6);
  CHECK_REL(eos.hugoniot_pressure_slope(1 - e), eos.hugoniot_pressure_slope(1 + e), 1e-6);
  CHECK_REL(eos.hugoniot_pressure_slope(1.0), K0, 1e-14);

  // Rankine-Hugoniot jump states (physics-notes section 3): at rho = rho0 Us / (Us - up) on the
  // Hugoniot (E = E_H = up^2 / 2) the pressure is rho0 Us up.
  const double table[3][3] = {{500, 8.127e9, 2944.6}, {1000, 18.063e9, 3174.5}, {2000, 43.362e9, 3595.5}};
  for (const auto& row : table) {
    const double up = row[0], Us = c0 + s * up;
    const double J = (Us - up) / Us;
    CHECK_REL(rho0 / J, row[2], 1e-4);
    CHECK_REL(eos.hugoniot_energy(J), 0.5 * up * up, 1e-12);
    CHECK_REL(eos.pressure(J, 0.5 * up * up), row[1], 1e-4);
  }

  // Off the Hugoniot: dP/dE = gamma / V = gamma0 rho0 at every volume (gamma rho constant).
  for (double J : {0.7, 0.9, 1.0, 1.1}) {
    const double dE = 1e4;
    CHECK_REL((eos.pressure(J, 2e5 + dE) - eos.pressure(J, 2e5)) / dE, 1.96 * rho0, 1e-9);
  }

  // Bulk sound speed: c0 at the reference state; and c^2 = -V^2 (dP/dV)_S checked numerically
  // along an isentrope dE = -P dV.
  CHECK_REL(std::sqrt(eos.sound_speed_squared(1.0, 0.0)), c0, 1e-14);
  for (const MieGruneisen* e : {&eos, &bounded})
    for (double J : {0.8, 0.9, 0.95, 1.05, 1.3}) {
      const double E = 3e5, P = e->pressure(J, E), dJ = 1e-7;
      const double V = J / rho0, dV = dJ / rho0;
      const double P_plus = e->pressure(J + dJ, E - P * dV), P_minus = e->pressure(J - dJ, E + P * dV);
      const double c2_numeric = -V * V * (P_plus - P_minus) / (2 * dV);
      CHECK_REL(e->sound_speed_squared(J, P), c2_numeric, 1e-5);
    }
  CHECK_REL(eos.pole(), 1 - 1 / s, 1e-15);
  // The admitted states stop 2 % of the way from the pole (P_H about 1.2e5 GPa for aluminium).
  CHECK_REL(eos.limiting_compression(), eos.pole() + 0.02 * (1 - eos.pole()), 1e-15);
  CHECK(eos.hugoniot_pressure(eos.limiting_compression()) > 1e14);
  // The constitutive update's combined evaluation gives the same state.
  for (double J : {0.7, 0.9, 1.0, 1.05}) {
    const MieGruneisen::State st = eos.state(J, 1.5e5);
    CHECK(st.pressure == eos.pressure(J, 1.5e5));
    CHECK(st.sound_speed_squared == eos.sound_speed_squared(J, st.pressure));
  }
  return check::result();
}
