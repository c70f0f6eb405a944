// Artificial heat flux (av_heat_flux = beta > 0): the shock-capturing companion of the artificial
// viscosity that Noh (1987) introduced against "wall heating", the excess entropy a viscous scheme
// leaves where a converging flow stagnates (the focus of a collapsing void, a jet's tip meeting the
// far wall). It conducts heat where and only while the viscosity acts, with a diffusivity that
// grows with the viscous pressure, alpha_p = beta h q_p / (rho_p c0) = beta h^2 |tr D| (A1 c + A2 h |tr D|) / c0:
// zero outside compression and continuous as the compression starts (a diffusivity of the viscous
// speed, beta h (A1 c + A2 h |tr D|), switched on by the sign of tr D, turned round-off in the rate
// into differences of 1e-9 between a symmetric and a whole run), so uniform states and plateaus are
// untouched, and the total energy is conserved to round-off.
//
//   1. nodal rate and temperature   r_i = sum_p N_ip C_p r_p / C_i,  T_i = sum_p N_ip C_p T_p / C_i
//   2. point energy                 E_p += c_v,p sum_i N_ip r_i (T_i - T_p)
//
// with C_p = m_p c_v,p / c_v,flyer the point's heat capacity in units of the flyer material's
// specific heat and C_i = sum_p N_ip C_p; with one material C_p = m_p and C_i the nodal mass m_i.
//
// with r_p = 1 - exp(-dt / tau_p), tau_p = h^2 / (pi^2 alpha_p) the decay time of the slowest
// sub-cell temperature mode (wavelength 2h, as heat conduction's relaxation). Each point relaxes
// toward its nodes' mean temperature at their rate; with r_i <= 1 the new temperature is a convex
// combination (no new extremes, stable at any dt). Energy: sum_p m_p c_v,p sum_i N_ip r_i (T_i - T_p)
// = c_v,flyer sum_i r_i (C_i T_i - sum_p N_ip C_p T_p) = 0 at every node. T is the energy model's temperature
// T_H(J) + (E - E_H(J)) / c_v whatever temperature_model reports (the flux moves internal energy).
//
// It runs after P2G on the step's stencils and bins, with the states of the step's start, folds its
// nodal sums across a symmetry plane and sums them across MPI ranks' shared rows as conduction does.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/lanes.hpp"
#include "mpmshock/node_rows.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/step_effect.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/symmetry_plane.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

struct ArtificialHeatFlux {
  double beta = 0.0;                     // alpha = beta h q / (rho c0)
  double cell_size = 0.0;                // h
  std::array<double, kBodies> specific_heat{};  // c_v by body
  std::array<double, kBodies> sound_speed{};    // c0 by body, the scale of the viscous pressure
  bool one_material = true;               // C_p = m_p, C_i = m_i
  std::vector<double> point_rate;                   // r_p, by point (the step's scratch)
  std::vector<double> node_rate, node_temperature;  // C_i r_i and C_i T_i, then r_i and T_i
  std::vector<double> node_capacity;                // C_i, with two materials
};

// The exponent of a point's rate, r_p = 1 - exp(x) = -expm1(x), x = -pi^2 dt alpha_p / h^2, from its
// viscous pressure q, density rho and its material's c0 (a double, or four points' Lanes).
template <class T>
T rate_exponent(const ArtificialHeatFlux& flux, const T& q, const T& rho, double c0, double pi2_dt_over_h2) {
  const T alpha = flux.beta * flux.cell_size * q / (rho * c0);
  return -alpha * pi2_dt_over_h2;
}

// Four points' temperatures (the energy model's) and rates, from F, the thermal energy, the failure
// J (0: intact), m, V0 and q: one body of instructions whichever way the lanes were filled, so that
// a point gives the same bits in any group (MPMSHOCK_ONE_BODY, number.hpp).
template <int D>
MPMSHOCK_ONE_BODY void heat_flux_lanes(const HugoniotTemperature& model, const ArtificialHeatFlux& flux, double c0,
                                       double pi2_dt_over_h2, const Mat<D, Lanes>& F, const Lanes& E_thermal,
                                       const Lanes& failure_J, const Lanes& m, const Lanes& V0, const Lanes& q,
                                       Lanes& T, Lanes& r) {
  const Lanes J = det(F);
  const Lanes J_material = failure_J > 0.0 ? minimum(J, failure_J) : J;  // Particles::material_J
  model.temperature_lanes(T, J_material, E_thermal);
  const Lanes x = rate_exponent(flux, q, m / (V0 * J_material), c0, pi2_dt_over_h2);
  r = q != 0.0 ? -exponential_minus_one(x) : Lanes{};
}

