#include "mpmshock/setup.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "mpmshock/decomposition.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {

template <int D>
GridGeometry<D> build_grid_geometry(const Scene& s) {
  GridGeometry<D> g;
  g.h = s.cell_size;
  g.inv_h = 1.0 / s.cell_size;
  g.nx = static_cast<int>(std::lround(s.width / s.cell_size));
  if constexpr (D == 3) g.nz = static_cast<int>(std::lround(s.derived_depth() / s.cell_size));
  const double margin = s.derived_grid_margin();
  // Node row `below` sits on the impact plane y = 0, so the plane is a grid line.
  const int below = static_cast<int>(std::ceil((s.flyer_height + margin) / s.cell_size - 1e-9));
  const int above = static_cast<int>(std::ceil((s.target_height + s.window_height + margin) / s.cell_size - 1e-9));
  g.y_min = -below * s.cell_size;
  g.lp = 0.5 / static_cast<double>(s.particles_per_cell);  // GIMP: the point's initial half-width
  g.ny = below + above + 1;
  return g;
}

namespace {

// The optional per-point fields the scene's effects need.
template <int D>
void enable_fields(Particles<D>& p, const Scene& s) {
  const StrengthLaw strength = strength_laws(s)[index_of(Body::target)];  // every body's type
  p.enable_strength(has_stress(strength), has_back_stress(strength));
  p.enable_failure(s.effects.spall);
  p.enable_cold_work(s.effects.plasticity && s.taylor_quinney < 1.0);
  p.enable_plastic_heat(s.tracks_plastic_heat());
}

}  // namespace

template <int D>
SizeEstimate estimate_size(const Scene& s) {
  SizeEstimate e;
  const double a = s.particle_spacing();
  const double across = s.points_across();
  const double rows = std::round(s.target_height / a) + std::round(s.flyer_height / a) + std::round(s.window_height / a);
  const bool mirrored = s.symmetry == Symmetry::on;  // the target alone, the flyer its mirror image
  e.points = across * (mirrored ? std::round(s.target_height / a) : rows);  // before the voids are cut: an upper bound
  const GridGeometry<D> g = build_grid_geometry<D>(s);
  e.nodes = static_cast<double>(g.nodes());
  Particles<D> sample;
  enable_fields(sample, s);
  e.point_bytes = e.points * static_cast<double>(sample.bytes_per_point() + step_scratch_bytes<D>(s));
  e.node_bytes = e.nodes * static_cast<double>(Grid<D>::bytes_per_node());
  return e;
}

template <int D>
void check_fits(const Scene& s, int ranks, int node_ranks) {
  const SizeEstimate e = estimate_size<D>(s);
  // Each rank on this machine holds at most kMaxPointShare times its even share (decomposition.hpp),
  // and all of them together never more than the whole.
  const double share = std::min(1.0, static_cast<double>(Decomposition::kMaxPointShare * node_ranks) /
                                         static_cast<double>(std::max(ranks, 1)));
  // The key that makes the size: the points' spacing, or the grid's margin (which grows with
  // end_time when it is automatic).
  const bool points_dominate = e.point_bytes >= e.node_bytes;
  const std::string key = points_dominate ? "cell_size" : (s.grid_margin >= 0.0 ? "grid_margin" : "end_time");
  auto fail = [&](const std::string& why) { throw SceneError(s.where(key) + ": key '" + key + "': " + why); };
  char counts[160];
  std::snprintf(counts, sizeof counts, "%.3g material points, %.3g grid nodes (grid margin %.3g m)", e.points, e.nodes,
                s.derived_grid_margin());
  if (!(e.nodes < 2e9)) fail(std::string("the grid would be too large to index: ") + counts);
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES)), page = static_cast<double>(sysconf(_SC_PAGESIZE));
  const double memory = pages > 0 && page > 0 ? pages * page : 0.0;
  if (memory > 0.0 && !(share * e.bytes() <= 0.9 * memory)) {
    char text[480];
    char on_ranks[120] = "";
    if (ranks > 1)
      std::snprintf(on_ranks, sizeof on_ranks, " for the %d of its %d MPI ranks on this machine", node_ranks, ranks);
    std::snprintf(text, sizeof text, "the run would need about %.3g GiB%s (%s), more than this machine's %.3g GiB of memory%s",
                  share * e.bytes() / 1073741824.0, on_ranks, counts, memory / 1073741824.0,
                  key == "end_time" ? "; the automatic grid margin grows with end_time: set grid_margin" : "");
    fail(text);
  }
  check_rank_count<D>(s, build_grid_geometry<D>(s), ranks);
}

