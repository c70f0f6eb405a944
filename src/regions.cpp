#include "mpmshock/regions.hpp"

#include <cmath>
#include <limits>

namespace mpmshock {

const char* const kRegionsHeader =
    "time,region,count,density_mean,density_std,pressure_mean,pressure_std,temperature_mean,temperature_std,"
    "velocity_x_mean,velocity_x_std,velocity_y_mean,velocity_y_std,rot2_mean,div2_mean,strain_rate2_mean,"
    "macro_density,macro_pressure,macro_normal_stress";

std::string regions_header(bool paper_temperature) {
  return std::string(kRegionsHeader) + (paper_temperature ? ",paper_temperature_mean,paper_temperature_std" : "");
}

template <int D>
double target_top(const Particles<D>& p) {
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::target) top = std::max(top, p.x[q][1]);
  return top;
}

namespace {

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

}  // namespace

template <int D>
std::vector<std::size_t> points_in_region(const Particles<D>& p, const RegionSpec& r, double y_top) {
  const Band b = band_of(r, y_top);
  std::vector<std::size_t> out;
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (b.target_only && p.body[q] != Body::target) continue;
    if (p.x[q][1] >= b.lo && p.x[q][1] <= b.hi) out.push_back(q);
  }
  return out;
}

template <int D>
void macro_averages(const Particles<D>& p, double lo, double hi, bool target_only, double cross_section,
                    RegionStats& s) {
  double mass = 0.0, pressure = 0.0, normal = 0.0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (target_only && p.body[q] != Body::target) continue;
    // The point's y extent: its initial spacing V0^(1/D) stretched by F_yy.
    const double half = 0.5 * std::pow(p.V0[q], 1.0 / D) * std::abs(p.F[q](1, 1));
    const double y = p.x[q][1];
    const double inside = std::min(hi, y + half) - std::max(lo, y - half);
    if (inside <= 0.0) continue;
    const double share = std::min(1.0, inside / (2.0 * half)), V = share * p.volume(q);
    mass += share * p.m[q];
    pressure += V * p.P[q];
    normal += V * (p.P[q] + p.q[q] - (p.s.empty() ? 0.0 : p.s[q].yy));
  }
  const double area = (hi - lo) * cross_section;
  s.macro_density = mass / area;
  s.macro_pressure = pressure / area;
  s.macro_normal_stress = normal / area;
}

namespace {

// Mean and population deviation of f over the points, in two passes (no cancellation).
template <class F>
MeanStd mean_std(const std::vector<std::size_t>& points, F&& f) {
  if (points.empty()) return {std::nan(""), std::nan("")};
  double sum = 0.0;
  for (std::size_t q : points) sum += f(q);
  const double mean = sum / static_cast<double>(points.size());
  double dev2 = 0.0;
  for (std::size_t q : points) {
    const double d = f(q) - mean;
    dev2 += d * d;
  }
  return {mean, std::sqrt(dev2 / static_cast<double>(points.size()))};
}

template <class F>
double mean_of(const std::vector<std::size_t>& points, F&& f) {
  if (points.empty()) return std::nan("");
  double sum = 0.0;
  for (std::size_t q : points) sum += f(q);
  return sum / static_cast<double>(points.size());
}

}  // namespace

template <int D>
RegionStats region_stats(const Particles<D>& p, const std::vector<std::size_t>& points, const std::string& name,
                         const HugoniotTemperature* thermal) {
  RegionStats s;
  s.name = name;
  s.count = points.size();
  s.density = mean_std(points, [&](std::size_t q) { return p.density(q); });
  s.pressure = mean_std(points, [&](std::size_t q) { return p.P[q]; });
  if (thermal) {
    s.temperature = mean_std(points, [&](std::size_t q) { return thermal->of_point(p, q); });
    if (thermal->reports_paper_temperature())
      s.paper_temperature = mean_std(points, [&](std::size_t q) { return thermal->paper_of_point(p, q); });
  } else {
    s.temperature = {std::nan(""), std::nan("")};
  }
  s.velocity_x = mean_std(points, [&](std::size_t q) { return p.v[q][0]; });
  s.velocity_y = mean_std(points, [&](std::size_t q) { return p.v[q][1]; });
  s.rot2 = mean_of(points, [&](std::size_t q) { return rotation2(p.L[q]); });
  s.div2 = mean_of(points, [&](std::size_t q) {
    const double div = trace(p.L[q]);
    return div * div;
  });
  s.strain_rate2 = mean_of(points, [&](std::size_t q) { return strain_rate(p.L[q]).norm2(); });
  return s;
}

template <int D>
std::vector<RegionStats> sample_regions(const Particles<D>& p, const std::vector<RegionSpec>& regions,
                                        const HugoniotTemperature* thermal, double cross_section) {
  const double y_top = target_top(p);
  std::vector<RegionStats> out;
  out.reserve(regions.size());
  for (const RegionSpec& r : regions) {
    out.push_back(region_stats(p, points_in_region(p, r, y_top), r.name, thermal));
    const Band b = band_of(r, y_top);
    macro_averages(p, b.lo, b.hi, b.target_only, cross_section, out.back());
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

#define MPMSHOCK_INSTANTIATE(D)                                                                              \
  template double target_top<D>(const Particles<D>&);                                                     \
  template std::vector<std::size_t> points_in_region<D>(const Particles<D>&, const RegionSpec&, double);  \
  template RegionStats region_stats<D>(const Particles<D>&, const std::vector<std::size_t>&, const std::string&, \
                                       const HugoniotTemperature*);                                       \
  template void macro_averages<D>(const Particles<D>&, double, double, bool, double, RegionStats&);          \
  template std::vector<RegionStats> sample_regions<D>(const Particles<D>&, const std::vector<RegionSpec>&, \
                                                      const HugoniotTemperature*, double);
MPMSHOCK_INSTANTIATE(2)
MPMSHOCK_INSTANTIATE(3)
#undef MPMSHOCK_INSTANTIATE

}  // namespace mpmshock
