// Volumetric smoothing (volumetric_smoothing = on): the points of a cell compress together, and the
// grid feels their mean pressure. A B-bar method on the MPM grid, in two halves that are each
// other's adjoint, so that energy stays conserved to round-off:
//
//   before P2G   the pressure the nodal forces see is the grid's field of it,
//                (P + q)-bar_p = rho_p sum_i N_ip Pi_i / m_i,   Pi_i = sum_q N_iq V_q (P + q)_q
//   after G2P    each point's rate of volume change is the grid's mass-weighted field of it,
//                tr L-bar_p = sum_i N_ip d_i,   d_i = sum_q N_iq m_q tr L_q / m_i
//                (the point update moves F by it: constitutive.hpp),
//                and so is the trace of the averaged gradient A that its work is computed from
//                (transfer.hpp): work_p += (dt/2)(V_p/m_p)(-(P + q)_p)(tr A-bar_p - tr A_p).
//
// Why: the nodal velocities a cell's points share cannot express a volume change of one point
// against its neighbours, so a point that was over-compressed within a cell (the tip of a jet
// meeting the far wall of a collapsing void, a point rung by a shock) kept its excess compression
// and pressure: at a void's focus single points reached J = 0.44 and 540 GPa among neighbours at
// 20 GPa and held 20-40 MJ/kg. With the smoothed rate they compress with their neighbours.
//
// Energy: the pressure forces' power is sum_p V_p (P + q)-bar_p tr A_p, and with the two
// projections above it equals sum_p V_p (P + q)_p tr A-bar_p exactly (both are
// sum_i Pi_i (m tr A)_i / m_i), the work the points' own pressures do on their own smoothed volume
// change. So the kinetic energy the forces take is the internal energy the points get, point by
// point consistent with how each one deforms, as without smoothing. The projections keep the total
// volume rate (the weights N_ip m_p / m_i of a node sum to one), so a uniform state and a steady
// shock's jump conditions are untouched. The deviatoric strain rate stays the point's own: L_p is
// kept, and the point update adds (tr L-bar - tr L) / D I to it for F alone (in plane strain a
// shifted in-plane trace would put a spurious deviator into the zz direction).
//
// The passes use the step's stencils and bins, fold their nodal sums across a symmetry plane (the
// fields are even in y) and sum them across the rows MPI ranks share first, as heat conduction
// does: the same bits on any number of threads and ranks.
#pragma once

#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/step_effect.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/symmetry_plane.hpp"

namespace mpmshock {

// The scratch of the two passes.
struct VolumetricSmoothing {
  std::vector<double> node_mass;  // m_i
  std::vector<double> node_a;     // Pi_i, then the nodal tr L
  std::vector<double> node_b;     // the nodal tr A
  std::vector<double> trace_A;    // tr A_p
  std::vector<double> volume_rate;  // tr L-bar_p, for the point update
};

namespace detail {

// Zeroes the nodal fields of the active rows (and the rows shared with MPI neighbours).
template <int D, class... Fields>
void zero_active(const GridGeometry<D>& geo, RowRange rows, const Halo<D>& halo, Fields&... fields) {
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  (fields.resize(geo.nodes()), ...);
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) ((fields[i] = 0.0), ...);
  halo.zero(fields...);
}

}  // namespace detail

// Before P2G: the smoothed (P + q)-bar of every binned point in pts.work (the step's scratch), which
// P2G then uses for the pressure part of the stress.
template <int D, class Shape>
void smooth_pressure(Particles<D>& pts, PointRange range, const StripBins& bins, const GridGeometry<D>& geo,
                     const StencilStore<D>& store, const Halo<D>& halo, const SymmetryPlane<D>* plane,
                     const Grid<D>& g, VolumetricSmoothing& vs) {
  const auto& stencils = store.template of<Shape::support>();
  const RowRange rows = bins.rows();
  detail::zero_active(geo, rows, halo, vs.node_mass, vs.node_a);
  bins.scatter([&](std::size_t p) {
    const auto& st = stencils[p];
    const double m = pts.m[p], Vpq = pts.volume(p) * (pts.P[p] + pts.q[p]);
    for_each_node(st, geo, [&](std::size_t i, double N, const Vec<D>&) {
      vs.node_mass[i] += N * m;
      vs.node_a[i] += N * Vpq;
    });
  }, [&] { halo.between_colours(vs.node_mass, vs.node_a); }, [&] { halo.after_colours(vs.node_mass, vs.node_a); });
  if (plane) {
    plane->fold_scalar(g, vs.node_mass, rows);
    plane->fold_scalar(g, vs.node_a, rows);
  }
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) vs.node_a[i] = vs.node_mass[i] > 0.0 ? vs.node_a[i] / vs.node_mass[i] : 0.0;
  pts.work.resize(pts.size());
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    double per_mass = 0.0;  // sum_i N_ip Pi_i / m_i
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) { per_mass += N * vs.node_a[i]; });
    pts.work[p] = per_mass * pts.m[p] / pts.volume(p);
  }
}

