// Particle <-> grid transfers, templates on the dimension and the shape function (shape.hpp).
// P2G: m_i = sum N m_p, p_i = sum N m_p v_p, f_i = -sum V_p sigma_p grad N (the paper's f_int).
// G2P: FLIP velocity v_p += dt sum N a_i; position x_p += dt sum N v_i^{n+1};
// velocity gradient L_p = sum u_i (x) grad N_i, with u_i the re-mapped velocity (MUSL) or
// v_i^{n+1} (USL); and the work the step's nodal forces did on each point (see below).
#pragma once

#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/heat_flux_rider.hpp"
#include "mpmshock/node_rows.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {

constexpr std::size_t kNoPoint = std::numeric_limits<std::size_t>::max();

// The Cauchy stress of a point, sigma = s - (P + q) I; without strength s = 0. Smoothed: the
// grid's (P + q)-bar in pts.work instead of the point's own (volumetric_smoothing.hpp).
template <int D, bool Strength, bool Smoothed = false>
inline Mat<D> cauchy_stress(const Particles<D>& pts, std::size_t p) {
  const double pq = Smoothed ? pts.work[p] : pts.P[p] + pts.q[p];
  Mat<D> sigma{};
  for (int d = 0; d < D; ++d) sigma(d, d) = -pq;
  if constexpr (Strength) {
    const Deviator<D>& s = pts.s[p];
    sigma(0, 0) += s.xx;
    sigma(1, 1) += s.yy;
    sigma(0, 1) = sigma(1, 0) = s.xy;
    if constexpr (D == 3) {
      sigma(2, 2) += s.zz();
      sigma(1, 2) = sigma(2, 1) = s.yz();
      sigma(0, 2) = sigma(2, 0) = s.zx();
    }
  }
  return sigma;
}

// The stencil of every point of `range` for the step (its nodes, 1D weights and derivatives: the
// N_ip and grad N_ip every pass of the step reads, shape.hpp), four points at a time (Shape::at_four).
// The last group repeats the range's last point in its spare lanes, which are not kept.
template <int D, class Shape>
void compute_stencils(const Particles<D>& pts, PointRange range, const GridGeometry<D>& geo, StencilStore<D>& store) {
  using St = Stencil<Shape::support, D>;
  auto& stencils = store.template of<Shape::support>();
  stencils.resize(pts.size());
  if (range.end <= range.begin) return;
  const std::size_t groups = (range.end - range.begin + 3) / 4;
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < groups; ++k) {
    St spare;
    const Vec<D>* x[4];
    const Mat<D>* F[4];
    St* out[4];
    for (int l = 0; l < 4; ++l) {
      const std::size_t p = range.begin + 4 * k + static_cast<std::size_t>(l), q = p < range.end ? p : range.end - 1;
      x[l] = &pts.x[q];
      F[l] = &pts.F[q];
      out[l] = p < range.end ? &stencils[p] : &spare;
    }
    Shape::at_four(x, F, geo, out);
  }
}

