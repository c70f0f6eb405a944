// Particle <-> grid transfers, templates on the shape function (see shape.hpp).
// P2G: m_i = sum N m_p, p_i = sum N m_p v_p, f_i = -sum V_p sigma_p grad N (the paper's f_int).
// G2P: FLIP velocity v_p += dt sum N a_i; position x_p += dt sum N v_i^{n+1};
// velocity gradient L_p = sum u_i (x) grad N_i, with u_i the re-mapped velocity (MUSL) or
// v_i^{n+1} (USL); and the work the step's nodal forces did on each point (see below).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "mpmshock/grid.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {

constexpr std::size_t kNoPoint = std::numeric_limits<std::size_t>::max();

// P2G of mass, momentum and internal force. Stress sigma = s - (P + q) I; without strength s = 0.
template <class Shape, bool Strength>
void particles_to_grid(const Particles& p, const StripBins& bins, Grid& g) {
  const GridGeometry& geo = g.geo;
  bins.scatter([&](std::size_t q) {
    const auto st = Shape::at(p.x[q], p.y[q], geo);
    const double m = p.mass[q], V = p.volume(q);
    const double mvx = m * p.vx[q], mvy = m * p.vy[q];
    const double pq = p.pressure[q] + p.viscosity[q];
    double sxx = -pq, syy = -pq, sxy = 0.0;
    if constexpr (Strength) {
      sxx += p.sxx[q];
      syy += p.syy[q];
      sxy = p.sxy[q];
    }
    for_each_node(st, geo, [&](std::size_t i, double N, double dNx, double dNy) {
      g.m[i] += N * m;
      g.px[i] += N * mvx;
      g.py[i] += N * mvy;
      g.fx[i] -= V * (sxx * dNx + sxy * dNy);
      g.fy[i] -= V * (sxy * dNx + syy * dNy);
    });
  });
}

// Explicit momentum update on the nodes of rows [row_begin, row_end): a_i = f_i / m_i (kept in f),
// v_i^{n+1} = (p_i + dt f_i) / m_i. Periodic in x by construction, free in y: no constraints.
// p_i is consumed, leaving zeros for the MUSL re-map.
void update_grid_momentum(Grid& g, int row_begin, int row_end, double dt);

// MUSL: the nodal velocity re-mapped from the updated point velocities, v~_i = p_i / m_i, in (px, py).
void remap_grid_velocity(Grid& g, int row_begin, int row_end);

// G2P of the FLIP velocity increment. With Remap (MUSL), also scatters m_p v_p^{n+1} back to the
// nodes at the same stencil.
template <class Shape, bool Remap>
void grid_to_particles_velocity(Particles& p, const StripBins& bins, Grid& g, double dt) {
  const GridGeometry& geo = g.geo;
  auto kernel = [&](std::size_t q) {
    const auto st = Shape::at(p.x[q], p.y[q], geo);
    double ax = 0.0, ay = 0.0;
    for_each_node(st, geo, [&](std::size_t i, double N, double, double) {
      ax += N * g.fx[i];
      ay += N * g.fy[i];
    });
    const double vx = p.vx[q] + dt * ax, vy = p.vy[q] + dt * ay;
    p.vx[q] = vx;
    p.vy[q] = vy;
    if constexpr (Remap) {
      const double mvx = p.mass[q] * vx, mvy = p.mass[q] * vy;
      for_each_node(st, geo, [&](std::size_t i, double N, double, double) {
        g.px[i] += N * mvx;
        g.py[i] += N * mvy;
      });
    }
  };
  if constexpr (Remap) {
    bins.scatter(kernel);
  } else {
#pragma omp parallel for schedule(dynamic, kChunk)
    for (std::size_t q = 0; q < p.size(); ++q) kernel(q);
  }
}

// The velocity gradient, the work of the step's forces, and the position update, per point.
//
// L_p = sum_i u_i (x) grad N_i from the nodal velocity u (ux, uy): the re-mapped v~^{n+1} in MUSL,
// v^{n+1} in USL. It drives the kinematics (F, the stress rate) as in standard MUSL, a symplectic
// step that is stable up to cfl 1.
//
// work_p = dt (V_p / m_p) sigma_p : (L_p[v^n] + L_p[v~^{n+1}]) / 2 [J/kg], with v^n = v^{n+1} - dt a
// the nodal velocity the step started from. For FLIP points the kinetic energy changes in a step
// by exactly dt sum_i f_i . (v_i^n + v~_i^{n+1}) / 2 = -sum_p m_p work_p, so adding work_p to the
// internal energy conserves kinetic + internal energy to round-off (in MUSL; USL has no v~ and
// uses v^{n+1}, which is close but not exact). Using this averaged gradient for the kinematics
// too would be exact but unstable at any time step (its amplification factor is
// sqrt(1 + (omega dt)^2 / 2)); hence the two gradients.
//
// Positions move with v^{n+1}; x wraps into [0, width). Returns the lowest index of a point that
// left the grid, or kNoPoint.
template <class Shape, bool Strength>
std::size_t velocity_gradient_work_and_move(Particles& p, const Grid& g, const std::vector<double>& ux,
                                            const std::vector<double>& uy, double dt) {
  const GridGeometry& geo = g.geo;
  const double width = geo.width();
  const int last_row = geo.ny - Shape::support;
  std::size_t first_out = kNoPoint;
#pragma omp parallel for schedule(dynamic, kChunk) reduction(min : first_out)
  for (std::size_t q = 0; q < p.size(); ++q) {
    const auto st = Shape::at(p.x[q], p.y[q], geo);
    double Lxx = 0.0, Lxy = 0.0, Lyx = 0.0, Lyy = 0.0;  // L[u]
    double Axx = 0.0, Axy = 0.0, Ayx = 0.0, Ayy = 0.0;  // L[v^n + u], twice the averaged gradient
    double vx = 0.0, vy = 0.0;
    for_each_node(st, geo, [&](std::size_t i, double N, double dNx, double dNy) {
      Lxx += ux[i] * dNx;
      Lxy += ux[i] * dNy;
      Lyx += uy[i] * dNx;
      Lyy += uy[i] * dNy;
      const double sx = g.vx[i] - dt * g.fx[i] + ux[i], sy = g.vy[i] - dt * g.fy[i] + uy[i];
      Axx += sx * dNx;
      Axy += sx * dNy;
      Ayx += sy * dNx;
      Ayy += sy * dNy;
      vx += N * g.vx[i];
      vy += N * g.vy[i];
    });
    p.Lxx[q] = Lxx;
    p.Lxy[q] = Lxy;
    p.Lyx[q] = Lyx;
    p.Lyy[q] = Lyy;
    // sigma : L_avg with sigma = s - (P + q) I; the spin does no work.
    double power = -(p.pressure[q] + p.viscosity[q]) * (Axx + Ayy);
    if constexpr (Strength) power += p.sxx[q] * Axx + p.syy[q] * Ayy + p.sxy[q] * (Axy + Ayx);
    p.work[q] = 0.5 * dt * p.volume(q) / p.mass[q] * power;

    double x = p.x[q] + dt * vx;  // a point moves far less than a period per step
    x = x < 0.0 ? x + width : (x >= width ? x - width : x);
    p.x[q] = x < width ? x : 0.0;  // x + width can round up to width
    p.y[q] += dt * vy;
    const int row = Shape::first_row(p.y[q], geo);
    if (!(row >= 0 && row <= last_row)) first_out = q < first_out ? q : first_out;
  }
  return first_out;
}

}  // namespace mpmshock
