// Region statistics (regions.hpp): sample_regions against the regions taken one at a time, as the
// definitions read (each region's members, their exact sums, the deviations about the region's
// mean, each point's share of a band), bit for bit; and against what a uniform state must give.
// sample_regions sums the points of a set of regions once and merges the sums into each region of
// the set (issue 32), which changes no bit only because exact sums merge exactly: this test fails
// if a point is left out of, or counted twice in, any region or band sum.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "mpmshock/exact_sum.hpp"
#include "mpmshock/regions.hpp"

using namespace mpmshock;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Flyer points in y < 1 mm and target points above, at random, with random states: every
// region below then has members of both bodies, members at its edges, and overlaps others.
Particles<2> random_points(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  Particles<2> p;
  p.enable_strength(true, false);
  const double spacing = 5e-6;
  for (std::size_t k = 0; k < n; ++k) {
    const double y = 2e-3 * unit(rng);
    const Body b = y < 1e-3 ? Body::flyer : Body::target;
    const Vec<2> velocity{{10.0 * sym(rng), -1000.0 + 50.0 * sym(rng)}};
    p.add(Vec<2>{{1e-4 * unit(rng), y}}, velocity, 2700.0 * spacing * spacing, spacing * spacing, b);
    p.F.back()(1, 1) = 0.8 + 0.3 * unit(rng);  // compressed and stretched extents
    p.F.back()(0, 1) = 0.01 * sym(rng);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) p.L.back()(i, j) = 1e6 * sym(rng);
    p.P.back() = 1e10 * unit(rng);
    p.q.back() = 1e9 * unit(rng);
    p.s.back().yy = 1e8 * sym(rng);
  }
  return p;
}

struct Expected {
  std::int64_t count = 0;
  double mean[6]{}, deviation[6]{}, rot2 = 0, div2 = 0, strain_rate2 = 0, macro[3]{};
};

// One region at a time, as regions.hpp defines its statistics (no thermal model: T is NaN).
Expected one_region(const Particles<2>& p, const RegionSpec& r, double cross_section) {
  double y_top = -1.0;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::target) y_top = std::max(y_top, p.x[q][1]);
  double lo = r.a, hi = r.b;
  const bool target_only = r.kind != RegionSpec::Kind::band;
  if (r.kind == RegionSpec::Kind::bottom) hi = r.a + r.b;
  if (r.kind == RegionSpec::Kind::top) lo = y_top - r.b, hi = y_top;
  auto member = [&](std::size_t q) {
    return (!target_only || p.body[q] == Body::target) && p.x[q][1] >= lo && p.x[q][1] <= hi;
  };
  auto quantity = [&](int k, std::size_t q) {
    switch (k) {
      case 0: return p.density(q);
      case 1: return p.P[q];
      case 2: return p.v[q][0];
      case 3: return p.v[q][1];
      case 4: return rotation2(p.L[q]);
      case 5: return trace(p.L[q]) * trace(p.L[q]);
      default: return strain_rate(p.L[q]).norm2();
    }
  };
  Expected e;
  ExactSum sums[7];
  for (std::size_t q = 0; q < p.size(); ++q)
    if (member(q)) {
      ++e.count;
      for (int k = 0; k < 7; ++k) sums[k].add(quantity(k, q));
    }
  const double n = static_cast<double>(e.count);
  double mean[7];
  for (int k = 0; k < 7; ++k) mean[k] = sums[k].value() / n;
  ExactSum deviations[4];
  for (std::size_t q = 0; q < p.size(); ++q)
    if (member(q))
      for (int k = 0; k < 4; ++k) {
        const double d = quantity(k, q) - mean[k];
        deviations[k].add(d * d);
      }
  for (int k = 0; k < 4; ++k) {
    e.mean[k] = mean[k];
    e.deviation[k] = std::sqrt(deviations[k].value() / n);
  }
  e.rot2 = mean[4];
  e.div2 = mean[5];
  e.strain_rate2 = mean[6];
  ExactSum band[3];
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (target_only && p.body[q] != Body::target) continue;
    const double half = 0.5 * std::pow(p.V0[q], 0.5) * std::abs(p.F[q](1, 1));
    const double inside = std::min(hi, p.x[q][1] + half) - std::max(lo, p.x[q][1] - half);
    if (inside <= 0.0) continue;
    const double share = std::min(1.0, inside / (2.0 * half)), V = share * p.volume(q);
    band[0].add(share * p.m[q]);
    band[1].add(V * p.P[q]);
    band[2].add(V * (p.P[q] + p.q[q] - p.s[q].yy));
  }
  for (int k = 0; k < 3; ++k) e.macro[k] = band[k].value() / ((hi - lo) * cross_section);
  return e;
}