// Points p..p+3 (kFour: of one body) or p alone: T_p into `work`, r_p into flux.point_rate.
template <bool kFour, int D>
[[gnu::always_inline]] inline void heat_flux_four(Particles<D>& pts, std::size_t p, const HugoniotTemperature& model,
                                                  ArtificialHeatFlux& flux, double c0, double pi2_dt_over_h2) {
  Mat<D, Lanes> F;
  Lanes E, E_stored{}, failure_J{}, m, V0, q, T, r;
  load_points<kFour>(F, &pts.F[p]);
  load_points<kFour>(E, &pts.E[p]);
  if (pts.stores_cold_work()) load_points<kFour>(E_stored, &pts.E_stored[p]);
  if (pts.has_failure()) load_points<kFour>(failure_J, &pts.failure_J[p]);
  load_points<kFour>(m, &pts.m[p]);
  load_points<kFour>(V0, &pts.V0[p]);
  load_points<kFour>(q, &pts.q[p]);
  const Lanes E_thermal = pts.stores_cold_work() ? E - E_stored : E;  // Particles::thermal_energy
  heat_flux_lanes<D>(model, flux, c0, pi2_dt_over_h2, F, E_thermal, failure_J, m, V0, q, T, r);
  store_points<kFour>(&pts.work[p], T);
  store_points<kFour>(&flux.point_rate[p], r);
}

// Every point's temperature T_p (into pts.work, the step's scratch) and rate r_p (flux.point_rate):
// four points at a time where every body's temperature may be (temperature.hpp), else one by one.
// A point that does not compress (q = 0: at rest, or expanding) has rate 0 exactly.
template <int D>
void point_temperatures_and_rates(Particles<D>& pts, PointRange range, const BodyTemperatures& thermal,
                                  ArtificialHeatFlux& flux, double pi2_dt_over_h2) {
  if (flux.point_rate.size() < pts.size()) flux.point_rate.resize(pts.size());
  if (thermal.in_lanes()) {
    auto points = [&](auto four, std::size_t p) __attribute__((always_inline)) {
      heat_flux_four<decltype(four)::value>(pts, p, thermal.of_body(pts.body[p]), flux,
                                            flux.sound_speed[static_cast<std::size_t>(pts.body[p])], pi2_dt_over_h2);
    };
    const std::size_t groups = groups_of_four(range);
#pragma omp parallel for schedule(dynamic, kChunk / 4)
    for (std::size_t g = 0; g < groups; ++g)
      for_group_of_four(
          pts, range, g, [&](std::size_t p) __attribute__((always_inline)) { points(std::true_type{}, p); },
          [&](std::size_t q) __attribute__((always_inline)) { points(std::false_type{}, q); });
    return;
  }
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    pts.work[p] = thermal.energy_temperature(pts, p);
    const double q = pts.q[p];
    flux.point_rate[p] =
        q != 0.0 ? -std::expm1(rate_exponent(flux, q, pts.density(p), flux.sound_speed[static_cast<std::size_t>(pts.body[p])],
                                             pi2_dt_over_h2))
                 : 0.0;
  }
}

