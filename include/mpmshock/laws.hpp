// The registry of the laws the kernels take as types, one line per law. Each law's header gives its
// physics, the word its slot's key takes for it (kName), its declaration (law(): keys, checks and
// --check lines, in its file under src/laws/) and, where it has constants of its own, their struct
// (Constants, held in the material by type: material.hpp). The material laws without a kernel type of
// their own (the solid's constants, the bilinear law and its Steinberg-Guinan softening) are listed in
// src/laws/registry.cpp, which lists these after them.
#pragma once

#include <cstddef>
#include <utility>
#include <variant>

#include "mpmshock/eos.hpp"
#include "mpmshock/johnson_cook.hpp"
#include "mpmshock/polynomial.hpp"
#include "mpmshock/tillotson.hpp"

namespace mpmshock {

// The equations of state (equation_of_state = WORD); the first is the default. Each one's kernels are
// instantiated in its file under src/laws/.
using EquationOfStateLaw = std::variant<MieGruneisen, Tillotson, Polynomial>;

// The strength laws of a type of their own (strength_model = WORD), besides the default bilinear law,
// whose four forms (von_mises.hpp) follow from hardening_beta and thermal_softening (model.cpp).
using OwnStrengthLaw = std::variant<JohnsonCook>;

// std::variant<A..., B...>.
template <class A, class B>
struct Joined;
template <class... A, class... B>
struct Joined<std::variant<A...>, std::variant<B...>> {
  using type = std::variant<A..., B...>;
};
template <class A, class B>
using JoinedVariant = typename Joined<A, B>::type;

// f(tag) for each law of the list in order, tag a null pointer to the law's type.
template <class Variant, class F, std::size_t... I>
void for_each_law_of(F&& f, std::index_sequence<I...>) {
  (f(static_cast<std::variant_alternative_t<I, Variant>*>(nullptr)), ...);
}
template <class Variant, class F>
void for_each_law(F&& f) {
  for_each_law_of<Variant>(std::forward<F>(f), std::make_index_sequence<std::variant_size_v<Variant>>{});
}

}  // namespace mpmshock
