#include "openmp_wait.hpp"

#include <dlfcn.h>
#include <omp.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

namespace mpmshock {

namespace {

constexpr const char* kShortSpinCount = "3000";  // about 30 us of spinning before a waiting thread sleeps
// Holds the pid of the process that set GOMP_SPINCOUNT; execv keeps the pid, so the program started
// again knows the setting is mpmshock's, and one inherited from another process is not taken for it.
constexpr const char* kMarker = "MPMSHOCK_SET_GOMP_SPINCOUNT";

std::optional<std::string> given(const char* name) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return std::nullopt;
  return std::string(v);
}

// libgomp, not LLVM's libomp (which has __kmpc_fork_call and no GOMP_SPINCOUNT).
bool runtime_is_libgomp() { return ::dlsym(RTLD_DEFAULT, "__kmpc_fork_call") == nullptr; }

// The settings as the environment has them now (what a runtime loaded now would read).
std::string described_now() {
  const auto spin = given("GOMP_SPINCOUNT"), policy = given("OMP_WAIT_POLICY");
  if (!spin && !policy) return runtime_is_libgomp() ? "libgomp's default" : "the OpenMP runtime's default";
  if (spin && !policy && given(kMarker) == std::to_string(::getpid())) return "GOMP_SPINCOUNT=" + *spin + " (set by mpmshock)";
  std::string text;
  if (policy) text = "OMP_WAIT_POLICY=" + *policy;
  if (spin) text += (text.empty() ? "" : ", ") + ("GOMP_SPINCOUNT=" + *spin);
  return text + " (from the environment)";
}

std::optional<std::string>& found_on_entry() {
  static std::optional<std::string> text;
  return text;
}

// The thread count main() will use is one: the last --threads (main's parse_args keeps the last),
// else OMP_NUM_THREADS or the cores.
bool one_thread(char** argv) {
  const char* threads = nullptr;
  for (int i = 1; argv[i] != nullptr; ++i)
    if (std::strcmp(argv[i], "--threads") == 0 && argv[i + 1] != nullptr) threads = argv[++i];
  if (threads != nullptr) {
    char* end = nullptr;
    const long n = std::strtol(threads, &end, 10);
    if (*end == '\0') return n == 1;
  }
  return omp_get_max_threads() == 1;
}

// /proc/self/exe is the file this code was loaded from: not so under valgrind (it is valgrind's
// tool) or when the dynamic loader was started by hand (it is the loader).
bool exe_is_this_program() {
  struct stat exe {};
  if (::stat("/proc/self/exe", &exe) != 0) return false;
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (maps == nullptr) return false;
  const auto here = reinterpret_cast<std::uintptr_t>(&prefer_short_waits);
  bool same = false;
  char line[4096];
  while (std::fgets(line, sizeof line, maps) != nullptr) {
    std::uintptr_t begin = 0, end = 0;
    unsigned major_dev = 0, minor_dev = 0;
    unsigned long long inode = 0;
    if (std::sscanf(line, "%" SCNxPTR "-%" SCNxPTR " %*s %*s %x:%x %llu", &begin, &end, &major_dev, &minor_dev,
                    &inode) != 5)
      continue;
    if (here < begin || here >= end) continue;
    same = inode == static_cast<unsigned long long>(exe.st_ino) && major_dev == major(exe.st_dev) &&
           minor_dev == minor(exe.st_dev);
    break;
  }
  std::fclose(maps);
  return same;
}

}  // namespace

void prefer_short_waits(char** argv) {
  found_on_entry() = described_now();
  if (argv == nullptr || argv[0] == nullptr) return;
  if (given("OMP_WAIT_POLICY") || given("GOMP_SPINCOUNT") || one_thread(argv)) return;
  if (!runtime_is_libgomp() || !exe_is_this_program()) return;
  if (::setenv("GOMP_SPINCOUNT", kShortSpinCount, 1) == 0 &&
      ::setenv(kMarker, std::to_string(::getpid()).c_str(), 1) == 0)
    ::execv("/proc/self/exe", argv);
  // Not started again: the run goes on with the settings libgomp already read.
  ::unsetenv("GOMP_SPINCOUNT");
  ::unsetenv(kMarker);
}

std::string openmp_wait() {
  const std::optional<std::string>& entry = found_on_entry();
  return entry ? *entry : described_now();
}

}  // namespace mpmshock
