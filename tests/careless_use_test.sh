#!/usr/bin/env bash
# Careless and hostile use of the command line on one process (issue 30; the MPI cases are in
# mpi_test.sh): restarts that would mix two things under one name or continue another run's files,
# the row at the restart time, files that are not regular, 3D columns and probes, the step estimate
# with conduction, every scene error at once, look-alike characters, the system's reason for an
# unreadable file, and the size of probes.csv. Each case ends with its message and exit code, and a
# refused request changes nothing already written.
# usage: careless_use_test.sh MPMSHOCK_BINARY TESTS_DATA_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
bin=$(realpath "$1")
data=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# A digest of every file of a directory, to show that a refused request changed nothing.
digest() { (cd "$1" && find . -type f ! -name .mpmshock.lock | sort | xargs md5sum); }
# The first data row's time of a CSV file.
first_time() { sed -n 2p "$1" | cut -d, -f1; }

cp "$data/tiny_porous.scene" tiny.scene
printf 'probe.a = surface\n' >> tiny.scene
"$bin" tiny.scene --quiet --set end_time=40ns --set output_dir=A >/dev/null 2>&1 || fail "the source run failed"
[ -f A/snapshot_00001.h5 ] || fail "no snapshot at 30 ns in A"

# 2. A restart may add a probe or region under a new name but not redefine one already in the files.
before=$(digest A)
expect 2 "key 'probe.a': the run of .* already has 'probe.a = surface'.* not redefine one" -- \
  --restart A/snapshot_00001.h5 --force --quiet --set "probe.a=point 100 um 100 um" --set end_time=50ns
expect 2 "key 'region.T800': the run of .* already has .* not redefine one" -- \
  --restart A/snapshot_00001.h5 --force --quiet --set "region.T800=bottom 0 um 100 um" --set end_time=50ns
[ "$(digest A)" = "$before" ] || fail "a refused redefinition changed A"
cp -r A B
expect 0 "restarted at" -- --restart B/snapshot_00001.h5 --force --quiet --set "probe.b=point 100 um 290 um" \
  --set "region.low=bottom 0 um 100 um" --set end_time=50ns
grep -q ",b,1," B/probes.csv || fail "the new probe b has no rows in probes.csv"
grep -q ",a,[0-9]*," B/probes.csv || fail "probe a lost its rows"

# 3. Outputs that cannot be checked against a scene are not continued.
cp -r A C
rm C/scene.txt
before=$(digest C)
expect 2 "/C/regions.csv is there but .*/C/scene.txt is not" -- --restart C/snapshot_00001.h5 --force --quiet --set end_time=50ns
[ "$(digest C)" = "$before" ] || fail "a refused restart without scene.txt changed C"

# 5. Every file a restart starts has the row at the restart time (3e-08 s); files it continues
# keep theirs, and scene.txt names the directory the run now writes.
expect 0 "restarted at 30 ns" -- --restart A/snapshot_00001.h5 --quiet --set output_dir=D --set end_time=50ns
for f in regions.csv conservation.csv probes.csv; do
  [ "$(first_time "D/$f")" = "3e-08" ] || fail "restart into a new directory: D/$f starts at $(first_time "D/$f"), not 3e-08"
done
mkdir E
cp A/snapshot_00001.h5 E/
expect 0 "restarted at 30 ns" -- --restart E/snapshot_00001.h5 --quiet --set end_time=50ns
for f in regions.csv conservation.csv probes.csv; do
  [ "$(first_time "E/$f")" = "3e-08" ] || fail "a snapshot alone: E/$f starts at $(first_time "E/$f"), not 3e-08"
done
grep -qx "output_dir = .*/E" E/scene.txt || fail "a snapshot alone: E/scene.txt has $(grep output_dir E/scene.txt)"
cp -r A F
rm F/regions.csv
expect 0 "restarted at 30 ns" -- --restart F/snapshot_00001.h5 --force --quiet --set end_time=50ns
[ "$(first_time F/regions.csv)" = "3e-08" ] || fail "regions.csv deleted: it starts at $(first_time F/regions.csv)"
[ "$(first_time F/conservation.csv)" = "0" ] || fail "regions.csv deleted: conservation.csv lost its earlier rows"

# 6. What is not a regular file is refused before it is opened (a FIFO would block open() for
# ever), and a signal during set-up ends the program at once.
mkfifo fifo.scene
expect 2 "fifo.scene: cannot open the scene file: it is a FIFO" -- fifo.scene --check
expect 2 "it is a directory" -- A --check
# Its set-up (1468 voids, 246 k points, the first snapshot) takes ~0.6 s on a quiet machine; the
# signal lands in it or, on a busy machine, wherever it lands: either way the program must end.
printf 'porosity = 1.3\nvoid_radius = 6 um\nwidth = 0.6 mm\ncell_size = 3 um\ntarget_height = 0.6 mm\n' > slow.scene
printf 'flyer_height = 0.6 mm\nend_time = 10 us\noutput_dir = slow\n' >> slow.scene
timeout 120 "$bin" slow.scene --quiet >slow.out 2>&1 &
pid=$!
sleep 0.2
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 143 ] || fail "SIGTERM during set-up: exit $rc (124: it did not end), expected 143: $(cat slow.out)"

# 7. A 3D column needs the stencil's cells of depth (four with the default bspline2_domain), as of width.
expect 2 "key 'depth': must be at least 4 cells" -- "$data/tiny_porous_3d.scene" --check --set depth=10um --set cell_size=10um