// P2G of mass, momentum and internal force, on the stencils of the step (compute_stencils), and
// with Flux the artificial heat flux's nodal sums, which ride on this sweep (heat_flux_rider.hpp;
// `flux` is null without). On MPI ranks the rows shared with a neighbour are summed across the two
// (halo.hpp).
template <int D, class Shape, bool Strength, bool Smoothed = false, FluxSums Flux = FluxSums::none>
void particles_to_grid(const Particles<D>& pts, const StripBins& bins, Grid<D>& g, const StencilStore<D>& store,
                       const Halo<D>& halo, [[maybe_unused]] const HeatFluxRider* flux) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();
  constexpr bool rides = Flux != FluxSums::none, three = Flux == FluxSums::three;
  assert(rides == (flux != nullptr));
  assert(!three || (flux->capacity && flux->node_capacity));
  halo.zero(g.m, g.mv, g.f);  // (the flux zeroes its own sums: they start before this sweep)
  // The nodal sums the rows shared with another rank add across the two: the flux's too.
  auto shared_rows = [&](auto sum) __attribute__((always_inline)) {
    if constexpr (three) sum(g.m, g.mv, g.f, *flux->node_rate, *flux->node_temperature, *flux->node_capacity);
    else if constexpr (rides) sum(g.m, g.mv, g.f, *flux->node_rate, *flux->node_temperature);
    else sum(g.m, g.mv, g.f);
  };
  bins.scatter([&](std::size_t p) __attribute__((always_inline)) {  // inlined: pointers loaded once
    const auto& st = stencils[p];
    const double m = pts.m[p], V = pts.volume(p);
    Vec<D> mv;
    for (int d = 0; d < D; ++d) mv[d] = m * pts.v[p][d];
    const Mat<D> sigma = cauchy_stress<D, Strength, Smoothed>(pts, p);
    if constexpr (Shape::support == 4) {
      // A row's four nodes at once (node_rows.hpp): the point's values weighed by the columns once,
      // then added to each row with its factors. f_i = -V sigma grad N_i, so the force's x-derivative
      // part goes with the columns' derivatives and the row weight, the others with the columns'
      // weights and the row's derivatives.
      const Columns<D> c = columns_of(st);
      const Lanes mass_columns = c.weight * m;
      RowLanes<D> mv_lanes, momentum_columns, force_columns[D];
      component_lanes<D>(mv_lanes, mv.c);
      for (int k = 0; k < D; ++k) momentum_columns.v[k] = c.w.v[k] * mv_lanes.v[k];
      for (int j = 0; j < D; ++j) {
        double column[D];
        for (int d = 0; d < D; ++d) column[d] = -V * sigma(d, j);
        RowLanes<D> sigma_lanes;
        component_lanes<D>(sigma_lanes, column);
        for (int k = 0; k < D; ++k) force_columns[j].v[k] = (j == 0 ? c.g.v[k] : c.w.v[k]) * sigma_lanes.v[k];
      }
      [[maybe_unused]] FluxColumns<Flux> flux_columns;
      if constexpr (rides) flux_columns = FluxColumns<Flux>(*flux, p, c.weight);
      for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& r, const auto& nodes) __attribute__((always_inline)) {
        Lanes mass;
        nodes.load(mass, &g.m[row]);
        mass += r.weight * mass_columns;
        nodes.store(&g.m[row], mass);
        RowLanes<D> momentum, force;
        nodes.load(momentum, &g.mv[row]);
        nodes.load(force, &g.f[row]);
        for (int k = 0; k < D; ++k) {
          momentum.v[k] += r.weight * momentum_columns.v[k];
          Lanes t = r.weight * force_columns[0].v[k];
          for (int j = 1; j < D; ++j) t += r.gradient[j] * force_columns[j].v[k];
          force.v[k] += t;
        }
        nodes.store(&g.mv[row], momentum);
        nodes.store(&g.f[row], force);
        if constexpr (rides) flux_columns.add_to_row(*flux, row, r.weight, nodes);
      });
    } else {
      for_each_node(st, geo, [&](std::size_t i, double N, const Vec<D>& dN) {
        g.m[i] += N * m;
        for (int d = 0; d < D; ++d) g.mv[i][d] += N * mv[d];
        for (int d = 0; d < D; ++d) {
          double t = sigma(d, 0) * dN[0];
          for (int j = 1; j < D; ++j) t += sigma(d, j) * dN[j];
          g.f[i][d] -= V * t;
        }
        if constexpr (rides) {
          (*flux->node_rate)[i] += N * flux->rate[p];
          (*flux->node_temperature)[i] += N * flux->heat[p];
          if constexpr (three) (*flux->node_capacity)[i] += N * flux->capacity[p];
        }
      });
    }
  }, [&] { shared_rows([&](auto&... f) { halo.between_colours(f...); }); },
     [&] { shared_rows([&](auto&... f) { halo.after_colours(f...); }); });
}

