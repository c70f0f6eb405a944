// The constitutive update of a material point from its velocity gradient L and the work the
// step's nodal forces did on it (see velocity_gradient_work_and_move): internal energy E += work
// (compression, plastic and viscous work alike, exactly what the kinetic energy lost);
// F <- (I + dt L) F; the deviatoric stress by the strength law; the pressure from the equation of
// state at the new volume and energy; the artificial viscous pressure q. One function per point,
// pure and grid-free, over the law types the model chose, so tests drive it directly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "mpmshock/model.hpp"
#include "mpmshock/number.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/particles.hpp"

namespace mpmshock {

// T: a double, or four points in the lanes of Lanes (number.hpp), each computed as it would be alone.
template <int D, class T = double>
struct PointState {
  Mat<D, T> L;  // in: the velocity gradient
  T work;       // in: the work of the step's forces [J/kg]
  Mat<D, T> F;
  T E, P, q;
  Deviator<D, T> s, alpha;
  T eps_p;
  T failure_J{};      // in/out with spall: 0 while intact, else the J it began to open at
  T damage{};         // in/out with spall: 0 intact ... 1 separated (spall.hpp)
  T E_stored{};       // in/out: the cold work stored in E [J/kg]
  T plastic_heat{};   // in/out: the plastic work turned to heat [J/kg] (temperature_model = paper)
  T work_mismatch{};  // out: work minus the trapezoid-rule work of the point's own deformation
  // in: the rate of volume change F follows, tr L (NaN) unless volumetric smoothing gives its own
  // (volumetric_smoothing.hpp); the deviatoric rate is always L's.
  T volume_rate = constant<T>(std::numeric_limits<double>::quiet_NaN());
};

// The rate of volume change F follows: the smoothed one where there is one, else tr L.
template <int D, class T>
inline T volume_rate_of(const PointState<D, T>& st) {
  return st.volume_rate != st.volume_rate ? trace(st.L) : st.volume_rate;  // NaN: none
}

// The energy-consistency diagnostic of a point's step: the work it was given (the exact work of the
// nodal forces) minus the work of its own deformation by the trapezoid rule,
// -(1/2)((P + q)^n + (P + q)^{n+1}) dV + V^{n+1/2} (1/2)(s^n + s^{n+1}) : L dt, per unit mass.
// Summed over points and steps (times m) it is the internal energy the points hold that their own
// compression did not give them (conservation.csv, work_mismatch).
template <int D, class T>
inline void own_work_mismatch(PointState<D, T>& st, double rho0, const T& J_before, const T& J, const T& pq_before,
                              const Deviator<D, T>& s_before, double dt) {
  T own = -0.5 * (pq_before + st.P + st.q) * (J - J_before) / rho0;
  own += 0.25 * dt * (J_before + J) / rho0 * (contract(s_before, st.L) + contract(st.s, st.L));
  st.work_mismatch = st.work - own;
}

// One point, one step (or four in Lanes). Returns the point's signal speed (for the next time
// step), or a negative number if the new state is not physical (J <= the EOS limit, or a
// non-finite result). Inlined into the loop over points: as a call it costs 40 % more instructions
// per point. A double returns at once from a state that is not physical; four lanes finish the
// step in every lane (the run stops at such a state either way).
// `taylor_quinney` is the share of plastic work that becomes heat; the rest goes to E_stored.
template <int D, class T, class Eos, class Strength, class Viscosity, class Failure = NoFailure>
[[gnu::always_inline]] inline T update_point(PointState<D, T>& st, const Eos& eos, const Strength& strength,
                                             const Viscosity& viscosity, double h, double dt,
                                             [[maybe_unused]] const Failure& failure = {},
                                             [[maybe_unused]] double taylor_quinney = 1.0) {
  constexpr bool lanes = !std::is_same_v<T, double>;
  static_assert(!lanes || !Failure::active, "spall is computed point by point");
  const StrainRate<D, T> rate = strain_rate(st.L);
  const T volume_rate = volume_rate_of(st);
  const T volume_shift = (volume_rate - trace(st.L)) / static_cast<double>(D);  // 0 without smoothing
  const PointState<D, T> before = st;  // (a double keeps only its s; lanes keep more, below)
  const T J_before = det(st.F), pq_before = st.P + st.q;

  // Energy: the exact work of the step's nodal forces on the point (compression, plastic and
  // viscous work alike), which is what the points' kinetic energy lost.
  st.E += st.work;

  // Kinematics: F^{n+1} = (I + dt L) F^n, L with the volume rate's trace.
  Mat<D, T> A;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) A(i, j) = i == j ? 1.0 + dt * (st.L(i, j) + volume_shift) : dt * st.L(i, j);
  st.F = product(A, st.F);
  const T J = det(st.F);
  const auto admitted = J > eos.limiting_compression();
  if constexpr (!lanes)
    if (!admitted) return -1.0;
  // A failed point's material keeps the volume it failed at while the space around it opens.
  T J_material = J;
  if constexpr (Failure::active)
    if (st.failure_J > 0.0) J_material = std::min(J, st.failure_J);
  const T rho = eos.rho0() / J_material;

