// The registry of material laws: one line per law, in the order their keys are listed (--keys) and
// their checks run. The laws of a kernel type of their own (equations of state, strength laws other
// than the bilinear one) come from their lists in laws.hpp, one line each there; the others are
// listed here. A new law is its header (physics, word, constants), its file in this folder (keys,
// checks; for an equation of state, its kernels), its line in laws.hpp and its test
// (docs/adding-an-effect.md).
#include <stdexcept>

#include "mpmshock/laws.hpp"
#include "mpmshock/material_law.hpp"

namespace mpmshock {

// The laws without a kernel type of their own, each in its file here (src/laws/NAME.cpp).
MaterialLaw solid_law();
MaterialLaw bilinear_law();
MaterialLaw steinberg_guinan_law();

const std::vector<MaterialLaw>& material_laws() {
  static const std::vector<MaterialLaw> laws = [] {
    std::vector<MaterialLaw> all = {solid_law(), bilinear_law(), steinberg_guinan_law()};
    auto add = [&](auto tag) { all.push_back(std::remove_pointer_t<decltype(tag)>::law()); };
    for_each_law<OwnStrengthLaw>(add);
    for_each_law<EquationOfStateLaw>(add);
    return all;
  }();
  return laws;
}

bool takes(const MaterialLaw& law, const Scene& s, const Material& m) {
  switch (law.slot) {
    case LawSlot::equation_of_state:
      if (m.equation_of_state != law.name) return false;
      break;
    case LawSlot::strength:
      if (m.strength_model != law.name) return false;
      break;
    case LawSlot::always:
    case LawSlot::softening: break;
  }
  return law.used(s, m);
}

const MaterialLaw& material_law(const std::string& name) {
  for (const MaterialLaw& law : material_laws())
    if (law.name == name) return law;
  throw std::logic_error("no material law named " + name);
}

const MaterialLaw& law_of(LawSlot slot, const Material& m) {
  if (slot == LawSlot::equation_of_state) return material_law(m.equation_of_state);
  if (slot == LawSlot::strength) return material_law(m.strength_model);
  throw std::logic_error("law_of: a slot no material key chooses");
}

Material without(const std::string& name, Material m) {
  for (const MaterialKey& key : material_law(name).keys) {
    if (key.reference) continue;
    if (const auto* number = std::get_if<NumberField>(&key.field))
      (*number)(m) = 0.0;
    else
      std::get<FlagField>(key.field)(m) = false;
  }
  return m;
}

bool same_constants(const Material& a, const Material& b) {
  if (a.equation_of_state != b.equation_of_state || a.strength_model != b.strength_model) return false;
  for (const MaterialLaw& law : material_laws())
    for (const MaterialKey& key : law.keys) {
      const bool same = std::visit([&](const auto& field) { return field(a) == field(b); }, key.field);
      if (!same) return false;
    }
  return true;
}

}  // namespace mpmshock
