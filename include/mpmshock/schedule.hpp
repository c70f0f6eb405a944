// When a run writes what: samples (regions.csv, conservation.csv) every sample_interval,
// snapshots every snapshot_interval and at each of snapshot_times, both at the end; and time steps
// that land exactly on those times. Pure arithmetic on times, shared by the time loop and restart
// so that both continue identically (test_schedule checks it directly).
#pragma once

#include <cstddef>
#include <cstdint>

#include "mpmshock/scene.hpp"

namespace mpmshock {

// Where the output schedule of a run stands.
struct OutputSchedule {
  std::int64_t next_sample = 1;    // index k of the next regions.csv sample at k * sample_interval
  std::int64_t next_snapshot = 1;  // index k of the next snapshot at k * snapshot_interval
  std::size_t next_listed = 0;     // index of the next of snapshot_times
  int snapshot_index = 0;          // number of the next snapshot file
  double last_dt = 0.0;            // the step that led here (conservation.csv's dt column)
};

// Time of the k-th event of a periodic output; interval 0 means never (before the end).
double event_time(std::int64_t k, double interval);

// The end time, moved onto a sample or snapshot time that it equals up to round-off (3e-8 and
// 3 * 1e-8 differ in the last bit): a run that ends at T/2 then lands exactly where a longer run
// passes T/2, so the two step identically and a restart from there reproduces the longer run.
double landing_end_time(const Scene& s);

// The first k with event_time(k) after t (k >= 1): the same rule whether the loop just wrote an
// event at t or a restart resumes at t, so both continue identically.
std::int64_t next_event_after(double t, double interval, double tol);

// The next time step from the stable one, landing exactly on the next event `remaining` away: a
// step that would leave a sliver of less than a step is split into two equal ones.
double landing_step(double stable_dt, double remaining);

// Whether a snapshot is due at time t (a periodic or a listed one, or both: one snapshot); if so,
// moves the schedule past t.
bool snapshot_due(OutputSchedule& schedule, const Scene& scene, double t, double tol);

// Whether the schedule's last snapshot (periodic or listed) was at time t: the end of a run then
// needs no snapshot of its own.
bool snapshot_written_at(const OutputSchedule& schedule, const Scene& scene, double t, double tol);

// The next event (sample, snapshot or the end) of a schedule.
double next_event_time(const OutputSchedule& schedule, const Scene& scene, double end_time);

// The schedule's indices resumed at time t (a restart, or after writing an event at t).
void resume_schedule(OutputSchedule& schedule, const Scene& scene, double t, double tol);

}  // namespace mpmshock
