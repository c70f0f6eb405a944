// The point update four points at a time (Lanes, number.hpp; constitutive.hpp's step_lanes, which
// the run's kernel calls for Mie-Grüneisen with no strength or von Mises without softening):
//   1. each lane agrees with the same point updated alone as a double, the same formulas (within
//      1e-12 of each field's scale: the compiler may contract a*b + c into an FMA differently in the
//      two), marks the same states as not physical and leaves them as a double leaves them;
//   2. a point's lane gives the same bits whatever the other lanes hold and whichever lane it is
//      in (threads and MPI ranks group points differently: outputs must not depend on it), and the
//      run's kernels (update_all_points, the heat flux's point_temperatures_and_rates) give every
//      stored field the same bits for any start of the range, with bodies mixed in groups.
// The states are random: compressed and expanded (Rose's bound curve and the linear branch),
// elastic and yielding, with and without back stress, viscosity and volumetric smoothing, in 2D
// and 3D, and a few not physical (J past the equation of state's limit, an infinite energy).
//   3. The heat flux's lane functions: exp and expm1 (number.hpp) within 1 and 4 ulp of libm's
//      over their whole range, with its special values; the energy model's temperature in lanes
//      (temperature.hpp) against the double one, across the table, in tension and past the limit.
#include <cstring>
#include <random>

#include "check.hpp"
#include "mpmshock/artificial_heat_flux.hpp"
#include "mpmshock/constitutive.hpp"
#include "mpmshock/model.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/von_mises.hpp"

using namespace mpmshock;

namespace {

constexpr double kDt = 1e-10, kH = 5e-6;

template <int D>
PointState<D> random_state(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PointState<D> st{};
  const double kind = 0.5 * (u(rng) + 1.0);
  // F near the identity, compressed by up to 40 % or expanded by up to 40 %; rare extremes.
  const double volume = kind < 0.05 ? 0.2 : 1.0 + 0.4 * u(rng);
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      st.F(i, j) = (i == j ? (i == D - 1 ? volume : 1.0) : 0.0) + 0.05 * u(rng);
      st.L(i, j) = 1e8 * u(rng);
    }
  st.E = 1e6 * (u(rng) + 1.0);
  if (kind > 0.97) st.E = std::numeric_limits<double>::infinity();
  st.work = 1e3 * u(rng);
  st.P = 1e10 * u(rng);
  st.q = 1e9 * (u(rng) + 1.0);
  const double s_scale = kind < 0.5 ? 1e7 : 3e8;  // below and far above the yield stress
  if constexpr (D == 2) {
    st.s = {s_scale * u(rng), s_scale * u(rng), s_scale * u(rng)};
    st.alpha = {1e7 * u(rng), 1e7 * u(rng), 1e7 * u(rng)};
  } else {
    st.s = {s_scale * u(rng), s_scale * u(rng), s_scale * u(rng), s_scale * u(rng), s_scale * u(rng)};
    st.alpha = {1e7 * u(rng), 1e7 * u(rng), 1e7 * u(rng), 1e7 * u(rng), 1e7 * u(rng)};
  }
  st.eps_p = 0.1 * (u(rng) + 1.0);
  st.E_stored = 1e4 * (u(rng) + 1.0);
  st.plastic_heat = 1e4 * (u(rng) + 1.0);
  if (u(rng) > 0.0) st.volume_rate = 1e8 * u(rng);  // smoothed, else tr L (NaN)
  return st;
}

// Lane l of a Lanes-form field (a struct of Lanes) as its double form.
template <class Scalar, class Vector>
Scalar lane_of(const Vector& v, int l) {
  constexpr std::size_t n = sizeof(Scalar) / sizeof(double);
  Lanes parts[n];
  std::memcpy(parts, static_cast<const void*>(&v), sizeof parts);
  double out[n];
  for (std::size_t k = 0; k < n; ++k) out[k] = parts[k][l];
  Scalar s;
  std::memcpy(static_cast<void*>(&s), out, sizeof s);
  return s;
}
template <class Scalar, class Vector>
void set_lane(Vector& v, int l, const Scalar& s) {
  constexpr std::size_t n = sizeof(Scalar) / sizeof(double);
  Lanes parts[n];
  std::memcpy(parts, static_cast<const void*>(&v), sizeof parts);
  double in[n];
  std::memcpy(in, static_cast<const void*>(&s), sizeof in);
  for (std::size_t k = 0; k < n; ++k) parts[k][l] = in[k];
  std::memcpy(static_cast<void*>(&v), parts, sizeof parts);
}

