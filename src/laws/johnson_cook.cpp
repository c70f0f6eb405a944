// Johnson-Cook's flow stress (johnson_cook.hpp): (A + B eps_p^n)(1 + C ln rate)(1 - T*^m).
#include <algorithm>
#include <sstream>

#include "mpmshock/johnson_cook.hpp"
#include "mpmshock/material_law.hpp"
#include "mpmshock/scene.hpp"

namespace mpmshock {

MaterialLaw JohnsonCook::law() {
  using D = Dimension;
  MaterialLaw law;
  law.slot = LawSlot::strength;
  law.name = kName;
  law.summary = "johnson_cook, (A + B eps_p^n)(1 + C ln rate)(1 - T*^m) with the jc_* constants, strain rate in 1/s, "
                "its own thermal softening and melt at jc_melt_temperature (isotropic hardening; built-in constants: "
                "aluminium, copper)";
  law.plasticity = "Johnson-Cook flow stress: strain, rate and temperature; molten at jc_melt_temperature";
  // Its own melt, without latent heat.
  law.melt = [](const Material& m) {
    std::ostringstream out;
    out << "Johnson-Cook's T_m " << m.law_constants<Constants>().melt_temperature << " K";
    return out.str();
  };
  law.keys = {
      {"jc_yield_stress", D::pressure, non_negative_bound(), "324 MPa",
       "Johnson-Cook A, the yield stress at zero plastic strain, 1 /s and room temperature "
       "(strength_model = johnson_cook; 6061-T6 after Johnson and Holmquist 1989); 0: the material "
       "has no Johnson-Cook constants",
       field<&JohnsonCookConstants::yield_stress>},
      {"jc_hardening", D::pressure, non_negative_bound(), "114 MPa", "Johnson-Cook B, the strain hardening",
       field<&JohnsonCookConstants::hardening>},
      {"jc_hardening_exponent", D::none, closed_bound(0.0, 10.0), "0.42", "Johnson-Cook n",
       field<&JohnsonCookConstants::hardening_exponent>},
      {"jc_rate_coefficient", D::none, closed_bound(0.0, 10.0), "0.002",
       "Johnson-Cook C, per e-fold of the equivalent strain rate above 1 /s", field<&JohnsonCookConstants::rate_coefficient>},
      {"jc_thermal_exponent", D::none, closed_bound(0.0, 100.0), "1.34", "Johnson-Cook m",
       field<&JohnsonCookConstants::thermal_exponent>},
      {"jc_melt_temperature", D::temperature, closed_bound(0.0, 1e5), "925 K",
       "Johnson-Cook T_m: T* = (T - jc_room_temperature) / (T_m - jc_room_temperature); molten at T_m",
       field<&JohnsonCookConstants::melt_temperature>},
      {"jc_room_temperature", D::temperature, closed_bound(0.0, 1e5), "298 K",
       "Johnson-Cook T_r, the temperature of its tests, where T* = 0", field<&JohnsonCookConstants::room_temperature>,
       /*reference=*/true},
  };
  // Each such material needs its constants, in a state where it has strength.
  law.check = [](const MaterialCheck& c) {
    const Material& m = c.material;
    const Constants& jc = m.law_constants<Constants>();
    if (!jc.present())
      c.fail(c.prefix + "jc_yield_stress", "strength_model = johnson_cook, but material " + c.name +
                                               " has no Johnson-Cook constants: give its " + c.prefix +
                                               "jc_* keys (mpmshock --keys), or use strength_model = bilinear");
    else if (m.hardening_beta != 1.0)
      c.fail(c.prefix + "hardening_beta",
             "johnson_cook hardens isotropically: needs hardening_beta = 1 (material " + c.name + ")");
    else if (!(jc.thermal_exponent > 0.0))
      c.fail(c.prefix + "jc_thermal_exponent", "must be > 0 with strength_model = johnson_cook (material " + c.name + ")");
    else if (!(jc.melt_temperature > std::max(jc.room_temperature, m.initial_temperature)))
      c.fail(c.prefix + "jc_melt_temperature", "must be above jc_room_temperature and initial_temperature (material " +
                                                   c.name + "): the material would start molten");
  };
  law.check_scene = [](const Scene& s, const std::string& key, const auto& fail) {
    if (!s.effects.plasticity) fail(key, "johnson_cook needs plasticity = on");
    // Its thermal term softens by the energy model's temperature: the run's must be that one.
    if (!s.effects.thermal) fail(key, "johnson_cook needs thermal = on (it softens by temperature)");
    if (s.temperature_model == TemperatureModel::paper)
      fail(key, "johnson_cook cannot go with temperature_model = paper: the paper's temperature leaves "
                "out the compaction heat, and the law softens by the energy model's; use "
                "temperature_model = energy (paper_temperature = on reports the paper's beside it)");
    const auto in_use = s.materials_in_use();
    const bool any_bilinear = std::any_of(in_use.begin(), in_use.end(), [&](const std::string& name) {
      return s.material_by_name(name).strength_model == "bilinear";
    });
    if (s.effects.thermal_softening && !any_bilinear)
      fail(key, "johnson_cook softens by its own (1 - T*^m) and melts at jc_melt_temperature, and no body takes "
                "the bilinear law that thermal_softening (Steinberg-Guinan) softens: use thermal_softening = off");
  };
  return law;
}

}  // namespace mpmshock
