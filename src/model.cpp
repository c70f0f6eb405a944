#include "mpmshock/model.hpp"

#include <stdexcept>
#include <type_traits>

namespace mpmshock {

namespace {

ShapeChoice shape_of(const Scene& s) {
  switch (s.shape_function) {
    case ShapeFunction::bilinear: return BilinearShape{};
    case ShapeFunction::gimp: return GimpShape{};
    case ShapeFunction::bspline2_domain: return QuadraticBSplineDomainShape{};
    case ShapeFunction::bspline2: break;
  }
  return QuadraticBSplineShape{};
}

ViscosityLaw viscosity_of(const Scene& s) {
  if (!s.effects.artificial_viscosity) return NoViscosity{};
  return ArtificialViscosity{s.av_linear, s.av_quadratic};
}

}  // namespace

ThermalSoftening softening_of(const Material& mat) {
  ThermalSoftening soft;
  soft.melt = melt_curve_of(mat);
  soft.T_s = mat.softening_temperature;
  soft.pressure_hardening = 1.0 / mat.pressure_hardening_scale;
  soft.yield_max = mat.yield_stress_max;
  soft.latent_heat = mat.latent_heat;
  return soft;
}

MeltCurve melt_curve_of(const Material& mat) { return {mat.melt_temperature, mat.lindemann_a, mat.gruneisen_gamma}; }

namespace {

// The material of each body; without a window its slot holds the target's, so that it adds no
// law and no table of its own.
std::array<const Material*, kBodies> body_materials(const Scene& s) {
  const Material& target = s.material_of(Body::target);
  return {&s.material_of(Body::flyer), &target, s.has_window() ? &s.material_of(Body::window) : &target};
}

// Each body's equation of state: its law's type where the bodies share one law, else each wrapped
// (mixed_equation_of_state.hpp), so that the kernels see one type.
std::array<EquationOfState, kBodies> equations_of_state(const std::array<const Material*, kBodies>& m) {
  std::array<EquationOfStateLaw, kBodies> laws{equation_of_state_of(*m[0]), equation_of_state_of(*m[1]),
                                               equation_of_state_of(*m[2])};
  const bool one_law = laws[0].index() == laws[1].index() && laws[0].index() == laws[2].index();
  std::array<EquationOfState, kBodies> eos;
  for (std::size_t b = 0; b < kBodies; ++b) {
    if (!one_law) eos[b] = MixedEquationOfState(laws[b]);
    else std::visit([&](const auto& law) { eos[b] = law; }, laws[b]);
  }
  return eos;
}

// The strength law a scene calls for in a material; `back_stress`: the kinematic form even for
// isotropic hardening (when another body needs it, so that the bodies' laws are one type).
StrengthLaw strength_of(const Scene& s, const Material& mat, bool back_stress) {
  if (!s.effects.plasticity) return NoStrength{};
  // A law of its own type (laws.hpp: Johnson-Cook, isotropic, its own softening), else bilinear.
  std::optional<StrengthLaw> own;
  for_each_law<OwnStrengthLaw>([&](auto tag) {
    using Law = std::remove_pointer_t<decltype(tag)>;
    if (mat.strength_model == Law::kName) own = Law(mat);
  });
  if (own) return *own;
  const bool isotropic = mat.hardening_beta == 1.0 && !back_stress;
  if (s.effects.thermal_softening) {
    if (isotropic) return VonMises<false, true>(mat, softening_of(mat));
    return VonMises<true, true>(mat, softening_of(mat));
  }
  if (isotropic) return VonMises<false>(mat);
  return VonMises<true>(mat);
}

// Whether any body's material hardens kinematically (hardening_beta < 1): then all store a back stress.
bool kinematic_hardening(const Scene& s) {
  const auto m = body_materials(s);
  return std::any_of(m.begin(), m.end(), [](const Material* b) { return b->hardening_beta != 1.0; });
}

}  // namespace

std::array<StrengthLaw, kBodies> strength_laws(const Scene& s) {
  const auto m = body_materials(s);
  const bool back_stress = kinematic_hardening(s);
  std::array<StrengthLaw, kBodies> laws{strength_of(s, *m[0], back_stress), strength_of(s, *m[1], back_stress),
                                        strength_of(s, *m[2], back_stress)};
  if (laws[0].index() == laws[1].index() && laws[0].index() == laws[2].index()) return laws;
  // Bodies of different laws (plasticity is the scene's: each body has one): each wrapped.
  for (StrengthLaw& law : laws)
    law = std::visit(
        [](const auto& l) -> StrengthLaw {
          if constexpr (std::is_same_v<std::decay_t<decltype(l)>, NoStrength> ||
                        std::is_same_v<std::decay_t<decltype(l)>, MixedStrength>)
            throw std::logic_error("strength_laws: a body without a law of its own among bodies of different laws");
          else
            return MixedStrength(StrengthWithStress(l));
        },
        law);
  return laws;
}

const JohnsonCook* johnson_cook_of(const StrengthLaw& law) {
  if (const auto* jc = std::get_if<JohnsonCook>(&law)) return jc;
  if (const auto* mixed = std::get_if<MixedStrength>(&law)) return std::get_if<JohnsonCook>(&mixed->law);
  return nullptr;
}

Model::Model(const Scene& s) : Model(s, body_materials(s)) {}

Model::Model(const Scene& s, const std::array<const Material*, kBodies>& m)
    : shape(shape_of(s)),
      eos(equations_of_state(m)),
      strength(strength_laws(s)),
      viscosity(viscosity_of(s)),
      failure(s.effects.spall ? FailureLaw(Spall{s.spall_strength, s.spall_void_fraction,
                                                         s.spall_criterion == SpallCriterion::neighbourhood, s.spall_point_ceiling}) : FailureLaw(NoFailure{})),
      scheme(s.update_scheme), flip_fraction(s.flip_fraction), taylor_quinney(s.taylor_quinney), cell_size(s.cell_size), cfl(s.cfl),
      volume_change_signal(s.cfl * s.cell_size / s.max_volume_change),
      // No material point outruns several times the impact speed plus the sound speed; a point
      // that does is a blow-up.
      speed_limit(10.0 * (2.0 * s.fastest_body_speed() +
                          std::max({reference_sound_speed(Body::flyer), reference_sound_speed(Body::target),
                                    reference_sound_speed(Body::window)}))) {
  if (s.effects.thermal) thermal.emplace(*m[0], *m[1], *m[2], s.temperature_model, s.paper_temperature);
  // Steinberg-Guinan's melting is the bilinear law's: a Johnson-Cook body melts at its own T_m.
  if (thermal && s.effects.thermal_softening)
    for (const Body b : {Body::flyer, Body::target, Body::window})
      if (m[index_of(b)]->strength_model == "bilinear")
        thermal->set_melting(b, melt_curve_of(*m[index_of(b)]), m[index_of(b)]->latent_heat);
  symmetry_plane = s.symmetry == Symmetry::on;
  skip_unreached = s.skip_unreached;
  volumetric_smoothing = s.volumetric_smoothing == Smoothing::on;
  if (s.has_heat_flux()) heat_flux_beta = s.av_heat_flux;
  diffusion_number = s.dimension == 3 ? 0.15 : 0.2;
  if (s.effects.heat_conduction)
    for (std::size_t b = 0; b < kBodies; ++b) {
      conductivity[b] = m[b]->thermal_conductivity;
      diffusivity[b] = conductivity[b] / (m[b]->density * m[b]->specific_heat);
    }
}

double Model::limiting_compression(Body b) const {
  return std::visit([](const auto& e) { return e.limiting_compression(); }, eos[static_cast<std::size_t>(b)]);
}

double Model::reference_sound_speed(Body b) const {
  return std::visit([](const auto& e) { return e.reference_sound_speed(); }, eos[static_cast<std::size_t>(b)]);
}

double Model::eos_fit_limit(Body b) const {
  return std::visit([](const auto& e) { return e.fit_limit(); }, eos[static_cast<std::size_t>(b)]);
}

double Model::shear_modulus(Body b) const {
  return std::visit(
      [](const auto& law) {
        if constexpr (std::decay_t<decltype(law)>::has_stress) return law.shear_modulus;
        else return 0.0;
      },
      strength[static_cast<std::size_t>(b)]);
}

}  // namespace mpmshock
