// The registry of material laws (src/laws/): every constant of Material is declared by exactly one
// law, each key reads and writes its own field through the scene, a law's "without" mark is what its
// check refuses, and each law's checks and scene checks reach the user under the key that chose it.
#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <set>
#include <utility>
#include <variant>
#include <string>

#include "check.hpp"
#include "mpmshock/material_law.hpp"
#include "mpmshock/laws.hpp"
#include "mpmshock/scene.hpp"

using namespace mpmshock;

static Scene parse(const std::string& text) { return parse_scene(text, "t.scene", {}); }

// The text of the SceneError a scene raises ("" if none).
static std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// The number of members of an aggregate: the most initializers T{...} takes (each converting to
// whatever the member is).
struct AnyField {
  template <class T>
  operator T() const {
    return T{};
  }
};
template <class T, std::size_t... I>
constexpr auto takes(std::index_sequence<I...>) -> decltype(T{(void(I), AnyField{})...}, true) {
  return true;
}
template <class T>
constexpr bool takes(...) {
  return false;
}
template <class T, std::size_t N = 1>
constexpr std::size_t field_count() {
  if constexpr (takes<T>(std::make_index_sequence<N>{}))
    return field_count<T, N + 1>();
  else
    return N - 1;
}

// Whether a law type keeps its constants in a struct of its own (Law::Constants).
template <class Law, class = void>
struct HasConstants : std::false_type {};
template <class Law>
struct HasConstants<Law, std::void_t<typename Law::Constants>> : std::true_type {};

// Whether `at` lies inside the object x.
template <class T>
bool inside(const char* at, const T& x) {
  const char* begin = reinterpret_cast<const char*>(&x);
  return at >= begin && at < begin + sizeof(T);
}

