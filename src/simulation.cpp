#include "mpmshock/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <sstream>

#include "mpmshock/shape.hpp"
#include "mpmshock/symmetry_plane.hpp"
#include "mpmshock/transfer.hpp"
#include "mpmshock/zero_kelvin_check.hpp"

namespace mpmshock {
namespace {

template <int D, class Shape>
bool bin_points(StripBins& bins, const Particles<D>& pts, PointRange range, const GridGeometry<D>& g) {
  return bins.build<Shape>(pts.x, range, g);
}

// The kernels for one choice of shape function and laws: every combination the variants of
// model.hpp allow is instantiated by std::visit, none is listed by hand.
template <int D, class Shape, class Eos, class Strength, class Viscosity, class Failure>
Kernels<D> kernels_for(UpdateScheme scheme, double flip_fraction, bool conduction) {
  constexpr bool stress = Strength::has_stress;
  Kernels<D> k{};
  k.bin = bin_points<D, Shape>;
  k.to_grid = particles_to_grid<D, Shape, stress>;
  const bool musl = scheme == UpdateScheme::musl, blend = flip_fraction < 1.0;
  k.velocity_to_points = musl ? (blend ? grid_to_particles_velocity<D, Shape, true, true>
                                       : grid_to_particles_velocity<D, Shape, true, false>)
                              : (blend ? grid_to_particles_velocity<D, Shape, false, true>
                                       : grid_to_particles_velocity<D, Shape, false, false>);
  k.gradient_work_and_move = velocity_gradient_work_and_move<D, Shape, stress>;
  k.update_points = update_all_points<D, Eos, Strength, Viscosity, Failure>;
  if (conduction) k.conduct = conduct_heat<D, Shape>;
  return k;
}

template <int D>
Kernels<D> kernels_for(const Model& m) {
  return std::visit(
      [&](auto shape, const auto& eos, const auto& strength, const auto& viscosity, const auto& failure) {
        return kernels_for<D, decltype(shape), std::decay_t<decltype(eos)>, std::decay_t<decltype(strength)>,
                           std::decay_t<decltype(viscosity)>, std::decay_t<decltype(failure)>>(
            m.scheme, m.flip_fraction, m.conducts_heat());
      },
      m.shape, m.eos, m.strength, m.viscosity, m.failure);
}

// The step effects a model calls for, in the order their slots run.
template <int D>
std::vector<std::unique_ptr<StepEffect<D>>> effects_for(const Model& m, const GridGeometry<D>& grid) {
  std::vector<std::unique_ptr<StepEffect<D>>> effects;
  if (m.symmetry_plane) effects.push_back(std::make_unique<SymmetryPlane<D>>(grid));
  if (m.thermal) effects.push_back(std::make_unique<ZeroKelvinCheck<D>>(*m.thermal));
  return effects;
}

template <int D>
void print_vector(std::ostream& out, const Vec<D>& v) {
  out << "(";
  for (int d = 0; d < D; ++d) out << (d ? ", " : "") << v[d];
  out << ")";
}

}  // namespace

template <int D>
Simulation<D>::Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points, const Clock& clock)
    : model_(scene), points_(std::move(points)), grid_(grid), kernels_(kernels_for<D>(model_)),
      effects_(effects_for<D>(model_, grid)), unreached_(points_.size()), clock_(clock) {
  points_.work.assign(points_.size(), 0.0);  // scratch of every step, however the points were made
  for (const auto& e : effects_)
    if (const auto* plane = dynamic_cast<const SymmetryPlane<D>*>(e.get())) plane_ = plane;
  if (model_.symmetry_plane && std::find(points_.body.begin(), points_.body.end(), Body::flyer) != points_.body.end())
    throw std::logic_error("symmetry = on simulates the target's points alone (build_initial_state gives them)");
  if (model_.skip_unreached && clock.unreached_tail != Clock::kNoneSaved)
    unreached_ = UnreachedMaterial<D>(scene, model_, points_, clock.unreached_head, clock.unreached_tail);
  remember_unreached();
  heat_.conductivity = model_.conductivity;
  heat_.specific_heat = scene.material.specific_heat;
  if (model_.conducts_heat())
    heat_.relaxation_time = model_.cell_size * model_.cell_size / (M_PI * M_PI * model_.diffusivity);
}

template <int D>
Simulation<D>::Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points)
    : Simulation(scene, grid, std::move(points), Clock{}) {
  if (model_.skip_unreached) unreached_ = UnreachedMaterial<D>(scene, model_, points_);
  remember_unreached();
  clock_.max_signal = initial_signal_speed(points_, model_);
}

template <int D>
void Simulation<D>::remember_unreached() {
  clock_.unreached_head = unreached_.head();
  clock_.unreached_tail = unreached_.tail();
}

