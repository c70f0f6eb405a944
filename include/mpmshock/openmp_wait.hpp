// How a thread that waits at one of OpenMP's barriers waits. GCC's libgomp makes it spin for about
// 3 ms (300,000 spins) before it sleeps. On an idle machine that is harmless; where another program
// holds a core, the spinning thread keeps the core that the thread with work left needs, and every
// barrier waits for the scheduler (docs/method.md, "Threads on a busy machine"). A short spin keeps
// the idle speed and loses most of that: 2 threads on every step beside a busy loop took 10.4-11.3 s
// with 1,000 spins where the default took 14.1-24.3 s and 1 thread 9.8-11.0 s; idle, 3,000 spins cost
// 0.3-0.5 % and 1,000 spins 0.8-1.0 % over the default (docs/method.md has the runs).
//
// libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, as it is loaded, before main() runs; a
// program cannot change them for itself. So main() calls prefer_short_waits() first, before MPI
// starts: where the user set neither variable and more than one thread may run, it sets
// GOMP_SPINCOUNT=3000 (about 30 us of spinning) and starts the same program again with the same
// arguments (execv of /proc/self/exe: the same process, the same pid), whose libgomp then reads it.
// A user's own setting is left as it is. The run records which applied (log.txt, summary.json).
// Under valgrind, whose child programs run outside it unless traced, use --threads 1 or set one of
// the variables.
#pragma once

#include <string>

namespace mpmshock {

// The spin count mpmshock sets: about 30 us of spinning before a waiting thread sleeps.
inline constexpr const char* kShortSpinCount = "3000";

// Called first in main(), with main's argv. Returns where nothing needs changing (or the new
// program could not be started, when the run goes on with libgomp's defaults); otherwise it does
// not return.
void prefer_short_waits(char** argv);

// How this process's OpenMP threads wait, for the run's records: "GOMP_SPINCOUNT=3000 (set by
// mpmshock)", "OMP_WAIT_POLICY=passive (from the environment)", "libgomp's default".
std::string openmp_wait();

}  // namespace mpmshock
