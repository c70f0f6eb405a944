// Random voids cut from a body's lattice of material points until the porosity computed from the
// remaining points matches the requested one: circular (cylinders) in 2D, spherical in 3D.
#pragma once

#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

namespace mpmshock {

struct Void {
  double x, y, r;
  double z = 0.0;  // 3D only
};

// A body's regular lattice of material points: point (i, j, k) sits at
// (x0 + (i + 1/2) spacing, y0 + (j + 1/2) spacing, (k + 1/2) spacing); the lattice is periodic in x
// with period columns * spacing, and in 3D in z with period layers * spacing. Points are numbered
// row by row (y slowest), then layer, then column: the order the bodies' points are stored in.
struct Lattice {
  double x0 = 0.0, y0 = 0.0, spacing = 0.0;
  int columns = 0, rows = 0;
  int layers = 1;      // in z; 1 in 2D
  int dimension = 2;   // 3: spherical voids, periodic in z too

  std::size_t size() const {
    return static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows) * static_cast<std::size_t>(layers);
  }
  std::size_t index(int i, int j, int k = 0) const {
    return (static_cast<std::size_t>(j) * static_cast<std::size_t>(layers) + static_cast<std::size_t>(k)) *
               static_cast<std::size_t>(columns) +
           static_cast<std::size_t>(i);
  }
  double width() const { return columns * spacing; }
  double height() const { return rows * spacing; }
  double depth() const { return layers * spacing; }
};

struct VoidRequest {
  double porosity = 1.0;       // delta = rho_solid / rho_porous
  double radius = 0.0;         // mean radius
  double radius_spread = 0.0;  // radii uniform in [radius - spread, radius + spread]
  double min_gap = 0.0;        // smallest ligament between voids when they may not overlap
  bool overlap = false;
};

// The porosity of a body cut from a lattice: delta = lattice points / remaining material points
// (the volume the body spans over the volume of its material).
inline double porosity_of(std::size_t lattice_points, std::size_t material_points) {
  return static_cast<double>(lattice_points) / static_cast<double>(material_points);
}

struct VoidLayout {
  std::vector<Void> voids;
  std::vector<std::uint8_t> removed;  // per lattice point: 1 if inside a void
  std::size_t removed_count = 0;
  std::size_t lattice_points = 0;

  double porosity() const { return porosity_of(lattice_points, lattice_points - removed_count); }
};

// Thrown when the voids cannot be placed (they do not fit, or the porosity cannot be reached
// within tolerance). The message says why and what to change.
class VoidSeedingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Places voids one at a time (random sequential addition), fully inside the body in y and
// periodic in x (and z in 3D), until the point porosity reaches the request; keeps the last void only if that
// lands closer. Throws VoidSeedingError if the result is not within `tolerance` (relative).
VoidLayout seed_voids(const Lattice& lattice, const VoidRequest& request, std::mt19937_64& rng,
                      double tolerance = 0.005);

// The mirror image about y = 0 of a layout cut from `lattice`, on the mirrored lattice (same
// columns and rows, y0 -> -(y0 + height)): the flyer in the paper's symmetric set-up.
VoidLayout mirror_layout(const VoidLayout& layout, const Lattice& lattice);

// A uniform double in [0, 1) from 53 random bits: the same on every standard library, unlike
// std::uniform_real_distribution.
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace mpmshock
