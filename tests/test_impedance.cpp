// A flyer of one material on a target of another, in the laboratory frame (the target at rest),
// against the impedance match: the interface state is where the two Hugoniots cross,
//   P = rho_t (c_t + s_t u) u = rho_f (c_f + s_f (v - u)) (v - u),
// u the interface (particle) velocity, v the flyer's speed (physics-notes section 3). The
// hydrodynamic runs must meet it within 1 % in pressure and particle velocity, in both bodies;
// with strength the difference is printed (the normal stress then carries (2/3) Y beside P).
// Each Hugoniot is its equation of state's (a Mie-Grüneisen flyer on a Tillotson target too).
// Also: the same named material on both bodies runs bit for bit as the bare keys, and a window's
// shocked state and the sample-window interface velocity against the impedance match there.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "check.hpp"
#include "mpmshock/eos.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/rankine_hugoniot.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"

using namespace mpmshock;

namespace {

// A material's Johnson-Cook constants.
const JohnsonCookConstants& jc_constants(const Material& m) { return m.law_constants<JohnsonCookConstants>(); }

// The Rankine-Hugoniot state of a material's equation of state at particle velocity up: with
// Mie-Grüneisen P = rho0 (c0 + s up) up (rankine_hugoniot.hpp; test_tillotson checks the two agree).
ShockState hugoniot(const Material& m, double up) {
  return std::visit([&](const auto& eos) { return shock_from_rest(eos, up); }, equation_of_state_of(m));
}
double hugoniot_pressure(const Material& m, double up) { return hugoniot(m, up).pressure; }

// The interface velocity u of a flyer at v on a target at rest (bisection: P_t rises, P_f falls in u).
double interface_velocity(const Material& flyer, const Material& target, double v) {
  double lo = 0.0, hi = v;
  for (int k = 0; k < 200; ++k) {
    const double u = 0.5 * (lo + hi);
    (hugoniot_pressure(target, u) < hugoniot_pressure(flyer, v - u) ? lo : hi) = u;
  }
  return 0.5 * (lo + hi);
}

// Row means of a quantity over one body, by height from y0 in rows of `spacing`.
struct Rows {
  double y0, spacing;
  std::vector<double> sum, count;
  double mean(std::size_t r) const { return count[r] > 0 ? sum[r] / count[r] : std::nan(""); }
};

struct Measured {
  double P_target, u_target, P_flyer, u_flyer, sigma_target;
  double von_mises_target, von_mises_flyer;  // mean equivalent stress of the deviator (0 without strength)
};

// `law`: further scene lines (the strength law).
Measured run(const std::string& flyer, const std::string& target, double v, bool strength, double end_time,
             const std::string& law = "") {
  char text[1024];
  std::snprintf(text, sizeof text,
                "flyer_material = %s\ntarget_material = %s\nflyer_velocity = %g m/s\ntarget_velocity = 0\n"
                "porosity = 1\nwidth = 40 um\ntarget_height = 1.6 mm\nflyer_height = 1.6 mm\ncell_size = 10 um\n"
                "end_time = %g s\nplasticity = %s\n%s",
                flyer.c_str(), target.c_str(), v, end_time, strength ? "on" : "off", law.c_str());
  const Scene scene = parse_scene(text, "impedance");
  CHECK(scene.symmetry == Symmetry::off);  // two materials: the flyer is not the target's mirror image
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  while (sim.time() < end_time * (1 - 1e-12)) {
    const StepStatus st = sim.step(std::min(sim.stable_time_step(), end_time - sim.time()));
    if (!st.ok()) {
      check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(st));
      return {};
    }
  }
  const Particles<2>& p = sim.particles();
  const Material& mf = scene.material_of(Body::flyer);
  const Material& mt = scene.material_of(Body::target);
  const double u = interface_velocity(mf, mt, v);
  // The interface is where the bodies meet; each shock front is where its body's row-mean density
  // crosses the mean of its initial and shocked densities (the Hugoniot's at u).
  double interface = -1.0, bottom = 1.0;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::flyer) interface = std::max(interface, p.x[q][1]);
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::flyer) bottom = std::min(bottom, p.x[q][1]);
  const double a = scene.particle_spacing();
  auto rows_of = [&](Body b, double y0) {
    Rows r{y0, a, std::vector<double>(800, 0.0), std::vector<double>(800, 0.0)};
    for (std::size_t q = 0; q < p.size(); ++q) {
      if (p.body[q] != b) continue;
      const long k = std::lround(std::floor((p.x[q][1] - y0) / a));
      if (k < 0 || k >= 800) continue;
      r.sum[static_cast<std::size_t>(k)] += p.density(q);
      r.count[static_cast<std::size_t>(k)] += 1;
    }
    return r;
  };
  auto shocked_density = [](const Material& m, double up) { return m.density / hugoniot(m, up).J; };
  // Target: rows upward from the interface; flyer: rows downward from it.
  const Rows t = rows_of(Body::target, interface);
  const double mid_t = 0.5 * (mt.density + shocked_density(mt, u));
  double front_t = interface;
  for (std::size_t k = 0; k + 1 < t.sum.size(); ++k)
    if (t.mean(k) > mid_t && !(t.mean(k + 1) > mid_t)) {
      front_t = interface + (k + 1) * a;
      break;
    }
  const Rows f = rows_of(Body::flyer, bottom);
  const double mid_f = 0.5 * (mf.density + shocked_density(mf, v - u));
  double front_f = interface;
  for (std::size_t k = f.sum.size() - 1; k > 0; --k)
    if (f.mean(k) > mid_f && !(f.mean(k - 1) > mid_f) && f.count[k - 1] > 0) {
      front_f = bottom + k * a;
      break;
    }
  CHECK(front_t > interface + 0.3e-3 && front_f < interface - 0.2e-3);
  // The middle half of each shocked layer.
  Measured m{};
  double nt = 0, nf = 0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    const double y = p.x[q][1];
    if (p.body[q] == Body::target && y > interface + 0.25 * (front_t - interface) &&
        y < interface + 0.75 * (front_t - interface)) {
      m.P_target += p.P[q];
      m.sigma_target += p.P[q] + p.q[q] - (p.s.empty() ? 0.0 : p.s[q].yy);
      m.u_target += p.v[q][1];
      if (!p.s.empty()) m.von_mises_target += equivalent_stress(p.s[q]);
      ++nt;
    }
    if (p.body[q] == Body::flyer && y < interface - 0.25 * (interface - front_f) &&
        y > interface - 0.75 * (interface - front_f)) {
      m.P_flyer += p.P[q];
      m.u_flyer += p.v[q][1];
      if (!p.s.empty()) m.von_mises_flyer += equivalent_stress(p.s[q]);
      ++nf;
    }
  }
  m.P_target /= nt, m.u_target /= nt, m.sigma_target /= nt, m.P_flyer /= nf, m.u_flyer /= nf;
  m.von_mises_target /= nt, m.von_mises_flyer /= nf;
  const double P = hugoniot_pressure(mt, u);
  std::printf("%-9s on %-9s at %4.0f m/s, %s%s: u %.1f m/s (exact %.1f), P %.3f GPa (exact %.3f): target P %.3f GPa "
              "(%+.2f %%), sigma_n %.3f GPa, u %.1f m/s (%+.2f %%); flyer P %.3f GPa (%+.2f %%), u %.1f m/s (%+.2f %%)\n",
              flyer.c_str(), target.c_str(), v, strength ? "with strength" : "hydrodynamic",
              law.empty()                                   ? ""
              : law.find("tillotson") != std::string::npos  ? " (Tillotson target)"
              : law.find("material.") != std::string::npos  ? " (Johnson-Cook flyer, bilinear target)"
                                                            : " (Johnson-Cook)",
              u, u,
              P / 1e9, P / 1e9,
              m.P_target / 1e9, 100 * (m.P_target / P - 1), m.sigma_target / 1e9, m.u_target, 100 * (m.u_target / u - 1),
              m.P_flyer / 1e9, 100 * (m.P_flyer / P - 1), m.u_flyer, 100 * (m.u_flyer / u - 1));
  if (!strength) {
    CHECK_REL(m.P_target, P, 0.01);
    CHECK_REL(m.u_target, u, 0.01);
    CHECK_REL(m.P_flyer, P, 0.01);
    CHECK_REL(m.u_flyer, u, 0.01);
  }
  return m;
}

