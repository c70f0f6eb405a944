// The laws a material is built from, each declared once: its name, the material keys its constants
// are set by (unit, range, default, meaning) and its checks of them. The registry
// (src/laws/registry.cpp, with the laws of a kernel type of their own from laws.hpp) lists them, one
// line per law; the scene's key table, --keys, docs/keys.md, scene.txt, same_constants and the
// library's "without" marks all iterate it, so a new law's constants' keys and checks are declared in
// its own file under src/laws/ (its constants are its own struct, which the material holds by type).
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "mpmshock/material.hpp"
#include "mpmshock/units.hpp"

namespace mpmshock {

struct Scene;

// The values a key admits: lo .. hi, each end open or closed (every key's, scene.cpp).
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;

  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  // "> 0 m/s and <= 100000 m/s", for errors and --keys.
  std::string describe(std::string_view unit) const {
    const std::string u = unit.empty() ? "" : " " + std::string(unit);
    std::string out;
    if (lo > -std::numeric_limits<double>::infinity()) out += std::string(lo_open ? "> " : ">= ") + format_number(lo) + u;
    if (hi < std::numeric_limits<double>::infinity())
      out += std::string(out.empty() ? "" : " and ") + (hi_open ? "< " : "<= ") + format_number(hi) + u;
    return out;
  }
};
inline Bounds positive_bound() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
inline Bounds non_negative_bound() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
inline Bounds closed_bound(double lo, double hi) { return {lo, hi, false, false}; }
inline Bounds open_bound(double lo, double hi) { return {lo, hi, true, true}; }

// Where a key's value lives in a material: one of Material's own fields (&Material::density) or one of
// a law's constants (&TillotsonConstants::a, in the struct the material holds for the law).
template <class Member>
struct MemberOf;
template <class Owner, class Value>
struct MemberOf<Value Owner::*> {
  using owner = Owner;
  using value = Value;
};
template <auto Member, class M>  // M: Material or const Material
auto& field_at(M& m) {
  using Owner = typename MemberOf<decltype(Member)>::owner;
  if constexpr (std::is_same_v<Owner, Material>)
    return m.*Member;
  else
    return m.template law_constants<Owner>().*Member;
}
template <class Value>
struct FieldOf {
  Value& (*ref)(Material&);
  const Value& (*read)(const Material&);
  Value& operator()(Material& m) const { return ref(m); }
  const Value& operator()(const Material& m) const { return read(m); }
};
using NumberField = FieldOf<double>;
using FlagField = FieldOf<bool>;
// The field of a key: field<&Material::density>, field<&TillotsonConstants::a>.
template <auto Member>
inline constexpr FieldOf<typename MemberOf<decltype(Member)>::value> field{&field_at<Member, Material>,
                                                                          &field_at<Member, const Material>};

// A constant of a material as a scene sets it: bare for the scene's own material, material.NAME.KEY
// for a named one. A quantity (with dim and range) or an on/off flag.
struct MaterialKey {
  std::string name;
  Dimension dim = Dimension::none;
  Bounds range;
  std::string default_text;
  std::string meaning;
  std::variant<NumberField, FlagField> field;
  // A reference value rather than a constant of the law (Johnson-Cook's room temperature): without()
  // keeps it, so a material given the law's constants later need not give it too.
  bool reference = false;
};

// What a law's checks see of one material a body takes: the scene, the material, how the scene
// names its keys, and where a refusal goes (fail names the key).
struct MaterialCheck {
  const Scene& scene;
  const Material& material;
  std::string name;    // "scene" (the bare keys) or the NAME of material.NAME
  std::string prefix;  // "" or "material.NAME."
  std::function<void(const std::string& key, const std::string& message)> fail;
  // "the scene's own material (the bare keys)" or "material NAME", for messages.
  std::string named() const {
    return name == "scene" ? std::string("the scene's own material (the bare keys)") : "material " + name;
  }
};

// Which material key chooses a law: none (every material has it: density, c_v, elastic constants),
// equation_of_state, strength_model, or an effect of the scene (thermal_softening).
enum class LawSlot { always, equation_of_state, strength, softening };

struct MaterialLaw {
  LawSlot slot = LawSlot::always;
  std::string name;     // as its slot's key writes it (equation_of_state = tillotson): the material's word
  std::string summary;  // what choosing it means, for the slot key's meaning
  // The line --check's list of effects gives it where a body takes it ("" for none: the slot's
  // default law, or a law another line of the list already names).
  std::string effect;
  // A strength law with a flow stress of its own: how --check's plasticity line names it, and its
  // melt for the melting line ("" for the bilinear law, which Steinberg-Guinan softens and melts).
  std::string plasticity;
  std::function<std::string(const Material&)> melt;
  std::vector<MaterialKey> keys;
  // Beyond its slot's choice (takes(), below), whether the law acts on a body of this material in
  // this scene (Steinberg-Guinan: with thermal_softening = on, on the bilinear law's bodies).
  std::function<bool(const Scene&, const Material&)> used = [](const Scene&, const Material&) { return true; };
  // Refuses constants of one material that do not fit the law.
  std::function<void(const MaterialCheck&)> check = [](const MaterialCheck&) {};
  // Refuses scene settings the law cannot go with, once, if any body takes it; key: the key that
  // chose it (the first such material's strength_model, say).
  std::function<void(const Scene&, const std::string& key,
                     const std::function<void(const std::string&, const std::string&)>& fail)>
      check_scene = [](const Scene&, const std::string&, const auto&) {};
};

// The registry: every law a material can take, in the order their keys are listed (src/laws/registry.cpp).
const std::vector<MaterialLaw>& material_laws();
// Whether a body of material m takes the law in scene s: its slot's key names it (equation_of_state,
// strength_model; the other slots always) and the law's own condition holds (the checks run only then).
bool takes(const MaterialLaw& law, const Scene& s, const Material& m);
// The law of that name; throws std::logic_error if none.
const MaterialLaw& material_law(const std::string& name);
// The law a material's key of the slot names (equation_of_state, strength_model).
const MaterialLaw& law_of(LawSlot slot, const Material& m);
// The material with every constant of the law zeroed: how the library marks a material without the
// law's constants (tantalum has no Johnson-Cook ones), which the law's check then refuses.
Material without(const std::string& law, Material m);

}  // namespace mpmshock
