// Region averages as the paper defines them (physics-notes section 5): over the material points
// inside a horizontal band, the mean and standard deviation of density, pressure, temperature and
// velocity, and the means of Rot^2, Div^2 and the squared strain-rate norm. These are means of the
// points' own states: density_mean is each point's m / (V0 J), blind to the voids between points.
//
// The macroscopic averages are per area of the band instead (what a porous Hugoniot predicts):
// macro_density = band mass / band area, macro_pressure = sum V P / band area, macro_normal_stress
// = sum V (P + q - s_yy) / band area (the compressive stress across the band, which the jump
// conditions give). Each point counts with the share of its y extent (its spacing stretched by
// F_yy) inside the band, so a row of points crossing an edge does not make them jump. A band that
// reaches past the material (a free surface, an open gap) counts the empty part as area.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "mpmshock/comm.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

struct MeanStd {
  double mean = 0.0, std = 0.0;  // population standard deviation (divides by count)
};

struct RegionStats {
  std::string name;
  std::size_t count = 0;
  MeanStd density, pressure, temperature, velocity_x, velocity_y;
  std::optional<MeanStd> paper_temperature;  // the paper model's, when the thermal model reports it
  double rot2 = 0.0;          // |curl v|^2; in 2D (dv_y/dx - dv_x/dy)^2
  double div2 = 0.0;          // (div v)^2
  double strain_rate2 = 0.0;  // D : D with D = sym(grad v)
  double macro_density = 0.0, macro_pressure = 0.0, macro_normal_stress = 0.0;
};

// The statistics of every region over the points of all ranks of `comm` (each rank passes its own);
// temperature is NaN when `thermal` is null, and an empty region has NaN means. Every sum is exact
// (exact_sum.hpp): the same bits on any number of threads and ranks.
template <int D>
std::vector<RegionStats> sample_regions(const Particles<D>& p, const std::vector<RegionSpec>& regions,
                                        const BodyTemperatures* thermal, double cross_section,
                                        const Comm& comm = Comm::world());

// Squared rotation |curl v|^2 of a velocity gradient (the paper's Rot^2).
inline double rotation2(const Mat<2>& L) {
  const double rot = L(1, 0) - L(0, 1);
  return rot * rot;
}
inline double rotation2(const Mat<3>& L) {
  const double a = L(2, 1) - L(1, 2), b = L(0, 2) - L(2, 0), c = L(1, 0) - L(0, 1);
  return a * a + b * b + c * c;
}

// regions.csv: the header, and one row per region and sample time; paper_temperature = on adds the
// columns paper_temperature_mean and paper_temperature_std at the end.
extern const char* const kRegionsHeader;
std::string regions_header(bool paper_temperature);
void write_region_rows(std::FILE* out, double time, const std::vector<RegionStats>& stats);

}  // namespace mpmshock
