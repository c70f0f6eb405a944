// Temperature from the state, with T_H(V) the temperature on the Hugoniot from the Walsh-Christian
// equation (physics-notes section 2), integrated once at start-up into a table:
//   energy (default): T = T_H(V) + (E - E_H(V)) / c_v, all the heat the internal energy holds beyond
//                     the Hugoniot's: shock, plastic and compaction (PdV work on collapsing voids);
// With Tillotson's equation of state (equation_of_state = tillotson), which has no Hugoniot of
// closed form, the reference curve is instead the isentrope through the reference state (J = 1,
// E = 0, T0): dE_s/dJ = -P(J, E_s) / rho0, dT_s/dJ = -T_s (dP/dE)_V / rho0, tabulated at start-up
// (uniform in J from the EOS's limiting compression to 1, uniform in ln J from 1 to 100; beyond
// 100 the values at 100), and T = T_s(V) + (E - E_s(V)) / c_v with the same constant c_v.
//   (Below, T_H and E_H stand for whichever reference curve the material's equation of state has.)
//   paper:            T = T_H(V) + W_p / c_v, W_p the plastic work turned to heat. The paper's text
//                     takes E - E_H as plastic energy, but its reported temperatures (432 K at
//                     250 ns, ~60 K left after release at delta 1.03) fit this model, which leaves
//                     out the compaction heating; it is offered to compare with the paper, and does
//                     not feed back (it cannot go with conduction or softening: scene.cpp).
// With melting (thermal_softening = on: set_melting), the energy model's temperature stops at the
// melt temperature T_m(J) while the latent heat L is taken up: T = T_m for a sensible excess
// c_v (T_sensible - T_m) up to L, then T = T_m + (excess - L) / c_v.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "mpmshock/eos.hpp"
#include "mpmshock/number.hpp"
#include "mpmshock/material.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/thermal_softening.hpp"

namespace mpmshock {

class HugoniotTemperature {
 public:
  HugoniotTemperature() = default;
  // Tabulates T_H on J in [J_min, 1] with `intervals` equal steps, J_min the equation of state's
  // limiting compression (2 % short of the Us-up pole 1 - 1/s, where T_H diverges: eos.hpp). For
  // J >= 1 (tension) the reference curve is the linear branch
  // P_H = rho0 c0^2 eta, on which the Walsh-Christian equation has no shock-heating term (s = 0):
  // T_H = T0 exp(gamma0 (1 - J)), the isentrope, continuous with its slope at J = 1.
  // `report_paper`: outputs also carry the paper model's temperature (scene key paper_temperature).
  HugoniotTemperature(const Material& mat, TemperatureModel model = TemperatureModel::energy,
                      bool report_paper = false, int intervals = 4096);

  // T_H(J), the reference curve's temperature (with Tillotson: the isentrope's).
  double hugoniot_temperature(double J) const;
  // E_H(J), the reference curve's energy.
  double reference_energy(double J) const {
    return isentrope_.empty() ? eos_.hugoniot_energy(J) : isentrope_lookup(J).energy;
  }

  // T = T_H(J) + (E - E_H(J)) / c_v, held at T_m(J) while the latent heat is taken up.
  double temperature(double J, double E) const {
    const double T = hugoniot_temperature(J) + (E - reference_energy(J)) / cv_;
    if (latent_heat_ > 0.0) {
      const double T_m = melt_.at(J);
      if (T > T_m) return T_m + std::max(0.0, (T - T_m) * cv_ - latent_heat_) / cv_;
    }
    return T;
  }

  // The same, four points at a time (Lanes, number.hpp), where the reference curve is the
  // Hugoniot's table and there is no latent heat (in_lanes()): each lane what temperature(J, E)
  // gives it, to within a few ulp (the tension branch's exponential is number.hpp's, not libm's).
  bool in_lanes() const { return isentrope_.empty() && table_.size() >= 2 && latent_heat_ == 0.0; }
  void temperature_lanes(Lanes& T, const Lanes& J, const Lanes& E) const {
    // The table between J_min and 1 (hugoniot_temperature): the interval k = floor(u) of each
    // lane, held within the table for the lanes that take another branch.
    // Each branch only where a lane takes it (uncompressed material: only the tension branch's):
    // the lanes' values are the same either way.
    const LaneBits tension = J >= 1.0;  // (NaN: the table's branch)
    Lanes T_H{};
    if (any(~tension)) {
      const Lanes u = (1.0 - J) / dJ_;
      const double last = static_cast<double>(table_.size() - 2);
      const Lanes held = u >= 0.0 ? (u <= last ? u : Lanes{} + last) : Lanes{};  // NaN: 0
      const LaneInts k = __builtin_convertvector(held, LaneInts);
      const Lanes below{table_[k[0]], table_[k[1]], table_[k[2]], table_[k[3]]};
      const Lanes above{table_[k[0] + 1], table_[k[1] + 1], table_[k[2] + 1], table_[k[3] + 1]};
      const Lanes frac = u - __builtin_convertvector(k, Lanes);
      T_H = u < last + 1.0 ? below + frac * (above - below) : Lanes{} + table_.back();
      T_H = J >= J_min_ ? T_H : Lanes{} + std::numeric_limits<double>::infinity();
    }
    if (any(tension)) T_H = tension ? T0_ * exponential(gamma0_ * (1.0 - J)) : T_H;
    T = T_H + (E - eos_.hugoniot_energy(J)) / cv_;
  }

