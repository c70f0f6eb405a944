// Heat conduction (heat_conduction = on): Fourier's law, q = -k grad T, through the grid.
//
//   1. nodal temperature   T_i = sum_p N_ip m_p T_p / m_i             (scatter, then divide)
//   2. point gradient      g_p = sum_i T_i grad N_ip
//   3. nodal heat rate     Q_i = -sum_p V_p k g_p . grad N_ip         (scatter) [W per m of depth]
//   4. point energy        E_p += dt sum_i N_ip Q_i / m_i             (gather)  [J/kg]
//                               + c_v (T~_p - T_p)(1 - exp(-dt / tau)),  T~_p = sum_i N_ip T_i
//
// Steps 1-4 without the last term are the Galerkin heat equation on the grid, its increments
// carried to the points as FLIP carries velocity increments: they never see how the points' own
// temperatures vary within a cell (a point hotter than its neighbours stays hotter for ever; at a
// hot/cold interface the rows next to it kept 30 K of their initial offset whatever the cell size).
// The last term is the sub-cell conduction the grid cannot resolve: each point's deviation from
// the grid's temperature field decays at the rate of the slowest sub-cell mode, wavelength 2h,
// tau = h^2 / (pi^2 alpha). Energy is conserved exactly: sum_i Q_i = 0 because sum_i grad N_ip = 0
// (partition of unity), step 4 hands each node's Q_i out in the shares N_ip m_p / m_i that sum to
// one, and the deviations sum to zero, sum_p m_p (T~_p - T_p) = sum_i m_i T_i - sum_p m_p T_p = 0. It runs on
// the grid and strips of the step's P2G (before the points move), with the temperatures of the
// step's start. Explicit diffusion is stable for dt <= h^2 / (2 D alpha) (alpha = k / (rho c_v));
// the time step keeps 0.2 h^2 / alpha, which for aluminium (alpha = 1e-4 m2/s) binds only below
// 0.1 um cells: at the paper's cells the mechanical step is 10^3-10^4 times shorter.
//
// With a symmetry plane (symmetry = on) each of the three nodal sums is folded across it
// (SymmetryPlane::fold_scalar) before it is read: the temperature field and heat rates are even in y,
// so the mirror flyer's share at a node is the target's own share at the mirror node, and the plane
// is adiabatic (no heat crosses it), as in the whole impact by symmetry. On MPI ranks each sum is
// also completed across the rows two ranks share (halo.hpp) before it is folded or read.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/symmetry_plane.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

// The nodal scratch fields of the conduction and its constants.
struct HeatConduction {
  double conductivity = 0.0;  // k [W/(m K)]
  double specific_heat = 0.0;  // c_v [J/(kg K)]
  double relaxation_time = 0.0;  // tau = h^2 / (pi^2 alpha) of the sub-cell deviations [s]
  std::vector<double> node_heat;  // m_i T_i, then T_i
  std::vector<double> node_rate;  // Q_i
};

// `plane`: the symmetry plane (symmetry = on), or null.
template <int D, class Shape>
void conduct_heat(Particles<D>& pts, PointRange range, const StripBins& bins, const Grid<D>& g,
                  const StencilStore<D>& store, const Halo<D>& halo, const BodyTemperatures& thermal,
                  HeatConduction& h, const SymmetryPlane<D>* plane, double dt) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();  // P2G's, of the same x and F
  const RowRange rows = bins.rows();
  auto fold = [&](std::vector<double>& field) {
    if (plane) plane->fold_scalar(g, field, rows);
  };
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  h.node_heat.resize(geo.nodes());
  h.node_rate.resize(geo.nodes());
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) h.node_heat[i] = h.node_rate[i] = 0.0;

  // The step's scratch (work is written later in the step) holds T_p, then d_p.
  std::vector<double>& T = pts.work;
  // Each nodal sum is summed across the rows MPI ranks share (halo.hpp) before it is read.
  auto summed_across_ranks = [&](std::vector<double>& field) {
    return std::make_pair([&] { halo.between_colours(field); }, [&] { halo.after_colours(field); });
  };
  halo.zero(h.node_heat, h.node_rate);
  const auto [heat_between, heat_after] = summed_across_ranks(h.node_heat);
  bins.scatter([&](std::size_t p) {  // 1. m_i T_i
    T[p] = thermal.of_point(pts, p);
    const double mT = pts.m[p] * T[p];
    for_each_node(stencils[p], geo,
                  [&](std::size_t i, double N, const Vec<D>&) { h.node_heat[i] += N * mT; });
  }, heat_between, heat_after);
  fold(h.node_heat);
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) h.node_heat[i] = g.m[i] > 0.0 ? h.node_heat[i] / g.m[i] : 0.0;

  const auto [rate_between, rate_after] = summed_across_ranks(h.node_rate);
  bins.scatter([&](std::size_t p) {  // 2. and 3.
    const auto& st = stencils[p];
    Vec<D> grad{};
    for_each_node(st, geo, [&](std::size_t i, double, const Vec<D>& dN) {
      for (int d = 0; d < D; ++d) grad[d] += h.node_heat[i] * dN[d];
    });
    const double kV = h.conductivity * pts.volume(p);
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
  // O(h^2 grad^2 T), which is not sub-cell structure): d_i = sum_p N_ip m_p d_p / m_i.
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) h.node_heat[i] = 0.0;
  halo.zero(h.node_heat);
  bins.scatter([&](std::size_t p) {
    const double md = pts.m[p] * d[p];
    for_each_node(stencils[p], geo,
                  [&](std::size_t i, double N, const Vec<D>&) { h.node_heat[i] += N * md; });
  }, heat_between, heat_after);
  fold(h.node_heat);
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) h.node_heat[i] = g.m[i] > 0.0 ? h.node_heat[i] / g.m[i] : 0.0;
  // 4c. The grid's heat, and the decay of the sub-cell part d_p - sum_i N_ip d_i.
  const double relax = 1.0 - std::exp(-dt / h.relaxation_time);
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    double heat = 0.0, d_grid = 0.0;
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
      if (N > 0.0) heat += N * h.node_rate[i] / g.m[i];  // N > 0: this point gave node i its mass
      d_grid += N * h.node_heat[i];
    });
    pts.E[p] += dt * heat - h.specific_heat * (d[p] - d_grid) * relax;
  }
}

}  // namespace mpmshock
