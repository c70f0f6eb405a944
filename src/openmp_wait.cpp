#include "mpmshock/openmp_wait.hpp"

#include <omp.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace mpmshock {

namespace {

constexpr const char* kMarker = "MPMSHOCK_SET_GOMP_SPINCOUNT";  // tells the new program who set it

bool set(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0';
}

// --threads 1 (or one core, or OMP_NUM_THREADS=1): no thread ever waits for another.
bool one_thread(char** argv) {
  for (int i = 1; argv[i] != nullptr; ++i)
    if (std::strcmp(argv[i], "--threads") == 0 && argv[i + 1] != nullptr) return std::strcmp(argv[i + 1], "1") == 0;
  return omp_get_max_threads() == 1;
}

}  // namespace

void prefer_short_waits(char** argv) {
  if (set("OMP_WAIT_POLICY") || set("GOMP_SPINCOUNT") || one_thread(argv)) return;
  if (::setenv("GOMP_SPINCOUNT", kShortSpinCount, 1) != 0 || ::setenv(kMarker, "1", 1) != 0) return;
  ::execv("/proc/self/exe", argv);
  // Not started (no /proc): go on with the defaults libgomp already read, and say so.
  ::unsetenv("GOMP_SPINCOUNT");
  ::unsetenv(kMarker);
}

std::string openmp_wait() {
  if (set("GOMP_SPINCOUNT"))
    return std::string("GOMP_SPINCOUNT=") + std::getenv("GOMP_SPINCOUNT") +
           (set(kMarker) ? " (set by mpmshock)" : " (from the environment)");
  if (set("OMP_WAIT_POLICY")) return std::string("OMP_WAIT_POLICY=") + std::getenv("OMP_WAIT_POLICY") + " (from the environment)";
  return "libgomp's default";
}

}  // namespace mpmshock
