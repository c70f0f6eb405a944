// Johnson-Cook strength (johnson_cook.hpp) against its closed form. Under isochoric pure shear
// without spin, D = diag(rate, -rate, 0), the trial equivalent stress grows by 3 G dt times the
// equivalent strain rate r = sqrt(2/3 D':D') each step, and the radial return keeps the load
// proportional, so once yielded, at every step and for any step size,
//
//   q = 3 G (eps_t - eps_p) = k (A + B eps_p^n),   k = (1 + C ln max(r, 1)) (1 - T*^m),
//
// eps_t = r t the total equivalent strain: eps_p is the root of that equation, found here by
// bisection, and the plastic work is the integral of the flow stress, k (A eps_p + B eps_p^(n+1) / (n+1)).
// The temperature enters through the energy: at J = 1, T = T0 + E / c_v. Each check is made with
// the built-in copper (Johnson and Cook 1983) in 2D and 3D, at several rates, temperatures and step
// sizes, and in the melt. Scene checks: the constants each material must have.
#include <cmath>
#include <string>

#include "check.hpp"
#include "mpmshock/johnson_cook.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/scene.hpp"

using namespace mpmshock;

namespace {

// A material's Johnson-Cook constants.
const JohnsonCookConstants& jc_constants(const Material& m) { return m.law_constants<JohnsonCookConstants>(); }

// The velocity gradient of isochoric pure shear at rate `rate` (no spin).
template <int D>
Mat<D> pure_shear(double rate) {
  Mat<D> L{};
  L(0, 0) = rate;
  L(1, 1) = -rate;
  return L;
}

// eps_p from q = 3 G (eps_t - eps_p) = k (A + B eps_p^n) by bisection (independent of the law's Newton).
double exact_plastic_strain(const Material& m, double k, double eps_t) {
  const double G3 = 3.0 * m.shear_modulus();
  auto g = [&](double e) { return G3 * (eps_t - e) - k * (jc_constants(m).yield_stress + jc_constants(m).hardening * std::pow(e, jc_constants(m).hardening_exponent)); };
  if (g(0.0) <= 0.0) return 0.0;
  double lo = 0.0, hi = eps_t;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The rate and temperature factor written out from the law's definition.
double factor(const Material& m, double rate, double T) {
  const double T_star = (T - jc_constants(m).room_temperature) / (jc_constants(m).melt_temperature - jc_constants(m).room_temperature);
  return (1.0 + jc_constants(m).rate_coefficient * std::log(std::max(rate, 1.0))) *
         (1.0 - std::pow(std::max(T_star, 0.0), jc_constants(m).thermal_exponent));
}

// Strains copper in pure shear to eps_t = 0.3 at the equivalent rate r and temperature T in `steps`
// steps, and checks the plastic strain, the stress and the plastic work against the closed form.
template <int D>
void shear_path(const Material& cu, double r, double T, int steps) {
  const JohnsonCook law(cu);
  const double rate = r / std::sqrt(4.0 / 3.0);  // r = sqrt(2/3 (rate^2 + rate^2))
  const StrainRate<D> D_rate = strain_rate(pure_shear<D>(rate));
  const double eps_total = 0.3, dt = eps_total / r / steps;
  const double E = cu.specific_heat * (T - cu.initial_temperature);  // at J = 1: T = T0 + E / c_v
  Deviator<D> s{}, alpha{};
  double eps_p = 0.0, work = 0.0;
  for (int i = 0; i < steps; ++i) work += law.update(s, alpha, eps_p, D_rate, dt, 1.0, E, 0.0);
  const double k = factor(cu, r, T);
  const double exact = exact_plastic_strain(cu, k, eps_total);
  CHECK_REL(eps_p, exact, 1e-9);
  const double q = equivalent_stress(s);
  CHECK_REL(q, k * (jc_constants(cu).yield_stress + jc_constants(cu).hardening * std::pow(exact, jc_constants(cu).hardening_exponent)), 1e-9);
  CHECK_REL(q, 3.0 * cu.shear_modulus() * (eps_total - eps_p), 1e-9);
  // The work: a right Riemann sum of the flow stress over eps_p, first order in the step.
  const double n = jc_constants(cu).hardening_exponent;
  const double W = k * (jc_constants(cu).yield_stress * exact + jc_constants(cu).hardening * std::pow(exact, n + 1.0) / (n + 1.0));
  if (steps >= 1000) CHECK_REL(work, W, 2e-3);
  // The deviator stays along the path's direction: s_xy = 0, s_xx = -s_yy.
  CHECK(std::abs(s.xy) <= 1e-9 * q);
  CHECK_REL(s.xx, -s.yy, 1e-12);
}

template <int D>
void flow_stress_closed_form(const Material& cu) {
  for (int steps : {3000, 30, 1})  // one step yields and hardens at once: Newton from eps_p = 0
    for (double r : {1e-3, 1e3, 1e6})
      for (double T : {300.0, 800.0}) shear_path<D>(cu, r, T, steps);
  // The rate and temperature factors compose as the law says.
  const JohnsonCook law(cu);
  CHECK_REL(law.flow_stress(0.1, 1e4, 700.0) / law.flow_stress(0.1, 1.0, 700.0), 1.0 + 0.025 * std::log(1e4), 1e-12);
  CHECK_REL(law.flow_stress(0.1, 1.0, 700.0) / law.flow_stress(0.1, 1.0, 298.0),
            1.0 - std::pow((700.0 - 298.0) / (1356.0 - 298.0), 1.09), 1e-12);
  CHECK(law.flow_stress(0.1, 0.5, 298.0) == law.flow_stress(0.1, 1.0, 298.0));  // no softening below 1 /s
  // In the melt the law is a fluid: no deviator, no plastic work.
  Deviator<D> s{}, alpha{};
  s.xx = 50e6;
  s.yy = -50e6;
  double eps_p = 0.2;
  const double E_melt = cu.specific_heat * (1400.0 - cu.initial_temperature);
  const double w = law.update(s, alpha, eps_p, strain_rate(pure_shear<D>(1e4)), 1e-9, 1.0, E_melt, 0.0);
  CHECK(w == 0.0 && s.xx == 0.0 && s.yy == 0.0 && eps_p == 0.2);
  // Elastic below yield: a small step leaves eps_p and the elastic increment 2 G D' dt exact.
  Deviator<D> e{}, a{};
  double eps0 = 0.0;
  CHECK(law.update(e, a, eps0, strain_rate(pure_shear<D>(1e3)), 1e-9, 1.0, 0.0, 0.0) == 0.0 && eps0 == 0.0);
  CHECK_REL(e.xx, 2.0 * cu.shear_modulus() * 1e3 * 1e-9, 1e-12);
}

Scene parse(const std::string& text) { return parse_scene(text, "jc.scene"); }

bool parses(const std::string& text) {
  try {
    parse(text);
    return true;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "unexpected error: %s\n", e.what());
    return false;
  }
}

bool refuses(const std::string& text, const std::string& needle) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    if (std::string(e.what()).find(needle) != std::string::npos) return true;
    std::fprintf(stderr, "unexpected error: %s\n", e.what());
    return false;
  }
  return false;
}

}  // namespace