// The window: an aluminium flyer at v on an aluminium sample at rest with a window on its far
// surface. The sample's shock (P1 = P_Al(v/2), u1 = v/2) reaches the window; the transmitted state
// lies where the window's Hugoniot crosses the sample's release isentrope from state 1 (a softer
// window: LiF, PMMA): along it dE/dJ = -P/rho0 and du/dJ = c/J (the reflected wave runs back into
// the sample, dP = -rho c du), integrated with RK4 in J.
struct WindowState {
  double u, P;
};
WindowState window_match(const Material& sample, const Material& window, double v) {
  const MieGruneisen eos(sample);
  const double u1 = 0.5 * v, Us = sample.sound_speed + sample.hugoniot_slope * u1;
  double J = (Us - u1) / Us, E = 0.5 * u1 * u1, u = u1;
  auto rhs = [&](double j, double e, double& dE, double& du) {
    const auto st = eos.state(j, e);
    dE = -st.pressure / sample.density;
    du = std::sqrt(st.sound_speed_squared) / j;
  };
  const double dJ = 1e-6;
  for (int k = 0; k < 400000; ++k) {
    if (eos.pressure(J, E) <= hugoniot_pressure(window, u)) break;
    double e1, u1k, e2, u2k, e3, u3k, e4, u4k;
    rhs(J, E, e1, u1k);
    rhs(J + 0.5 * dJ, E + 0.5 * dJ * e1, e2, u2k);
    rhs(J + 0.5 * dJ, E + 0.5 * dJ * e2, e3, u3k);
    rhs(J + dJ, E + dJ * e3, e4, u4k);
    E += dJ / 6 * (e1 + 2 * e2 + 2 * e3 + e4);
    u += dJ / 6 * (u1k + 2 * u2k + 2 * u3k + u4k);
    J += dJ;
  }
  return {u, hugoniot_pressure(window, u)};
}

