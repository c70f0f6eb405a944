#include "mpmshock/constitutive.hpp"

namespace mpmshock {

template <int D>
double initial_signal_speed(const Particles<D>& pts, const Model& model) {
  const double G = model.shear_modulus();
  return std::visit(
      [&](const auto& eos) {
        double max_signal = 0.0;
        for (std::size_t p = 0; p < pts.size(); ++p) {
          double c2 = std::max(eos.sound_speed_squared(pts.J(p), pts.P[p]), 0.0);
          if (model.has_strength()) c2 += (4.0 / 3.0) * G / pts.density(p);
          max_signal = std::max(max_signal, speed(pts.v[p]) + std::sqrt(c2));
        }
        return max_signal;
      },
      model.eos);
}

template double initial_signal_speed<2>(const Particles<2>&, const Model&);
template double initial_signal_speed<3>(const Particles<3>&, const Model&);

}  // namespace mpmshock
