#include "mpmshock/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "mpmshock/run_log.hpp"

namespace mpmshock {

std::string human_time(double seconds) {
  char buf[64];
  if (seconds < 60) std::snprintf(buf, sizeof buf, "%.0fs", seconds);
  else if (seconds < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(seconds) / 3600, (int(seconds) % 3600) / 60);
  return buf;
}

Progress::Progress(bool enabled, double start_time, double end_time)
    : enabled_(enabled), start_(start_time), end_time_(end_time), tty_(isatty(fileno(stderr))),
      wall_start_(WallClock::now()), last_(wall_start_), last_logged_(wall_start_) {}

void Progress::update(double t, std::int64_t step, double dt) {
  if (!enabled_) return;
  const auto now = WallClock::now();
  if (std::chrono::duration<double>(now - last_).count() < (tty_ ? 1.0 : 10.0)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - wall_start_).count();
  const double done = (t - start_) / (end_time_ - start_);
  const double eta = done > 0 ? elapsed * (1.0 - done) / done : 0.0;
  char line[160];
  std::snprintf(line, sizeof line, "[%5.1f%%] t = %.4g ns  step %lld  dt = %.4g ns  ETA %s", 100.0 * t / end_time_,
                t * 1e9, static_cast<long long>(step), dt * 1e9, human_time(eta).c_str());
  std::fprintf(stderr, tty_ ? "\r%s   " : "%s\n", line);
  std::fflush(stderr);
  // log.txt gets a line every 10 s, as a file does.
  if (std::chrono::duration<double>(now - last_logged_).count() >= 10.0) {
    last_logged_ = now;
    log_only(std::string(line) + "\n");
  }
  shown_ = true;
}

void Progress::finish() {
  if (enabled_ && tty_ && shown_) std::fprintf(stderr, "\n");
}

}  // namespace mpmshock
