#include "mpmshock/regions.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <map>

#include "mpmshock/exact_sum.hpp"
#include "mpmshock/lanes.hpp"

namespace mpmshock {

const char* const kRegionsHeader =
    "time,region,count,density_mean,density_std,pressure_mean,pressure_std,temperature_mean,temperature_std,"
    "velocity_x_mean,velocity_x_std,velocity_y_mean,velocity_y_std,rot2_mean,div2_mean,strain_rate2_mean,"
    "macro_density,macro_pressure,macro_normal_stress";

std::string regions_header(bool paper_temperature) {
  return std::string(kRegionsHeader) + (paper_temperature ? ",paper_temperature_mean,paper_temperature_std" : "");
}

namespace {

// Highest y of the target's points on every rank.
template <int D>
double target_top(const Particles<D>& p, const Comm& comm) {
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::target) top = std::max(top, p.x[q][1]);
  return comm.max(top);
}

struct Band {
  double lo, hi;
  bool target_only;
};

Band band_of(const RegionSpec& r, double y_top) {
  switch (r.kind) {
    case RegionSpec::Kind::bottom: return {r.a, r.a + r.b, true};
    case RegionSpec::Kind::top: return {y_top - r.b, y_top, true};
    case RegionSpec::Kind::band: break;
  }
  return {r.a, r.b, false};
}

template <int D>
bool in_band(const Particles<D>& p, std::size_t q, const Band& b) {
  return (!b.target_only || p.body[q] == Body::target) && p.x[q][1] >= b.lo && p.x[q][1] <= b.hi;
}

// The quantities of a region: those with a mean and a deviation, those with a mean only, and the
// band sums of the macroscopic averages.
enum Spread { kDensity, kPressure, kTemperature, kPaperTemperature, kVelocityX, kVelocityY, kSpreads };
enum Mean { kRot2 = kSpreads, kDiv2, kStrainRate2, kMeans };
enum BandSum { kBandMass = kMeans, kBandPressure, kBandNormal, kSums };

// Adds term(m, k) of every member m of a region to s[k], for k < fields: four members at a time
// (ExactSum::add_lanes gives the words that four add() calls give, a third of their instructions).
template <class Term>
void add_over_members(ExactSum* s, int fields, const std::vector<std::uint32_t>& members, Term&& term) {
  std::size_t i = 0;
  for (; i + 4 <= members.size(); i += 4)
    for (int k = 0; k < fields; ++k)
      s[k].add_lanes(Lanes{term(members[i], k), term(members[i + 1], k), term(members[i + 2], k), term(members[i + 3], k)});
  const int rest = static_cast<int>(members.size() - i);
  if (rest == 0) return;
  for (int k = 0; k < fields; ++k) {
    Lanes x{};
    for (int l = 0; l < rest; ++l) x[l] = term(members[i + static_cast<std::size_t>(l)], k);
    s[k].add_lanes(x, rest);
  }
}

template <int D>
struct PointValues {
  const Particles<D>& p;
  const BodyTemperatures* thermal;
  double operator()(int k, std::size_t q) const {
    switch (k) {
      case kDensity: return p.density(q);
      case kPressure: return p.P[q];
      case kTemperature: return thermal ? thermal->of_point(p, q) : std::nan("");
      case kPaperTemperature: return thermal && thermal->reports_paper_temperature() ? thermal->paper_of_point(p, q) : 0.0;
      case kVelocityX: return p.v[q][0];
      case kVelocityY: return p.v[q][1];
      case kRot2: return rotation2(p.L[q]);
      case kDiv2: {
        const double div = trace(p.L[q]);
        return div * div;
      }
      case kStrainRate2: return strain_rate(p.L[q]).norm2();
      default: return 0.0;
    }
  }
};

// Points that lie in the same set of regions: each set's sums are taken once and merged into each
// of its regions' sums (exact sums merge exactly, so the totals are the same bits), so that a point
// in k of the nested bands costs one sum per quantity, not k (issue 32: with the default six bands,
// 1,710 -> 1,350 instructions per point and sample; tests/test_regions.cpp checks the same bits).
class RegionSets {
 public:
  explicit RegionSets(std::size_t regions) : words_((regions + 63) / 64), bits_(words_) {}
  // Starts a point's set; add(r) for each region it lies in; then set() is its set's index.
  void clear() { std::fill(bits_.begin(), bits_.end(), 0); }
  void add(std::size_t r) { bits_[r / 64] |= std::uint64_t{1} << (r % 64); }
  bool empty() const {
    for (const std::uint64_t w : bits_)
      if (w != 0) return false;
    return true;
  }
  std::size_t set() {
    if (const auto it = index_.find(bits_); it != index_.end()) return it->second;  // no node made
    index_.emplace(bits_, regions_of_.size());
    regions_of_.emplace_back();
    for (std::size_t r = 0; r < 64 * words_; ++r)
      if ((bits_[r / 64] >> (r % 64)) & 1u) regions_of_.back().push_back(r);
    return regions_of_.size() - 1;
  }
  std::size_t count() const { return regions_of_.size(); }
  const std::vector<std::size_t>& regions_of(std::size_t set) const { return regions_of_[set]; }

