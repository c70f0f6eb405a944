// Bodies of different strength laws (a Johnson-Cook copper flyer on a bilinear aluminium target):
// each body's law is held as a variant and called through it at every point, as
// MixedEquationOfState does for equations of state. Only scenes whose bodies mix laws use it
// (model.cpp), so the kernels of the others keep their direct calls. Its points store a back stress
// (zero in the bodies whose law has none), so that one kernel serves every body.
#pragma once

#include <variant>

#include "mpmshock/laws.hpp"
#include "mpmshock/von_mises.hpp"

namespace mpmshock {

// One material's strength law when there is strength (model.cpp: strength_of): the bilinear law's
// four forms and the registry's others (laws.hpp).
using StrengthWithStress = JoinedVariant<
    std::variant<VonMises<false>, VonMises<true>, VonMises<false, true>, VonMises<true, true>>, OwnStrengthLaw>;

struct MixedStrength {
  static constexpr bool has_stress = true;
  static constexpr bool has_back_stress = true;

  StrengthWithStress law;
  double shear_modulus = 0.0;  // G of the law (the longitudinal sound speed reads it)

  MixedStrength() = default;
  explicit MixedStrength(StrengthWithStress l)
      : law(std::move(l)), shear_modulus(std::visit([](const auto& s) { return s.shear_modulus; }, law)) {}

  // The law's step (von_mises.hpp, johnson_cook.hpp): the plastic work per unit volume.
  template <int D>
  double update(Deviator<D>& s, Deviator<D>& alpha, double& eps_p, const StrainRate<D>& rate, double dt, double J,
                double E_thermal, double P) const {
    return std::visit([&](const auto& l) { return l.update(s, alpha, eps_p, rate, dt, J, E_thermal, P); }, law);
  }
};

}  // namespace mpmshock
