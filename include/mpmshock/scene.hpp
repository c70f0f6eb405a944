// A scene: everything one run needs, parsed once from a key = value file into typed SI fields.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "mpmshock/material.hpp"

namespace mpmshock {

// USL: the stress update uses the grid velocities right after the momentum update.
// MUSL (default): it uses the nodal velocity re-mapped from the updated point velocities, and the
// energy update the exact work of the step's forces (kinetic + internal energy conserved).
enum class UpdateScheme { musl, usl };

// Shape functions (see shape.hpp): the quadratic B-spline over each point's domain (bspline2_domain,
// the default), the quadratic B-spline at points (bspline2), cpGIMP, or the paper's 4-node bilinear
// cells, whose grid-crossing noise turns into spurious heat in porous runs.
enum class ShapeFunction { bilinear, gimp, bspline2, bspline2_domain };
// The nodes per axis a point's stencil touches (shape.hpp's Shape::support).
constexpr int support_of(ShapeFunction f) {
  return f == ShapeFunction::bilinear ? 2 : f == ShapeFunction::bspline2_domain ? 4 : 3;
}

// How the temperature follows from the state (temperature.hpp): energy (default) counts all the heat
// in E, T = T_H(V) + (E - E_H(V))/c_v; paper counts only plastic work, T = T_H(V) + W_p/c_v, leaving
// out the compaction heating of collapsing voids, which is what the paper's reported numbers fit.
enum class TemperatureModel { energy, paper };

// What a point's spall criterion reads (spall_neighbourhood.hpp): the largest principal stress of
// its neighbourhood (default) or its own.
enum class SpallCriterion { neighbourhood, point };

// Symmetry about the impact plane y = 0 (symmetry_plane.hpp, mirror_image.hpp): on simulates the
// target alone and takes the flyer as its mirror image; automatic (the key's "auto") becomes on or
// off when the scene is parsed, so a parsed Scene holds on or off.
enum class Symmetry { automatic, on, off };

// Volumetric smoothing (volumetric_smoothing.hpp): automatic (the key's "auto") becomes on where a
// body is porous and off where every body is solid when the scene is parsed (auto_volumetric_smoothing).
enum class Smoothing { automatic, on, off };

struct RegionSpec {
  // bottom: target points with y in [y1, y1 + height]        (a = y1, b = height)
  // top:    target points with y in [y_top - height, y_top]   (b = height), y_top = highest target point
  // band:   all points with y in [y1, y2]                     (a = y1, b = y2)
  enum class Kind { bottom, top, band };
  std::string name;
  Kind kind = Kind::bottom;
  double a = 0.0, b = 0.0;
};

// A probe follows material points through the run (probes.csv):
//   surface:  the target's free surface, the points of its top cell at t = 0
//   point:    the material point nearest to (x, y) at t = 0 (x, y, z in 3D; z defaults to mid-depth)
struct ProbeSpec {
  enum class Kind { surface, point };
  std::string name;
  Kind kind = Kind::surface;
  double x = 0.0, y = 0.0;
  double z = -1.0;  // < 0: not given
};

struct Effects {
  bool plasticity = true;            // von Mises strength; off: hydrodynamic (no deviatoric stress)
  bool thermal = true;               // temperatures (temperature_model says how)
  bool artificial_viscosity = true;  // shock-capturing bulk viscosity
  bool spall = false;                // failure in tension (spall.hpp)
  bool heat_conduction = false;      // Fourier conduction (heat_conduction.hpp)
  bool thermal_softening = false;    // G and sigma_Y fall with T, vanish in the melt (thermal_softening.hpp)
};

struct Scene {
  std::string source;  // the scene file's path, for messages

