// What an equation of state given in closed form offers the rest of the code, from one function:
// its pressure and the pressure's two partial derivatives, P(rho, E), (dP/drho)_E and (dP/dE)_rho.
// A law derives from FromPressureTerms<Law> and defines rho0() and terms(J, E) (tillotson.hpp,
// polynomial.hpp); the state, the pressure, the energy slope and the isentropic sound speed
// c^2 = (dP/drho)_E + (P / rho^2) (dP/dE)_rho follow here, the same for every such law.
#pragma once

namespace mpmshock {

struct PressureTerms {
  double P, dP_drho, dP_dE;
};

template <class Law>
class FromPressureTerms {
 public:
  struct State {
    double pressure, sound_speed_squared;
  };
  State state(double J, double E) const {
    const PressureTerms t = law().terms(J, E);
    const double rho = law().rho0() / J;
    return {t.P, t.dP_drho + t.P / (rho * rho) * t.dP_dE};
  }
  double pressure(double J, double E) const { return law().terms(J, E).P; }
  // (dP/dE) at fixed volume: gamma / V, the Grüneisen parameter's share of the state.
  double pressure_energy_slope(double J, double E) const { return law().terms(J, E).dP_dE; }
  // Both at once, for the isentrope's tabulation (temperature.cpp).
  struct PressureAndSlope {
    double pressure, energy_slope;
  };
  PressureAndSlope pressure_and_energy_slope(double J, double E) const {
    const PressureTerms t = law().terms(J, E);
    return {t.P, t.dP_dE};
  }
  // The squared sound speed of a state (P follows from J and E).
  double sound_speed_squared(double J, double E, double /*P*/) const { return state(J, E).sound_speed_squared; }

 private:
  const Law& law() const { return static_cast<const Law&>(*this); }
};

}  // namespace mpmshock
