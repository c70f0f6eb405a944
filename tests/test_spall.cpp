// Spall (spall = on): a 0.4 mm flyer on a 1.2 mm target at +-150 m/s, hydrodynamic (plasticity
// off), 10 um cells. The shock (2.25 GPa) reflects from both free surfaces as releases that meet
// inside the target; where the tension they make first reaches the spall strength (1.2 GPa) the
// material opens, its tension held at the strength, and separates once its void fraction reaches
// spall_void_fraction (0.15). Theory: the releases meet 0.81 mm above the impact plane (their heads
// run at the Lagrangian sound speed of the shocked state, 5.75 km/s, and leave the flyer's back at
// 72 ns and the target's top at 216 ns), 0.39 mm below the free surface; the free-surface velocity
// falls from its plateau by du = 2 sigma_s / (rho0 c0) = 166 m/s before the spall signal turns it
// back (the acoustic relation sigma_s = rho0 c0 du / 2).
//
// Checked: the first failure lies at that plane (within 0.1 mm, ten cells); after every step no
// intact or opening point holds a principal tension above the strength and no separated point holds
// any; some points separate; the strength the pullback gives is the set one within 0.1 GPa (8 %:
// the acoustic relation's rho0 c0 stands for the impedance of material in tension and of a release
// fan some 20 ns wide; it reads 1.17 GPa at 10 um cells, 1.18 at 5 and 2.5 um); energy stays
// conserved to round-off; without spall the same scene holds the full 2.2 GPa tension; with
// spall_void_fraction = 0 (a point separates the moment it reaches the strength) the pullback reads
// well below the strength (0.5-0.7 GPa), the reason the tension is held while a point opens.
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
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
  std::size_t failed = 0, separated = 0;
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
  int plateau_steps = 0;
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
      if (p.failed(q) && p.damage[q] == 1.0 && !(p.P[q] >= 0.0))
        check::fail(__FILE__, __LINE__, "a separated point holds tension");
      if (p.failed(q) && out.first_failure_y < 0.0) out.first_failure_y = p.x[q][1];
      if (p.has_failure() && tension > strength)
        check::fail(__FILE__, __LINE__, "an intact or opening point holds tension above the strength");
    }
    double u = 0.0;
    for (std::size_t q : surface) u += p.v[q][1];
    u /= static_cast<double>(surface.size());
    if (sim.time() > 260e-9 && sim.time() < 320e-9) {  // after the arrival's ringing
      u_plateau += u;
      ++plateau_steps;
    }
    if (sim.time() > 320e-9) u_min = std::min(u_min, u);
  }
  const Particles<2>& p = sim.particles();
  for (std::size_t q = 0; q < p.size(); ++q) {
    out.failed += p.failed(q) ? 1 : 0;
    out.separated += p.failed(q) && p.damage[q] == 1.0 ? 1 : 0;
  }
  const Totals end = compute_totals(p);
  out.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
  u_plateau /= plateau_steps;
  out.pullback_strength = scene.material.density * scene.material.sound_speed * (u_plateau - u_min) / 2.0;
  return out;
}

}  // namespace

int main() {
  // The law in closed form: damage is the opened void fraction 1 - J_f/J over f_c, never falling;
  // tension held at the strength while opening, none once separated.
  const Spall law{1.2e9, 0.15};
  CHECK_NEAR(law.damage(0.9, 0.9 / (1 - 0.075), 0.0), 0.5, 1e-12);
  CHECK(law.damage(0.9, 0.85, 0.3) == 0.3);
  CHECK(law.damage(0.9, 2.0, 0.0) == 1.0);
  CHECK(law.pressure(-2e9, 0.5) == -1.2e9);
  CHECK(law.pressure(-2e9, 1.0) == 0.0);
  CHECK(law.pressure(1e9, 1.0) == 1e9);
  const Spall at_once_law{1.2e9, 0.0};
  CHECK(at_once_law.damage(0.9, 0.9, 0.0) == 1.0);

  // The largest principal stress in 3D (trigonometric, from J2 and J3) against Eigen's eigenvalues
  // of random deviators, and equal to the plane-strain formula on a deviator with no yz, zx.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e9, 1e9);
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Deviator<3> d{u(rng), u(rng), u(rng), u(rng), u(rng)};
    Eigen::Matrix3d m;
    m << d.xx, d.xy, d.zx(), d.xy, d.yy, d.yz(), d.zx(), d.yz(), d.zz();
    const double P = u(rng), largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().maxCoeff() - P;
    worst = std::max(worst, std::abs(max_principal_stress(d, P) - largest) / 1e9);
    const Deviator<2> plane{d.xx, d.yy, d.xy};
    worst = std::max(worst, std::abs(max_principal_stress(Deviator<3>{d.xx, d.yy, d.xy, 0.0, 0.0}, P) -
                                     max_principal_stress(plane, P)) / 1e9);
  }
  std::printf("3D largest principal stress against Eigen and the plane-strain formula: %.1e of 1 GPa\n", worst);
  CHECK(worst < 1e-12);

  const Outcome spall = run("spall = on\nspall_strength = 1.2 GPa\n");
  std::printf("spall on: %zu points failed (%zu separated), the first at y = %.3f mm (theory 0.81); largest "
              "tension %.3f GPa; pullback strength %.3f GPa for 1.2 set; energy error %.1e\n",
              spall.failed, spall.separated, spall.first_failure_y * 1e3, spall.max_tension / 1e9,
              spall.pullback_strength / 1e9, spall.energy_error);
  CHECK(spall.failed > 0);
  CHECK(spall.separated > 0);
  CHECK_NEAR(spall.first_failure_y, 0.81e-3, 0.1e-3);
  CHECK(spall.max_tension <= 1.2e9 * (1 + 1e-12));
  CHECK_NEAR(spall.pullback_strength, 1.2e9, 0.1e9);
  CHECK(spall.energy_error < 1e-10);

  const Outcome at_once = run("spall = on\nspall_strength = 1.2 GPa\nspall_void_fraction = 0\n");
  std::printf("spall_void_fraction = 0: pullback strength %.3f GPa for 1.2 set\n", at_once.pullback_strength / 1e9);
  CHECK(at_once.failed == at_once.separated);
  CHECK(at_once.pullback_strength < 0.9e9);

  const Outcome intact = run("");
  std::printf("spall off: largest tension %.3f GPa\n", intact.max_tension / 1e9);
  CHECK(intact.failed == 0);
  CHECK(intact.max_tension > 2.0e9);
  return check::result();
}
