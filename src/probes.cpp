#include "mpmshock/probes.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "mpmshock/decomposition.hpp"
#include "mpmshock/exact_sum.hpp"

namespace mpmshock {

std::string probes_header(bool paper_temperature, int dimension) {
  return std::string(dimension == 3 ? "time,probe,count,x,y,z,velocity_x,velocity_y,velocity_z"
                                    : "time,probe,count,x,y,velocity_x,velocity_y") +
         ",pressure,density,temperature" + (paper_temperature ? ",paper_temperature" : "");
}

std::string probes_size_warning(const Scene& s, double first_step) {
  if (s.probes.empty() || !(first_step > 0.0)) return "";
  const bool every_step = s.probe_interval <= 0.0;
  const double rows = std::floor(s.end_time / (every_step ? first_step : s.probe_interval)) + 1.0;
  // Each number is written with 10 significant digits (about 17 characters with its comma).
  const std::string header = probes_header(s.paper_temperature, s.dimension);
  const double numbers = static_cast<double>(std::count(header.begin(), header.end(), ',')), per_row = 17.0 * numbers;
  double bytes = 0.0;
  for (const ProbeSpec& probe : s.probes) bytes += rows * (per_row + static_cast<double>(probe.name.size()));
  if (bytes < kProbesWarnBytes) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "probes: %zu probes %s write %s%.0f MB to probes.csv (%.3g rows each); a larger probe_interval "
                "writes less",
                s.probes.size(), every_step ? "every step" : "at probe_interval", every_step ? "at least " : "about ",
                bytes / 1e6, rows);
  return text;
}

namespace {

std::string format_length(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g um", metres * 1e6);
  return text;
}

// Every rank's ids, in increasing order, at every rank.
std::vector<std::uint32_t> ids_of_all_ranks(const std::vector<std::uint32_t>& mine, const Comm& comm) {
  if (!comm.parallel()) return mine;
  const auto* first = reinterpret_cast<const char*>(mine.data());
  std::vector<char> all;
  for (const std::vector<char>& part : comm.gather(std::vector<char>(first, first + mine.size() * sizeof(std::uint32_t))))
    all.insert(all.end(), part.begin(), part.end());
  comm.broadcast(all);
  std::vector<std::uint32_t> ids(all.size() / sizeof(std::uint32_t));
  if (!all.empty()) std::memcpy(ids.data(), all.data(), all.size());
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace

template <int D>
Probes<D>::Probes(const Scene& scene, const Particles<D>& p, const GridGeometry<D>& grid, const MirrorImage<D>& mirror,
                  const Comm& comm)
    : interval_(scene.probe_interval) {
  auto periodic = [](double a, double b, double period) {
    const double d = std::abs(a - b);
    return std::min(d, period - d);
  };
  // Every point of the whole impact this rank holds or mirrors: its id in the whole, position, body.
  auto for_each_point = [&](auto&& visit) {
    const std::size_t first_target = mirror.flyer_points();
    for (std::size_t q = 0; q < p.size(); ++q) {
      visit(static_cast<std::uint32_t>(first_target + p.id[q]), p.x[q], p.body[q]);
      if (!mirror.on()) continue;
      Vec<D> image = p.x[q];
      image[1] = -image[1];
      visit(mirror.image_of(p.id[q]), image, Body::flyer);
    }
  };
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.body[q] == Body::target) top = std::max(top, p.x[q][1]);
  top = comm.max(top);
  for (const ProbeSpec& spec : scene.probes) {
    Probe probe{spec.name, {}};
    if (spec.kind == ProbeSpec::Kind::surface) {
      // The top cell: particles_per_cell rows of points (the top row alone rings after the shock
      // reflects; a cell's worth of rows is what the grid resolves).
      const double depth = scene.cell_size * (1.0 - 1e-9);
      std::vector<std::uint32_t> mine;
      for_each_point([&](std::uint32_t id, const Vec<D>& x, Body body) {
        if (body == Body::target && x[1] > top - depth) mine.push_back(id);
      });
      std::sort(mine.begin(), mine.end());
      probe.ids = ids_of_all_ranks(mine, comm);
    } else {
      // The nearest point, the lowest id of those as near.
      double best = std::numeric_limits<double>::infinity();
      std::uint32_t nearest = std::numeric_limits<std::uint32_t>::max();
      const double z = spec.z >= 0.0 ? spec.z : 0.5 * grid.depth();  // 3D only
      for_each_point([&](std::uint32_t id, const Vec<D>& x, Body) {
        const double dx = periodic(x[0], spec.x, grid.width());
        double d2 = dx * dx + (x[1] - spec.y) * (x[1] - spec.y);
        if constexpr (D == 3) {
          const double dz = periodic(x[2], z, grid.depth());
          d2 += dz * dz;
        }
        if (d2 < best || (d2 == best && id < nearest)) {
          best = d2;
          nearest = id;
        }
      });
      const double least = comm.min(best);
      const double id = comm.min(best == least ? static_cast<double>(nearest) : std::numeric_limits<double>::infinity());
      // A probe follows the material at the point asked for; with none within a cell of it (a
      // void there) it would follow some other material under the name.
      if (!(std::sqrt(least) <= scene.cell_size)) {
        char where[160];
        if constexpr (D == 3) std::snprintf(where, sizeof where, "(%g, %g, %g) m", spec.x, spec.y, z);
        else std::snprintf(where, sizeof where, "(%g, %g) m", spec.x, spec.y);
        throw SceneError(scene.where("probe." + spec.name) + ": key 'probe." + spec.name + "': no material point lies "
                         "within a cell of " + where + " at t = 0 (the nearest is " + format_length(std::sqrt(least)) +
                         " away: a void?); choose a point in the material");
      }
      probe.ids.push_back(static_cast<std::uint32_t>(id));
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
void Probes<D>::write_rows(std::FILE* out, double time, const Particles<D>& p, const BodyTemperatures* thermal,
                           const MirrorImage<D>& mirror, const Comm& comm) const {
  enum { kX, kY, kZ, kVx, kVy, kVz, kP, kRho, kT, kPaperT, kSums };
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
      if constexpr (D == 3) {
        s[kZ].add(p.x[q][2]);
        s[kVz].add(p.v[q][2]);
      }
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
    std::fprintf(out, "%.10g,%s,%zu,%.10g,%.10g,", time, probe.name.c_str(), probe.ids.size(), mean(kX), mean(kY));
    if (D == 3) std::fprintf(out, "%.10g,", mean(kZ));
    std::fprintf(out, "%.10g,%.10g,", mean(kVx), mean(kVy));
    if (D == 3) std::fprintf(out, "%.10g,", mean(kVz));
    std::fprintf(out, "%.10g,%.10g,%.10g", mean(kP), mean(kRho), mean(kT));
    if (paper) std::fprintf(out, ",%.10g", mean(kPaperT));
    std::fputc('\n', out);
  }
}

template class Probes<2>;
template class Probes<3>;

}  // namespace mpmshock
