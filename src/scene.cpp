#include "mpmshock/scene.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <utility>
#include <variant>

#include "mpmshock/material_law.hpp"
#include "mpmshock/mixed_equation_of_state.hpp"
#include "mpmshock/units.hpp"

namespace mpmshock {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A scene file is a page of text: anything much larger is not one (`mpmshock /dev/zero`).
constexpr std::size_t kMaxSceneBytes = 1 << 20;
constexpr std::size_t kMaxLineBytes = 4096;
constexpr std::size_t kMaxKeyLength = 64;

// Text from the input as a message quotes it: at most 60 characters.
std::string excerpt(const std::string& text) {
  if (text.size() <= 60) return "'" + text + "'";
  return "'" + text.substr(0, 50) + "...' (" + std::to_string(text.size()) + " characters)";
}

// Where a value came from: a file line or a --set argument.
struct Origin {
  std::string where;  // "scene.cfg:12" or "--set"
};

SceneError error_at(const Origin& at, const std::string& key, const std::string& message) {
  return SceneError(at.where + ": key '" + key + "': " + message);
}

// Every error of a scene, reported at once in the order of its lines (the file's, then --set's), as
// a compiler reports them: one line each, each naming the file, line and key.
class SceneErrors {
 public:
  void add(const Origin& at, const std::string& message) { errors_.emplace_back(order_of(at.where), message); }
  // Runs f, keeping the SceneError it throws instead of passing it on.
  template <class F>
  void collect(const Origin& at, F&& f) {
    try {
      f();
    } catch (const SceneError& e) {
      add(at, e.what());
    }
  }
  bool empty() const { return errors_.empty(); }
  void throw_if_any() const {
    if (errors_.empty()) return;
    std::vector<std::pair<long, std::string>> sorted = errors_;
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    constexpr std::size_t kMost = 20;
    std::string text;
    for (std::size_t k = 0; k < std::min(sorted.size(), kMost); ++k) text += (k ? "\n" : "") + sorted[k].second;
    if (sorted.size() > kMost) text += "\n... and " + std::to_string(sorted.size() - kMost) + " more errors";
    throw SceneError(text);
  }

 private:
  // "NAME:LINE" by its line, then "--set #I" by I, then the rest ("defaults").
  static long order_of(const std::string& where) {
    if (where.rfind("--set #", 0) == 0) return 1000000000L + std::atol(where.c_str() + 7);
    const auto colon = where.rfind(':');
    if (colon != std::string::npos && colon + 1 < where.size() &&
        where.find_first_not_of("0123456789", colon + 1) == std::string::npos)
      return std::atol(where.c_str() + colon + 1);
    return 2000000000L;
  }
  std::vector<std::pair<long, std::string>> errors_;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n\f\v");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n\f\v");
  return s.substr(b, e - b + 1);
}

// A key's range: the one type the material laws' keys declare theirs with (material_law.hpp).
using Range = Bounds;
Range positive() { return positive_bound(); }
Range non_negative() { return non_negative_bound(); }
Range open(double lo, double hi) { return open_bound(lo, hi); }
Range closed(double lo, double hi) { return closed_bound(lo, hi); }

enum class Kind { quantity, integer, flag, text, choice, times };

struct Key {
  std::string name;
  Kind kind = Kind::quantity;
  Dimension dim = Dimension::none;
  Range range;
  std::string default_text;
  std::string meaning;
  std::string choices;  // for Kind::choice and flags: "musl|usl"
  std::function<void(Scene&, const std::string& text, const Origin&)> set;
  std::function<std::string(const Scene&)> get;  // resolved value, SI
  bool material = false;  // a constant of the material (Scene::material), also set as material.NAME.KEY
};

// What every key has: its name, kind, default and meaning.
Key describe_key(Kind kind, const std::string& name, std::string def, std::string meaning) {
  Key k;
  k.name = name;
  k.kind = kind;
  k.default_text = std::move(def);
  k.meaning = std::move(meaning);
  return k;
}

template <class Ref>
Key quantity(std::string name, Dimension dim, Range range, std::string def, std::string meaning,
             Ref ref) {
  Key k = describe_key(Kind::quantity, name, std::move(def), std::move(meaning));
  k.dim = dim;
  k.range = range;
  k.set = [name, dim, range, ref](Scene& s, const std::string& text, const Origin& at) {
    double v = 0.0;
    try {
      v = parse_quantity(text, dim);
    } catch (const std::invalid_argument& e) {
      throw error_at(at, name, e.what());
    }
    if (!range.contains(v)) {
      const std::string unit(si_unit(dim));
      throw error_at(at, name,
                     "value " + format_number(v) + (unit.empty() ? "" : " " + unit) + " is out of range: must be " +
                         range.describe(unit));
    }
    ref(s) = v;
  };
  k.get = [dim, ref](const Scene& s) {
    const std::string unit(si_unit(dim));
    return format_number(ref(s)) + (unit.empty() ? "" : " " + unit);
  };
  return k;
}

// A comma-separated list of increasing positive times ("250 ns, 750 ns"), or "none".
template <class Ref>
Key times(std::string name, std::string meaning, Ref ref) {
  Key k = describe_key(Kind::times, name, "none", std::move(meaning));
  k.dim = Dimension::time;
  k.set = [name, ref](Scene& s, const std::string& text, const Origin& at) {
    std::vector<double> values;
    if (text != "none") {
      std::size_t start = 0;
      while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        double t = 0.0;
        try {
          t = parse_quantity(item, Dimension::time);
        } catch (const std::invalid_argument& e) {
          throw error_at(at, name, "'" + item + "': " + e.what() + " (a list is '250 ns, 750 ns', or none)");
        }
        if (!(t > 0.0)) throw error_at(at, name, "time " + format_number(t) + " s must be > 0");
        if (!values.empty() && !(t > values.back()))
          throw error_at(at, name, "times must increase (" + format_number(t) + " s follows " +
                                       format_number(values.back()) + " s)");
        values.push_back(t);
        start = comma + 1;
      }
    }
    ref(s) = values;
  };
  k.get = [ref](const Scene& s) {
    std::string out;
    for (double t : ref(s)) out += (out.empty() ? "" : ", ") + format_number(t) + " s";
    return out.empty() ? std::string("none") : out;
  };
  return k;
}

template <class Ref>
Key integer(std::string name, Range range, std::string def, std::string meaning, Ref ref) {
  Key k = describe_key(Kind::integer, name, std::move(def), std::move(meaning));
  k.range = range;
  k.set = [name, range, ref](Scene& s, const std::string& text, const Origin& at) {
    std::int64_t v = 0;
    const char* first = text.data();
    const char* last = text.data() + text.size();
    if (first != last && *first == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::result_out_of_range) throw error_at(at, name, "'" + text + "' is too large for an integer");
    if (ec != std::errc() || ptr != last || first == last)
      throw error_at(at, name, "'" + text + "' is not a whole number");
    if (!range.contains(static_cast<double>(v)))
      throw error_at(at, name, "value " + text + " is out of range: must be " + range.describe(""));
    ref(s) = v;
  };
  k.get = [ref](const Scene& s) { return std::to_string(ref(s)); };
  return k;
}

template <class Ref>
Key flag(std::string name, std::string def, std::string meaning, Ref ref) {
  Key k = describe_key(Kind::flag, name, std::move(def), std::move(meaning));
  k.choices = "on|off";
  k.set = [name, ref](Scene& s, const std::string& text, const Origin& at) {
    if (text == "on" || text == "yes" || text == "true") {
      ref(s) = true;
    } else if (text == "off" || text == "no" || text == "false") {
      ref(s) = false;
    } else {
      throw error_at(at, name, "'" + text + "' is not on or off");
    }
  };
  k.get = [ref](const Scene& s) { return std::string(ref(s) ? "on" : "off"); };
  return k;
}

