#!/usr/bin/env bash
# Builds mpmshock with AddressSanitizer and UndefinedBehaviorSanitizer (GCC) into build-sanitize/
# and runs the unit and integration tests under them. Any sanitizer report fails the test that
# triggered it. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMPMSHOCK_NATIVE=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-sanitize -j "$(nproc)"
cd build-sanitize
# OpenMP's runtime keeps thread pools to the end; those are not leaks of ours.
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --output-on-failure -j "$(nproc)" -L "unit|integration|mpi" "$@"
