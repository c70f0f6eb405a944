// Spall's criterion over a point's neighbourhood (spall = on, spall_criterion = neighbourhood, the
// default): an intact point opens when the largest principal stress of the material around it,
// not its own, reaches the spall strength. The neighbourhood is the point's stencil:
//
//   1. nodal tension   sigma1_i = sum_p N_ip m_p sigma1_p / m_i     (sigma1_p = max principal of s - P I)
//   2. its mean        sigma1-bar_p = sum_i N_ip sigma1_i           (a mass-weighted mean over ~3 cells)
//   3. an intact point with sigma1-bar_p > strength that is itself in tension (P_p < 0) opens at its
//      present J, as spall.hpp describes.
//
// Why: a shocked and released solid holds a standing pattern of the points' stresses with a
// wavelength of two cells that the grid's forces barely see (behind a 400 m/s impact, rows of points
// 10 um apart at +1.4 and -1.5 GPa where the mean stress is 0.0); judged point by point, the rows at
// its crests fail where the material is not in tension. The mean over the stencil removes the pattern
// and keeps the tension of a release fan tens of cells wide. It is the non-local form of a damage
// criterion (Pijaudier-Cabot and Bazant 1987), with the stencil as its length, so that length is
// numerical (1.5 h either side for bspline2): refine and it shrinks with the cell. The point's own
// tension is required too: a compressed point beside a void's tensile rim would otherwise open with
// its own material compressed (J_f < 1), which then pushes forever as the space around it opens and
// drives its energy below zero (seen in the hard cases' jetting and thin ligaments).
//
// It runs after the point update, on the step's stencils and bins (the states are the new ones, the
// weights those of the step's start), folds its nodal sums across a symmetry plane and sums them
// across MPI ranks' shared rows, as the artificial heat flux does. A point that opens here has its
// tension held and its shear removed at once; the work-mismatch diagnostic of that one step uses its
// state before it opened.
#pragma once

#include <cmath>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/spall.hpp"
#include "mpmshock/step_effect.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/symmetry_plane.hpp"

namespace mpmshock {

template <int D, class Shape>
void open_by_neighbourhood_tension(Particles<D>& pts, PointRange range, const StripBins& bins, const Grid<D>& g,
                                   const StencilStore<D>& store, const Halo<D>& halo, const SymmetryPlane<D>* plane,
                                   const Spall& law, std::vector<double>& node_tension) {
  const GridGeometry<D>& geo = g.geo;
  const auto& stencils = store.template of<Shape::support>();
  const RowRange rows = bins.rows();
  const std::size_t first = geo.row_start(rows.begin), last = geo.row_start(rows.end);
  node_tension.resize(geo.nodes());
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) node_tension[i] = 0.0;
  halo.zero(node_tension);

  const bool strength = pts.has_strength();
  bins.scatter([&](std::size_t p) {  // 1.
    const double tension = max_principal_stress(strength ? pts.s[p] : Deviator<D>{}, pts.P[p]);
    if (!std::isfinite(tension)) return;  // a bad state the step reports gives its nodes nothing
    const double mt = pts.m[p] * tension;
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) { node_tension[i] += N * mt; });
  }, [&] { halo.between_colours(node_tension); }, [&] { halo.after_colours(node_tension); });
  if (plane) plane->fold_scalar(g, node_tension, rows);
#pragma omp parallel for schedule(static)
  for (std::size_t i = first; i < last; ++i) node_tension[i] = g.m[i] > 0.0 ? node_tension[i] / g.m[i] : 0.0;

  const bool back_stress = !pts.alpha.empty();
#pragma omp parallel for schedule(dynamic, kChunk)
  for (std::size_t p = range.begin; p < range.end; ++p) {  // 2. and 3.
    if (pts.failure_J[p] > 0.0 || !(pts.P[p] < 0.0)) continue;
    double mean = 0.0;
    for_each_node(stencils[p], geo, [&](std::size_t i, double N, const Vec<D>&) { mean += N * node_tension[i]; });
    if (!(mean > law.strength)) continue;
    const double J = pts.J(p);
    pts.failure_J[p] = J;
    pts.damage[p] = law.damage(J, J, 0.0);
    pts.P[p] = law.pressure(pts.P[p], pts.damage[p]);
    if (strength) pts.s[p] = {};
    if (back_stress) pts.alpha[p] = {};
  }
}

// The criterion as a step effect: after the point update, on its new states.
template <int D, class Shape>
class SpallNeighbourhoodEffect final : public StepEffect<D> {
 public:
  explicit SpallNeighbourhoodEffect(const Spall& law) : law_(law) {}
  const char* name() const override { return "spall by the neighbourhood's tension"; }
  unsigned slots() const override { return slot_bit(StepSlot::after_point_update); }
  StepStatus after_point_update(StepContext<D>& c) override {
    open_by_neighbourhood_tension<D, Shape>(c.points, c.reached, c.bins, c.grid, c.stencils, c.halo, c.plane, law_,
                                            node_tension_);
    return {};
  }

 private:
  Spall law_;
  std::vector<double> node_tension_;  // its nodal sums
};

}  // namespace mpmshock
