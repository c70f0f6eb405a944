// Void seeding: the requested porosity from the material points, non-overlapping periodic circles
// (2D) and spheres (3D, periodic in x and z) inside the body, mirror images, reproducibility, and
// refusal when voids cannot fit.
#include <random>

#include "check.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/voids.hpp"

using namespace mpmshock;

// The distance between two coordinates on a periodic axis.
static double periodic(double a, double b, double period) {
  const double d = std::abs(a - b);
  return std::min(d, period - d);
}

static void check_layout(const Lattice& lat, const VoidLayout& v, const VoidRequest& req) {
  CHECK_REL(v.porosity(), req.porosity, 0.005);
  const bool spheres = lat.dimension == 3;
  // Recount the removed points from the circles (spheres) themselves, by brute force.
  std::size_t inside = 0;
  for (int j = 0; j < lat.rows; ++j)
    for (int k = 0; k < lat.layers; ++k)
      for (int i = 0; i < lat.columns; ++i) {
        const double x = lat.x0 + (i + 0.5) * lat.spacing, y = lat.y0 + (j + 0.5) * lat.spacing;
        const double z = (k + 0.5) * lat.spacing;
        bool in = false;
        for (const Void& c : v.voids) {
          const double dx = periodic(x, c.x, lat.width()), dz = spheres ? periodic(z, c.z, lat.depth()) : 0.0;
          in = in || dx * dx + (y - c.y) * (y - c.y) + dz * dz < c.r * c.r;
        }
        CHECK(in == (v.removed[lat.index(i, j, k)] != 0));
        inside += in;
      }
  CHECK(inside == v.removed_count);
  for (std::size_t a = 0; a < v.voids.size(); ++a) {
    const Void& p = v.voids[a];
    CHECK(p.y - p.r >= lat.y0 - 1e-15 && p.y + p.r <= lat.y0 + lat.height() + 1e-15);
    CHECK(p.r >= req.radius - req.radius_spread && p.r <= req.radius + req.radius_spread);
    CHECK(spheres ? p.z >= 0.0 && p.z < lat.depth() : p.z == 0.0);
    if (req.overlap) continue;
    for (std::size_t b = a + 1; b < v.voids.size(); ++b) {
      const Void& q = v.voids[b];
      const double dx = periodic(p.x, q.x, lat.width()), dz = spheres ? periodic(p.z, q.z, lat.depth()) : 0.0;
      CHECK(std::hypot(dx, p.y - q.y, dz) >= p.r + q.r + req.min_gap);
    }
  }
}