template <class Ref>
Key text(std::string name, std::string def, std::string meaning, Ref ref) {
  Key k = describe_key(Kind::text, name, std::move(def), std::move(meaning));
  k.set = [ref](Scene& s, const std::string& value, const Origin&) { ref(s) = value; };
  k.get = [ref](const Scene& s) { return ref(s); };
  return k;
}

template <class Enum, class Ref>
Key choice(std::string name, std::vector<std::pair<std::string, Enum>> options, std::string def,
           std::string meaning, Ref ref) {
  Key k = describe_key(Kind::choice, name, std::move(def), std::move(meaning));
  for (const auto& [word, value] : options) k.choices += (k.choices.empty() ? "" : "|") + word;
  k.set = [name, options, ref](Scene& s, const std::string& value, const Origin& at) {
    for (const auto& [word, e] : options) {
      if (word == value) {
        ref(s) = e;
        return;
      }
    }
    std::string list;
    for (const auto& [word, e] : options) list += (list.empty() ? "" : ", ") + word;
    throw error_at(at, name, "'" + value + "' is not one of " + list);
  };
  k.get = [options, ref](const Scene& s) {
    for (const auto& [word, e] : options)
      if (e == ref(s)) return word;
    return std::string("?");
  };
  return k;
}

#define FIELD(member) [](auto& s) -> auto& { return s.member; }

// The key that chooses a law of the slot: a material key (equation_of_state, strength_model), the
// scene's effect (thermal_softening), or none (every material has the law).
std::string choosing_key(LawSlot slot) {
  switch (slot) {
    case LawSlot::equation_of_state: return "equation_of_state";
    case LawSlot::strength: return "strength_model";
    case LawSlot::softening: return "thermal_softening";
    case LawSlot::always: break;
  }
  return "";
}

// Whether the law comes first of its slot's in the registry: the slot's default, and where --keys
// lists the slot's choosing key.
bool first_of_its_slot(const MaterialLaw& law) {
  for (const MaterialLaw& l : material_laws())
    if (l.slot == law.slot) return &l == &law;
  return false;
}

// The key that chooses a material's law of a slot (equation_of_state, strength_model): its words and
// their meanings from the registry; the default is the slot's first law.
template <class Enum>
Key slot_key(LawSlot slot, const std::string& intro, const std::string& tail, Enum Material::*field) {
  std::vector<std::pair<std::string, Enum>> options;
  std::string meaning;
  for (const MaterialLaw& law : material_laws()) {
    if (law.slot != slot) continue;
    options.emplace_back(law.name, law.name);
    meaning += (meaning.empty() ? "" : "; ") + law.summary;
  }
  const std::string def = options.front().first;
  return choice<Enum>(choosing_key(slot), std::move(options), def, intro + meaning + tail,
                      [field](auto& s) -> auto& { return s.material.*field; });
}

// The material keys, from the registry of laws (src/laws/registry.cpp): each law's constants, the
// key that chooses a slot's law before the slot's first.
void append_material_keys(std::vector<Key>& k) {
  const std::size_t first = k.size();
  for (const MaterialLaw& law : material_laws()) {
    if (law.slot == LawSlot::equation_of_state && first_of_its_slot(law))
      k.push_back(slot_key(law.slot, "", "; each body takes its own material's", &Material::equation_of_state));
    if (law.slot == LawSlot::strength && first_of_its_slot(law))
      k.push_back(slot_key(law.slot, "the flow stress of plasticity: ",
                           "; each body takes its material's; a named material without its own "
                           "material.NAME.strength_model takes the bare key's",
                           &Material::strength_model));
    for (const MaterialKey& mk : law.keys) {
      if (const auto* field = std::get_if<NumberField>(&mk.field)) {
        k.push_back(quantity(mk.name, mk.dim, mk.range, mk.default_text, mk.meaning,
                             [f = *field](auto& s) -> auto& { return f(s.material); }));
      } else {
        k.push_back(flag(mk.name, mk.default_text, mk.meaning,
                         [f = std::get<FlagField>(mk.field)](auto& s) -> auto& { return f(s.material); }));
      }
    }
  }
  for (std::size_t i = first; i < k.size(); ++i) k[i].material = true;
}

