// ExactSum: the same bits whatever the order of the terms and however they are split into partial
// sums (threads, MPI ranks), and the exact total where double addition loses it.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "check.hpp"
#include "mpmshock/exact_sum.hpp"

using mpmshock::ExactSum;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

double sum_of(const std::vector<double>& terms) {
  ExactSum s;
  for (double x : terms) s.add(x);
  return s.value();
}

// Terms over 600 decades, both signs, and subnormals: every digit position and carry is used.
std::vector<double> wild_terms(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-1070, 1000), sign(0, 1);
  std::vector<double> terms(n);
  for (double& x : terms) x = (sign(rng) ? -1.0 : 1.0) * std::ldexp(mantissa(rng), exponent(rng));
  terms[0] = std::numeric_limits<double>::denorm_min();
  terms[1] = -5e-320;
  return terms;
}

void order_does_not_matter() {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> terms = wild_terms(rng, 2000);
    // Physical-looking terms too: energies of points, 1e-12 to 1e3 J, mostly positive.
    std::uniform_real_distribution<double> u(-0.1, 1.0);
    for (int k = 0; k < 2000; ++k) terms.push_back(u(rng) * std::pow(10.0, 3.0 - (k % 15)));
    const double reference = sum_of(terms);
    for (int shuffle = 0; shuffle < 5; ++shuffle) {
      std::shuffle(terms.begin(), terms.end(), rng);
      CHECK(same_bits(sum_of(terms), reference));
      // Split into partial sums, merged in another order (as threads and ranks do).
      std::vector<ExactSum> parts(7);
      for (std::size_t k = 0; k < terms.size(); ++k) parts[(k * 31) % parts.size()].add(terms[k]);
      ExactSum merged;
      for (int k = 6; k >= 0; --k) merged += parts[k];
      CHECK(same_bits(merged.value(), reference));
      // Through the integer words, as an MPI sum adds them.
      std::vector<std::int64_t> words(ExactSum::kWords, 0);
      for (ExactSum& p : parts) {
        p.carry();
        for (int w = 0; w < ExactSum::kWords; ++w) words[w] += p.words()[w];
      }
      CHECK(same_bits(ExactSum::from_words(words.data()).value(), reference));
    }
  }
}

void exact_where_doubles_are_not() {
  // 1e300 + 1 - 1e300 is 0 in doubles, 1 exactly.
  ExactSum a;
  for (double x : {1e300, 1.0, -1e300}) a.add(x);
  CHECK(a.value() == 1.0);
  // 0.1 added 10 times: 0.9999999999999999 in doubles; the exact sum of those ten doubles rounds to 1.
  ExactSum b;
  for (int k = 0; k < 10; ++k) b.add(0.1);
  CHECK(b.value() == 1.0);
  // Integers: exact far beyond 2^53 partial sums, and a total of zero is +0.
  ExactSum c;
  for (int k = 0; k < 1000; ++k) c.add(std::ldexp(1.0, 60)), c.add(3.0);
  for (int k = 0; k < 1000; ++k) c.add(-std::ldexp(1.0, 60));
  CHECK(c.value() == 3000.0);
  ExactSum z;
  z.add(2.5), z.add(-2.5);
  CHECK(z.value() == 0.0 && !std::signbit(z.value()));
  CHECK(ExactSum().value() == 0.0);
  // Negative totals, and the largest and smallest doubles.
  ExactSum n;
  n.add(-std::numeric_limits<double>::max()), n.add(std::numeric_limits<double>::denorm_min());
  CHECK(n.value() == -std::numeric_limits<double>::max());
  ExactSum d;
  d.add(std::numeric_limits<double>::denorm_min()), d.add(std::numeric_limits<double>::denorm_min());
  CHECK(d.value() == 2 * std::numeric_limits<double>::denorm_min());
}

