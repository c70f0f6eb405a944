// Effects that act on the grid or on all points once per step (or once per sample), as opposed to
// the per-point laws of model.hpp: the symmetry plane, heat conduction, the artificial heat flux,
// volumetric smoothing, spall's neighbourhood criterion, the 0 K check. Each is a small class that
// declares the slots it acts in (slots()) and overrides them, as a LAMMPS fix declares its
// masks; Simulation builds one list per slot once, at set-up, from what the effects declare, and
// step() calls each slot's list in the order the effects were made (simulation.cpp: effects_for).
// A slot gets the step's context: its points, grid, stencils and scratch. A virtual call per slot
// per step, never per point.
#pragma once

#include <cstddef>
#include <vector>

#include "mpmshock/grid.hpp"
#include "mpmshock/halo.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {

template <int D>
class SymmetryPlane;
struct HeatFluxRider;

// What the step hands its effects: everything a grid pass needs, and what one pass leaves for the
// step (the smoothed volume rate for the point update).
template <int D>
struct StepContext {
  Particles<D>& points;
  PointRange reached;  // the points the step computes (unreached.hpp)
  const StripBins& bins;
  Grid<D>& grid;
  StencilStore<D>& stencils;  // the step's shape weights (compute_stencils, before the effects)
  const Halo<D>& halo;
  const SymmetryPlane<D>* plane;  // symmetry = on, else null
  RowRange rows;                   // the node rows the step's points touch
  double dt;
  const std::vector<Vec<D>>* velocity = nullptr;  // the nodal velocity the points moved by (after_move)
  const double* volume_rate = nullptr;            // the smoothed tr L per point, set in after_move
  // What P2G carries for the artificial heat flux, set in before_to_grid (heat_flux_rider.hpp).
  const HeatFluxRider* heat_flux = nullptr;
};

// The slots of a step, in the order step() runs them (an effect declares them as a mask, slot_bit).
enum class StepSlot : unsigned {
  before_to_grid,      // before P2G (volumetric smoothing's pressure; the heat flux's point values)
  after_to_grid,       // after P2G, before anything reads the grid
  after_grid_update,   // after the grid momentum update: nodal v^{n+1} and a set, final after this
                       // slot (G2P sums v^{n+1} at the points, and they move with that sum)
  before_remap,        // MUSL: after the points' momenta are scattered again
  after_remap,         // MUSL: after the re-mapped nodal velocity is set
  after_move,          // after the velocity gradient, work and move
  after_point_update,  // after the constitutive update of every point
  at_sample,           // at each sample time, for checks worth their cost only there
  count
};
constexpr unsigned slot_bit(StepSlot s) { return 1u << static_cast<unsigned>(s); }
constexpr std::size_t kStepSlots = static_cast<std::size_t>(StepSlot::count);

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
  // The slots it acts in: slot_bit(...) | ...; step() calls only those.
  virtual unsigned slots() const = 0;

  virtual void before_to_grid(StepContext<D>&) {}
  // The symmetry plane folds its mirror's share here, then conduction and the heat flux act.
  virtual void after_to_grid(StepContext<D>&) {}
  // Boundary conditions act here.
  virtual void after_grid_update(StepContext<D>&) {}
  virtual void before_remap(StepContext<D>&) {}
  virtual void after_remap(StepContext<D>&) {}
  virtual void after_move(StepContext<D>&) {}
  // A check's failure is its status (the point's storage index); the step stops at the first.
  virtual StepStatus after_point_update(StepContext<D>&) { return {}; }
  virtual StepStatus at_sample(const Particles<D>&) { return {}; }
};

}  // namespace mpmshock
