// HDF5 snapshots: one file per output time (see docs/output-format.md for the layout).
//
//   /particles  every material point's fields for users (SI units, rows in id order)
//   /restart    the exact state mpmshock --restart needs that /particles does not hold
//   /grid       nodal mass and velocity (only with snapshot_grid = on)
#pragma once

#include <cstdint>
#include <string>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/grid.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

// Where the output schedule of a run stands.
struct OutputSchedule {
  std::int64_t next_sample = 1;    // index k of the next regions.csv sample at k * sample_interval
  std::int64_t next_snapshot = 1;  // index k of the next snapshot at k * snapshot_interval
  int snapshot_index = 0;          // number of the next snapshot file
  double last_dt = 0.0;            // the step that led here (conservation.csv's dt column)
};

// The run state beyond the points: everything a restart needs to continue bit for bit.
struct RunState {
  std::string scene_text;  // the resolved scene
  Clock clock;
  OutputSchedule schedule;
  Totals initial;          // totals at t = 0, for the conservation errors of the summary
  BodySummary target, flyer;
};

struct SnapshotOptions {
  int compression = 0;  // gzip level for every field; 0: only the fields that compress >100x
  const Grid* grid = nullptr;  // write /grid when given
  int grid_row_begin = 0, grid_row_end = 0;  // the grid's rows that hold this step's values
};

// Writes PATH.tmp and renames it over PATH when complete, so an interrupted write never leaves a
// half-written PATH. Throws std::runtime_error naming the path.
void write_snapshot(const std::string& path, const Particles& p, const HugoniotTemperature* thermal,
                    const RunState& run, const SnapshotOptions& options);

struct Restart {
  RunState run;
  Particles points;
};

// Reads a snapshot back into the state it was written from (the next sample and snapshot times
// are left to the caller, which derives them from the time as the time loop does). Throws std::runtime_error naming the
// path and what is wrong (not a snapshot, a missing dataset, a bad shape).
Restart read_snapshot(const std::string& path);

// The time and point count of a snapshot, for indexing a run's files.
struct SnapshotHeader {
  double time = 0.0;
  std::size_t points = 0;
  bool grid = false;
};
SnapshotHeader read_snapshot_header(const std::string& path);

}  // namespace mpmshock
