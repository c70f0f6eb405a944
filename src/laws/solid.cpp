// The constants every material has, whatever laws it takes: reference density, elastic constants,
// specific heat, conductivity and starting temperature.
#include "mpmshock/material_law.hpp"

namespace mpmshock {

MaterialLaw solid_law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::always;
  law.name = "solid";
  law.keys = {
      {"density", D::density, {0.0, 1e5, true, false}, "2700 kg/m3", "solid reference density rho0", field<&Material::density>},
      {"youngs_modulus", D::pressure, {0.0, 1e13, true, false}, "69 GPa",
       "Young's modulus E (with nu gives the shear modulus)", field<&Material::youngs_modulus>},
      {"poisson_ratio", D::none, open_bound(-1.0, 0.5), "0.33", "Poisson's ratio nu", field<&Material::poisson_ratio>},
      {"specific_heat", D::specific_heat, positive_bound(), "880 J/(kg K)", "specific heat c_v", field<&Material::specific_heat>},
      {"thermal_conductivity", D::conductivity, non_negative_bound(), "167 W/(m K)",
       "thermal conductivity k, used with heat_conduction = on (6061-T6; pure aluminium: 237 W/(m K))",
       field<&Material::thermal_conductivity>},
      {"initial_temperature", D::temperature, positive_bound(), "300 K", "initial temperature T0",
       field<&Material::initial_temperature>},
  };
  return law;
}

}  // namespace mpmshock
