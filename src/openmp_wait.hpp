// How a thread that waits at one of OpenMP's barriers waits. GCC's libgomp makes it spin for about
// 3 ms before it sleeps. Where another program holds a core, the spinning thread keeps the core that
// the thread with work left needs, and every barrier waits for the scheduler; a spin of about 30 us
// loses most of that for about 1 % of the idle speed (docs/method.md, "Threads on a busy machine",
// has the measurements).
//
// libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, as it is loaded, before main() runs; a
// program cannot change them for itself. So main() calls prefer_short_waits() first, before MPI
// starts: where the user set neither variable, more than one thread may run and the OpenMP runtime
// is libgomp (LLVM's libomp does not read GOMP_SPINCOUNT), it sets GOMP_SPINCOUNT=3000 and starts the
// same program again with the same arguments (execv of /proc/self/exe: the same process, the same
// pid), whose libgomp then reads it. It does not where /proc/self/exe is not the file the running
// code came from (under valgrind, or the dynamic loader started by hand): the run keeps libgomp's
// default there. A user's own setting is left as it is. The run records which applied (log.txt,
// summary.json). Private to the program (src/): a library user's process is not started again.
#pragma once

#include <string>

namespace mpmshock {

// Called first in main(), with main's argv. Returns where nothing needs changing (or the program
// cannot be started again: the run goes on with libgomp's defaults); otherwise it does not return.
void prefer_short_waits(char** argv);

// The wait settings this process's OpenMP runtime read as it loaded, for the run's records:
// "GOMP_SPINCOUNT=3000 (set by mpmshock)", "OMP_WAIT_POLICY=passive (from the environment)",
// "libgomp's default". As prefer_short_waits() found them on entry where it ran, else as the
// environment has them now.
std::string openmp_wait();

}  // namespace mpmshock
