#include "mpmshock/signals.hpp"

#include <csignal>

namespace mpmshock {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
volatile std::sig_atomic_t g_heard = 0;  // live StopRequestsHeard objects

extern "C" void on_stop_signal(int sig) {
  g_stop_signal = sig;
  std::signal(sig, SIG_DFL);  // a second signal ends the program at once
  if (g_heard == 0) std::raise(sig);  // nothing would act on it: end now
}

}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

int stop_signal() { return g_stop_signal; }

StopRequestsHeard::StopRequestsHeard() { g_heard = g_heard + 1; }
StopRequestsHeard::~StopRequestsHeard() { g_heard = g_heard - 1; }

}  // namespace mpmshock