int main() {
  // Every field is one law's key: a field no law declares would be missed by same_constants, the
  // scene's keys, scene.txt and restart. Material is its two law choices (equation_of_state,
  // strength_model), the structs of the laws' own constants and the other keys' fields; each law's
  // struct is its keys' fields; each key a field of its own.
  std::set<std::string> names;
  std::set<const char*> fields;
  Material probe;  // each law's struct is stored in it as its keys reach it
  for (const MaterialLaw& law : material_laws())
    for (const MaterialKey& key : law.keys) {
      CHECK(names.insert(key.name).second);  // no key declared twice
      const char* at = std::visit([&](const auto& f) { return reinterpret_cast<const char*>(&f(probe)); }, key.field);
      CHECK(fields.insert(at).second);  // nor one field by two keys
    }
  auto count_inside = [&](const auto& x) {
    return static_cast<std::size_t>(std::count_if(fields.begin(), fields.end(), [&](const char* at) { return inside(at, x); }));
  };
  std::size_t in_laws = 0, law_types = 0;
  auto count_law = [&](auto tag) {
    using Law = std::remove_pointer_t<decltype(tag)>;
    // Every law of the kernels' lists is a law of the registry by its word.
    bool registered = false;
    for (const MaterialLaw& law : material_laws()) registered = registered || law.name == Law::kName;
    CHECK(registered);
    ++law_types;
    if constexpr (HasConstants<Law>::value) {
      const std::size_t n = count_inside(probe.law_constants<typename Law::Constants>());
      CHECK(n > 0 && n == field_count<typename Law::Constants>());
      in_laws += n;
    }
  };
  for_each_law<EquationOfStateLaw>(count_law);
  for_each_law<OwnStrengthLaw>(count_law);
  CHECK(law_types >= 3);
  const std::size_t own = count_inside(probe);
  CHECK(own + in_laws == fields.size());  // each key is Material's or a law's struct's
  static_assert(field_count<Material>() > 3);
  CHECK(field_count<Material>() == 3 + own);

  // Each slot's laws have words of their own.
  for (const LawSlot slot : {LawSlot::equation_of_state, LawSlot::strength}) {
    std::set<std::string> words;
    for (const MaterialLaw& law : material_laws())
      if (law.slot == slot) CHECK(words.insert(law.name).second);
  }

  // Each key sets its own field and no other (as the bare key and as material.NAME.KEY), and
  // same_constants sees each.
  for (const MaterialLaw& law : material_laws())
    for (const MaterialKey& key : law.keys) {
      const auto* field = std::get_if<NumberField>(&key.field);
      if (!field) {  // a flag: on, bare and named
        const FlagField flag = std::get<FlagField>(key.field);
        CHECK(!flag(Material{}));
        CHECK(flag(parse(key.name + " = on\n").material));
        CHECK(flag(parse("material.mine." + key.name + " = on\n").materials.at("mine")));
        continue;
      }
      Material base;
      // A value other than the default, inside the key's range.
      const double v0 = (*field)(base);
      double changed = v0;
      for (const double c : {v0 * 0.9, v0 * 1.1, 1.0})
        if (c != v0 && (key.range.lo_open ? c > key.range.lo : c >= key.range.lo) &&
            (key.range.hi_open ? c < key.range.hi : c <= key.range.hi)) {
          changed = c;
          break;
        }
      CHECK(changed != v0);
      const std::string value = format_number(changed);
      const Scene bare = parse(key.name + " = " + value + "\n");
      Material expected = base;
      (*field)(expected) = changed;
      CHECK(same_constants(bare.material, expected));
      CHECK(!same_constants(bare.material, base));
      const Scene named = parse("material.mine." + key.name + " = " + value + "\n");
      CHECK((*field)(named.materials.at("mine")) == changed);
    }

  // without(law) zeroes the law's constants (the library's mark of a material without them) and
  // keeps the reference values (Johnson-Cook's room temperature).
  const Material none = without("johnson_cook", without("tillotson", without("steinberg_guinan", Material{})));
  CHECK(!none.law_constants<JohnsonCookConstants>().present() && !none.law_constants<TillotsonConstants>().present() &&
        !none.has_softening());
  CHECK(none.law_constants<JohnsonCookConstants>().room_temperature == 298.0);
  CHECK(none.density == Material{}.density && none.yield_stress == Material{}.yield_stress);

  // The slot keys list their laws from the registry: an unknown word names every law of the slot.
  const std::string eos = error_of("equation_of_state = ideal_gas\n");
  CHECK(eos.find("mie_gruneisen") != std::string::npos && eos.find("tillotson") != std::string::npos);
  const std::string strength = error_of("strength_model = zerilli\n");
  CHECK(strength.find("bilinear") != std::string::npos && strength.find("johnson_cook") != std::string::npos);

  // A law's check runs for the materials bodies take, under the key that names the material's constant.
  const std::string no_jc = error_of(
      "flyer_material = tantalum\nmaterial.tantalum.strength_model = johnson_cook\nporosity = 1\n");
  CHECK(no_jc.find("material.tantalum.jc_yield_stress") != std::string::npos);
  // ... and not for a material no body takes.
  CHECK(error_of("material.tantalum.strength_model = johnson_cook\nporosity = 1\n").empty());
  // A law's scene check runs once however many bodies take it, named by the key that chose it for
  // the first: the bare key ...
  const std::string jc_paper = error_of(
      "strength_model = johnson_cook\ntemperature_model = paper\nporosity = 1\nflyer_material = copper\n");
  CHECK(jc_paper.find("t.scene:1: key 'strength_model': johnson_cook cannot go with temperature_model = paper") !=
        std::string::npos);
  CHECK(jc_paper.find("cannot go") == jc_paper.rfind("cannot go"));
  // ... or the material's own.
  const std::string jc_named = error_of(
      "flyer_material = copper\nmaterial.copper.strength_model = johnson_cook\ntemperature_model = paper\nporosity = 1\n");
  CHECK(jc_named.find("t.scene:2: key 'material.copper.strength_model': johnson_cook cannot go") != std::string::npos);
  // Steinberg-Guinan's check runs only with thermal_softening = on and a bilinear body.
  CHECK(!error_of("flyer_material = tantalum\ntarget_material = tantalum\nthermal_softening = on\nporosity = 1\n").empty());
  CHECK(error_of("flyer_material = tantalum\ntarget_material = tantalum\nporosity = 1\n").empty());
  return check::result();
}
