// Effects that act on the grid or on all points once per step (or once per sample), as opposed to
// the per-point laws of model.hpp. Each is a small class that overrides the slots it acts in, as a
// LAMMPS fix declares its slots; Simulation::step() calls the slots in a fixed order, and the set
// of effects is chosen once at set-up (Simulation's constructor). A virtual call per slot per
// step, never per point.
#pragma once

#include <cstddef>

#include "mpmshock/grid.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

// What a step (or a check) found. Numerical trouble is a status, not an exception: the caller
// decides to stop, writes a final snapshot and reports (Simulation::describe explains every code).
struct StepStatus {
  enum class Code {
    ok,
    bad_state,          // J <= 0 or past the EOS limit, a non-finite value, a runaway speed
    left_grid,          // a point outside the grid's rows
    below_zero_kelvin,  // internal energy below the 0 K isotherm (ZeroKelvinCheck)
  };
  // How many codes there are: the ranks agree on a status packed with its code in [0, kCodes)
  // (simulation.cpp, status_key). A new code goes last and raises this, or the assert fails.
  static constexpr int kCodes = 4;
  Code code = Code::ok;
  std::size_t point = 0;  // id of the offending material point (its storage index on one rank)
  bool ok() const { return code == Code::ok; }
};
static_assert(static_cast<int>(StepStatus::Code::below_zero_kelvin) + 1 == StepStatus::kCodes,
              "StepStatus::kCodes must count every code (status_key packs them)");

template <int D>
class StepEffect {
 public:
  virtual ~StepEffect() = default;
  virtual const char* name() const = 0;

  // After P2G, before anything reads the grid (the symmetry plane folds its mirror's share here).
  virtual void after_to_grid(Grid<D>&, RowRange) {}
  // After the grid momentum update: nodal v^{n+1} and a are set (boundary conditions act here).
  virtual void after_grid_update(Grid<D>&, RowRange, double /*dt*/) {}
  // MUSL: after the points' momenta are scattered again, before the re-mapped velocity is formed.
  virtual void before_remap(Grid<D>&, RowRange) {}
  // MUSL: after the re-mapped nodal velocity v_remap is set.
  virtual void after_remap(Grid<D>&, RowRange) {}
  // After the constitutive update of every point.
  virtual StepStatus after_point_update(Particles<D>&, double /*dt*/) { return {}; }
  // At each sample time, for checks worth their cost only there.
  virtual StepStatus at_sample(const Particles<D>&) { return {}; }
};

}  // namespace mpmshock