# 8. 3D probes have z columns, and a point probe must lie in the material.
expect 0 "steps: " -- "$data/tiny_porous_3d.scene" --quiet --set end_time=5ns --set output_dir=G --set probe.s=surface
head -n 1 G/probes.csv | grep -qx "time,probe,count,x,y,z,velocity_x,velocity_y,velocity_z,pressure,density,temperature" ||
  fail "3D probes.csv header: $(head -n 1 G/probes.csv)"
[ "$(sed -n 2p G/probes.csv | tr , '\n' | wc -l)" -eq 12 ] || fail "3D probes.csv rows lack the z columns"
expect 2 "key 'probe.far': .*outside.*bare numbers are metres" -- tiny.scene --check --set "probe.far=point 1 2"
# The centre of the largest void of run A: no point lies within a cell of it.
void=$(awk -F, 'NR > 1 && $4 > r { r = $4; x = $2; y = $3 } END { printf "%.9g %.9g", x, y }' A/voids.csv)
expect 2 "key 'probe.hole': no material point lies within a cell" -- tiny.scene --check --set "probe.hole=point $void"

# 9. --check's step count includes the conduction limit, and the run takes that many steps.
cond=(--set heat_conduction=on --set "thermal_conductivity=2e7 W/(m K)" --set end_time=0.2ns)
check=$("$bin" tiny.scene --check "${cond[@]}" 2>&1)
echo "$check" | grep -q "set by heat conduction" || fail "--check does not name the conduction limit: $check"
predicted=$(echo "$check" | sed -n 's/.*at least \([0-9]*\) steps.*/\1/p')
ran=$("$bin" tiny.scene --quiet "${cond[@]}" --set output_dir=H 2>&1 | sed -n 's/^steps: \([0-9]*\) .*/\1/p')
[ -n "$predicted" ] && [ -n "$ran" ] && [ "$ran" -ge "$predicted" ] && [ "$ran" -le $((predicted + 2)) ] ||
  fail "conduction-limited run: --check predicted ${predicted:-?} steps, the run took ${ran:-?}"
expect 0 "set by sound" -- tiny.scene --check
# A solid scene's estimate from its shocked state (sound and viscous speeds) is a little short of
# the steps the run takes (the quadratic term and the points' noise add to its signal): measured
# 634 for 678 (solid_plate.scene), 792 for 838 (the speed scene), here within 15 %.
solid=(--set porosity=1 --set end_time=60ns)
check=$("$bin" tiny.scene --check "${solid[@]}" 2>&1)
about=$(echo "$check" | sed -n 's/.*, about \([0-9]*\) at the step of the shocked state.*/\1/p')
ran=$("$bin" tiny.scene --quiet "${solid[@]}" --set output_dir=S 2>&1 | sed -n 's/^steps: \([0-9]*\) .*/\1/p')
[ -n "$about" ] && [ -n "$ran" ] && [ "$ran" -ge "$about" ] && [ "$((ran * 100))" -le "$((about * 115))" ] ||
  fail "solid run: --check estimated ${about:-?} steps once shocked, the run took ${ran:-?}: $check"

# 11. Every error of a file, in line order, each with its line and key.
printf 'velocty = 1000 m/s\nwidth = 3 furlongs\nporosty = 1.1\n' > errors.scene
out=$("$bin" errors.scene --check 2>&1)
[ "$(echo "$out" | grep -c "^mpmshock: error: errors.scene:")" -eq 3 ] || fail "not every error reported: $out"
[ "$(echo "$out" | sed -n 's/^mpmshock: error: errors.scene:\([0-9]\):.*/\1/p' | tr -d '\n')" = "123" ] ||
  fail "errors not in line order: $out"

# 13. The Greek mu reads as the micro sign, and any Unicode space as a space.
printf 'width = 200 \xce\xbcm\nvelocity = 1000\xc2\xa0m/s\ncell_size = 10\xe2\x80\x89\xc2\xb5m\n' > look_alike.scene
expect 0 "bodies \(width 0.2 mm" -- look_alike.scene --check

# 14. The system's reason for a file that cannot be read, and what a key name may hold.
expect 2 "missing.scene: cannot open the scene file: No such file or directory" -- missing.scene --check
ln -s nowhere.scene dangling.scene
expect 2 "dangling.scene: cannot open the scene file: it is a symbolic link to a file that does not exist" -- dangling.scene --check
ln -s loop_b.scene loop_a.scene
ln -s loop_a.scene loop_b.scene
expect 2 "loop_a.scene: cannot open the scene file: .*a loop of symbolic links" -- loop_a.scene --check
printf 'probe.\xc3\xb6 = surface\n' > key.scene
expect 2 "is not a key name \(a key name is ASCII letters, digits" -- key.scene --check

# 15. Probes that would write a large probes.csv are warned about.
{ cat tiny.scene; for i in $(seq 1 3000); do echo "probe.p$i = surface"; done; } > many_probes.scene
expect 0 "warning: probes: 3001 probes every step write at least [0-9]+ MB to probes.csv" -- many_probes.scene --check --set end_time=150ns
out=$("$bin" tiny.scene --check 2>&1)
echo "$out" | grep -q "warning: probes" && fail "one probe warned about: $out"

if [ "$failures" -eq 0 ]; then echo "all checks passed"; else echo "$failures check(s) failed"; exit 1; fi