// The run: the window's shocked layer (the middle half between the interface and its front) and
// the sample's top row (what probe.NAME = surface follows: the sample-window interface), its
// velocity averaged over the last 60 ns.
// `row_checked`: the top row is checked too (through PMMA it rings, +-40 m/s with a period of
// ~18 ns, and its mean lies 1.9 % below the match: the points of one single-velocity grid at a
// strong impedance mismatch; stated in docs/scenes.md, not checked).
void run_window(const std::string& window, double v, bool row_checked) {
  char text[1024];
  std::snprintf(text, sizeof text,
                "window_material = %s\nwindow_height = 0.8 mm\nflyer_velocity = %g m/s\ntarget_velocity = 0\n"
                "porosity = 1\nwidth = 40 um\ntarget_height = 0.6 mm\nflyer_height = 1.2 mm\ncell_size = 10 um\n"
                "end_time = 200 ns\nplasticity = off\n",
                window.c_str(), v);
  const Scene scene = parse_scene(text, "window");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  // The sample's top row (its points from t = 0), averaged over time from 140 ns, when the
  // transmitted shock has run ~0.2 mm into the window, as a VISAR record's plateau is read.
  const Particles<2>& p = sim.particles();
  std::vector<char> top(p.size(), 0);  // by id
  for (std::size_t q = 0; q < p.size(); ++q)
    top[p.id[q]] = p.body[q] == Body::target && p.x[q][1] > scene.target_height - scene.particle_spacing();
  double u_top = 0, n_top = 0;
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    const StepStatus st = sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
    if (!st.ok()) {
      check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(st));
      return;
    }
    if (sim.time() < 140e-9) continue;
    double row = 0, count = 0;
    for (std::size_t q = 0; q < p.size(); ++q)
      if (top[p.id[q]]) row += p.v[q][1], ++count;
    u_top += row / count;
    ++n_top;
  }
  const Material& mw = scene.material_of(Body::window);
  const WindowState exact = window_match(scene.material_of(Body::target), mw, v);
  double interface = 1.0;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::window) interface = std::min(interface, p.x[q][1]);
  // The window's front: the highest window point whose speed is above half the interface's.
  double front = interface;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::window && p.v[q][1] > 0.5 * exact.u) front = std::max(front, p.x[q][1]);
  double P = 0, u = 0, n = 0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    const double y = p.x[q][1];
    if (p.body[q] == Body::window && y > interface + 0.25 * (front - interface) && y < interface + 0.75 * (front - interface)) {
      P += p.P[q];
      u += p.v[q][1];
      ++n;
    }
  }
  P /= n, u /= n, u_top /= n_top;
  std::printf("aluminium at %4.0f m/s, window %-5s: interface u %.1f m/s, P %.3f GPa (impedance match); window layer "
              "u %.1f m/s (%+.2f %%), P %.3f GPa (%+.2f %%); sample's top row u %.1f m/s (%+.2f %%); free surface "
              "would be %.0f m/s\n",
              v, window.c_str(), exact.u, exact.P / 1e9, u, 100 * (u / exact.u - 1), P / 1e9, 100 * (P / exact.P - 1),
              u_top, 100 * (u_top / exact.u - 1), v);
  CHECK(front > interface + 0.2e-3);
  CHECK_REL(u, exact.u, 0.01);
  CHECK_REL(P, exact.P, 0.01);
  if (row_checked) CHECK_REL(u_top, exact.u, 0.01);
}

