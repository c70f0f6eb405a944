// Material points as a struct of arrays: one std::vector per physical field, a small fixed-size
// vector or matrix per point where the field is one (tensor.hpp).
//
//   x, v       position [m] (periodic coordinates kept in [0, period)) and velocity [m/s]
//   m, V0      mass [kg; per m of depth in 2D] and reference volume [m3; m2 in 2D]
//   F, L       deformation gradient (J = det F = V / V0) and the last step's velocity gradient
//   E          specific internal energy [J/kg], 0 at the reference state
//   P, q       equation-of-state pressure and artificial viscous pressure [Pa]
//   s, alpha   deviatoric stress and back stress [Pa] (with strength; alpha only with kinematic
//              hardening)
//   eps_p      effective plastic strain (with strength)
//   failure_J  0 while intact; the J at which the point began to open in tension (with spall)
//   damage     0 intact, rising while it opens, 1 separated (with spall; spall.hpp)
//   E_stored   the part of E stored as cold work, not heat [J/kg] (taylor_quinney < 1)
//   plastic_heat  the plastic work turned to heat so far [J/kg] (temperature_model = paper)
//   work       the work of the last step's nodal forces on the point [J/kg] (scratch of a step)
//   work_mismatch  m (work - the trapezoid-rule work of the point's own deformation), summed over
//              its steps [J]: conservation.csv's work_mismatch is their exact sum (constitutive.hpp)
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "mpmshock/material.hpp"
#include "mpmshock/tensor.hpp"

namespace mpmshock {

// The points [begin, end) by storage index: those a step computes (unreached.hpp).
struct PointRange {
  std::size_t begin = 0, end = 0;
};

// The passes that compute four points at a time (lanes.hpp) take a range in groups of four from its
// begin: group g is the points from begin + 4 g, the last group has one to four.
inline std::size_t groups_of_four(PointRange range) { return (range.end - range.begin + 3) / 4; }
// Calls four(p) for group g's points p..p+3 if they are four of one body, else one(q) for each of
// its points.
template <class Points, class Four, class One>
[[gnu::always_inline]] inline void for_group_of_four(const Points& pts, PointRange range, std::size_t g, Four&& four,
                                                     One&& one) {
  const std::size_t p = range.begin + 4 * g, n = std::min<std::size_t>(4, range.end - p);
  bool one_body = n == 4;
  for (std::size_t l = 1; l < n; ++l) one_body = one_body && pts.body[p + l] == pts.body[p];
  if (one_body) {
    four(p);
    return;
  }
  for (std::size_t q = p; q < p + n; ++q) one(q);
}

template <int D>
struct Particles {
  std::vector<Vec<D>> x, v;
  std::vector<double> m, V0;
  std::vector<Mat<D>> F, L;
  std::vector<double> work, E, P, q;
  std::vector<double> work_mismatch;
  std::vector<Deviator<D>> s, alpha;
  std::vector<double> eps_p;
  std::vector<double> failure_J, damage;
  std::vector<double> E_stored;
  std::vector<double> plastic_heat;
  std::vector<std::uint32_t> id;  // stable index, the order points were created in
  std::vector<Body> body;

  std::size_t size() const { return x.size(); }
  bool has_strength() const { return strength_; }
  bool has_back_stress() const { return back_stress_; }
  bool has_failure() const { return failure_; }
  bool failed(std::size_t p) const { return failure_ && failure_J[p] > 0.0; }
  bool stores_cold_work() const { return stored_; }
  bool tracks_plastic_heat() const { return plastic_heat_; }
  // The part of the internal energy that is heat: E less the stored cold work.
  double thermal_energy(std::size_t p) const { return stored_ ? E[p] - E_stored[p] : E[p]; }

  // J = det F: the volume the point occupies over its reference volume.
  double J(std::size_t p) const { return det(F[p]); }
  // The material's own volume ratio: J, except for a failed point, whose expansion beyond the J it
  // began to open at is opened space (spall.hpp). Density, pressure and temperature are the material's.
  double material_J(std::size_t p) const { return failed(p) ? std::min(J(p), failure_J[p]) : J(p); }
  double volume(std::size_t p) const { return V0[p] * J(p); }
  double density(std::size_t p) const { return m[p] / (V0[p] * material_J(p)); }

  // Appends a point in its reference state (stress free, E = 0) at `position` moving at `velocity`.
  void add(const Vec<D>& position, const Vec<D>& velocity, double mass, double volume0, Body b);
  // Allocates (or drops) the strength fields s and eps_p, and the back stress alpha.
  void enable_strength(bool on, bool back_stress);
  // Allocates (or drops) failure_J and damage, all intact.
  void enable_failure(bool on);
  // Allocates (or drops) E_stored, all zero.
  void enable_cold_work(bool on);
  // Allocates (or drops) plastic_heat, all zero.
  void enable_plastic_heat(bool on);
  // Allocates the optional fields `other` has (and drops the others).
  void enable_fields_of(const Particles& other);
  // Appends a copy of point p of `from`, which holds the same fields, every field as it is there.
  void append_copy(const Particles& from, std::size_t p);
  void reserve(std::size_t n);

  // Calls f(&Particles::field) for every per-point field this layout holds, for the bulk
  // operations (copy, reserve, bytes per point) that must not forget one.
  template <class F>
  void for_each_member(F&& f) const {
    f(&Particles::x), f(&Particles::v), f(&Particles::m), f(&Particles::V0), f(&Particles::F), f(&Particles::L);
    f(&Particles::work), f(&Particles::E), f(&Particles::P), f(&Particles::q), f(&Particles::work_mismatch);
    f(&Particles::id), f(&Particles::body);
    if (strength_) f(&Particles::s), f(&Particles::eps_p);
    if (back_stress_) f(&Particles::alpha);
    if (failure_) f(&Particles::failure_J), f(&Particles::damage);
    if (stored_) f(&Particles::E_stored);
    if (plastic_heat_) f(&Particles::plastic_heat);
  }
  // Memory this layout holds per point, for --check and the benchmarks.
  std::size_t bytes_per_point() const;

 private:
  bool strength_ = false, back_stress_ = false, failure_ = false, stored_ = false, plastic_heat_ = false;
};

// The number of flyer points, which set-up stores before the target's.
template <int D>
std::size_t flyer_points(const Particles<D>& p) {
  std::size_t n = 0;
  while (n < p.size() && p.body[n] == Body::flyer) ++n;
  return n;
}

extern template struct Particles<2>;
extern template struct Particles<3>;

}  // namespace mpmshock
