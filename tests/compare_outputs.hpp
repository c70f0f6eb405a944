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
