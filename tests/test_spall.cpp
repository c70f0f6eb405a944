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
// Checked, with the default criterion (a point opens when the mean tension of its neighbourhood, its
// stencil, reaches the strength, or its own twice the strength): the first failure lies at that plane
// (within 0.1 mm, ten cells); after every step no opening point holds a principal tension above the
// strength and no separated point holds any; no mean over 3 cells of rows about an intact point
// exceeds the strength by more than 2 % (that band and the stencil's quadratic weights differ); some
// points separate; the strength the pullback gives is the set one within 0.1 GPa (8 %: the acoustic
// relation's rho0 c0 stands for the impedance of material in tension and of a release fan some 20 ns
// wide; it reads 1.17 GPa at 10 um cells, 1.18 at 5 and 2.5 um); energy stays conserved to
// round-off; without spall the same scene holds the full 2.2 GPa tension; with spall_void_fraction = 0
// (a point separates the moment it opens) the pullback reads well below the strength (0.5-0.7 GPa),
// the reason the tension is held while a point opens. With spall_criterion = point no intact point
// holds more than the strength. With strength (plasticity on) the pullback follows the
// elastic-plastic relation (below) to within 0.1 GPa: 1.14 GPa, where the acoustic one reads 1.05.
// The issue-28 case: the neighbourhood criterion fails no flyer point where the point criterion does.
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
  double first_failure_y = -1.0, max_tension = 0.0, max_band_tension = 0.0, pullback_strength = 0.0,
         energy_error = 1.0, du = 0.0;
  std::size_t failed = 0, separated = 0;
};

// The largest mean principal stress over 3 cells of rows (|y - y_p| < 1.5 h) about any intact point:
// the material's tension where the neighbourhood criterion judges it (the column is one-dimensional).
double largest_band_tension(const Particles<2>& p, double h) {
  std::vector<std::pair<double, double>> rows(p.size());  // (y, tension)
  for (std::size_t q = 0; q < p.size(); ++q)
    rows[q] = {p.x[q][1], max_principal_stress(p.has_strength() ? p.s[q] : Deviator<2>{}, p.P[q])};
  std::vector<std::size_t> order(p.size());
  for (std::size_t q = 0; q < p.size(); ++q) order[q] = q;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rows[a].first < rows[b].first; });
  std::vector<double> sum(p.size() + 1, 0.0), y(p.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    sum[k + 1] = sum[k] + rows[order[k]].second;
    y[k] = rows[order[k]].first;
  }
  double largest = -1e300;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (p.failed(order[k])) continue;
    const std::size_t lo = std::lower_bound(y.begin(), y.end(), y[k] - 1.5 * h) - y.begin();
    const std::size_t hi = std::upper_bound(y.begin(), y.end(), y[k] + 1.5 * h) - y.begin();
    largest = std::max(largest, (sum[hi] - sum[lo]) / static_cast<double>(hi - lo));
  }
  return largest;
}

Outcome run(const std::string& extra, bool plasticity = false) {
  const Scene scene = parse_scene(
      "velocity = 150 m/s\nporosity = 1\nflyer_mirror = off\nwidth = 40 um\ntarget_height = 1.2 mm\n"
      "flyer_height = 0.4 mm\ncell_size = 10 um\nend_time = 420 ns\n" +
          std::string(plasticity ? "" : "plasticity = off\n") + extra,
      "spall");
  const bool by_neighbourhood = scene.spall_criterion == SpallCriterion::neighbourhood;
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
      if (p.has_failure() && (p.failed(q) || !by_neighbourhood) && tension > strength * (1 + 1e-12))
        check::fail(__FILE__, __LINE__, "an opening point (or, judged point by point, an intact one) holds tension "
                                        "above the strength");
    }
    if (p.has_failure() && by_neighbourhood) out.max_band_tension = std::max(out.max_band_tension, largest_band_tension(p, scene.cell_size));
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
  out.du = u_plateau - u_min;
  out.pullback_strength = scene.material.density * scene.material.sound_speed * out.du / 2.0;
  return out;
}

