// The time loop, shared by new and restarted runs: choose the time step, step, stop on trouble or
// a signal, write what is due; at the end the closing sample and snapshot and the summary.
#pragma once

#include "mpmshock/outputs.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/snapshot.hpp"

namespace mpmshock {

template <int D>
RunResult advance(const Scene& scene, Simulation<D>& sim, RunState& run, Outputs<D>& out, const fs::path& dir,
                  const RunOptions& options);

// summary.json: the result of a run, written to a temporary name and renamed.
void write_summary_json(const fs::path& path, const RunResult& r);

}  // namespace mpmshock
