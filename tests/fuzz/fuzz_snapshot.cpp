// libFuzzer target for the snapshot reader behind --restart: the input is a file's bytes, given to
// the same validation a restart runs (mpmshock --restart FILE --check). Property: it either
// validates or throws SceneError (exit 2), whatever the bytes; no other exception, no crash, no
// sanitizer report. Seeds: snapshots of a tiny run (scripts/fuzz.sh makes them).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "mpmshock/hdf5_io.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/mpmshock_fuzz_snapshot_" + std::to_string(::getpid()) + ".h5";
  mpmshock::h5::prepare_library();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    (void)mpmshock::check_restart(path, {});
  } catch (const mpmshock::SceneError&) {
    // refused: the expected outcome for almost every input
  } catch (const std::exception& e) {
    std::fprintf(stderr, "a snapshot was refused with the wrong kind of error: %s\n", e.what());
    std::abort();
  }
  return 0;
}
