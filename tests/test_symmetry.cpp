// symmetry = on (the target alone, a symmetry plane at y = 0, the flyer its mirror image) against
// the whole impact: the same point states in a solid impact with each shape function, the same
// regions, probes, conservation and snapshots in a porous impact whose voids touch the plane; and
// which scenes are symmetric.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "compare_outputs.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/snapshot.hpp"

using namespace mpmshock;
namespace fs = std::filesystem;

namespace {

Scene parse(const std::string& text) { return parse_scene(text, "s.scene"); }

// The tests' tiny porous scene with more and smaller voids, so that some cut the row of points on
// the plane, run with symmetry on or off, and further keys.
std::vector<std::string> dense(const std::string& symmetry, std::vector<std::string> more = {}) {
  more.insert(more.end(), {"porosity=1.3", "void_radius=10um", "void_radius_spread=2um", "symmetry=" + symmetry});
  return more;
}

void which_scenes_are_symmetric() {
  CHECK(parse("velocity = 1000 m/s\n").symmetry == Symmetry::on);  // the paper's set-up, the default
  CHECK(parse("porosity = 1\nflyer_height = 2 mm\n").symmetry == Symmetry::off);
  CHECK(parse("porosity = 1.2\nflyer_mirror = off\n").symmetry == Symmetry::off);
  CHECK(parse("porosity = 1\nflyer_mirror = off\n").symmetry == Symmetry::on);  // no voids to differ
  CHECK(parse("heat_conduction = on\n").symmetry == Symmetry::on);  // conduction folds across the plane too
  CHECK(parse("symmetry = off\n").symmetry == Symmetry::off);
  CHECK_THROWS_WITH(parse("porosity = 1\nflyer_height = 2 mm\nsymmetry = on\n"), "s.scene:3", "'symmetry'",
                    "flyer_height");
  CHECK_THROWS_WITH(parse("porosity = 1.2\nflyer_mirror = off\nsymmetry = on\n"), "'symmetry'", "flyer_mirror");
  CHECK_THROWS_WITH(parse("symmetry = half\n"), "'symmetry'", "auto, on, off");
  // The resolved scene says which way the run went, and reads back the same.
  CHECK(resolved_scene(parse("")).find("symmetry = on\n") != std::string::npos);
}

// The mirror image of the target's initial points is the whole initial state, point for point.
void mirror_image_is_the_whole(const std::string& porous) {
  const InitialState<2> on = build_initial_state<2>(load_scene(porous, dense("on")));
  const InitialState<2> off = build_initial_state<2>(load_scene(porous, dense("off")));
  CHECK(on.mirror.on() && !off.mirror.on());
  CHECK(on.particles.size() == on.target.material_points);
  const Particles<2> whole = on.mirror.whole(on.particles);
  CHECK(whole.size() == off.particles.size());
  if (whole.size() != off.particles.size()) return;
  double worst = 0.0;
  std::size_t differ = 0;
  for (std::size_t p = 0; p < whole.size(); ++p) {
    for (int d = 0; d < 2; ++d) worst = std::max(worst, std::abs(whole.x[p][d] - off.particles.x[p][d]));
    differ += whole.id[p] != off.particles.id[p] || whole.body[p] != off.particles.body[p] ||
              whole.v[p][0] != off.particles.v[p][0] || whole.v[p][1] != off.particles.v[p][1] ||
              whole.m[p] != off.particles.m[p] || whole.V0[p] != off.particles.V0[p];
  }
  CHECK(differ == 0);
  CHECK(worst < 1e-15);  // the flyer's lattice and the reflected target's, to round-off of 1e-4 m
  // Voids that touch the plane, so that the comparison below tests the plane where it is open.
  std::size_t touching = 0;
  const double a = on.particles.V0[0] > 0 ? std::sqrt(on.particles.V0[0]) : 0.0;
  for (const Void& v : on.target.voids) touching += v.y - v.r < a;  // it cuts the row of points on the plane
  std::printf("porous scene: %zu target voids, %zu touch the plane\n", on.target.voids.size(), touching);
  CHECK(touching > 0);
}

// A solid impact, the target alone against the whole: every target point in the same state.
void solid_point_states_agree(const char* shape) {
  const std::string text = std::string("velocity = 1000 m/s\nporosity = 1\nwidth = 40 um\ntarget_height = 0.8 mm\n"
                                       "flyer_height = 0.8 mm\ncell_size = 10 um\nend_time = 150 ns\n"
                                       "shape_function = ") + shape + "\n";
  std::vector<Particles<2>> finals;
  for (const char* symmetry : {"on", "off"}) {
    const Scene scene = parse_scene(text, "solid", {std::string("symmetry=") + symmetry});
    InitialState<2> initial = build_initial_state<2>(scene);
    Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
    if (!compare::march(sim, scene.end_time, shape)) return;
    finals.push_back(sim.particles());
  }
  const Particles<2>& half = finals[0];
  const Particles<2>& whole = finals[1];
  CHECK(2 * half.size() == whole.size());
  // Round-off only: the two runs sum the same contributions in another order.
  compare::same_point_states(half, whole, whole.size() - half.size(), std::string(shape) + " solid, 150 ns");
}

// A porous impact whose voids touch the plane, through every output, the target alone against the
// whole; a band region across the plane and a probe in the flyer read the mirror image. `more`: further
// keys for both runs (heat_conduction = on: conduction's nodal sums fold across the plane too).
void porous_outputs_agree(const std::string& porous, const std::vector<std::string>& more = {}) {
  const fs::path root = fs::temp_directory_path() / ("mpmshock_test_symmetry_" + std::to_string(::getpid()));
  fs::remove_all(root);
  std::vector<RunResult> results;
  for (const char* symmetry : {"on", "off"}) {
    std::vector<std::string> keys = {"output_dir=" + (root / symmetry).string(),
                                     "region.across = band -100 um 100 um",
                                     "region.T100 = top 100 um", "probe.top = surface",
                                     "probe.flyer = point 101 um -151 um",
                                     "probe.target = point 101 um 151 um"};
    keys.insert(keys.end(), more.begin(), more.end());
    const Scene scene = load_scene(porous, dense(symmetry, keys));
    results.push_back(run_scene(scene, {true, false}));
    CHECK(results.back().exit_code == kExitOk);
  }
  const RunResult &on = results[0], &off = results[1];
  CHECK(on.symmetry && !off.symmetry);
  CHECK(2 * on.points == off.points);
  CHECK(on.mass_error == 0.0 && on.momentum_error < 1e-14 && on.energy_error < 1e-10);
  std::printf("energy error: %.2e on, %.2e off\n", on.energy_error, off.energy_error);
  // The snapshots show the whole impact: the same points, ids and bodies as the whole run's.
  compare::same_run_outputs(root / "on", root / "off");
  fs::remove_all(root);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const std::string porous = argv[1];
  which_scenes_are_symmetric();
  mirror_image_is_the_whole(porous);
  for (const char* shape : {"bspline2", "gimp", "bilinear", "bspline2_domain"}) solid_point_states_agree(shape);
  porous_outputs_agree(porous);
  // Conduction needs the hot spots of collapsed voids: its conductivity raised 100-fold so that in
  // the tiny run heat visibly moves (a diffusion length of a few cells), across the plane too.
  porous_outputs_agree(porous, {"heat_conduction=on", "thermal_conductivity=23700"});
  return check::result();
}