namespace {

// The surviving points of each lattice row of a body, bottom row first.
std::vector<std::size_t> points_per_row(const Lattice& lat, const VoidLayout& layout) {
  std::vector<std::size_t> out(static_cast<std::size_t>(lat.rows), 0);
  for (int j = 0; j < lat.rows; ++j)
    for (int k = 0; k < lat.layers; ++k)
      for (int i = 0; i < lat.columns; ++i) out[static_cast<std::size_t>(j)] += !layout.removed[lat.index(i, j, k)];
  return out;
}

// Adds the surviving lattice points of one body in lattice order (bottom row first, so that
// storage follows y), of the rows whose flag in `keep` (from `row`, one per lattice row) is set,
// numbered from `id`.
template <int D>
void add_points(Particles<D>& p, const Lattice& lat, const VoidLayout& layout, double vy, double rho0, Body body,
                const std::vector<std::size_t>& per_row, const std::vector<char>* keep, std::size_t row,
                std::size_t id) {
  const double a = lat.spacing;
  const double V0 = D == 2 ? a * a : a * a * a;
  Vec<D> velocity{};
  velocity[1] = vy;
  for (int j = 0; j < lat.rows; ++j, ++row) {
    if (keep && !(*keep)[row]) {
      id += per_row[static_cast<std::size_t>(j)];
      continue;
    }
    for (int k = 0; k < lat.layers; ++k)
      for (int i = 0; i < lat.columns; ++i) {
        if (layout.removed[lat.index(i, j, k)]) continue;
        Vec<D> x{};
        x[0] = lat.x0 + (i + 0.5) * a;
        x[1] = lat.y0 + (j + 0.5) * a;
        if constexpr (D == 3) x[2] = (k + 0.5) * a;
        p.add(x, velocity, rho0 * V0, V0, body);
        p.id.back() = static_cast<std::uint32_t>(id++);
      }
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

template <int D>
InitialBuilder<D>::InitialBuilder(const Scene& s) : scene_(s) {
  const double a = s.particle_spacing();
  target_ = Lattice{0.0, 0.0, a, static_cast<int>(std::lround(s.width / a)), static_cast<int>(std::lround(s.target_height / a))};
  if constexpr (D == 3) target_.layers = static_cast<int>(std::lround(s.derived_depth() / a)), target_.dimension = 3;
  flyer_ = target_;
  flyer_.y0 = -s.flyer_height;
  flyer_.rows = static_cast<int>(std::lround(s.flyer_height / a));

  const VoidRequest request{s.porosity, s.void_radius, s.void_radius_spread, s.void_min_gap, s.void_overlap};
  std::mt19937_64 rng(static_cast<std::uint64_t>(s.seed));
  try {
    target_voids_ = seed_voids(target_, request, rng);
    VoidRequest flyer_request = request;
    flyer_request.porosity = s.flyer_porosity;
    flyer_voids_ = s.mirrors_flyer() ? mirror_layout(target_voids_, target_) : seed_voids(flyer_, flyer_request, rng);
  } catch (const VoidSeedingError& e) {
    throw SceneError(s.where("porosity") + ": key 'porosity': " + e.what());
  }
  // The window: solid, on the target's free surface (no symmetry with it: scene.cpp).
  window_ = target_;
  window_.y0 = target_.y0 + target_.height();
  window_.rows = static_cast<int>(std::lround(s.window_height / a));
  window_voids_ = seed_voids(window_, VoidRequest{1.0, s.void_radius, 0.0, 0.0, false}, rng);
  flyer_rows_ = points_per_row(flyer_, flyer_voids_);
  target_rows_ = points_per_row(target_, target_voids_);
  window_rows_ = points_per_row(window_, window_voids_);
  // The rows simulated, in the order their points are made: with symmetry = on the target's alone.
  if (s.symmetry != Symmetry::on)
    row_points_ = flyer_rows_;
  row_points_.insert(row_points_.end(), target_rows_.begin(), target_rows_.end());
  row_points_.insert(row_points_.end(), window_rows_.begin(), window_rows_.end());
}

template <int D>
InitialState<D> InitialBuilder<D>::build(const std::vector<char>* keep) const {
  const Scene& s = scene_;
  InitialState<D> st;
  st.grid = build_grid_geometry<D>(s);
  std::size_t n = 0;
  for (std::size_t r = 0; r < row_points_.size(); ++r) n += !keep || (*keep)[r] ? row_points_[r] : 0;
  enable_fields(st.particles, s);
  st.particles.reserve(n);
  const bool mirrored = s.symmetry == Symmetry::on;
  std::size_t row = 0, id = 0;
  if (!mirrored) {
    add_points(st.particles, flyer_, flyer_voids_, s.velocity_of(Body::flyer), s.material_of(Body::flyer).density, Body::flyer, flyer_rows_, keep,
               row, id);
    row += static_cast<std::size_t>(flyer_.rows);
    for (std::size_t c : flyer_rows_) id += c;
  }
  add_points(st.particles, target_, target_voids_, s.velocity_of(Body::target), s.material_of(Body::target).density, Body::target,
             target_rows_, keep, row, id);
  if (s.has_window()) {  // above the target, numbered after it, moving with it
    row += static_cast<std::size_t>(target_.rows);
    for (std::size_t c : target_rows_) id += c;
    add_points(st.particles, window_, window_voids_, s.velocity_of(Body::window), s.material_of(Body::window).density,
               Body::window, window_rows_, keep, row, id);
  }
  st.window_points = window_.size();
  st.target = summarize("target", target_, target_voids_);
  st.flyer = summarize("flyer", flyer_, flyer_voids_);
  if (mirrored) st.mirror = MirrorImage<D>(flyer_rows_, target_rows_);
  return st;
}

template <int D>
InitialState<D> InitialBuilder<D>::build_share(int rank, int ranks) const {
  if (ranks <= 1) return build();
  std::size_t total = 0;
  for (std::size_t n : row_points_) total += n;
  std::vector<char> keep(row_points_.size(), 0);
  std::size_t before = 0;  // the points of the rows below
  for (std::size_t r = 0; r < row_points_.size(); ++r) {
    // A row goes to the rank whose equal share of the points its first point falls in.
    const auto owner = total > 0 ? static_cast<int>(std::min<std::uint64_t>(
                                       static_cast<std::uint64_t>(ranks) - 1,
                                       static_cast<std::uint64_t>(before) * static_cast<std::uint64_t>(ranks) / total))
                                 : 0;
    keep[r] = owner == rank;
    before += row_points_[r];
  }
  return build(&keep);
}

template <int D>
InitialState<D> build_initial_state(const Scene& s) {
  return InitialBuilder<D>(s).build();
}

template class InitialBuilder<2>;
template class InitialBuilder<3>;
template InitialState<2> build_initial_state<2>(const Scene&);
template InitialState<3> build_initial_state<3>(const Scene&);
template SizeEstimate estimate_size<2>(const Scene&);
template SizeEstimate estimate_size<3>(const Scene&);
template void check_fits<2>(const Scene&, int, int);
template void check_fits<3>(const Scene&, int, int);
template GridGeometry<2> build_grid_geometry<2>(const Scene&);
template GridGeometry<3> build_grid_geometry<3>(const Scene&);

}  // namespace mpmshock
