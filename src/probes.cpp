#include "mpmshock/probes.hpp"

#include <cmath>
#include <limits>

#include "mpmshock/decomposition.hpp"
#include "mpmshock/exact_sum.hpp"

namespace mpmshock {

const char* const kProbesHeader = "time,probe,count,x,y,velocity_x,velocity_y,pressure,density,temperature";

std::string probes_header(bool paper_temperature) {
  return std::string(kProbesHeader) + (paper_temperature ? ",paper_temperature" : "");
}

template <int D>
Probes<D>::Probes(const Scene& scene, const Particles<D>& p, const GridGeometry<D>& grid)
    : interval_(scene.probe_interval) {
  auto periodic = [](double a, double b, double period) {
    const double d = std::abs(a - b);
    return std::min(d, period - d);
  };
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::target) top = std::max(top, p.x[q][1]);
  for (const ProbeSpec& spec : scene.probes) {
    Probe probe{spec.name, {}};
    if (spec.kind == ProbeSpec::Kind::surface) {
      // The top cell: particles_per_cell rows of points (the top row alone rings after the shock
      // reflects; a cell's worth of rows is what the grid resolves).
      const double depth = scene.cell_size * (1.0 - 1e-9);
      for (std::size_t q = 0; q < p.size(); ++q)
        if (p.body[q] == Body::target && p.x[q][1] > top - depth) probe.ids.push_back(p.id[q]);
    } else {
      double best = std::numeric_limits<double>::infinity();
      std::uint32_t nearest = 0;
      const double z = spec.z >= 0.0 ? spec.z : 0.5 * grid.depth();  // 3D only
      for (std::size_t q = 0; q < p.size(); ++q) {
        const double dx = periodic(p.x[q][0], spec.x, grid.width());
        double d2 = dx * dx + (p.x[q][1] - spec.y) * (p.x[q][1] - spec.y);
        if constexpr (D == 3) {
          const double dz = periodic(p.x[q][2], z, grid.depth());
          d2 += dz * dz;
        }
        if (d2 < best) {
          best = d2;
          nearest = p.id[q];
        }
      }
      probe.ids.push_back(nearest);
    }
    probes_.push_back(std::move(probe));
  }
}

template <int D>
double Probes<D>::next_after(double t) const {
  if (interval_ <= 0.0) return t;
  return (std::floor(t / interval_ * (1.0 + 1e-12)) + 1.0) * interval_;
}

template <int D>
void Probes<D>::write_rows(std::FILE* out, double time, const Particles<D>& p, const HugoniotTemperature* thermal,
                           const MirrorImage<D>& mirror, const Comm& comm) const {
  enum { kX, kY, kVx, kVy, kP, kRho, kT, kPaperT, kSums };
  const bool paper = thermal && thermal->reports_paper_temperature();
  std::vector<ExactSum> sums(probes_.size() * kSums);
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    ExactSum* s = &sums[k * kSums];
    for (std::uint32_t id : probes_[k].ids) {
      const auto [simulated, mirrored] = mirror.source_of(id);
      // One rank holds every point at its id's index; a rank of several looks its own ones up.
      const std::size_t q = comm.parallel() ? index_of_id(p, simulated) : simulated;
      if (q >= p.size()) continue;
      const double y_sign = mirrored ? -1.0 : 1.0;
      s[kX].add(p.x[q][0]);
      s[kY].add(y_sign * p.x[q][1]);
      s[kVx].add(p.v[q][0]);
      s[kVy].add(y_sign * p.v[q][1]);
      s[kP].add(p.P[q]);
      s[kRho].add(p.density(q));
      s[kT].add(thermal ? thermal->of_point(p, q) : std::nan(""));
      if (paper) s[kPaperT].add(thermal->paper_of_point(p, q));
    }
  }
  comm.sum(sums.data(), static_cast<int>(sums.size()));
  if (out == nullptr) return;
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const Probe& probe = probes_[k];
    const double n = static_cast<double>(probe.ids.size());
    auto mean = [&](int i) { return sums[k * kSums + i].value() / n; };
    std::fprintf(out, "%.10g,%s,%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", time, probe.name.c_str(),
                 probe.ids.size(), mean(kX), mean(kY), mean(kVx), mean(kVy), mean(kP), mean(kRho), mean(kT));
    if (paper) std::fprintf(out, ",%.10g", mean(kPaperT));
    std::fputc('\n', out);
  }
}

template class Probes<2>;
template class Probes<3>;

}  // namespace mpmshock