  // Impact
  double velocity = 1000.0;
  // Each body's speed toward the impact plane y = 0 (the flyer moves up, the target down); NaN until
  // parsed: automatic, `velocity` (the symmetric frame). The laboratory frame: target_velocity = 0.
  double flyer_velocity = std::numeric_limits<double>::quiet_NaN();
  double target_velocity = std::numeric_limits<double>::quiet_NaN();
  double porosity = 1.03;
  double flyer_porosity = std::numeric_limits<double>::quiet_NaN();  // NaN until parsed: automatic, porosity
  double void_radius = 50e-6;
  double void_radius_spread = 0.0;
  double void_min_gap = 0.0;
  bool void_overlap = false;
  bool flyer_mirror = true;
  double target_height = 5e-3;
  double flyer_height = 5e-3;
  double width = 2e-3;
  int dimension = 2;    // 2: plane strain (x, y); 3: a column periodic in x and z
  double depth = -1.0;  // [m] the z extent in 3D; < 0: automatic, the width (see derived_depth)
  Symmetry symmetry = Symmetry::automatic;

  // Discretisation and time stepping
  double cell_size = 20e-6;
  std::int64_t particles_per_cell = 2;
  double grid_margin = -1.0;  // < 0: automatic (see derived_grid_margin)
  double end_time = 1e-6;
  double cfl = -1.0;  // < 0 until parsed: automatic, auto_cfl(*this)
  // The largest relative volume change |tr D| dt of a point in one step: the step is also at most
  // this over the fastest rate of volume change (a collapsing void's jet).
  double max_volume_change = 0.02;
  UpdateScheme update_scheme = UpdateScheme::musl;
  ShapeFunction shape_function = ShapeFunction::bspline2_domain;
  double spall_strength = 1.2e9;  // [Pa] tension at which a point fails (spall = on)
  double spall_void_fraction = 0.15;  // void fraction at which a failed point separates (spall.hpp)
  SpallCriterion spall_criterion = SpallCriterion::neighbourhood;
  double spall_point_ceiling = 2.0;  // a point's own tension that opens it regardless, over spall_strength
  double taylor_quinney = 1.0;    // share of plastic work that becomes heat
  TemperatureModel temperature_model = TemperatureModel::energy;
  bool paper_temperature = false;  // also report the paper model's temperature beside the energy model's
  double flip_fraction = 1.0;  // share of FLIP in the point velocity update; the rest is PIC
  bool skip_unreached = true;  // advance material nothing has reached in closed form (unreached.hpp)
  Smoothing volumetric_smoothing = Smoothing::automatic;  // tr L_p from the grid's field of it (volumetric_smoothing.hpp)
  double av_linear = -1.0;  // < 0 until parsed: automatic, auto_av_linear(every_body_solid())
  double av_quadratic = 2.0;
  double av_heat_flux = 10.0;  // beta of the artificial heat flux (artificial_heat_flux.hpp); 0: none
  std::int64_t seed = 1;

  // Output
  std::string output_dir = "output";
  double sample_interval = 10e-9;
  double snapshot_interval = 100e-9;
  std::vector<double> snapshot_times;  // further snapshot times, increasing [s]
  std::int64_t snapshot_compression = 0;
  bool snapshot_grid = false;

  Material material;  // the bare material keys: the material named "scene"
  // The materials a body may name: the library's (material_library.cpp), with the scene's
  // material.NAME.KEY values, and new ones those keys define.
  std::map<std::string, Material> materials;
  std::string flyer_material = "scene", target_material = "scene", window_material = "lif";
  double window_height = 0.0;  // [m] a window bonded to the target's free surface; 0: none
  Effects effects;
  std::vector<RegionSpec> regions;  // the paper's six unless the scene names its own
  std::vector<ProbeSpec> probes;    // none unless the scene names some
  double probe_interval = 0.0;      // [s] between rows of probes.csv; 0: every step

  // Where each key was set ("scene.cfg:12", "--set #1 (...)"), for errors found after parsing.
  std::map<std::string, std::string> origin;
  std::string where(const std::string& key) const {
    auto it = origin.find(key);
    return it != origin.end() ? it->second : source + " (default value)";
  }

