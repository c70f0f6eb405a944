// HDF5 snapshots of every material point.
#pragma once

#include <cstdint>
#include <string>

#include "mpmshock/model.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

struct SnapshotMeta {
  double time = 0.0;
  std::int64_t step = 0;
  int index = 0;             // the snapshot's number in its run
  std::string scene;         // the resolved scene text, so a snapshot says how it was made
};

// Writes /particles/<field> datasets (SI units, plane strain per metre of depth) with the time,
// step, units and scene as attributes. Writes to PATH.tmp and renames it over PATH when complete,
// so an interrupted write never leaves a half-written PATH. Throws std::runtime_error naming the path.
void write_snapshot(const std::string& path, const Particles& p, const Model& model,
                    const HugoniotTemperature* thermal, const SnapshotMeta& meta);

}  // namespace mpmshock
