#include "mpmshock/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <sstream>

#include "mpmshock/artificial_heat_flux.hpp"
#include "mpmshock/exact_sum.hpp"
#include "mpmshock/heat_conduction.hpp"
#include "mpmshock/point_update_kernels.hpp"
#include "mpmshock/shape.hpp"
#include "mpmshock/signals.hpp"
#include "mpmshock/spall_neighbourhood.hpp"
#include "mpmshock/symmetry_plane.hpp"
#include "mpmshock/transfer.hpp"
#include "mpmshock/volumetric_smoothing.hpp"
#include "mpmshock/zero_kelvin_check.hpp"
#include "slab_rows.hpp"

namespace mpmshock {
namespace {

template <int D, class Shape>
bool bin_points(StripBins& bins, const Particles<D>& pts, PointRange range, const GridGeometry<D>& g) {
  return bins.build<Shape>(pts.x, range, g);
}

// P2G by what the points carry: stress or not, smoothed pressure or the point's own, and the heat
// flux's nodal sums riding on it (heat_flux_rider.hpp) or not.
template <int D, class Shape, FluxSums Flux>
auto to_grid_kernel(bool stress, bool smoothing) {
  return stress ? (smoothing ? particles_to_grid<D, Shape, true, true, Flux> : particles_to_grid<D, Shape, true, false, Flux>)
                : (smoothing ? particles_to_grid<D, Shape, false, true, Flux> : particles_to_grid<D, Shape, false, false, Flux>);
}

// The kernels of a run, in two dispatches: the transfers by the shape function (and whether the
// points carry stress), the point update by the laws (point_update_kernels.hpp, compiled per
// equation of state). Every combination the variants of model.hpp allow is instantiated by
// std::visit, none is listed by hand; the two apart instantiate the sum of the choices, not their
// product (within the transfers, P2G is compiled for each of its 4 x 3 choices).
template <int D, class Shape>
void add_transfer_kernels(Kernels<D>& k, const Model& m, FluxSums flux) {
  const bool stress = m.has_strength(), smoothing = m.volumetric_smoothing;
  k.support = Shape::support;
  k.first_row = Shape::template first_row<D>;
  k.bin = bin_points<D, Shape>;
  k.stencils = compute_stencils<D, Shape>;
  k.to_grid = flux == FluxSums::three ? to_grid_kernel<D, Shape, FluxSums::three>(stress, smoothing)
              : flux == FluxSums::two ? to_grid_kernel<D, Shape, FluxSums::two>(stress, smoothing)
                                      : to_grid_kernel<D, Shape, FluxSums::none>(stress, smoothing);
  const bool musl = m.scheme == UpdateScheme::musl, blend = m.flip_fraction < 1.0;
  k.velocity_to_points = musl ? (blend ? grid_to_particles_velocity<D, Shape, true, true>
                                       : grid_to_particles_velocity<D, Shape, true, false>)
                              : (blend ? grid_to_particles_velocity<D, Shape, false, true>
                                       : grid_to_particles_velocity<D, Shape, false, false>);
  k.gradient_work_and_move =
      stress ? velocity_gradient_work_and_move<D, Shape, true> : velocity_gradient_work_and_move<D, Shape, false>;
}

// The heat flux's nodal sums the transfers carry: none without the flux, two with one material (its
// heat capacity is the nodal mass), three with several.
FluxSums flux_sums_for(const Scene& s, const Model& m) {
  if (!(m.heat_flux_beta > 0.0)) return FluxSums::none;
  return s.one_material() ? FluxSums::two : FluxSums::three;
}

template <int D>
Kernels<D> kernels_for(const Scene& s, const Model& m) {
  Kernels<D> k{};
  const FluxSums flux = flux_sums_for(s, m);
  std::visit([&](auto shape) { add_transfer_kernels<D, decltype(shape)>(k, m, flux); }, m.shape);
  std::visit([&](const auto& eos) { k.update_points = update_points_kernel<D, std::decay_t<decltype(eos)>>(m); },
             m.eos[1]);  // every body's equation of state is of one type
  return k;
}

// The step effects a scene calls for, in the order each slot runs them: the symmetry plane folds
// the grid before conduction and the heat flux read it; and the symmetry plane, for the passes that
// fold their own nodal sums.
template <int D>
struct StepEffects {
  std::vector<std::unique_ptr<StepEffect<D>>> list;
  const SymmetryPlane<D>* plane = nullptr;
};

template <int D, class Shape>
void add_grid_effects(StepEffects<D>& e, const Scene& s, const Model& m) {
  if (m.volumetric_smoothing) e.list.push_back(std::make_unique<VolumetricSmoothingEffect<D, Shape>>());
  if (m.conducts_heat()) {
    HeatConduction heat;
    heat.conductivity = m.conductivity;
    heat.one_material = s.one_material();
    for (std::size_t b = 0; b < kBodies; ++b) {
      heat.specific_heat[b] = s.material_of(Body(b)).specific_heat;  // (a window's slot unused without one)
      if (m.diffusivity[b] > 0.0) heat.relaxation_time[b] = m.cell_size * m.cell_size / (M_PI * M_PI * m.diffusivity[b]);
    }
    e.list.push_back(std::make_unique<HeatConductionEffect<D, Shape>>(*m.thermal, std::move(heat)));
  }
  if (m.heat_flux_beta > 0.0) {
    ArtificialHeatFlux flux;
    flux.beta = m.heat_flux_beta;
    flux.cell_size = m.cell_size;
    for (const Body b : {Body::flyer, Body::target, Body::window}) {
      flux.specific_heat[index_of(b)] = s.material_of(b).specific_heat;
      flux.sound_speed[index_of(b)] = m.reference_sound_speed(b);
    }
    flux.one_material = s.one_material();
    e.list.push_back(std::make_unique<ArtificialHeatFluxEffect<D, Shape>>(*m.thermal, std::move(flux)));
  }
  if (const Spall* spall = std::get_if<Spall>(&m.failure))
    if (spall->by_neighbourhood) e.list.push_back(std::make_unique<SpallNeighbourhoodEffect<D, Shape>>(*spall));
}

template <int D>
StepEffects<D> effects_for(const Scene& s, const Model& m, const GridGeometry<D>& grid) {
  StepEffects<D> e;
  if (m.symmetry_plane) {
    auto plane = std::make_unique<SymmetryPlane<D>>(grid);
    e.plane = plane.get();
    e.list.push_back(std::move(plane));
  }
  std::visit([&](auto shape) { add_grid_effects<D, decltype(shape)>(e, s, m); }, m.shape);
  if (m.thermal) e.list.push_back(std::make_unique<ZeroKelvinCheck<D>>(*m.thermal));
  return e;
}

template <int D>
void print_vector(std::ostream& out, const Vec<D>& v) {
  out << "(";
  for (int d = 0; d < D; ++d) out << (d ? ", " : "") << v[d];
  out << ")";
}

}  // namespace

template <int D>
void check_rank_count(const Scene& scene, const GridGeometry<D>& grid, int ranks) {
  const Model model(scene);
  const int support = std::visit([](auto shape) { return decltype(shape)::support; }, model.shape);
  Decomposition::check_ranks(strip_count(grid.whole()), ranks,
                             first_strip_end_needed(grid.whole(), model.symmetry_plane, support));
}

template <int D>
Simulation<D>::Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points, const Clock& clock,
                          const Comm& comm)
    : comm_(&comm), whole_geo_(grid.whole()), slabs_(strip_count(grid)), model_(scene), points_(std::move(points)),
      kernels_(kernels_for<D>(scene, model_)), unreached_(points_.size()), clock_(clock) {
  StepEffects<D> effects = effects_for<D>(scene, model_, grid);
  effects_ = std::move(effects.list);
  plane_ = effects.plane;
  for (const auto& e : effects_)  // each slot's list, in the order the effects were made
    for (std::size_t slot = 0; slot < kStepSlots; ++slot)
      if (e->slots() & slot_bit(StepSlot(slot))) slot_effects_[slot].push_back(e.get());
  // Each rank is given a share of the points (one rank: all of them), in id order.
  total_points_ = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(points_.size())));
  if (model_.symmetry_plane && std::find(points_.body.begin(), points_.body.end(), Body::flyer) != points_.body.end())
    throw std::logic_error("symmetry = on simulates the target's points alone (build_initial_state gives them)");
  points_.work.assign(points_.size(), 0.0);  // scratch of every step, however the points were made
  if (!comm.parallel()) grid_ = Grid<D>(whole_geo_.holding(first_row_held(), whole_geo_.ny));
  if (comm.parallel()) {
    // Slabs of as many points each (the first step's end re-balances them by what it computes);
    // then every point moves to the rank whose slab holds it.
    std::vector<std::int64_t> work(static_cast<std::size_t>(slabs_.strips()), 0);
    for (std::size_t p = 0; p < points_.size(); ++p) ++work[static_cast<std::size_t>(strip_of(points_.x[p][1]))];
    comm.sum(work.data(), static_cast<int>(work.size()));
    take_slab(Decomposition::balanced(work, comm.size(), first_strip_end_needed()));
    redistribute();
  }
  unreached_ = UnreachedMaterial<D>(total_points_);
  if (model_.skip_unreached && clock.unreached_tail != Clock::kNoneSaved)
    unreached_ = UnreachedMaterial<D>(scene, model_, points_, clock.unreached_head, clock.unreached_tail, comm);
  remember_unreached();
}

