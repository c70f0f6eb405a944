// Mie-Grüneisen's equation of state on the linear Us-up Hugoniot (eos.hpp), with its expanded branch
// linear or bound by Rose's binding curve.
#include "../point_update_kernels.inl"
#include "mpmshock/eos.hpp"
#include "mpmshock/material_law.hpp"

namespace mpmshock {

MaterialLaw MieGruneisen::law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::equation_of_state;
  law.name = kName;
  law.summary = "mie_gruneisen: referenced to the Us-up Hugoniot (sound_speed, hugoniot_slope, gruneisen_gamma)";
  law.keys = {
      {"sound_speed", D::speed, {0.0, 1e5, true, false}, "5350 m/s", "bulk sound speed c0 (Us = c0 + s up)",
       field<&Material::sound_speed>},
      {"hugoniot_slope", D::none, closed_bound(1.0, 5.0), "1.34", "Us-up slope s (the paper's lambda)",
       field<&Material::hugoniot_slope>},
      {"gruneisen_gamma", D::none, closed_bound(0.0, 10.0), "1.96", "Grüneisen gamma0 at rho0; gamma rho is held constant",
       field<&Material::gruneisen_gamma>},
      {"cohesive_energy", D::specific_energy, positive_bound(), "12.1 MJ/kg",
       "cohesive energy, with bounded_expansion = on: the expanded branch of the equation of state binds with it (Rose's "
       "universal binding curve; tension at most 13.2 GPa for aluminium, zero at full expansion)",
       field<&Material::cohesive_energy>},
      {"bounded_expansion", D::none, {}, "off",
       "on: the expanded branch of the equation of state is Rose's binding curve with cohesive_energy "
       "(tension bounded, zero at full expansion; past its peak the material cavitates, a material "
       "instability: use with spall = on); off: the linear branch P = rho0 c0^2 (1 - V/V0), unbounded",
       field<&Material::bound_expansion>},
      {"fit_particle_velocity", D::speed, positive_bound(), "6 km/s",
       "the largest particle velocity the Us-up fit describes (217 GPa on the aluminium Hugoniot); "
       "points compressed past its Hugoniot state are counted as outside the equation of state's range",
       field<&Material::fit_particle_velocity>},
  };
  return law;
}

// Its point-update kernels, for every strength, viscosity and failure law (point_update_kernels.hpp).
template UpdatePointsKernel<2> update_points_kernel<2, MieGruneisen>(const Model&);
template UpdatePointsKernel<3> update_points_kernel<3, MieGruneisen>(const Model&);

}  // namespace mpmshock
