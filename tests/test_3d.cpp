// 3D against what it must equal:
// - a 3D column three cells deep (the least depth a periodic column may have, one point per cell)
//   is the 2D plane-strain run, point for point in each of its three layers, with each shape
//   function, through the shock, its reflection at the free surfaces and the release;
// - symmetry = on and skip_unreached = on give the full 3D computation's outputs to round-off in a
//   porous run whose spheres cut the impact plane;
// - a porous 3D run through run_scene conserves mass exactly and momentum and energy to round-off,
//   and writes N x 3 snapshots.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
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

template <int D>
Particles<D> final_state(const Scene& scene) {
  InitialState<D> initial = build_initial_state<D>(scene);
  Simulation<D> sim(scene, initial.grid, std::move(initial.particles));
  compare::march(sim, scene.end_time, "column");
  return sim.particles();
}

void three_layers_are_plane_strain(const char* shape) {
  const std::string text = std::string("velocity = 1000 m/s\nporosity = 1\nwidth = 40 um\ntarget_height = 0.2 mm\n"
                                       "flyer_height = 0.2 mm\ncell_size = 10 um\nparticles_per_cell = 1\n"
                                       "end_time = 100 ns\ncfl = 0.3\nshape_function = ") + shape + "\n";
  const Particles<2> p2 = final_state<2>(parse_scene(text, "column", {"dimension=2"}));
  // 40 um wide, 30 um deep (40 um for bspline2_domain's 4-node stencil), 10 um cells, one point each.
  const std::size_t layers = std::string(shape) == "bspline2_domain" ? 4 : 3, columns = 4;
  const Particles<3> p3 =
      final_state<3>(parse_scene(text, "column", {"dimension=3", "depth=" + std::to_string(10 * layers) + "um"}));
  CHECK(p3.size() == layers * p2.size());
  // Lattice ids run row by row, each row layer by layer, each layer column by column.
  std::vector<std::size_t> by_id2(p2.size()), by_id3(p3.size());
  for (std::size_t q = 0; q < p2.size(); ++q) by_id2[p2.id[q]] = q;
  for (std::size_t q = 0; q < p3.size(); ++q) by_id3[p3.id[q]] = q;
  double dx = 0.0, dv = 0.0, dP = 0.0, dE = 0.0, P_max = 0.0, E_max = 0.0, z_off = 0.0, vz = 0.0;
  for (std::size_t n = 0; n < p3.size() && p3.size() == layers * p2.size(); ++n) {
    const std::size_t row = n / (layers * columns), layer = (n / columns) % layers, column = n % columns;
    const std::size_t q = by_id3[n], q2 = by_id2[row * columns + column];
    for (int d = 0; d < 2; ++d) {
      dx = std::max(dx, std::abs(p2.x[q2][d] - p3.x[q][d]));
      dv = std::max(dv, std::abs(p2.v[q2][d] - p3.v[q][d]));
    }
    z_off = std::max(z_off, std::abs(p3.x[q][2] - (static_cast<double>(layer) + 0.5) * 10e-6));  // layers stay put
    vz = std::max(vz, std::abs(p3.v[q][2]));
    dP = std::max(dP, std::abs(p2.P[q2] - p3.P[q]));
    dE = std::max(dE, std::abs(p2.E[q2] - p3.E[q]));
    P_max = std::max(P_max, std::abs(p2.P[q2]));
    E_max = std::max(E_max, std::abs(p2.E[q2]));
  }
  std::printf("%-8s three layers vs 2D: x %.1e m, v %.1e m/s, P %.1e and E %.1e of their peaks; "
              "z drift %.1e m, |v_z| %.1e m/s\n",
              shape, dx, dv, dP / P_max, dE / E_max, z_off, vz);
  // Round-off: the 3D weights of a node column sum to 1 and their z derivatives to 0 only to the
  // last bit, which is all that separates the two runs.
  CHECK(dx < 1e-12);
  CHECK(dv < 1e-6);
  CHECK(dP < 1e-10 * P_max);
  CHECK(dE < 1e-10 * E_max);
  CHECK(z_off < 1e-12);
  CHECK(vz < 1e-6);
}

RunResult run(const std::string& scene, const fs::path& out, std::vector<std::string> keys) {
  keys.insert(keys.end(), {"output_dir=" + out.string(), "probe.surface=surface", "probe.inside=point 40um 60um 20um"});
  return run_scene(load_scene(scene, keys), {true, true});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const std::string porous = argv[1];
  for (const char* shape : {"bspline2", "gimp", "bilinear", "bspline2_domain"}) three_layers_are_plane_strain(shape);

  const fs::path root = fs::temp_directory_path() / ("mpmshock_test_3d_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const RunResult whole = run(porous, root / "whole", {"symmetry=off", "skip_unreached=off"});
  const RunResult mirrored = run(porous, root / "mirrored", {"symmetry=on", "skip_unreached=off"});
  const RunResult both = run(porous, root / "both", {"symmetry=on", "skip_unreached=on"});
  for (const RunResult* r : {&whole, &mirrored, &both}) {
    CHECK(r->exit_code == kExitOk);
    CHECK(r->mass_error == 0.0);
    CHECK(r->momentum_error < 1e-12);
    CHECK(r->energy_error < 1e-10);
  }
  std::printf("porous 3D: %zu points, porosity %.4f with %zu spheres; energy error %.1e\n", whole.points,
              whole.porosity, whole.voids, whole.energy_error);
  CHECK(whole.points == 2 * mirrored.points);
  const InitialState<3> initial = build_initial_state<3>(load_scene(porous));
  std::size_t cutting = 0;  // spheres that cut the row of points on the plane
  for (const Void& v : initial.target.voids) cutting += v.y - v.r < 0.5 * load_scene(porous).particle_spacing();
  std::printf("%zu of %zu target spheres cut the plane's row of points\n", cutting, initial.target.voids.size());
  CHECK(cutting > 0);
  compare::same_run_outputs(root / "whole", root / "mirrored");
  compare::same_run_outputs(root / "whole", root / "both");
  const SnapshotHeader h = read_snapshot_header((root / "both" / "snapshot_00002.h5").string());
  CHECK(h.dimension == 3 && h.points == whole.points);
  fs::remove_all(root);
  return check::result();
}