template <int D>
Simulation<D>::Simulation(const Scene& scene, const GridGeometry<D>& grid, Particles<D> points, const Comm& comm)
    : Simulation(scene, grid, std::move(points), Clock{}, comm) {
  if (model_.skip_unreached) unreached_ = UnreachedMaterial<D>(scene, model_, points_, comm);
  remember_unreached();
  clock_.max_signal = comm.max(initial_signal_speed(points_, model_));
}

template <int D>
void Simulation<D>::remember_unreached() {
  clock_.unreached_head = unreached_.head();
  clock_.unreached_tail = unreached_.tail();
}

namespace {

// A status as one number whose maximum over the ranks is the failure of the lowest id (then the
// lowest code), as one process meets it first; no failure is -inf. Ids are below 2^32, so the key
// is exact in a double; an unknown point (kNoPoint) counts as id 2^40.
constexpr double kUnknownPoint = 1099511627776.0;
constexpr double kCodes = StepStatus::kCodes;
static_assert((kUnknownPoint + 1.0) * kCodes <= 9007199254740992.0, "a status key must be exact in a double (2^53)");
double status_key(const StepStatus& s) {
  if (s.ok()) return -std::numeric_limits<double>::infinity();
  const double id = s.point == kNoPoint ? kUnknownPoint : static_cast<double>(s.point);
  return -(id * kCodes + static_cast<double>(s.code));
}
StepStatus status_of_key(double key) {
  if (key == -std::numeric_limits<double>::infinity()) return {};
  const double k = -key, id = std::floor(k / kCodes);
  return {static_cast<StepStatus::Code>(static_cast<int>(k - kCodes * id)),
          id == kUnknownPoint ? kNoPoint : static_cast<std::size_t>(id)};
}

}  // namespace

