#include "mpmshock/thread_tuner.hpp"

#include <algorithm>

namespace mpmshock {

ThreadTuner::ThreadTuner(int max_threads) : max_(std::max(1, max_threads)), current_(max_) {}

// Half or double the current count, alternating where both are possible.
int ThreadTuner::next_candidate() {
  const bool can_go_down = current_ > 1, can_go_up = current_ < max_;
  go_down_ = can_go_down && (!can_go_up || !go_down_);
  return go_down_ ? current_ / 2 : std::min(max_, 2 * current_);
}

double ThreadTuner::mean_without_largest(const std::vector<double>& v) {
  if (v.size() == 1) return v.front();
  double sum = 0.0;
  for (double x : v) sum += x;
  return (sum - *std::max_element(v.begin(), v.end())) / static_cast<double>(v.size() - 1);
}

void ThreadTuner::record(double seconds) {
  ++steps_;
  if (threads() < max_) ++below_max_;
  if (max_ == 1) return;
  if (changes_team_) {
    changes_team_ = false;
    return;
  }
  if (trying_) {
    trial_.push_back(seconds);
    const double now = mean_without_largest(recent_);
    const int n = static_cast<int>(trial_.size());
    const bool clear_loss =
        n == kClearLoss && *std::min_element(trial_.begin(), trial_.end()) > (1.0 + kMargin) * now;
    if (n < static_cast<int>(recent_.size()) && !clear_loss) return;
    trying_ = false;
    if (!clear_loss && mean_without_largest(trial_) < (1.0 - kMargin) * now) {
      current_ = candidate_;
      period_ = kPeriodAfterSwitch;
      recent_.clear();
    } else {
      period_ = std::min(kMaxPeriod, 2 * period_);
    }
    trial_.clear();
    since_try_ = 0;
    changes_team_ = true;
    return;
  }
  recent_.push_back(seconds);
  if (static_cast<int>(recent_.size()) > kWindow) recent_.erase(recent_.begin());
  if (++since_try_ >= period_ && static_cast<int>(recent_.size()) >= kSamples) {
    trying_ = true;
    changes_team_ = true;
    candidate_ = next_candidate();
  }
}

}  // namespace mpmshock