// A short run's state: the same named material on both bodies is the bare keys' material.
std::vector<double> state_of(const std::string& extra) {
  const std::string text = "porosity = 1.2\nvoid_radius = 10 um\nwidth = 200 um\ntarget_height = 200 um\n"
                           "flyer_height = 200 um\ncell_size = 10 um\nend_time = 30 ns\n" + extra;
  const Scene scene = parse_scene(text, "same");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  while (sim.time() < scene.end_time * (1 - 1e-12)) sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
  std::vector<double> out;
  for (std::size_t q = 0; q < sim.particles().size(); ++q) {
    out.push_back(sim.particles().E[q]);
    out.push_back(sim.particles().x[q][1]);
  }
  return out;
}

}  // namespace

// Thermal softening per material (thermal_softening = on): a copper flyer on aluminium closing at
// 1000 m/s (flyer 698 m/s, target 302 m/s: the shocked material at rest), each body softening with
// its own material's Steinberg-Guinan constants. Steinberg-Guinan scales the yield stress by
// f(P, T, J); copper's pressure term is 1/2.3 of aluminium's, so at 11.8 GPa f is about 1.3 for
// copper and 1.7 for aluminium. Checked: in each shocked layer, the mean equivalent stress with
// softening over the mean without (the same deformation, its points 16-25 % below their hardened
// yield radius at 10 um either way) is the mean f of the body's own material within 5 %, and more
// than 15 % from the other material's.
void softening_per_material() {
  const std::string text =
      "flyer_material = copper\ntarget_material = aluminium\nflyer_velocity = 698 m/s\ntarget_velocity = 302 m/s\n"
      "porosity = 1\nwidth = 40 um\ntarget_height = 1.6 mm\nflyer_height = 1.6 mm\ncell_size = 10 um\n"
      "end_time = 150 ns\n";
  const Material cu = find_library_material("copper")->constants, al;
  const double P_match = hugoniot_pressure(al, interface_velocity(cu, al, 1000.0));
  struct Layer {
    double stress = 0, own = 0, other = 0, n = 0;  // sums of sigma_eq and of f by each material's law
  };
  auto run_layers = [&](bool softening) {
    const Scene scene = parse_scene(text + (softening ? "thermal_softening = on\n" : ""), "softening");
    InitialState<2> initial = build_initial_state<2>(scene);
    Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
    std::array<Layer, 2> layers{};
    while (sim.time() < scene.end_time * (1 - 1e-12)) {
      const StepStatus st = sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
      if (!st.ok()) {
        check::fail(__FILE__, __LINE__, "run stopped: " + sim.describe(st));
        return layers;
      }
    }
    const Particles<2>& p = sim.particles();
    for (const Body b : {Body::flyer, Body::target}) {
      const Material& own = scene.material_of(b);
      const Material& other = b == Body::flyer ? al : cu;
      const HugoniotTemperature& thermal = sim.model().thermal->of_body(b);
      auto factor = [&](const Material& m, std::size_t q) {
        return softening_of(m).factor(p.P[q], thermal.temperature(p.material_J(q), p.thermal_energy(q)), p.material_J(q));
      };
      Layer& l = layers[index_of(b)];
      for (std::size_t q = 0; q < p.size(); ++q) {
        if (p.body[q] != b || p.P[q] < 0.8 * P_match) continue;
        l.stress += equivalent_stress(p.s[q]);
        l.own += factor(own, q);
        l.other += factor(other, q);
        ++l.n;
      }
    }
    return layers;
  };
  const std::array<Layer, 2> hard = run_layers(false), soft = run_layers(true);
  for (const Body b : {Body::flyer, Body::target}) {
    const Layer &h = hard[index_of(b)], &s = soft[index_of(b)];
    const double ratio = (s.stress / s.n) / (h.stress / h.n), f_own = s.own / s.n, f_other = s.other / s.n;
    std::printf("softening, %s: sigma_eq %.1f MPa softened, %.1f MPa without: ratio %.3f; mean f of its own material "
                "%.3f (%+.1f %%), of the other's %.3f (%+.1f %%)\n",
                b == Body::flyer ? "copper flyer" : "aluminium target", s.stress / s.n / 1e6, h.stress / h.n / 1e6, ratio,
                f_own, 100 * (ratio / f_own - 1), f_other, 100 * (ratio / f_other - 1));
    CHECK(s.n > 100 && h.n > 100);
    CHECK_REL(ratio, f_own, 0.05);
    CHECK(std::abs(ratio / f_other - 1) > 0.15);
  }
}

