#!/usr/bin/env bash
# Fuzzes the scene parser with libFuzzer (clang, AddressSanitizer, UndefinedBehaviorSanitizer) for
# a bounded time. Seeds: every scene in configs/ and tests/data. Inputs that crash are written to
# tests/data/fuzz-crashers/; keep them there (the corpus test replays them) after fixing the bug.
# usage: scripts/fuzz.sh [SECONDS]   (default 120)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
command -v clang++ >/dev/null || { echo "fuzz.sh needs clang (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }
cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j "$(nproc)" >/dev/null
corpus=build-fuzz/corpus
mkdir -p "$corpus" tests/data/fuzz-crashers
cp configs/*.scene tests/data/*.scene tests/data/bad/*.scene tests/data/good/*.scene "$corpus"/ 2>/dev/null || true
cp tests/data/fuzz-crashers/* "$corpus"/ 2>/dev/null || true
build-fuzz/fuzz_scene "$corpus" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
  -artifact_prefix=tests/data/fuzz-crashers/ -print_final_stats=1