// After the velocity gradient and work: tr L-bar_p in vs.volume_rate and the work corrected to the
// smoothed tr A, with A = L[v^n + u] from the grid's v_sum, written for the step before the move
// (sum_step_velocities, transfer.hpp).
template <int D, class Shape>
void smooth_volume_rate(Particles<D>& pts, PointRange range, const StripBins& bins, const Grid<D>& g,
                        const StencilStore<D>& store, const Halo<D>& halo, const SymmetryPlane<D>* plane,
                        double dt, VolumetricSmoothing& vs) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();
  const RowRange rows = bins.rows();
  detail::zero_active(geo, rows, halo, vs.node_a, vs.node_b);
  vs.trace_A.resize(pts.size());
  vs.volume_rate.resize(pts.size());
  bins.scatter([&](std::size_t p) {
    const auto& st = stencils[p];
    double trA = 0.0;  // tr L[v^n + u], as velocity_gradient_work_and_move sums it
    for_each_node(st, geo, [&](std::size_t i, double, const Vec<D>& dN) {
      for (int d = 0; d < D; ++d) trA += g.v_sum[i][d] * dN[d];
    });
    vs.trace_A[p] = trA;
    const double m = pts.m[p], m_trL = m * trace(pts.L[p]), m_trA = m * trA;
    for_each_node(st, geo, [&](std::size_t i, double N, const Vec<D>&) {
      vs.node_a[i] += N * m_trL;
      vs.node_b[i] += N * m_trA;
    });
  }, [&] { halo.between_colours(vs.node_a, vs.node_b); }, [&] { halo.after_colours(vs.node_a, vs.node_b); });
  if (plane) {
    plane->fold_scalar(g, vs.node_a, rows);
    plane->fold_scalar(g, vs.node_b, rows);
  }
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) {
    const double inv_m = vs.node_mass[i] > 0.0 ? 1.0 / vs.node_mass[i] : 0.0;
    vs.node_a[i] *= inv_m;
    vs.node_b[i] *= inv_m;
  }
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    double trL = 0.0, trA = 0.0;
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) {
      trL += N * vs.node_a[i];
      trA += N * vs.node_b[i];
    });
    vs.volume_rate[p] = trL;
    pts.work[p] -= 0.5 * dt * pts.volume(p) / pts.m[p] * (pts.P[p] + pts.q[p]) * (trA - vs.trace_A[p]);
  }
}

// The two passes as a step effect: the pressure before P2G, the volume rate after the move (which the
// point update then reads from the context).
template <int D, class Shape>
class VolumetricSmoothingEffect final : public StepEffect<D> {
 public:
  const char* name() const override { return "volumetric smoothing"; }
  unsigned slots() const override { return slot_bit(StepSlot::before_to_grid) | slot_bit(StepSlot::after_move); }
  void before_to_grid(StepContext<D>& c) override {
    smooth_pressure<D, Shape>(c.points, c.reached, c.bins, c.grid.geo, c.stencils, c.halo, c.plane, c.grid, scratch_);
  }
  void after_move(StepContext<D>& c) override {
    smooth_volume_rate<D, Shape>(c.points, c.reached, c.bins, c.grid, c.stencils, c.halo, c.plane, c.dt, scratch_);
    c.volume_rate = scratch_.volume_rate.data();
  }

 private:
  VolumetricSmoothing scratch_;
};

}  // namespace mpmshock