template <int D>
PointState<D, Lanes> pack(const PointState<D> (&pts)[4]) {
  PointState<D, Lanes> st;
  for (int l = 0; l < 4; ++l) {
    set_lane(st.L, l, pts[l].L);
    set_lane(st.F, l, pts[l].F);
    set_lane(st.s, l, pts[l].s);
    set_lane(st.alpha, l, pts[l].alpha);
    st.work[l] = pts[l].work;
    st.E[l] = pts[l].E;
    st.P[l] = pts[l].P;
    st.q[l] = pts[l].q;
    st.eps_p[l] = pts[l].eps_p;
    st.E_stored[l] = pts[l].E_stored;
    st.plastic_heat[l] = pts[l].plastic_heat;
    st.volume_rate[l] = pts[l].volume_rate;
  }
  return st;
}

template <int D>
PointState<D> unpack(const PointState<D, Lanes>& st, int l) {
  PointState<D> p{};
  p.L = lane_of<Mat<D>>(st.L, l);
  p.F = lane_of<Mat<D>>(st.F, l);
  p.s = lane_of<Deviator<D>>(st.s, l);
  p.alpha = lane_of<Deviator<D>>(st.alpha, l);
  p.work = st.work[l];
  p.E = st.E[l];
  p.P = st.P[l];
  p.q = st.q[l];
  p.eps_p = st.eps_p[l];
  p.E_stored = st.E_stored[l];
  p.plastic_heat = st.plastic_heat[l];
  p.work_mismatch = st.work_mismatch[l];
  return p;
}

bool same_bits(const void* a, const void* b, std::size_t n) { return std::memcmp(a, b, n) == 0; }

// Within a few ulp of the scalar value, in units of the field's scale.
void check_close(double lanes, double scalar, double scale, const char* what) {
  if (!(std::abs(lanes - scalar) <= 1e-12 * scale) && !(lanes == scalar)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s: lanes %.17g, alone %.17g", what, lanes, scalar);
    check::fail(__FILE__, __LINE__, buf);
  }
}

