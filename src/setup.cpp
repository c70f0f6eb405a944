#include "mpmshock/setup.hpp"

#include <cmath>
#include <random>

#include "mpmshock/model.hpp"

namespace mpmshock {

template <int D>
GridGeometry<D> build_grid_geometry(const Scene& s) {
  GridGeometry<D> g;
  g.h = s.cell_size;
  g.inv_h = 1.0 / s.cell_size;
  g.nx = static_cast<int>(std::lround(s.width / s.cell_size));
  const double margin = s.derived_grid_margin();
  // Node row `below` sits on the impact plane y = 0, so the plane is a grid line.
  const int below = static_cast<int>(std::ceil((s.flyer_height + margin) / s.cell_size - 1e-9));
  const int above = static_cast<int>(std::ceil((s.target_height + margin) / s.cell_size - 1e-9));
  g.y_min = -below * s.cell_size;
  g.lp = 0.5 / static_cast<double>(s.particles_per_cell);  // uGIMP: the point's initial half-width
  g.ny = below + above + 1;
  return g;
}

namespace {

// Adds the surviving lattice points of one body, bottom row first so that storage follows y.
void add_points(Particles<2>& p, const Lattice& lat, const VoidLayout& layout, double vy, double rho0, Body body) {
  const double a = lat.spacing;
  const double V0 = a * a;
  for (int j = 0; j < lat.rows; ++j)
    for (int i = 0; i < lat.columns; ++i) {
      if (layout.removed[lat.index(i, j)]) continue;
      p.add({{lat.x0 + (i + 0.5) * a, lat.y0 + (j + 0.5) * a}}, {{0.0, vy}}, rho0 * V0, V0, body);
    }
}

BodySummary summarize(const char* name, const Lattice& lat, const VoidLayout& layout) {
  BodySummary b;
  b.name = name;
  b.y_bottom = lat.y0;
  b.y_top = lat.y0 + lat.height();
  b.lattice_points = layout.lattice_points;
  b.material_points = layout.lattice_points - layout.removed_count;
  b.voids = layout.voids;
  return b;
}

}  // namespace

template <>
InitialState<2> build_initial_state<2>(const Scene& s) {
  InitialState<2> st;
  st.grid = build_grid_geometry<2>(s);

  const double a = s.particle_spacing();
  const int columns = static_cast<int>(std::lround(s.width / a));
  const Lattice target{0.0, 0.0, a, columns, static_cast<int>(std::lround(s.target_height / a))};
  const Lattice flyer{0.0, -s.flyer_height, a, columns, static_cast<int>(std::lround(s.flyer_height / a))};

  const VoidRequest request{s.porosity, s.void_radius, s.void_radius_spread, s.void_min_gap, s.void_overlap};
  std::mt19937_64 rng(static_cast<std::uint64_t>(s.seed));
  VoidLayout target_voids, flyer_voids;
  try {
    target_voids = seed_voids(target, request, rng);
    flyer_voids = (s.flyer_mirror && s.porosity > 1.0) ? mirror_layout(target_voids, target)
                                                       : seed_voids(flyer, request, rng);
  } catch (const VoidSeedingError& e) {
    throw SceneError(s.where("porosity") + ": key 'porosity': " + e.what());
  }

  const std::size_t n = target.size() + flyer.size() - target_voids.removed_count - flyer_voids.removed_count;
  const StrengthLaw strength = strength_of(s);
  st.particles.enable_strength(has_stress(strength), has_back_stress(strength));
  st.particles.reserve(n);
  add_points(st.particles, flyer, flyer_voids, +s.velocity, s.material.density, Body::flyer);
  add_points(st.particles, target, target_voids, -s.velocity, s.material.density, Body::target);

  st.target = summarize("target", target, target_voids);
  st.flyer = summarize("flyer", flyer, flyer_voids);
  return st;
}

template GridGeometry<2> build_grid_geometry<2>(const Scene&);
template GridGeometry<3> build_grid_geometry<3>(const Scene&);

}  // namespace mpmshock
