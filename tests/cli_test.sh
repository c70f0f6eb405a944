#!/usr/bin/env bash
# The mpmshock command line: help and version, exit codes, errors that name the file, line and key,
# nothing written on bad input, --check, --set, and refusal to overwrite an earlier run.
# usage: cli_test.sh MPMSHOCK_BINARY TESTS_DATA_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
bin=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

expect 0 "usage: mpmshock SCENE" -- --help
expect 0 "^mpmshock [0-9]+\.[0-9]+\.[0-9]+" -- --version
expect 0 "\| \`velocity\` \| m/s \|" -- --keys
expect 0 "material.copper.sound_speed = 3940 m/s" -- --materials
expect 0 "tillotson \(equation_of_state = tillotson\); built in for: aluminium" -- --laws
expect 0 "bilinear \(strength_model = bilinear, the default\)" -- --laws
expect 2 "no scene file given" --
expect 2 "unknown option '--frobnicate'" -- --frobnicate x.scene
expect 2 "--threads needs a whole number" -- x.scene --threads zero
expect 2 "missing.scene: cannot open" -- missing.scene

printf 'velocity = 1000 m/s\nporosty = 1.1\noutput_dir = should_not_exist\n' > typo.scene
expect 2 "typo.scene:2: key 'porosty': unknown key; did you mean 'porosity'\?" -- typo.scene
[ -e should_not_exist ] && fail "a bad scene created its output_dir"

printf 'velocity = 1000 m/s\nporosity = 0.5\n' > range.scene
expect 2 "range.scene:2: key 'porosity': value 0.5 is out of range" -- range.scene
expect 2 "--set #1 \(cfl=1.5\): key 'cfl'" -- range.scene --set cfl=1.5

cp "$data/tiny_porous.scene" tiny.scene
expect 0 "material points: [0-9]+" -- tiny.scene --check
# --check names every effect the run simulates, and none that it does not.
expect 0 "effects: plasticity \(with Steinberg-Guinan softening\), thermal \(energy temperature model\), melting \(T_m0 1220 K, Lindemann a 1.5, latent heat 397000 J/kg\), bounded expansion" -- tiny.scene --check --set thermal_softening=on --set bounded_expansion=on
expect 0 "thermal \(energy temperature model, the paper's reported beside it\)" -- tiny.scene --check --set paper_temperature=on
# Solid bodies: the impact state where their Hugoniots cross (the symmetric impact's Rankine-Hugoniot
# pressure; copper on aluminium at rest, the impedance match of test_impedance), and the materials.
expect 0 "impact \(solid Hugoniots, hydrodynamic\): 18.06[0-9]* GPa, the interface moving at 0 m/s" -- tiny.scene --check --set porosity=1
expect 0 "impact \(solid Hugoniots, hydrodynamic\): 11.84[0-9]* GPa, the interface moving at 697.8[0-9]* m/s" -- \
  tiny.scene --check --set porosity=1 --set flyer_material=copper --set target_velocity=0
expect 0 "materials: target the scene's material keys \(2700 kg/m3\), flyer copper \(8930 kg/m3\)" -- \
  tiny.scene --check --set porosity=1 --set flyer_material=copper
expect 0 "window: y 0.3 .. 0.35 mm, [0-9]+ material points of pmma" -- \
  tiny.scene --check --set "window_height=50 um" --set window_material=pmma
expect 0 "effects: thermal \(energy temperature model\), volumetric smoothing, voids; update" -- tiny.scene --check --set plasticity=off --set artificial_viscosity=off
[ -e tiny_porous_out ] && fail "--check wrote output"

expect 0 "porosity \(from material points\): 1\.19" -- tiny.scene --quiet --set end_time=20ns --set output_dir=run1
for f in regions.csv conservation.csv summary.json scene.txt voids.csv snapshot_00000.h5; do
  [ -s "run1/$f" ] || fail "run1/$f missing or empty"
done
grep -q "^end_time = 2e-08 s$" run1/scene.txt || fail "--set end_time not in the resolved scene"
cp run1/regions.csv before.csv
expect 2 "key 'output_dir': 'run1' holds the outputs of an earlier run; pass --force" -- tiny.scene --set output_dir=run1
cmp -s before.csv run1/regions.csv || fail "a refused run changed the earlier outputs"
expect 0 "steps: " -- tiny.scene --quiet --force --set end_time=20ns --set output_dir=run1

[ "$(wc -l < run1/voids.csv)" -gt 10 ] || fail "voids.csv lists too few voids"