const std::vector<Key>& keys() {
  static const std::vector<Key> table = [] {
    using D = Dimension;
    std::vector<Key> k;
    // Impact
    k.push_back(quantity("velocity", D::speed, Range{0.0, 1e5, true, false}, "1000 m/s",
                         "each body moves at this speed toward the impact plane y = 0 (target down, flyer up)",
                         FIELD(velocity)));
    k.push_back(quantity("flyer_velocity", D::speed, Range{0.0, 1e5, false, false}, "auto",
                         "the flyer's speed toward the impact plane (up); auto = velocity", FIELD(flyer_velocity)));
    k.push_back(quantity("target_velocity", D::speed, Range{0.0, 1e5, false, false}, "auto",
                         "the target's speed toward the impact plane (down); auto = velocity; 0: the laboratory "
                         "frame, the target at rest", FIELD(target_velocity)));
    k.push_back(quantity("porosity", D::none, closed(1.0, 10.0), "1.03",
                         "delta = rho_solid / rho_porous of the target (and of the flyer unless flyer_porosity is "
                         "set); 1 means solid, no voids", FIELD(porosity)));
    k.push_back(quantity("flyer_porosity", D::none, closed(1.0, 10.0), "auto",
                         "delta of the flyer; auto = porosity (1: a solid flyer on a porous target)",
                         FIELD(flyer_porosity)));
    k.push_back(text("flyer_material", "scene",
                     "the flyer's material: scene (the bare material keys below), a built-in one (mpmshock "
                     "--materials: aluminium, copper, tantalum, lif, pmma) or one material.NAME.KEY keys define",
                     FIELD(flyer_material)));
    k.push_back(text("target_material", "scene", "the target's material, as flyer_material",
                     FIELD(target_material)));
    k.push_back(quantity("window_height", D::length, non_negative(), "0 m",
                         "a window of window_material bonded to the target's free surface, this thick (solid, moving "
                         "with the target); probe.NAME = surface then follows the sample-window interface, as a "
                         "VISAR through the window; 0: none",
                         FIELD(window_height)));
    k.push_back(text("window_material", "lif", "the window's material, as flyer_material (with window_height > 0)",
                     FIELD(window_material)));
    k.push_back(quantity("void_radius", D::length, positive(), "50 um", "mean void radius",
                         FIELD(void_radius)));
    k.push_back(quantity("void_radius_spread", D::length, non_negative(), "0 m",
                         "void radii are uniform in [void_radius - spread, void_radius + spread]",
                         FIELD(void_radius_spread)));
    k.push_back(quantity("void_min_gap", D::length, non_negative(), "0 m",
                         "smallest ligament kept between two voids (when void_overlap = off)", FIELD(void_min_gap)));
    k.push_back(flag("void_overlap", "off", "allow voids to overlap", FIELD(void_overlap)));
    k.push_back(flag("flyer_mirror", "on",
                     "the flyer is the mirror image of the target about y = 0, as in the paper; off: its own voids",
                     FIELD(flyer_mirror)));
    k.push_back(choice<Symmetry>(
        "symmetry", {{"auto", Symmetry::automatic}, {"on", Symmetry::on}, {"off", Symmetry::off}}, "auto",
        "on: simulate the target alone, with a symmetry plane at y = 0 (no normal velocity, no shear traction), "
        "the flyer its mirror image in every output: half the cost; auto: on whenever the flyer is the target's "
        "mirror image",
        FIELD(symmetry)));
    k.push_back(quantity("target_height", D::length, Range{0.0, 10.0, true, false}, "5 mm", "target (upper body) height",
                         FIELD(target_height)));
    k.push_back(quantity("flyer_height", D::length, Range{0.0, 10.0, true, false}, "5 mm", "flyer (lower body) height",
                         FIELD(flyer_height)));
    k.push_back(quantity("width", D::length, Range{0.0, 10.0, true, false}, "2 mm", "width of the periodic column (x)",
                         FIELD(width)));
    k.push_back(choice<int>("dimension", {{"2", 2}, {"3", 3}}, "2",
                            "2: plane strain in x, y (per metre of depth); 3: a column periodic in x and z, "
                            "spherical voids",
                            FIELD(dimension)));
    k.push_back(quantity("depth", D::length, Range{0.0, 10.0, true, false}, "auto",
                         "z extent of the periodic column in 3D (dimension = 3); auto = width",
                         FIELD(depth)));
    // Discretisation
    k.push_back(quantity("cell_size", D::length, Range{0.0, 1.0, true, false}, "20 um", "background grid cell size h",
                         FIELD(cell_size)));
    k.push_back(integer("particles_per_cell", closed(1, 8), "2",
                        "material points per cell in each direction", FIELD(particles_per_cell)));
    k.push_back(quantity("grid_margin", D::length, closed(0.0, 10.0), "auto",
                         "empty grid kept beyond each free surface; auto = 8 cells + 2 velocity end_time",
                         FIELD(grid_margin)));
    k.push_back(quantity("end_time", D::time, Range{0.0, 1.0, true, false}, "1 us", "simulated time to run",
                         FIELD(end_time)));
    k.push_back(quantity("cfl", D::none, open(0.0, 1.0), "auto",
                         "time step = cfl h / (fastest signal: sound speed + viscous speed + particle speed); "
                         "auto = 0.6 with bspline2_domain (0.8 where artificial viscosity is on with av_linear >= 0.6, as in every "
                         "solid scene: its viscous speed already slows the step), 0.3 with the other shapes (larger steps cost "
                         "accuracy: docs/stability.md)",
                         FIELD(cfl)));
    k.push_back(quantity("max_volume_change", D::none, Range{0.0, kInf, true, true}, "0.02",
                         "the time step is also at most this over the fastest rate of volume change |tr D| a "
                         "point had in the step before: no point's volume changes by much more than this share in "
                         "one step (a collapsing void's jet; docs/stability.md); 1e9 turns the limit off",
                         FIELD(max_volume_change)));
    k.push_back(choice<UpdateScheme>("update_scheme", {{"musl", UpdateScheme::musl}, {"usl", UpdateScheme::usl}}, "musl",
                                     "musl: stress from the re-mapped velocity, energy from the exact work of the forces (conserved); usl: classic",
                                     FIELD(update_scheme)));
    k.push_back(choice<ShapeFunction>("shape_function", {{"bilinear", ShapeFunction::bilinear}, {"gimp", ShapeFunction::gimp}, {"bspline2", ShapeFunction::bspline2}, {"bspline2_domain", ShapeFunction::bspline2_domain}},
        "bspline2_domain",
        "bspline2 and gimp (3 x 3 nodes) remove most grid-crossing noise; bspline2_domain, the B-spline averaged "
        "over each point's domain (4 x 4 nodes, 1.45x the cost per point-step), also the noise of compressed "
        "material moving across the grid (laboratory frame: the strength state behind the shock; docs/accuracy-and-cost.md); "
        "bilinear: the paper's 4-node cells",
        FIELD(shape_function)));
    k.push_back(quantity("flip_fraction", D::none, closed(0.0, 1.0), "1",
                         "point velocity = f FLIP + (1 - f) PIC: 1 conserves energy to round-off but keeps point-to-point "
                         "velocity noise; below 1 damps the noise, its kinetic energy becoming heat; not energy-consistent "
                         "in jetting porous flows (docs/method.md)",
                         FIELD(flip_fraction)));
    k.push_back(flag("skip_unreached", "on",
                     "advance material nothing has reached yet (ahead of the fastest signal) in closed form, "
                     "x += v0 dt, leaving it out of the transfers; off: compute it (the same to round-off)",
                     FIELD(skip_unreached)));
    k.push_back(choice<Smoothing>(
        "volumetric_smoothing", {{"auto", Smoothing::automatic}, {"on", Smoothing::on}, {"off", Smoothing::off}}, "auto",
        "each point's rate of volume change from the grid's mass-weighted field of it, so the points of a cell "
        "compress together and no single point is over-compressed (collapse foci); auto = on where a body is "
        "porous, off where every body is solid (it spoils a solid plate's elastic-plastic plateau): "
        "docs/method.md",
        FIELD(volumetric_smoothing)));
    k.push_back(quantity("av_linear", D::none, non_negative(), "auto",
                         "linear artificial viscosity coefficient A1; auto = 0.6 where every body is solid (the exact "
                         "elastic-plastic two-wave state behind the shock, tests/test_two_wave.cpp; 0.2 rings it below "
                         "yield), 0.2 where a body is porous (its temperatures nearer their converged values): "
                         "docs/method.md", FIELD(av_linear)));
    k.push_back(quantity("av_quadratic", D::none, non_negative(), "2",
                         "quadratic artificial viscosity coefficient A2", FIELD(av_quadratic)));
    k.push_back(quantity("av_heat_flux", D::none, closed(0.0, 100.0), "10",
                         "artificial heat flux coefficient beta (Noh): where the viscosity acts, heat is conducted "
                         "with diffusivity beta h q / (rho c0), against the excess heating where converging flows "
                         "stagnate (void-collapse foci); 0: none (needs thermal = on)",
                         FIELD(av_heat_flux)));
    k.push_back(integer("seed", closed(0, 9.0e18), "1", "random seed of the void layout",
                        FIELD(seed)));
    // Effects
    k.push_back(flag("plasticity", "on",
                     "von Mises strength with mixed hardening; off: hydrodynamic, no deviatoric stress",
                     FIELD(effects.plasticity)));
    k.push_back(flag("thermal", "on", "temperatures by temperature_model; off: no temperature is computed",
                     FIELD(effects.thermal)));
    k.push_back(choice<TemperatureModel>(
        "temperature_model", {{"energy", TemperatureModel::energy}, {"paper", TemperatureModel::paper}}, "energy",
        "energy: T = T_H(V) + (E - E_H(V))/c_v, all the heat in E (compaction, shock and plastic work); paper: "
        "T = T_H(V) + (plastic work)/c_v, without the compaction heating of collapsing voids, which is what the "
        "paper's reported temperatures fit (a diagnostic: not with heat_conduction or thermal_softening)",
        FIELD(temperature_model)));
    k.push_back(flag("paper_temperature", "off",
                     "also report temperature_model = paper's temperature beside the energy model's, from the same "
                     "run (regions.csv paper_temperature_mean/std, probes.csv and snapshot paper_temperature): "
                     "both models for the cost of one run; the run itself is unchanged",
                     FIELD(paper_temperature)));
    k.push_back(flag("spall", "off",
                     "failure in tension: a point in tension whose neighbourhood's largest principal stress "
                     "reaches spall_strength (spall_criterion) opens with its tension held at the strength and no "
                     "shear, and separates (no tension) once its void fraction reaches spall_void_fraction",
                     FIELD(effects.spall)));
    k.push_back(quantity("spall_strength", D::pressure, Range{0.0, 1e12, true, false}, "1.2 GPa",
                         "spall strength (aluminium alloys: 1.0-1.6 GPa at 1e4-1e6 /s)", FIELD(spall_strength)));
    k.push_back(quantity("spall_void_fraction", D::none, Range{0.0, 1.0, false, true}, "0.15",
                         "void fraction 1 - J_f/J at which an opening point separates (0: at once; 0.15: void "
                         "coalescence in ductile metals)",
                         FIELD(spall_void_fraction)));
    k.push_back(choice<SpallCriterion>("spall_criterion",
                       {{"neighbourhood", SpallCriterion::neighbourhood}, {"point", SpallCriterion::point}},
                       "neighbourhood",
                       "what reaches spall_strength: neighbourhood, the mass-weighted mean of the largest principal "
                       "stress over the point's stencil (a point-to-point stress pattern does not fail material "
                       "whose mean is not in tension); point, the point's own",
                       FIELD(spall_criterion)));
    k.push_back(quantity("spall_point_ceiling", D::none, Range{1.0, 1e6, true, false}, "2",
                         "with spall_criterion = neighbourhood: the point's own largest principal stress, in units of "
                         "spall_strength, that opens it whatever its neighbourhood holds (a point at a void's rim "
                         "stretched while the material around it is compressed)",
                         FIELD(spall_point_ceiling)));
    k.push_back(flag("heat_conduction", "off",
                     "Fourier heat conduction between points through the grid, with thermal_conductivity "
                     "(needs thermal = on)",
                     FIELD(effects.heat_conduction)));
    k.push_back(flag("thermal_softening", "off",
                     "Steinberg-Guinan: shear modulus and yield stress scaled by 1 + P J^(1/3) / "
                     "pressure_hardening_scale - (T - 300 K) / (softening_temperature - 300 K), the yield capped "
                     "at yield_stress_max, both zero in the melt, which takes latent_heat, each body with its "
                     "material's constants (built in: aluminium 6061-T6, copper, LiF); needs plasticity and thermal on",
                     FIELD(effects.thermal_softening)));
    k.push_back(quantity("taylor_quinney", D::none, closed(0.0, 1.0), "1",
                         "share of plastic work that becomes heat; the rest is stored as cold work",
                         FIELD(taylor_quinney)));
    k.push_back(flag("artificial_viscosity", "on", "shock-capturing bulk viscosity in compression",
                     FIELD(effects.artificial_viscosity)));
    // Material (the paper's aluminium): the material named "scene"; material.NAME.KEY sets the same
    // keys of a named material.
    append_material_keys(k);
    // Output
    k.push_back(text("output_dir", "output", "directory for regions.csv, snapshots and the summary (no control characters, no '#')",
                     FIELD(output_dir)));
    k.push_back(quantity("sample_interval", D::time, positive(), "10 ns",
                         "simulated time between rows of regions.csv and conservation.csv", FIELD(sample_interval)));
    k.push_back(quantity("snapshot_interval", D::time, non_negative(), "100 ns",
                         "simulated time between HDF5 snapshots; 0: only the first and the last",
                         FIELD(snapshot_interval)));
    k.push_back(times("snapshot_times",
                      "further snapshots at these times, e.g. 250 ns, 750 ns (beside snapshot_interval; 0 there "
                      "and a list here writes the first, the listed and the last)",
                      FIELD(snapshot_times)));
    k.push_back(quantity("probe_interval", D::time, non_negative(), "0 s",
                         "time between rows of probes.csv (probe.NAME keys); 0: every step", FIELD(probe_interval)));
    k.push_back(integer("snapshot_compression", closed(0, 9), "0",
                        "gzip level for every snapshot field (slower, ~1/3 smaller); 0: only id, body, mass",
                        FIELD(snapshot_compression)));
    k.push_back(flag("snapshot_grid", "off", "also write the grid's nodal mass and velocity",
                     FIELD(snapshot_grid)));
    return k;
  }();
  return table;
}
#undef FIELD

