// The physics of a run, resolved once from the scene: which law fills each slot of the point
// update (equation of state, strength, artificial viscosity), the temperature model, and the
// constants. Each slot is a variant of law types; the kernels are instantiated for the types
// chosen (simulation.cpp), so hot loops test no flags and a new law is a new type in a variant.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <variant>

#include "mpmshock/artificial_viscosity.hpp"
#include "mpmshock/eos.hpp"
#include "mpmshock/laws.hpp"
#include "mpmshock/mixed_equation_of_state.hpp"
#include "mpmshock/mixed_strength.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/spall.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/von_mises.hpp"

namespace mpmshock {

// A body's equation of state in the kernels: its law's own type where every body has that law, else
// each body's law through MixedEquationOfState (the laws are listed once, in laws.hpp).
using EquationOfState = JoinedVariant<EquationOfStateLaw, std::variant<MixedEquationOfState>>;
// A body's strength law in the kernels: none, its law's own type where every body has that law, else
// each body's law through MixedStrength (mixed_strength.hpp).
using StrengthLaw =
    JoinedVariant<std::variant<NoStrength>, JoinedVariant<StrengthWithStress, std::variant<MixedStrength>>>;
using ViscosityLaw = std::variant<NoViscosity, ArtificialViscosity>;
using FailureLaw = std::variant<NoFailure, Spall>;
using ShapeChoice = std::variant<BilinearShape, GimpShape, QuadraticBSplineShape, QuadraticBSplineDomainShape>;

// Each body's strength law, by Body: strength_of each body's material, of one type (MixedStrength
// where the bodies' laws differ).
std::array<StrengthLaw, kBodies> strength_laws(const Scene& s);
// The Johnson-Cook law of a body's strength, direct or mixed; null for any other law.
const JohnsonCook* johnson_cook_of(const StrengthLaw& law);
// The Lindemann melt curve of a material, and its Steinberg-Guinan softening (thermal_softening.hpp).
MeltCurve melt_curve_of(const Material& mat);
ThermalSoftening softening_of(const Material& mat);
inline bool has_stress(const StrengthLaw& law) { return !std::holds_alternative<NoStrength>(law); }
inline bool has_back_stress(const StrengthLaw& law) {
  return std::holds_alternative<VonMises<true>>(law) || std::holds_alternative<VonMises<true, true>>(law) ||
         std::holds_alternative<MixedStrength>(law);
}

struct Model {
  ShapeChoice shape;
  // The laws of each body's material, by Body (flyer, target, window); every body's are of one type
  // each, so the kernels are instantiated once and pick a point's constants by its body.
  std::array<EquationOfState, kBodies> eos;
  std::array<StrengthLaw, kBodies> strength;
  ViscosityLaw viscosity;
  FailureLaw failure;
  std::optional<BodyTemperatures> thermal;  // the temperature models of the bodies (thermal = on)
  UpdateScheme scheme;
  double flip_fraction;  // 1: pure FLIP
  double taylor_quinney;  // share of plastic work that becomes heat
  double cell_size;
  double cfl;
  // cfl h / max_volume_change: a point whose volume changes at the rate |tr D| counts as a signal
  // of this times |tr D|, so that the step cfl h / signal keeps |tr D| dt <= max_volume_change.
  double volume_change_signal;
  double speed_limit;  // |v| above this is a numerical runaway, not physics
  // With heat_conduction = on, each body's k [W/(m K)] and diffusivity k / (rho0 c_v) [m2/s]; else 0.
  std::array<double, kBodies> conductivity{}, diffusivity{};
  double diffusion_number = 0.2;  // the conduction step's share of h^2 / alpha (time_step)
  bool symmetry_plane = false;  // symmetry = on: the target alone, mirrored about y = 0
  bool skip_unreached = false;  // advance material nothing has reached in closed form (unreached.hpp)
  bool volumetric_smoothing = false;  // volumetric_smoothing.hpp
  double heat_flux_beta = 0.0;  // the artificial heat flux's beta, 0 without (artificial_heat_flux.hpp)

  explicit Model(const Scene& s);

 private:
  // With each body's material (model.cpp).
  Model(const Scene& s, const std::array<const Material*, kBodies>& materials);

 public:

  // The smallest J = V/V0 a body's equation of state admits.
  double limiting_compression(Body b) const;
  // The bulk sound speed of a body's material in its reference state (Mie-Grüneisen: c0).
  double reference_sound_speed(Body b) const;
  // The smallest J its fit describes (eos.hpp); below it the state is an extrapolation.
  double eos_fit_limit(Body b) const;
  // The shear modulus G a body's longitudinal sound speed sees; 0 without strength.
  double shear_modulus(Body b) const;
  bool has_strength() const { return has_stress(strength[0]); }
  bool has_failure() const { return std::holds_alternative<Spall>(failure); }
  bool conducts_heat() const { return *std::max_element(conductivity.begin(), conductivity.end()) > 0.0; }
  double max_diffusivity() const { return *std::max_element(diffusivity.begin(), diffusivity.end()); }
  // The time step the physics allows: cfl h over the fastest signal (which counts the fastest
  // volume change, volume_change_signal), and with conduction the explicit diffusion bound
  // diffusion_number h^2 / alpha (0.2 in 2D, 0.15 in 3D: below h^2 / (2 D alpha), 0.25 and 0.167)
  // of the most diffusive body.
  double time_step(double max_signal) const {
    const double mechanical = cfl * cell_size / max_signal;
    return conducts_heat() ? std::min(mechanical, diffusion_number * cell_size * cell_size / max_diffusivity()) : mechanical;
  }
};

}  // namespace mpmshock
