// Exact sums of doubles, the same bits in whatever order the terms come: what makes a sum over
// material points independent of how the points are shared between threads and MPI ranks.
//
// Every finite double is an integer multiple of 2^-1074 below 2^1024, so a sum of them is an integer
// in those units. ExactSum keeps it as 68 signed 64-bit digits of 32 bits each (digit k weighs
// 2^(32k - 1074)); adding a double adds its 53-bit significand, shifted, into three digits, with no
// rounding. The digits absorb 2^30 additions before carries must be passed up, so normalising is rare.
// Two sums merge by adding digits (integers: exact and commutative), which is also how MPI combines
// them (comm.hpp). value() rounds the exact total once, to nearest (ties to even), from its
// canonical digits, so the result depends on the terms alone, never on their order (below 2^-1022
// a second rounding to the subnormal grid may follow; a total of zero is +0). NaN and infinities are
// counted apart and give what IEEE addition would: NaN if any term is NaN or both infinities occur,
// else the infinity.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "mpmshock/lanes.hpp"

namespace mpmshock {

class ExactSum {
 public:
  static constexpr int kDigits = 68;  // 2046 exponents + 53 bits + carries, in 32-bit digits
  // The digits and the counts of NaN, +inf and -inf: all of the state, as integers to add.
  static constexpr int kWords = kDigits + 3;

  ExactSum() { words_.fill(0); }

  [[gnu::always_inline]] void add(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    if ((bits << 1) == 0) return;  // +-0, common (states at rest)
    const int exponent = static_cast<int>((bits >> 52) & 0x7ff);
    if (exponent == 0x7ff) {  // NaN or infinity
      count_special(bits);
      return;
    }
    // x = significand * 2^(offset - 1074), offset = max(exponent, 1) - 1 in [0, 2045]. Without
    // branches: the sign and the subnormal case as masks, as this runs per point.
    const std::uint64_t normal = exponent != 0 ? 1 : 0;
    const std::uint64_t significand = (bits & ((std::uint64_t{1} << 52) - 1)) | (normal << 52);
    const int offset = exponent - static_cast<int>(normal);
    const int digit = offset >> 5, shift = offset & 31;
    // significand << shift has up to 85 bits: 64 in `bits64`, the rest in `high` (0 for shift 0).
    const std::uint64_t bits64 = significand << shift;
    const auto low = static_cast<std::int64_t>(bits64 & 0xffffffffu);
    const auto mid = static_cast<std::int64_t>(bits64 >> 32);
    const auto high = static_cast<std::int64_t>((significand >> 1) >> (63 - shift));
    const std::int64_t negate = -static_cast<std::int64_t>(bits >> 63);  // -1 for x < 0: (v ^ -1) + 1 = -v
    words_[digit] += (low ^ negate) - negate;
    words_[digit + 1] += (mid ^ negate) - negate;
    words_[digit + 2] += (high ^ negate) - negate;
    if (++additions_ >= kAdditionsBeforeCarry) carry();
  }

  // The first `count` lanes of x (four doubles, lanes.hpp), as that many add() calls give them:
  // the digits and shifts of the four computed at once, each lane's three digits added apart.
  void add_lanes(const Lanes& x, int count = 4) {
    typedef std::uint64_t Bits __attribute__((vector_size(32)));
    typedef std::int64_t Signed __attribute__((vector_size(32)));
    const Bits bits = reinterpret_cast<Bits>(x);
    const Bits mantissa = Bits{} + ((std::uint64_t{1} << 52) - 1);
    const Signed exponent = reinterpret_cast<Signed>((bits >> 52) & 0x7ff);
    const Signed normal = -(exponent != 0);  // 1 where normal (a comparison gives -1)
    const Bits significand = (bits & mantissa) | (reinterpret_cast<Bits>(normal) << 52);
    const Signed offset = exponent - normal;
    const Signed digit = offset >> 5;
    const Bits shift = reinterpret_cast<Bits>(offset & 31);
    const Bits bits64 = significand << shift;
    const Signed low = reinterpret_cast<Signed>(bits64 & 0xffffffffu), mid = reinterpret_cast<Signed>(bits64 >> 32);
    const Signed high = reinterpret_cast<Signed>((significand >> 1) >> (63 - shift));
    const Signed negate = -reinterpret_cast<Signed>(bits >> 63);
    const Signed low_s = (low ^ negate) - negate, mid_s = (mid ^ negate) - negate, high_s = (high ^ negate) - negate;
    for (int l = 0; l < count; ++l) {
      if ((bits[l] << 1) == 0) continue;  // +-0
      if (exponent[l] == 0x7ff) {  // NaN or infinity
        count_special(bits[l]);
        continue;
      }
      const auto d = static_cast<std::size_t>(digit[l]);
      words_[d] += low_s[l];
      words_[d + 1] += mid_s[l];
      words_[d + 2] += high_s[l];
    }
    additions_ += count;
    if (additions_ >= kAdditionsBeforeCarry) carry();
  }