int main() {
  {
    // The exact interface state of copper on aluminium at 1000 m/s: u = 698 m/s, P = 11.9 GPa.
    const Material cu = find_library_material("copper")->constants, al;
    const double u = interface_velocity(cu, al, 1000.0);
    CHECK_REL(hugoniot_pressure(al, u), hugoniot_pressure(cu, 1000.0 - u), 1e-12);
    CHECK(u > 690.0 && u < 705.0);
  }
  run("copper", "aluminium", 1000.0, false, 150e-9);
  run("aluminium", "copper", 1000.0, false, 150e-9);
  run("tantalum", "copper", 800.0, false, 150e-9);
  // Bodies of different equations of state: the Mie-Grüneisen copper flyer on Tillotson aluminium,
  // against the crossing of the copper's Us-up Hugoniot with Tillotson's (11.874 GPa, 697.2 m/s).
  run("copper", "aluminium", 1000.0, false, 150e-9, "material.aluminium.equation_of_state = tillotson\n");
  const Measured cu_al = run("copper", "aluminium", 1000.0, true, 150e-9);
  // With strength the normal stress in the target exceeds its pressure by about (2/3) Y.
  CHECK(cu_al.sigma_target > cu_al.P_target);
  // Both bodies with Johnson-Cook strength, each of its own constants (OFHC copper, 6061-T6): the
  // shocked state stays the impedance match's within 1 % in velocity and normal stress (measured
  // -0.27 % and +0.59 %). The target's deviator is on the yield surface, sigma_n - P about (2/3) A
  // (A = 324 MPa: 216 MPa; measured 199), so its pressure lies that far below the hydrodynamic
  // match (-1.09 %). Until 2026-12-05 the porous scenes' A1 = 0.2 rang it off the surface (P -0.45 %).
  const Measured jc = run("copper", "aluminium", 1000.0, true, 150e-9, "strength_model = johnson_cook\n");
  {
    const Material cu = find_library_material("copper")->constants, al;
    const double u = interface_velocity(cu, al, 1000.0), P_match = hugoniot_pressure(al, u);
    CHECK_REL(jc.sigma_target, P_match, 0.01);
    CHECK_REL(jc.u_target, u, 0.01);
    CHECK_REL(jc.P_flyer, P_match, 0.01);
    CHECK_REL(jc.sigma_target - jc.P_target, (2.0 / 3.0) * jc_constants(al).yield_stress, 0.15);
  }
  // Bodies of different strength laws: the Johnson-Cook copper flyer on bilinear aluminium. Each
  // body's deviator is its own law's: the flyer's von Mises stress as in the run where both bodies
  // take Johnson-Cook, the target's as where both take the bilinear law (within 3 %), where the two
  // laws put each body's more than 15 % apart; the state stays the impedance match's within 1 %.
  const Measured mixed =
      run("copper", "aluminium", 1000.0, true, 150e-9, "material.copper.strength_model = johnson_cook\n");
  {
    std::printf("strength laws per body: flyer von Mises %.1f MPa (Johnson-Cook run %.1f, bilinear run %.1f), target "
                "%.1f MPa (bilinear run %.1f, Johnson-Cook run %.1f)\n",
                mixed.von_mises_flyer / 1e6, jc.von_mises_flyer / 1e6, cu_al.von_mises_flyer / 1e6,
                mixed.von_mises_target / 1e6, cu_al.von_mises_target / 1e6, jc.von_mises_target / 1e6);
    CHECK_REL(mixed.von_mises_flyer, jc.von_mises_flyer, 0.03);
    CHECK_REL(mixed.von_mises_target, cu_al.von_mises_target, 0.03);
    CHECK(std::abs(jc.von_mises_flyer / cu_al.von_mises_flyer - 1) > 0.15);
    CHECK(std::abs(jc.von_mises_target / cu_al.von_mises_target - 1) > 0.15);
    const Material cu = find_library_material("copper")->constants, al;
    const double u = interface_velocity(cu, al, 1000.0);
    CHECK_REL(mixed.u_target, u, 0.01);
    CHECK_REL(mixed.u_flyer, u, 0.01);
  }
  CHECK(state_of("") == state_of("flyer_material = aluminium\ntarget_material = aluminium\n"));
  // The windows experimenters use behind a sample: LiF (nearly aluminium's impedance: a slight
  // release) and PMMA (a strong release).
  run_window("lif", 1000.0, true);
  run_window("pmma", 1000.0, false);
  softening_per_material();
  return check::result();
}