  if constexpr (Strength::has_stress) {
    const T plastic_work = strength.update(st.s, st.alpha, st.eps_p, rate, dt, J_material, st.E - st.E_stored, st.P);
    st.E_stored += (1.0 - taylor_quinney) * plastic_work / rho;
    st.plastic_heat += taylor_quinney * plastic_work / rho;
  }

  // Pressure from the new volume and energy; artificial viscosity from this step's compression rate.
  const auto eos_state = eos.state(J_material, st.E);
  st.P = eos_state.pressure;
  const auto physical = admitted && finite(st.E) && finite(st.P);
  if constexpr (!lanes)
    if (!physical) return -1.0;
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
  const T c2_bulk = maximum(eos_state.sound_speed_squared, T{});
  T c2 = c2_bulk;  // longitudinal: bulk plus shear
  if constexpr (Strength::has_stress) c2 += (4.0 / 3.0) * strength.shear_modulus / rho;
  T signal;
  if constexpr (!Viscosity::active) {
    st.q = T{};
    own_work_mismatch(st, eos.rho0(), J_before, J, pq_before, before.s, dt);
    signal = square_root(c2);
  } else {
    const T c_bulk = square_root(c2_bulk);
    st.q = viscosity.pressure(rho, c_bulk, h, volume_rate);
    own_work_mismatch(st, eos.rho0(), J_before, J, pq_before, before.s, dt);
    // Fastest signal at this point: longitudinal sound speed plus the viscous speed.
    const T Q = viscosity.signal(c_bulk, h, volume_rate);
    signal = Q + square_root(Q * Q + c2);
  }
  if constexpr (lanes) {
    // A lane whose state is not physical keeps what a double leaves when it returns early: past
    // the limiting compression, all but E and F as they were; non-finite, q as it was. Its work
    // mismatch is 0, as a double's. (The run stops at such a state either way.)
    if (!any(!physical)) return signal;
    st.P = admitted ? st.P : before.P;
    st.q = physical ? st.q : before.q;
    st.s = choose(admitted, st.s, before.s);
    st.alpha = choose(admitted, st.alpha, before.alpha);
    st.eps_p = admitted ? st.eps_p : before.eps_p;
    st.E_stored = admitted ? st.E_stored : before.E_stored;
    st.plastic_heat = admitted ? st.plastic_heat : before.plastic_heat;
    st.work_mismatch = physical ? st.work_mismatch : T{};
    return physical ? signal : constant<T>(-1.0);
  } else {
    return signal;
  }
}

struct StressUpdateResult {
  // The fastest |v| + sound (+ viscous) speed, or volume_change_signal |tr D| where that is more:
  // the next dt is cfl h over it.
  double max_signal = 0.0;
  std::size_t first_bad = ~std::size_t{0};  // lowest index of a point in a bad state, if any
};

// Whether a law's part of the point update is written for Lanes as well as a double: its
// `in_lanes` (number.hpp; the laws without it compute point by point).
template <class Law, class = void>
struct InLanes : std::false_type {};
template <class Law>
struct InLanes<Law, std::void_t<decltype(Law::in_lanes)>> : std::bool_constant<Law::in_lanes> {};