template <int D>
StepStatus Simulation<D>::step(double dt) {
  const PointRange reached = unreached_.computed();                    // all but what nothing has reached
  if (!kernels_.bin(bins_, points_, reached, grid_.geo))               // strips for race-free scatter
    return {StepStatus::Code::left_grid, points_.size()};             // moves check this; here only a bad restart
  const RowRange rows = bins_.rows();
  const bool musl = model_.scheme == UpdateScheme::musl;
  grid_.reset(rows);                                                   // reset grid
  kernels_.to_grid(points_, bins_, grid_, stencils_);                  // P2G: m_i, p_i, f_i (and N_ip)
  for (auto& e : effects_) e->after_to_grid(grid_, rows);              //   (symmetry plane: the mirror's share)
  if (kernels_.conduct)                                                //   heat conduction: E_p
    kernels_.conduct(points_, reached, bins_, grid_, stencils_, *model_.thermal, heat_, plane_, dt);
  update_grid_momentum(grid_, rows, dt);                               // a_i, v_i^{n+1}
  for (auto& e : effects_) e->after_grid_update(grid_, rows, dt);      //   (boundary conditions)
  kernels_.velocity_to_points(points_, reached, bins_, grid_, stencils_, dt,  // G2P: FLIP (/PIC) v_p (MUSL: re-map)
                              model_.flip_fraction);
  if (musl) {
    for (auto& e : effects_) e->before_remap(grid_, rows);
    remap_grid_velocity(grid_, rows);                                  // MUSL: v~_i
    for (auto& e : effects_) e->after_remap(grid_, rows);
  }
  const std::size_t left = kernels_.gradient_work_and_move(            // L_p, work_p, x_p
      points_, reached, grid_, stencils_, musl ? grid_.v_remap : grid_.v, dt);
  unreached_.advance(points_, dt);                                     //   the rest: x_p += v0 dt
  const StressUpdateResult update = kernels_.update_points(points_, reached, model_, dt);  // E, F, s, P, q
  clock_.time += dt;
  ++clock_.steps;
  clock_.max_signal = std::max(update.max_signal, unreached_.signal());
  clock_.work_mismatch += update.work_mismatch.value();
  if (update.first_bad != ~std::size_t{0}) return {StepStatus::Code::bad_state, update.first_bad};
  if (left != kNoPoint) return {StepStatus::Code::left_grid, left};
  for (auto& e : effects_)
    if (const StepStatus s = e->after_point_update(points_, dt); !s.ok()) return s;
  unreached_.follow(points_);                                          // compute what the step reached
  remember_unreached();
  return {};
}

template <int D>
StepStatus Simulation<D>::check_at_sample() {
  for (auto& e : effects_)
    if (const StepStatus s = e->at_sample(points_); !s.ok()) return s;
  return {};
}

template <int D>
std::string Simulation<D>::describe(const StepStatus& status) const {
  if (status.ok()) return "ok";
  std::ostringstream out;
  const Particles<D>& pts = points_;
  const std::size_t p = status.point;
  // The id the outputs give the point: with symmetry = on the mirrored flyer's come first.
  auto id = [&](std::size_t q) { return pts.id[q] + (model_.symmetry_plane ? pts.size() : 0); };
  out << "step " << clock_.steps << ", t = " << clock_.time << " s: ";
  if (p >= pts.size()) {
    out << "a material point is outside the grid";
    return out.str();
  }
  const double J = pts.J(p);
  switch (status.code) {
    case StepStatus::Code::left_grid:
      out << "material point " << id(p) << " left the grid (y range " << grid_.geo.y_min << " .. "
          << grid_.geo.y_max() << " m); enlarge grid_margin";
      break;
    case StepStatus::Code::bad_state:
      out << "material point " << id(p) << " reached a non-physical state";
      if (!(J > 0.0)) out << " (J = det F <= 0: the point turned inside out)";
      else if (!(J > model_.limiting_compression())) out << " (compressed past the Hugoniot's limit J = 1 - 1/s)";
      else if (!std::isfinite(pts.P[p]) || !std::isfinite(pts.E[p])) out << " (non-finite pressure or energy)";
      else out << " (runaway speed above " << model_.speed_limit << " m/s)";
      break;
    case StepStatus::Code::below_zero_kelvin:
      out << "material point " << id(p) << " reached a non-physical state (temperature "
          << model_.thermal->temperature(pts.material_J(p), pts.thermal_energy(p)) << " K: its internal energy " << pts.E[p]
          << " J/kg is below the 0 K isotherm at J = " << J << "); at ";
      print_vector(out, pts.x[p]);
      out << " m with pressure " << pts.P[p] << " Pa. Typical cause: a shock without enough artificial viscosity";
      return out.str();
    case StepStatus::Code::ok: break;
  }
  out << "\n  position ";
  print_vector(out, pts.x[p]);
  out << " m, velocity ";
  print_vector(out, pts.v[p]);
  out << " m/s\n  J = " << J << ", density = " << pts.density(p) << " kg/m3, pressure = " << pts.P[p]
      << " Pa, q = " << pts.q[p] << " Pa, energy = " << pts.E[p] << " J/kg\n  velocity gradient (";
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) out << (j ? ", " : (i ? "; " : "")) << pts.L[p](i, j);
  out << ") 1/s";
  return out.str();
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace mpmshock
