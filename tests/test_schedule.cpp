// The output schedule: steps land exactly on sample and snapshot times, the end time snaps onto an
// output time it equals up to round-off, and the rule that resumes a schedule after an event is
// the one a restart uses.
#include <algorithm>
#include <cmath>
#include <vector>

#include "check.hpp"
#include "mpmshock/schedule.hpp"

using namespace mpmshock;

int main() {
  // Events every interval; interval 0 means never.
  CHECK(event_time(3, 10e-9) == 3 * 10e-9);
  CHECK(std::isinf(event_time(1, 0.0)));

  // A step that would overshoot lands exactly; one that would leave a sliver is halved.
  CHECK(landing_step(1.0, 0.5) == 0.5);
  CHECK(landing_step(1.0, 1.0) == 1.0);
  CHECK(landing_step(1.0, 1.5) == 0.75);
  CHECK(landing_step(1.0, 2.0) == 1.0);
  CHECK(landing_step(1.0, 5.0) == 1.0);

  // The end time snaps onto an output time it equals up to round-off: 3e-8 is not 3 * 1e-8.
  Scene s;
  s.sample_interval = 1e-8;
  s.snapshot_interval = 5e-8;
  s.end_time = 3e-8;
  CHECK(3e-8 != 3 * 1e-8);
  CHECK(landing_end_time(s) == 3 * 1e-8);
  s.end_time = 3.5e-8;  // not an output time: kept
  CHECK(landing_end_time(s) == 3.5e-8);

  // next_event_after: the first event strictly after t (within tol), never index 0.
  CHECK(next_event_after(0.0, 1e-8, 1e-18) == 1);
  CHECK(next_event_after(3 * 1e-8, 1e-8, 1e-18) == 4);          // an event just written at t
  CHECK(next_event_after(3 * 1e-8 - 1e-20, 1e-8, 1e-18) == 4);  // within tol of it
  CHECK(next_event_after(2.5e-8, 1e-8, 1e-18) == 3);
  CHECK(next_event_after(1e-6, 0.0, 1e-18) == 1);               // never: stays at 1

  // The next event of a schedule is the earliest of sample, snapshot and end.
  OutputSchedule sch;
  sch.next_sample = 2;
  sch.next_snapshot = 1;
  CHECK(next_event_time(sch, s, 1.0) == 2e-8);
  CHECK(next_event_time(sch, s, 1.5e-8) == 1.5e-8);

  // A schedule resumed at t continues exactly as the loop that wrote events up to t would.
  double t = 0.0;
  OutputSchedule loop;
  const double dt_stable = 0.37e-8;
  int samples = 0;
  while (t < 2e-7 * (1 - 1e-12)) {
    const double dt = landing_step(dt_stable, next_event_time(loop, s, 2e-7) - t);
    t += dt;
    const double tol = 1e-9 * dt;
    if (t >= event_time(loop.next_sample, s.sample_interval) - tol) {
      ++samples;
      loop.next_sample = next_event_after(t, s.sample_interval, tol);
    }
    if (t >= event_time(loop.next_snapshot, s.snapshot_interval) - tol)
      loop.next_snapshot = next_event_after(t, s.snapshot_interval, tol);
    OutputSchedule resumed;
    resume_schedule(resumed, s, t, tol);
    CHECK(resumed.next_sample == loop.next_sample);
    CHECK(resumed.next_snapshot == loop.next_snapshot);
  }
  CHECK(samples == 20);  // every 10 ns to 200 ns, none missed, none twice

  // Listed snapshot times beside the interval: steps land on them, a time that is also a periodic
  // one gives one snapshot, and a resumed schedule continues as the loop does.
  Scene listed = s;
  listed.snapshot_interval = 5e-8;
  listed.snapshot_times = {2.5e-8, 5e-8, 1.2e-7};
  std::vector<double> written;
  OutputSchedule run;
  t = 0.0;
  while (t < 1.5e-7 * (1 - 1e-12)) {
    const double dt = landing_step(dt_stable, next_event_time(run, listed, 1.5e-7) - t);
    t += dt;
    const double tol = 1e-9 * dt;
    if (t >= event_time(run.next_sample, listed.sample_interval) - tol)
      run.next_sample = next_event_after(t, listed.sample_interval, tol);
    if (snapshot_due(run, listed, t, tol)) written.push_back(t);
    CHECK(snapshot_written_at(run, listed, t, tol) == (!written.empty() && written.back() == t));
    OutputSchedule resumed;
    resume_schedule(resumed, listed, t, tol);
    CHECK(resumed.next_snapshot == run.next_snapshot);
    CHECK(resumed.next_listed == run.next_listed);
  }
  // 25 ns (listed), 50 ns (both: once), 100 ns (periodic), 120 ns (listed), 150 ns (periodic).
  const std::vector<double> expected = {2.5e-8, 5e-8, 2 * 5e-8, 1.2e-7, 3 * 5e-8};
  CHECK(written.size() == expected.size());
  for (std::size_t i = 0; i < std::min(written.size(), expected.size()); ++i) CHECK_REL(written[i], expected[i], 1e-12);
  // Listed times only (interval 0): none due before the first, and the end is not a snapshot time.
  listed.snapshot_interval = 0.0;
  OutputSchedule only;
  CHECK(!snapshot_due(only, listed, 1e-8, 1e-18));
  CHECK(snapshot_due(only, listed, 2.5e-8, 1e-18) && only.next_listed == 1);
  CHECK(!snapshot_written_at(only, listed, 3e-8, 1e-18));
  return check::result();
}