template <int D, class Strength, class Viscosity>
void compare(const MieGruneisen& eos, const Strength& strength, const Viscosity& viscosity, std::mt19937_64& rng,
             int groups) {
  const PointStepConstants model{kH, kDt, 0.9, 1e5, 1e-6};
  int bad_seen = 0, yielded = 0, expanded = 0;
  for (int g = 0; g < groups; ++g) {
    PointState<D> alone[4];
    for (auto& p : alone) p = random_state<D>(rng);
    PointState<D, Lanes> four = pack(alone);
    Vec<D, Lanes> v{};
    LaneSignals signals;
    step_lanes<D>(four, v, eos, strength, viscosity, model, signals);
    for (int l = 0; l < 4; ++l) {
      PointState<D> st = alone[l];
      const double eps_before = st.eps_p;
      expanded += det(st.F) > 1.0;
      const double signal = update_point<D>(st, eos, strength, viscosity, kH, kDt, NoFailure{}, 0.9);
      const PointState<D> got = unpack(four, l);
      CHECK((signal < 0.0) == (signals.bad[l] != 0));
      if (signal < 0.0) {
        // A double stops at once; the lanes finish the step but keep what it leaves.
        ++bad_seen;
        CHECK(same_bits(&got.q, &st.q, sizeof st.q) && got.work_mismatch == 0.0);
        if (!(det(st.F) > eos.limiting_compression()))
          CHECK(same_bits(&got.P, &st.P, sizeof st.P) && same_bits(&got.s, &st.s, sizeof st.s) &&
                same_bits(&got.alpha, &st.alpha, sizeof st.alpha) && same_bits(&got.eps_p, &st.eps_p, sizeof st.eps_p));
        continue;
      }
      yielded += st.eps_p > eps_before;
      check_close(signals.sound[l], signal, signal, "signal speed");
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) check_close(got.F(i, j), st.F(i, j), 1.0, "F");
      check_close(got.E, st.E, std::abs(st.E) + 1e3, "E");
      check_close(got.P, st.P, std::abs(st.P) + 1e6, "P");
      check_close(got.q, st.q, std::abs(st.q) + 1e6, "q");
      for (std::size_t k = 0; k < sizeof st.s / sizeof(double); ++k) {
        check_close(reinterpret_cast<const double*>(&got.s)[k], reinterpret_cast<const double*>(&st.s)[k], 1e9, "s");
        check_close(reinterpret_cast<const double*>(&got.alpha)[k], reinterpret_cast<const double*>(&st.alpha)[k], 1e9,
                    "alpha");
      }
      check_close(signals.volume[l], model.volume_change_signal * std::abs(volume_rate_of(alone[l])), 1.0, "volume");
      check_close(got.eps_p, st.eps_p, 1.0, "eps_p");
      check_close(got.E_stored, st.E_stored, std::abs(st.E_stored) + 1e3, "E_stored");
      check_close(got.plastic_heat, st.plastic_heat, std::abs(st.plastic_heat) + 1e3, "plastic_heat");
      check_close(got.work_mismatch, st.work_mismatch, 1e3, "work_mismatch");
    }
  }
  // The random states reach every branch.
  CHECK(bad_seen > 0);
  CHECK(expanded > 0);
  if constexpr (Strength::has_stress) CHECK(yielded > 0);
}

// A point in lane k beside others gives the bits it gives in every lane alone.
template <int D, class Strength>
void lane_independence(const MieGruneisen& eos, const Strength& strength, std::mt19937_64& rng, int groups) {
  const PointStepConstants model{kH, kDt, 0.9, 1e5, 0.0};
  const ArtificialViscosity viscosity{0.6, 2.0};
  for (int g = 0; g < groups; ++g) {
    PointState<D> pts[4];
    for (auto& p : pts) p = random_state<D>(rng);
    PointState<D, Lanes> four = pack(pts);
    const Vec<D, Lanes> v{};
    LaneSignals together;
    step_lanes<D>(four, v, eos, strength, viscosity, model, together);
    for (int l = 0; l < 4; ++l) {
      PointState<D> same[4] = {pts[l], pts[l], pts[l], pts[l]};
      PointState<D, Lanes> alone = pack(same);
      LaneSignals by_itself;
      step_lanes<D>(alone, v, eos, strength, viscosity, model, by_itself);
      const PointState<D> a = unpack(four, l), b = unpack(alone, (l + 1) % 4);
      CHECK(same_bits(&a.F, &b.F, sizeof a.F) && same_bits(&a.s, &b.s, sizeof a.s));
      CHECK(same_bits(&a.E, &b.E, sizeof a.E) && same_bits(&a.P, &b.P, sizeof a.P) && same_bits(&a.q, &b.q, sizeof a.q));
      CHECK(same_bits(&a.eps_p, &b.eps_p, sizeof a.eps_p) &&
            same_bits(&a.work_mismatch, &b.work_mismatch, sizeof a.work_mismatch));
      const double s1 = together.sound[l], s2 = by_itself.sound[(l + 1) % 4];
      CHECK(same_bits(&s1, &s2, sizeof s1));
    }
  }
}

