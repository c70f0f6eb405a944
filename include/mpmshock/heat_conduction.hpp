// Heat conduction (heat_conduction = on): Fourier's law, q = -k grad T, through the grid, each
// point with its body's material's k, c_v and diffusivity alpha = k / (rho0 c_v).
//
//   1. nodal temperature   T_i = sum_p N_ip C_p T_p / C_i             (scatter, then divide)
//   2. point gradient      g_p = sum_i T_i grad N_ip
//   3. nodal heat rate     Q_i = -sum_p V_p k_p g_p . grad N_ip       (scatter) [W per m of depth]
//   4. point energy        E_p += dt sum_i N_ip Q_i / m_i             (gather)  [J/kg]
//                               + c_v,p (T~_p - T_p) r_p,  T~_p = sum_i N_ip T_i,  r_p = 1 - exp(-dt / tau_p)
//
// C_p = m_p c_v,p is a point's heat capacity and C_i = sum_p N_ip C_p a node's; with one material
// the weights are the masses (c_v cancels), as they were before conduction took a material per body.
//
// Steps 1-4 without the last term are the Galerkin heat equation on the grid, its increments
// carried to the points as FLIP carries velocity increments: they never see how the points' own
// temperatures vary within a cell (a point hotter than its neighbours stays hotter for ever; at a
// hot/cold interface the rows next to it kept 30 K of their initial offset whatever the cell size).
// The last term is the sub-cell conduction the grid cannot resolve: each point's deviation from
// the grid's temperature field decays at the rate of the slowest sub-cell mode, wavelength 2h,
// tau_p = h^2 / (pi^2 alpha_p). Energy is conserved exactly: sum_i Q_i = 0 because sum_i grad N_ip = 0
// (partition of unity), step 4 hands each node's Q_i out in the shares N_ip m_p / m_i that sum to
// one, and the deviations' heat sums to zero: the part of them the grid resolves (4b) is the nodal
// mean weighted by C_p r_p, so sum_p C_p r_p (d_p - sum_i N_ip d_i) = 0 for any r_p (one material:
// r_p is one number and the weights the masses). Where a point's material conducts slowly (PMMA's
// alpha is 1/600 of aluminium's) its r_p is small and it barely takes part in the sub-cell
// exchange, as its own diffusion would have it. It runs on
// the grid and strips of the step's P2G (before the points move), with the temperatures of the
// step's start. Explicit diffusion is stable for dt <= h^2 / (2 D alpha) (alpha = k / (rho c_v));
// the time step keeps 0.2 h^2 / alpha (0.15 in 3D) of the most diffusive body (at a node shared by
// two materials the effective diffusivity, k of one over rho c_v of the other, can exceed either's:
// copper on PMMA about 2x copper's), which for aluminium (alpha = 1e-4 m2/s) binds only below
// 0.1 um cells: at the paper's cells the mechanical step is 10^3-10^4 times shorter.
//
// With a symmetry plane (symmetry = on) each of the three nodal sums is folded across it
// (SymmetryPlane::fold_scalar) before it is read: the temperature field and heat rates are even in y,
// so the mirror flyer's share at a node is the target's own share at the mirror node, and the plane
// is adiabatic (no heat crosses it), as in the whole impact by symmetry. On MPI ranks each sum is
// also completed across the rows two ranks share (halo.hpp) before it is folded or read.
#pragma once

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/step_effect.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/symmetry_plane.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

// The nodal scratch fields of the conduction and each body's constants.
struct HeatConduction {
  std::array<double, kBodies> conductivity{};     // k [W/(m K)]
  std::array<double, kBodies> specific_heat{};    // c_v [J/(kg K)]
  std::array<double, kBodies> relaxation_time{};  // tau = h^2 / (pi^2 alpha) of the sub-cell deviations [s]
  bool one_material = true;  // every body of one material: the nodal means are mass-weighted
  std::vector<double> node_heat;  // C_i T_i, then T_i
  std::vector<double> node_rate;  // Q_i
  std::vector<double> node_capacity;  // C_i (two materials), then the weights of 4b
};

