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
// Before P2G it finds each point's temperature and rate from the states of the step's start; P2G
// scatters them (its sweep carries step 1: heat_flux_rider.hpp) and sums them across MPI ranks'
// shared rows; after P2G the flux folds them across a symmetry plane, normalises them and gathers
// step 2 on the step's stencils. Where conduction acts too, both move heat between the temperatures
// of the step's start.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/heat_flux_rider.hpp"
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
  // By point, the step's scratch: T_p, and what P2G scatters (C_p r_p, C_p T_p, C_p; zero for a
  // point in a bad state); C_p only with several materials.
  std::vector<double> point_temperature, point_rate, point_heat, point_capacity;
  std::vector<double> node_rate, node_temperature;  // C_i r_i and C_i T_i, then r_i and T_i
  std::vector<double> node_capacity;                // C_i, with several materials
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
  const LaneBits compressing = q != 0.0;
  r = Lanes{};
  if (!any(compressing)) return;  // (the lanes' rates are 0 either way)
  const Lanes x = rate_exponent(flux, q, m / (V0 * J_material), c0, pi2_dt_over_h2);
  r = compressing ? -exponential_minus_one(x) : Lanes{};
}

// What a point gives its nodes from its temperature T, rate r and heat capacity C: C r, C T and C,
// or nothing from a point in a bad state (a non-finite T or a rate below 0: a NaN the step will
// report), so that the report names it and not its neighbours. A double, or four points' Lanes.
template <class T, class Ok>
[[gnu::always_inline]] inline void point_gives(const T& temperature, const T& rate, const T& C, const Ok& ok,
                                                T& C_rate, T& C_temperature, T& capacity) {
  C_rate = ok ? C * rate : T{};
  C_temperature = ok ? C * temperature : T{};
  capacity = ok ? C : T{};
}

// Points p..p+3 (kFour: of one body) or p alone: T_p, and what they give their nodes (point_gives).
template <bool kFour, int D>
[[gnu::always_inline]] inline void heat_flux_four(Particles<D>& pts, std::size_t p, const HugoniotTemperature& model,
                                                  ArtificialHeatFlux& flux, double c0, double capacity,
                                                  double pi2_dt_over_h2) {
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
  Lanes C_rate, C_temperature, C;
  point_gives(T, r, m * capacity, finite(T) & (r >= 0.0), C_rate, C_temperature, C);
  store_points<kFour>(&flux.point_temperature[p], T);
  store_points<kFour>(&flux.point_rate[p], C_rate);
  store_points<kFour>(&flux.point_heat[p], C_temperature);
  if (!flux.one_material) store_points<kFour>(&flux.point_capacity[p], C);
}

// Every point's temperature T_p and what it gives its nodes (point_gives), into the flux's scratch:
// four points at a time where every body's temperature may be (temperature.hpp), else one by one.
// A point that does not compress (q = 0: at rest, or expanding) has rate 0 exactly. C_p is m_p
// times c_v,b / c_v,flyer (1 with one material: m_p exactly).
template <int D>
void point_temperatures_and_rates(Particles<D>& pts, PointRange range, const BodyTemperatures& thermal,
                                  ArtificialHeatFlux& flux, double pi2_dt_over_h2) {
  for (std::vector<double>* v : {&flux.point_temperature, &flux.point_rate, &flux.point_heat})
    if (v->size() < pts.size()) v->resize(pts.size());
  if (!flux.one_material && flux.point_capacity.size() < pts.size()) flux.point_capacity.resize(pts.size());
  double capacity[kBodies] = {1.0, 1.0, 1.0};  // c_v,b / c_v,flyer
  if (!flux.one_material)
    for (std::size_t b = 1; b < kBodies; ++b) capacity[b] = flux.specific_heat[b] / flux.specific_heat[0];
  if (thermal.in_lanes()) {
    auto points = [&](auto four, std::size_t p) __attribute__((always_inline)) {
      const auto b = static_cast<std::size_t>(pts.body[p]);
      heat_flux_four<decltype(four)::value>(pts, p, thermal.of_body(pts.body[p]), flux, flux.sound_speed[b],
                                            capacity[b], pi2_dt_over_h2);
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
    const auto b = static_cast<std::size_t>(pts.body[p]);
    const double T = thermal.energy_temperature(pts, p), q = pts.q[p];
    const double r =
        q != 0.0 ? -std::expm1(rate_exponent(flux, q, pts.density(p), flux.sound_speed[b], pi2_dt_over_h2)) : 0.0;
    double C_rate, C_temperature, C;
    point_gives(T, r, pts.m[p] * capacity[b], std::isfinite(T) && r >= 0.0, C_rate, C_temperature, C);
    flux.point_temperature[p] = T;
    flux.point_rate[p] = C_rate;
    flux.point_heat[p] = C_temperature;
    if (!flux.one_material) flux.point_capacity[p] = C;
  }
}

// The gather's row sums, sum_rows weight r_i (T_i - T_p), by column, from the nodal r_i and T_i.
struct FluxRowSums {
  Lanes sums{};
  template <class Nodes, class Factor>
  [[gnu::always_inline]] void add(const double* node_rate, const double* node_temperature, std::size_t row,
                                  const Factor& weight, double T_p, const Nodes& nodes) {
    Lanes rate, temperature;
    nodes.load(rate, node_rate + row);
    nodes.load(temperature, node_temperature + row);
    sums += weight * (rate * (temperature - T_p));
  }
  // sum_i N_ip r_i (T_i - T_p): the row sums weighed by the columns.
  [[gnu::always_inline]] double value(const Lanes& column_weight) const {
    const Lanes lanes = column_weight * sums;
    return (lanes[0] + lanes[2]) + (lanes[1] + lanes[3]);
  }
};

// Before P2G: the nodal sums zeroed on the step's rows (and an MPI rank's shared ones), the points'
// values found, and the rider that hands them to P2G.
template <int D>
void start_heat_flux(Particles<D>& pts, PointRange range, const StripBins& bins, const GridGeometry<D>& geo,
                     const Halo<D>& halo, const BodyTemperatures& thermal, ArtificialHeatFlux& flux, double dt,
                     HeatFluxRider& rider) {
  const RowRange rows = bins.rows();
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  const bool several = !flux.one_material;
  flux.node_rate.resize(geo.nodes());
  flux.node_temperature.resize(geo.nodes());
  if (several) flux.node_capacity.resize(geo.nodes());
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) {
    flux.node_rate[i] = flux.node_temperature[i] = 0.0;
    if (several) flux.node_capacity[i] = 0.0;
  }
  halo.zero(flux.node_rate, flux.node_temperature);
  if (several) halo.zero(flux.node_capacity);
  point_temperatures_and_rates(pts, range, thermal, flux, M_PI * M_PI * dt / (flux.cell_size * flux.cell_size));
  rider.rate = flux.point_rate.data();
  rider.heat = flux.point_heat.data();
  rider.capacity = several ? flux.point_capacity.data() : nullptr;
  rider.node_rate = &flux.node_rate;
  rider.node_temperature = &flux.node_temperature;
  rider.node_capacity = several ? &flux.node_capacity : nullptr;
}