int main() {
  const Material cu = find_library_material("copper")->constants;
  CHECK(jc_constants(cu).yield_stress == 90e6 && jc_constants(cu).hardening == 292e6 && jc_constants(cu).melt_temperature == 1356.0);
  flow_stress_closed_form<2>(cu);
  flow_stress_closed_form<3>(cu);

  // The scene: the model takes each body's constants; materials without any are refused by name.
  const std::string base = "porosity = 1\nflyer_height = 0.1 mm\ntarget_height = 0.1 mm\nwidth = 80 um\n"
                           "strength_model = johnson_cook\n";
  const Scene two = parse(base + "flyer_material = copper\ntarget_material = aluminium\n");
  const Model model(two);
  CHECK(std::holds_alternative<JohnsonCook>(model.strength[index_of(Body::flyer)]));
  CHECK(std::get<JohnsonCook>(model.strength[index_of(Body::flyer)]).A == 90e6);
  CHECK(std::get<JohnsonCook>(model.strength[index_of(Body::target)]).A == 324e6);
  CHECK(refuses(base + "target_material = tantalum\n", "material.tantalum.jc_yield_stress"));
  CHECK(refuses(base + "window_material = lif\nwindow_height = 50 um\n", "material.lif.jc_yield_stress"));
  CHECK(parses(base + "window_material = lif\nwindow_height = 50 um\nmaterial.lif.jc_yield_stress = 0.2 GPa\n"
                      "material.lif.jc_thermal_exponent = 1\nmaterial.lif.jc_melt_temperature = 1121 K\n"));
  // A new material starts from aluminium without its Johnson-Cook constants; bare keys keep them.
  CHECK(refuses(base + "target_material = steel\nmaterial.steel.density = 7850 kg/m3\n", "material.steel.jc_yield_stress"));
  CHECK(parses(base + "jc_yield_stress = 0.3 GPa\n"));
  // The law softens by the energy model's temperature: the run must compute that one.
  CHECK(refuses(base + "thermal = off\n", "needs thermal = on"));
  CHECK(refuses(base + "temperature_model = paper\n", "temperature_model = paper"));
  CHECK(parses(base + "paper_temperature = on\n"));
  CHECK(refuses(base + "thermal_softening = on\n", "strength_model"));
  CHECK(refuses(base + "plasticity = off\n", "needs plasticity = on"));
  CHECK(refuses(base + "hardening_beta = 0.5\n", "hardening_beta"));
  CHECK(refuses(base + "jc_melt_temperature = 250 K\n", "jc_melt_temperature"));
  // strength_model is each material's: a named one takes the bare key's unless given its own, and
  // bodies of different laws each run theirs through MixedStrength.
  const std::string plates = "porosity = 1\nflyer_height = 0.1 mm\ntarget_height = 0.1 mm\nwidth = 80 um\n"
                             "flyer_material = copper\ntarget_material = aluminium\n";
  const Scene mixed_scene = parse(plates + "material.copper.strength_model = johnson_cook\n");
  CHECK(mixed_scene.material_of(Body::flyer).strength_model == JohnsonCook::kName);
  CHECK(mixed_scene.material_of(Body::target).strength_model == "bilinear");
  const Model mixed(mixed_scene);
  for (const Body b : {Body::flyer, Body::target, Body::window})
    CHECK(std::holds_alternative<MixedStrength>(mixed.strength[index_of(b)]));
  const JohnsonCook* flyer_jc = johnson_cook_of(mixed.strength[index_of(Body::flyer)]);
  CHECK(flyer_jc && flyer_jc->A == 90e6);
  CHECK(!johnson_cook_of(mixed.strength[index_of(Body::target)]));
  CHECK(mixed.shear_modulus(Body::flyer) == cu.shear_modulus());
  // The bare key is every named material's unless it has its own.
  const Scene overridden = parse(base + "flyer_material = copper\ntarget_material = aluminium\n"
                                        "material.aluminium.strength_model = bilinear\n");
  CHECK(overridden.material_of(Body::flyer).strength_model == JohnsonCook::kName);
  CHECK(overridden.material_of(Body::target).strength_model == "bilinear");
  // Steinberg-Guinan softens the bilinear bodies beside a Johnson-Cook one; with none it is refused,
  // and a bilinear body needs its softening constants (tantalum has none).
  CHECK(parses(plates + "material.copper.strength_model = johnson_cook\nthermal_softening = on\n"));
  CHECK(refuses("porosity = 1\nflyer_material = copper\ntarget_material = tantalum\n"
                "material.copper.strength_model = johnson_cook\nthermal_softening = on\n",
                "material.tantalum.melt_temperature"));
  CHECK(refuses(plates + "material.copper.strength_model = johnson_cook\nthermal = off\n",
                "material.copper.strength_model"));
  // Without the key nothing changes: the bilinear law.
  const Model bilinear(parse("porosity = 1\nflyer_height = 0.1 mm\ntarget_height = 0.1 mm\nwidth = 80 um\n"));
  CHECK(std::holds_alternative<VonMises<false>>(bilinear.strength[index_of(Body::target)]));
  return check::result();
}