// Each lane's candidates for the largest signal speed and its check, from step_lanes.
struct LaneSignals {
  Lanes sound, volume;  // |v| + the point's signal speed; volume_change_signal |tr D|
  LaneBits bad;         // a state that is not physical, or a runaway speed
};
// The model's numbers a step of points needs (model.hpp).
struct PointStepConstants {
  double cell_size, dt, taylor_quinney;
  double speed_limit;           // |v| above this is a runaway
  double volume_change_signal;  // a volume change's signal speed per |tr D|
};
// The arithmetic of four lanes' step: the point update, then each lane's speed check and its
// candidates for the largest signal speed. One body of instructions whichever way its lanes were
// filled (MPMSHOCK_ONE_BODY, number.hpp).
template <int D, class Eos, class Strength, class Viscosity>
MPMSHOCK_ONE_BODY void step_lanes(PointState<D, Lanes>& st, const Vec<D, Lanes>& v, const Eos& eos,
                                  const Strength& strength, const Viscosity& viscosity, const PointStepConstants& k,
                                  LaneSignals& out) {
  const Lanes signal = update_point<D>(st, eos, strength, viscosity, k.cell_size, k.dt, NoFailure{}, k.taylor_quinney);
  Lanes speed2 = v[0] * v[0];
  for (int d = 1; d < D; ++d) speed2 += v[d] * v[d];
  out.bad = !(signal >= 0.0) || !(speed2 < k.speed_limit * k.speed_limit);
  Lanes rate;
  abs_lanes(rate, volume_rate_of(st));
  out.sound = square_root(speed2) + signal;
  out.volume = k.volume_change_signal * rate;
}

// Visits each point field the update writes, with its member of the point's state:
// f(the field's values, the member). Those it only reads (L, work, v) are not among them.
template <class Strength, class Failure, int D, class State, class F>
[[gnu::always_inline]] inline void for_each_updated_field(Particles<D>& pts, State& st, bool stores, bool heats, F&& f) {
  f(pts.F.data(), st.F);
  f(pts.E.data(), st.E);
  f(pts.P.data(), st.P);
  f(pts.q.data(), st.q);
  if constexpr (Strength::has_stress) {
    f(pts.s.data(), st.s);
    f(pts.eps_p.data(), st.eps_p);
    if (stores) f(pts.E_stored.data(), st.E_stored);
    if (heats) f(pts.plastic_heat.data(), st.plastic_heat);
  }
  if constexpr (Strength::has_back_stress) f(pts.alpha.data(), st.alpha);
  if constexpr (Failure::active) {
    f(pts.failure_J.data(), st.failure_J);
    f(pts.damage.data(), st.damage);
  }
}

// sum += m w: one body of instructions for both ways a group of four is filled (MPMSHOCK_ONE_BODY: an
// FMA contracted in one inlined copy and not in the other would give a point other bits in
// another group).
MPMSHOCK_ONE_BODY inline void add_work_mismatch(Lanes& sum, const Lanes& m, const Lanes& w) { sum += m * w; }

// The update of points p..p+3 (kFour: all of one body) or of point p alone in every lane.
template <bool kFour, int D, class Eos, class Strength, class Viscosity>
[[gnu::always_inline]] inline void update_four(Particles<D>& pts, std::size_t p, const Eos& eos, const Strength& strength,
                                               const Viscosity& viscosity, const PointStepConstants& k,
                                               const double* volume_rate, bool stores, bool heats, double& max_signal,
                                               std::size_t& first_bad) {
  PointState<D, Lanes> st;
  load_points<kFour>(st.L, &pts.L[p]);
  load_points<kFour>(st.work, &pts.work[p]);
  if (volume_rate) load_points<kFour>(st.volume_rate, &volume_rate[p]);
  for_each_updated_field<Strength, NoFailure>(
      pts, st, stores, heats, [&](auto* field, auto& x) __attribute__((always_inline)) { load_points<kFour>(x, field + p); });
  Vec<D, Lanes> v;
  load_points<kFour>(v, &pts.v[p]);
  LaneSignals checks;
  step_lanes<D>(st, v, eos, strength, viscosity, k, checks);
  for_each_updated_field<Strength, NoFailure>(
      pts, st, stores, heats,
      [&](auto* field, const auto& x) __attribute__((always_inline)) { store_points<kFour>(field + p, x); });
  // NaN never wins the maximum (as in std::max over a list), so the largest speed is the same
  // however points are grouped; comparisons are exact.
  Lanes largest = Lanes{} + max_signal;
  largest = checks.sound > largest ? checks.sound : largest;
  largest = checks.volume > largest ? checks.volume : largest;
  max_signal = std::max(std::max(largest[0], largest[1]), std::max(largest[2], largest[3]));
  // Each point's own running sum of m (work - own work): the same bits in any group (per point).
  Lanes m, mismatch;
  load_points<kFour>(m, &pts.m[p]);
  load_points<kFour>(mismatch, &pts.work_mismatch[p]);
  add_work_mismatch(mismatch, m, st.work_mismatch);
  if constexpr (kFour) store_points<kFour>(&pts.work_mismatch[p], mismatch);
  else pts.work_mismatch[p] = mismatch[0];
  if (any(checks.bad))
    for (std::size_t l = 0; l < (kFour ? 4 : 1); ++l)
      if (checks.bad[l]) first_bad = std::min(first_bad, p + l);
}

