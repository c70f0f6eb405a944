// SIGINT and SIGTERM ask a running run to stop after its current step (the time loop looks at
// stop_signal() between steps); a second one ends the program at once. Where nothing looks at the
// request (set-up, a blocking open or read), the first one ends the program at once, as it would
// without a handler: a request nobody acts on would be swallowed.
#pragma once

namespace mpmshock {

void install_stop_handlers();

// The signal that asked the run to stop, or 0.
int stop_signal();

// While an object of this type lives, a stop signal is a request that the code looks at
// (stop_signal()): the time loop, a wait that polls. Nests.
class StopRequestsHeard {
 public:
  StopRequestsHeard();
  ~StopRequestsHeard();
  StopRequestsHeard(const StopRequestsHeard&) = delete;
  StopRequestsHeard& operator=(const StopRequestsHeard&) = delete;
};

}  // namespace mpmshock