void check_region(const RegionStats& got, const Expected& e, const std::string& name) {
  CHECK(got.name == name);
  CHECK(got.count == static_cast<std::size_t>(e.count));
  const MeanStd spread[4] = {got.density, got.pressure, got.velocity_x, got.velocity_y};
  for (int k = 0; k < 4; ++k) {
    CHECK(same_bits(spread[k].mean, e.mean[k]));
    CHECK(same_bits(spread[k].std, e.deviation[k]));
  }
  CHECK(std::isnan(got.temperature.mean));  // no thermal model
  CHECK(same_bits(got.rot2, e.rot2));
  CHECK(same_bits(got.div2, e.div2));
  CHECK(same_bits(got.strain_rate2, e.strain_rate2));
  CHECK(same_bits(got.macro_density, e.macro[0]));
  CHECK(same_bits(got.macro_pressure, e.macro[1]));
  CHECK(same_bits(got.macro_normal_stress, e.macro[2]));
}

// Nested, overlapping and disjoint regions of every kind, and more than 64 of them (a set of
// regions is then more than one word of bits): each one as if it were alone.
void regions_as_if_alone() {
  std::mt19937_64 rng(11);
  const Particles<2> p = random_points(rng, 3000);
  std::vector<RegionSpec> regions;
  for (double h : {100e-6, 400e-6, 800e-6}) {
    regions.push_back({"B" + std::to_string(h), RegionSpec::Kind::bottom, 1e-3, h});
    regions.push_back({"T" + std::to_string(h), RegionSpec::Kind::top, 0.0, h});
  }
  regions.push_back({"across", RegionSpec::Kind::band, 0.7e-3, 1.3e-3});  // both bodies
  for (int k = 0; k < 64; ++k) {  // thin bands, 30 um apart and 50 um wide: each overlaps the next
    const double y = 0.05e-3 + 30e-6 * k;
    regions.push_back({"thin" + std::to_string(k), RegionSpec::Kind::band, y, y + 50e-6});
  }
  const double cross_section = 1e-4;
  const std::vector<RegionStats> got = sample_regions(p, regions, nullptr, cross_section);
  CHECK(got.size() == regions.size());
  for (std::size_t r = 0; r < std::min(got.size(), regions.size()); ++r) {
    const Expected e = one_region(p, regions[r], cross_section);
    CHECK(e.count > 0);  // every region above has members
    check_region(got[r], e, regions[r].name);
  }
}

// A region with no points has NaN statistics; and a uniform state gives its own values with zero
// spread, whatever regions overlap it.
void empty_and_uniform() {
  Particles<2> p;
  p.enable_strength(true, false);
  const double spacing = 5e-6;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 200; ++j)
      p.add(Vec<2>{{(i + 0.5) * spacing, (j + 0.5) * spacing}}, Vec<2>{{0.0, -500.0}}, 2700.0 * spacing * spacing,
            spacing * spacing, Body::target);
  for (std::size_t q = 0; q < p.size(); ++q) p.P[q] = 5e9;
  const std::vector<RegionSpec> regions = {{"above", RegionSpec::Kind::band, 2e-3, 3e-3},
                                           {"all", RegionSpec::Kind::bottom, 0.0, 1e-3},
                                           {"inner", RegionSpec::Kind::band, 0.2e-3, 0.4e-3},
                                           {"top", RegionSpec::Kind::top, 0.0, 0.3e-3}};
  const double width = 20 * spacing;
  const std::vector<RegionStats> got = sample_regions(p, regions, nullptr, width);
  CHECK(got[0].count == 0);
  CHECK(std::isnan(got[0].density.mean) && std::isnan(got[0].pressure.std));
  CHECK(got[0].macro_density == 0.0);  // an empty band has no mass
  CHECK(got[1].count == p.size());
  for (std::size_t r = 1; r < got.size(); ++r) {
    CHECK_NEAR(got[r].density.mean, 2700.0, 1e-9);
    CHECK(got[r].density.std == 0.0 && got[r].pressure.std == 0.0 && got[r].velocity_y.std == 0.0);
    CHECK(got[r].pressure.mean == 5e9);
    CHECK(got[r].velocity_y.mean == -500.0);
  }
  // The points tile [0, 1 mm] in y: a band inside the material has the material's density.
  CHECK_NEAR(got[2].macro_density, 2700.0, 2700.0 * 1e-12);
  CHECK_NEAR(got[2].macro_pressure, 5e9, 5e9 * 1e-12);
  CHECK_NEAR(got[1].macro_density, 2700.0, 2700.0 * 1e-12);
}

}  // namespace

int main() {
  regions_as_if_alone();
  empty_and_uniform();
  return check::result();
}
