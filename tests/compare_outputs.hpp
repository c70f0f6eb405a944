// Comparisons of two runs' outputs for the tests that check a shortcut (symmetry, unreached
// material) against the full computation.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/snapshot.hpp"

namespace compare {

namespace fs = std::filesystem;

inline std::vector<std::vector<std::string>> csv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::istringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

// Every number of two CSV files alike to `rel` of its column's largest magnitude (or of `floor`, for
// columns that are round-off about zero); text fields equal.
inline void same_csv(const fs::path& a, const fs::path& b, double rel, double floor = 0.0) {
  const auto x = csv(a), y = csv(b);
  CHECK(x.size() == y.size() && !x.empty());
  if (x.size() != y.size() || x.empty()) return;
  CHECK(x[0] == y[0]);
  const std::size_t columns = x[0].size();
  std::vector<double> scale(columns, 0.0);
  for (std::size_t r = 1; r < y.size(); ++r)
    for (std::size_t c = 0; c < columns && c < y[r].size(); ++c) {
      char* end = nullptr;
      const double v = std::strtod(y[r][c].c_str(), &end);
      if (*end == '\0' && std::isfinite(v)) scale[c] = std::max(scale[c], std::abs(v));
    }
  double worst = 0.0;
  std::string where;
  for (std::size_t r = 1; r < x.size(); ++r) {
    CHECK(x[r].size() == columns && y[r].size() == columns);
    for (std::size_t c = 0; c < columns && c < x[r].size() && c < y[r].size(); ++c) {
      char *ea = nullptr, *eb = nullptr;
      const double u = std::strtod(x[r][c].c_str(), &ea), v = std::strtod(y[r][c].c_str(), &eb);
      if (*ea != '\0' || *eb != '\0') {
        CHECK(x[r][c] == y[r][c]);
        continue;
      }
      if (std::isnan(u) || std::isnan(v)) {
        CHECK(std::isnan(u) && std::isnan(v));
        continue;
      }
      const double d = std::abs(u - v) / std::max({scale[c], floor, 1e-300});
      if (d > worst) worst = d, where = x[0][c] + " in row " + std::to_string(r) + " (" + x[r][1] + ")";
    }
  }
  std::printf("%s: largest difference %.2e of the column's scale (%s)\n", a.filename().c_str(), worst, where.c_str());
  CHECK(worst <= rel);
}

// The states of points a[k] and b[offset + k] for every k of a alike to round-off: positions to
// 1e-12 m, velocities to 1e-8 m/s, pressures to 1e-11 of the peak.
template <int D>
void same_point_states(const mpmshock::Particles<D>& a, const mpmshock::Particles<D>& b, std::size_t offset,
                       const std::string& what) {
  double dx = 0.0, dv = 0.0, dP = 0.0, P_max = 0.0;
  for (std::size_t k = 0; k < a.size() && offset + k < b.size(); ++k) {
    const std::size_t q = offset + k;
    for (int d = 0; d < D; ++d) {
      dx = std::max(dx, std::abs(a.x[k][d] - b.x[q][d]));
      dv = std::max(dv, std::abs(a.v[k][d] - b.v[q][d]));
    }
    dP = std::max(dP, std::abs(a.P[k] - b.P[q]));
    P_max = std::max(P_max, std::abs(b.P[q]));
  }
  std::printf("%s: largest difference x %.2e m, v %.2e m/s, P %.2e of the peak pressure\n", what.c_str(), dx, dv,
              dP / P_max);
  CHECK(dx < 1e-12);
  CHECK(dv < 1e-8);
  CHECK(dP < 1e-11 * P_max);
}

// Two snapshots hold the same points (ids, bodies) at positions alike to `tol` [m].
template <int D>
void same_snapshot_in(const fs::path& a_path, const fs::path& b_path, double tol) {
  const mpmshock::Restart<D> a = mpmshock::read_snapshot<D>(a_path.string());
  const mpmshock::Restart<D> b = mpmshock::read_snapshot<D>(b_path.string());
  CHECK(a.points.size() == b.points.size());
  double dx = 0.0;
  bool same_ids = true;
  for (std::size_t p = 0; p < a.points.size() && p < b.points.size(); ++p) {
    same_ids = same_ids && a.points.id[p] == b.points.id[p] && a.points.body[p] == b.points.body[p];
    for (int d = 0; d < D; ++d) dx = std::max(dx, std::abs(a.points.x[p][d] - b.points.x[p][d]));
  }
  CHECK(same_ids);
  std::printf("%s: largest position difference %.2e m\n", a_path.filename().c_str(), dx);
  CHECK(dx < tol);
}
inline void same_snapshot(const fs::path& a_path, const fs::path& b_path, double tol) {
  const int d = mpmshock::read_snapshot_header(a_path.string()).dimension;
  CHECK(mpmshock::read_snapshot_header(b_path.string()).dimension == d);
  if (d == 3) same_snapshot_in<3>(a_path, b_path, tol);
  else same_snapshot_in<2>(a_path, b_path, tol);
}

// Two run directories of a small porous impact, one with a shortcut and one without, alike to
// round-off: regions.csv, probes.csv and conservation.csv to 1e-9 of each column's scale (round-off
// grows in a porous run, void collapse amplifies it, but stays far below any physics), and the
// positions in snapshot_00002.h5 to 1e-10 m.
inline void same_run_outputs(const fs::path& a, const fs::path& b) {
  same_csv(a / "regions.csv", b / "regions.csv", 1e-9);
  same_csv(a / "probes.csv", b / "probes.csv", 1e-9);
  // The momenta are round-off about 0 (1e-17 kg/s per metre of depth): against a floor of 1e-6, a
  // few 1e-9 of the bodies' momentum sum m |v| (270 kg/s per metre).
  same_csv(a / "conservation.csv", b / "conservation.csv", 1e-9, 1e-6);
  same_snapshot(a / "snapshot_00002.h5", b / "snapshot_00002.h5", 1e-10);
}

// Steps a simulation to end_time at its stable time step; false (and a failed check) if a step fails.
template <class Simulation>
bool march(Simulation& sim, double end_time, const std::string& what) {
  while (sim.time() < end_time * (1 - 1e-12)) {
    const auto status = sim.step(std::min(sim.stable_time_step(), end_time - sim.time()));
    if (!status.ok()) {
      check::fail(__FILE__, __LINE__, what + ": " + sim.describe(status));
      return false;
    }
  }
  return true;
}

}  // namespace compare
