// Isentropic release of a shocked block: no shock, no viscosity, no strength, so the exact flow
// keeps every point on its isentrope. With gamma/V constant and c_v constant the isentrope is
// T exp(gamma0 J) = const (test_temperature checks that), so theta = T exp(gamma0 (J - J0)) stays at
// its initial value and any rise of its mean is heat the discretisation made.
//
// The block is 400 um of aluminium in the Hugoniot state at J0 = 0.85 (18 GPa, T_H 489 K),
// translating at 500 m/s, released from both free surfaces for 120 ns (10 um cells, 2 x 2 points
// per cell). Measured spurious heating (2026-12-05): bspline2 40 K, cpGIMP 12 K, the B-spline over
// the point domains (bspline2_domain) 8.7 K at cfl 0.3; at cfl 0.6 74, 28 and 21 K; bilinear cells
// 138 K. Uniform GIMP (half-width fixed while the point is compressed) gave 137 K, hence cpGIMP. A compressed
// lattice moving across the grid is what a domain integrates exactly and points do not (test_shape).
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "mpmshock/eos.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"

using namespace mpmshock;

namespace {

double spurious_heating(const std::string& shape, double cfl, const std::string& viscosity = "off") {
  const double J0 = 0.85;
  const Scene scene = parse_scene(
      "velocity = 500 m/s\nporosity = 1\nwidth = 40 um\ntarget_height = 200 um\nflyer_height = 200 um\n"
      "cell_size = 10 um\nend_time = 120 ns\nplasticity = off\nartificial_viscosity = " + viscosity + "\nshape_function = " +
          shape + "\nsymmetry = off\ncfl = " + std::to_string(cfl) + "\n",  // the state set below is one block, not a symmetric impact
      "release");
  InitialState<2> initial = build_initial_state<2>(scene);
  Particles<2>& p = initial.particles;
  const double E0 = MieGruneisen(scene.material).hugoniot_energy(J0);
  for (std::size_t q = 0; q < p.size(); ++q) {  // one block, uniformly compressed along y, moving up
    p.v[q] = Vec<2>{{0.0, 500.0}};
    p.x[q][1] *= J0;
    p.F[q](1, 1) = J0;
    p.E[q] = E0;
  }
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const HugoniotTemperature thermal(scene.material);
  const double gamma0 = scene.material.gruneisen_gamma;
  auto mean_theta = [&] {
    const Particles<2>& pts = sim.particles();
    double sum = 0.0;
    for (std::size_t q = 0; q < pts.size(); ++q)
      sum += thermal.temperature(pts.J(q), pts.E[q]) * std::exp(gamma0 * (pts.J(q) - J0));
    return sum / static_cast<double>(pts.size());
  };
  const double before = mean_theta();
  CHECK_NEAR(before, thermal.hugoniot_temperature(J0), 1e-9);
  while (sim.time() < scene.end_time) {
    const StepStatus s = sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
    if (s.code != StepStatus::Code::ok) {
      std::printf("%s at cfl %g: %s\n", shape.c_str(), cfl, sim.describe(s).c_str());
      CHECK(false);
      return 1e9;
    }
  }
  const double heating = mean_theta() - before;
  std::printf("%-15s cfl %.1f, viscosity %-3s: spurious heating %6.2f K in 120 ns\n", shape.c_str(), cfl, viscosity.c_str(),
              heating);
  return heating;
}

}  // namespace

int main() {
  // At cfl 0.3, each shape against its measured level.
  CHECK(spurious_heating("gimp", 0.3) < 20.0);
  const double old_default = spurious_heating("bspline2", 0.3);  // the default until 2026-12-05
  CHECK(old_default < 50.0);
  CHECK(spurious_heating("bspline2_domain", 0.3) < 10.0);
  // The default since 2026-12-05 (bspline2_domain at cfl 0.6): half the steps of the old default,
  // and still less heating than it.
  const double now_default = spurious_heating("bspline2_domain", kCflDomain);
  CHECK(now_default < 25.0);
  CHECK(now_default < 0.6 * old_default);
  // With the viscosity on (a solid scene's A1 = 0.6) the block heats several times more (measured
  // 2026-12-06: 134 K at cfl 0.6; A1 = 0.2 72 K, A2 alone 35 K): the linear term acts on every
  // compression, the points' noise and the compressions the free surfaces reflect back into the
  // tension between the two releases, which steepen and may shock, so not all of it is spurious
  // (not separated). The larger automatic step of such scenes (0.8, scene.hpp) adds none of its own
  // (131 K).
  const double viscous = spurious_heating("bspline2_domain", kCflDomain, "on");
  CHECK(spurious_heating("bspline2_domain", kCflDomainViscous, "on") < viscous + 2.0);
  // Reported, not bounded: bspline2 at the larger step, and bilinear cells (noisy: README, "Method").
  spurious_heating("bspline2", 0.6);
  spurious_heating("bilinear", 0.3);
  return check::result();
}
