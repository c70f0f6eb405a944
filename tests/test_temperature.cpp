// The Walsh-Christian T_H table against physics-notes section 3, and T = T_H + (E - E_H)/c_v.
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
  CHECK_NEAR(temp.hugoniot_temperature(1.05), 300.0, 0.0);
  // Heat added at fixed volume raises T by dE / c_v.
  CHECK_NEAR(temp.temperature(0.9, eos.hugoniot_energy(0.9) + 88000.0) - temp.hugoniot_temperature(0.9), 100.0,
             1e-9);
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