int main() {
  const Lattice lat{0.0, 0.0, 2.5e-6, 200, 400};  // 0.5 mm x 1 mm
  for (double delta : {1.03, 1.1, 1.4, 1.7}) {
    const VoidRequest req{delta, 10e-6, 3e-6, 1e-6, false};
    std::mt19937_64 rng(1);
    const VoidLayout v = seed_voids(lat, req, rng);
    std::printf("porosity %.3f: %zu voids, achieved %.5f\n", delta, v.voids.size(), v.porosity());
    check_layout(lat, v, req);
  }
  {  // Overlap allowed.
    const VoidRequest req{1.3, 8e-6, 0.0, 0.0, true};
    std::mt19937_64 rng(3);
    check_layout(lat, seed_voids(lat, req, rng), req);
  }
  {  // Same seed, same layout; another seed, another.
    const VoidRequest req{1.1, 10e-6, 0.0, 0.0, false};
    std::mt19937_64 a(5), b(5), c(6);
    const VoidLayout va = seed_voids(lat, req, a), vb = seed_voids(lat, req, b), vc = seed_voids(lat, req, c);
    CHECK(va.voids.size() == vb.voids.size() && va.voids[0].x == vb.voids[0].x && va.removed == vb.removed);
    CHECK(va.removed != vc.removed);
  }
  {  // Mirror image: voids at -y, the same points removed row for mirrored row.
    const VoidRequest req{1.2, 10e-6, 0.0, 0.0, false};
    std::mt19937_64 rng(9);
    const VoidLayout v = seed_voids(lat, req, rng);
    const VoidLayout m = mirror_layout(v, lat);
    const Lattice mirrored{0.0, -lat.height(), lat.spacing, lat.columns, lat.rows};
    check_layout(mirrored, m, req);
    CHECK(m.removed_count == v.removed_count && m.voids[3].y == -v.voids[3].y);
  }
  {  // Voids that cannot fit are refused with the reason.
    const VoidRequest req{3.0, 10e-6, 0.0, 2e-6, false};
    std::mt19937_64 rng(1);
    CHECK_THROWS_WITH(seed_voids(lat, req, rng), "cannot fit");
    const Lattice tiny{0.0, 0.0, 2.5e-6, 20, 20};  // one void would remove most of it
    const VoidRequest big{1.05, 20e-6, 0.0, 0.0, false};
    CHECK_THROWS_WITH(seed_voids(tiny, big, rng), "porosity");
  }
  {  // 3D: spheres periodic in x and z, at the porosities a random packing of spheres reaches.
    Lattice cube{0.0, 0.0, 5e-6, 40, 40};
    cube.layers = 40, cube.dimension = 3;  // 0.2 mm on each side
    for (double delta : {1.05, 1.2, 1.4}) {
      const VoidRequest req{delta, 15e-6, 3e-6, 1e-6, false};
      std::mt19937_64 rng(2);
      const VoidLayout v = seed_voids(cube, req, rng);
      std::printf("3D porosity %.3f: %zu spheres, achieved %.5f\n", delta, v.voids.size(), v.porosity());
      check_layout(cube, v, req);
    }
    const VoidRequest req{1.2, 15e-6, 0.0, 0.0, false};
    std::mt19937_64 rng(4);
    const VoidLayout v = seed_voids(cube, req, rng);
    Lattice mirrored = cube;
    mirrored.y0 = -cube.height();
    const VoidLayout m = mirror_layout(v, cube);
    check_layout(mirrored, m, req);
    CHECK(m.removed_count == v.removed_count && m.voids[3].y == -v.voids[3].y && m.voids[3].z == v.voids[3].z);
    // Through the scene: 2 x 2 x 2 points per cell, spheres in both bodies, the mirrored flyer.
    const Scene s = parse_scene("dimension = 3\nporosity = 1.2\nvoid_radius = 15 um\ncell_size = 10 um\n"
                                "width = 0.15 mm\ndepth = 0.1 mm\ntarget_height = 0.15 mm\nflyer_height = 0.15 mm\n",
                                "t3.scene");
    const InitialState<3> st = build_initial_state<3>(s);
    CHECK(st.target.lattice_points == 30u * 20u * 30u);
    CHECK_REL(st.target.porosity(), 1.2, 0.005);
    CHECK(st.grid.nx == 15 && st.grid.nz == 10);
    CHECK(st.mirror.on() && st.mirror.whole(st.particles).size() == 2 * st.target.material_points);
    CHECK_THROWS_WITH(parse_scene("dimension = 3\ndepth = 25 um\ncell_size = 10 um\n", "t3.scene"), "t3.scene:2",
                      "'depth'", "whole number of cells");
    CHECK_THROWS_WITH(parse_scene("dimension = 3\ndepth = 20 um\ncell_size = 10 um\nporosity = 1.1\n"
                                  "void_radius = 15 um\n",
                                  "t3.scene"),
                      "'void_radius'", "does not fit");
    CHECK_THROWS_WITH(parse_scene("dimension = 4\n", "t3.scene"), "t3.scene:1", "'dimension'", "not one of 2, 3");
  }
  {  // Through the scene: both bodies porous, the points' porosity reported, mirrored flyer.
    Scene s = parse_scene("porosity = 1.4\nvoid_radius = 10 um\ncell_size = 5 um\nwidth = 0.2 mm\n"
                          "target_height = 0.3 mm\nflyer_height = 0.3 mm\n",
                          "t.scene");
    const InitialState<2> st = build_initial_state<2>(s);
    CHECK_REL(st.target.porosity(), 1.4, 0.005);
    CHECK_REL(porosity_of(st.target, st.flyer), 1.4, 0.005);
    CHECK(st.flyer.material_points == st.target.material_points);
    // symmetry = auto: the target's points are simulated, the flyer is their mirror image
    CHECK(st.mirror.on() && st.particles.size() == st.target.material_points);
    CHECK(st.mirror.whole(st.particles).size() == st.flyer.material_points + st.target.material_points);
    CHECK_THROWS_WITH(build_initial_state<2>(parse_scene("porosity = 2.5\nvoid_radius = 10 um\ncell_size = 5 um\n"
                                                      "width = 0.2 mm\ntarget_height = 0.3 mm\n"
                                                      "flyer_height = 0.3 mm\nvoid_min_gap = 5 um\n",
                                                      "t.scene")),
                      "t.scene:1", "'porosity'", "cannot fit");
  }
  return check::result();
}
