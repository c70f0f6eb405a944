// Bodies of different equations of state (a Mie-Grüneisen copper flyer on a Tillotson aluminium
// target): each body's law is held as a variant and called through it at every point. Only scenes
// whose bodies mix laws use it (model.cpp), so the kernels of the others keep their direct calls;
// its own kernels cost a branch on the law per call.
#pragma once

#include <cassert>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

#include "mpmshock/laws.hpp"

namespace mpmshock {

// f(tag) with tag a null pointer to the law of the registry's list (EquationOfStateLaw, laws.hpp)
// whose kName the material's equation_of_state names: the one walk of the list by word.
template <std::size_t I = 0, class F>
decltype(auto) with_law_named_by(const Material& mat, F&& f) {
  using Law = std::variant_alternative_t<I, EquationOfStateLaw>;
  if constexpr (I + 1 < std::variant_size_v<EquationOfStateLaw>)
    if (mat.equation_of_state != Law::kName) return with_law_named_by<I + 1>(mat, std::forward<F>(f));
  assert(mat.equation_of_state == Law::kName);  // every word is some law's kName
  return f(static_cast<Law*>(nullptr));
}

// A material's equation of state.
inline EquationOfStateLaw equation_of_state_of(const Material& mat) {
  return with_law_named_by(mat, [&](auto tag) -> EquationOfStateLaw { return std::remove_pointer_t<decltype(tag)>(mat); });
}

// A material's reference bulk sound speed from its law's constants alone, without building the law
// (the scene's checks call it before they have checked the constants).
inline double reference_sound_speed_of(const Material& mat) {
  return with_law_named_by(mat, [&](auto tag) { return std::remove_pointer_t<decltype(tag)>::sound_speed_of(mat); });
}

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
