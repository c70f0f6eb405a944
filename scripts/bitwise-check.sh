#!/usr/bin/env bash
# Checks that a change leaves every output bit for bit as it was: builds REF (a commit; default
# HEAD) in a temporary worktree and the working tree beside it, runs the same scenes with both,
# and compares the run directories with scripts/compare-runs.py. For refactorings and
# optimisations that must not change the results.
#
# Both are built with -ffp-contract=off (strict IEEE evaluation: every product and sum rounded as
# the source writes it), so equal outputs mean the two sources compute the same arithmetic. The
# release build lets the compiler fuse a*b + c into one rounding where it sees fit, and where it
# sees fit depends on the code's shape (a field stored as x[p][0], x[p][1] rather than x[p], y[p]
# is vectorised and fused differently): two sources that are arithmetically identical can then
# differ in the last bits. --release compares the release builds instead.
#
# usage: scripts/bitwise-check.sh [REF] [--keep DIR] [--release]
#   REF         the commit to compare against (default HEAD, i.e. the uncommitted change)
#   --keep DIR  keep the run directories in DIR (default: a temporary directory, removed)
#   --release   compare the release builds (build/ and REF's), fused multiply-adds and all
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
ref=HEAD
keep=""
flags="-ffp-contract=off"
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) keep=$2; shift 2 ;;
    --release) flags=""; shift ;;
    *) ref=$1; shift ;;
  esac
done
sha=$(git rev-parse --short "$ref")
work=${keep:-$(mktemp -d)}
mkdir -p "$work"
[ -z "$keep" ] && trap 'git -C "$root" worktree remove --force "$work/src-$sha" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT

# The reference build, cached by commit and flags in /tmp so repeated checks build it once.
suffix=${flags:+-strict}
refbuild=/tmp/mpmshock-ref-$sha$suffix
if [ ! -x "$refbuild/src/mpmshock" ]; then
  git worktree add --detach "$work/src-$sha" "$sha" >/dev/null
  cmake -S "$work/src-$sha" -B "$refbuild" -DCMAKE_BUILD_TYPE=Release -DMPMSHOCK_BUILD_TESTS=OFF \
    -DCMAKE_CXX_FLAGS="$flags" >/dev/null
  cmake --build "$refbuild" -j "$(nproc)" --target mpmshock >/dev/null
  git worktree remove --force "$work/src-$sha"
fi
newbuild=$root/build$suffix
cmake -S . -B "$newbuild" -DCMAKE_BUILD_TYPE=Release -DMPMSHOCK_BUILD_TESTS=OFF -DCMAKE_CXX_FLAGS="$flags" >/dev/null
cmake --build "$newbuild" -j "$(nproc)" --target mpmshock >/dev/null
new=$newbuild/src/mpmshock
old=$refbuild/src/mpmshock

# name | scene | overrides
cases=(
  "default|configs/default.scene|end_time=100ns"
  "solid_plate|configs/solid_plate.scene|end_time=100ns"
  "paper_base|configs/paper_base.scene|end_time=30ns"
  "paper_delta1.4|configs/paper_delta1.4.scene|end_time=30ns"
  "tiny|tests/data/tiny_porous.scene|"
  "tiny_gimp|tests/data/tiny_porous.scene|shape_function=gimp"
  "tiny_bilinear|tests/data/tiny_porous.scene|shape_function=bilinear"
  "tiny_usl|tests/data/tiny_porous.scene|update_scheme=usl"
  "tiny_hydro|tests/data/tiny_porous.scene|plasticity=off"
  "tiny_mixed|tests/data/tiny_porous.scene|hardening_beta=0.5"
  "tiny_kinematic|tests/data/tiny_porous.scene|hardening_beta=0 artificial_viscosity=off"
  "tiny_cold|tests/data/tiny_porous.scene|thermal=off"
  "tiny_grid|tests/data/tiny_porous.scene|snapshot_grid=on snapshot_compression=1"
)
for scene in tests/data/hard/*.scene; do
  name=$(basename "$scene" .scene)
  cases+=("hard_$name|$scene|")
done

failures=0
run_case() {  # binary outdir scene overrides...
  local bin=$1 out=$2 scene=$3
  shift 3
  local sets=()
  for o in "$@"; do sets+=(--set "$o"); done
  "$bin" "$scene" --quiet --force --set "output_dir=$out" "${sets[@]}" >/dev/null 2>&1 || true
}
for c in "${cases[@]}"; do
  IFS='|' read -r name scene overrides <<<"$c"
  read -r -a extra <<<"$overrides"
  run_case "$old" "$work/old/$name" "$scene" "${extra[@]}"
  run_case "$new" "$work/new/$name" "$scene" "${extra[@]}"
  if [ ! -d "$work/old/$name" ] && [ ! -d "$work/new/$name" ]; then
    echo "same      $name (refused by both: no outputs)"
  elif diff=$(/usr/bin/python3 scripts/compare-runs.py "$work/old/$name" "$work/new/$name"); then
    echo "same      $name"
  else
    echo "DIFFERENT $name"
    echo "$diff" | head -n 8 | sed 's/^/          /'
    failures=$((failures + 1))
  fi
done

# A restart: run to 30 ns, restart to 60 ns, in both builds.
for side in old new; do
  bin=$old
  [ "$side" = new ] && bin=$new
  run_case "$bin" "$work/$side/restart" tests/data/tiny_porous.scene end_time=30ns grid_margin=100um
  "$bin" --restart "$work/$side/restart/snapshot_00001.h5" --quiet --force --set end_time=60ns >/dev/null 2>&1 || true
done
if diff=$(/usr/bin/python3 scripts/compare-runs.py "$work/old/restart" "$work/new/restart"); then
  echo "same      restart"
else
  echo "DIFFERENT restart"
  echo "$diff" | head -n 8 | sed 's/^/          /'
  failures=$((failures + 1))
fi

if [ "$failures" -eq 0 ]; then
  echo "bitwise-check: every output is bit for bit as at $sha (${flags:-release build})"
else
  echo "bitwise-check: $failures case(s) differ from $sha"
  exit 1
fi