# thermal = off: no temperature is computed, and the columns say so.
expect 0 "steps: " -- tiny.scene --quiet --set end_time=10ns --set thermal=off --set output_dir=cold
tail -n 1 cold/regions.csv | cut -d, -f8,9 | grep -qx "nan,nan" || fail "thermal = off did not write nan temperatures"

# A scene with old Mac line endings (a lone CR) is read line by line, not as one comment line.
expect 0 "bodies \(width 0.04 mm" -- "$data/good/cr_only_line_endings.scene" --check

# Paths that could not be read back from scene.txt, and over-long arguments, are refused.
expect 2 "key 'output_dir': the path has a '#'" -- tiny.scene --check --set "output_dir=a#b"
expect 2 "key 'output_dir': the path has a control character" -- tiny.scene --check --set "output_dir=a
b"
expect 2 "at most 4096" -- tiny.scene --check --set "velocity=$(head -c 5000 /dev/zero | tr '\0' 1)"
expect 2 "it is a device, not a regular file" -- /dev/zero --check
# A leading space in a restart's --set names the same key: the run goes to the new directory.
"$bin" tiny.scene --quiet --set end_time=20ns --set output_dir=lead >/dev/null 2>&1
expect 0 "outputs: .*lead2" -- --restart lead/snapshot_00001.h5 --quiet --set end_time=30ns --set " output_dir=lead2"

# Material that leaves the grid stops the run with a diagnostic and a last snapshot (exit 3).
printf 'porosity = 1\nwidth = 40 um\ntarget_height = 300 um\nflyer_height = 300 um\ncell_size = 10 um\n' > thin.scene
printf 'grid_margin = 20 um\nend_time = 200 ns\nsnapshot_interval = 0\noutput_dir = thin\n' >> thin.scene
expect 3 "material point [0-9]+ left the grid .* enlarge grid_margin" -- thin.scene --quiet
ls thin/snapshot_0000[1-9].h5 >/dev/null 2>&1 || fail "no final snapshot after leaving the grid"
grep -q '"exit_code": 3' thin/summary.json || fail "summary.json does not record exit code 3"

# SIGTERM: the current step finishes, the state is saved and the summary written (exit 143), and
# the run restarts from that snapshot. The signal lands whenever it lands (a loaded machine may run
# far past the point where it was sent): the test takes the snapshot and the time that the stop
# message names, so its verdict does not depend on the machine's speed. The run is sent the signal
# once regions.csv has a few rows, at ~130 ns of its 50 us, so it cannot have ended by then.
"$bin" tiny.scene --quiet --threads 2 --set end_time=50us --set output_dir=stopped >stop.out 2>stop.err &
pid=$!
while kill -0 "$pid" 2>/dev/null; do
  [ -f stopped/regions.csv ] && [ "$(wc -l < stopped/regions.csv)" -ge 13 ] && break
  sleep 0.05
done
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 143 ] || fail "SIGTERM: exit $rc, expected 143: $(cat stop.err)"
snapshot=$(sed -n 's/.*continue with: mpmshock --restart \(.*snapshot_[0-9]*\.h5\)$/\1/p' stop.err)
stop_ns=$(sed -n 's/.*stopped by SIGTERM at t = \([0-9.e+]*\) ns.*/\1/p' stop.err)
[ -n "$snapshot" ] && [ -n "$stop_ns" ] || fail "SIGTERM: no stop message naming a snapshot and time: $(cat stop.err)"
grep -q '"exit_code": 143' stopped/summary.json || fail "SIGTERM: summary.json lacks exit code 143"
[ -f "$snapshot" ] || fail "SIGTERM: the snapshot the message names ($snapshot) does not exist"
[ "$(ls stopped/snapshot_*.h5 | tail -n 1)" = "$snapshot" ] ||
  fail "SIGTERM: the named snapshot $snapshot is not the newest: $(ls stopped)"
