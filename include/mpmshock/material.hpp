// Material constants, SI. Defaults are the paper's aluminium with the physics-notes errata
// (E = 69 GPa, not MPa).
#pragma once

#include <any>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <vector>

namespace mpmshock {

// The bodies of an impact, each of its own material: the flyer (y < 0, moving up), the target
// (moving down) and, where a scene has one, the window bonded to the target's far surface.
enum class Body : std::uint8_t { flyer = 0, target = 1, window = 2 };
constexpr std::size_t kBodies = 3;
constexpr std::size_t index_of(Body b) { return static_cast<std::size_t>(b); }

// The constants of the laws that keep them in a struct of their own (Tillotson's, Johnson-Cook's:
// each law's header defines it with its defaults), held by type: a material carries the structs a
// scene or the library set, and reads the defaults of the others. A new law so adds no field here.
class LawConstants {
 public:
  template <class C>
  const C& get() const {
    const auto it = by_type_.find(std::type_index(typeid(C)));
    if (it != by_type_.end()) return *std::any_cast<C>(&it->second);
    static const C defaults{};
    return defaults;
  }
  template <class C>
  C& get() {
    auto it = by_type_.find(std::type_index(typeid(C)));
    if (it == by_type_.end()) it = by_type_.emplace(std::type_index(typeid(C)), C{}).first;
    return *std::any_cast<C>(&it->second);
  }

 private:
  std::map<std::type_index, std::any> by_type_;  // a node per law: references stay valid
};

struct Material {
  // Its equation of state and strength law by the words of their laws (src/laws/): Mie-Grüneisen
  // (eos.hpp) or Tillotson (tillotson.hpp); bilinear von Mises (von_mises.hpp) or Johnson-Cook
  // (johnson_cook.hpp). A library material without its own material.NAME.strength_model takes the
  // bare key's (scene.cpp).
  std::string equation_of_state = "mie_gruneisen";
  std::string strength_model = "bilinear";
  double density = 2700.0;               // rho0, solid reference density [kg/m3]
  double youngs_modulus = 69e9;          // E [Pa]; with nu gives only the shear modulus
  double poisson_ratio = 0.33;           // nu
  double yield_stress = 120e6;           // sigma_Y0 [Pa]
  double tangent_modulus = 384e6;        // E_tan [Pa], slope of the uniaxial stress-strain curve past yield
  double hardening_beta = 1.0;           // 1 isotropic, 0 kinematic, between: mixed
  double sound_speed = 5350.0;           // c0, Us-up intercept [m/s]
  double hugoniot_slope = 1.34;          // s (the paper's lambda)
  double gruneisen_gamma = 1.96;         // gamma0 at rho0; gamma*rho held constant
  double specific_heat = 880.0;          // c_v [J/(kg K)]
  double thermal_conductivity = 167.0;   // k [W/(m K)] of 6061-T6, used only with heat conduction on
  double initial_temperature = 300.0;    // T0 [K]
  // Cohesive (sublimation) energy per mass: 3.39 eV per atom for aluminium (Kittel), the energy
  // of the expanded branch of the equation of state (eos.hpp) [J/kg].
  double cohesive_energy = 12.1e6;
  // Expansion on that bounded binding curve (true) or on the linear branch P = rho0 c0^2 (1 - J).
  bool bound_expansion = false;
  // The largest particle velocity the Us-up fit describes: compression past its Hugoniot state
  // is counted as outside the equation of state's range (eos.hpp) [m/s].
  double fit_particle_velocity = 6000.0;

  // Steinberg-Guinan softening and melting (thermal_softening = on, thermal_softening.hpp). The
  // defaults are 6061-T6's (Steinberg 1996); melt_temperature = 0 marks a material without them
  // (material_library.cpp).
  double softening_temperature = 1923.0;       // [K] where linear softening would reach zero, 300 K + 1/B
  double melt_temperature = 1220.0;            // [K] T_m0, the melt temperature at J = 1
  double lindemann_a = 1.5;                    // volume exponent a of the Lindemann melt curve
  double pressure_hardening_scale = 15.337e9;  // [Pa] 1/A of Steinberg-Guinan's pressure term
  double yield_stress_max = 0.68e9;            // [Pa] Steinberg-Guinan's Y_max
  double latent_heat = 397e3;                  // [J/kg] heat of fusion, taken at T_m
  bool has_softening() const { return melt_temperature > 0.0; }

  // The constants of the laws with a struct of their own, by type (law_constants<TillotsonConstants>()).
  LawConstants laws;
  template <class C>
  const C& law_constants() const { return laws.get<C>(); }
  template <class C>
  C& law_constants() { return laws.get<C>(); }

  // G = E / (2 (1 + nu)): the only elastic constant the deviatoric update uses (physics-notes 1).
  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }

  // Plastic modulus of the bilinear uniaxial curve: E_p = E E_tan / (E - E_tan).
  double plastic_modulus() const {
    return youngs_modulus * tangent_modulus / (youngs_modulus - tangent_modulus);
  }
};

// Whether two materials have every constant equal (each law's keys, src/laws/registry.cpp).
bool same_constants(const Material& a, const Material& b);

// A material of the built-in library (material_library.cpp): its name as scenes write it
// (flyer_material = copper), its constants, and where they come from.
struct LibraryMaterial {
  std::string name;
  Material constants;
  std::string source;
};

// The built-in materials, aluminium first (the defaults of the bare material keys).
const std::vector<LibraryMaterial>& material_library();
// The library's material of that name, or null.
const LibraryMaterial* find_library_material(const std::string& name);

}  // namespace mpmshock
