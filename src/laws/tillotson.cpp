// Tillotson's equation of state (tillotson.hpp): compressed, cold expanded, mixed and vapour branches.
#include "../point_update_kernels.inl"
#include "mpmshock/material_law.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/tillotson.hpp"

namespace mpmshock {

MaterialLaw Tillotson::law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::equation_of_state;
  law.name = kName;
  law.summary = "tillotson: Tillotson's compressed, expanded and vapour branches with the tillotson_* keys (built-in "
                "constants: aluminium)";
  law.effect = "Tillotson equation of state (compressed, expanded and vapour branches)";
  law.keys = {
      {"tillotson_a", D::none, closed_bound(0.0, 10.0), "0.5",
       "Tillotson a (equation_of_state = tillotson; aluminium, Tillotson 1962)", field<&TillotsonConstants::a>},
      {"tillotson_b", D::none, closed_bound(0.0, 10.0), "1.63", "Tillotson b", field<&TillotsonConstants::b>},
      {"tillotson_bulk_modulus", D::pressure, non_negative_bound(), "75.2 GPa",
       "Tillotson A, the bulk modulus of the reference state; 0: the material has no Tillotson constants",
       field<&TillotsonConstants::bulk_modulus>},
      {"tillotson_nonlinear_modulus", D::pressure, non_negative_bound(), "65 GPa",
       "Tillotson B, the coefficient of mu^2 (mu = rho/rho0 - 1)", field<&TillotsonConstants::nonlinear_modulus>},
      {"tillotson_energy", D::specific_energy, non_negative_bound(), "5 MJ/kg",
       "Tillotson E0, the energy scale of the b term", field<&TillotsonConstants::energy>},
      {"tillotson_incipient_vaporisation", D::specific_energy, non_negative_bound(), "2.7 MJ/kg",
       "Tillotson E_iv: expanded material below it follows the cold (compressed) branch",
       field<&TillotsonConstants::incipient_vaporisation>},
      {"tillotson_complete_vaporisation", D::specific_energy, non_negative_bound(), "14.1 MJ/kg",
       "Tillotson E_cv: expanded material above it follows the vapour branch; between E_iv and "
       "E_cv the pressure is interpolated in E",
       field<&TillotsonConstants::complete_vaporisation>},
      {"tillotson_alpha", D::none, closed_bound(0.0, 100.0), "5",
       "Tillotson alpha, the decay of the vapour branch's b term with expansion", field<&TillotsonConstants::alpha>},
      {"tillotson_beta", D::none, closed_bound(0.0, 100.0), "5",
       "Tillotson beta, the decay of the vapour branch's A term with expansion", field<&TillotsonConstants::beta>},
  };
  law.check = [](const MaterialCheck& c) {
    const Material& m = c.material;
    const Constants& t = m.law_constants<Constants>();
    if (!t.present())
      c.fail(c.prefix + "equation_of_state", "is tillotson, but " + c.named() + " has no Tillotson constants: give its " +
                                                 c.prefix + "tillotson_* keys (mpmshock --keys)");
    else if (!(t.energy > 0.0))
      c.fail(c.prefix + "tillotson_energy", "must be > 0 with equation_of_state = tillotson (" + c.named() + ")");
    else if (!(t.complete_vaporisation > t.incipient_vaporisation))
      c.fail(c.prefix + "tillotson_complete_vaporisation",
             "must exceed tillotson_incipient_vaporisation (" + c.named() + ")");
    if (m.bound_expansion)
      c.fail(c.prefix + "bounded_expansion", "is Mie-Grüneisen's expanded branch; Tillotson has its own (" + c.named() +
                                                 "): leave it off with equation_of_state = tillotson");
  };
  // temperature_model = paper is refused by the registry, as for every law referenced to its isentrope.
  return law;
}

// Its point-update kernels, for every strength, viscosity and failure law (point_update_kernels.hpp).
template UpdatePointsKernel<2> update_points_kernel<2, Tillotson>(const Model&);
template UpdatePointsKernel<3> update_points_kernel<3, Tillotson>(const Model&);

}  // namespace mpmshock
