#include "mpmshock/temperature.hpp"

#include <cmath>
#include <limits>

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
  const double J_limit = eos_.limiting_compression();
  // Stop short of the pole at J = 1 - 1/s where T_H diverges; no physical state gets close.
  J_min_ = J_limit + 0.02 * (1.0 - J_limit);
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

double HugoniotTemperature::hugoniot_temperature(double J) const {
  if (J >= 1.0) return T0_ * std::exp(gamma0_ * (1.0 - J));
  if (!(J >= J_min_)) return std::numeric_limits<double>::infinity();
  const double u = (1.0 - J) / dJ_;
  const auto k = static_cast<std::size_t>(u);
  if (k + 1 >= table_.size()) return table_.back();
  const double frac = u - static_cast<double>(k);
  return table_[k] + frac * (table_[k + 1] - table_[k]);
}

}  // namespace mpmshock
