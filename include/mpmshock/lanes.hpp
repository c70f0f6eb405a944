// Four doubles in the lanes of one vector register (AVX2 width; two SSE2 halves on a baseline
// x86-64 build), with the GCC/Clang vector extensions (g++ 12 or newer for __builtin_shufflevector;
// CMakeLists.txt checks): arithmetic, comparisons and ?: act lane by lane, so a formula written once
// computes four independent values, each exactly as it would alone. Used for a stencil row's four
// nodes (node_rows.hpp), four points' stencil weights (shape.hpp) and four points' states in the
// point update (constitutive.hpp) and the heat flux (artificial_heat_flux.hpp).
//
// Without AVX each vector is two SSE2 halves. These helpers take and give vectors by reference;
// the point update's formulas (number.hpp) pass them by value between inline functions of one
// build, where GCC's -Wpsabi note (the calling convention differs with AVX) does not apply and is
// turned off (src/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace mpmshock {

typedef double Lanes __attribute__((vector_size(32)));
typedef std::int64_t LaneBits __attribute__((vector_size(32)));  // a lane's bits; comparison results
typedef std::int32_t LaneInts __attribute__((vector_size(16)));  // an int per lane

// Loads and stores through vector types of doubles aligned as a double: to the compiler they touch
// doubles only (a vector type aliases its element type), where a memcpy may touch any object. With
// memcpy every store into a nodal field made the transfers reload the field's data pointer, the
// stencil's columns and the grid's sizes for each row (issue 32: about 30 % of a transfer's
// instructions).
typedef double UnalignedLanes __attribute__((vector_size(32), aligned(alignof(double))));
typedef double UnalignedHalfLanes __attribute__((vector_size(16), aligned(alignof(double))));
[[gnu::always_inline]] inline void load_lanes(Lanes& v, const double* p) {
  v = *reinterpret_cast<const UnalignedLanes*>(p);
}
[[gnu::always_inline]] inline void store_lanes(double* p, const Lanes& v) { *reinterpret_cast<UnalignedLanes*>(p) = v; }

// A vector from two 2-lane halves (two nodes of (x, y) pairs, or parts of (x, y, z) triples), and
// its halves back.
typedef double HalfLanes __attribute__((vector_size(16)));
[[gnu::always_inline]] inline void load_half(HalfLanes& h, const double* p) {
  h = *reinterpret_cast<const UnalignedHalfLanes*>(p);
}
[[gnu::always_inline]] inline void store_half(double* p, const HalfLanes& h) {
  *reinterpret_cast<UnalignedHalfLanes*>(p) = h;
}
[[gnu::always_inline]] inline void join_halves(Lanes& v, const HalfLanes& low, const HalfLanes& high) {
  v = __builtin_shufflevector(low, high, 0, 1, 2, 3);
}
[[gnu::always_inline]] inline void split_halves(HalfLanes& low, HalfLanes& high, const Lanes& v) {
  low = __builtin_shufflevector(v, v, 0, 1);
  high = __builtin_shufflevector(v, v, 2, 3);
}

// std::abs and std::copysign lane by lane: the sign bit alone, so the same bits for every input.
[[gnu::always_inline]] inline void abs_lanes(Lanes& out, const Lanes& x) {
  const LaneBits sign = LaneBits{} + std::numeric_limits<std::int64_t>::min();
  out = reinterpret_cast<Lanes>(reinterpret_cast<LaneBits>(x) & ~sign);
}
[[gnu::always_inline]] inline void copysign_lanes(Lanes& out, const Lanes& magnitude, const Lanes& sign_of) {
  const LaneBits sign = LaneBits{} + std::numeric_limits<std::int64_t>::min();
  out = reinterpret_cast<Lanes>((reinterpret_cast<LaneBits>(magnitude) & ~sign) |
                                (reinterpret_cast<LaneBits>(sign_of) & sign));
}

// floor(u) lane by lane as ints, as detail::floor_index (shape.hpp) gives it: u held within
// [-1e9, 1e9] first (NaN to -1e9), truncated, and one less where that rounded a negative u up.
[[gnu::always_inline]] inline void floor_lanes(LaneInts& out, const Lanes& u) {
  Lanes held = u >= -1e9 ? u : Lanes{} - 1e9;
  held = held > 1e9 ? Lanes{} + 1e9 : held;
  const LaneInts truncated = __builtin_convertvector(held, LaneInts);
  const LaneBits rounded_up = __builtin_convertvector(truncated, Lanes) > held;  // -1 where true
  out = truncated + __builtin_convertvector(rounded_up, LaneInts);
}

// A 4 x 4 transpose of four 4-lane vectors (Lanes, LaneInts): afterwards v[l] holds lane l of each
// of the four vectors it held (moves only).
template <class V>
[[gnu::always_inline]] inline void transpose_lanes(V (&v)[4]) {
  const V t0 = __builtin_shufflevector(v[0], v[1], 0, 4, 2, 6), t1 = __builtin_shufflevector(v[0], v[1], 1, 5, 3, 7);
  const V t2 = __builtin_shufflevector(v[2], v[3], 0, 4, 2, 6), t3 = __builtin_shufflevector(v[2], v[3], 1, 5, 3, 7);
  v[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  v[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  v[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  v[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// A per-point field as four lanes (a point's values in a struct of arrays, Particles): points p..p+3 (kFour) or point p in every lane; and back.
// Scalar is a double or a struct of n doubles (Mat, Deviator), Vector its Lanes form: component
// k of the four points in lane order. Whole blocks of four components move as 4 x 4 transposes.
template <bool kFour, class Scalar, class Vector>
[[gnu::always_inline]] inline void load_points(Vector& out, const Scalar* at) {
  constexpr std::size_t n = sizeof(Scalar) / sizeof(double);
  static_assert(sizeof(Vector) == n * sizeof(Lanes), "a field's Lanes form holds four of its doubles each");
  const auto* d = reinterpret_cast<const double*>(at);
  Lanes v[n];
  std::size_t k = 0;
  if constexpr (kFour) {
    for (; k + 4 <= n; k += 4) {
      Lanes block[4];
      for (std::size_t l = 0; l < 4; ++l) load_lanes(block[l], d + l * n + k);
      transpose_lanes(block);
      for (std::size_t c = 0; c < 4; ++c) v[k + c] = block[c];
    }
    for (; k < n; ++k) v[k] = Lanes{d[k], d[n + k], d[2 * n + k], d[3 * n + k]};
  } else {
    for (; k < n; ++k) v[k] = Lanes{} + d[k];
  }
  std::memcpy(static_cast<void*>(&out), v, sizeof v);
}
template <bool kFour, class Scalar, class Vector>
[[gnu::always_inline]] inline void store_points(Scalar* at, const Vector& from) {
  constexpr std::size_t n = sizeof(Scalar) / sizeof(double);
  auto* d = reinterpret_cast<double*>(at);
  Lanes v[n];
  std::memcpy(v, static_cast<const void*>(&from), sizeof v);
  std::size_t k = 0;
  if constexpr (kFour) {
    for (; k + 4 <= n; k += 4) {
      Lanes block[4] = {v[k], v[k + 1], v[k + 2], v[k + 3]};
      transpose_lanes(block);
      for (std::size_t l = 0; l < 4; ++l) store_lanes(d + l * n + k, block[l]);
    }
    for (; k < n; ++k)
      for (std::size_t l = 0; l < 4; ++l) d[l * n + k] = v[k][l];
  } else {
    for (; k < n; ++k) d[k] = v[k][0];
  }
}

}  // namespace mpmshock
