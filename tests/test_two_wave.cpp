// The elastic-plastic two-wave structure of a solid symmetric impact with von Mises strength
// (linear isotropic hardening), against its exact solution from the jump conditions:
//
//   precursor  uniaxial elastic compression to yield, J_1 = exp(-sigma_Y0 / (2 G)) (hypoelastic
//              s_yy = (4/3) G ln J), normal stress sigma_1 = P(J_1, E_1) + (2/3) sigma_Y0 (the
//              HEL), E_1 = sigma_1 (1 - J_1) / (2 rho0); it runs at U_1 = sqrt(sigma_1 / (rho0 (1 - J_1)))
//              (-> c_L = sqrt((K + 4G/3) / rho0) for a weak precursor) and moves the material by u_1 = U_1 (1 - J_1);
//   plastic    from state 1 to the piston speed u_2 = v: sigma_2 - sigma_1 = rho0 (u_2 - u_1)^2 / (J_1 - J_2),
//              E_2 = E_1 + (sigma_1 + sigma_2)(J_1 - J_2) / (2 rho0), sigma_2 = P(J_2, E_2) + (2/3) Y(eps_p),
//              eps_p = ((2/3)|ln J_2| - sigma_Y0 / (3G)) / (1 + H / (3G)) for monotone uniaxial strain.
//
// K = rho0 c0^2 is the equation of state's; G and H come from E, nu and E_tan. The run is a narrow
// periodic column at 5 um cells, read as a 1D problem: the precursor's speed from its front over
// time, its plateau's normal stress (the HEL), and the plastic plateau's normal stress, its excess
// over the pressure (the deviator on the yield surface) and plastic strain.
//
// At the defaults of a solid scene (av_linear = auto = 0.6, cfl = auto = 0.6: scene.hpp). With
// the porous scenes' A1 = 0.2 it fails (measured 2026-12-05, bspline2_domain, 5 um): the ringing
// plastic front leaves the plateau below yield, sigma_n - P 46.0 MPa for 88.7 at 300 m/s and
// 4.0 MPa for 107.2 at 1000 m/s, and the points yield back and forth (eps_p 0.197 for 0.106); A1 =
// 0.5 holds 300 m/s (88.2 MPa) but not 1000 m/s (43.4 MPa), 0.6 holds both (the last case below).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "check.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"

using namespace mpmshock;

