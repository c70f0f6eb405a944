// The artificial heat flux (av_heat_flux, artificial_heat_flux.hpp) does what it is for and nothing
// else: at the foci of collapsing voids it removes the single points heated to thousands of kelvin
// (wall heating), with energy conserved to round-off; in a solid impact's plateau, where the
// temperature is uniform, it leaves the Rankine-Hugoniot state alone (within 0.2 % in pressure and
// density, 2 K in temperature); with several materials too.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "mpmshock/diagnostics.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"

using namespace mpmshock;

namespace {

struct Outcome {
  bool finished = false;
  double energy_error = 1.0;
  double T_max = 0.0, hot_mass = 0.0;     // hottest point; mass share above 5 MJ/kg
  double P = 0.0, rho = 0.0, T = 0.0;     // means over the band 0.3-0.6 mm of the target
};

Outcome run(const std::string& text) {
  const Scene scene = parse_scene(text, "heat-flux");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const Totals start = compute_totals(sim.particles());
  const HugoniotTemperature thermal(scene.material);
  Outcome out;
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    const StepStatus st = sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
    if (!st.ok()) {
      check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(st));
      return out;
    }
  }
  out.finished = true;
  const Particles<2>& p = sim.particles();
  const Totals end = compute_totals(p);
  out.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
  double mass = 0, hot = 0, n = 0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    const double T = thermal.temperature(p.J(q), p.E[q]);
    out.T_max = std::max(out.T_max, T);
    mass += p.m[q];
    if (p.E[q] > 5e6) hot += p.m[q];
    if (p.x[q][1] > 0.3e-3 && p.x[q][1] < 0.6e-3) out.P += p.P[q], out.rho += p.density(q), out.T += T, ++n;
  }
  out.hot_mass = hot / mass;
  if (n > 0) out.P /= n, out.rho /= n, out.T /= n;
  return out;
}

}  // namespace

int main() {
  // A solid plate at 1000 m/s: the band lies in the plateau at 200 ns.
  const std::string solid =
      "velocity = 1000 m/s\nporosity = 1\nwidth = 40 um\ntarget_height = 1.6 mm\nflyer_height = 1.6 mm\n"
      "cell_size = 10 um\nend_time = 200 ns\n";
  const Outcome plain = run(solid + "av_heat_flux = 0\n"), flux = run(solid + "av_heat_flux = 10\n");
  std::printf("solid plateau: P %.4f / %.4f GPa, rho %.2f / %.2f, T %.1f / %.1f K (without / with); energy %.1e / %.1e\n",
              plain.P / 1e9, flux.P / 1e9, plain.rho, flux.rho, plain.T, flux.T, plain.energy_error, flux.energy_error);
  CHECK(plain.finished && flux.finished);
  CHECK_REL(flux.P, plain.P, 0.002);
  CHECK_REL(flux.rho, plain.rho, 0.002);
  CHECK_NEAR(flux.T, plain.T, 2.0);
  CHECK(flux.energy_error < 1e-12);

  // Porous delta 1.1, voids of 20 um at 5 um cells, 60 ns: the collapse foci, without the volumetric
  // smoothing a porous scene takes by default (the flux's own effect).
  const std::string porous =
      "velocity = 1000 m/s\nporosity = 1.1\nvoid_radius = 20 um\nwidth = 0.4 mm\ntarget_height = 0.4 mm\n"
      "flyer_height = 0.4 mm\ncell_size = 5 um\nend_time = 60 ns\n";
  const std::string unsmoothed = porous + "volumetric_smoothing = off\n";
  const Outcome foci = run(unsmoothed + "av_heat_flux = 0\n"), tamed = run(unsmoothed + "av_heat_flux = 10\n");
  std::printf("porous foci: hottest point %.0f / %.0f K, mass above 5 MJ/kg %.3f / %.3f %%; energy %.1e / %.1e\n",
              foci.T_max, tamed.T_max, 100 * foci.hot_mass, 100 * tamed.hot_mass, foci.energy_error, tamed.energy_error);
  CHECK(foci.finished && tamed.finished);
  CHECK(foci.T_max > 10000.0);          // the artefact is there without the flux ...
  CHECK(tamed.T_max < 0.2 * foci.T_max);  // ... and gone with it
  CHECK(tamed.hot_mass < 0.6 * foci.hot_mass);
  CHECK(tamed.energy_error < 1e-12);
  // The porous defaults, the flux with volumetric smoothing: the hot mass the flux leaves falls again
  // (measured 2026-12-05: 0.013 % for 0.073 %, the hottest point 1631 K for 1871 K).
  const Outcome defaults = run(porous);
  std::printf("porous defaults (with volumetric smoothing): hottest point %.0f K, mass above 5 MJ/kg %.3f %%; energy %.1e\n",
              defaults.T_max, 100 * defaults.hot_mass, defaults.energy_error);
  CHECK(defaults.finished);
  CHECK(defaults.hot_mass < 0.3 * tamed.hot_mass);
  CHECK(defaults.T_max <= tamed.T_max);
  CHECK(defaults.energy_error < 1e-12);

  // Several materials, a solid copper flyer on the porous aluminium target: the points' heat
  // capacities differ by body, so P2G carries their nodal sum C_i too (heat_flux_rider.hpp's three
  // sums). Energy is still conserved to round-off, and the flux still tames the foci.
  const std::string copper =
      "velocity = 1000 m/s\nporosity = 1.1\nvoid_radius = 15 um\nwidth = 0.2 mm\ntarget_height = 0.3 mm\n"
      "flyer_height = 0.2 mm\ncell_size = 5 um\nend_time = 50 ns\nvolumetric_smoothing = off\n"
      "flyer_material = copper\nflyer_porosity = 1\n";
  const Outcome cu_foci = run(copper + "av_heat_flux = 0\n"), cu_tamed = run(copper + "av_heat_flux = 10\n");
  std::printf("copper on porous aluminium: mass above 5 MJ/kg %.3f / %.3f %%; energy %.1e / %.1e\n",
              100 * cu_foci.hot_mass, 100 * cu_tamed.hot_mass, cu_foci.energy_error, cu_tamed.energy_error);
  CHECK(cu_foci.finished && cu_tamed.finished);
  CHECK(cu_tamed.hot_mass < 0.6 * cu_foci.hot_mass);
  CHECK(cu_tamed.energy_error < 1e-12);
  return check::result();
}