const Key* find_key(const std::string& name) {
  for (const Key& k : keys())
    if (k.name == name) return &k;
  return nullptr;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(const std::string& name) {
  const Key* best = nullptr;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const Key& k : keys()) {
    const std::size_t d = edit_distance(name, k.name);
    if (d < best_d) {
      best_d = d;
      best = &k;
    }
  }
  if (best && best_d <= std::max<std::size_t>(2, name.size() / 3)) return "; did you mean '" + best->name + "'?";
  return "";
}

bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t n = 0;
    if (c < 0x80) n = 0;
    else if ((c & 0xE0) == 0xC0 && c >= 0xC2) n = 1;
    else if ((c & 0xF0) == 0xE0) n = 2;
    else if ((c & 0xF8) == 0xF0 && c <= 0xF4) n = 3;
    else return false;
    if (n > 0 && i + n >= s.size()) return false;  // truncated sequence
    for (std::size_t k = 1; k <= n; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return false;
    i += n + 1;
  }
  return true;
}

constexpr const char* kKeyNameRule =
    " (a key name is ASCII letters, digits, '_', '.' and '-', as in region.T800 or probe.rear_1)";

bool valid_key_name(const std::string& key) {
  if (key.empty() || key.size() > kMaxKeyLength) return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-';
  });
}

// A path must read back from scene.txt as it was written: no control characters (a newline would
// end the line) and no '#' (it would start a comment).
void check_path(const Origin& at, const std::string& key, const std::string& path) {
  for (char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      throw error_at(at, key, "the path has a control character (byte " + std::to_string(u) + "); choose another name");
    if (c == '#') throw error_at(at, key, "the path has a '#', which starts a comment in scene files; choose another name");
  }
}

struct Entry {
  std::string key, value;
  Origin at;
};

// The value of a spec key (region.NAME, probe.NAME): its first word names the kind, the rest are
// lengths, "100 um" style, a word that is only a unit joining the number before it.
struct SpecWords {
  std::string kind;
  std::vector<std::string> args;
};
SpecWords spec_words(const std::string& value) {
  std::istringstream words(plain_spacing(value));
  SpecWords out;
  words >> out.kind;
  for (std::string t; words >> t;) {
    const bool starts_numeric =
        std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '.' || t[0] == '-' || t[0] == '+';
    if (!starts_numeric && !out.args.empty()) out.args.back() += " " + t;
    else out.args.push_back(t);
  }
  return out;
}

// A length argument of a spec key; a bad one is an error naming the key.
double spec_length(const Entry& e, const std::string& text) {
  try {
    return parse_quantity(text, Dimension::length);
  } catch (const std::invalid_argument& ex) {
    throw error_at(e.at, e.key, ex.what());
  }
}

// A region key: region.NAME = bottom Y1 H | top H | band Y1 Y2.
RegionSpec parse_region(const Entry& e) {
  RegionSpec r;
  r.name = e.key.substr(std::string("region.").size());
  if (r.name.empty()) throw error_at(e.at, e.key, "a region needs a name: region.NAME = ...");
  const auto [kind, args] = spec_words(e.value);
  auto length = [&](const std::string& t) { return spec_length(e, t); };
  if (kind == "bottom" && args.size() == 2) {
    r.kind = RegionSpec::Kind::bottom;
    r.a = length(args[0]);
    r.b = length(args[1]);
    if (!(r.b > 0)) throw error_at(e.at, e.key, "the height must be > 0");
  } else if (kind == "top" && args.size() == 1) {
    r.kind = RegionSpec::Kind::top;
    r.b = length(args[0]);
    if (!(r.b > 0)) throw error_at(e.at, e.key, "the height must be > 0");
  } else if (kind == "band" && args.size() == 2) {
    r.kind = RegionSpec::Kind::band;
    r.a = length(args[0]);
    r.b = length(args[1]);
    if (!(r.b > r.a)) throw error_at(e.at, e.key, "a band needs y2 > y1");
  } else {
    throw error_at(e.at, e.key, "expected 'bottom Y1 HEIGHT', 'top HEIGHT' or 'band Y1 Y2', got '" + e.value + "'");
  }
  return r;
}