// Explicit momentum update on the nodes of the given rows: a_i = f_i / m_i,
// v_i^{n+1} = (p_i + dt f_i) / m_i. Periodic in x (and z) by construction, free in y: no
// constraints. p_i is zeroed for the MUSL re-map.
template <int D>
void update_grid_momentum(Grid<D>& g, RowRange rows, double dt);

// MUSL: the nodal velocity re-mapped from the updated point velocities, v~_i = sum N m_p v_p / m_i.
template <int D>
void remap_grid_velocity(Grid<D>& g, RowRange rows);

// v_sum_i = v^n_i + u_i with v^n = v^{n+1} - dt a_i (grid.hpp), on the nodes of the given rows: once
// a node, not in every stencil row that reads it (a node lies in 64 points' stencils in 2D and 512
// in 3D, at 2 points per cell and axis).
template <int D>
void sum_step_velocities(Grid<D>& g, RowRange rows, const std::vector<Vec<D>>& u, double dt);

// G2P of the point velocity. FLIP: v_p += dt sum N a_i. With Blend, v_p = f v_FLIP + (1 - f) v_PIC,
// v_PIC = sum N v_i^{n+1}: the PIC part damps point-to-point velocity noise. The kinetic energy it
// removes becomes heat at the point (below), so total energy stays conserved to about 1e-4, not
// to round-off (the MUSL re-map then carries the blended velocities, which the exact-work identity
// of velocity_gradient_work_and_move assumes are FLIP's). With Remap (MUSL), also scatters
// m_p v_p^{n+1} back to the nodes at the same stencil.
//
// Every point's v_PIC, blended or not, goes to v_pic[p], the velocity that moves it
// (velocity_gradient_work_and_move): gathered here beside a_i, a field more in the same sweep, and
// not in the gradient pass, where its three sums in 3D pushed the gradients' out of AVX2's 16
// registers onto the stack (x86-64-v3, per point-step: 3D narrow column 4,164 -> 3,973; 2D
// 1,136 -> 1,138; the same bits).
template <int D, class Shape, bool Remap, bool Blend>
void grid_to_particles_velocity(Particles<D>& pts, PointRange range, const StripBins& bins, Grid<D>& g,
                                const StencilStore<D>& store, [[maybe_unused]] const Halo<D>& halo, double dt,
                                [[maybe_unused]] double flip_fraction, std::vector<Vec<D>>& v_pic) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();
  if (v_pic.size() < pts.size()) v_pic.resize(pts.size());
  auto kernel = [&](std::size_t p) __attribute__((always_inline)) {
    const auto& st = stencils[p];
    Vec<D> acc{}, pic{};
    if constexpr (Shape::support == 4) {  // a row's four nodes at once (node_rows.hpp)
      RowSums<D, false> acc_sums, pic_sums;
      for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& r, const auto& nodes) __attribute__((always_inline)) {
        RowLanes<D> an, vn;
        nodes.load(an, &g.a[row]);
        nodes.load(vn, &g.v[row]);
        acc_sums.add(r, an);
        pic_sums.add(r, vn);
      });
      const Columns<D> c = columns_of(st);
      acc = acc_sums.value(c);
      pic = pic_sums.value(c);
    } else {
      for_each_node(st, geo, [&](std::size_t i, double N, const Vec<D>&) {
        for (int d = 0; d < D; ++d) acc[d] += N * g.a[i][d];
        for (int d = 0; d < D; ++d) pic[d] += N * g.v[i][d];
      });
    }
    v_pic[p] = pic;
    Vec<D>& v = pts.v[p];
    for (int d = 0; d < D; ++d) v[d] = v[d] + dt * acc[d];
    if constexpr (Blend) {
      double k_flip = 0.0, k_blend = 0.0;
      for (int d = 0; d < D; ++d) {
        k_flip += v[d] * v[d];
        v[d] = flip_fraction * v[d] + (1.0 - flip_fraction) * pic[d];
        k_blend += v[d] * v[d];
      }
      // The kinetic energy the blend took from the point becomes its heat. Where the blend speeds a
      // point up (a jet's tip among slower neighbours) nothing is taken from its heat: that cooled
      // jetting points below 0 K. The total energy then grows by what those points gained.
      pts.E[p] += 0.5 * std::max(k_flip - k_blend, 0.0);
    }
    if constexpr (Remap) {
      Vec<D> mv;
      for (int d = 0; d < D; ++d) mv[d] = pts.m[p] * v[d];
      if constexpr (Shape::support == 4) {  // as P2G's momentum
        const Columns<D> c = columns_of(st);
        RowLanes<D> mv_lanes, momentum_columns;
        component_lanes<D>(mv_lanes, mv.c);
        for (int k = 0; k < D; ++k) momentum_columns.v[k] = c.w.v[k] * mv_lanes.v[k];
        for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& r, const auto& nodes) __attribute__((always_inline)) {
          RowLanes<D> momentum;
          nodes.load(momentum, &g.mv[row]);
          for (int k = 0; k < D; ++k) momentum.v[k] += r.weight * momentum_columns.v[k];
          nodes.store(&g.mv[row], momentum);
        });
      } else {
        for_each_node(st, geo, [&](std::size_t i, double N, const Vec<D>&) {
          for (int d = 0; d < D; ++d) g.mv[i][d] += N * mv[d];
        });
      }
    }
  };
  if constexpr (Remap) {
    halo.zero(g.mv);
    bins.scatter(kernel, [&] { halo.between_colours(g.mv); }, [&] { halo.after_colours(g.mv); });
  } else {
#pragma omp parallel for schedule(dynamic, kChunk)
    for (std::size_t p = range.begin; p < range.end; ++p) kernel(p);
  }
}

