// Material points as a struct of arrays: one std::vector per physical field.
#pragma once

#include <cstdint>
#include <vector>

namespace mpmshock {

enum class Body : std::uint8_t { flyer = 0, target = 1 };

struct Particles {
  // Kinematics
  std::vector<double> x, y;    // position [m]; x kept in [0, width)
  std::vector<double> vx, vy;  // velocity [m/s]
  // Per-point constants
  std::vector<double> mass;     // m_p [kg per m of depth]
  std::vector<double> volume0;  // reference volume V0_p [m2 per m of depth]
  // Deformation gradient F (plane strain, F_zz = 1); J = det F = V / V0
  std::vector<double> Fxx, Fxy, Fyx, Fyy;
  // Time-centred velocity gradient L = grad v of the last step
  std::vector<double> Lxx, Lxy, Lyx, Lyy;
  // Thermodynamic state
  std::vector<double> work;       // work of the last step's nodal forces on the point [J/kg] (scratch)
  std::vector<double> energy;     // specific internal energy E [J/kg], 0 at the reference state
  std::vector<double> pressure;   // EOS pressure P [Pa]
  std::vector<double> viscosity;  // artificial viscous pressure q [Pa]
  // Strength state; allocated only when plasticity is on. The yield radius is a function of
  // plastic_strain (VonMises::yield_radius) and is not stored.
  std::vector<double> sxx, syy, sxy;   // deviatoric stress s (s_zz = -(sxx + syy)) [Pa]
  std::vector<double> plastic_strain;  // effective plastic strain eps_p
  std::vector<double> axx, ayy, axy;   // back stress alpha [Pa]; only with kinematic hardening
  // Identity
  std::vector<std::uint32_t> id;  // stable index, the order points were created in
  std::vector<Body> body;

  std::size_t size() const { return x.size(); }
  bool has_strength() const { return strength_; }
  bool has_back_stress() const { return back_stress_; }

  double J(std::size_t p) const { return Fxx[p] * Fyy[p] - Fxy[p] * Fyx[p]; }
  double volume(std::size_t p) const { return volume0[p] * J(p); }
  double density(std::size_t p) const { return mass[p] / volume(p); }

  // Appends a point in its reference state (stress free, E = 0) moving at (pvx, pvy).
  void add(double px, double py, double pvx, double pvy, double m, double V0, Body b);
  // Allocates (or drops) the strength fields, and the back stress for kinematic hardening.
  void enable_strength(bool on, bool back_stress);
  void reserve(std::size_t n);
  // Memory this layout holds per point, for --check and the benchmarks.
  std::size_t bytes_per_point() const;

 private:
  bool strength_ = false, back_stress_ = false;
};

}  // namespace mpmshock
