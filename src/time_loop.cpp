#include "mpmshock/time_loop.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <sstream>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/progress.hpp"
#include "mpmshock/provenance.hpp"
#include "mpmshock/run_log.hpp"
#include "mpmshock/signals.hpp"
#include "mpmshock/thread_tuner.hpp"

namespace mpmshock {
namespace {

using WallClock = std::chrono::steady_clock;

// Counts, errors and rates of a finished run.
template <int D>
void finish_result(RunResult& result, const Simulation<D>& sim, const Totals& start, const Totals& end,
                   std::int64_t start_steps) {
  result.steps = sim.steps();
  result.end_time = sim.time();
  result.point_steps_per_second =
      result.wall_seconds > 0
          ? static_cast<double>(sim.total_points()) * static_cast<double>(sim.steps() - start_steps) /
                result.wall_seconds
          : 0.0;
  result.mass_error = std::abs(end.mass - start.mass) / start.mass;
  Vec<D> momentum_change;
  for (int d = 0; d < D; ++d) momentum_change[d] = end.momentum[d] - start.momentum[d];
  result.momentum_error = speed(momentum_change) / start.momentum_magnitude;
  result.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
}

}  // namespace

template <int D>
RunResult advance(const Scene& scene, Simulation<D>& sim, RunState& run, Outputs<D>& out, const fs::path& dir,
                  const RunOptions& options) {
  RunResult result;
  result.output_dir = dir.string();
  result.start_time = sim.time();
  // The bodies' porosity; the target's where the flyer has its own (flyer_porosity).
  result.porosity = scene.flyer_porosity == scene.porosity ? porosity_of(run.target, run.flyer) : run.target.porosity();
  result.voids = run.target.voids.size() + run.flyer.voids.size();
  result.points = sim.total_points();
  result.symmetry = sim.model().symmetry_plane;
  result.dimension = D;
  const std::int64_t start_steps = sim.steps();
  OutputSchedule& sch = run.schedule;
  auto take_snapshot = [&](bool fast = false) {
    sim.settle();
    run.clock = sim.clock();
    out.snapshot(sim, run, fast);
    ++sch.snapshot_index;
  };
  const StopRequestsHeard heard;  // from here a SIGINT or SIGTERM asks for a stop with a snapshot

  const double end_time = landing_end_time(scene);
  const int all_threads = omp_get_max_threads();
  ThreadTuner threads(options.fixed_threads ? 1 : all_threads);
  const Comm& comm = sim.comm();
  const Comm::Traffic traffic_start = comm.traffic();
  Progress progress(!options.quiet && comm.root(), sim.time(), end_time);
  // A signal to one rank stops them all after the same step (the ranks agree on it every step).
  int stop = 0;
  auto stop_requested = [&] {
    stop = comm.parallel() ? sim.agreed_stop_signal() : stop_signal();
    return stop != 0;
  };
  const auto wall_start = WallClock::now();
  StepStatus status;
  bool failed_at_sample = false;  // the failing check ran after the sample was written
  double stable_sum = 0.0, dt_sum = 0.0;  // for step_share
  while (sim.time() < end_time * (1.0 - 1e-12)) {
    const double stable = sim.stable_time_step();
    const double dt = landing_step(stable, next_event_time(sch, scene, end_time) - sim.time());
    stable_sum += stable;
    dt_sum += dt;
    if (!options.fixed_threads) omp_set_num_threads(threads.threads());
    const auto step_start = WallClock::now();
    status = sim.step(dt);
    threads.record(std::chrono::duration<double>(WallClock::now() - step_start).count());
    sch.last_dt = dt;
    if (!status.ok()) break;
    out.probe(sim);
    if (stop_requested()) break;  // after a whole step, so the state is consistent
    const double tol = 1e-9 * dt;
    if (sim.time() >= event_time(sch.next_sample, scene.sample_interval) - tol) {
      out.sample(sim, dt);
      result.beyond_eos_fit = std::max(result.beyond_eos_fit, sim.points_beyond_eos_fit());
      sch.next_sample = next_event_after(sim.time(), scene.sample_interval, tol);
      status = sim.check_at_sample();
      failed_at_sample = !status.ok();
      if (failed_at_sample) break;
    }
    if (snapshot_due(sch, scene, sim.time(), tol)) take_snapshot();
    progress.update(sim.time(), sim.steps(), dt);
  }
  progress.finish();
  result.threads = all_threads;
  result.ranks = comm.size();
  if (comm.parallel()) {
    const Comm::Traffic t = comm.traffic();
    const double steps = std::max<double>(1.0, static_cast<double>(sim.steps() - start_steps));
    std::int64_t sent[2] = {static_cast<std::int64_t>(t.bytes - traffic_start.bytes),
                            static_cast<std::int64_t>(t.messages - traffic_start.messages)};
    comm.sum(sent, 2);
    result.mpi_bytes_per_step = static_cast<double>(sent[0]) / steps;
    result.mpi_messages_per_step = static_cast<double>(sent[1]) / steps;
    result.mpi_seconds = comm.max(t.seconds - traffic_start.seconds);
    result.mpi_seconds_least = comm.min(t.seconds - traffic_start.seconds);
    result.imbalance = sim.imbalance();
  }
  result.steps_with_fewer_threads = threads.steps_below_max();
  if (stable_sum > 0.0) result.step_share = dt_sum / stable_sum;
  result.wall_seconds = std::chrono::duration<double>(WallClock::now() - wall_start).count();

  if (!status.ok()) {
    result.exit_code = kExitNumerical;
    result.failure = sim.describe(status);
    if (!failed_at_sample) out.sample(sim, sch.last_dt);
    take_snapshot();  // the state that went wrong, for inspection
  } else if (stop != 0 && sim.time() < end_time * (1.0 - 1e-12)) {
    // Under mpirun the ranks may be killed soon after the signal (Open MPI: 1 s, the MCA parameter
    // odls_base_sigkill_timeout): say at once what is being written and what to restart from if it
    // is not finished, put that in summary.json, and write the snapshot uncompressed (the fastest).
    const int sig = stop;
    result.exit_code = 128 + sig;
    const std::string name = snapshot_name(sch.snapshot_index);
    const std::string signal = sig == SIGINT    ? "SIGINT"
                               : sig != SIGTERM ? "a signal"
                               : comm.parallel() ? "SIGTERM (mpirun passes a SIGINT on as SIGTERM)"
                                                 : "SIGTERM";
    std::ostringstream at;
    at << "t = " << sim.time() * 1e9 << " ns, step " << sim.steps();
    std::string fallback = "the run's set-up";
    for (int k = sch.snapshot_index - 1; k >= 0; --k)
      if (fs::exists(dir / snapshot_name(k))) {
        fallback = (dir / snapshot_name(k)).string() + " (with --force: the rows after it go)";
        break;
      }
    result.failure = "a stop was asked for by " + signal + " at " + at.str() + "; writing " + (dir / name).string() +
                     " to restart from; if that file is not there, the run was killed while writing it: restart from " +
                     fallback;
    if (comm.root()) {
      say(stderr, "mpmshock: " + result.failure + "\n");
      result.wall_seconds = std::chrono::duration<double>(WallClock::now() - wall_start).count();
      write_summary_json(dir / "summary.json", result);
    }
    out.sample(sim, sch.last_dt);
    take_snapshot(true);  // a state to restart from
    result.failure = "stopped by " + signal + " at " + at.str() + "; continue with: mpmshock --restart " +
                     (dir / name).string();
  } else {
    // The end time is an output time whatever the intervals.
    const double tol = 1e-9 * sch.last_dt;
    if (event_time(sch.next_sample - 1, scene.sample_interval) < sim.time() - tol) out.sample(sim, sch.last_dt);
    if (!snapshot_written_at(sch, scene, sim.time(), tol)) take_snapshot();
  }

  result.beyond_eos_fit = std::max(result.beyond_eos_fit, sim.points_beyond_eos_fit());
  result.beyond_eos_fit_J = sim.model().eos_fit_limit(Body::target);
  finish_result(result, sim, run.initial, out.totals(sim), start_steps);
  omp_set_num_threads(all_threads);
  if (comm.root()) write_summary_json(dir / "summary.json", result);
  return result;
}

template RunResult advance<2>(const Scene&, Simulation<2>&, RunState&, Outputs<2>&, const fs::path&,
                              const RunOptions&);
template RunResult advance<3>(const Scene&, Simulation<3>&, RunState&, Outputs<3>&, const fs::path&,
                              const RunOptions&);

}  // namespace mpmshock