// A probe key: probe.NAME = surface | point X Y [Z].
ProbeSpec parse_probe(const Entry& e) {
  ProbeSpec p;
  p.name = e.key.substr(std::string("probe.").size());
  if (p.name.empty()) throw error_at(e.at, e.key, "a probe needs a name: probe.NAME = ...");
  const auto [kind, args] = spec_words(e.value);
  if (kind == "surface" && args.empty()) {
    p.kind = ProbeSpec::Kind::surface;
  } else if (kind == "point" && (args.size() == 2 || args.size() == 3)) {
    p.kind = ProbeSpec::Kind::point;
    p.x = spec_length(e, args[0]);
    p.y = spec_length(e, args[1]);
    if (args.size() == 3) {
      p.z = spec_length(e, args[2]);
      if (!(p.z >= 0.0)) throw error_at(e.at, e.key, "Z must be >= 0 (the column spans z in [0, depth))");
    }
  } else {
    throw error_at(e.at, e.key, "expected 'surface', 'point X Y' or, in 3D, 'point X Y Z', got '" + e.value + "'");
  }
  return p;
}

// Lines of a scene file as entries; syntax errors name the file and line.
// Lines end at \n, \r\n or a lone \r (old Mac files).
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n' && text[i] != '\r') continue;
    lines.push_back(text.substr(start, i - start));
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    start = i + 1;
  }
  if (start < text.size()) lines.push_back(text.substr(start));
  return lines;
}

std::vector<Entry> read_entries(const std::string& text, const std::string& name, SceneErrors& errors) {
  std::vector<Entry> out;
  int number = 0;
  for (std::string line : split_lines(text)) {
    ++number;
    const Origin at{name + ":" + std::to_string(number)};
    if (line.size() > kMaxLineBytes) {
      errors.add(at, at.where + ": the line is " + std::to_string(line.size()) + " bytes long; a scene line has at most " +
                         std::to_string(kMaxLineBytes));
      continue;
    }
    if (!valid_utf8(line)) {
      errors.add(at, at.where + ": the line has bytes that are not UTF-8 text");
      continue;
    }
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    line = trim(line);
    if (line.empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) {
      errors.add(at, at.where + ": expected 'key = value', got " + excerpt(line));
      continue;
    }
    Entry e{trim(line.substr(0, eq)), trim(line.substr(eq + 1)), at};
    if (e.key.empty()) errors.add(at, at.where + ": a key is missing before '='");
    else if (!valid_key_name(e.key)) errors.add(at, at.where + ": " + excerpt(e.key) + " is not a key name" + kKeyNameRule);
    else if (e.value.empty()) errors.add(at, error_at(at, e.key, "missing value").what());
    else out.push_back(std::move(e));
  }
  return out;
}

}  // namespace

std::string override_key(const std::string& arg) { return trim(arg.substr(0, arg.find('='))); }

std::vector<std::string> scene_warnings(const Scene& s) {
  std::vector<std::string> out;
  const double cfl_auto = auto_cfl(s);
  if (s.cfl > cfl_auto)
    out.push_back("cfl " + format_number(s.cfl) + " > " + format_number(cfl_auto) + " (the automatic value for "
                  "this shape_function and viscosity): fewer steps, larger errors (an isentropic release heats about twice "
                  "as much at twice the step: docs/stability.md)");
  if (s.snapshot_interval > 0.0 && s.end_time / s.snapshot_interval > 1000)
    out.push_back("snapshot_interval " + format_number(s.snapshot_interval) + " s writes " +
                  format_number(std::floor(s.end_time / s.snapshot_interval)) + " snapshot files");
  const auto late = std::count_if(s.snapshot_times.begin(), s.snapshot_times.end(),
                                  [&](double t) { return t > s.end_time * (1.0 + 1e-12); });
  if (late > 0)
    out.push_back("snapshot_times: " + std::to_string(late) + " of them after end_time " + format_number(s.end_time) +
                  " s will not be written");
  if (s.end_time / s.sample_interval > 100000)
    out.push_back("sample_interval " + format_number(s.sample_interval) + " s writes " +
                  format_number(std::floor(s.end_time / s.sample_interval)) + " rows per region to regions.csv");
  // The shocked material rests on the grid only where the impact is symmetric: equal speeds and materials.
  const bool interface_moves = s.flyer_velocity != s.target_velocity ||
                               !same_constants(s.material_of(Body::flyer), s.material_of(Body::target));
  const bool at_points = s.shape_function == ShapeFunction::bspline2 || s.shape_function == ShapeFunction::bilinear;
  if (s.effects.plasticity && at_points && interface_moves)
    out.push_back("the shocked material moves across the grid (flyer_velocity " + format_number(s.flyer_velocity) +
                  " m/s, target_velocity " + format_number(s.target_velocity) + " m/s, flyer_material " +
                  s.flyer_material + ", target_material " + s.target_material + "): with shape_function " +
                  (s.shape_function == ShapeFunction::bspline2 ? "bspline2" : "bilinear") +
                  " its deviatoric stress rings below yield (about half at 5 um; the normal stress 1 % low); "
                  "shape_function = bspline2_domain holds it on the yield surface at 1.45x the cost per point-step "
                  "(docs/accuracy-and-cost.md)");
  return out;
}

