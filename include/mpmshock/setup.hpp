// The initial state of a scene: the grid, the two bodies' material points and their voids.
#pragma once

#include <string>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/voids.hpp"

namespace mpmshock {

struct BodySummary {
  std::string name;
  double y_bottom = 0.0, y_top = 0.0;
  std::size_t lattice_points = 0;   // points the solid body would have
  std::size_t material_points = 0;  // points left after cutting the voids
  std::vector<Void> voids;
  double porosity = 1.0;            // lattice_points / material_points: the porosity of the points
};

struct InitialState {
  GridGeometry grid;
  Particles particles;
  BodySummary target, flyer;

  // Porosity of both bodies together, from the material points.
  double porosity() const {
    return static_cast<double>(target.lattice_points + flyer.lattice_points) /
           static_cast<double>(target.material_points + flyer.material_points);
  }
};

// The grid of a scene: a periodic column covering both bodies plus grid_margin, with the impact
// plane y = 0 on a grid line.
GridGeometry build_grid_geometry(const Scene& scene);

// Builds the grid and the material points:
// a regular lattice of particles_per_cell^2 points per cell, the flyer in [-flyer_height, 0] moving
// up at +velocity, the target in [0, target_height] moving down, voids cut from both.
// Throws SceneError (naming the porosity key) if the voids cannot be placed.
InitialState build_initial_state(const Scene& scene);

}  // namespace mpmshock