template <int D>
StepStatus Simulation<D>::agree(const StepStatus& mine) const {
  if (!comm_->parallel()) return mine;
  return status_of_key(comm_->max(status_key(mine)));
}

template <int D>
StepStatus Simulation<D>::step(double dt) {
  const auto started = std::chrono::steady_clock::now();
  const double mpi_before = comm_->traffic().seconds;
  if (comm_->parallel()) rebalance();                                  // MPI: slabs to the work
  const PointRange reached = unreached_.computed(points_);             // all but what nothing has reached
  // Off the grid on one rank: a point left it. Off the rows held here (an MPI rank's slab, or the
  // ghost rows below a symmetry plane): moves and restarts check this, so a bug. Every rank stops (main).
  if (!kernels_.bin(bins_, points_, reached, grid_.geo)) {             // strips for race-free scatter
    if (comm_->parallel()) throw std::logic_error("a material point outside the grid's rows at binning");
    return {StepStatus::Code::left_grid, kNoPoint};
  }
  if (!bins_within_slab()) throw std::logic_error("a material point outside the grid rows held here at binning");
  const bool musl = model_.scheme == UpdateScheme::musl;
  StepContext<D> c{points_, reached, bins_, grid_, stencils_, halo_, plane_, bins_.rows(), dt};
  auto run = [&](StepSlot slot, void (StepEffect<D>::*act)(StepContext<D>&)) {
    for (StepEffect<D>* e : in_slot(slot)) (e->*act)(c);
  };
  grid_.reset(c.rows);                                                 // reset grid
  kernels_.stencils(points_, reached, grid_.geo, stencils_);           // N_ip, grad N_ip
  run(StepSlot::before_to_grid, &StepEffect<D>::before_to_grid);       //   (smoothing: (P + q)-bar_p; heat flux: T_p, C_p r_p, C_p T_p)
  kernels_.to_grid(points_, bins_, grid_, stencils_, halo_, c.heat_flux);  // P2G: m_i, p_i, f_i (heat flux: C_i r_i, C_i T_i)
  run(StepSlot::after_to_grid, &StepEffect<D>::after_to_grid);         //   (plane's fold; conduction, heat flux: E_p)
  update_grid_momentum(grid_, c.rows, dt);                             // a_i, v_i^{n+1}
  run(StepSlot::after_grid_update, &StepEffect<D>::after_grid_update); //   (boundary conditions)
  kernels_.velocity_to_points(points_, reached, bins_, grid_, stencils_, halo_, dt,  // G2P: FLIP (/PIC) v_p
                              model_.flip_fraction, v_pic_);           //   (MUSL: re-map m_p v_p)
  if (musl) {
    run(StepSlot::before_remap, &StepEffect<D>::before_remap);         //   (plane's fold)
    remap_grid_velocity(grid_, c.rows);                                // MUSL: v~_i
    run(StepSlot::after_remap, &StepEffect<D>::after_remap);
  }
  c.velocity = musl ? &grid_.v_remap : &grid_.v;
  sum_step_velocities(grid_, c.rows, *c.velocity, dt);                 // v^n_i + u_i
  const std::size_t left = kernels_.gradient_work_and_move(            // L_p, work_p, x_p
      points_, reached, grid_, stencils_, *c.velocity, v_pic_, dt);
  unreached_.advance(points_, dt);                                     //   the rest: x_p += v0 dt
  run(StepSlot::after_move, &StepEffect<D>::after_move);               //   (smoothing: tr L_p, work_p)
  StressUpdateResult update = kernels_.update_points(points_, reached, model_, dt, c.volume_rate);  // E, F, s, P, q
  StepStatus effect;  // the effects' checks (spall's neighbourhood opens points), agreed with the step's
  for (StepEffect<D>* e : in_slot(StepSlot::after_point_update))
    if (effect = with_id(e->after_point_update(c)); !effect.ok()) break;
  const StepStatus failed = agree_on(update, left, effect);            // the ranks' maxima and failures
  clock_.time += dt;
  ++clock_.steps;
  clock_.max_signal = std::max(update.max_signal, unreached_.signal());
  if (!failed.ok()) return failed;
  unreached_.follow(points_);                                          // compute what the step reached
  if (comm_->parallel()) migrate();                                    // MPI: points into their new slabs
  remember_unreached();
  busy_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() -
                   (comm_->traffic().seconds - mpi_before);
  return {};
}