 private:
  std::size_t words_;
  std::vector<std::uint64_t> bits_;
  std::map<std::vector<std::uint64_t>, std::size_t> index_;
  std::vector<std::vector<std::size_t>> regions_of_;
};

// Adds a set's exact sums from[0 .. fields) to into[r * kSums + first + k] for each region r of it.
void merge_into_regions(const std::vector<std::size_t>& regions, const ExactSum* from, int fields,
                        std::vector<ExactSum>& into, int first = 0) {
  for (const std::size_t r : regions)
    for (int k = 0; k < fields; ++k) into[r * kSums + static_cast<std::size_t>(first + k)] += from[k];
}

// The bands' mass, V P and V (P + q - s_yy), each point counted with the share of its y extent (its
// initial spacing V0^(1/D) stretched by F_yy) inside [lo, hi]; each point's extent once for all bands.
// A point wholly inside a band adds the same three terms to each such band, so those go to the sums
// of its set of bands (RegionSets) and are merged once; the shares of a band's edge points are added apart.
template <int D>
void add_band_sums(const Particles<D>& p, const std::vector<Band>& bands, std::vector<ExactSum>& sums) {
  RegionSets whole(bands.size());
  std::vector<std::array<ExactSum, 3>> of_set;
  for (std::size_t q = 0; q < p.size(); ++q) {
    const bool target = p.body[q] == Body::target;
    const double half = 0.5 * std::pow(p.V0[q], 1.0 / D) * std::abs(p.F[q](1, 1));
    const double y = p.x[q][1];
    const double V = p.volume(q), normal_stress = p.P[q] + p.q[q] - (p.s.empty() ? 0.0 : p.s[q].yy);
    whole.clear();
    for (std::size_t r = 0; r < bands.size(); ++r) {
      const Band& b = bands[r];
      if (b.target_only && !target) continue;
      const double inside = std::min(b.hi, y + half) - std::max(b.lo, y - half);
      if (inside <= 0.0) continue;
      const double share = std::min(1.0, inside / (2.0 * half));
      if (share == 1.0) {  // the terms below with share 1, bitwise
        whole.add(r);
        continue;
      }
      const double Vs = share * V;
      ExactSum* s = &sums[r * kSums];
      s[kBandMass].add(share * p.m[q]);
      s[kBandPressure].add(Vs * p.P[q]);
      s[kBandNormal].add(Vs * normal_stress);
    }
    if (whole.empty()) continue;
    const std::size_t set = whole.set();
    if (set == of_set.size()) of_set.emplace_back();
    std::array<ExactSum, 3>& s = of_set[set];
    s[0].add(p.m[q]);
    s[1].add(V * p.P[q]);
    s[2].add(V * normal_stress);
  }
  for (std::size_t set = 0; set < of_set.size(); ++set)
    merge_into_regions(whole.regions_of(set), of_set[set].data(), 3, sums, kBandMass);
}

}  // namespace