// After P2G has summed C_i r_i and C_i T_i (and C_i): their mirror's share folded across a symmetry
// plane, r_i and T_i, and step 2, E_p += c_v,p sum_i N_ip r_i (T_i - T_p).
template <int D, class Shape>
void finish_heat_flux(Particles<D>& pts, PointRange range, const StripBins& bins, const Grid<D>& g,
                      const StencilStore<D>& store, ArtificialHeatFlux& flux, const SymmetryPlane<D>* plane) {
  const GridGeometry<D>& geo = g.geo;
  const RowRange rows = bins.rows();
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  if (plane) {  // a symmetry plane has one material on both sides (scene.cpp)
    plane->fold_scalar(g, flux.node_rate, rows);
    plane->fold_scalar(g, flux.node_temperature, rows);
  }
  const std::vector<double>& node_C = flux.one_material ? g.m : flux.node_capacity;
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) {
    const double inv_m = node_C[i] > 0.0 ? 1.0 / node_C[i] : 0.0;
    flux.node_rate[i] *= inv_m;
    flux.node_temperature[i] *= inv_m;
  }
  const auto& stencils = store.template of<Shape::support>();
  const double* const node_rate = flux.node_rate.data();
  const double* const node_temperature = flux.node_temperature.data();
  const double* const T = flux.point_temperature.data();
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {  // 2.
    double heat = 0.0;
    if constexpr (Shape::support == 4) {  // a row's four nodes at once (node_rows.hpp)
      const auto& st = stencils[p];
      FluxRowSums sums;
      for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& f, const auto& nodes) __attribute__((always_inline)) {
        sums.add(node_rate, node_temperature, row, f.weight, T[p], nodes);
      });
      heat = sums.value(columns_of(st).weight);
    } else {
      for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
        heat += N * node_rate[i] * (node_temperature[i] - T[p]);
      });
    }
    pts.E[p] += flux.specific_heat[static_cast<std::size_t>(pts.body[p])] * heat;
  }
}

// The heat flux as a step effect: its point values before P2G, which P2G scatters (heat_flux_rider.hpp,
// with the kernels Simulation chose at set-up for a scene with the flux: simulation.cpp,
// flux_sums_for); after P2G and the symmetry plane's fold (after conduction where both act), the
// nodal sums normalised and gathered.
template <int D, class Shape>
class ArtificialHeatFluxEffect final : public StepEffect<D> {
 public:
  ArtificialHeatFluxEffect(const BodyTemperatures& thermal, ArtificialHeatFlux constants)
      : thermal_(thermal), flux_(std::move(constants)) {}
  const char* name() const override { return "artificial heat flux"; }
  unsigned slots() const override { return slot_bit(StepSlot::before_to_grid) | slot_bit(StepSlot::after_to_grid); }
  void before_to_grid(StepContext<D>& c) override {
    start_heat_flux<D>(c.points, c.reached, c.bins, c.grid.geo, c.halo, thermal_, flux_, c.dt, rider_);
    c.heat_flux = &rider_;
  }
  void after_to_grid(StepContext<D>& c) override {
    finish_heat_flux<D, Shape>(c.points, c.reached, c.bins, c.grid, c.stencils, flux_, c.plane);
  }

 private:
  const BodyTemperatures& thermal_;
  ArtificialHeatFlux flux_;  // the constants and the scratch
  HeatFluxRider rider_;      // what P2G carries, pointing into flux_'s scratch
};

}  // namespace mpmshock
