// The scene parser on good and bad input: units, defaults, overrides, regions, and errors that name
// the file, the line and the key.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "check.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/scene.hpp"

using namespace mpmshock;

static Scene parse(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return parse_scene(text, "t.scene", overrides);
}

int main() {
  // Defaults: the paper's aluminium and base case.
  const Scene d = parse("velocity = 1000 m/s\n");
  CHECK(d.material.youngs_modulus == 69e9 && d.material.yield_stress == 120e6 && d.material.density == 2700);
  CHECK(d.porosity == 1.03 && d.void_radius == 50e-6 && d.width == 2e-3 && d.target_height == 5e-3);
  CHECK(d.regions.size() == 6 && d.regions[0].name == "B800" && d.regions[5].name == "T100");
  CHECK(d.effects.plasticity && d.effects.thermal && d.effects.artificial_viscosity);

  // Units, comments, blank lines, attached units.
  const Scene s = parse(
      "# a comment\n\n"
      "velocity = 2 km/s   # trailing comment\n"
      "void_radius = 10um\n"
      "cell_size = 5 um\n"
      "width = 0.5 mm\n"
      "target_height = 1.5 mm\nflyer_height = 1.5 mm\n"
      "end_time = 0.4 us\n"
      "density = 2.7 g/cm3\n"
      "yield_stress = 0.12 GPa\n"
      "specific_heat = 880 J/(kg K)\n"
      "thermal_conductivity = 237 W/(m K)\n"
      "porosity = 1.4\n"
      "plasticity = off\n"
      "output_dir = runs/a b\n"
      "region.mid = band -100 um 100um\n"
      "region.top = top 50 um\n");
  CHECK_REL(s.velocity, 2000.0, 1e-15);
  CHECK_REL(s.void_radius, 10e-6, 1e-15);
  CHECK_REL(s.end_time, 0.4e-6, 1e-15);
  CHECK_REL(s.material.density, 2700.0, 1e-15);
  CHECK_REL(s.material.yield_stress, 120e6, 1e-15);
  CHECK(!s.effects.plasticity);
  CHECK(s.output_dir == "runs/a b");
  // The shock physicist's units: 0.2 Mbar = 20 GPa, 0.1 cm/us = 1 km/s.
  const Scene shock = parse("velocity = 0.1 cm/us\nyield_stress = 0.002 Mbar\n");
  CHECK_REL(shock.velocity, 1000.0, 1e-15);
  CHECK_REL(shock.material.yield_stress, 200e6, 1e-15);
  CHECK(s.regions.size() == 2 && s.regions[0].name == "mid" && s.regions[0].kind == RegionSpec::Kind::band);
  CHECK_REL(s.regions[0].a, -100e-6, 1e-12);
  CHECK_REL(s.regions[0].b, 100e-6, 1e-12);
  CHECK(s.regions[1].kind == RegionSpec::Kind::top);

  // --set overrides the file's value and may add keys.
  const Scene o = parse("velocity = 1000 m/s\n", {"velocity=500 m/s", "seed = 7"});
  CHECK(o.velocity == 500.0 && o.seed == 7);

  // The resolved scene reads back to the same scene.
  const Scene back = parse(resolved_scene(s));
  CHECK(back.velocity == s.velocity && back.void_radius == s.void_radius && back.porosity == s.porosity);
  CHECK(back.regions.size() == 2 && back.regions[0].a == s.regions[0].a);
  CHECK(resolved_scene(back) == resolved_scene(s));

  // Errors name the file, the line and the key.
  CHECK_THROWS_WITH(parse("\nvelocty = 1000 m/s\n"), "t.scene:2", "'velocty'", "unknown key", "did you mean 'velocity'");
  CHECK_THROWS_WITH(parse("velocity = 1\nvelocity = 2\n"), "t.scene:2", "'velocity'", "repeated", "t.scene:1");
  CHECK_THROWS_WITH(parse("velocity = fast\n"), "t.scene:1", "'velocity'", "not a number");
  CHECK_THROWS_WITH(parse("velocity = 1000 furlongs\n"), "t.scene:1", "'velocity'", "unknown unit 'furlongs'");
  CHECK_THROWS_WITH(parse("velocity = 1000 mm\n"), "'velocity'", "is a length", "speed");
  CHECK_THROWS_WITH(parse("velocity =\n"), "t.scene:1", "'velocity'", "missing value");
  CHECK_THROWS_WITH(parse("velocity 1000\n"), "t.scene:1", "expected 'key = value'");
  CHECK_THROWS_WITH(parse("porosity = 0.9\n"), "t.scene:1", "'porosity'", "out of range", ">= 1");
  CHECK_THROWS_WITH(parse("cell_size = -1 um\n"), "'cell_size'", "out of range");
  CHECK_THROWS_WITH(parse("cfl = 1\n"), "'cfl'", "< 1");
  CHECK_THROWS_WITH(parse("max_volume_change = 0\n"), "t.scene:1", "'max_volume_change'", "> 0");
  CHECK(parse("").max_volume_change == 0.02);
  CHECK(parse("max_volume_change = 1e9\n").max_volume_change == 1e9);
  CHECK_THROWS_WITH(parse("velocity = 1e999\n"), "'velocity'", "out of the range");
  CHECK_THROWS_WITH(parse("particles_per_cell = 2.5\n"), "'particles_per_cell'", "whole number");
  CHECK_THROWS_WITH(parse("plasticity = maybe\n"), "'plasticity'", "on or off");
  CHECK_THROWS_WITH(parse("shape_function = cubic\n"), "'shape_function'", "bilinear", "bspline2");
  CHECK_THROWS_WITH(parse("void_radius = 3 mm\n"), "'void_radius'", "cannot fit");
  CHECK_THROWS_WITH(parse("width = 2.005 mm\n"), "'width'", "whole number of cells");
  CHECK_THROWS_WITH(parse("region.x = sideways 1 um\n"), "t.scene:1", "'region.x'", "bottom Y1 HEIGHT");
  CHECK_THROWS_WITH(parse("velocity = \xff\xfe\n"), "t.scene:1", "not UTF-8");
  CHECK_THROWS_WITH(parse("cell_size = 1 nm\n"), "'cell_size'", "material points");
  CHECK_THROWS_WITH(parse("velocity = 1\n", {"velocty=2"}), "--set #1", "unknown key", "did you mean 'velocity'");
  CHECK_THROWS_WITH(parse("velocity = 1\n", {"velocity=2", "velocity=3"}), "--set #2", "set twice");
  CHECK_THROWS_WITH(parse("velocity = 1\n", {"novalue"}), "--set #1", "key=value");
  // A cross-key error found with a default value points at the default.
  CHECK_THROWS_WITH(parse("target_height = 3 mm\n"), "'flyer_mirror'", "flyer_height");

  // Files: missing, a directory, empty.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("mpmshock_test_scene_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  CHECK_THROWS_WITH(load_scene((dir / "missing.scene").string()), "missing.scene", "cannot open");
  CHECK_THROWS_WITH(load_scene(dir.string()), "is a directory");
  std::ofstream((dir / "empty.scene").string()) << "  \n\n";
  CHECK_THROWS_WITH(load_scene((dir / "empty.scene").string()), "empty.scene");
  std::ofstream((dir / "good.scene").string()) << "velocity = 750 m/s\n";
  CHECK(load_scene((dir / "good.scene").string()).velocity == 750.0);
  std::ofstream((dir / "comments.scene").string()) << "# every key at its default\n";
  CHECK(load_scene((dir / "comments.scene").string()).velocity == 1000.0);
  fs::remove_all(dir);
  // 3D keys: the time step's default by shape, depth and probes in z.
  {
    CHECK(kCflDomain == 0.6 && kCfl == 0.3);
    CHECK(parse_scene("", "d.scene").cfl == kCflDomain);  // bspline2_domain, the default shape
    CHECK(parse_scene("dimension = 3\n", "d.scene").cfl == kCflDomain);
    CHECK(parse_scene("shape_function = bspline2\n", "d.scene").cfl == kCfl);
    CHECK(parse_scene("shape_function = gimp\n", "d.scene").cfl == kCfl);
    CHECK(parse_scene("dimension = 3\nshape_function = bspline2\n", "d.scene").cfl == kCfl);
    CHECK(parse_scene("dimension = 3\ncfl = 0.25\n", "d.scene").cfl == 0.25);
    CHECK(parse_scene("dimension = 3\n", "d.scene", {"cfl=auto"}).cfl == kCflDomain);
    // The default A1 by the bodies (porous: the default porosity 1.03, or either body's); the
    // automatic step follows it (below).
    CHECK(parse_scene("", "d.scene").av_linear == kAvLinearPorous);
    CHECK(parse_scene("porosity = 1\nflyer_porosity = 1.1\n", "d.scene").av_linear == kAvLinearPorous);
    CHECK(parse_scene("porosity = 1.1\nflyer_porosity = 1\n", "d.scene").av_linear == kAvLinearPorous);
    const Scene solid = parse_scene("porosity = 1\n", "d.scene");
    CHECK(solid.av_linear == kAvLinearSolid && kAvLinearSolid == 0.6 && kAvLinearPorous == 0.2);
    // A solid scene's A1 = 0.6 takes the larger automatic step; one set below 0.6, or no viscosity, does not.
    CHECK(solid.cfl == kCflDomainViscous && kCflDomainViscous == 0.8);
    CHECK(parse_scene("porosity = 1\nav_linear = 0.3\n", "d.scene").cfl == kCflDomain);
    CHECK(parse_scene("porosity = 1\nartificial_viscosity = off\n", "d.scene").cfl == kCflDomain);
    CHECK(parse_scene("av_linear = 0.75\n", "d.scene").cfl == kCflDomainViscous);  // porous, by its A1
    CHECK(parse_scene("porosity = 1\nshape_function = bspline2\n", "d.scene").cfl == kCfl);
    CHECK(parse_scene("porosity = 1\n", "d.scene", {"av_linear=auto"}).av_linear == kAvLinearSolid);
    CHECK(parse_scene("porosity = 1\nav_linear = 0.3\n", "d.scene").av_linear == 0.3);
    CHECK(resolved_scene(solid).find("av_linear = 0.6\n") != std::string::npos);  // what a restart reads back
    CHECK(scene_warnings(solid).empty());
    CHECK(resolved_scene(parse_scene("dimension = 3\n", "d.scene")).find("cfl = 0.6\n") != std::string::npos);
    // Above the automatic value, in either dimension, a warning says what a larger step costs.
    for (const char* d : {"", "dimension = 3\n"}) {
      const std::vector<std::string> w = scene_warnings(parse_scene(std::string(d) + "cfl = 0.45\nshape_function = bspline2\n", "d.scene"));
      CHECK(std::any_of(w.begin(), w.end(), [](const std::string& s) { return s.find("cfl 0.45 > 0.3") != std::string::npos; }));
      CHECK(scene_warnings(parse_scene(d, "d.scene")).empty());
    }
    // The shocked material moving across the grid with the B-spline at points: a warning, in the
    // laboratory frame and for two materials at equal speeds; none with bspline2_domain or symmetric.
    auto moving = [](const std::string& text) {
      const std::vector<std::string> w = scene_warnings(parse_scene(text, "d.scene"));
      return std::any_of(w.begin(), w.end(), [](const std::string& s) { return s.find("moves across the grid") != std::string::npos; });
    };
    CHECK(moving("target_velocity = 0\nflyer_velocity = 1000 m/s\nshape_function = bspline2\n"));
    CHECK(moving("flyer_material = copper\nflyer_porosity = 1\nshape_function = bilinear\n"));
    CHECK(!moving("target_velocity = 0\nflyer_velocity = 1000 m/s\n"));  // bspline2_domain, the default
    CHECK(!moving("target_velocity = 0\nflyer_velocity = 1000 m/s\nplasticity = off\n"));
    CHECK(!moving(""));
    // bspline2_domain's 4-node stencil needs a column of 4 cells (3 for the others).
    CHECK(parse_scene("width = 30 um\ncell_size = 10 um\nporosity = 1\nshape_function = bspline2\n", "d.scene").width == 30e-6);
    CHECK_THROWS_WITH(parse_scene("width = 30 um\ncell_size = 10 um\nporosity = 1\n", "d.scene"),
                      "'width'", "at least 4 cells", "shape_function = bspline2 needs 3");
    CHECK(parse_scene("dimension = 3\nwidth = 0.2 mm\n", "d.scene").derived_depth() == 0.2e-3);
    CHECK(parse_scene("dimension = 3\ndepth = 0.1 mm\n", "d.scene").derived_depth() == 0.1e-3);
    CHECK_THROWS_WITH(parse_scene("probe.p = point 10 um 20 um 30 um\n", "d.scene"), "d.scene:1", "'probe.p'",
                      "dimension = 3");
    const Scene s = parse_scene("dimension = 3\nprobe.p = point 10 um 20 um 30 um\n", "d.scene");
    CHECK(s.probes.size() == 1 && s.probes[0].z == 30e-6);
    CHECK(resolved_scene(s).find("probe.p = point 1e-05 m 2e-05 m 3e-05 m") != std::string::npos);
  }
  // Materials (issue 29): the bare keys are the material "scene" of both bodies; a body may name a
  // built-in material, material.NAME.KEY changes one or defines a new one (from aluminium's values).
  {
    const Scene plain = parse_scene("", "m.scene");
    CHECK(plain.flyer_material == "scene" && plain.target_material == "scene" && plain.one_material());
    CHECK(plain.flyer_velocity == 1000.0 && plain.target_velocity == 1000.0 && plain.flyer_porosity == plain.porosity);
    CHECK(same_constants(plain.materials.at("aluminium"), plain.material));  // the bare keys' defaults
    const Scene cu = parse_scene("flyer_material = copper\ntarget_velocity = 0\nflyer_velocity = 500 m/s\n"
                                 "material.copper.yield_stress = 0.2 GPa\nmaterial.steel.density = 7850 kg/m3\n",
                                 "m.scene");
    CHECK(cu.material_of(Body::flyer).density == 8930.0 && cu.material_of(Body::flyer).yield_stress == 0.2e9);
    CHECK(cu.material_of(Body::target).density == 2700.0 && !cu.one_material());
    CHECK(cu.materials.at("steel").density == 7850.0 && cu.materials.at("steel").sound_speed == 5350.0);
    CHECK(cu.symmetry == Symmetry::off && cu.target_velocity == 0.0 && cu.fastest_body_speed() == 500.0);
    // The resolved scene holds every constant of the named material and reads back to the same run.
    const std::string text = resolved_scene(cu);
    CHECK(text.find("material.copper.yield_stress = 2e+08 Pa\n") != std::string::npos);
    CHECK(text.find("material.steel.") == std::string::npos);  // defined, but no body's
    CHECK(resolved_scene(parse_scene(text, "scene.txt")) == text);
    CHECK(parse_scene("flyer_material = aluminium\ntarget_material = aluminium\n", "m.scene").symmetry == Symmetry::on);
    CHECK_THROWS_WITH(parse_scene("flyer_material = steel\n", "m.scene"), "m.scene:1", "'flyer_material'",
                      "'steel' is not a material", "copper");
    CHECK_THROWS_WITH(parse_scene("material.copper.colour = red\n", "m.scene"), "m.scene:1",
                      "'material.copper.colour'", "not a material key", "density");
    CHECK_THROWS_WITH(parse_scene("material.scene.density = 1\n", "m.scene"), "m.scene:1", "bare keys");
    CHECK_THROWS_WITH(parse_scene("material.copper.density = -1\n", "m.scene"), "m.scene:1", "out of range");
    CHECK_THROWS_WITH(parse_scene("material.copper\n", "m.scene"), "m.scene:1");
    // Softening takes each body's constants; a material without them is refused, naming its key.
    CHECK(parse_scene("flyer_material = copper\nthermal_softening = on\n", "m.scene").effects.thermal_softening);
    CHECK_THROWS_WITH(parse_scene("flyer_material = tantalum\nthermal_softening = on\n", "m.scene"),
                      "'material.tantalum.melt_temperature'", "no Steinberg-Guinan constants");
    CHECK_THROWS_WITH(parse_scene("flyer_material = copper\nthermal_softening = on\n"
                                  "material.copper.initial_temperature = 2000 K\n", "m.scene"),
                      "'material.copper.melt_temperature'", "start molten", "(material copper)");
    // Conduction takes each body's constants (heat_conduction.hpp).
    CHECK(parse_scene("target_material = pmma\nheat_conduction = on\n", "m.scene").effects.heat_conduction);
    CHECK_THROWS_WITH(parse_scene("flyer_velocity = 0\ntarget_velocity = 0\n", "m.scene"), "'flyer_velocity'",
                      "do not approach");
    CHECK_THROWS_WITH(parse_scene("flyer_material = lif\nsymmetry = on\n", "m.scene"), "'symmetry'",
                      "material differs");
    CHECK(find_library_material("tantalum") && !find_library_material("steel"));
    // A restart of a run written before the Steinberg-Guinan constants were each material's: its
    // bare keys were every body's, so its named materials go on with them (restart.cpp).
    const std::string old_run = "flyer_material = copper\ntarget_material = copper\nthermal_softening = on\n"
                                "melt_temperature = 1000 K\nlatent_heat = 300000 J/kg\n";
    const Scene migrated = parse_scene(old_run, "old.scene", with_old_defaults(old_run, {}));
    CHECK(migrated.material_of(Body::flyer).melt_temperature == 1000.0);
    CHECK(migrated.material_of(Body::target).latent_heat == 300000.0);
    CHECK(migrated.material_of(Body::target).pressure_hardening_scale == find_library_material("copper")->constants.pressure_hardening_scale);
    // One written since keeps its materials' own.
    const std::string new_run = old_run + "material.copper.melt_temperature = 1790 K\n";
    CHECK(parse_scene(new_run, "new.scene", with_old_defaults(new_run, {})).material_of(Body::flyer).melt_temperature == 1790.0);
    // A porous run written before volumetric smoothing existed ran without it, and goes on so; one
    // written since keeps what its scene says (auto resolves to on for a porous scene).
    const std::string porous_run = "porosity = 1.2\n";
    CHECK(parse_scene(porous_run, "old.scene").volumetric_smoothing == Smoothing::on);
    CHECK(parse_scene(porous_run, "old.scene", with_old_defaults(porous_run, {})).volumetric_smoothing == Smoothing::off);
    const std::string smoothed_run = porous_run + "volumetric_smoothing = on\n";
    CHECK(parse_scene(smoothed_run, "new.scene", with_old_defaults(smoothed_run, {})).volumetric_smoothing == Smoothing::on);
  }
  return check::result();
}