ls stopped/*.tmp >/dev/null 2>&1 && fail "SIGTERM left temporary files"
restart_end=$(awk -v t="$stop_ns" 'BEGIN { printf "%.6gns", t + 20 }')
expect 0 "restarted at" -- --restart "$snapshot" --quiet --set end_time="$restart_end"

# A full disk: with a file-size limit (and SIGXFSZ ignored) writes fail as on a full disk; the run
# ends with exit 4 and a clear message, leaving no half-written file.
( ulimit -f 400; trap '' XFSZ; "$bin" tiny.scene --quiet --set output_dir=full ) >full.out 2>&1
rc=$?
[ "$rc" -eq 4 ] || fail "file-size limit: exit $rc, expected 4: $(cat full.out)"
grep -q "writing snapshot .*snapshot_00000.h5: .*disk full" full.out || fail "file-size limit: no clear message: $(cat full.out)"
ls full/*.tmp >/dev/null 2>&1 && fail "file-size limit left a temporary file"
# A real small file system, where this machine lets us mount one: the snapshots written before
# it filled up stay complete and readable.
mkdir -p small
if mount -t tmpfs -o size=3M tmpfs small 2>/dev/null; then
  "$bin" tiny.scene --quiet --set output_dir=small/run --set snapshot_interval=10ns >small.out 2>&1
  rc=$?
  [ "$rc" -eq 4 ] || fail "full tmpfs: exit $rc, expected 4"
  for f in small/run/snapshot_*.h5; do
    h5dump -H "$f" >/dev/null 2>&1 || fail "full tmpfs: $f is not a readable HDF5 file"
  done
  [ "$(ls small/run/snapshot_*.h5 | wc -l)" -ge 2 ] || fail "full tmpfs: fewer than 2 complete snapshots"
  umount small
else
  echo "note: cannot mount a tmpfs here; the full-file-system check ran with a file-size limit only"
fi
# OpenMP's waits (src/openmp_wait.hpp): with neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT set and two
# threads, mpmshock starts itself again with a short spin count, keeping its arguments (a bad scene is
# still reported, with its exit code), and records what libgomp read as it loaded (the environment on
# entry: a run that was not started again says "libgomp's default"); a user's own setting, a marker
# inherited from another process and one-thread runs are left as they are, and so is a program the
# dynamic loader was asked to start (/proc/self/exe is then the loader).
unset_waits=(-u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u MPMSHOCK_SET_GOMP_SPINCOUNT)
waits() {  # waits NAME EXPECTED-LOG-LINE ENV... -- COMMAND...
  local name=$1 line=$2 envs=()
  shift 2
  while [ "$1" != "--" ]; do envs+=("$1"); shift; done
  shift
  timeout 120 env "${unset_waits[@]}" "${envs[@]}" "$@" tiny.scene --quiet --set end_time=5ns \
    --set output_dir="$name" >"$name.out" 2>&1 || fail "waits $name: exit $?: $(cat "$name.out")"
  grep -qxF "# OpenMP waits: $line" "$name/log.txt" || fail "waits $name: log.txt lacks '$line': $(grep OpenMP "$name/log.txt")"
  grep -qF "\"openmp_wait\": \"$line\"" "$name/summary.json" || fail "waits $name: summary.json lacks '$line'"
}
waits wait_set "GOMP_SPINCOUNT=3000 (set by mpmshock)" -- "$bin" --threads 2
waits wait_last "GOMP_SPINCOUNT=3000 (set by mpmshock)" -- "$bin" --threads 1 --threads 2
waits wait_user "GOMP_SPINCOUNT=5000 (from the environment)" GOMP_SPINCOUNT=5000 -- "$bin" --threads 2
waits wait_policy "OMP_WAIT_POLICY=passive (from the environment)" OMP_WAIT_POLICY=passive -- "$bin" --threads 2
waits wait_both "OMP_WAIT_POLICY=active, GOMP_SPINCOUNT=5000 (from the environment)" OMP_WAIT_POLICY=active \
  GOMP_SPINCOUNT=5000 -- "$bin" --threads 2
waits wait_inherited "GOMP_SPINCOUNT=5000 (from the environment)" MPMSHOCK_SET_GOMP_SPINCOUNT=1 GOMP_SPINCOUNT=5000 -- \
  "$bin" --threads 2
waits wait_one "libgomp's default" -- "$bin" --threads 1
waits wait_one_env "libgomp's default" OMP_NUM_THREADS=1 -- "$bin"
loader=$(readelf -l "$bin" 2>/dev/null | sed -n 's/.*Requesting program interpreter: \(.*\)]$/\1/p')
if [ -x "$loader" ]; then
  waits wait_loader "libgomp's default" -- "$loader" "$bin" --threads 2
else
  echo "note: no program interpreter found for $bin; the loader-started run was not checked"
fi
out=$(timeout 120 env "${unset_waits[@]}" "$bin" typo.scene --threads 2 2>&1)
rc=$?
[ "$rc" -eq 2 ] && echo "$out" | grep -q "typo.scene:2: key 'porosty'" ||
  fail "a bad scene, started again for the spin count: exit $rc, output: $out"

# A directory that cannot be created or written.
expect 4 "cannot create output_dir '/proc/mpmshock-test" -- tiny.scene --quiet --set output_dir=/proc/mpmshock-test/out

if [ "$failures" -eq 0 ]; then echo "all checks passed"; else echo "$failures check(s) failed"; exit 1; fi
