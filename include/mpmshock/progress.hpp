// The progress line on stderr: percent, simulated time, step, time step and the estimated time
// left; redrawn every second on a terminal, a line every 10 s otherwise.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace mpmshock {

// "42s", "3m07s", "2h05m".
std::string human_time(double seconds);

class Progress {
 public:
  Progress(bool enabled, double start_time, double end_time);
  void update(double t, std::int64_t step, double dt);
  void finish();

 private:
  using WallClock = std::chrono::steady_clock;
  bool enabled_;
  double start_, end_time_;
  bool tty_;
  bool shown_ = false;
  WallClock::time_point wall_start_, last_, last_logged_;
};

}  // namespace mpmshock
