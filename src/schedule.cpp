#include "mpmshock/schedule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpmshock {

double event_time(std::int64_t k, double interval) {
  return interval > 0.0 ? static_cast<double>(k) * interval : std::numeric_limits<double>::infinity();
}

double landing_end_time(const Scene& s) {
  for (double interval : {s.sample_interval, s.snapshot_interval}) {
    if (!(interval > 0.0)) continue;
    const double k = std::round(s.end_time / interval);
    if (k >= 1 && std::abs(k * interval - s.end_time) <= 1e-9 * s.end_time) return k * interval;
  }
  return s.end_time;
}

std::int64_t next_event_after(double t, double interval, double tol) {
  if (!(interval > 0.0)) return 1;
  auto k = static_cast<std::int64_t>(std::floor(t / interval));
  while (event_time(k, interval) <= t + tol) ++k;
  while (k > 1 && event_time(k - 1, interval) > t + tol) --k;
  return std::max<std::int64_t>(k, 1);
}

double landing_step(double stable_dt, double remaining) {
  if (stable_dt >= remaining) return remaining;
  if (2.0 * stable_dt > remaining) return 0.5 * remaining;
  return stable_dt;
}

namespace {

double listed_time(std::size_t index, const Scene& scene) {
  return index < scene.snapshot_times.size() ? scene.snapshot_times[index] : std::numeric_limits<double>::infinity();
}

// The first of the (increasing) listed times after t, within tol.
std::size_t next_listed_after(double t, const Scene& scene, double tol) {
  std::size_t i = 0;
  while (listed_time(i, scene) <= t + tol) ++i;
  return i;
}

}  // namespace

double next_event_time(const OutputSchedule& sch, const Scene& scene, double end_time) {
  return std::min({end_time, event_time(sch.next_sample, scene.sample_interval),
                   event_time(sch.next_snapshot, scene.snapshot_interval), listed_time(sch.next_listed, scene)});
}

bool snapshot_due(OutputSchedule& sch, const Scene& scene, double t, double tol) {
  const bool periodic = t >= event_time(sch.next_snapshot, scene.snapshot_interval) - tol;
  const bool listed = t >= listed_time(sch.next_listed, scene) - tol;
  if (periodic) sch.next_snapshot = next_event_after(t, scene.snapshot_interval, tol);
  if (listed) sch.next_listed = next_listed_after(t, scene, tol);
  return periodic || listed;
}

bool snapshot_written_at(const OutputSchedule& sch, const Scene& scene, double t, double tol) {
  const bool periodic = scene.snapshot_interval > 0.0 && event_time(sch.next_snapshot - 1, scene.snapshot_interval) >= t - tol;
  const bool listed = sch.next_listed > 0 && listed_time(sch.next_listed - 1, scene) >= t - tol;
  return periodic || listed;
}

void resume_schedule(OutputSchedule& sch, const Scene& scene, double t, double tol) {
  sch.next_sample = next_event_after(t, scene.sample_interval, tol);
  sch.next_snapshot = next_event_after(t, scene.snapshot_interval, tol);
  sch.next_listed = next_listed_after(t, scene, tol);
}

}  // namespace mpmshock