template <int D>
bool Simulation<D>::bins_within_slab() const {
  const RowRange rows = bins_.rows();
  return rows.end <= rows.begin ||
         (rows.begin >= grid_.geo.row0 && rows.end <= grid_.geo.row0 + grid_.geo.rows_held());
}

template <int D>
void Simulation<D>::settle() {
  // Exact: the same bits however the points are shared between threads and ranks.
  ExactSum sum;
  const std::vector<double>& own = points_.work_mismatch;
  std::size_t p = 0;
  for (; p + 4 <= own.size(); p += 4) sum.add_lanes(Lanes{own[p], own[p + 1], own[p + 2], own[p + 3]});
  for (; p < own.size(); ++p) sum.add(own[p]);
  comm_->sum(&sum, 1);
  clock_.work_mismatch = clock_.work_mismatch_before + sum.value();
}

template <int D>
StepStatus Simulation<D>::agree_on(StressUpdateResult& update, std::size_t left, const StepStatus& effect) {
  const auto id_of = [&](std::size_t p) { return p < points_.size() ? static_cast<std::size_t>(points_.id[p]) : p; };
  const std::size_t bad = id_of(update.first_bad), outside = id_of(left);
  if (!comm_->parallel()) {
    if (bad != kNoPoint) return {StepStatus::Code::bad_state, bad};
    if (outside != kNoPoint) return {StepStatus::Code::left_grid, outside};
    return effect;
  }
  // A bad state before a point off the grid before an effect's failure, each of the lowest id.
  double agreed[5] = {update.max_signal, status_key({StepStatus::Code::bad_state, bad}),
                      status_key({StepStatus::Code::left_grid, outside}), status_key(effect),
                      static_cast<double>(stop_signal())};
  if (bad == kNoPoint) agreed[1] = -std::numeric_limits<double>::infinity();
  if (outside == kNoPoint) agreed[2] = -std::numeric_limits<double>::infinity();
  comm_->max(agreed, 5);
  update.max_signal = agreed[0];
  stop_signal_ = static_cast<int>(agreed[4]);
  for (int k = 1; k <= 3; ++k)
    if (const StepStatus s = status_of_key(agreed[k]); !s.ok()) return s;
  return {};
}

