// The initial state of a scene: the grid, the two bodies' material points and their voids.
#pragma once

#include <string>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/mirror_image.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/strip_bins.hpp"
#include "mpmshock/voids.hpp"

namespace mpmshock {

struct BodySummary {
  std::string name;
  double y_bottom = 0.0, y_top = 0.0;
  std::size_t lattice_points = 0;   // points the solid body would have
  std::size_t material_points = 0;  // points left after cutting the voids
  std::vector<Void> voids;
  double porosity() const { return porosity_of(lattice_points, material_points); }
};

// The porosity of both bodies together, from their material points.
inline double porosity_of(const BodySummary& a, const BodySummary& b) {
  return porosity_of(a.lattice_points + b.lattice_points, a.material_points + b.material_points);
}

// The initial state of a run: the grid and the points it simulates. With symmetry = on these are
// the target's alone and `mirror` makes the whole impact of them (mirror_image.hpp).
template <int D>
struct InitialState {
  GridGeometry<D> grid;
  Particles<D> particles;
  MirrorImage<D> mirror;
  BodySummary target, flyer;
  std::size_t window_points = 0;  // the window's, solid (window_height > 0)
};

// The step's scratch per point besides the points' own fields: the scatter bins, the stencil the
// step's passes share, the grid velocity that moves the point (transfer.hpp, v_pic), and the
// artificial heat flux's T_p, C_p r_p, C_p T_p (and C_p with several materials;
// artificial_heat_flux.hpp).
template <int D>
std::size_t step_scratch_bytes(const Scene& s) {
  const std::size_t flux_bytes = s.has_heat_flux() ? (s.one_material() ? 3 : 4) * sizeof(double) : 0;
  return StripBins::kBytesPerPoint + StencilStore<D>::bytes_per_point(support_of(s.shape_function)) +
         sizeof(Vec<D>) + flux_bytes;
}

// The memory a scene's run needs, estimated from the scene alone (nothing is allocated).
struct SizeEstimate {
  double points = 0.0, nodes = 0.0;
  double point_bytes = 0.0, node_bytes = 0.0;
  double bytes() const { return point_bytes + node_bytes; }
};
template <int D>
SizeEstimate estimate_size(const Scene& scene);

// Refuses (SceneError naming the key that makes it so) a scene whose points, grid or memory
// cannot fit: more memory than the machine has, a grid too large to index, or too few strips of
// the grid for `ranks` MPI ranks. Run before anything
// is allocated, deleted or written. On MPI ranks a rank holds at most twice its even share of the
// points and grid (decomposition.hpp), and `node_ranks` of them share this machine's memory.
template <int D>
void check_fits(const Scene& scene, int ranks = 1, int node_ranks = 1);

// The grid of a scene: a periodic column covering both bodies plus grid_margin, with the impact
// plane y = 0 on a grid line.
template <int D>
GridGeometry<D> build_grid_geometry(const Scene& scene);

// Builds the grid and the material points:
// a regular lattice of particles_per_cell^D points per cell, the flyer in [-flyer_height, 0]
// moving up at +velocity, the target in [0, target_height] moving down, voids cut from both; with
// symmetry = on, the target's points only (the flyer in `mirror`).
// Throws SceneError (naming the porosity key) if the voids cannot be placed.
template <int D>
InitialState<D> build_initial_state(const Scene& scene);

// The same in two steps, for MPI ranks that each make only their share of the points: first the
// lattices and voids, and the number of points of every lattice row the run simulates (in the order
// the points are made: the flyer's bottom row first, then the target's); then the points of a
// rank's rows, each with the id it has in the whole.
template <int D>
class InitialBuilder {
 public:
  explicit InitialBuilder(const Scene& scene);  // throws SceneError as build_initial_state
  // The initial state with the points of the rows whose `keep` flag is set (null: all of them).
  InitialState<D> build(const std::vector<char>* keep = nullptr) const;
  // The initial state with rank `rank` of `ranks`' share of the points: consecutive rows holding
  // about as many points as every other rank's (one rank: all of them).
  InitialState<D> build_share(int rank, int ranks) const;

 private:
  const Scene& scene_;
  Lattice target_, flyer_, window_;
  VoidLayout target_voids_, flyer_voids_, window_voids_;  // the window's: none
  std::vector<std::size_t> row_points_;
  std::vector<std::size_t> flyer_rows_, target_rows_, window_rows_;  // points per lattice row of each body
};

}  // namespace mpmshock
