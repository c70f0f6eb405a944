// The built-in materials. Each is a Mie-Grüneisen solid on its linear Us-up Hugoniot with von Mises
// strength (bilinear hardening) and a constant specific heat: the laws every body of a scene uses.
// Hugoniot constants (rho0, c0, s, gamma0) and the strength are sourced per material below;
// where a source gives a Steinberg-Guinan strength, the initial yield Y0 is its Y0 and the
// tangent modulus the slope from Y0 to its Y_max over a plastic strain of 0.5 (an approximation
// of its power-law hardening by the bilinear law). fit_particle_velocity, where no source gives the
// range of the linear fit, is an estimate (3 km/s for the metals and PMMA, 5 km/s for LiF), and the
// cohesive energy is used only with bounded_expansion = on. Johnson-Cook constants
// (strength_model = johnson_cook) are given where a source gives them: aluminium and copper; tantalum,
// LiF and PMMA have none (jc_yield_stress = 0) until a scene sets material.NAME.jc_*. Tillotson
// constants (equation_of_state = tillotson): aluminium's; the others have none (tillotson_bulk_modulus
// = 0) until a scene sets material.NAME.tillotson_*. Steinberg-Guinan softening and melting
// (thermal_softening = on): aluminium (6061-T6), copper and LiF after Steinberg (1996); tantalum and
// PMMA have none (melt_temperature = 0).
#include "mpmshock/johnson_cook.hpp"
#include "mpmshock/material.hpp"
#include "mpmshock/material_law.hpp"

