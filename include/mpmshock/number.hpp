// The number a formula computes with: a double, or four points' values in the lanes of one vector
// (Lanes, lanes.hpp). The point update's laws are written once for either (constitutive.hpp): the
// arithmetic operators, comparisons and ?: act lane by lane on Lanes as on a double, and the few
// operations the language does not give both (a square root, min and max, finiteness, whether any
// lane holds a condition, a constant) are here, each giving a lane exactly what the scalar
// operation gives that value alone (IEEE division and square root are correctly rounded either
// way). A branch that only some lanes take is computed for all and chosen by ?: per lane.
#pragma once

#include <cmath>
#include <limits>

#include "mpmshock/lanes.hpp"

#if defined(__AVX__) || defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mpmshock {

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

}  // namespace mpmshock
