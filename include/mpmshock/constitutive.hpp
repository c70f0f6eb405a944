// The constitutive update of a material point from its velocity gradient L and the work the
// step's nodal forces did on it (see velocity_gradient_work_and_move): internal energy E += work
// (compression, plastic and viscous work alike, exactly what the kinetic energy lost);
// F <- (I + dt L) F; the deviatoric stress by the strength law; the pressure from the equation of
// state at the new volume and energy; the artificial viscous pressure q. One function per point,
// pure and grid-free, over the law types the model chose, so tests drive it directly.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "mpmshock/exact_sum.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

template <int D>
struct PointState {
  Mat<D> L;     // in: the velocity gradient
  double work;  // in: the work of the step's forces [J/kg]
  Mat<D> F;
  double E, P, q;
  Deviator<D> s, alpha;
  double eps_p;
  double failure_J = 0.0;      // in/out with spall: 0 while intact, else the J it began to open at
  double damage = 0.0;         // in/out with spall: 0 intact ... 1 separated (spall.hpp)
  double E_stored = 0.0;       // in/out: the cold work stored in E [J/kg]
  double plastic_heat = 0.0;   // in/out: the plastic work turned to heat [J/kg] (temperature_model = paper)
  double work_mismatch = 0.0;  // out: work minus the trapezoid-rule work of the point's own deformation
  // in: the rate of volume change F follows, tr L (NaN) unless volumetric smoothing gives its own
  // (volumetric_smoothing.hpp); the deviatoric rate is always L's.
  double volume_rate = std::numeric_limits<double>::quiet_NaN();
};

// The rate of volume change F follows: the smoothed one where there is one, else tr L.
template <int D>
inline double volume_rate_of(const PointState<D>& st) {
  return std::isnan(st.volume_rate) ? trace(st.L) : st.volume_rate;
}

// The energy-consistency diagnostic of a point's step: the work it was given (the exact work of the
// nodal forces) minus the work of its own deformation by the trapezoid rule,
// -(1/2)((P + q)^n + (P + q)^{n+1}) dV + V^{n+1/2} (1/2)(s^n + s^{n+1}) : L dt, per unit mass.
// Summed over points and steps (times m) it is the internal energy the points hold that their own
// compression did not give them (conservation.csv, work_mismatch).
template <int D>
inline void own_work_mismatch(PointState<D>& st, double rho0, double J_before, double J, double pq_before,
                              const Deviator<D>& s_before, double dt) {
  double own = -0.5 * (pq_before + st.P + st.q) * (J - J_before) / rho0;
  own += 0.25 * dt * (J_before + J) / rho0 * (contract(s_before, st.L) + contract(st.s, st.L));
  st.work_mismatch = st.work - own;
}

// One point, one step. Returns the point's signal speed (for the next time step), or a negative
// number if the new state is not physical (J <= the EOS limit, or a non-finite result). Inlined
// into the loop over points: as a call it costs 40 % more instructions per point.
// `taylor_quinney` is the share of plastic work that becomes heat; the rest goes to E_stored.
template <int D, class Eos, class Strength, class Viscosity, class Failure = NoFailure>
[[gnu::always_inline]] inline double update_point(PointState<D>& st, const Eos& eos, const Strength& strength,
                                                  const Viscosity& viscosity, double h, double dt,
                                                  [[maybe_unused]] const Failure& failure = {},
                                                  [[maybe_unused]] double taylor_quinney = 1.0) {
  const StrainRate<D> rate = strain_rate(st.L);
  const double volume_rate = volume_rate_of(st);
  const double volume_shift = (volume_rate - trace(st.L)) / D;  // 0 without smoothing
  const double J_before = det(st.F), pq_before = st.P + st.q;
  [[maybe_unused]] const Deviator<D> s_before = st.s;

  // Energy: the exact work of the step's nodal forces on the point (compression, plastic and
  // viscous work alike), which is what the points' kinetic energy lost.
  st.E += st.work;

  // Kinematics: F^{n+1} = (I + dt L) F^n, L with the volume rate's trace.
  Mat<D> A;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) A(i, j) = i == j ? 1.0 + dt * (st.L(i, j) + volume_shift) : dt * st.L(i, j);
  st.F = product(A, st.F);
  const double J = det(st.F);
  if (!(J > eos.limiting_compression())) return -1.0;
  // A failed point's material keeps the volume it failed at while the space around it opens.
  double J_material = J;
  if constexpr (Failure::active)
    if (st.failure_J > 0.0) J_material = std::min(J, st.failure_J);
  const double rho = eos.rho0() / J_material;

  if constexpr (Strength::has_stress) {
    const double plastic_work = strength.update(st.s, st.alpha, st.eps_p, rate, dt, J_material, st.E - st.E_stored, st.P);
    st.E_stored += (1.0 - taylor_quinney) * plastic_work / rho;
    st.plastic_heat += taylor_quinney * plastic_work / rho;
  }

  // Pressure from the new volume and energy; artificial viscosity from this step's compression rate.
  const auto eos_state = eos.state(J_material, st.E);
  st.P = eos_state.pressure;
  if (!std::isfinite(st.E) || !std::isfinite(st.P)) return -1.0;
  if constexpr (Failure::active) {
    // Opens when its tension exceeds the strength: no shear from then on, its tension held at the
    // strength until it has separated, none after.
    if (st.failure_J == 0.0 && failure.exceeded(st.s, st.P)) st.failure_J = J;
    if (st.failure_J > 0.0) {
      st.damage = failure.damage(st.failure_J, J, st.damage);
      st.P = failure.pressure(st.P, st.damage);
      st.s = {};
      st.alpha = {};
    }
  }
  const double c2_bulk = std::max(eos_state.sound_speed_squared, 0.0);
  double c2 = c2_bulk;  // longitudinal: bulk plus shear
  if constexpr (Strength::has_stress) c2 += (4.0 / 3.0) * strength.shear_modulus / rho;
  if constexpr (!Viscosity::active) {
    st.q = 0.0;
    own_work_mismatch(st, eos.rho0(), J_before, J, pq_before, s_before, dt);
    return std::sqrt(c2);
  } else {
    const double c_bulk = std::sqrt(c2_bulk);
    st.q = viscosity.pressure(rho, c_bulk, h, volume_rate);
    own_work_mismatch(st, eos.rho0(), J_before, J, pq_before, s_before, dt);
    // Fastest signal at this point: longitudinal sound speed plus the viscous speed.
    const double Q = viscosity.signal(c_bulk, h, volume_rate);
    return Q + std::sqrt(Q * Q + c2);
  }
}

