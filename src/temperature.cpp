#include "mpmshock/temperature.hpp"

#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "mpmshock/mixed_equation_of_state.hpp"

namespace mpmshock {

namespace {

// dT_H/dJ from the Walsh-Christian equation in J = V/V0 with gamma/V = gamma0/V0:
// dT_H/dJ = c0^2 s (1 - J)^2 / (c_v [(s - 1) - s J]^3) - gamma0 T_H.
struct WalshChristian {
  double c0, s, gamma0, cv;
  double operator()(double J, double T) const {
    const double d = (s - 1.0) - s * J;
    const double e = 1.0 - J;
    return c0 * c0 * s * e * e / (cv * d * d * d) - gamma0 * T;
  }
};

}  // namespace

HugoniotTemperature::HugoniotTemperature(const Material& mat, TemperatureModel model, bool report_paper,
                                         int intervals)
    : model_(model), report_paper_(report_paper), eos_(mat), cv_(mat.specific_heat), T0_(mat.initial_temperature), gamma0_(mat.gruneisen_gamma) {
  // Equations of state without a Hugoniot in closed form take the isentrope.
  bool isentrope = false;
  std::visit(
      [&](const auto& law) {
        if constexpr (!std::decay_t<decltype(law)>::kHugoniotReference) {
          tabulate_isentrope(law, intervals);
          isentrope = true;
        }
      },
      equation_of_state_of(mat));
  if (isentrope) return;
  // Down to the smallest J the equation of state admits, short of the pole where T_H diverges
  // (eos.hpp): every state the point update admits has a finite temperature.
  J_min_ = eos_.limiting_compression();
  dJ_ = (1.0 - J_min_) / intervals;
  const WalshChristian rhs{mat.sound_speed, mat.hugoniot_slope, mat.gruneisen_gamma, mat.specific_heat};

  table_.resize(intervals + 1);
  table_[0] = T0_;
  double T = T0_;
  // Classic RK4 stepping in -J with 8 substeps per table interval: the table error is then set
  // by interpolation, not by integration.
  constexpr int kSub = 8;
  const double h = -dJ_ / kSub;
  for (int k = 1; k <= intervals; ++k) {
    double J = 1.0 - (k - 1) * dJ_;
    for (int sub = 0; sub < kSub; ++sub) {
      const double k1 = rhs(J, T);
      const double k2 = rhs(J + 0.5 * h, T + 0.5 * h * k1);
      const double k3 = rhs(J + 0.5 * h, T + 0.5 * h * k2);
      const double k4 = rhs(J + h, T + h * k3);
      T += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      J += h;
    }
    table_[k] = T;
  }
}

template <class Eos>
void HugoniotTemperature::tabulate_isentrope(const Eos& eos, int intervals) {
  constexpr double kTop = 100.0;  // the largest J tabulated
  constexpr int kExpandedPerCompressed = 4;  // ln J spacing 1.1e-3 for 4096 intervals
  // Down to the limiting compression itself (an isentrope has no pole there): every state the
  // point update admits has a temperature (a state between the limit and the table would read an
  // infinite one, which the heat flux would spread as NaN).
  J_min_ = eos.limiting_compression();
  dJ_ = (1.0 - J_min_) / intervals;
  const int expanded = kExpandedPerCompressed * intervals;
  dlnJ_ = std::log(kTop) / expanded;
  compressed_nodes_ = static_cast<std::size_t>(intervals) + 1;
  isentrope_.assign(compressed_nodes_ + static_cast<std::size_t>(expanded), IsentropeNode{0.0, T0_});
  // d(E, T)/dx along the isentrope, x = J in compression and ln J in expansion (dJ/dx = J there).
  const double rho0 = eos.rho0();
  auto rhs = [&](bool log_step, double x, double E, double T, double& dE, double& dT) {
    const double J = log_step ? std::exp(x) : x, dJ_dx = log_step ? J : 1.0;
    const auto ps = eos.pressure_and_energy_slope(J, E);
    dE = -ps.pressure / rho0 * dJ_dx;
    dT = -T * ps.energy_slope / rho0 * dJ_dx;
  };
  // RK4 with 4 substeps per table interval, from J = 1 down to J_min and up to the top: the table's
  // error is its interpolation's (test_tillotson: within 1e-6 of the closed form at the nodes).
  constexpr int kSub = 4;
  for (const bool up : {false, true}) {
    double x = up ? 0.0 : 1.0, E = 0.0, T = T0_;
    const double h = up ? dlnJ_ / kSub : -dJ_ / kSub;
    const int steps = up ? expanded : intervals;
    for (int k = 1; k <= steps; ++k) {
      for (int sub = 0; sub < kSub; ++sub) {
        double e1, t1, e2, t2, e3, t3, e4, t4;
        rhs(up, x, E, T, e1, t1);
        rhs(up, x + 0.5 * h, E + 0.5 * h * e1, T + 0.5 * h * t1, e2, t2);
        rhs(up, x + 0.5 * h, E + 0.5 * h * e2, T + 0.5 * h * t2, e3, t3);
        rhs(up, x + h, E + h * e3, T + h * t3, e4, t4);
        E += h / 6.0 * (e1 + 2.0 * e2 + 2.0 * e3 + e4);
        T += h / 6.0 * (t1 + 2.0 * t2 + 2.0 * t3 + t4);
        x += h;
      }
      const std::size_t one = compressed_nodes_ - 1;  // the J = 1 node
      isentrope_[up ? one + static_cast<std::size_t>(k) : one - static_cast<std::size_t>(k)] = {E, T};
    }
  }
}

double HugoniotTemperature::hugoniot_temperature(double J) const {
  if (!isentrope_.empty()) {
    if (!(J >= J_min_)) return std::numeric_limits<double>::infinity();
    return isentrope_lookup(J).temperature;
  }
  if (J >= 1.0) return T0_ * std::exp(gamma0_ * (1.0 - J));
  if (!(J >= J_min_)) return std::numeric_limits<double>::infinity();
  const double u = (1.0 - J) / dJ_;
  const auto k = static_cast<std::size_t>(u);
  if (k + 1 >= table_.size()) return table_.back();
  const double frac = u - static_cast<double>(k);
  return table_[k] + frac * (table_[k + 1] - table_[k]);
}

}  // namespace mpmshock