namespace {

struct TwoWave {
  double J1, sigma1, E1, U1, u1;            // precursor (HEL) state and speed
  double J2, sigma2, P2, eps_p2, U2, rho2;  // plastic state
};

TwoWave exact_two_wave(const Material& mat, double v) {
  const MieGruneisen eos(mat);
  const double rho0 = mat.density, G = mat.shear_modulus(), H = mat.plastic_modulus(), Y0 = mat.yield_stress;
  TwoWave w{};
  w.J1 = std::exp(-Y0 / (2.0 * G));
  w.sigma1 = Y0;
  for (int k = 0; k < 100; ++k) {  // sigma_1 and E_1 depend on each other weakly: a fixed point
    w.E1 = w.sigma1 * (1.0 - w.J1) / (2.0 * rho0);
    w.sigma1 = eos.pressure(w.J1, w.E1) + (2.0 / 3.0) * Y0;
  }
  w.U1 = std::sqrt(w.sigma1 / (rho0 * (1.0 - w.J1)));
  w.u1 = w.U1 * (1.0 - w.J1);
  // The plastic state at J_2: its normal stress on the yield surface, with its energy from the jump.
  auto state = [&](double J2, double& sigma2, double& P2, double& eps_p) {
    eps_p = ((2.0 / 3.0) * -std::log(J2) - Y0 / (3.0 * G)) / (1.0 + H / (3.0 * G));
    const double Y = Y0 + H * eps_p;
    sigma2 = w.sigma1;
    for (int k = 0; k < 100; ++k) {
      const double E2 = w.E1 + (w.sigma1 + sigma2) * (w.J1 - J2) / (2.0 * rho0);
      P2 = eos.pressure(J2, E2);
      sigma2 = P2 + (2.0 / 3.0) * Y;
    }
  };
  // Momentum across the plastic wave decides J_2 (bisection: the residual rises with compression).
  double lo = w.J1 * (1.0 - 1e-9), hi = 0.5;
  for (int k = 0; k < 200; ++k) {
    const double J2 = 0.5 * (lo + hi);
    double sigma2, P2, eps_p;
    state(J2, sigma2, P2, eps_p);
    const double residual = (sigma2 - w.sigma1) * (w.J1 - J2) - rho0 * (v - w.u1) * (v - w.u1);
    (residual < 0.0 ? lo : hi) = J2;
  }
  w.J2 = 0.5 * (lo + hi);
  state(w.J2, w.sigma2, w.P2, w.eps_p2);
  w.U2 = (v - w.u1) / (w.J1 - w.J2);
  w.rho2 = rho0 / w.J2;
  return w;
}

// Row means of a quantity over the target, by height.
template <class F>
std::vector<double> rows_of(const Particles<2>& p, double spacing, int rows, F f) {
  std::vector<double> sum(static_cast<std::size_t>(rows), 0.0), count(static_cast<std::size_t>(rows), 0.0);
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (p.body[q] != Body::target || p.x[q][1] < 0) continue;
    const int b = static_cast<int>(p.x[q][1] / spacing);
    if (b >= rows) continue;
    sum[static_cast<std::size_t>(b)] += f(q);
    count[static_cast<std::size_t>(b)] += 1;
  }
  for (int b = 0; b < rows; ++b) sum[static_cast<std::size_t>(b)] = count[static_cast<std::size_t>(b)] > 0 ? sum[static_cast<std::size_t>(b)] / count[static_cast<std::size_t>(b)] : 0.0;
  return sum;
}

// The normal stress sigma_n = -sigma_yy = P + q - s_yy of a point.
double normal_stress(const Particles<2>& p, std::size_t q) { return p.P[q] + p.q[q] - p.s[q].yy; }

// The height (from the impact plane) of the highest row where f exceeds `level`.
double front_above(const std::vector<double>& rows, double spacing, double level) {
  for (int b = static_cast<int>(rows.size()) - 1; b > 0; --b)
    if (rows[static_cast<std::size_t>(b - 1)] > level && rows[static_cast<std::size_t>(b)] <= level)
      return spacing * (b - 0.5 + (level - rows[static_cast<std::size_t>(b - 1)]) /
                                      (rows[static_cast<std::size_t>(b)] - rows[static_cast<std::size_t>(b - 1)]));
  return 0.0;
}

struct Measured {
  double U1, hel, sigma2, excess2, eps_p2, rho2;
};