namespace {

Entry parse_override(const std::string& arg, int index) {
  const Origin at{"--set #" + std::to_string(index) + " (" + (arg.size() <= 60 ? arg : excerpt(arg)) + ")"};
  if (arg.size() > kMaxLineBytes)
    throw SceneError(at.where + ": the argument is " + std::to_string(arg.size()) + " bytes long; at most " +
                     std::to_string(kMaxLineBytes));
  const auto eq = arg.find('=');
  if (eq == std::string::npos) throw SceneError(at.where + ": expected --set key=value");
  Entry e{override_key(arg), trim(arg.substr(eq + 1)), at};
  if (!valid_key_name(e.key)) throw SceneError(at.where + ": " + excerpt(e.key) + " is not a key name" + kKeyNameRule);
  if (e.value.empty()) throw error_at(at, e.key, "missing value");
  if (!valid_utf8(e.value)) throw error_at(at, e.key, "the value has bytes that are not UTF-8 text");
  return e;
}

// material.NAME.KEY = value: KEY, a material key, of the material NAME (a built-in one, or a new
// one that starts from aluminium's constants).
void set_material_key(Scene& scene, const Entry& e) {
  const std::string rest = e.key.substr(std::string("material.").size());
  const auto dot = rest.find('.');
  const std::string name = rest.substr(0, dot), key = dot == std::string::npos ? "" : rest.substr(dot + 1);
  if (name.empty() || key.empty()) throw error_at(e.at, e.key, "expected material.NAME.KEY = value");
  if (name == "scene")
    throw error_at(e.at, e.key, "the material named scene is set by the bare keys: write " + key + " = " + e.value);
  const Key* k = find_key(key);
  if (!k || !k->material) {
    std::string list;
    for (const Key& m : keys())
      if (m.material) list += (list.empty() ? "" : ", ") + m.name;
    throw error_at(e.at, e.key, "'" + key + "' is not a material key (" + list + ")");
  }
  Scene holder;  // the key sets Scene::material: set it on a scene holding this material
  const auto it = scene.materials.find(name);
  // A new material starts from aluminium's constants, without its (6061-T6) Johnson-Cook and its Tillotson ones.
  holder.material = it != scene.materials.end() ? it->second : without("tillotson", without("johnson_cook", Material{}));
  k->set(holder, e.value, e.at);
  scene.materials[name] = holder.material;
}

// How a scene names a key of the material NAME: bare for the scene's own, else material.NAME.KEY.
std::string material_key_prefix(const std::string& name) { return name == "scene" ? "" : "material." + name + "."; }

// Every constant of a material as the material.NAME.KEY lines a scene writes.
std::string material_lines(const std::string& name, const Material& m) {
  Scene holder;  // the material keys read Scene::material
  holder.material = m;
  std::string out;
  for (const Key& k : keys())
    if (k.material) out += "material." + name + "." + k.name + " = " + k.get(holder) + "\n";
  return out;
}

bool is_multiple(double length, double unit) {
  const double n = std::round(length / unit);
  return n >= 1 && std::abs(n * unit - length) <= 1e-9 * length;
}

// Checks that involve more than one key. `at` finds where a key was set (or "defaults").
void check_consistency(const Scene& s, const std::function<Origin(const std::string&)>& at, SceneErrors& errors) {
  auto fail = [&](const std::string& key, const std::string& msg) { errors.add(at(key), error_at(at(key), key, msg).what()); };
  const double a = s.particle_spacing();
  if (!is_multiple(s.width, s.cell_size))
    fail("width", "must be a whole number of cells (cell_size = " + format_number(s.cell_size) + " m)");
  // The widest stencil's nodes per axis (3 for every shape but bspline2_domain's 4; bilinear's 2 is
  // held to 3 too): a periodic column narrower would put one node in a stencil twice.
  const double stencil = std::max(3, support_of(s.shape_function));
  const std::string cells = stencil > 3.0 ? "4 cells (bspline2_domain's stencil; shape_function = bspline2 needs 3)"
                                          : "3 cells (the shape function's stencil)";
  if (s.width < stencil * s.cell_size * (1.0 - 1e-9))
    fail("width", "must be at least " + cells + "; a narrower periodic column would put one node in a stencil twice");
  if (s.dimension == 3 && !is_multiple(s.derived_depth(), s.cell_size))
    fail("depth", "must be a whole number of cells (cell_size = " + format_number(s.cell_size) + " m)");
  if (s.dimension == 3 && s.derived_depth() < stencil * s.cell_size * (1.0 - 1e-9))
    fail("depth", "must be at least " + cells + ", as width must; a thinner periodic column would put one node in "
                  "a stencil twice");
  if (!is_multiple(s.target_height, a))
    fail("target_height", "must be a whole number of material-point spacings (cell_size / particles_per_cell = " +
                              format_number(a) + " m)");
  if (!is_multiple(s.flyer_height, a))
    fail("flyer_height", "must be a whole number of material-point spacings (cell_size / particles_per_cell = " +
                             format_number(a) + " m)");
  if (s.effects.thermal_softening && !(s.effects.thermal && s.effects.plasticity))
    fail("thermal_softening", "needs thermal = on and plasticity = on (it softens the strength by temperature)");
  if (s.temperature_model == TemperatureModel::paper) {
    if (!s.effects.thermal) fail("temperature_model", "paper needs thermal = on");
    if (s.effects.heat_conduction)
      fail("temperature_model", "paper cannot go with heat_conduction = on: conduction moves heat in E, which the "
                                "paper's temperature does not count; use temperature_model = energy");
    if (s.effects.thermal_softening)
      fail("temperature_model", "paper cannot go with thermal_softening = on: the paper's temperature leaves out "
                                "the compaction heat and would under-predict softening and melt; use "
                                "temperature_model = energy");
  }
  if (s.paper_temperature) {
    if (!s.effects.thermal) fail("paper_temperature", "needs thermal = on");
    if (s.temperature_model == TemperatureModel::paper)
      fail("paper_temperature", "is already the temperature with temperature_model = paper; use it with "
                                "temperature_model = energy");
    if (s.effects.heat_conduction)
      fail("paper_temperature", "cannot go with heat_conduction = on: conduction moves heat in E, which the "
                                "paper's temperature does not count");
    if (s.effects.thermal_softening)
      fail("paper_temperature", "cannot go with thermal_softening = on, as temperature_model = paper cannot: "
                                "the paper's temperature is not the one that softens the material");
  }
  if (s.effects.heat_conduction && !s.effects.thermal)
    fail("heat_conduction", "needs thermal = on (conduction moves heat by temperature differences)");
  // The bodies' materials: each named one must exist, and its constants fit together.
  bool materials_known = true;
  for (const auto& [key, name] : {std::pair{"flyer_material", s.flyer_material}, std::pair{"target_material", s.target_material},
                                   std::pair{"window_material", s.window_material}}) {
    if (name == "scene" || s.materials.count(name)) continue;
    std::string list;
    for (const auto& m : s.materials) list += ", " + m.first;
    fail(key, "'" + name + "' is not a material: scene (the bare material keys)" + list +
                  " (mpmshock --materials lists the built-in ones; material.NAME.KEY keys define new ones)");
    materials_known = false;
  }
  // Each law a body's material takes checks the scene settings it cannot go with, once, named by the
  // key that chose it for its first body, then each such material's constants (src/laws/).
  if (materials_known)
    for (const MaterialLaw& law : material_laws()) {
      std::vector<std::string> takers;  // the materials in use that take the law
      for (const std::string& name : s.materials_in_use())
        if (takes(law, s, s.material_by_name(name))) takers.push_back(name);
      if (takers.empty()) continue;
      const std::string chooser = choosing_key(law.slot);
      // (A named material's law the bare key set is named by the bare key.)
      const std::string own = chooser.empty() ? chooser : material_key_prefix(takers.front()) + chooser;
      law.check_scene(s, s.origin.count(own) ? own : chooser, fail);
      for (const std::string& name : takers)
        law.check(MaterialCheck{s, s.material_by_name(name), name, material_key_prefix(name), fail});
    }
  if (s.has_window() && !is_multiple(s.window_height, a))
    fail("window_height", "must be a whole number of material-point spacings (cell_size / particles_per_cell = " +
                              format_number(a) + " m)");
  if (!(s.flyer_velocity + s.target_velocity > 0.0))
    fail("flyer_velocity", "the bodies do not approach each other: flyer_velocity + target_velocity must be > 0");
  if (!s.every_body_solid()) {
    if (s.void_radius_spread >= s.void_radius) fail("void_radius_spread", "must be smaller than void_radius");
    const double r_min = s.void_radius - s.void_radius_spread;
    const double r_max = s.void_radius + s.void_radius_spread;
    if (2.0 * r_min < a)
      fail("void_radius", "voids smaller than the material-point spacing (" + format_number(a) +
                              " m) cannot be cut from the points; refine cell_size or use larger voids");
    const double across = s.dimension == 3 ? std::min(s.width, s.derived_depth()) : s.width;
    const double porous_height = s.porosity > 1.0 && s.flyer_porosity > 1.0 ? std::min(s.target_height, s.flyer_height)
                                 : s.porosity > 1.0                           ? s.target_height
                                                                              : s.flyer_height;
    if (2.0 * r_max + s.void_min_gap > std::min(across, porous_height))
      fail("void_radius", "voids that cannot fit: a void of diameter " + format_number(2.0 * r_max) +
                              " m does not fit in the bodies");
    if (s.mirrors_flyer() && std::abs(s.flyer_height - s.target_height) > 1e-12 * s.target_height)
      fail("flyer_mirror", "a mirrored flyer needs flyer_height = target_height");
  }
  if (s.symmetry == Symmetry::on) {
    if (const std::string why = asymmetry_of(s); !why.empty())
      fail("symmetry", "on needs a flyer that is the target's mirror image about y = 0, but " + why);
  }
  for (const ProbeSpec& p : s.probes) {
    if (p.z >= 0.0 && s.dimension != 3) fail("probe." + p.name, "a Z coordinate needs dimension = 3");
    if (p.kind != ProbeSpec::Kind::point) continue;
    // Bare numbers are metres: 'point 1 2' asks for a point a metre away.
    if (!(p.x >= 0.0 && p.x <= s.width))
      fail("probe." + p.name, "X = " + format_number(p.x) + " m lies outside the column (0 .. width = " +
                                  format_number(s.width) + " m; bare numbers are metres)");
    if (!(p.y >= -s.flyer_height - s.cell_size && p.y <= s.target_height + s.window_height + s.cell_size))
      fail("probe." + p.name, "Y = " + format_number(p.y) + " m lies outside the bodies (-flyer_height = " +
                                  format_number(-s.flyer_height) + " m .. target_height" +
                                  (s.has_window() ? " + window_height" : "") + " = " +
                                  format_number(s.target_height + s.window_height) + " m; bare numbers are metres)");
    if (s.dimension == 3 && p.z > s.derived_depth())
      fail("probe." + p.name, "Z = " + format_number(p.z) + " m lies outside the column (0 .. depth = " +
                                  format_number(s.derived_depth()) + " m; bare numbers are metres)");
  }
  if (s.grid_margin >= 0.0 && s.grid_margin < 2.0 * s.cell_size)
    fail("grid_margin", "must be at least two cells (or 'auto')");
  // Sizes that would not fit in memory are refused here, before anything is allocated.
  const double points = (s.target_height + s.flyer_height + s.window_height) / a * s.points_across();
  if (!(points <= 2.0e9))
    fail("cell_size", "the scene would need " + format_number(std::round(points)) +
                          " material points; at most 2e9 are supported");
  // The first time step sees the longitudinal sound speed (bulk plus shear with strength) and the
  // impact speed; shocked material is faster still, so this is a floor on the step count.
  double signal = 0.0;
  for (const Body b : {Body::flyer, Body::target, Body::window}) {
    if (b == Body::window && !s.has_window()) continue;
    const Material& mat = materials_known ? s.material_of(b) : s.material;
    const double c0 = reference_sound_speed_of(mat);
    const double cL2 = c0 * c0 +
                       (s.effects.plasticity ? (4.0 / 3.0) * mat.shear_modulus() / mat.density : 0.0);
    signal = std::max(signal, std::sqrt(cL2) + (b == Body::flyer ? s.flyer_velocity : s.target_velocity));
  }
  const double steps_estimate = s.end_time * signal / (s.cfl * s.cell_size);
  if (!(steps_estimate <= 1e12))
    fail("end_time", "the run would take more than " + format_number(std::floor(steps_estimate)) +
                         " time steps (fastest signal " + format_number(signal) + " m/s); at most 1e12 are supported");
  if (s.snapshot_interval > 0.0 && s.end_time / s.snapshot_interval > 99999)
    fail("snapshot_interval", "the run would write " + format_number(std::floor(s.end_time / s.snapshot_interval)) +
                                  " snapshots; at most 99999 are supported");
}

}  // namespace

