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

double next_event_time(const OutputSchedule& sch, const Scene& scene, double end_time) {
  return std::min({end_time, event_time(sch.next_sample, scene.sample_interval),
                   event_time(sch.next_snapshot, scene.snapshot_interval)});
}

void resume_schedule(OutputSchedule& sch, const Scene& scene, double t, double tol) {
  sch.next_sample = next_event_after(t, scene.sample_interval, tol);
  sch.next_snapshot = next_event_after(t, scene.snapshot_interval, tol);
}

}  // namespace mpmshock
