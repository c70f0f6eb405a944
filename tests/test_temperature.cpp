// The Walsh-Christian T_H table against physics-notes section 3, T = T_H + (E - E_H)/c_v (energy
// model) and T = T_H + W_p/c_v (paper model).
#include "check.hpp"
#include "mpmshock/eos.hpp"
#include "mpmshock/temperature.hpp"

using namespace mpmshock;

int main() {
  const Material al;
  const HugoniotTemperature temp(al);
  const MieGruneisen eos(al);
  const double c0 = 5350, s = 1.34;

  // physics-notes section 3: T_H at the jump states of 500, 1000 and 2000 m/s, to 0.1 K.
  const double table[3][2] = {{500, 364.3}, {1000, 487.7}, {2000, 1104.4}};
  for (const auto& row : table) {
    const double up = row[0], Us = c0 + s * up, J = (Us - up) / Us;
    CHECK_NEAR(temp.hugoniot_temperature(J), row[1], 0.1);
    CHECK_NEAR(temp.temperature(J, eos.hugoniot_energy(J)), row[1], 0.1);
  }
  // Reference state and the tension branch.
  CHECK_NEAR(temp.temperature(1.0, 0.0), 300.0, 1e-12);
  CHECK_REL(temp.hugoniot_temperature(1.05), 300.0 * std::exp(1.96 * -0.05), 1e-15);
  // No kink at J = 1: the one-sided slopes of T_H agree (both -gamma0 T0).
  const double dJ = 1e-6;
  CHECK_REL((temp.hugoniot_temperature(1.0 + dJ) - 300.0) / dJ, -1.96 * 300.0, 1e-4);
  CHECK_REL((300.0 - temp.hugoniot_temperature(1.0 - dJ)) / dJ, -1.96 * 300.0, 2e-3);
  // The whole model on an isentrope: from rest, dE = -P dV = -(P / rho0) dJ with P from the
  // Mie-Gruneisen EOS. With gamma/V constant and c_v constant the isentrope is
  // T = T0 exp(gamma0 (1 - J)) exactly, in expansion and in compression (RK4 in J, 2000 steps).
  for (const double J_end : {1.08, 0.85}) {
    double J = 1.0, E = 0.0;
    const int n = 2000;
    const double h = (J_end - 1.0) / n;
    auto dE = [&](double j, double e) { return -eos.pressure(j, e) / al.density; };
    for (int k = 0; k < n; ++k, J += h) {
      const double k1 = dE(J, E), k2 = dE(J + h / 2, E + h / 2 * k1), k3 = dE(J + h / 2, E + h / 2 * k2),
                   k4 = dE(J + h, E + h * k3);
      E += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    CHECK_NEAR(temp.temperature(J_end, E), 300.0 * std::exp(1.96 * (1.0 - J_end)), J_end > 1 ? 1e-6 : 0.05);
  }
  // Heat added at fixed volume raises T by dE / c_v.
  CHECK_NEAR(temp.temperature(0.9, eos.hugoniot_energy(0.9) + 88000.0) - temp.hugoniot_temperature(0.9), 100.0,
             1e-9);
  // The paper model: T_H(J) plus the plastic heat over c_v, whatever E holds.
  CHECK_NEAR(temp.paper_temperature(0.9, 0.0), temp.hugoniot_temperature(0.9), 1e-12);
  CHECK_NEAR(temp.paper_temperature(0.9, 88000.0) - temp.hugoniot_temperature(0.9), 100.0, 1e-9);
  // Every state the equation of state admits has a finite temperature: the table reaches its
  // limiting compression (a state between them read an infinite one, which the heat flux spread as NaN).
  CHECK_NEAR(temp.min_tabulated_J(), eos.limiting_compression(), 1e-15);
  for (double J : {eos.limiting_compression() * (1 + 1e-12), eos.limiting_compression() + 1e-4})
    CHECK(std::isfinite(temp.temperature(J, eos.hugoniot_energy(J))));
  // T_H grows monotonically with compression down to the table's end.
  double last = 0;
  for (double J = 1.0; J > temp.min_tabulated_J(); J -= 0.01) {
    const double T = temp.hugoniot_temperature(J);
    CHECK(T >= last);
    last = T;
  }
  // The equation is linear in T: T_H = T0 exp(gamma0 (1 - J)) (adiabatic compression) plus a shock
  // part proportional to 1 / c_v. Halving c_v doubles the shock part exactly.
  Material hot = al;
  hot.specific_heat = 440.0;
  const HugoniotTemperature temp2(hot);
  const double J1000 = (c0 + s * 1000 - 1000) / (c0 + s * 1000);
  const double adiabatic = 300.0 * std::exp(1.96 * (1 - J1000));
  CHECK_REL(temp2.hugoniot_temperature(J1000) - adiabatic, 2 * (temp.hugoniot_temperature(J1000) - adiabatic), 1e-6);
  return check::result();
}
