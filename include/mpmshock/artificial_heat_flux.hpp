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
  std::vector<double> node_rate, node_temperature;  // C_i r_i and C_i T_i, then r_i and T_i
  std::vector<double> node_capacity;                // C_i, with two materials
};

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
  // 1. scattered with the heat capacities where the bodies differ (a choice made once, not per node).
  auto scatter = [&](auto materials) {
    constexpr bool several = decltype(materials)::value;
    bins.scatter([&](std::size_t p) {
      const auto b = static_cast<std::size_t>(pts.body[p]);
      T[p] = thermal.energy_temperature(pts, p);
      // A point that does not compress (q = 0: at rest, or expanding) has rate 0 exactly, and adding
      // N * 0 to a nodal rate changes no bit, so it adds its temperature (and capacity) alone. Points
      // in uniform motion are not among them: round-off in their nodal velocities leaves tiny
      // compression rates (67-84 % of the points of a solid 2D impact had q != 0, r down to 1e-17),
      // so a pass over only the compressing points would not save work (tried 2026-12-06: more
      // instructions).
      const double q = pts.q[p];
      double r = 0.0;
      if (q != 0.0) {
        const double alpha = flux.beta * flux.cell_size * q / (pts.density(p) * flux.sound_speed[b]);
        r = -std::expm1(-alpha * pi2_dt_over_h2);
      }
      // A point in a bad state (a NaN the step will report) gives its nodes nothing, so the report
      // names it and not its neighbours.
      if (!std::isfinite(T[p]) || !(r >= 0.0)) return;
      const double C = several ? pts.m[p] * capacity[b] : pts.m[p], Cr = C * r, CT = C * T[p];
      const bool rates = r > 0.0;
      if constexpr (Shape::support == 4) {  // each node given what the loop below gives it
        const auto& st = stencils[p];
        const bool consecutive = consecutive_columns(st);
        for_each_row(st, geo, [&](std::size_t row, const RowShape<D>& shape) __attribute__((always_inline)) {
          if (rates) {
            Lanes rate;
            load_scalar_row(rate, &flux.node_rate[row], st.column, consecutive);
            rate += shape.scalar * Cr;
            store_scalar_row(&flux.node_rate[row], st.column, consecutive, rate);
          }
          Lanes temperature;
          load_scalar_row(temperature, &flux.node_temperature[row], st.column, consecutive);
          temperature += shape.scalar * CT;
          store_scalar_row(&flux.node_temperature[row], st.column, consecutive, temperature);
          if constexpr (several) {
            Lanes capacity;
            load_scalar_row(capacity, &flux.node_capacity[row], st.column, consecutive);
            capacity += shape.scalar * C;
            store_scalar_row(&flux.node_capacity[row], st.column, consecutive, capacity);
          }
        });
      } else {
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
      const bool consecutive = consecutive_columns(st);
      Lanes lanes{};
      for_each_row(st, geo, [&](std::size_t row, const RowShape<D>& shape) __attribute__((always_inline)) {
        Lanes rate, temperature;
        load_scalar_row(rate, &flux.node_rate[row], st.column, consecutive);
        load_scalar_row(temperature, &flux.node_temperature[row], st.column, consecutive);
        lanes += shape.scalar * rate * (temperature - T[p]);
      });
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