template <int D, class Shape>
void artificial_heat_flux(Particles<D>& pts, PointRange range, const StripBins& bins, const Grid<D>& g,
                          const StencilStore<D>& store, const Halo<D>& halo, const BodyTemperatures& thermal,
                          ArtificialHeatFlux& flux, const SymmetryPlane<D>* plane, double dt) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();
  const RowRange rows = bins.rows();
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  flux.node_rate.resize(geo.nodes());
  flux.node_temperature.resize(geo.nodes());
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) flux.node_rate[i] = flux.node_temperature[i] = 0.0;
  halo.zero(flux.node_rate, flux.node_temperature);
  const bool two = !flux.one_material;
  if (two) {
    flux.node_capacity.resize(geo.nodes());
#pragma omp parallel for schedule(static)
    for (std::size_t i = first; i < last; ++i) flux.node_capacity[i] = 0.0;
    halo.zero(flux.node_capacity);
  }
  const double capacity[kBodies] = {1.0, flux.specific_heat[1] / flux.specific_heat[0],
                                    flux.specific_heat[2] / flux.specific_heat[0]};  // c_v,b / c_v,flyer

  // The step's scratch holds T_p (written again by the velocity gradient later in the step).
  std::vector<double>& T = pts.work;
  const double pi2_dt_over_h2 = M_PI * M_PI * dt / (flux.cell_size * flux.cell_size);
  point_temperatures_and_rates(pts, range, thermal, flux, pi2_dt_over_h2);
  // 1. scattered with the heat capacities where the bodies differ (a choice made once, not per node).
  auto scatter = [&](auto materials) {
    constexpr bool several = decltype(materials)::value;
    bins.scatter([&](std::size_t p) __attribute__((always_inline)) {
      const auto b = static_cast<std::size_t>(pts.body[p]);
      // A point that does not compress has rate 0, and adding N * 0 to a nodal rate changes no bit,
      // so node by node it adds its temperature (and capacity) alone; the four-column rows add its
      // zero rate too, as a test per row cost more. Points in uniform motion are not among
      // them: round-off in their nodal velocities leaves tiny compression rates (67-84 % of the
      // points of a solid 2D impact had q != 0, r down to 1e-17), so a pass over only the
      // compressing points would not save work (tried 2026-12-06: more instructions).
      const double r = flux.point_rate[p];
      // A point in a bad state (a NaN the step will report) gives its nodes nothing, so the report
      // names it and not its neighbours.
      if (!std::isfinite(T[p]) || !(r >= 0.0)) return;
      const double C = several ? pts.m[p] * capacity[b] : pts.m[p], Cr = C * r, CT = C * T[p];
      if constexpr (Shape::support == 4) {  // weighed by the columns once, then by each row (node_rows.hpp)
        const auto& st = stencils[p];
        const Columns<D> c = columns_of(st);
        const Lanes Cr_columns = c.weight * Cr, CT_columns = c.weight * CT, C_columns = c.weight * C;
        for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& f, const auto& nodes) __attribute__((always_inline)) {
          Lanes rate;  // with r = 0 too: a test per row cost more than the adds of zero it saves
          nodes.load(rate, &flux.node_rate[row]);
          rate += f.weight * Cr_columns;
          nodes.store(&flux.node_rate[row], rate);
          Lanes temperature;
          nodes.load(temperature, &flux.node_temperature[row]);
          temperature += f.weight * CT_columns;
          nodes.store(&flux.node_temperature[row], temperature);
          if constexpr (several) {
            Lanes capacity;
            nodes.load(capacity, &flux.node_capacity[row]);
            capacity += f.weight * C_columns;
            nodes.store(&flux.node_capacity[row], capacity);
          }
        });
      } else {
        const bool rates = r > 0.0;
        for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
          if (rates) flux.node_rate[i] += N * Cr;
          flux.node_temperature[i] += N * CT;
          if constexpr (several) flux.node_capacity[i] += N * C;
        });
      }
    }, [&] {
      halo.between_colours(flux.node_rate, flux.node_temperature);
      if constexpr (several) halo.between_colours(flux.node_capacity);
    }, [&] {
      halo.after_colours(flux.node_rate, flux.node_temperature);
      if constexpr (several) halo.after_colours(flux.node_capacity);
    });
  };
  if (two) scatter(std::true_type{});
  else scatter(std::false_type{});
  if (plane) {  // a symmetry plane has one material on both sides (scene.cpp)
    plane->fold_scalar(g, flux.node_rate, rows);
    plane->fold_scalar(g, flux.node_temperature, rows);
  }
  const std::vector<double>& node_C = two ? flux.node_capacity : g.m;
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) {
    const double inv_m = node_C[i] > 0.0 ? 1.0 / node_C[i] : 0.0;
    flux.node_rate[i] *= inv_m;
    flux.node_temperature[i] *= inv_m;
  }
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {  // 2.
    double heat = 0.0;
    if constexpr (Shape::support == 4) {  // a row's four nodes at once (node_rows.hpp)
      const auto& st = stencils[p];
      const double T_p = T[p];
      Lanes sums{};  // sum over rows of the row weight times r_i (T_i - T_p), by column
      for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& f, const auto& nodes) __attribute__((always_inline)) {
        Lanes rate, temperature;
        nodes.load(rate, &flux.node_rate[row]);
        nodes.load(temperature, &flux.node_temperature[row]);
        sums += f.weight * (rate * (temperature - T_p));
      });
      const Lanes lanes = columns_of(st).weight * sums;
      heat = (lanes[0] + lanes[2]) + (lanes[1] + lanes[3]);
    } else {
      for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
        heat += N * flux.node_rate[i] * (flux.node_temperature[i] - T[p]);
      });
    }
    pts.E[p] += flux.specific_heat[static_cast<std::size_t>(pts.body[p])] * heat;
  }
}

// The heat flux as a step effect: after P2G and the symmetry plane's fold (after conduction where
// both act), with the states of the step's start.
template <int D, class Shape>
class ArtificialHeatFluxEffect final : public StepEffect<D> {
 public:
  ArtificialHeatFluxEffect(const BodyTemperatures& thermal, ArtificialHeatFlux constants)
      : thermal_(thermal), flux_(std::move(constants)) {}
  const char* name() const override { return "artificial heat flux"; }
  unsigned slots() const override { return slot_bit(StepSlot::after_to_grid); }
  void after_to_grid(StepContext<D>& c) override {
    artificial_heat_flux<D, Shape>(c.points, c.reached, c.bins, c.grid, c.stencils, c.halo, thermal_, flux_, c.plane,
                                   c.dt);
  }

 private:
  const BodyTemperatures& thermal_;
  ArtificialHeatFlux flux_;  // the constants and the nodal scratch
};

}  // namespace mpmshock