std::string asymmetry_of(const Scene& s) {
  if (std::abs(s.flyer_height - s.target_height) > 1e-12 * s.target_height)
    return "flyer_height differs from target_height";
  if (s.flyer_porosity != s.porosity) return "flyer_porosity differs from porosity";
  if (s.porosity > 1.0 && !s.flyer_mirror) return "flyer_mirror = off gives the flyer its own voids";
  if (s.flyer_velocity != s.target_velocity) return "flyer_velocity differs from target_velocity";
  if (s.has_window()) return "the target has a window, the flyer none";
  if ((s.flyer_material == "scene" || s.materials.count(s.flyer_material)) &&
      (s.target_material == "scene" || s.materials.count(s.target_material)) &&
      !same_constants(s.material_of(Body::flyer), s.material_of(Body::target)))
    return "the flyer's material differs from the target's";
  return "";
}

const std::string& Scene::material_name(Body b) const {
  return b == Body::flyer ? flyer_material : b == Body::target ? target_material : window_material;
}

std::vector<std::string> Scene::materials_in_use() const {
  std::vector<std::string> names;
  for (const Body b : {Body::target, Body::flyer, Body::window}) {
    if (b == Body::window && !has_window()) continue;
    const std::string& name = material_name(b);
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

const Material& Scene::material_of(Body b) const { return material_by_name(material_name(b)); }

const Material& Scene::material_by_name(const std::string& name) const {
  return name == "scene" ? material : materials.at(name);
}

bool Scene::one_material() const {
  return same_constants(material_of(Body::flyer), material_of(Body::target)) &&
         (!has_window() || same_constants(material_of(Body::window), material_of(Body::target)));
}

bool Scene::mirrors_flyer() const { return flyer_mirror && porosity > 1.0 && flyer_porosity == porosity; }

double Scene::fastest_body_speed() const { return std::max(flyer_velocity, target_velocity); }

double Scene::points_across() const {
  const double a = particle_spacing();
  return std::round(width / a) * (dimension == 3 ? std::round(derived_depth() / a) : 1.0);
}

double Scene::derived_grid_margin() const {
  if (grid_margin >= 0.0) return grid_margin;
  return 8.0 * cell_size + 2.0 * fastest_body_speed() * end_time;
}

std::vector<RegionSpec> paper_regions() {
  using K = RegionSpec::Kind;
  return {
      {"B800", K::bottom, 100e-6, 800e-6}, {"B400", K::bottom, 100e-6, 400e-6}, {"B100", K::bottom, 100e-6, 100e-6},
      {"T800", K::top, 0.0, 800e-6},       {"T400", K::top, 0.0, 400e-6},       {"T100", K::top, 0.0, 100e-6},
  };
}

Scene parse_scene(const std::string& text, const std::string& name, const std::vector<std::string>& overrides) {
  SceneErrors errors;
  std::vector<Entry> entries = read_entries(text, name, errors);

  // One place per key: repeated keys in the file are errors, --set replaces the file's value.
  std::map<std::string, Entry> by_key;
  for (Entry& e : entries) {
    if (auto it = by_key.find(e.key); it != by_key.end()) {
      errors.add(e.at, error_at(e.at, e.key, "repeated key (first set at " + it->second.at.where + ")").what());
      continue;
    }
    by_key.emplace(e.key, std::move(e));
  }
  std::map<std::string, std::string> overridden;
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    const Origin at{"--set #" + std::to_string(i + 1)};
    std::optional<Entry> e;
    errors.collect(at, [&] { e = parse_override(overrides[i], static_cast<int>(i + 1)); });
    if (!e) continue;
    if (overridden.count(e->key)) {
      errors.add(at, error_at(e->at, e->key, "set twice on the command line").what());
      continue;
    }
    overridden[e->key] = e->value;
    by_key[e->key] = std::move(*e);
  }

  Scene scene;
  scene.source = name;
  for (const Key& k : keys()) {
    if (k.default_text == "auto") continue;  // grid_margin, depth, cfl, av_linear, ...: a sentinel in Scene stands for auto
    k.set(scene, k.default_text, Origin{"default"});
  }
  std::vector<RegionSpec> regions;
  std::vector<const Entry*> material_entries;
  for (const auto& [key, e] : by_key) {
    const Entry& entry = e;
    errors.collect(e.at, [&] {
      if (key.rfind("region.", 0) == 0) {
        regions.push_back(parse_region(entry));
        return;
      }
      if (key.rfind("probe.", 0) == 0) {
        scene.probes.push_back(parse_probe(entry));
        return;
      }
      if (key.rfind("material.", 0) == 0) {
        material_entries.push_back(&entry);
        return;
      }
      const Key* k = find_key(key);
      if (!k) throw error_at(entry.at, key, "unknown key" + did_you_mean(key));
      if (k->kind == Kind::text && key == "output_dir") check_path(entry.at, key, entry.value);
      if (k->default_text == "auto" && entry.value == "auto") return;
      k->set(scene, entry.value, entry.at);
    });
  }
  for (const LibraryMaterial& m : material_library()) scene.materials[m.name] = m.constants;
  for (const Entry* e : material_entries) errors.collect(e->at, [&] { set_material_key(scene, *e); });
  // A named material's strength law is the bare key's unless the scene gives it its own: a scene
  // that names strength_model once sets every body's, as before the key was a material's.
  for (auto& [material_name, m] : scene.materials)
    if (!by_key.count("material." + material_name + ".strength_model")) m.strength_model = scene.material.strength_model;
  // The consistency of the keys is judged only on keys that are each right.
  errors.throw_if_any();
  // Regions and probes in the order the file lists them, not alphabetical.
  const auto line_of = [&](const std::string& key) {
    const std::string& w = by_key.at(key).at.where;
    const auto c = w.rfind(':');
    return c == std::string::npos ? 1 << 30 : std::atoi(w.c_str() + c + 1);
  };
  std::sort(regions.begin(), regions.end(), [&](const RegionSpec& x, const RegionSpec& y) {
    return line_of("region." + x.name) < line_of("region." + y.name);
  });
  std::sort(scene.probes.begin(), scene.probes.end(), [&](const ProbeSpec& x, const ProbeSpec& y) {
    return line_of("probe." + x.name) < line_of("probe." + y.name);
  });
  scene.regions = regions.empty() ? paper_regions() : regions;

  for (const auto& [key, e] : by_key) scene.origin[key] = e.at.where;
  if (std::isnan(scene.flyer_velocity)) scene.flyer_velocity = scene.velocity;
  if (std::isnan(scene.target_velocity)) scene.target_velocity = scene.velocity;
  if (std::isnan(scene.flyer_porosity)) scene.flyer_porosity = scene.porosity;
  if (scene.av_linear < 0.0) scene.av_linear = auto_av_linear(scene.every_body_solid());
  if (scene.volumetric_smoothing == Smoothing::automatic)
    scene.volumetric_smoothing = auto_volumetric_smoothing(scene.every_body_solid());
  if (scene.cfl < 0.0) scene.cfl = auto_cfl(scene);
  check_consistency(scene, [&](const std::string& key) { return Origin{scene.where(key)}; }, errors);
  errors.throw_if_any();
  if (scene.symmetry == Symmetry::automatic)
    scene.symmetry = asymmetry_of(scene).empty() ? Symmetry::on : Symmetry::off;
  return scene;
}

void check_input_file(const std::string& path, const std::string& what) {
  const std::string cannot = path + ": cannot open the " + what + ": ";
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    struct stat link {};
    if (err == ENOENT && ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode))
      throw SceneError(cannot + "it is a symbolic link to a file that does not exist");
    if (err == ELOOP) throw SceneError(cannot + std::strerror(err) + " (a loop of symbolic links)");
    throw SceneError(cannot + std::strerror(err));
  }
  if (S_ISDIR(st.st_mode)) throw SceneError(cannot + "it is a directory, not a file");
  if (!S_ISREG(st.st_mode))
    throw SceneError(cannot + "it is " + (S_ISFIFO(st.st_mode) ? "a FIFO (named pipe)" : S_ISSOCK(st.st_mode) ? "a socket" : "a device") +
                     ", not a regular file; mpmshock reads only regular files");
  if (::access(path.c_str(), R_OK) != 0) throw SceneError(cannot + std::strerror(errno));
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  check_input_file(path, "scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file: " + std::strerror(errno));
  std::string text(kMaxSceneBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxSceneBytes)
    throw SceneError(path + ": is larger than " + std::to_string(kMaxSceneBytes / 1024) +
                     " KiB; a scene file is a page of text (is this the right file?)");
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // a UTF-8 byte-order mark (some editors write one)
  if (text.find('\0') != std::string::npos) throw SceneError(path + ": is not a text file (it holds NUL bytes)");
  if (trim(text).empty()) throw SceneError(path + ": the scene file is empty; an empty scene is most likely a mistake "
                                                  "(write at least one key, e.g. 'velocity = 1000 m/s')");
  return parse_scene(text, path, overrides);
}

