#!/usr/bin/env bash
# Finds tests whose verdict depends on timing: runs the whole CTest suite ROUNDS times (default 5)
# with a busy loop on every core, as `ctest -j` runs it in CI, and reports every test that failed
# in any round, with how often. A developer tool (a round takes a few minutes under load); CI runs
# the suite once, idle. Extra arguments go to ctest (e.g. -L unit).
#
# usage: scripts/stress-tests.sh [ROUNDS] [ctest arguments...]
set -uo pipefail
cd "$(dirname "$0")/.."
rounds=5
if [ $# -gt 0 ] && [[ $1 =~ ^[0-9]+$ ]]; then rounds=$1; shift; fi
scripts/build.sh >/dev/null || exit 1
cores=$(nproc)
busy=()
for _ in $(seq 1 "$cores"); do
  ( while :; do :; done ) &
  busy+=($!)
done
trap 'kill "${busy[@]}" 2>/dev/null' EXIT
echo "stress-tests: $rounds round(s) of the suite with $cores busy loop(s) beside it"

declare -A failed=()
for round in $(seq 1 "$rounds"); do
  log=$(mktemp)
  start=$(date +%s)
  (cd build && ctest -j "$cores" --output-on-failure "$@") >"$log" 2>&1
  rc=$?
  names=$(sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) (.*/\1/p' "$log")
  for n in $names; do failed[$n]=$((${failed[$n]:-0} + 1)); done
  echo "round $round: exit $rc in $(($(date +%s) - start)) s; failed: ${names:-none}"
  [ "$rc" -ne 0 ] && cp "$log" "build/stress-round-$round.log" && echo "  log: build/stress-round-$round.log"
  rm -f "$log"
done

if [ "${#failed[@]}" -eq 0 ]; then
  echo "stress-tests: no test failed in $rounds round(s) under full load"
else
  echo "stress-tests: tests that failed under load (a timing dependence to fix):"
  for n in "${!failed[@]}"; do echo "  $n: ${failed[$n]} of $rounds round(s)"; done
  exit 1
fi
