// The paper's temperature model: T = T_H(V) + (E - E_H(V)) / c_v, with T_H(V) the temperature on
// the Hugoniot from the Walsh-Christian equation (physics-notes section 2), integrated once at
// start-up into a table.
#pragma once

#include <vector>

#include "mpmshock/eos.hpp"
#include "mpmshock/material.hpp"

namespace mpmshock {

class HugoniotTemperature {
 public:
  HugoniotTemperature() = default;
  // Tabulates T_H on J in [J_min, 1] with `intervals` equal steps, J_min close to the Hugoniot's
  // limiting compression 1 - 1/s. For J >= 1 (tension) the reference curve is the linear branch
  // P_H = rho0 c0^2 eta, on which the Walsh-Christian equation has no shock-heating term (s = 0):
  // T_H = T0 exp(gamma0 (1 - J)), the isentrope, continuous with its slope at J = 1.
  HugoniotTemperature(const Material& mat, int intervals = 4096);

  double hugoniot_temperature(double J) const;

  // T = T_H(J) + (E - E_H(J)) / c_v.
  double temperature(double J, double E) const {
    return hugoniot_temperature(J) + (E - eos_.hugoniot_energy(J)) / cv_;
  }

  double min_tabulated_J() const { return J_min_; }

 private:
  MieGruneisen eos_;
  double cv_ = 880.0, T0_ = 300.0, gamma0_ = 1.96;
  double J_min_ = 0.0, dJ_ = 0.0;
  std::vector<double> table_;  // table_[k] = T_H(1 - k dJ)
};

}  // namespace mpmshock