// The run's kernels over a range split at k = 1, 2, 3 (so every group of four starts elsewhere)
// give every stored field the bits of one pass over the whole range; copper flyer points and
// aluminium target points alternate in runs of 6 and 5, so groups of mixed bodies go point by point.
template <int D>
void kernels_do_not_depend_on_grouping(std::mt19937_64& rng) {
  const Scene scene = parse_scene("dimension = " + std::to_string(D) + "\nflyer_material = copper\n", "grouping");
  const Model model(scene);
  CHECK(std::holds_alternative<VonMises<false>>(model.strength[0]) &&
        std::holds_alternative<ArtificialViscosity>(model.viscosity) && std::holds_alternative<NoFailure>(model.failure));
  constexpr std::size_t n = 103;
  Particles<D> start;
  start.enable_strength(true, false);
  for (std::size_t i = 0; i < n; ++i) {
    const PointState<D> st = random_state<D>(rng);
    Vec<D> x{}, v{};
    for (int d = 0; d < D; ++d) v[d] = 500.0 * st.L(0, d) / 1e8;
    start.add(x, v, 1e-6, 1e-10, i % 11 < 6 ? Body::flyer : Body::target);
    start.F[i] = st.F, start.L[i] = st.L, start.work[i] = st.work, start.E[i] = st.E, start.P[i] = st.P;
    start.q[i] = i % 3 == 0 ? 0.0 : st.q, start.s[i] = st.s, start.eps_p[i] = st.eps_p;
  }
  auto kernel = update_all_points<D, MieGruneisen, VonMises<false>, ArtificialViscosity, NoFailure>;
  Particles<D> whole = start;
  const StressUpdateResult all = kernel(whole, {0, n}, model, kDt, nullptr);
  CHECK(all.first_bad < n);  // some random states are not physical
  const BodyTemperatures thermal(scene.material_of(Body::flyer), scene.material_of(Body::target),
                                 scene.material_of(Body::window));
  CHECK(thermal.in_lanes());
  ArtificialHeatFlux flux;
  flux.beta = 10.0;
  flux.cell_size = kH;
  flux.sound_speed = {3940.0, 5350.0, 5150.0};
  flux.specific_heat = {385.0, 896.0, 1600.0};
  flux.one_material = false;  // the heat capacities C_p too
  ArtificialHeatFlux flux_whole = flux;
  Particles<D> heat_whole = start;
  point_temperatures_and_rates(heat_whole, {0, n}, thermal, flux_whole, 1e-3);
  auto same_field = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0;
  };
  for (std::size_t k = 1; k <= 3; ++k) {
    Particles<D> split = start;
    const StressUpdateResult first = kernel(split, {0, k}, model, kDt, nullptr);
    const StressUpdateResult rest = kernel(split, {k, n}, model, kDt, nullptr);
    CHECK(same_field(split.F, whole.F) && same_field(split.E, whole.E) && same_field(split.P, whole.P));
    CHECK(same_field(split.q, whole.q) && same_field(split.s, whole.s) && same_field(split.eps_p, whole.eps_p));
    CHECK(std::max(first.max_signal, rest.max_signal) == all.max_signal);
    CHECK(std::min(first.first_bad, rest.first_bad) == all.first_bad);
    CHECK(same_field(split.work_mismatch, whole.work_mismatch));  // each point's own running sum
    Particles<D> heat = start;
    ArtificialHeatFlux flux_split = flux;
    point_temperatures_and_rates(heat, {0, k}, thermal, flux_split, 1e-3);
    point_temperatures_and_rates(heat, {k, n}, thermal, flux_split, 1e-3);
    CHECK(same_field(flux_split.point_temperature, flux_whole.point_temperature) &&
          same_field(flux_split.point_rate, flux_whole.point_rate) &&
          same_field(flux_split.point_heat, flux_whole.point_heat) &&
          same_field(flux_split.point_capacity, flux_whole.point_capacity));
  }
}

template <int D>
void run_all(std::mt19937_64& rng) {
  kernels_do_not_depend_on_grouping<D>(rng);
  for (const bool rose : {false, true}) {
    Material al;
    al.bound_expansion = rose;
    const MieGruneisen eos(al);
    compare<D>(eos, NoStrength{}, NoViscosity{}, rng, 300);
    compare<D>(eos, NoStrength{}, ArtificialViscosity{0.2, 2.0}, rng, 300);
    compare<D>(eos, VonMises<false>(al), ArtificialViscosity{0.6, 2.0}, rng, 300);
    Material mixed = al;
    mixed.hardening_beta = 0.5;
    compare<D>(eos, VonMises<true>(mixed), ArtificialViscosity{0.6, 2.0}, rng, 300);
    lane_independence<D>(eos, VonMises<false>(al), rng, 200);
    lane_independence<D>(eos, VonMises<true>(mixed), rng, 200);
  }
}