  // The material of a body: the bare keys' ("scene") or a named one.
  const Material& material_of(Body b) const;
  // The material of that name: "scene" (the bare keys') or a named one the scene holds.
  const Material& material_by_name(const std::string& name) const;
  const std::string& material_name(Body b) const;
  // The names of the materials the bodies use, each once: the target's, the flyer's, the window's
  // (with a window); "scene" for the bare keys'.
  std::vector<std::string> materials_in_use() const;
  bool has_window() const { return window_height > 0.0; }
  // No body has voids (a window is always solid).
  bool every_body_solid() const { return porosity == 1.0 && flyer_porosity == 1.0; }
  // Every body of one material (the same constants, whatever their names).
  bool one_material() const;
  // The flyer's voids are the target's mirror image (flyer_mirror = on, both bodies equally porous).
  bool mirrors_flyer() const;
  // A body's initial velocity along y: the flyer's up, the target's (and its window's) down; a target
  // at rest has +0, not -0.
  double velocity_of(Body b) const { return b == Body::flyer ? flyer_velocity : 0.0 - target_velocity; }
  // The faster body's speed toward the impact plane.
  double fastest_body_speed() const;
  // Whether the artificial heat flux acts: it needs temperatures and the viscosity it follows.
  bool has_heat_flux() const { return effects.thermal && effects.artificial_viscosity && av_heat_flux > 0.0; }
  // Points carry their plastic heat W_p when some output reports the paper's temperature T_H + W_p/c_v.
  bool tracks_plastic_heat() const { return temperature_model == TemperatureModel::paper || paper_temperature; }
  // Material-point spacing h / ppc.
  double particle_spacing() const { return cell_size / static_cast<double>(particles_per_cell); }
  // Empty space kept on the grid beyond each body's free surface.
  double derived_grid_margin() const;
  // The z extent of a 3D column: depth, or the width when it is automatic.
  double derived_depth() const { return depth >= 0.0 ? depth : width; }
  // The lattice points of the material-point lattice across the column: columns in 2D, columns x
  // layers in 3D.
  double points_across() const;
};

// The default linear viscosity A1 (docs/method.md, "Choosing A1"), by what the scene simulates.
// Where every body is solid, 0.6: the ringing of a weaker linear term leaves the deviatoric stress
// behind a plastic shock below yield (at 1000 m/s and 5 um, sigma_n - P 4 MPa for the exact 107.2 at
// 0.2, 102.5 at 0.6; tests/test_two_wave.cpp) and opens spurious spall rows. Where a body is porous,
// 0.2: the band temperatures of a porous run rise with A1 at a given cell, and 0.2 is the nearer to
// their finest value at 5 um (2D, delta 1.1, 20 um voids, one layout: 610 K at 0.2 and 660 K at 0.6
// at 5 um, 620 K and 632 K at 1.25 um).
constexpr double kAvLinearSolid = 0.6, kAvLinearPorous = 0.2;
constexpr double auto_av_linear(bool every_body_solid) { return every_body_solid ? kAvLinearSolid : kAvLinearPorous; }

// Volumetric smoothing, automatically: on where a body is porous, off where every body is solid
// (since 2026-12-05; docs/method.md "Shock capturing"). At the collapse foci it keeps single points
// from being over-compressed: the 3D r/4 column of docs/3d.md (delta 1.1, 20 um voids, 5 um cells,
// 50 ns) takes 481 steps for 919, its hottest point 8.7 MJ/kg for 17.3, pressures -23.6..172 GPa for
// -44..355, 0.0076 % of the mass above 5 MJ/kg for 0.071 %, and its band 589 K for 615 K (the hot
// points no longer lift it). In a solid plate it spoils the elastic-plastic plateau (sigma_n - P
// 15 MPa for the exact 107) and raises the points' pressure scatter, so solid scenes go without.
constexpr Smoothing auto_volumetric_smoothing(bool every_body_solid) {
  return every_body_solid ? Smoothing::off : Smoothing::on;
}

// The default Courant numbers (docs/stability.md), by the shape function's measured error. In 2D
// every hard case holds to 0.99 once max_volume_change bounds the step of a collapsing void's jet.
// With the B-spline at points (and gimp, bilinear) 0.3, because the error of a larger step is not
// small (an isentropic release heats 74 K at 0.6 for 40 K at 0.3, test_release). The B-spline over
// the point domains heats 21 K at 0.6 (9 K at 0.3) and keeps the solid plateau within 0.2 %, so
// it takes 0.6: half the steps (the default since 2026-12-05). 3D likewise: every 3D hard case and
// the r/4 collapse-focus column hold at 0.6 with it (the column's band 1.4 K cooler and 0.6 % higher
// in pressure than at 0.3); with the others 0.3 (0.2 until 2026-12-04, when 3D jetting had stopped
// at 0.25).
constexpr double kCfl = 0.3, kCflDomain = 0.6;
// With the domain B-spline and a linear viscosity of at least a solid scene's A1 = 0.6 (so every
// solid scene by default), 0.8 (since 2026-12-06). The step counts the viscous speed
// (A1 + sqrt(A1^2 + 1)) c of a compressing point, 1.77 c at A1 = 0.6 for 1.22 c at 0.2, so 0.8
// gives compressing material the sound Courant number 0.45, below the 0.49 of the porous default
// (0.6 at A1 = 0.2), where 0.6 gave 0.34: the speed scene takes 838 steps for 1112 with its plateau
// unchanged (sigma_n 18113.3 MPa for 18112.6, the two-wave exact 18112.1; T 490.70 K for 490.67),
// and an isentropic release with the viscosity on heats 131 K at 0.8 for 134 K at 0.6 (the
// viscosity's heating, not the step's; docs/stability.md). The cost: the points' work mismatch
// grows (test_hugoniot, 10 um, 1000 m/s: -0.48 % of E for -0.31 %; its bound 0.5 %).
constexpr double kCflDomainViscous = 0.8;
// A scene's automatic cfl, by its shape function and (with the domain B-spline) its viscosity: the
// larger step where the viscosity is on with A1 >= 0.6.
inline double auto_cfl(const Scene& s) {
  if (s.shape_function != ShapeFunction::bspline2_domain) return kCfl;
  const bool strongly_viscous = s.effects.artificial_viscosity && s.av_linear >= kAvLinearSolid;
  return strongly_viscous ? kCflDomainViscous : kCflDomain;
}

// A scene error names the file, the line and the key: "scene.cfg:12: key 'porosity': ...".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Refuses (SceneError "PATH: cannot open the WHAT: REASON") a path that is not a regular file
// that can be read, with the system's reason: missing, a dangling symlink or a symlink loop, a
// directory, or a FIFO, socket or device (which would block or never end), or not readable.
void check_input_file(const std::string& path, const std::string& what);

// Reads a scene file and applies `overrides` ("key=value", from --set) on top.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Parses scene text; `name` stands for the file in messages.
Scene parse_scene(const std::string& text, const std::string& name,
                  const std::vector<std::string>& overrides = {});

// The key a --set argument ("key=value") sets, trimmed as the parser trims it.
std::string override_key(const std::string& arg);

// Warnings about settings that run but may not be what the user wants: a cfl measured unstable,
// thousands of snapshot files, millions of rows.
std::vector<std::string> scene_warnings(const Scene& scene);

// Every key with its resolved value in SI, one "key = value" line each: the scene exactly as run.
std::string resolved_scene(const Scene& scene);

// The documentation table of all keys (markdown), as in the README.
std::string key_reference_markdown();
// The built-in materials (mpmshock --materials): each one's source and every constant as the
// material.NAME.KEY line a scene would write.
std::string material_library_text();
// The material laws of the registry (mpmshock --laws): each one's slot, which built-in materials
// carry its constants, and its keys.
std::string material_laws_text();

// Why the flyer is not the mirror image of the target about y = 0 (its height, its own voids), or
// "" when it is: the condition for symmetry = on.
std::string asymmetry_of(const Scene& scene);

// The paper's default regions B800, B400, B100, T800, T400, T100.
std::vector<RegionSpec> paper_regions();

}  // namespace mpmshock
