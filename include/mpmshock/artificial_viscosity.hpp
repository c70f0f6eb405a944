// Artificial bulk viscosity for shock capturing (physics-notes section 4), one type per choice:
//
//   NoViscosity          q = 0
//   ArtificialViscosity  q = rho (A1 c h |tr D| + A2 h^2 (tr D)^2), in compression (tr D < 0) only
#pragma once

namespace mpmshock {

struct NoViscosity {
  static constexpr bool active = false;
};

struct ArtificialViscosity {
  static constexpr bool active = true;
  double linear;     // A1
  double quadratic;  // A2

  // The viscous pressure q. rho: current density, c: bulk sound speed, h: cell size, trD:
  // volumetric strain rate. T: a double or four points' Lanes (number.hpp).
  template <class T>
  T pressure(const T& rho, const T& c, double h, const T& trD) const {
    const T rate = -trD;
    return trD >= 0.0 ? T{} : rho * h * rate * (linear * c + quadratic * h * rate);
  }

  // The viscous part of the signal speed, Q = A1 c + A2 h |tr D|, for the time-step bound
  // dt <= h / (Q + sqrt(Q^2 + c^2)) of a viscous explicit scheme.
  template <class T>
  T signal(const T& c, double h, const T& trD) const {
    return trD >= 0.0 ? T{} : linear * c + quadratic * h * (-trD);
  }
};

}  // namespace mpmshock