// `law`: further scene lines (the strength law, the shape function). `laboratory`: the same impact
// with the target at rest and the flyer at 2 v, so that the shocked material moves across the grid
// at v (in the symmetric frame it rests on it); the states are the same, moved by v.
Measured run(double v, double end_time, const std::string& law = "", bool laboratory = false) {
  char text[768];
  std::snprintf(text, sizeof text,
                "flyer_velocity = %g m/s\ntarget_velocity = %g m/s\nporosity = 1\nwidth = 20 um\n"
                "target_height = 3.2 mm\nflyer_height = 3.2 mm\n"
                "cell_size = 5 um\nend_time = %g s\n%s",
                laboratory ? 2 * v : v, laboratory ? 0.0 : v, end_time, law.c_str());
  const double ahead = laboratory ? 0.0 : v;  // the speed of the material ahead of the precursor
  const Scene scene = parse_scene(text, "two-wave");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const double spacing = scene.particle_spacing();
  const int rows = static_cast<int>(3.2e-3 / spacing) + 8;
  const TwoWave w = exact_two_wave(scene.material, v);
  std::vector<double> ts, fronts;
  double next = 0.5 * end_time;
  while (sim.time() < end_time * (1 - 1e-12)) {
    const double dt = std::min(sim.stable_time_step(), next - sim.time());
    const StepStatus st = sim.step(dt);
    if (!st.ok()) {
      check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(st));
      return {};
    }
    if (sim.time() >= next - 1e-18) {
      const Particles<2>& p = sim.particles();
      const auto sigma = rows_of(p, spacing, rows, [&](std::size_t q) { return normal_stress(p, q); });
      ts.push_back(sim.time());
      fronts.push_back(front_above(sigma, spacing, 0.5 * w.sigma1));
      next += 0.05 * end_time;
    }
  }
  // The precursor's grid speed is U_1 - `ahead` (the material ahead moves down at it): least squares.
  double mt = 0, my = 0;
  for (std::size_t k = 0; k < ts.size(); ++k) mt += ts[k] / ts.size(), my += fronts[k] / ts.size();
  double num = 0, den = 0;
  for (std::size_t k = 0; k < ts.size(); ++k) num += (ts[k] - mt) * (fronts[k] - my), den += (ts[k] - mt) * (ts[k] - mt);
  Measured m{};
  m.U1 = num / den + ahead;

  const Particles<2>& p = sim.particles();
  const auto rho = rows_of(p, spacing, rows, [&](std::size_t q) { return p.density(q); });
  const double elastic_front = fronts.back();
  const double plastic_front = front_above(rho, spacing, 0.5 * (scene.material.density / w.J1 + w.rho2));
  // The HEL: the median of the row means between the plastic front and the precursor's (both fronts
  // are smeared over tens of um, the plateau between them is a few cells); the plastic plateau: the
  // middle half between the impact plane and the plastic front.
  const auto sigma = rows_of(p, spacing, rows, [&](std::size_t q) { return normal_stress(p, q); });
  std::vector<double> between;
  for (int r = 0; r < rows; ++r)
    if ((r + 0.5) * spacing > plastic_front && (r + 0.5) * spacing < elastic_front) between.push_back(sigma[static_cast<std::size_t>(r)]);
  std::sort(between.begin(), between.end());
  m.hel = between.empty() ? 0.0 : between[between.size() / 2];
  double n2 = 0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (p.body[q] != Body::target) continue;
    const double y = p.x[q][1];
    if (y > 0.25 * plastic_front && y < 0.75 * plastic_front) {
      m.sigma2 += normal_stress(p, q);
      m.excess2 += normal_stress(p, q) - p.P[q];
      m.eps_p2 += p.eps_p[q];
      m.rho2 += p.density(q);
      ++n2;
    }
  }
  m.sigma2 /= n2, m.excess2 /= n2, m.eps_p2 /= n2, m.rho2 /= n2;
  std::printf("v = %4.0f m/s: precursor %.0f m/s (exact %.0f), HEL %.1f MPa (%.1f); plateau sigma_n %.1f MPa (%.1f), "
              "sigma_n - P %.1f MPa (%.1f), eps_p %.4f (%.4f), rho %.1f (%.1f); fronts %.0f / %.0f um\n",
              v, m.U1, w.U1, m.hel / 1e6, w.sigma1 / 1e6, m.sigma2 / 1e6, w.sigma2 / 1e6, m.excess2 / 1e6,
              (w.sigma2 - w.P2) / 1e6, m.eps_p2, w.eps_p2, m.rho2, w.rho2, plastic_front * 1e6, elastic_front * 1e6);
  return m;
}

}  // namespace

