// SIGINT and SIGTERM ask a running run to stop after its current step (the time loop looks at
// stop_signal() between steps); a second one ends the program at once.
#pragma once

namespace mpmshock {

void install_stop_handlers();

// The signal that asked the run to stop, or 0.
int stop_signal();

}  // namespace mpmshock
