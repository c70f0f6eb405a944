#!/usr/bin/env bash
# Fuzzes with libFuzzer (clang, AddressSanitizer, UndefinedBehaviorSanitizer) for a bounded time:
#   scene     the scene parser; seeds: every scene in configs/ and tests/data
#   snapshot  the snapshot reader behind --restart; seeds: the snapshots of a tiny run
# Inputs that crash are written to tests/data/fuzz-crashers/ (scene) or build-fuzz/crashers/
# (snapshot); keep scene crashers there after fixing the bug (the corpus test replays them).
# A snapshot without a valid checksum is first read in a child process (src/snapshot.cpp): a libhdf5
# crash there is contained and reported as damage, but libFuzzer's handlers, inherited by the child,
# still save the input as crash-* in build-fuzz/crashers/. The run goes on after those; it stops only
# when this process itself fails, so "Done N runs" at the end means the property held.
# usage: scripts/fuzz.sh [SECONDS] [scene|snapshot]   (default 120 s, scene)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
target=${2:-scene}
command -v clang++ >/dev/null || { echo "fuzz.sh needs clang (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }
cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j "$(nproc)" >/dev/null
if [ "$target" = snapshot ]; then
  # HDF5 allocates what a damaged file claims; that returns null (and an error) outside ASan too.
  export ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1
  scripts/build.sh >/dev/null
  corpus=build-fuzz/snapshot-corpus
  mkdir -p "$corpus" build-fuzz/crashers
  printf 'porosity = 1\nwidth = 40 um\ntarget_height = 40 um\nflyer_height = 40 um\ncell_size = 10 um\nend_time = 4 ns\nsnapshot_interval = 2 ns\n' \
    >build-fuzz/seed.scene
  build/src/mpmshock build-fuzz/seed.scene --quiet --force --set output_dir=build-fuzz/seed >/dev/null
  cp build-fuzz/seed/snapshot_*.h5 "$corpus"/
  exec build-fuzz/fuzz_snapshot "$corpus" -max_total_time="$seconds" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
    -artifact_prefix=build-fuzz/crashers/ -print_final_stats=1
fi
corpus=build-fuzz/corpus
mkdir -p "$corpus" tests/data/fuzz-crashers
cp configs/*.scene tests/data/*.scene tests/data/bad/*.scene tests/data/good/*.scene "$corpus"/ 2>/dev/null || true
cp tests/data/fuzz-crashers/* "$corpus"/ 2>/dev/null || true
build-fuzz/fuzz_scene "$corpus" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
  -artifact_prefix=tests/data/fuzz-crashers/ -print_final_stats=1