int main() {
  const Material al;  // the paper's aluminium with the errata
  {
    // The closed form against the numbers of physics-notes section 3 (K = rho0 c0^2).
    const TwoWave w = exact_two_wave(al, 300.0);
    const double K = al.density * al.sound_speed * al.sound_speed, G = al.shear_modulus();
    CHECK_REL(w.sigma1, al.yield_stress * (K + 4.0 * G / 3.0) / (2.0 * G), 0.01);  // 259.8 MPa, linearised
    CHECK_REL(w.U1, std::sqrt((K + 4.0 * G / 3.0) / al.density), 0.01);           // c_L = 6.44 km/s
    CHECK_REL(w.sigma2, 4705.5e6, 2e-4);
    // On the yield surface sigma_n - P = (2/3)(sigma_Y0 + H eps_p) = 88.7 MPa; physics-notes' 87.6 MPa
    // is (2/3) Y at eps_p = 0.0295, not at its own 0.0337.
    CHECK_REL(w.sigma2 - w.P2, (2.0 / 3.0) * (al.yield_stress + al.plastic_modulus() * w.eps_p2), 1e-12);
    CHECK_REL(w.eps_p2, 0.0337, 3e-3);
    CHECK_REL(w.rho2, 2847.1, 1e-4);
  }
  // 300 m/s: the precursor runs ahead of the plastic wave by ~0.35 mm in 400 ns.
  const TwoWave w = exact_two_wave(al, 300.0);
  const Measured m = run(300.0, 400e-9);
  CHECK_REL(m.U1, w.U1, 0.02);
  CHECK_REL(m.hel, w.sigma1, 0.03);
  CHECK_REL(m.sigma2, w.sigma2, 0.003);
  CHECK_REL(m.excess2, w.sigma2 - w.P2, 0.10);  // on the yield surface, not rung below it
  CHECK_REL(m.eps_p2, w.eps_p2, 0.10);          // yielded once, not back and forth
  CHECK_REL(m.rho2, w.rho2, 0.002);
  {
    // The Johnson-Cook law with B = H, n = 1, C = 0 is the bilinear law (the thermal factor
    // 1 - T*^10 differs from 1 by 1e-25 at 300 K): the same exact state, through its own return map.
    char jc[256];
    std::snprintf(jc, sizeof jc,
                  "strength_model = johnson_cook\njc_yield_stress = %.17g\njc_hardening = %.17g\n"
                  "jc_hardening_exponent = 1\njc_rate_coefficient = 0\njc_thermal_exponent = 10\n",
                  al.yield_stress, al.plastic_modulus());
    // It runs the bilinear law's run to round-off (its Newton step is exact for a linear law).
    const Measured j = run(300.0, 400e-9, jc);
    CHECK_REL(j.U1, m.U1, 1e-9);
    CHECK_REL(j.hel, m.hel, 1e-9);
    CHECK_REL(j.sigma2, m.sigma2, 1e-9);
    CHECK_REL(j.excess2, m.excess2, 1e-7);
    CHECK_REL(j.eps_p2, m.eps_p2, 1e-9);
    CHECK_REL(j.rho2, m.rho2, 1e-9);
  }
  {
    // The laboratory frame (the target at rest, the flyer at 600 m/s): the same states, but the
    // shocked material crosses the grid at 300 m/s. The B-spline at points then rings the plateau
    // below yield (measured 2026-12-04 at A1 = 0.75: sigma_n - P 73.1 MPa, sigma_n -1.1 %); integrated
    // over the points' domains (bspline2_domain, the default) it meets the exact state as the
    // symmetric frame does.
    const Measured lab = run(300.0, 400e-9, "", true);
    CHECK_REL(lab.U1, w.U1, 0.02);
    CHECK_REL(lab.hel, w.sigma1, 0.03);
    CHECK_REL(lab.sigma2, w.sigma2, 0.003);
    CHECK_REL(lab.excess2, w.sigma2 - w.P2, 0.05);
    CHECK_REL(lab.eps_p2, w.eps_p2, 0.05);
    CHECK_REL(lab.rho2, w.rho2, 0.002);
  }
  {
    // 1000 m/s: the plastic shock overruns the precursor's plateau within ~100 ns at 5 um. In the
    // laboratory frame too (measured: sigma_n - P 102.5 MPa symmetric, 99.3 laboratory, for 107.2).
    const TwoWave w1 = exact_two_wave(al, 1000.0);
    for (const bool laboratory : {false, true}) {
      const Measured m1 = run(1000.0, 250e-9, "", laboratory);
      CHECK_REL(m1.sigma2, w1.sigma2, 0.003);
      CHECK_REL(m1.eps_p2, w1.eps_p2, 0.10);
      CHECK_REL(m1.excess2, w1.sigma2 - w1.P2, 0.10);
    }
  }
  return check::result();
}