// The velocity gradient, the work of the step's forces, and the position update, per point.
//
// L_p = sum_i u_i (x) grad N_i from the nodal velocity u: the re-mapped v~^{n+1} in MUSL, v^{n+1}
// in USL. It drives the kinematics (F, the stress rate) as in standard MUSL, a symplectic step
// that is stable up to cfl 1.
//
// work_p = dt (V_p / m_p) sigma_p : (L_p[v^n] + L_p[v~^{n+1}]) / 2 [J/kg], with v^n = v^{n+1} - dt a
// the nodal velocity the step started from. For FLIP points the kinetic energy changes in a step
// by exactly dt sum_i f_i . (v_i^n + v~_i^{n+1}) / 2 = -sum_p m_p work_p, so adding work_p to the
// internal energy conserves kinetic + internal energy to round-off (in MUSL; USL has no v~ and
// uses v^{n+1}, which is close but not exact). Using this averaged gradient for the kinematics
// too would be exact but unstable at any time step (its amplification factor is
// sqrt(1 + (omega dt)^2 / 2)); hence the two gradients.
//
// Positions move with v^{n+1}, as G2P interpolated it (v_pic); periodic coordinates wrap into
// [0, period). Returns the lowest index of a point that left the grid, or kNoPoint. Only the points
// of `range`.
//
// Reads v^n + u from the grid's v_sum, which sum_step_velocities must have written from the same
// u and dt on the rows of the step's points (step() calls it just before), and v_pic, which G2P
// must have written for the points of `range` in the same step.
template <int D, class Shape, bool Strength>
std::size_t velocity_gradient_work_and_move(Particles<D>& pts, PointRange range, const Grid<D>& g,
                                            const StencilStore<D>& store, const std::vector<Vec<D>>& u,
                                            const std::vector<Vec<D>>& v_pic, double dt) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();
  // The lowest and highest y the points move to (and whether one is NaN): the rows a point's
  // stencil starts at grow with its y, so if the extremes' rows are on the grid, every point's is.
  double y_low = std::numeric_limits<double>::infinity(), y_high = -y_low;
  bool nan = false;
