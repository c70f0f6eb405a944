// Thermal softening and melting (thermal_softening = on), in the Steinberg-Guinan form:
//
//   f(T, J) = 1 - (T - T_r) / (T_s - T_r)   for T below the melt temperature T_m(J), else 0
//   T_m(J)  = T_m0 exp(2 a (1 - J)) J^(-2 (gamma0 - a - 1/3))   (Lindemann's law, Gruneisen gamma)
//
// with T_r = 300 K. The shear modulus and the yield stress are both scaled by f: they fall
// linearly with temperature and vanish in the melt, where the material is a fluid. Steinberg-
// Guinan's aluminium 6061-T6 (Steinberg, LLNL UCRL-MA-106439, 1996): dG/dT / G0 = -6.16e-4 /K,
// so T_s = 300 K + 1 / 6.16e-4 K = 1923 K; T_m0 = 1220 K; a = 1.5; gamma0 = 1.97 (here the
// scene's gruneisen_gamma). The pressure term of their G(P, T) is left out: it stiffens, and
// the paper's model has none.
#pragma once

#include <algorithm>
#include <cmath>

namespace mpmshock {

struct MeltCurve {
  double T_m0 = 1220.0, a = 1.5, gamma0 = 1.96;
  double at(double J) const { return T_m0 * std::exp(2.0 * a * (1.0 - J)) * std::pow(J, -2.0 * (gamma0 - a - 1.0 / 3.0)); }
};

struct ThermalSoftening {
  MeltCurve melt;
  double T_r = 300.0, T_s = 1923.0;
  // The factor on G and sigma_Y at temperature T and volume ratio J.
  double factor(double T, double J) const {
    if (T >= melt.at(J)) return 0.0;
    return std::clamp(1.0 - (T - T_r) / (T_s - T_r), 0.0, 1.0);
  }
};

}  // namespace mpmshock
