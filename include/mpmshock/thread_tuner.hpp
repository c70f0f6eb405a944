// The number of threads a run uses, chosen as it runs by measuring its own steps.
//
// OpenMP's runtime (libgomp) makes threads that wait at a barrier spin for ~3 ms before they
// sleep. On a machine where another program uses a core, the thread that still has work is then
// often the one without a core, and a step with 2 threads measured 2.2x slower than with 1
// (docs/method.md, "Threads on a busy machine"). main() shortens the spin where the user has not
// chosen one (src/openmp_wait.hpp), which takes away most of that; the tuner chooses how many threads.
//
// The tuner runs the steps at its current thread count and, every `period` steps, tries a few
// steps at another candidate count (half or double, within [1, max]). If those are faster by a
// clear margin it switches; if not, it waits twice as long before the next try (up to
// kMaxPeriod), so a machine whose load does not change pays almost nothing for the probing. A try
// whose first steps are all clearly slower ends early.
//
// Faster means more steps per second: the counts are compared by their mean step time, not the
// median. On a busy machine the steps of 2 threads are fast most of the time and 3-4 times slower
// whenever the other program holds the core a thread waits for (speed scene beside a busy loop,
// 2026-12-04: median 0.032 s, 90th percentile 0.108 s, mean 0.046 s, against a steady 0.034 s on 1
// thread), so the median chose 2 threads where 1 ran 1.3 times faster. The largest sample of each
// set is left out, so that one isolated slow step (a page fault) does not decide; the first step
// of a try and the first after it are left out too, as they pay for the change of team (a thread
// moving to another core).
// Results do not depend on the thread count (every sum runs in a fixed order), so switching is
// free of side effects. Pure logic: step times come in from the caller, so tests drive it with
// made-up times.
#pragma once

#include <cstdint>
#include <vector>

namespace mpmshock {

class ThreadTuner {
 public:
  static constexpr int kSamples = 5;          // the fewest steps a measurement takes
  static constexpr int kWindow = 16;          // steps per measurement once there are as many
  static constexpr int kClearLoss = 2;        // a try ends early once this many steps were all slower
  static constexpr int kFirstPeriod = 8;      // steps before the first try
  static constexpr int kPeriodAfterSwitch = 40;  // steps before the next try after a switch
  static constexpr int kMaxPeriod = 1280;     // the longest wait between tries
  static constexpr double kMargin = 0.05;     // a try must be this much faster to win

  // max_threads: the most threads to use (--threads, or all cores); 1 turns the tuner off.
  explicit ThreadTuner(int max_threads);

  // The thread count for the next step.
  int threads() const { return trying_ ? candidate_ : current_; }
  // The wall time the step took at threads().
  void record(double seconds);

  int max_threads() const { return max_; }
  // Steps taken with fewer than max_threads() threads, for the summary.
  std::int64_t steps_below_max() const { return below_max_; }
  std::int64_t steps() const { return steps_; }

 private:
  int next_candidate();
  // The mean of the samples less the largest one (the mean if there is only one).
  static double mean_without_largest(const std::vector<double>& v);

  int max_;
  int current_;
  int candidate_ = 1;
  bool trying_ = false;
  bool go_down_ = false;  // direction of the last try
  int period_ = kFirstPeriod;
  int since_try_ = 0;
  std::vector<double> recent_;  // the last kWindow step times at current_
  std::vector<double> trial_;   // step times at candidate_ during a try, after its first
  // The next step changes the team (a try's first step, or the first after it): not measured.
  bool changes_team_ = false;
  std::int64_t below_max_ = 0, steps_ = 0;
};

}  // namespace mpmshock