#pragma omp parallel for schedule(dynamic, kChunk) reduction(min : y_low) reduction(max : y_high) reduction(|| : nan)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    const auto& st = stencils[p];
    Mat<D> L{};  // L[u]
    Mat<D> A{};  // L[v^n + u], twice the averaged gradient
    if constexpr (Shape::support == 4) {  // a row's four nodes at once (node_rows.hpp)
      RowSums<D, true> u_sums, vn_u_sums;  // of u, and of v^n + u
      auto of_u = [&](std::size_t row, const RowFactors<D>& r, const auto& nodes) __attribute__((always_inline)) {
        RowLanes<D> un;
        nodes.load(un, &u[row]);
        u_sums.add(r, un);
      };
      auto vn_plus_u = [&](std::size_t row, const RowFactors<D>& r, const auto& nodes) __attribute__((always_inline)) {
        RowLanes<D> vn_u;
        nodes.load(vn_u, &g.v_sum[row]);
        vn_u_sums.add(r, vn_u);
      };
      if constexpr (D == 3) {  // two sweeps: 18 vector sums would not fit AVX2's 16 registers (when
        // the pass also summed v^{n+1}, 21 in one sweep against 12 and 9: x86-64-v3, 1,743 -> 1,674
        // per point-step; with AVX-512's 32 the wall time was the same)
        for_each_row(st, geo, of_u);
        for_each_row(st, geo, vn_plus_u);
      } else {
        for_each_row(st, geo, [&](std::size_t row, const RowFactors<D>& r, const auto& nodes) __attribute__((always_inline)) {
          of_u(row, r, nodes);
          vn_plus_u(row, r, nodes);
        });
      }
      const Columns<D> c = columns_of(st);
      L = u_sums.gradient_of(c);
      A = vn_u_sums.gradient_of(c);
    } else {
      for_each_node(st, geo, [&](std::size_t i, double, const Vec<D>& dN) {
        for (int d = 0; d < D; ++d) {
          const double ud = u[i][d], sd = g.v_sum[i][d];
          for (int j = 0; j < D; ++j) {
            L(d, j) += ud * dN[j];
            A(d, j) += sd * dN[j];
          }
        }
      });
    }
    const Vec<D>& vel = v_pic[p];
    pts.L[p] = L;
    // sigma : L_avg with sigma = s - (P + q) I; the spin does no work.
    double power = -(pts.P[p] + pts.q[p]) * trace(A);
    if constexpr (Strength) power += contract(pts.s[p], A);
    pts.work[p] = 0.5 * dt * pts.volume(p) / pts.m[p] * power;

    Vec<D>& x = pts.x[p];
    for (int d = 0; d < D; ++d) {
      if (d == 1) {
        x[1] += dt * vel[1];
        continue;
      }
      const double period = geo.period(d);
      double c = x[d] + dt * vel[d];  // a point moves far less than a period per step
      c = c < 0.0 ? c + period : (c >= period ? c - period : c);
      x[d] = c < period ? c : 0.0;  // c + period can round up to period
    }
    y_low = x[1] < y_low ? x[1] : y_low;
    y_high = x[1] > y_high ? x[1] : y_high;
    nan = nan || x[1] != x[1];
  }
  const int last_row = geo.ny - Shape::support;
  auto on_grid = [&](double y) {
    const int row = Shape::first_row(y, geo);
    return row >= 0 && row <= last_row;
  };
  if (range.end <= range.begin || (!nan && on_grid(y_low) && on_grid(y_high))) return kNoPoint;
  for (std::size_t p = range.begin; p < range.end; ++p)  // rare: the run stops
    if (!on_grid(pts.x[p][1])) return p;
  return kNoPoint;
}

}  // namespace mpmshock
