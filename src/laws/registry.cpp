// The registry of material laws: one line per law, in the order their keys are listed (--keys) and
// their checks run. The laws of a kernel type of their own (equations of state, strength laws other
// than the bilinear one) come from their lists in laws.hpp, one line each there; the others are
// listed here. A new law is its header (physics, word, constants), its file in this folder (keys,
// checks; for an equation of state, its kernels), its line in laws.hpp and its test
// (docs/adding-an-effect.md).
#include <stdexcept>

#include "mpmshock/laws.hpp"
#include "mpmshock/material_law.hpp"
#include "mpmshock/scene.hpp"

namespace mpmshock {

// The laws without a kernel type of their own, each in its file here (src/laws/NAME.cpp).
MaterialLaw solid_law();
MaterialLaw bilinear_law();
MaterialLaw steinberg_guinan_law();

namespace {

// The paper's temperature model adds the plastic heat to the reference curve's temperature, which
// carries the shock heating only where that curve is the Hugoniot: an equation of state referenced to
// its isentrope (kHugoniotReference false: Tillotson, the polynomial) refuses it, after its own checks.
void refuse_paper_temperature(MaterialLaw& law) {
  law.check_scene = [own = law.check_scene, word = law.name](const Scene& s, const std::string& key, const auto& fail) {
    own(s, key, fail);
    const std::string why = "the Hugoniot's temperature, and equation_of_state = " + word + " is referenced to its isentrope";
    if (s.effects.thermal && s.temperature_model == TemperatureModel::paper)
      fail("temperature_model", "paper needs equation_of_state = mie_gruneisen: it adds the plastic heat to " + why +
                                    " (the shock heating would be lost)");
    if (s.effects.thermal && s.paper_temperature)
      fail("paper_temperature", "needs equation_of_state = mie_gruneisen: the paper's model adds the plastic heat to " + why);
  };
}

}  // namespace

const std::vector<MaterialLaw>& material_laws() {
  static const std::vector<MaterialLaw> laws = [] {
    std::vector<MaterialLaw> all = {solid_law(), bilinear_law(), steinberg_guinan_law()};
    for_each_law<OwnStrengthLaw>([&](auto tag) { all.push_back(std::remove_pointer_t<decltype(tag)>::law()); });
    for_each_law<EquationOfStateLaw>([&](auto tag) {
      using Law = std::remove_pointer_t<decltype(tag)>;
      all.push_back(Law::law());
      if constexpr (!Law::kHugoniotReference) refuse_paper_temperature(all.back());
    });
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