// The update of every point, for one choice of laws: four points at a time where the laws are
// written for Lanes, else point by point.
// `volume_rate`: the smoothed rates of volume change (volumetric_smoothing.hpp), or null.
template <int D, class Eos, class Strength, class Viscosity, class Failure>
StressUpdateResult update_all_points(Particles<D>& pts, PointRange range, const Model& model, double dt,
                                     const double* volume_rate) {
  // Each body's constants (one material: the same for all); a point takes its body's.
  const Eos* eos_of[kBodies] = {&std::get<Eos>(model.eos[0]), &std::get<Eos>(model.eos[1]), &std::get<Eos>(model.eos[2])};
  const Strength* strength_of[kBodies] = {&std::get<Strength>(model.strength[0]), &std::get<Strength>(model.strength[1]),
                                          &std::get<Strength>(model.strength[2])};
  const Viscosity& viscosity = std::get<Viscosity>(model.viscosity);
  double max_signal = 0.0;
  std::size_t first_bad = ~std::size_t{0};
  const bool stores = pts.stores_cold_work();       // taylor_quinney < 1
  const bool heats = pts.tracks_plastic_heat();     // temperature_model = paper
  if constexpr (InLanes<Eos>::value && InLanes<Strength>::value && !Failure::active) {
    // Groups of four points of one body; a group of points of different bodies, and the last
    // points, one point at a time.
    const PointStepConstants k{model.cell_size, dt, model.taylor_quinney, model.speed_limit, model.volume_change_signal};
    const std::size_t groups = groups_of_four(range);
#pragma omp parallel for schedule(dynamic, kChunk / 4) reduction(max : max_signal) reduction(min : first_bad)
    for (std::size_t g = 0; g < groups; ++g) {
      // Defined in the loop, so that it takes this thread's max_signal and first_bad.
      auto points = [&](auto four, std::size_t p) __attribute__((always_inline)) {
        const auto b = static_cast<std::size_t>(pts.body[p]);
        update_four<decltype(four)::value>(pts, p, *eos_of[b], *strength_of[b], viscosity, k, volume_rate, stores,
                                           heats, max_signal, first_bad);
      };
      for_group_of_four(
          pts, range, g, [&](std::size_t p) __attribute__((always_inline)) { points(std::true_type{}, p); },
          [&](std::size_t q) __attribute__((always_inline)) { points(std::false_type{}, q); });
    }
  } else {
    const Failure& failure = std::get<Failure>(model.failure);
    const double speed_limit2 = model.speed_limit * model.speed_limit;
#pragma omp parallel for schedule(dynamic, kChunk) reduction(max : max_signal) reduction(min : first_bad)
    for (std::size_t p = range.begin; p < range.end; ++p) {
      PointState<D> st{};
      st.L = pts.L[p];
      st.work = pts.work[p];
      if (volume_rate) st.volume_rate = volume_rate[p];
      for_each_updated_field<Strength, Failure>(pts, st, stores, heats,
                                                [&](auto* field, auto& x) __attribute__((always_inline)) { x = field[p]; });
      const auto b = static_cast<std::size_t>(pts.body[p]);
      const double signal =
          update_point<D>(st, *eos_of[b], *strength_of[b], viscosity, model.cell_size, dt, failure, model.taylor_quinney);
      for_each_updated_field<Strength, Failure>(
          pts, st, stores, heats, [&](auto* field, const auto& x) __attribute__((always_inline)) { field[p] = x; });
      pts.work_mismatch[p] += pts.m[p] * st.work_mismatch;
      const double speed2 = dot(pts.v[p], pts.v[p]);
      if (!(signal >= 0.0) || !(speed2 < speed_limit2)) first_bad = p < first_bad ? p : first_bad;
      max_signal = std::max(
          {max_signal, std::sqrt(speed2) + signal, model.volume_change_signal * std::abs(volume_rate_of(st))});
    }
  }
  return {max_signal, first_bad};
}

// The signal speed of the fastest point in its current state (|v| + longitudinal sound speed),
// for the first time step.
template <int D>
double initial_signal_speed(const Particles<D>& pts, const Model& model);

}  // namespace mpmshock