  // Melting: the melt curve and the latent heat L [J/kg] (0: none, the default).
  void set_melting(const MeltCurve& melt, double latent_heat) {
    melt_ = melt;
    latent_heat_ = latent_heat;
  }

  // T = T_H(J) + W_p / c_v (the paper model), W_p the plastic heat [J/kg].
  double paper_temperature(double J, double plastic_heat) const { return hugoniot_temperature(J) + plastic_heat / cv_; }

  // The temperature of point q by the scene's model: from the material's own volume and the point's
  // heat (its thermal energy, or its plastic heat with the paper model).
  template <int D>
  double of_point(const Particles<D>& p, std::size_t q) const {
    const double J = p.material_J(q);
    return model_ == TemperatureModel::paper ? paper_temperature(J, p.plastic_heat[q])
                                             : temperature(J, p.thermal_energy(q));
  }

  // The paper model's temperature of point q, reported beside the scene's (paper_temperature = on).
  bool reports_paper_temperature() const { return report_paper_; }
  template <int D>
  double paper_of_point(const Particles<D>& p, std::size_t q) const {
    return paper_temperature(p.material_J(q), p.plastic_heat[q]);
  }

  double min_tabulated_J() const { return J_min_; }

 private:
  // The reference isentrope of an equation of state without a Hugoniot in closed form (see the top
  // of the file): `Eos` offers rho0, limiting_compression and pressure_and_energy_slope.
  template <class Eos>
  void tabulate_isentrope(const Eos& eos, int intervals);
  struct IsentropeNode {
    double energy, temperature;
  };
  IsentropeNode isentrope_lookup(double J) const {
    double u;
    std::size_t base = 0;  // the J = 1 node's index: the compressed nodes come first
    if (!(J >= J_min_)) return isentrope_.front();  // (J_min: a refused state; NaN too)
    if (J <= 1.0) {
      u = (J - J_min_) / dJ_;
    } else {
      base = compressed_nodes_ - 1;
      u = std::min(std::log(J) / dlnJ_, static_cast<double>(isentrope_.size() - 1 - base));
    }
    const auto k = base + static_cast<std::size_t>(u);
    if (k + 1 >= isentrope_.size()) return isentrope_.back();
    const double frac = u - std::floor(u);
    const IsentropeNode &a = isentrope_[k], &b = isentrope_[k + 1];
    return {a.energy + frac * (b.energy - a.energy), a.temperature + frac * (b.temperature - a.temperature)};
  }

  TemperatureModel model_ = TemperatureModel::energy;
  bool report_paper_ = false;
  MieGruneisen eos_;
  double cv_ = 880.0, T0_ = 300.0, gamma0_ = 1.96;
  double J_min_ = 0.0, dJ_ = 0.0;
  MeltCurve melt_;
  double latent_heat_ = 0.0;
  std::vector<double> table_;  // table_[k] = T_H(1 - k dJ)
  // With Tillotson: E_s and T_s at J = J_min + k dJ up to 1 (compressed_nodes_ of them), then at
  // J = exp(k dlnJ) up to 100 (empty with Mie-Grüneisen).
  std::vector<IsentropeNode> isentrope_;
  std::size_t compressed_nodes_ = 0;
  double dlnJ_ = 0.0;
};

// The temperature models of the bodies, each of its own material (flyer_material,
// target_material, window_material): a point's temperature is its body's.
class BodyTemperatures {
 public:
  BodyTemperatures(const Material& flyer, const Material& target, const Material& window,
                   TemperatureModel model = TemperatureModel::energy, bool report_paper = false) {
    // A body of the flyer's (or the target's) constants shares its table.
    const Material* materials[kBodies] = {&flyer, &target, &window};
    for (std::size_t b = 0; b < kBodies; ++b) {
      std::size_t same = 0;
      while (same < b && !same_constants(*materials[same], *materials[b])) ++same;
      by_body_[b] = same < b ? by_body_[same] : HugoniotTemperature(*materials[b], model, report_paper);
    }
  }

  const HugoniotTemperature& of_body(Body b) const { return by_body_[static_cast<std::size_t>(b)]; }

  // The temperature of point q by the scene's model.
  template <int D>
  double of_point(const Particles<D>& p, std::size_t q) const { return of_body(p.body[q]).of_point(p, q); }
  // The energy model's temperature of point q, which the heat flux and the 0 K check read.
  template <int D>
  double energy_temperature(const Particles<D>& p, std::size_t q) const {
    return of_body(p.body[q]).temperature(p.material_J(q), p.thermal_energy(q));
  }
  // Whether every body's energy-model temperature may be computed four points at a time.
  bool in_lanes() const {
    return by_body_[0].in_lanes() && by_body_[1].in_lanes() && by_body_[2].in_lanes();
  }
  bool reports_paper_temperature() const { return by_body_[0].reports_paper_temperature(); }
  template <int D>
  double paper_of_point(const Particles<D>& p, std::size_t q) const { return of_body(p.body[q]).paper_of_point(p, q); }

  // Melting, of a body's material.
  void set_melting(Body b, const MeltCurve& melt, double latent_heat) {
    by_body_[static_cast<std::size_t>(b)].set_melting(melt, latent_heat);
  }

 private:
  std::array<HugoniotTemperature, kBodies> by_body_;
};

}  // namespace mpmshock
