#include "mpmshock/constitutive.hpp"

namespace mpmshock {

template <int D>
double initial_signal_speed(const Particles<D>& pts, const Model& model) {
  double max_signal = 0.0;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const Body b = pts.body[p];
    const double G = model.shear_modulus(b);
    double c2 = std::max(std::visit([&](const auto& eos) { return eos.sound_speed_squared(pts.J(p), pts.E[p], pts.P[p]); },
                                    model.eos[static_cast<std::size_t>(b)]),
                         0.0);
    if (model.has_strength()) c2 += (4.0 / 3.0) * G / pts.density(p);
    max_signal = std::max(max_signal, speed(pts.v[p]) + std::sqrt(c2));
  }
  return max_signal;
}

template double initial_signal_speed<2>(const Particles<2>&, const Model&);
template double initial_signal_speed<3>(const Particles<3>&, const Model&);

}  // namespace mpmshock