template <int D>
std::vector<RegionStats> sample_regions(const Particles<D>& p, const std::vector<RegionSpec>& regions,
                                        const BodyTemperatures* thermal, double cross_section, const Comm& comm) {
  const double y_top = target_top(p, comm);
  const PointValues<D> value{p, thermal};
  const std::size_t n = regions.size();
  std::vector<Band> bands(n);
  for (std::size_t r = 0; r < n; ++r) bands[r] = band_of(regions[r], y_top);
  // Pass 1, on every rank: counts and sums; then the means, the same on every rank. Each point in
  // a band has its quantities computed once (the temperature costs most) and kept for pass 2, in the
  // members of its set of regions (RegionSets); the sums are exact, so neither the order they are
  // added in nor the grouping by sets matters.
  std::vector<std::array<double, kMeans>> values;    // of the points in at least one band
  RegionSets sets(n);
  std::vector<std::vector<std::uint32_t>> members;  // of each set: indices into values
  for (std::size_t q = 0; q < p.size(); ++q) {
    sets.clear();
    for (std::size_t r = 0; r < n; ++r)
      if (in_band(p, q, bands[r])) sets.add(r);
    if (sets.empty()) continue;
    const std::size_t set = sets.set();
    if (set == members.size()) members.emplace_back();
    values.emplace_back();
    for (int k = 0; k < kMeans; ++k) values.back()[static_cast<std::size_t>(k)] = value(k, q);
    members[set].push_back(static_cast<std::uint32_t>(values.size() - 1));
  }
  std::vector<ExactSum> sums(n * kSums);
  std::vector<std::int64_t> counts(n);
  for (std::size_t set = 0; set < sets.count(); ++set) {
    ExactSum set_sums[kMeans];
    add_over_members(set_sums, kMeans, members[set],
                     [&](std::uint32_t m, int k) { return values[m][static_cast<std::size_t>(k)]; });
    merge_into_regions(sets.regions_of(set), set_sums, kMeans, sums);
    for (const std::size_t r : sets.regions_of(set)) counts[r] += static_cast<std::int64_t>(members[set].size());
  }
  add_band_sums(p, bands, sums);
  comm.sum(counts.data(), static_cast<int>(n));
  comm.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<double> means(n * kMeans);
  for (std::size_t r = 0; r < n; ++r)
    for (int k = 0; k < kMeans; ++k)
      means[r * kMeans + k] = counts[r] > 0 ? sums[r * kSums + k].value() / static_cast<double>(counts[r]) : std::nan("");
  // Pass 2: the population deviations about those means (no cancellation).
  std::vector<ExactSum> deviations(n * kSpreads);
  for (std::size_t set = 0; set < sets.count(); ++set)
    for (const std::size_t r : sets.regions_of(set))
      add_over_members(&deviations[r * kSpreads], kSpreads, members[set], [&](std::uint32_t m, int k) {
        const double d = values[m][static_cast<std::size_t>(k)] - means[r * kMeans + static_cast<std::size_t>(k)];
        return d * d;
      });
  comm.sum(deviations.data(), static_cast<int>(deviations.size()));

  std::vector<RegionStats> out(n);
  for (std::size_t r = 0; r < n; ++r) {
    RegionStats& s = out[r];
    s.name = regions[r].name;
    s.count = static_cast<std::size_t>(counts[r]);
    auto stat = [&](int k) -> MeanStd {
      if (counts[r] == 0) return {std::nan(""), std::nan("")};
      return {means[r * kMeans + k],
              std::sqrt(deviations[r * kSpreads + k].value() / static_cast<double>(counts[r]))};
    };
    s.density = stat(kDensity);
    s.pressure = stat(kPressure);
    s.temperature = stat(kTemperature);
    if (thermal && thermal->reports_paper_temperature()) s.paper_temperature = stat(kPaperTemperature);
    s.velocity_x = stat(kVelocityX);
    s.velocity_y = stat(kVelocityY);
    s.rot2 = means[r * kMeans + kRot2];
    s.div2 = means[r * kMeans + kDiv2];
    s.strain_rate2 = means[r * kMeans + kStrainRate2];
    const Band& b = bands[r];
    const double area = (b.hi - b.lo) * cross_section;
    s.macro_density = sums[r * kSums + kBandMass].value() / area;
    s.macro_pressure = sums[r * kSums + kBandPressure].value() / area;
    s.macro_normal_stress = sums[r * kSums + kBandNormal].value() / area;
  }
  return out;
}

void write_region_rows(std::FILE* out, double time, const std::vector<RegionStats>& stats) {
  for (const RegionStats& s : stats) {
    std::fprintf(out,
                 "%.10g,%s,%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,"
                 "%.10g",
                 time, s.name.c_str(), s.count, s.density.mean, s.density.std, s.pressure.mean, s.pressure.std,
                 s.temperature.mean, s.temperature.std, s.velocity_x.mean, s.velocity_x.std, s.velocity_y.mean,
                 s.velocity_y.std, s.rot2, s.div2, s.strain_rate2, s.macro_density, s.macro_pressure,
                 s.macro_normal_stress);
    if (s.paper_temperature) std::fprintf(out, ",%.10g,%.10g", s.paper_temperature->mean, s.paper_temperature->std);
    std::fputc('\n', out);
  }
}

template std::vector<RegionStats> sample_regions<2>(const Particles<2>&, const std::vector<RegionSpec>&,
                                                    const BodyTemperatures*, double, const Comm&);
template std::vector<RegionStats> sample_regions<3>(const Particles<3>&, const std::vector<RegionSpec>&,
                                                    const BodyTemperatures*, double, const Comm&);

}  // namespace mpmshock
