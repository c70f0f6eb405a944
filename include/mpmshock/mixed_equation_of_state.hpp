// Bodies of different equations of state (a Mie-Grüneisen copper flyer on a Tillotson aluminium
// target): each body's law is held as a variant and called through it at every point. Only scenes
// whose bodies mix laws use it (model.cpp), so the kernels of the others keep their direct calls;
// its own kernels cost a branch on the law per call.
#pragma once

#include <variant>

#include "mpmshock/eos.hpp"
#include "mpmshock/tillotson.hpp"

namespace mpmshock {

// One material's equation of state (model.cpp: equation_of_state_of): the list of the laws.
using EquationOfStateLaw = std::variant<MieGruneisen, Tillotson>;

class MixedEquationOfState {
  EquationOfStateLaw law_;
  // f applied to the law (defined first: the members below deduce their types from it).
  template <class F>
  auto call(F&& f) const {
    return std::visit(f, law_);
  }

 public:
  MixedEquationOfState() = default;
  explicit MixedEquationOfState(EquationOfStateLaw law) : law_(law) {}

  double rho0() const { return call([](const auto& e) { return e.rho0(); }); }
  double limiting_compression() const { return call([](const auto& e) { return e.limiting_compression(); }); }
  double fit_limit() const { return call([](const auto& e) { return e.fit_limit(); }); }
  double reference_sound_speed() const { return call([](const auto& e) { return e.reference_sound_speed(); }); }

  struct State {
    double pressure, sound_speed_squared;
  };
  State state(double J, double E) const {
    return call([&](const auto& e) {
      const auto s = e.state(J, E);
      return State{s.pressure, s.sound_speed_squared};
    });
  }
  double pressure(double J, double E) const { return call([&](const auto& e) { return e.pressure(J, E); }); }
  double sound_speed_squared(double J, double E, double P) const {
    return call([&](const auto& e) { return e.sound_speed_squared(J, E, P); });
  }

};

}  // namespace mpmshock
