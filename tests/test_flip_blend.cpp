// flip_fraction: the PIC blend damps the point-to-point velocity noise FLIP leaves in a shocked
// plateau, turns the kinetic energy it removes into heat (solid impacts: energy within 1e-3), and
// never cools a point (a porous, jetting run with the blend finishes; the point's own kinetic
// energy change, used as its heat, had cooled jet tips below 0 K).
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "mpmshock/diagnostics.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"

using namespace mpmshock;

namespace {

struct Outcome {
  bool finished = false;
  double noise = 0.0, energy_error = 0.0;
};

Outcome run(const std::string& text) {
  const Scene scene = parse_scene(text, "blend");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const Totals start = compute_totals(sim.particles());
  Outcome out;
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    if (!sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time())).ok()) return out;
    if (!sim.check_at_sample().ok()) return out;  // the 0 K check, every step here
  }
  out.finished = true;
  const Particles<2>& p = sim.particles();
  double sum = 0.0, sum2 = 0.0, n = 0.0;  // v_y spread in the plateau 0.1 .. 0.4 mm
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.x[q][1] > 0.1e-3 && p.x[q][1] < 0.4e-3) {
      sum += p.v[q][1];
      sum2 += p.v[q][1] * p.v[q][1];
      n += 1.0;
    }
  out.noise = std::sqrt(std::max(sum2 / n - (sum / n) * (sum / n), 0.0));
  const Totals end = compute_totals(p);
  out.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
  return out;
}

}  // namespace

int main() {
  // The blend removes 1 - f of a point's departure from the grid's velocity per step, so its damping
  // per unit time follows the number of steps: checked at cfl 0.3, the default at 0.6 reported.
  // Measured (v_y spread, m/s, this scene): bspline2_domain at 0.3 5.85 -> 1.00, at 0.6 7.04 -> 2.96
  // (mostly from row to row; within a row 1.1 -> 0.3); bspline2 at 0.3 8.5 -> 0.7. At A1 = 0.2, where
  // there is noise to damp: a solid scene's default A1 = 0.6 leaves a tenth of it (0.61 and 0.43 m/s
  // at cfl 0.3 and 0.6, measured 2026-12-05), and with it the blend's energy error at cfl 0.3 is
  // 1.8e-3, above this test's 1e-3 (7.5e-4 at 0.6).
  const std::string solid =
      "porosity = 1\nwidth = 60 um\ntarget_height = 1 mm\nflyer_height = 1 mm\ncell_size = 10 um\nend_time = 120 ns\n"
      "av_linear = 0.2\n";
  struct Step {
    const char* setting;
    const char* name;
    double noise_bound;  // blend's spread over FLIP's
  };
  for (const Step& step : {Step{"cfl = 0.3\n", "cfl 0.3", 0.2}, Step{"", "default cfl", 0.5}}) {
    const Outcome flip = run(solid + step.setting), blend = run(solid + step.setting + "flip_fraction = 0.95\n");
    std::printf("solid, %s: v_y spread %.3f m/s with FLIP, %.3f with 0.95 PIC blend; energy error %.1e, %.1e\n",
                step.name, flip.noise, blend.noise, flip.energy_error, blend.energy_error);
    CHECK(flip.finished && blend.finished);
    CHECK(blend.noise < step.noise_bound * flip.noise);
    CHECK(blend.energy_error < 1e-3);
  }

  const std::string porous =
      "porosity = 1.1\nvoid_radius = 15 um\nwidth = 200 um\ntarget_height = 300 um\nflyer_height = 300 um\n"
      "cell_size = 5 um\nend_time = 40 ns\nflip_fraction = 0.95\n";
  const Outcome jets = run(porous);
  std::printf("porous delta 1.1 with the blend: %s, energy error %.1e\n", jets.finished ? "finished" : "stopped",
              jets.energy_error);
  CHECK(jets.finished);
  return check::result();
}