std::string resolved_scene(const Scene& scene) {
  std::string out;
  for (const Key& k : keys()) {
    std::string value = k.get(scene);
    if (k.name == "grid_margin") value = format_number(scene.derived_grid_margin()) + " m";
    if (k.name == "depth") value = format_number(scene.derived_depth()) + " m";
    out += k.name + " = " + value + "\n";
  }
  // The named materials the bodies use, every constant: a run reads back as it ran, whatever the
  // library holds later.
  for (const std::string& name : scene.materials_in_use())
    if (name != "scene") out += material_lines(name, scene.materials.at(name));
  for (const RegionSpec& r : scene.regions) {
    out += "region." + r.name + " = ";
    switch (r.kind) {
      case RegionSpec::Kind::bottom: out += "bottom " + format_number(r.a) + " m " + format_number(r.b) + " m"; break;
      case RegionSpec::Kind::top: out += "top " + format_number(r.b) + " m"; break;
      case RegionSpec::Kind::band: out += "band " + format_number(r.a) + " m " + format_number(r.b) + " m"; break;
    }
    out += "\n";
  }
  for (const ProbeSpec& p : scene.probes) {
    out += "probe." + p.name + " = ";
    if (p.kind == ProbeSpec::Kind::surface) out += "surface";
    else out += "point " + format_number(p.x) + " m " + format_number(p.y) + " m";
    if (p.kind == ProbeSpec::Kind::point && p.z >= 0.0) out += " " + format_number(p.z) + " m";
    out += "\n";
  }
  return out;
}

std::string material_library_text() {
  std::string out =
      "# The built-in materials: flyer_material = NAME, target_material = NAME; each line is a key a\n"
      "# scene may set to change it (material.NAME.KEY = value); a new NAME starts from aluminium\n"
      "# (without its Johnson-Cook and Tillotson constants).\n";
  for (const LibraryMaterial& m : material_library()) {
    out += "\n# " + m.name + ": " + m.source + "\n" + material_lines(m.name, m.constants);
  }
  return out;
}

std::string material_laws_text() {
  std::string out =
      "# The laws a material is built from (src/laws/): each body's material takes one equation of state\n"
      "# and, with plasticity = on, one strength law; the keys after each law set its constants\n"
      "# (bare for the scene's own material, material.NAME.KEY for a named one; mpmshock --keys gives\n"
      "# their units and defaults). 'built in for' names the library materials that carry its constants.\n";
  for (const MaterialLaw& law : material_laws()) {
    const std::string chooser = choosing_key(law.slot);
    std::string chosen_by = law.slot == LawSlot::always    ? "every material"
                            : law.slot == LawSlot::softening ? "thermal_softening = on, on bodies of the bilinear law"
                                                             : chooser + " = " + law.name;
    if (law.slot != LawSlot::always && law.slot != LawSlot::softening && first_of_its_slot(law)) chosen_by += ", the default";
    std::string built_in;
    for (const LibraryMaterial& m : material_library())
      if (!same_constants(without(law.name, m.constants), m.constants))  // it has some of its own
        built_in += (built_in.empty() ? "" : ", ") + m.name;
    out += "\n" + law.name + " (" + chosen_by + "); built in for: " + (built_in.empty() ? "none" : built_in) + "\n ";
    for (const MaterialKey& key : law.keys) out += " " + key.name;
    out += "\n";
  }
  return out;
}

std::string key_reference_markdown() {
  std::string out = "| key | unit | default | meaning |\n|---|---|---|---|\n";
  for (const Key& k : keys()) {
    std::string unit;
    switch (k.kind) {
      case Kind::quantity: unit = k.dim == Dimension::none ? "-" : std::string(si_unit(k.dim)); break;
      case Kind::integer: unit = "-"; break;
      case Kind::flag:
      case Kind::choice: {
        unit = k.choices;
        for (char& c : unit)
          if (c == '|') c = ',';
        break;
      }
      case Kind::text: unit = "path"; break;
      case Kind::times: unit = std::string(si_unit(k.dim)); break;
    }
    out += "| `" + k.name + "` | " + unit + " | " + k.default_text + " | " + k.meaning + " |\n";
  }
  out += "| `region.NAME` | m | B800, B400, B100, T800, T400, T100 | `bottom Y1 H`, `top H` or `band Y1 Y2`; "
         "a scene that names regions replaces the defaults |\n";
  out += "| `probe.NAME` | m | none | `surface` (the target's free surface: its top cell of points at t = 0) or "
         "`point X Y` (the material point nearest to X Y at t = 0; `point X Y Z` in 3D, Z by default mid-depth), "
         "followed through the run into probes.csv |\n";
  return out;
}

}  // namespace mpmshock