// |a - b| in units in the last place of b.
double ulps(double a, double b) {
  if (a == b) return 0.0;
  return std::abs(a - b) / (std::nextafter(std::abs(b), INFINITY) - std::abs(b));
}

void exponentials(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_exp = 0.0, worst_expm1 = 0.0;
  for (int i = 0; i < 400000; ++i) {
    double x;
    switch (i % 4) {
      case 0: x = 745.0 * u(rng); break;
      case 1: x = 2.0 * u(rng); break;
      case 2: x = 1e-3 * u(rng); break;
      default: x = std::ldexp(u(rng), -static_cast<int>(rng() % 1000));
    }
    const Lanes v{x, -x, 0.5 * x, 2.0 * x};
    const Lanes e = exponential(v), m = exponential_minus_one(v);
    for (int l = 0; l < 4; ++l) {
      if (std::exp(v[l]) > std::numeric_limits<double>::min()) worst_exp = std::max(worst_exp, ulps(e[l], std::exp(v[l])));
      worst_expm1 = std::max(worst_expm1, ulps(m[l], std::expm1(v[l])));
    }
  }
  std::printf("exp within %.1f ulp of libm's, expm1 within %.1f\n", worst_exp, worst_expm1);
  CHECK(worst_exp <= 1.0);
  CHECK(worst_expm1 <= 4.0);
  const double inf = std::numeric_limits<double>::infinity();
  const Lanes special{0.0, -inf, inf, std::nan("")}, tiny{1e-300, -1e-300, -745.1, 709.8};
  const Lanes e = exponential(special), m = exponential_minus_one(special);
  CHECK(e[0] == 1.0 && e[1] == 0.0 && e[2] == inf && std::isnan(e[3]));
  CHECK(m[0] == 0.0 && m[1] == -1.0 && m[2] == inf && std::isnan(m[3]));
  const Lanes et = exponential(tiny), mt = exponential_minus_one(tiny);
  CHECK(mt[0] == 1e-300 && mt[1] == -1e-300 && et[2] == std::exp(-745.1) && et[3] == inf);
}

void temperatures(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Material al;
  const HugoniotTemperature model(al);
  const MieGruneisen eos(al);
  CHECK(model.in_lanes());
  const double J_min = model.min_tabulated_J();
  int tension = 0, table = 0, refused = 0;
  for (int i = 0; i < 20000; ++i) {
    Lanes J, E, T;
    for (int l = 0; l < 4; ++l) {
      const double kind = u(rng);
      J[l] = kind < 0.1 ? J_min * u(rng) : (kind < 0.4 ? 1.0 + 2.0 * u(rng) : J_min + (1.0 - J_min) * u(rng));
      if (kind > 0.98) J[l] = kind > 0.99 ? 1.0 : J_min;
      E[l] = eos.hugoniot_energy(std::max(J[l], J_min)) + 1e6 * u(rng);
    }
    model.temperature_lanes(T, J, E);
    for (int l = 0; l < 4; ++l) {
      const double alone = model.temperature(J[l], E[l]);
      if (!(J[l] >= J_min)) {
        ++refused;
        CHECK(T[l] == alone);  // infinite: refused, as alone
      } else {
        (J[l] >= 1.0 ? tension : table) += 1;
        CHECK_REL(T[l], alone, 1e-13);
      }
    }
  }
  CHECK(tension > 0 && table > 0 && refused > 0);
}

}  // namespace

int main() {
  std::mt19937_64 rng(20261206);
  run_all<2>(rng);
  run_all<3>(rng);
  exponentials(rng);
  temperatures(rng);
  return check::result();
}
