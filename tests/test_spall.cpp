// Spall (spall = on): a 0.4 mm flyer on a 1.2 mm target at +-150 m/s, hydrodynamic (plasticity
// off), 10 um cells. The shock (2.25 GPa) reflects from both free surfaces as releases that meet
// inside the target; where the tension they make first exceeds the spall strength (1.2 GPa) the
// material fails. Theory: the releases meet 0.81 mm above the impact plane (their heads run at
// the Lagrangian sound speed of the shocked state, 5.75 km/s, and leave the flyer's back at 72 ns
// and the target's top at 216 ns), 0.39 mm below the free surface.
//
// Checked: the first failure lies at that plane (within 0.1 mm, ten cells); after every step no
// intact point holds a principal tension above the strength and no failed point holds any; energy
// stays conserved to round-off; without spall the same scene holds the full 2.2 GPa tension.
//
// Reported, not checked: the strength the free-surface pullback gives by the acoustic relation
// sigma = rho0 c0 du / 2. It comes out 0.5-0.8 GPa for the 1.2 GPa set (the same at 10, 5 and
// 2.5 um cells): the pullback is cut short by the spall signal of the whole failed zone, which
// is about 0.1 mm thick, and the releases are fans about 20 ns wide, not the steps the acoustic
// relation assumes. Issue 12 holds this open.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "check.hpp"
#include "mpmshock/diagnostics.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/spall.hpp"

using namespace mpmshock;

namespace {

struct Outcome {
  double first_failure_y = -1.0, max_tension = 0.0, pullback_strength = 0.0, energy_error = 1.0;
  std::size_t failed = 0;
};

Outcome run(const std::string& extra) {
  const Scene scene = parse_scene(
      "velocity = 150 m/s\nporosity = 1\nflyer_mirror = off\nwidth = 40 um\ntarget_height = 1.2 mm\n"
      "flyer_height = 0.4 mm\ncell_size = 10 um\nend_time = 420 ns\nplasticity = off\n" + extra,
      "spall");
  InitialState<2> initial = build_initial_state<2>(scene);
  const Particles<2>& p0 = initial.particles;
  double top = 0.0;
  for (std::size_t q = 0; q < p0.size(); ++q) top = std::max(top, p0.x[q][1]);
  std::vector<std::size_t> surface;  // the top cell's two rows of points
  for (std::size_t q = 0; q < p0.size(); ++q)
    if (p0.x[q][1] > top - 6e-6) surface.push_back(q);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const Totals start = compute_totals(sim.particles());
  const double strength = scene.spall_strength;
  Outcome out;
  double u_plateau = 0.0, u_min = 1e9;
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    const StepStatus s = sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
    if (!s.ok()) {
      check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(s));
      return out;
    }
    const Particles<2>& p = sim.particles();
    for (std::size_t q = 0; q < p.size(); ++q) {
      const double tension = max_principal_stress(p.has_strength() ? p.s[q] : Deviator<2>{}, p.P[q]);
      out.max_tension = std::max(out.max_tension, tension);
      if (p.failed(q)) {
        if (!(p.P[q] >= 0.0)) check::fail(__FILE__, __LINE__, "a failed point holds tension");
        if (out.first_failure_y < 0.0) out.first_failure_y = p.x[q][1];
      } else if (p.has_failure() && tension > strength) {
        check::fail(__FILE__, __LINE__, "an intact point holds tension above the strength");
      }
    }
    double u = 0.0;
    for (std::size_t q : surface) u += p.v[q][1];
    u /= static_cast<double>(surface.size());
    if (sim.time() > 260e-9 && sim.time() < 320e-9) u_plateau = std::max(u_plateau, u);  // after ringing
    if (sim.time() > 320e-9) u_min = std::min(u_min, u);
  }
  const Particles<2>& p = sim.particles();
  for (std::size_t q = 0; q < p.size(); ++q) out.failed += p.failed(q) ? 1 : 0;
  const Totals end = compute_totals(p);
  out.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
  out.pullback_strength = scene.material.density * scene.material.sound_speed * (u_plateau - u_min) / 2.0;
  return out;
}

}  // namespace

int main() {
  const Outcome spall = run("spall = on\nspall_strength = 1.2 GPa\n");
  std::printf("spall on: %zu points failed, the first at y = %.3f mm (theory 0.81); largest tension %.3f GPa; "
              "pullback strength %.2f GPa for 1.2 set; energy error %.1e\n",
              spall.failed, spall.first_failure_y * 1e3, spall.max_tension / 1e9, spall.pullback_strength / 1e9,
              spall.energy_error);
  CHECK(spall.failed > 0);
  CHECK_NEAR(spall.first_failure_y, 0.81e-3, 0.1e-3);
  CHECK(spall.max_tension <= 1.2e9);
  CHECK(spall.energy_error < 1e-10);

  const Outcome intact = run("");
  std::printf("spall off: largest tension %.3f GPa\n", intact.max_tension / 1e9);
  CHECK(intact.failed == 0);
  CHECK(intact.max_tension > 2.0e9);
  return check::result();
}