struct StressUpdateResult {
  // The fastest |v| + sound (+ viscous) speed, or volume_change_signal |tr D| where that is more:
  // the next dt is cfl h over it.
  double max_signal = 0.0;
  std::size_t first_bad = ~std::size_t{0};  // lowest index of a point in a bad state, if any
  ExactSum work_mismatch;                   // sum of m (work - own trapezoid work) over the points [J]
};

// The update of every point, for one choice of laws.
// `volume_rate`: the smoothed rates of volume change (volumetric_smoothing.hpp), or null.
template <int D, class Eos, class Strength, class Viscosity, class Failure>
StressUpdateResult update_all_points(Particles<D>& pts, PointRange range, const Model& model, double dt,
                                     const double* volume_rate) {
  // Each body's constants (one material: the same for all); a point takes its body's.
  const Eos* eos_of[kBodies] = {&std::get<Eos>(model.eos[0]), &std::get<Eos>(model.eos[1]), &std::get<Eos>(model.eos[2])};
  const Strength* strength_of[kBodies] = {&std::get<Strength>(model.strength[0]), &std::get<Strength>(model.strength[1]),
                                          &std::get<Strength>(model.strength[2])};
  const Viscosity& viscosity = std::get<Viscosity>(model.viscosity);
  const Failure& failure = std::get<Failure>(model.failure);
  double max_signal = 0.0;
  std::size_t first_bad = ~std::size_t{0};
  const double speed_limit2 = model.speed_limit * model.speed_limit;
  // The mismatch summed exactly, a sum per thread: the same bits for any thread and rank count.
  struct alignas(64) ThreadSum {
    ExactSum sum;
  };
  std::vector<ThreadSum> mismatch(static_cast<std::size_t>(omp_get_max_threads()));
  const bool stores = pts.stores_cold_work();       // taylor_quinney < 1
  const bool heats = pts.tracks_plastic_heat();     // temperature_model = paper
#pragma omp parallel for schedule(dynamic, kChunk) reduction(max : max_signal) reduction(min : first_bad)
  for (std::size_t p = range.begin; p < range.end; ++p) {
    PointState<D> st{pts.L[p], pts.work[p], pts.F[p], pts.E[p], pts.P[p], pts.q[p], {}, {}, 0.0};
    if (volume_rate) st.volume_rate = volume_rate[p];
    if constexpr (Strength::has_stress) {
      st.s = pts.s[p];
      st.eps_p = pts.eps_p[p];
    }
    if constexpr (Strength::has_back_stress) st.alpha = pts.alpha[p];
    if constexpr (Failure::active) {
      st.failure_J = pts.failure_J[p];
      st.damage = pts.damage[p];
    }
    if constexpr (Strength::has_stress) {
      if (stores) st.E_stored = pts.E_stored[p];
      if (heats) st.plastic_heat = pts.plastic_heat[p];
    }
    const auto b = static_cast<std::size_t>(pts.body[p]);
    const double signal =
        update_point<D>(st, *eos_of[b], *strength_of[b], viscosity, model.cell_size, dt, failure, model.taylor_quinney);
    pts.F[p] = st.F;
    pts.E[p] = st.E;
    pts.P[p] = st.P;
    pts.q[p] = st.q;
    if constexpr (Strength::has_stress) {
      pts.s[p] = st.s;
      pts.eps_p[p] = st.eps_p;
    }
    if constexpr (Strength::has_back_stress) pts.alpha[p] = st.alpha;
    if constexpr (Failure::active) {
      pts.failure_J[p] = st.failure_J;
      pts.damage[p] = st.damage;
    }
    if constexpr (Strength::has_stress) {
      if (stores) pts.E_stored[p] = st.E_stored;
      if (heats) pts.plastic_heat[p] = st.plastic_heat;
    }
    mismatch[static_cast<std::size_t>(omp_get_thread_num())].sum.add(pts.m[p] * st.work_mismatch);
    const double speed2 = dot(pts.v[p], pts.v[p]);
    if (!(signal >= 0.0) || !(speed2 < speed_limit2)) first_bad = p < first_bad ? p : first_bad;
    max_signal = std::max(
        {max_signal, std::sqrt(speed2) + signal, model.volume_change_signal * std::abs(volume_rate_of(st))});
  }
  ExactSum total_mismatch;
  for (const ThreadSum& t : mismatch) total_mismatch += t.sum;
  return {max_signal, first_bad, total_mismatch};
}

// The signal speed of the fastest point in its current state (|v| + longitudinal sound speed),
// for the first time step.
template <int D>
double initial_signal_speed(const Particles<D>& pts, const Model& model);

}  // namespace mpmshock