  ExactSum& operator+=(const ExactSum& other) {
    carry();
    ExactSum o = other;
    o.carry();
    for (int k = 0; k < kWords; ++k) words_[k] += o.words_[k];
    carry();
    return *this;
  }

  // The total rounded once to a double (NaN or an infinity as IEEE addition gives them).
  double value() const {
    const std::int64_t nans = words_[kDigits], plus = words_[kDigits + 1], minus = words_[kDigits + 2];
    if (nans > 0 || (plus > 0 && minus > 0)) return std::nan("");
    if (plus > 0) return HUGE_VAL;
    if (minus > 0) return -HUGE_VAL;
    ExactSum c = *this;
    c.carry();
    double sign = 1.0;
    if (c.words_[kDigits - 1] < 0) {  // negative: round its magnitude
      for (int k = 0; k < kDigits; ++k) c.words_[k] = -c.words_[k];
      c.carry();
      sign = -1.0;
    }
    int top = kDigits - 1;
    while (top >= 0 && c.words_[top] == 0) --top;
    if (top < 0) return 0.0;
    // The 64 bits from the leading one down, and whether any bit below them is set.
    auto digit = [&](int k) { return k >= 0 ? static_cast<std::uint64_t>(c.words_[k]) : std::uint64_t{0}; };
    int lead = 31;
    while (!((digit(top) >> lead) & 1u)) --lead;
    const int shift = 31 - lead;  // puts the leading one at bit 63
    const std::uint64_t upper = (digit(top) << 32) | digit(top - 1), lower = digit(top - 2);
    std::uint64_t window = upper << shift;
    bool sticky = false;
    if (shift > 0) {
      window |= lower >> (32 - shift);
      sticky = (lower & ((std::uint64_t{1} << (32 - shift)) - 1)) != 0;
    } else {
      sticky = lower != 0;
    }
    for (int k = top - 3; k >= 0 && !sticky; --k) sticky = c.words_[k] != 0;
    // Round the 64 bits to 53, to nearest, ties to even.
    std::uint64_t kept = window >> 11;
    const std::uint64_t rest = window & 0x7ff, half = 0x400;
    if (rest > half || (rest == half && (sticky || (kept & 1u)))) ++kept;
    const int position = 32 * top + lead;  // of the leading one, in units of 2^-1074
    return sign * std::ldexp(static_cast<double>(kept), position - 52 - 1074);
  }

  // The state as integers, for a sum across processes (add word by word, then from_words).
  const std::array<std::int64_t, kWords>& words() const { return words_; }
  static ExactSum from_words(const std::int64_t* words) {
    ExactSum s;
    for (int k = 0; k < kWords; ++k) s.words_[k] = words[k];
    s.carry();
    return s;
  }
  // Canonical form (each digit but the top one in [0, 2^32)), so that words() can be added.
  void carry() {
    for (int k = 0; k + 1 < kDigits; ++k) {
      const std::int64_t up = words_[k] >> 32;  // floor division by 2^32
      words_[k] -= up * (std::int64_t{1} << 32);
      words_[k + 1] += up;
    }
    additions_ = 0;
  }

 private:
  // A NaN or an infinity (bits of exponent 0x7ff), counted apart.
  void count_special(std::uint64_t bits) {
    const bool nan = (bits & ((std::uint64_t{1} << 52) - 1)) != 0;
    ++words_[nan ? kDigits : (bits >> 63 ? kDigits + 2 : kDigits + 1)];
  }
  static constexpr int kAdditionsBeforeCarry = 1 << 30;
  std::array<std::int64_t, kWords> words_;
  int additions_ = 0;
};

}  // namespace mpmshock
