// Steinberg-Guinan's thermal softening and Lindemann melting of the bilinear flow stress
// (thermal_softening.hpp), a scene effect (thermal_softening = on) with each material's constants.
#include "mpmshock/material_law.hpp"
#include "mpmshock/scene.hpp"

namespace mpmshock {

MaterialLaw steinberg_guinan_law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::softening;
  law.name = "steinberg_guinan";
  law.keys = {
      {"softening_temperature", D::temperature, {0.0, 1e5, true, false}, "1923 K",
       "with thermal_softening: temperature at which linear softening would take G and sigma_Y to "
       "zero, 300 K + 1/B (Steinberg-Guinan 6061-T6: B = 6.16e-4 /K)",
       field<&Material::softening_temperature>},
      {"melt_temperature", D::temperature, {0.0, 1e5, true, false}, "1220 K",
       "with thermal_softening: melt temperature at J = 1; T_m(J) = T_m0 exp(2a(1 - J)) "
       "J^(-2(gamma0 - a - 1/3)) (Lindemann); 0: the material has no Steinberg-Guinan constants",
       field<&Material::melt_temperature>},
      {"lindemann_a", D::none, closed_bound(0.0, 10.0), "1.5",
       "volume coefficient a of the Lindemann melt curve (Steinberg-Guinan 6061-T6)", field<&Material::lindemann_a>},
      {"pressure_hardening_scale", D::pressure, non_negative_bound(), "15.337 GPa",
       "with thermal_softening: Steinberg-Guinan's pressure term A P eta^(-1/3), A = 1 / this "
       "(6061-T6: A = 6.52 /Mbar); pressure stiffens G and sigma_Y",
       field<&Material::pressure_hardening_scale>},
      {"yield_stress_max", D::pressure, non_negative_bound(), "680 MPa",
       "with thermal_softening: Steinberg-Guinan's cap Y_max on the work-hardened yield stress (6061-T6)",
       field<&Material::yield_stress_max>},
      {"latent_heat", D::specific_energy, non_negative_bound(), "397 kJ/kg",
       "with thermal_softening: heat of fusion taken at the melt temperature before the temperature "
       "rises further (aluminium, CRC Handbook)",
       field<&Material::latent_heat>},
  };
  // It softens the bodies of the bilinear law (Johnson-Cook has its own thermal term).
  law.used = [](const Scene& s, const Material& m) {
    return s.effects.thermal_softening && m.strength_model == "bilinear";
  };
  // A starting state the material cannot have (at or above its softening or melt temperature it has
  // no strength before anything happens) is refused.
  law.check = [](const MaterialCheck& c) {
    const Material& m = c.material;
    const std::string which = c.name == "scene" ? std::string() : " (material " + c.name + ")";
    const double T0 = m.initial_temperature;
    if (!m.has_softening()) {
      c.fail(c.prefix + "melt_temperature", "thermal_softening = on, but material " + c.name +
                                                " has no Steinberg-Guinan constants: give its " + c.prefix +
                                                "melt_temperature, softening_temperature, lindemann_a, "
                                                "pressure_hardening_scale, yield_stress_max and latent_heat");
      return;
    }
    if (m.softening_temperature <= T0)
      c.fail(c.prefix + "softening_temperature", "must be above initial_temperature (" + format_number(T0) +
                                                     " K): the material would start with no strength" + which);
    if (m.melt_temperature <= T0)
      c.fail(c.prefix + "melt_temperature",
             "must be above initial_temperature (" + format_number(T0) + " K): the material would start molten" + which);
    if (!(m.pressure_hardening_scale > 0.0))
      c.fail(c.prefix + "pressure_hardening_scale", "must be > 0 with thermal_softening = on" + which);
    if (m.yield_stress_max < m.yield_stress)
      c.fail(c.prefix + "yield_stress_max", "must be at least yield_stress (" + format_number(m.yield_stress) +
                                                " Pa): the cap would lie below the initial yield" + which);
  };
  return law;
}

}  // namespace mpmshock