template <int D>
Grid<D> Simulation<D>::gathered_grid(RowRange& rows) const {
  const RowRange mine = bins_.rows();
  std::vector<char> out(2 * sizeof(int));
  std::memcpy(out.data(), &mine.begin, sizeof(int));
  std::memcpy(out.data() + sizeof(int), &mine.end, sizeof(int));
  if (mine.end > mine.begin) {
    const std::size_t b = grid_.geo.row_start(mine.begin), e = grid_.geo.row_start(mine.end);
    const std::size_t at = out.size();
    out.resize(at + (e - b) * (sizeof(double) + sizeof(Vec<D>)));
    std::memcpy(out.data() + at, grid_.m.data() + b, (e - b) * sizeof(double));
    std::memcpy(out.data() + at + (e - b) * sizeof(double), grid_.v.data() + b, (e - b) * sizeof(Vec<D>));
  }
  const std::vector<std::vector<char>> parts = comm_->gather(out);
  if (!comm_->root()) return Grid<D>{};
  Grid<D> whole(whole_geo_);  // rows no rank used are empty: m = 0, v = 0, as one process leaves them
  rows = {whole_geo_.ny, 0};
  for (const std::vector<char>& part : parts) {
    RowRange r;
    std::memcpy(&r.begin, part.data(), sizeof(int));
    std::memcpy(&r.end, part.data() + sizeof(int), sizeof(int));
    if (r.end <= r.begin) continue;
    rows = {std::min(rows.begin, r.begin), std::max(rows.end, r.end)};
    const std::size_t b = whole.geo.row_start(r.begin), e = whole.geo.row_start(r.end);
    std::memcpy(whole.m.data() + b, part.data() + 2 * sizeof(int), (e - b) * sizeof(double));
    std::memcpy(static_cast<void*>(whole.v.data() + b), part.data() + 2 * sizeof(int) + (e - b) * sizeof(double),
                (e - b) * sizeof(Vec<D>));
  }
  if (rows.end <= rows.begin) rows = {};
  return whole;
}