// How many points of each body have failed at the end of a run (40 um wide; the caller sets the cells).
struct Flyer {
  std::size_t flyer = 0, target = 0;
};
Flyer failures_by_body(const std::string& text) {
  const Scene scene = parse_scene("porosity = 1\nflyer_mirror = off\nwidth = 40 um\n" + text, "flyer");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    const StepStatus s = sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
    if (!s.ok()) {
      check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(s));
      return {};
    }
  }
  Flyer out;
  const Particles<2>& p = sim.particles();
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.failed(q)) ++(p.body[q] == Body::flyer ? out.flyer : out.target);
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

  auto report = [](const char* what, const Outcome& o) {
    std::printf("%s: %zu points failed (%zu separated), the first at y = %.3f mm; largest point tension %.3f GPa, "
                "largest 3-cell band tension about an intact point %.3f GPa; free-surface pullback %.1f m/s, "
                "acoustic strength %.3f GPa; energy error %.1e\n",
                what, o.failed, o.separated, o.first_failure_y * 1e3, o.max_tension / 1e9, o.max_band_tension / 1e9,
                o.du, o.pullback_strength / 1e9, o.energy_error);
  };
  // The default criterion: the neighbourhood's tension.
  const Outcome spall = run("spall = on\nspall_strength = 1.2 GPa\n");
  report("spall on (theory: first failure at 0.81 mm)", spall);
  CHECK(spall.failed > 0);
  CHECK(spall.separated > 0);
  CHECK_NEAR(spall.first_failure_y, 0.81e-3, 0.1e-3);
  CHECK(spall.max_band_tension <= 1.2e9 * 1.02);  // the band's mean and the stencil's weighted mean differ
  CHECK(spall.max_tension <= 2.0 * 1.2e9 * (1 + 1e-12));  // spall_point_ceiling
  CHECK_NEAR(spall.pullback_strength, 1.2e9, 0.1e9);
  CHECK(spall.energy_error < 1e-10);

  // Judged point by point, no intact point holds more than the strength (checked in run()).
  const Outcome by_point = run("spall = on\nspall_strength = 1.2 GPa\nspall_criterion = point\n");
  report("spall on, spall_criterion = point", by_point);
  CHECK(by_point.max_tension <= 1.2e9 * (1 + 1e-12));
  CHECK_NEAR(by_point.first_failure_y, 0.81e-3, 0.1e-3);
  CHECK_NEAR(by_point.pullback_strength, 1.2e9, 0.1e9);

  // With strength the release runs ahead at the longitudinal speed c_L and the spall signal's front
  // overtakes the release's plastic part at the bulk speed c_b: the pullback relation is then
  // sigma_s = rho0 du c_L c_b / (c_L + c_b) (Romanchenko and Stepanov 1980; Kanel 2010), which is
  // 2 c_L / (c_L + c_b) = 1.09 times the acoustic rho0 c0 du / 2 for aluminium.
  const Outcome plastic = run("spall = on\nspall_strength = 1.2 GPa\n", true);
  const Scene plain = parse_scene("", "defaults");
  const Material& mat = plain.material;
  const double c_b = mat.sound_speed, c_L = std::sqrt(c_b * c_b + 4.0 * mat.shear_modulus() / (3.0 * mat.density));
  const double elastic_plastic = mat.density * plastic.du * c_L * c_b / (c_L + c_b);
  report("spall on, plasticity on", plastic);
  std::printf("  elastic-plastic pullback relation (c_L %.0f m/s, c_b %.0f m/s): %.3f GPa for 1.2 set\n", c_L, c_b,
              elastic_plastic / 1e9);
  CHECK_NEAR(elastic_plastic, 1.2e9, 0.1e9);
  CHECK(plastic.max_band_tension <= 1.2e9 * 1.02);
  CHECK(plastic.max_tension <= 2.0 * 1.2e9 * (1 + 1e-12));

  const Outcome at_once = run("spall = on\nspall_strength = 1.2 GPa\nspall_void_fraction = 0\n");
  report("spall_void_fraction = 0", at_once);
  CHECK(at_once.failed == at_once.separated);
  // Letting go at once reads a pullback below the gradual opening's: 0.94 GPa against 1.21 at the
  // default A1 (0.6 for these solid plates: 0.78 of it), 0.5-0.7 against 1.17 at A1 = 0.2 (measured).
  CHECK(at_once.pullback_strength < 0.8 * spall.pullback_strength);

  const Outcome intact = run("");
  report("spall off", intact);
  CHECK(intact.failed == 0);
  CHECK(intact.max_tension > 2.0e9);

  // The artefact the neighbourhood criterion removes: behind a 400 m/s impact of a 0.3 mm flyer (with
  // strength), the released flyer holds a two-cell pattern of point stresses about a mean near
  // zero; judged point by point its crests fail (with bspline2 at cfl 0.3: 64 flyer points at 10 um
  // cells, 48 at 5, 96 at 2.5; with bspline2_domain at cfl 0.6 and A1 = 0.2: 72 at 10 um, 96 at 5;
  // at a solid scene's default A1 = 0.6: 40 at 10 um, 64 at 5), judged by the neighbourhood none
  // does, and the target's spall zone forms as before. With A1 = 0.2 at 10 um from cfl 0.45 the
  // ringing release overshot to ~1.5 GPa of tension 22.5 um inside the flyer's back surface and
  // opened a row of 8 points there (none at cfl 0.3 or at 5 and 2.5 um; this case ran at 5 um from
  // 2026-12-05 until A1 = 0.6 removed it the same day).
  const std::string flyer_case =
      "velocity = 400 m/s\nflyer_height = 0.3 mm\ntarget_height = 1.5 mm\nend_time = 500 ns\nspall = on\n"
      "cell_size = 10 um\n";
  const Flyer flyer_by_point = failures_by_body(flyer_case + "spall_criterion = point\n");
  const Flyer flyer_by_neighbourhood = failures_by_body(flyer_case);
  std::printf("400 m/s, 0.3 mm flyer: failed flyer / target points, point criterion %zu / %zu, neighbourhood %zu / %zu\n",
              flyer_by_point.flyer, flyer_by_point.target, flyer_by_neighbourhood.flyer, flyer_by_neighbourhood.target);
  CHECK(flyer_by_point.flyer > 0);
  CHECK(flyer_by_neighbourhood.flyer == 0);
  CHECK(flyer_by_neighbourhood.target > 0);
  return check::result();
}
