#include "mpmshock/probes.hpp"

#include <cmath>
#include <limits>

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
                           const MirrorImage<D>& mirror) const {
  for (const Probe& probe : probes_) {
    double x = 0.0, y = 0.0, vx = 0.0, vy = 0.0, P = 0.0, rho = 0.0, T = 0.0, T_paper = 0.0;
    const bool paper = thermal && thermal->reports_paper_temperature();
    for (std::uint32_t id : probe.ids) {  // storage order is id order: points are never reordered
      const auto [q, mirrored] = mirror.source_of(id);
      const double y_sign = mirrored ? -1.0 : 1.0;
      x += p.x[q][0];
      y += y_sign * p.x[q][1];
      vx += p.v[q][0];
      vy += y_sign * p.v[q][1];
      P += p.P[q];
      rho += p.density(q);
      T += thermal ? thermal->of_point(p, q) : std::nan("");
      if (paper) T_paper += thermal->paper_of_point(p, q);
    }
    const double n = static_cast<double>(probe.ids.size());
    std::fprintf(out, "%.10g,%s,%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", time, probe.name.c_str(),
                 probe.ids.size(), x / n, y / n, vx / n, vy / n, P / n, rho / n, T / n);
    if (paper) std::fprintf(out, ",%.10g", T_paper / n);
    std::fputc('\n', out);
  }
}

template class Probes<2>;
template class Probes<3>;

}  // namespace mpmshock