// `plane`: the symmetry plane (symmetry = on), or null.
template <int D, class Shape>
void conduct_heat(Particles<D>& pts, PointRange range, const StripBins& bins, const Grid<D>& g,
                  const StencilStore<D>& store, const Halo<D>& halo, const BodyTemperatures& thermal,
                  HeatConduction& h, const SymmetryPlane<D>* plane, double dt) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();  // the step's, of the same x and F
  const RowRange rows = bins.rows();
  auto fold = [&](std::vector<double>& field) {
    if (plane) plane->fold_scalar(g, field, rows);
  };
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  const bool weighted = !h.one_material;  // heat capacities, not masses, weight the nodal means
  h.node_heat.resize(geo.nodes());
  h.node_rate.resize(geo.nodes());
  if (weighted) h.node_capacity.resize(geo.nodes());
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) {
    h.node_heat[i] = h.node_rate[i] = 0.0;
    if (weighted) h.node_capacity[i] = 0.0;
  }
  // Each body's sub-cell relaxation over this step, r = 1 - exp(-dt / tau).
  std::array<double, kBodies> relax{};
  for (std::size_t b = 0; b < kBodies; ++b)
    relax[b] = h.relaxation_time[b] > 0.0 ? 1.0 - std::exp(-dt / h.relaxation_time[b]) : 0.0;
  auto body = [&](std::size_t p) { return static_cast<std::size_t>(pts.body[p]); };

  // The step's scratch (work is written later in the step) holds T_p, then d_p.
  std::vector<double>& T = pts.work;
  // Each nodal sum is summed across the rows MPI ranks share (halo.hpp) before it is read.
  auto summed_across_ranks = [&](std::vector<double>& field) {
    return std::make_pair([&] { halo.between_colours(field); }, [&] { halo.after_colours(field); });
  };
  // The nodal means: the field over the nodes' masses, or over their heat capacities.
  auto divide_by_weights = [&](std::vector<double>& field) {
    fold(field);
    if (weighted) fold(h.node_capacity);
#pragma omp parallel for schedule(static)
    for (std::size_t i = first; i < last; ++i) {
      const double w = weighted ? h.node_capacity[i] : g.m[i];
      field[i] = w > 0.0 ? field[i] / w : 0.0;
    }
  };
  halo.zero(h.node_heat, h.node_rate);
  if (weighted) halo.zero(h.node_capacity);
  // The heat and, with two materials, the capacity: summed across ranks in one exchange.
  auto heat_and_capacity_between = [&] {
    if (weighted) halo.between_colours(h.node_heat, h.node_capacity);
    else halo.between_colours(h.node_heat);
  };
  auto heat_and_capacity_after = [&] {
    if (weighted) halo.after_colours(h.node_heat, h.node_capacity);
    else halo.after_colours(h.node_heat);
  };
  bins.scatter([&](std::size_t p) {  // 1. C_i T_i (and C_i)
    T[p] = thermal.of_point(pts, p);
    if (!weighted) {
      const double mT = pts.m[p] * T[p];
      for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) { h.node_heat[i] += N * mT; });
      return;
    }
    const double C = pts.m[p] * h.specific_heat[body(p)], CT = C * T[p];
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
      h.node_heat[i] += N * CT;
      h.node_capacity[i] += N * C;
    });
  }, heat_and_capacity_between, heat_and_capacity_after);
  divide_by_weights(h.node_heat);

  const auto [rate_between, rate_after] = summed_across_ranks(h.node_rate);
  bins.scatter([&](std::size_t p) {  // 2. and 3.
    const auto& st = stencils[p];
    Vec<D> grad{};
    for_each_node(st, geo, [&](std::size_t i, double, const Vec<D>& dN) {
      for (int d = 0; d < D; ++d) grad[d] += h.node_heat[i] * dN[d];
    });
    const double kV = h.conductivity[body(p)] * pts.volume(p);
    for_each_node(st, geo, [&](std::size_t i, double, const Vec<D>& dN) { h.node_rate[i] -= kV * dot(grad, dN); });
  }, rate_between, rate_after);
  fold(h.node_rate);

  // 4a. d_p = T_p - sum_i N_ip T_i, in place of T_p.
  std::vector<double>& d = pts.work;
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    double T_grid = 0.0;
    for_each_node(stencils[p], geo,
                  [&](std::size_t i, double N, const Vec<D>&) { T_grid += N * h.node_heat[i]; });
    d[p] = T[p] - T_grid;
  }
  // 4b. The part of d the grid resolves (projection and interpolation smooth a smooth T by
  // O(h^2 grad^2 T), which is not sub-cell structure): d_i = sum_p N_ip w_p d_p / sum_p N_ip w_p,
  // w_p = C_p r_p (one material: m_p).
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) {
    h.node_heat[i] = 0.0;
    if (weighted) h.node_capacity[i] = 0.0;
  }
  halo.zero(h.node_heat);
  if (weighted) halo.zero(h.node_capacity);
  bins.scatter([&](std::size_t p) {
    if (!weighted) {
      const double md = pts.m[p] * d[p];
      for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) { h.node_heat[i] += N * md; });
      return;
    }
    const double w = pts.m[p] * h.specific_heat[body(p)] * relax[body(p)], wd = w * d[p];
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
      h.node_heat[i] += N * wd;
      h.node_capacity[i] += N * w;
    });
  }, heat_and_capacity_between, heat_and_capacity_after);
  divide_by_weights(h.node_heat);
  // 4c. The grid's heat, and the decay of the sub-cell part d_p - sum_i N_ip d_i.
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    double heat = 0.0, d_grid = 0.0;
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
      // N > 0: this point gave node i its mass. The heat goes in mass shares with two materials too:
      // shares N C_p / C_i were tried and erred more (copper on aluminium: 0.545 / 0.285 / 0.145 K at
      // 10 / 5 / 2.5 um against 0.477 / 0.206 / 0.107 K).
      if (N > 0.0) heat += N * h.node_rate[i] / g.m[i];
      d_grid += N * h.node_heat[i];
    });
    const std::size_t b = body(p);
    pts.E[p] += dt * heat - h.specific_heat[b] * (d[p] - d_grid) * relax[b];
  }
}

// Heat conduction as a step effect: after P2G and the symmetry plane's fold, with the temperatures of
// the step's start.
template <int D, class Shape>
class HeatConductionEffect final : public StepEffect<D> {
 public:
  HeatConductionEffect(const BodyTemperatures& thermal, HeatConduction constants)
      : thermal_(thermal), heat_(std::move(constants)) {}
  const char* name() const override { return "heat conduction"; }
  unsigned slots() const override { return slot_bit(StepSlot::after_to_grid); }
  void after_to_grid(StepContext<D>& c) override {
    conduct_heat<D, Shape>(c.points, c.reached, c.bins, c.grid, c.stencils, c.halo, thermal_, heat_, c.plane, c.dt);
  }

 private:
  const BodyTemperatures& thermal_;
  HeatConduction heat_;  // the constants and the nodal scratch
};

}  // namespace mpmshock
