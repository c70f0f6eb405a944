// The registry of material laws: one line per law, in the order their keys are listed (--keys) and
// their checks run. A new law is its file in this folder (its keys and checks) and its line in
// src/CMakeLists.txt, its line and declaration here, its constants' fields in material.hpp, its
// physics in its header (eos.hpp, tillotson.hpp, ...) and its test (docs/adding-an-effect.md).
#include <stdexcept>

#include "mpmshock/material_law.hpp"

namespace mpmshock {

// Each law's declaration, in its own file here (src/laws/NAME.cpp).
MaterialLaw solid_law();
MaterialLaw mie_gruneisen_law();
MaterialLaw tillotson_law();
MaterialLaw bilinear_law();
MaterialLaw johnson_cook_law();
MaterialLaw steinberg_guinan_law();

const std::vector<MaterialLaw>& material_laws() {
  static const std::vector<MaterialLaw> laws = {
      solid_law(),
      bilinear_law(),
      steinberg_guinan_law(),
      johnson_cook_law(),
      mie_gruneisen_law(),
      tillotson_law(),
  };
  return laws;
}

bool takes(const MaterialLaw& law, const Scene& s, const Material& m) {
  switch (law.slot) {
    case LawSlot::equation_of_state:
      if (static_cast<int>(m.equation_of_state) != law.choice) return false;
      break;
    case LawSlot::strength:
      if (static_cast<int>(m.strength_model) != law.choice) return false;
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

Material without(const std::string& name, Material m) {
  for (const MaterialKey& key : material_law(name).keys) {
    if (key.reference) continue;
    if (const auto* field = std::get_if<double Material::*>(&key.field))
      m.*(*field) = 0.0;
    else
      m.*std::get<bool Material::*>(key.field) = false;
  }
  return m;
}

bool same_constants(const Material& a, const Material& b) {
  if (a.equation_of_state != b.equation_of_state || a.strength_model != b.strength_model) return false;
  for (const MaterialLaw& law : material_laws())
    for (const MaterialKey& key : law.keys) {
      const bool same = std::visit([&](auto field) { return a.*field == b.*field; }, key.field);
      if (!same) return false;
    }
  return true;
}

}  // namespace mpmshock