template <int D>
std::size_t Simulation<D>::points_beyond_eos_fit() const {
  const double J_fit[kBodies] = {model_.eos_fit_limit(Body::flyer), model_.eos_fit_limit(Body::target),
                                 model_.eos_fit_limit(Body::window)};
  std::int64_t n = 0;
#pragma omp parallel for schedule(static) reduction(+ : n)
  for (std::size_t p = 0; p < points_.size(); ++p)
    n += points_.material_J(p) < J_fit[static_cast<std::size_t>(points_.body[p])] ? 1 : 0;
  return static_cast<std::size_t>(comm_->sum(n));
}

template <int D>
StepStatus Simulation<D>::with_id(StepStatus s) const {
  if (!s.ok() && s.point < points_.size()) s.point = points_.id[s.point];
  return s;
}

template <int D>
StepStatus Simulation<D>::check_at_sample() {
  for (StepEffect<D>* e : in_slot(StepSlot::at_sample))
    if (const StepStatus s = agree(with_id(e->at_sample(points_))); !s.ok()) return s;
  return {};
}

template <int D>
std::string Simulation<D>::describe(const StepStatus& status) const {
  if (status.ok()) return "ok";
  std::ostringstream out;
  const Particles<D>& pts = points_;
  const std::size_t p = status.point < kNoPoint ? index_of_id(pts, static_cast<std::uint32_t>(status.point)) : kNoPoint;
  // The id the outputs give the point: with symmetry = on the mirrored flyer's come first.
  auto id = [&](std::size_t q) { return pts.id[q] + (model_.symmetry_plane ? total_points_ : 0); };
  out << "step " << clock_.steps << ", t = " << clock_.time << " s: ";
  if (status.point == kNoPoint) {
    out << "a material point is outside the grid";
    return comm_->root() ? out.str() : std::string();
  }
  if (p < pts.size()) describe_point(out, status.code, p, id(p));
  else out.str("");  // another rank holds the point and tells rank 0
  std::string text = out.str();
  if (!comm_->parallel()) return text;
  const std::vector<std::vector<char>> told = comm_->gather(std::vector<char>(text.begin(), text.end()));
  for (const std::vector<char>& t : told)
    if (!t.empty()) return std::string(t.begin(), t.end());
  return std::string();
}

template <int D>
void Simulation<D>::describe_point(std::ostream& out, StepStatus::Code code, std::size_t p, std::size_t id) const {
  const Particles<D>& pts = points_;
  const double J = pts.J(p);
  switch (code) {
    case StepStatus::Code::left_grid:
      out << "material point " << id << " left the grid (y range " << whole_geo_.y_min << " .. "
          << whole_geo_.y_max() << " m); enlarge grid_margin";
      break;
    case StepStatus::Code::bad_state:
      out << "material point " << id << " reached a non-physical state";
      if (!(J > 0.0)) out << " (J = det F <= 0: the point turned inside out)";
      else if (!(J > model_.limiting_compression(pts.body[p])))
        out << " (compressed past its equation of state's limit J = " << model_.limiting_compression(pts.body[p]) << ")";
      else if (!std::isfinite(pts.P[p]) || !std::isfinite(pts.E[p])) out << " (non-finite pressure or energy)";
      else out << " (runaway speed above " << model_.speed_limit << " m/s)";
      break;
    case StepStatus::Code::below_zero_kelvin:
      out << "material point " << id << " reached a non-physical state (temperature "
          << model_.thermal->energy_temperature(pts, p) << " K: its internal energy " << pts.E[p]
          << " J/kg is below the 0 K isotherm at J = " << J << "); at ";
      print_vector(out, pts.x[p]);
      out << " m with pressure " << pts.P[p] << " Pa. Typical cause: a shock without enough artificial viscosity";
      return;
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
}

template class Simulation<2>;
template class Simulation<3>;
template void check_rank_count<2>(const Scene&, const GridGeometry<2>&, int);
template void check_rank_count<3>(const Scene&, const GridGeometry<3>&, int);

}  // namespace mpmshock