void rounded_once_to_nearest() {
  // Against a sum that long double (64-bit significand) holds exactly, converted to double with one
  // rounding to nearest: terms of 40 bits at exponents within a span of 20, so every partial sum
  // fits in 64 bits. And ties: 1 + 2^-53 rounds to 1 (even), 1 + 3 2^-53 to 1 + 2^-51.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> digits(-(std::int64_t{1} << 40), std::int64_t{1} << 40);
  std::uniform_int_distribution<int> exponent(-10, 10);
  for (int trial = 0; trial < 100; ++trial) {
    ExactSum s;
    long double exact = 0.0L;
    for (int k = 0; k < 500; ++k) {
      const double x = std::ldexp(static_cast<double>(digits(rng)), exponent(rng));
      s.add(x);
      exact += x;
    }
    CHECK(same_bits(s.value(), static_cast<double>(exact)));
  }
  ExactSum tie;
  tie.add(1.0), tie.add(std::ldexp(1.0, -53));
  CHECK(tie.value() == 1.0);
  ExactSum up;
  up.add(1.0), up.add(std::ldexp(3.0, -53));
  CHECK(up.value() == 1.0 + std::ldexp(1.0, -51));
  ExactSum sticky;  // just above the tie: up
  sticky.add(1.0), sticky.add(std::ldexp(1.0, -53)), sticky.add(std::ldexp(1.0, -200));
  CHECK(sticky.value() == 1.0 + std::ldexp(1.0, -52));
  ExactSum negative;
  negative.add(-1.0), negative.add(-std::ldexp(3.0, -53));
  CHECK(negative.value() == -(1.0 + std::ldexp(1.0, -51)));
}

void nan_and_infinity_as_ieee() {
  const double inf = std::numeric_limits<double>::infinity();
  ExactSum a;
  a.add(1.0), a.add(inf);
  CHECK(a.value() == inf);
  ExactSum b;
  b.add(-inf), b.add(1.0);
  CHECK(b.value() == -inf);
  ExactSum c;
  c.add(inf), c.add(-inf);
  CHECK(std::isnan(c.value()));
  ExactSum d;
  d.add(std::nan("")), d.add(1.0);
  CHECK(std::isnan(d.value()));
  ExactSum e;
  e += d;
  CHECK(std::isnan(e.value()));
}

void many_terms_carry() {
  // More additions than a digit holds between carries would overflow without them: 2^31 terms is
  // too slow here, so check the carry itself keeps digits canonical under repeated large terms.
  ExactSum s;
  const double big = std::ldexp(0x1.fffffffffffffp0, 40);
  for (int k = 0; k < 3'000'000; ++k) s.add(big);
  CHECK_REL(s.value(), 3e6 * big, 1e-15);
  s.carry();
  for (int w = 0; w + 1 < ExactSum::kDigits; ++w) CHECK(s.words()[w] >= 0 && s.words()[w] < (std::int64_t{1} << 32));
}

}  // namespace

// Four terms at a time (add_lanes, the point update's) hold the very digits one at a time give,
// for wild terms, zeros of both signs, subnormals, NaN and infinities, and groups of 1 to 4.
void lanes_as_one_at_a_time() {
  std::mt19937_64 rng(11);
  std::vector<double> terms = wild_terms(rng, 4000);
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < terms.size(); k += 97) terms[k] = 0.0;
  for (std::size_t k = 5; k < terms.size(); k += 101) terms[k] = -0.0;
  terms[7] = inf, terms[8] = -inf, terms[9] = std::nan("");
  ExactSum one, four;
  std::size_t k = 0;
  for (int group = 0; k < terms.size(); ++group) {
    const int count = std::min<int>(1 + group % 4, static_cast<int>(terms.size() - k));
    mpmshock::Lanes x{};
    for (int l = 0; l < count; ++l) x[l] = terms[k + static_cast<std::size_t>(l)];
    for (int l = count; l < 4; ++l) x[l] = 1e300;  // beyond count: never added
    four.add_lanes(x, count);
    for (int l = 0; l < count; ++l) one.add(terms[k + static_cast<std::size_t>(l)]);
    k += static_cast<std::size_t>(count);
  }
  CHECK(one.words() == four.words());
  // Without the special values the totals compare as numbers too.
  ExactSum a, b;
  for (std::size_t j = 12; j + 4 <= terms.size(); j += 4) {
    a.add_lanes(mpmshock::Lanes{terms[j], terms[j + 1], terms[j + 2], terms[j + 3]});
    for (std::size_t l = 0; l < 4; ++l) b.add(terms[j + l]);
  }
  CHECK(same_bits(a.value(), b.value()));
  CHECK(a.words() == b.words());
}

int main() {
  order_does_not_matter();
  lanes_as_one_at_a_time();
  exact_where_doubles_are_not();
  rounded_once_to_nearest();
  nan_and_infinity_as_ieee();
  many_terms_carry();
  return check::result();
}