namespace mpmshock {

namespace {

Material make(double rho0, double c0, double s, double gamma0, double cv, double E, double nu, double Y0,
              double E_tan, double k, double cohesive, double fit_up) {
  Material m = without("tillotson", Material{});
  m.density = rho0;
  m.sound_speed = c0;
  m.hugoniot_slope = s;
  m.gruneisen_gamma = gamma0;
  m.specific_heat = cv;
  m.youngs_modulus = E;
  m.poisson_ratio = nu;
  m.yield_stress = Y0;
  m.tangent_modulus = E_tan;
  m.thermal_conductivity = k;
  m.cohesive_energy = cohesive;
  m.fit_particle_velocity = fit_up;
  return m;
}

// Johnson-Cook constants: A, B [Pa], n, C, m, T_m [K] (T_r stays 298 K).
Material with_johnson_cook(Material m, double A, double B, double n, double C, double mt, double T_m) {
  JohnsonCookConstants& jc = m.law_constants<JohnsonCookConstants>();
  jc.yield_stress = A;
  jc.hardening = B;
  jc.hardening_exponent = n;
  jc.rate_coefficient = C;
  jc.thermal_exponent = mt;
  jc.melt_temperature = T_m;
  return m;
}

}  // namespace

// Steinberg-Guinan softening and melting: A [1/Pa], B [1/K], T_m0 [K], a, Y_max [Pa], latent heat [J/kg].
static Material with_softening(Material m, double A, double B, double T_m0, double a, double Y_max, double L) {
  m.pressure_hardening_scale = 1.0 / A;
  m.softening_temperature = 300.0 + 1.0 / B;
  m.melt_temperature = T_m0;
  m.lindemann_a = a;
  m.yield_stress_max = Y_max;
  m.latent_heat = L;
  return m;
}

const std::vector<LibraryMaterial>& material_library() {
  static const std::vector<LibraryMaterial> library = {
      {"aluminium", Material{},
       "the paper's aluminium (Xu et al.) with the physics-notes errata (E = 69 GPa); k and the "
       "Steinberg-Guinan softening of 6061-T6 (Steinberg 1996); Johnson-Cook constants of 6061-T6 as commonly "
       "tabulated after Johnson and Holmquist (1989); Tillotson constants of aluminium (Tillotson 1962, as "
       "tabulated in Spheral's material library: a 0.5, b 1.63, A 75.2 GPa, B 65 GPa, E0 5 MJ/kg, E_iv "
       "2.7 MJ/kg, E_cv 14.1 MJ/kg, alpha 5, beta 5)"},
      // Steinberg 1996 (OFHC copper): rho0 8930, c0 3940, s 1.489, gamma0 2.02, G0 47.7 GPa,
      // Y0 0.12 GPa, Y_max 0.64 GPa; nu 0.34 gives E = 2 G0 (1 + nu) = 127.8 GPa.
      {"copper",
       // Johnson and Cook (1983), OFHC copper: A 90 MPa, B 292 MPa, n 0.31, C 0.025, m 1.09, T_m 1356 K.
       // Steinberg (1996), OFHC copper: A 2.83 /Mbar, B 3.77e-4 /K, T_m0 1790 K, a 1.5, Y_max 0.64 GPa;
       // heat of fusion 13.26 kJ/mol (CRC).
       with_softening(with_johnson_cook(make(8930.0, 3940.0, 1.489, 2.02, 383.0, 127.8e9, 0.34, 120e6, 1.04e9, 401.0,
                                             5.30e6, 3000.0),
                                        90e6, 292e6, 0.31, 0.025, 1.09, 1356.0),
                      2.83e-11, 3.77e-4, 1790.0, 1.5, 0.64e9, 208.7e3),
       "OFHC copper, Steinberg (1996) Equation of State and Strength Properties of Selected Materials "
       "(Hugoniot, G0, Y0; tangent modulus (Y_max - Y0)/0.5); c_v 383 J/(kg K), k 401 W/(m K), "
       "cohesive energy 3.49 eV/atom (Kittel); Johnson-Cook constants of OFHC copper, Johnson and Cook (1983); "
       "Steinberg-Guinan softening and melt curve of OFHC copper, Steinberg (1996) (T_m0 1790 K is its fit; pure "
       "copper melts at 1358 K), heat of fusion 13.26 kJ/mol (CRC)"},
      // Steinberg 1996 (tantalum): rho0 16690, c0 3414, s 1.201, gamma0 1.67, G0 69 GPa, Y0 0.77 GPa,
      // Y_max 1.1 GPa; nu 0.34 gives E = 184.9 GPa.
      {"tantalum",
       without("steinberg_guinan", without("johnson_cook",
           make(16690.0, 3414.0, 1.201, 1.67, 140.0, 184.9e9, 0.34, 770e6, 0.66e9, 57.5, 4.32e6, 3000.0))),
       "tantalum, Steinberg (1996) (Hugoniot, G0, Y0; tangent modulus (Y_max - Y0)/0.5); c_v 140 J/(kg K), "
       "k 57.5 W/(m K), cohesive energy 8.10 eV/atom (Kittel); no Johnson-Cook or Steinberg-Guinan softening "
       "constants"},
      // LiF: Marsh (1980) LASL Shock Hugoniot Data, c0 5150, s 1.35; gamma0 1.69; elastic constants of
      // the polycrystal (E 64.9 GPa, nu 0.22), elastic limit ~0.2 GPa.
      // Steinberg (1996), LiF (single crystal, [100]): A 5.00 /Mbar, B 6.18e-4 /K, T_m0 1480 K, a 1.4,
      // Y_max 0.36 GPa; heat of fusion 27.09 kJ/mol (CRC).
      {"lif", with_softening(without("johnson_cook", make(2638.0, 5150.0, 1.35, 1.69, 1560.0, 64.9e9, 0.22, 200e6,
                                                          0.0, 11.3, 39.9e6, 5000.0)),
                             5.00e-11, 6.18e-4, 1480.0, 1.4, 0.36e9, 1044e3),
       "lithium fluoride window, Marsh (1980) LASL Shock Hugoniot Data (c0, s), gamma0 1.69; polycrystal "
       "E and nu; yield 0.2 GPa (approximate, no hardening); c_v 1560 J/(kg K), k 11.3 W/(m K); cohesive "
       "energy: the lattice energy 1036 kJ/mol (CRC); no Johnson-Cook constants; Steinberg-Guinan softening "
       "and melt curve of single-crystal LiF, Steinberg (1996) (T_m0 1480 K is its fit; LiF melts at 1121 K), heat "
       "of fusion 27.09 kJ/mol (CRC)"},
      // PMMA: Marsh (1980), c0 2598, s 1.516; gamma0 0.97.
      {"pmma", without("steinberg_guinan", without("johnson_cook",
                   make(1186.0, 2598.0, 1.516, 0.97, 1466.0, 3.3e9, 0.35, 100e6, 0.0, 0.19, 20e6, 3000.0))),
       "PMMA window, Marsh (1980) LASL Shock Hugoniot Data (c0, s), gamma0 0.97; E 3.3 GPa, nu 0.35, "
       "yield 0.1 GPa (approximate, no hardening); c_v 1466 J/(kg K), k 0.19 W/(m K); no cohesive energy "
       "(a polymer decomposes): keep bounded_expansion off; no Johnson-Cook or Steinberg-Guinan softening "
       "constants"},
  };
  return library;
}

const LibraryMaterial* find_library_material(const std::string& name) {
  for (const LibraryMaterial& m : material_library())
    if (m.name == name) return &m;
  return nullptr;
}

}  // namespace mpmshock
