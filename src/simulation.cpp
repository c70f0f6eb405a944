#include "mpmshock/simulation.hpp"

#include <cmath>
#include <sstream>

#include "mpmshock/shape.hpp"
#include "mpmshock/transfer.hpp"

namespace mpmshock {
namespace {

template <class Shape>
bool bin_points(StripBins& bins, const Particles& p, const GridGeometry& g) {
  return bins.build<Shape>(p.y, g);
}

template <class Shape>
TransferKernels kernels_for_shape(bool strength, UpdateScheme scheme) {
  TransferKernels k{};
  k.bin = bin_points<Shape>;
  k.to_grid = strength ? particles_to_grid<Shape, true> : particles_to_grid<Shape, false>;
  k.velocity_to_points = scheme == UpdateScheme::musl ? grid_to_particles_velocity<Shape, true>
                                                      : grid_to_particles_velocity<Shape, false>;
  k.gradient_work_and_move = strength ? velocity_gradient_work_and_move<Shape, true>
                                      : velocity_gradient_work_and_move<Shape, false>;
  return k;
}

TransferKernels kernels_for(const Scene& s) {
  switch (s.shape_function) {
    case ShapeFunction::gimp: return kernels_for_shape<GimpShape>(s.effects.plasticity, s.update_scheme);
    case ShapeFunction::bspline2: return kernels_for_shape<QuadraticBSplineShape>(s.effects.plasticity, s.update_scheme);
    case ShapeFunction::bilinear: break;
  }
  return kernels_for_shape<BilinearShape>(s.effects.plasticity, s.update_scheme);
}

}  // namespace

Simulation::Simulation(const Scene& scene, const GridGeometry& grid, Particles points, const Clock& clock)
    : model_(scene), points_(std::move(points)), grid_(grid), kernels_(kernels_for(scene)),
      update_stress_(select_stress_update(strength_of(scene), scene.effects.artificial_viscosity)),
      scheme_(scene.update_scheme), cfl_(scene.cfl), clock_(clock) {
  points_.work.assign(points_.size(), 0.0);  // scratch of every step, however the points were made
}

Simulation::Simulation(const Scene& scene, const GridGeometry& grid, Particles points)
    : Simulation(scene, grid, std::move(points), Clock{}) {
  clock_.max_signal = initial_signal_speed(points_, model_);
}

StepStatus Simulation::step(double dt) {
  if (!kernels_.bin(bins_, points_, grid_.geo))                   // strips for race-free scatter
    return {StepStatus::Code::left_grid, points_.size()};  // moves check this; here only a bad restart
  const int rows_begin = bins_.row_begin(), rows_end = bins_.row_end();
  grid_.reset(rows_begin, rows_end);
  kernels_.to_grid(points_, bins_, grid_);                        // P2G: m_i, p_i, f_i
  update_grid_momentum(grid_, rows_begin, rows_end, dt);          // a_i, v_i^{n+1}
  kernels_.velocity_to_points(points_, bins_, grid_, dt);         // G2P: FLIP v_p (MUSL: re-map p_i)
  const bool musl = scheme_ == UpdateScheme::musl;
  if (musl) remap_grid_velocity(grid_, rows_begin, rows_end);     // MUSL: v~_i = p_i / m_i
  const std::size_t left = kernels_.gradient_work_and_move(       // L_p, work_p, x_p
      points_, grid_, musl ? grid_.px : grid_.vx, musl ? grid_.py : grid_.vy, dt);
  const StressUpdateResult stress = update_stress_(points_, model_, dt);  // E, F, s, P, q
  clock_.time += dt;
  ++clock_.steps;
  clock_.max_signal = stress.max_signal;
  if (stress.first_bad != ~std::size_t{0}) return {StepStatus::Code::bad_state, stress.first_bad};
  if (left != kNoPoint) return {StepStatus::Code::left_grid, left};
  return {};
}

std::string Simulation::describe(const StepStatus& status) const {
  if (status.ok()) return "ok";
  std::ostringstream out;
  const Particles& p = points_;
  const std::size_t q = status.point;
  out << "step " << clock_.steps << ", t = " << clock_.time << " s: ";
  if (q >= p.size()) {
    out << "a material point is outside the grid";
    return out.str();
  }
  const double J = p.J(q);
  switch (status.code) {
    case StepStatus::Code::left_grid:
      out << "material point " << p.id[q] << " left the grid (y range " << grid_.geo.y_min << " .. "
          << grid_.geo.y_max() << " m); enlarge grid_margin";
      break;
    case StepStatus::Code::bad_state:
      out << "material point " << p.id[q] << " reached a non-physical state";
      if (!(J > 0.0)) out << " (J = det F <= 0: the point turned inside out)";
      else if (!(J > model_.eos.limiting_compression())) out << " (compressed past the Hugoniot's limit J = 1 - 1/s)";
      else if (!std::isfinite(p.pressure[q]) || !std::isfinite(p.energy[q])) out << " (non-finite pressure or energy)";
      else out << " (runaway speed above " << model_.speed_limit << " m/s)";
      break;
    case StepStatus::Code::ok: break;
  }
  out << "\n  position (" << p.x[q] << ", " << p.y[q] << ") m, velocity (" << p.vx[q] << ", " << p.vy[q]
      << ") m/s\n  J = " << J << ", density = " << p.density(q) << " kg/m3, pressure = " << p.pressure[q]
      << " Pa, q = " << p.viscosity[q] << " Pa, energy = " << p.energy[q] << " J/kg\n  velocity gradient ("
      << p.Lxx[q] << ", " << p.Lxy[q] << "; " << p.Lyx[q] << ", " << p.Lyy[q] << ") 1/s";
  return out.str();
}

}  // namespace mpmshock
