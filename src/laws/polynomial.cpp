// The linear polynomial equation of state (polynomial.hpp): C0 + C1 mu + C2 mu^2 + C3 mu^3 +
// (C4 + C5 mu + C6 mu^2) rho0 E, the form of LS-DYNA's and AUTODYN's tabulated decks.
#include "../point_update_kernels.inl"
#include "mpmshock/material_law.hpp"
#include "mpmshock/polynomial.hpp"
#include "mpmshock/scene.hpp"

namespace mpmshock {

MaterialLaw Polynomial::law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::equation_of_state;
  law.name = kName;
  law.summary = "polynomial: C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) rho0 E with the polynomial_* keys "
                "(mu = rho/rho0 - 1; C2 and C6 zero in expansion; no built-in constants)";
  law.effect = "linear polynomial equation of state";
  const Bounds pressure_coefficient = closed_bound(-1e13, 1e13);
  const Bounds energy_coefficient = closed_bound(-100.0, 100.0);
  law.keys = {
      {"polynomial_c0", D::pressure, pressure_coefficient, "0 Pa",
       "polynomial C0, the pressure of the reference state (equation_of_state = polynomial)",
       field<&PolynomialConstants::c0>},
      {"polynomial_c1", D::pressure, non_negative_bound(), "0 Pa",
       "polynomial C1, the bulk modulus of the reference state (rho0 c0^2); 0: the material has no polynomial "
       "constants",
       field<&PolynomialConstants::c1>},
      {"polynomial_c2", D::pressure, pressure_coefficient, "0 Pa", "polynomial C2, the coefficient of mu^2 (in compression)",
       field<&PolynomialConstants::c2>},
      {"polynomial_c3", D::pressure, pressure_coefficient, "0 Pa", "polynomial C3, the coefficient of mu^3",
       field<&PolynomialConstants::c3>},
      {"polynomial_c4", D::none, energy_coefficient, "0",
       "polynomial C4, of rho0 E (the Grüneisen gamma0; gamma - 1 for an ideal gas)", field<&PolynomialConstants::c4>},
      {"polynomial_c5", D::none, energy_coefficient, "0", "polynomial C5, of mu rho0 E", field<&PolynomialConstants::c5>},
      {"polynomial_c6", D::none, energy_coefficient, "0", "polynomial C6, of mu^2 rho0 E (in compression)",
       field<&PolynomialConstants::c6>},
  };
  law.check = [](const MaterialCheck& c) {
    const Material& m = c.material;
    const Constants& k = m.law_constants<Constants>();
    if (!k.present())
      c.fail(c.prefix + "equation_of_state", "is polynomial, but " + c.named() + " has no polynomial constants: give its " +
                                                 c.prefix + "polynomial_* keys (mpmshock --keys)");
    else if (!(k.c1 + k.c0 * k.c4 > 0.0))
      c.fail(c.prefix + "polynomial_c0", "gives the reference state no sound speed (C1 + C0 C4 <= 0; " + c.named() + ")");
    if (m.bound_expansion)
      c.fail(c.prefix + "bounded_expansion", "is Mie-Grüneisen's expanded branch; the polynomial has its own (" +
                                                 c.named() + "): leave it off with equation_of_state = polynomial");
  };
  // temperature_model = paper is refused by the registry, as for every law referenced to its isentrope.
  return law;
}

// Its point-update kernels, for every strength, viscosity and failure law (point_update_kernels.hpp).
template UpdatePointsKernel<2> update_points_kernel<2, Polynomial>(const Model&);
template UpdatePointsKernel<3> update_points_kernel<3, Polynomial>(const Model&);

}  // namespace mpmshock
