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
  // limiting compression 1 - 1/s. For J >= 1 (tension) T_H = T0: the cold branch of P_H is linear
  // and carries no heating, so expansion changes T only through E - E_H.
  HugoniotTemperature(const Material& mat, int intervals = 4096);

  double hugoniot_temperature(double J) const;

  // T = T_H(J) + (E - E_H(J)) / c_v.
  double temperature(double J, double E) const {
    return hugoniot_temperature(J) + (E - eos_.hugoniot_energy(J)) / cv_;
  }

  double min_tabulated_J() const { return J_min_; }

 private:
  MieGruneisen eos_;
  double cv_ = 880.0, T0_ = 300.0;
  double J_min_ = 0.0, dJ_ = 0.0;
  std::vector<double> table_;  // table_[k] = T_H(1 - k dJ)
};

}  // namespace mpmshock
