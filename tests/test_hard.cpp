// A hard case (tests/data/hard/*.scene) stays numerically sound, or is refused clearly.
//
// The scene's first "# expect:" line says which: "stable" (the default), "refused REGEX" (set-up
// must throw a SceneError matching REGEX) or "stops REGEX" (the run, through run_scene, must stop
// with exit code 3 and a diagnostic matching REGEX, and write the state for inspection). A stable case is stepped to its end and, at every
// sample time, every material point must be finite with J > 0, density > 0 and T > 0; the total
// mass must be exactly the initial one; total momentum (zero in the symmetric impact) must stay
// below 1e-12 of sum m|v|; total energy within 1e-10 (see below); and no point may leave the grid.
// Arguments after the scene are key=value overrides: CTest runs every case a second time with
// every optional effect on (spall, heat conduction, thermal softening, taylor_quinney 0.9).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include <unistd.h>

#include "check.hpp"
#include "mpmshock/diagnostics.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"

using namespace mpmshock;

namespace {

std::string expectation(const std::string& path) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# expect:", 0) == 0) return line.substr(9);
  return " stable";
}

// Every point finite and physical; returns the number of bad points, printing the first.
template <int D>
std::size_t bad_points(const Particles<D>& p, const BodyTemperatures& thermal, double t) {
  std::size_t bad = 0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    const double J = p.J(q), T = thermal.energy_temperature(p, q);
    bool finite = std::isfinite(p.E[q]) && std::isfinite(p.P[q]) && std::isfinite(p.q[q]) && std::isfinite(J);
    for (int d = 0; d < D; ++d) finite = finite && std::isfinite(p.x[q][d]) && std::isfinite(p.v[q][d]);
    if (finite && J > 0 && p.density(q) > 0 && T > 0) continue;
    if (bad++ == 0)
      std::fprintf(stderr, "t = %g s: point %u: J = %g, density = %g, T = %g, E = %g, P = %g\n", t, p.id[q], J,
                   p.density(q), T, p.E[q], p.P[q]);
  }
  return bad;
}

// Steps a stable case to its end, checking every point and the conserved totals at each sample.
template <int D>
void run_stable(const Scene& scene) {
  InitialState<D> initial = build_initial_state<D>(scene);
  // symmetry = on: totals of the whole impact, whose y momentum is 0 by construction; x momentum
  // and energy still test the step (the all-effects variants run the whole domain: conduction)
  const MirrorImage<D> mirror = initial.mirror;
  Simulation<D> sim(scene, initial.grid, std::move(initial.particles));
  const BodyTemperatures thermal(scene.material_of(Body::flyer), scene.material_of(Body::target),
                                 scene.material_of(Body::window));
  const Totals start = mirror.whole(compute_totals(sim.particles()));
  double worst_energy = 0, worst_momentum = 0;
  double next = scene.sample_interval;
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    const double dt = std::min(sim.stable_time_step(), std::min(next, scene.end_time) - sim.time());
    const StepStatus status = sim.step(dt);
    if (!status.ok()) {
      check::fail(__FILE__, __LINE__, "the run stopped: " + sim.describe(status));
      break;
    }
    if (sim.time() < next * (1 - 1e-12) && sim.time() < scene.end_time * (1 - 1e-12)) continue;
    next += scene.sample_interval;
    const Totals now = mirror.whole(compute_totals(sim.particles()));
    CHECK(bad_points(sim.particles(), thermal, sim.time()) == 0);
    CHECK(now.mass == start.mass);
    // The change of the total momentum (zero in the symmetric impact, the flyer's in the laboratory frame).
    worst_momentum = std::max(worst_momentum, std::hypot(now.momentum[0] - start.momentum[0], now.momentum[1] - start.momentum[1],
                                                         now.momentum[2] - start.momentum[2]) /
                                                  start.momentum_magnitude);
    worst_energy = std::max(worst_energy, std::abs(now.total_energy() - start.total_energy()) / start.total_energy());
  }
  std::printf("%dD, %lld steps to %.4g ns, %zu points: worst relative momentum %.2e, worst relative energy error %.2e\n",
              D, static_cast<long long>(sim.steps()), sim.time() * 1e9, sim.particles().size(), worst_momentum,
              worst_energy);
  // Each step's nodal forces sum to zero up to round-off, so the momentum's change is a sum of
  // round-off: ~1e-16 relative per step, well under 1e-12 over 1e4 steps.
  CHECK(worst_momentum < 1e-12);
  // The energy update is the exact work of the step's forces, so the total changes only by the
  // round-off of the per-point sums: ~1e-16 relative per step, ~1e-12 if it grew linearly over
  // 1e4 steps; 1e-10 leaves a factor of 100 and still fails on any real energy error.
  CHECK(worst_energy < 1e-10);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const std::string path = argv[1];
  const std::vector<std::string> overrides(argv + 2, argv + argc);
  const std::string expect = expectation(path);
  std::printf("%s: expect%s\n", path.c_str(), expect.c_str());

  if (expect.rfind(" refused ", 0) == 0) {
    const std::regex pattern(expect.substr(9));
    try {
      const Scene scene = load_scene(path, overrides);
      if (scene.dimension == 3) build_initial_state<3>(scene);
      else build_initial_state<2>(scene);
      check::fail(__FILE__, __LINE__, "the scene was not refused");
    } catch (const SceneError& e) {
      std::printf("refused: %s\n", e.what());
      CHECK(std::regex_search(std::string(e.what()), pattern));
    }
    return check::result();
  }

  if (expect.rfind(" stops ", 0) == 0) {
    const std::regex pattern(expect.substr(7));
    const auto dir = std::filesystem::temp_directory_path() / ("mpmshock_hard_" + std::to_string(::getpid()));
    std::vector<std::string> with_dir = overrides;
    with_dir.push_back("output_dir=" + dir.string());
    const RunResult r = run_scene(load_scene(path, with_dir), {true, true});
    std::printf("exit code %d: %s\n", r.exit_code, r.failure.c_str());
    CHECK(r.exit_code == kExitNumerical);
    CHECK(std::regex_search(r.failure, pattern));
    CHECK(std::filesystem::exists(dir / "snapshot_00001.h5"));  // the state that went wrong
    std::filesystem::remove_all(dir);
    return check::result();
  }

  const Scene scene = load_scene(path, overrides);
  if (scene.dimension == 3) run_stable<3>(scene);
  else run_stable<2>(scene);
  return check::result();
}
