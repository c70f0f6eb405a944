// The number a formula computes with: a double, or four points' values in the lanes of one vector
// (Lanes, lanes.hpp). The point update's laws are written once for either (constitutive.hpp): the
// arithmetic operators, comparisons and ?: act lane by lane on Lanes as on a double, and the few
// operations the language does not give both (a square root, min and max, finiteness, whether any
// lane holds a condition, a constant) are here, each giving a lane exactly what the scalar
// operation gives that value alone (IEEE division and square root are correctly rounded either
// way). A branch that only some lanes take is computed for all and chosen by ?: per lane.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "mpmshock/lanes.hpp"

#if defined(__AVX__) || defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mpmshock {

// A function holding four lanes' arithmetic that must be one body of instructions wherever it is
// called: the compiler may contract a*b + c into an FMA differently in each inlined or cloned
// copy, and a point must give the same bits in a group of four as alone. GCC's noipa also rules
// out clones specialised for a call site; Clang has no such cloning and knows only noinline.
#if defined(__clang__)
#define MPMSHOCK_ONE_BODY [[gnu::noinline]]
#else
#define MPMSHOCK_ONE_BODY [[gnu::noipa]]
#endif

// The condition type of a comparison: bool for a double, a lane mask for Lanes.
inline bool any(bool m) { return m; }
[[gnu::always_inline]] inline bool any(const LaneBits& m) { return ((m[0] | m[1]) | (m[2] | m[3])) != 0; }

// A constant of the number type.
template <class T>
[[gnu::always_inline]] inline T constant(double x) {
  if constexpr (sizeof(T) == sizeof(double)) return x;
  else return T{} + x;
}

inline double square_root(double x) { return std::sqrt(x); }
[[gnu::always_inline]] inline Lanes square_root(const Lanes& x) {
#if defined(__AVX__)
  return reinterpret_cast<Lanes>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x)));
#elif defined(__SSE2__)
  HalfLanes low, high;
  split_halves(low, high, x);
  Lanes r;
  join_halves(r, reinterpret_cast<HalfLanes>(_mm_sqrt_pd(reinterpret_cast<__m128d>(low))),
              reinterpret_cast<HalfLanes>(_mm_sqrt_pd(reinterpret_cast<__m128d>(high))));
  return r;
#else
  return Lanes{std::sqrt(x[0]), std::sqrt(x[1]), std::sqrt(x[2]), std::sqrt(x[3])};
#endif
}

// std::min and std::max, lane by lane as they are defined: min(a, b) = b < a ? b : a,
// max(a, b) = a < b ? b : a (so a NaN in b is dropped, one in a kept, as std's).
template <class T>
[[gnu::always_inline]] inline T minimum(const T& a, const T& b) { return b < a ? b : a; }
template <class T>
[[gnu::always_inline]] inline T maximum(const T& a, const T& b) { return a < b ? b : a; }

// Finite (not NaN, not infinite): |x| <= the largest double, false for NaN.
inline bool finite(double x) { return std::isfinite(x); }
[[gnu::always_inline]] inline LaneBits finite(const Lanes& x) {
  Lanes magnitude;
  abs_lanes(magnitude, x);
  return magnitude <= std::numeric_limits<double>::max();
}

// exp and expm1 lane by lane, within 1 and 4 ulp of libm's (not its bits: a lane's value is the
// same whatever the other lanes hold, which is what the kernels need). exp(x) = 2^n exp(r) with
// x = n ln 2 + r, |r| <= ln 2 / 2 (Cody and Waite's two-part ln 2, so n ln 2 is exact), exp(r) by
// its Taylor series to r^13 (the next term is below 2e-17 of the sum), 2^n as two powers of two so
// that results down to the subnormals and up to overflow come out. expm1(x) by its own series to
// x^14 where |x| <= ln 2 / 2 (no cancellation near 0), else exp(x) - 1 (at least 0.29 in size).
// exp(0) = 1 and expm1(0) = 0 exactly; NaN gives NaN, -inf 0 (expm1: -1), +inf inf.
[[gnu::always_inline]] inline void exp_lanes(Lanes& out, const Lanes& x) {
  Lanes held = x < -746.0 ? Lanes{} - 746.0 : (x > 710.0 ? Lanes{} + 710.0 : x);
  held = x != x ? Lanes{} : held;  // NaN: computed as 0, replaced below
  LaneInts n;
  floor_lanes(n, held * 1.4426950408889634 + 0.5);  // nearest n = x / ln 2, in [-1076, 1024]
  const Lanes nd = __builtin_convertvector(n, Lanes);
  const Lanes r = (held - nd * 6.93147180369123816490e-01) - nd * 1.90821492927058770002e-10;
  constexpr double kInverseFactorial[14] = {1.0,
                                            1.0,
                                            1.0 / 2,
                                            1.0 / 6,
                                            1.0 / 24,
                                            1.0 / 120,
                                            1.0 / 720,
                                            1.0 / 5040,
                                            1.0 / 40320,
                                            1.0 / 362880,
                                            1.0 / 3628800,
                                            1.0 / 39916800,
                                            1.0 / 479001600,
                                            1.0 / 6227020800};
  Lanes p = Lanes{} + kInverseFactorial[13];
  for (int k = 12; k >= 0; --k) p = p * r + kInverseFactorial[k];
  // 2^half 2^rest, each a normal double: half and rest in [-538, 512], so the biased exponents
  // are positive and the shifts act on non-negative values.
  typedef std::uint64_t Wide __attribute__((vector_size(32)));
  const LaneInts half = n >> 1, rest = n - half;
  const Lanes scale_a = reinterpret_cast<Lanes>(__builtin_convertvector(half + 1023, Wide) << 52);
  const Lanes scale_b = reinterpret_cast<Lanes>(__builtin_convertvector(rest + 1023, Wide) << 52);
  const Lanes e = p * scale_a * scale_b;
  out = x > 709.782712893384 ? Lanes{} + std::numeric_limits<double>::infinity() : e;
  out = x != x ? x : out;
}
inline double exponential(double x) { return std::exp(x); }
[[gnu::always_inline]] inline Lanes exponential(const Lanes& x) {
  Lanes e;
  exp_lanes(e, x);
  return e;
}
inline double exponential_minus_one(double x) { return std::expm1(x); }
[[gnu::always_inline]] inline Lanes exponential_minus_one(const Lanes& x) {
  constexpr double kInverseFactorial[15] = {1.0,           1.0,            1.0 / 2,           1.0 / 6,
                                            1.0 / 24,      1.0 / 120,      1.0 / 720,         1.0 / 5040,
                                            1.0 / 40320,   1.0 / 362880,   1.0 / 3628800,     1.0 / 39916800,
                                            1.0 / 479001600, 1.0 / 6227020800, 1.0 / 87178291200};
  Lanes magnitude;
  abs_lanes(magnitude, x);
  const LaneBits small = magnitude <= 0.34657359027997264;  // (NaN: not small)
  // Each form only where a lane takes it: the lanes' values are the same either way.
  Lanes series{}, e{};
  if (any(small)) {
    Lanes p = Lanes{} + kInverseFactorial[14];
    for (int k = 13; k >= 2; --k) p = p * x + kInverseFactorial[k];
    series = x + x * (x * p);  // x + x^2/2 + ... + x^14/14!
  }
  if (any(~small)) exp_lanes(e, x);
  return small ? (x == 0.0 ? x : series) : e - 1.0;  // -0 stays -0
}

}  // namespace mpmshock
