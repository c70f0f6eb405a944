// The bilinear flow stress of von Mises plasticity (von_mises.hpp): sigma_Y0 + E_p eps_p, with
// isotropic, kinematic or mixed hardening.
#include "mpmshock/material_law.hpp"

namespace mpmshock {

MaterialLaw bilinear_law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::strength;
  law.name = "bilinear";
  law.summary = "bilinear, yield_stress + the plastic modulus of tangent_modulus times eps_p (with "
                "thermal_softening, Steinberg-Guinan's factor)";
  law.keys = {
      {"yield_stress", D::pressure, positive_bound(), "120 MPa", "initial yield stress sigma_Y0", field<&Material::yield_stress>},
      {"tangent_modulus", D::pressure, non_negative_bound(), "384 MPa", "tangent modulus E_tan past yield",
       field<&Material::tangent_modulus>},
      {"hardening_beta", D::none, closed_bound(0.0, 1.0), "1", "share of isotropic hardening: 1 isotropic, 0 kinematic",
       field<&Material::hardening_beta>},
  };
  law.check = [](const MaterialCheck& c) {
    if (c.material.tangent_modulus >= c.material.youngs_modulus)
      c.fail(c.prefix + "tangent_modulus",
             "must be smaller than youngs_modulus" + (c.name == "scene" ? std::string() : " of material " + c.name));
  };
  return law;
}

}  // namespace mpmshock
