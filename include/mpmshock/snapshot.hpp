// HDF5 snapshots: one file per output time (see docs/output-format.md for the layout).
//
//   /particles  every material point's fields for users (SI units, rows in id order)
//   /restart    the exact state mpmshock --restart needs that /particles does not hold
//   /grid       nodal mass and velocity (only with snapshot_grid = on)
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "mpmshock/comm.hpp"
#include "mpmshock/diagnostics.hpp"
#include "mpmshock/grid.hpp"
#include "mpmshock/mirror_image.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/schedule.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/thermal_softening.hpp"

namespace mpmshock {

// The run state beyond the points: everything a restart needs to continue bit for bit.
struct RunState {
  std::string scene_text;  // the resolved scene
  Clock clock;
  OutputSchedule schedule;
  Totals initial;          // totals at t = 0, for the conservation errors of the summary
  BodySummary target, flyer;
};

template <int D>
struct SnapshotOptions {
  int compression = 0;  // gzip level for every field; 0: only the fields that compress >100x
  const Grid<D>* grid = nullptr;  // write /grid when given
  RowRange grid_rows;             // the grid's rows that hold this step's values
  std::array<MeltCurve, kBodies> melt{};  // each body's, for /particles/melted (T_m0 = 0: none)
  // Johnson-Cook strength: each body's constant melt temperature (jc_melt_temperature), which
  // /particles/melted then uses; 0: the melt curve.
  std::array<double, kBodies> melt_temperature{};
  const MirrorImage<D>* mirror = nullptr;  // symmetry = on: write the whole impact (mirror_image.hpp)
  const Comm* comm = nullptr;              // the ranks whose points these are (default: the world)
};

// Writes PATH.tmp and renames it over PATH when complete, so an interrupted write never leaves a
// half-written PATH. With options.mirror on, the points are the target's and the file holds the
// whole impact. On MPI ranks every rank calls it with its own points, and rank 0 writes the file
// in chunks of rows gathered from all (no rank holds every point). Throws std::runtime_error naming
// the path (AgreedIoError, on every rank, with several ranks).
template <int D>
void write_snapshot(const std::string& path, const Particles<D>& p, const BodyTemperatures* thermal,
                    const RunState& run, const SnapshotOptions<D>& options);

template <int D>
struct Restart {
  RunState run;
  std::size_t total_points = 0;  // the snapshot's: the whole impact's
  std::size_t first_point = 0;   // `points` are those of ids [first_point, first_point + points.size())
  Particles<D> points;
};

// Which of a snapshot's n points (in id order) to read, [first, end), given its run state: an
// MPI rank's share. Null: all of them.
using PointChooser = std::function<std::pair<std::size_t, std::size_t>(const RunState&, std::size_t n)>;

// Reads a snapshot back into the state it was written from (the next sample and snapshot times
// are left to the caller, which derives them from the time as the time loop does), with the points
// `choose` picks. Throws SceneError naming the path and what is wrong (not a snapshot, a missing
// dataset, a bad shape).
template <int D>
Restart<D> read_snapshot(const std::string& path, const PointChooser& choose = nullptr);

// The time and point count of a snapshot, for indexing a run's files.
struct SnapshotHeader {
  double time = 0.0;
  std::size_t points = 0;
  bool grid = false;
  int dimension = 2;
};
SnapshotHeader read_snapshot_header(const std::string& path);

}  // namespace mpmshock
