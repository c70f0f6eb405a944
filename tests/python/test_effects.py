"""Probes (probes.csv) and spall (damage): what the simulator writes, a restart that reproduces it,
and the reader and `mpmshock-plot probe` on top.

    /usr/bin/python3 -m pytest tests/python/test_effects.py [--mpmshock BUILD/src/mpmshock]

The case is a hydrodynamic (plasticity off) symmetric plate impact: a 0.4 mm flyer on a 1.2 mm
target, each body at 150 m/s toward y = 0, in a 40 um column (2560 points, under a second). The
shock (5551 m/s) reaches the target's free surface at about 216 ns, which then moves at +150 m/s;
the releases from the flyer's back and from the free surface meet 0.4 mm below the free surface,
at y = 0.8 mm, near 300 ns, where the tension reaches spall_strength (1.2 GPa). With spall on the
material there opens, holding the strength, and separates; the free surface is pulled back by
2 sigma_s / (rho0 c0) = 166 m/s (to about -15 m/s) before the spall signal turns it up again; with
spall off the target holds together and its surface is pulled back to about -150 m/s. Four runs (one of them a restart) and seven mpmshock-plot calls: about 8 s on 2
cores.
"""

import argparse
import contextlib
import csv
import io
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import SCRIPTS, simulate
from mpmshock_post import PostError, reader
from mpmshock_post.cli import build_parser

PLOT = SCRIPTS / "mpmshock-plot"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
HEADER = "time,probe,count,x,y,velocity_x,velocity_y,pressure,density,temperature"
VELOCITY = 150.0  # m/s
PROBE_INTERVAL = 2e-9  # s
SCENE = """\
velocity = 150 m/s
porosity = 1
flyer_mirror = off
width = 40 um
target_height = 1.2 mm
flyer_height = 0.4 mm
cell_size = 10 um
end_time = 420 ns
plasticity = off
spall = on
snapshot_interval = 100 ns
probe.free_surface = surface
probe.spall_plane = point 20 um 0.8 mm
probe_interval = 2 ns
"""
RESTART_SNAPSHOT = "snapshot_00003.h5"  # 300 ns: some points have failed, more fail after it


def check(condition, message):
    assert condition, message


@pytest.fixture(scope="module")
def runs(mpmshock, tmp_path_factory):
    """spall: the scene; no_spall: spall off, a probe row every step; no_probes: no probe keys (and
    a shorter run); restarted: a copy of spall restarted from its 300 ns snapshot with --force."""
    tmp = tmp_path_factory.mktemp("effects")
    scene = tmp / "spall.scene"
    scene.write_text(SCENE)
    bare = tmp / "bare.scene"
    bare.write_text("".join(line + "\n" for line in SCENE.splitlines() if not line.startswith("probe")))
    r = argparse.Namespace(tmp=tmp, spall=tmp / "spall", no_spall=tmp / "no_spall", no_probes=tmp / "no_probes",
                           restarted=tmp / "restarted")
    simulate(mpmshock, str(scene), r.spall)
    simulate(mpmshock, str(scene), r.no_spall, "spall=off", "probe_interval=0")
    simulate(mpmshock, str(bare), r.no_probes, "end_time=60ns", "snapshot_interval=30ns")

    shutil.copytree(r.spall, r.restarted)
    command = [mpmshock, "--restart", str(r.restarted / RESTART_SNAPSHOT), "--force", "--quiet"]
    done = subprocess.run(command, capture_output=True, text=True, env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))
    if done.returncode != 0:
        pytest.fail(f"{' '.join(command)} exited {done.returncode}:\n{done.stdout}{done.stderr}")
    r.restart_stdout = done.stdout
    return r


def plot(*args):
    return subprocess.run([sys.executable, str(PLOT)] + [str(a) for a in args], capture_output=True, text=True)


def expect_png(args, path):
    done = plot(*args)
    check(done.returncode == 0, f"mpmshock-plot {' '.join(map(str, args))}: exit {done.returncode}\n{done.stderr}")
    check(path.is_file(), f"mpmshock-plot {' '.join(map(str, args))}: no {path}; stdout: {done.stdout}")
    data = path.read_bytes()
    check(data.startswith(PNG_MAGIC) and len(data) > 1024, f"{path} is not a PNG image of some size")
    return done


def surface_arrival(surface):
    """Time of the free surface's first positive u_y: half-way up its jump from -v to +v."""
    up = np.flatnonzero(surface["velocity_y"] > 0)
    check(up.size > 0, f"the free surface never moves up: u_y ends at {surface['velocity_y'][-1]} m/s")
    return surface["time"][up[0]]


# --- probes.csv -------------------------------------------------------------------------------------

def test_probes_csv_rows(runs):
    for run_dir in (runs.spall, runs.no_spall):
        with open(run_dir / "probes.csv") as f:
            check(f.readline().rstrip("\n") == HEADER, f"{run_dir}/probes.csv: header is not {HEADER}")
    # probe_interval 2 ns: a row per probe at the first step at or after each multiple of 2 ns.
    end_time = reader.Run(runs.spall).scene["end_time"]
    probes = reader.Run(runs.spall).probes()
    check(list(probes) == ["free_surface", "spall_plane"], f"probes in file order: {list(probes)}")
    expected = int(round(end_time / PROBE_INTERVAL)) + 1
    for name, columns in probes.items():
        times = columns["time"]
        check(len(times) == expected,
              f"{name}: {len(times)} rows at probe_interval 2 ns to 420 ns, expected {expected}")
        slot = np.floor(times / PROBE_INTERVAL * (1 + 1e-9))
        check(np.array_equal(slot, np.arange(expected)), f"{name}: rows are not one per 2 ns interval: {times[:6]} ...")
        check(times[-1] == end_time, f"{name}: last row at {times[-1]} s, not at the end {end_time} s")
    check(np.array_equal(probes["free_surface"]["time"], probes["spall_plane"]["time"]),
          "the probes' rows are at different times")
    # probe_interval 0: a row per probe at t = 0 and after every step.
    steps = reader.Run(runs.no_spall).summary()["steps"]
    for name, columns in reader.Run(runs.no_spall).probes().items():
        check(len(columns["time"]) == steps + 1, f"{name}: {len(columns['time'])} rows for {steps} steps (+ t = 0)")
        check(np.all(np.diff(columns["time"]) > 0), f"{name}: times do not increase step by step")


def test_probe_points(runs):
    run = reader.Run(runs.spall)
    scene, first = run.scene, run.probes()
    spacing = scene["cell_size"] / scene["particles_per_cell"]
    # The surface probe: the target's top cell of points, particles_per_cell rows of width/spacing.
    top_cell = round(scene["width"] / spacing) * int(scene["particles_per_cell"])
    surface = first["free_surface"]
    check(np.all(surface["count"] == top_cell), f"free_surface follows {surface['count'][0]} points, expected the "
          f"{top_cell} of the target's top cell")
    y0 = scene["target_height"] - 0.5 * scene["cell_size"]
    check(abs(surface["y"][0] - y0) < 1e-3 * spacing, f"free_surface starts at y = {surface['y'][0]} m, the middle "
          f"of the top cell is {y0} m")
    # The point probe: the one point nearest 20 um, 0.8 mm at t = 0 (periodic in x; the first on a tie).
    snapshot = run.snapshot(0)
    x, y = snapshot["position"].T
    dx = np.abs(x - 20e-6)
    dx = np.minimum(dx, scene["width"] - dx)
    nearest = int(np.argmin(dx * dx + (y - 0.8e-3) * (y - 0.8e-3)))
    point = first["spall_plane"]
    check(np.all(point["count"] == 1), f"spall_plane follows {point['count'][0]} points, not one")
    check((point["x"][0], point["y"][0]) == (float(f"{x[nearest]:.10g}"), float(f"{y[nearest]:.10g}")),
          f"spall_plane starts at {point['x'][0]}, {point['y'][0]} m, the nearest point is at "
          f"{x[nearest]}, {y[nearest]} m")
    # Every row is the mean over the probe's points, the same points throughout: the rows at the
    # snapshot times are the snapshots' means (summed in id order and written to 10 digits, as the
    # simulator does).
    top = np.flatnonzero((snapshot["body"] == 1) & (y > y.max() - scene["cell_size"] * (1 - 1e-9)))
    members = {"free_surface": top, "spall_plane": np.array([nearest])}
    for info in run.snapshots():
        snap = run.snapshot(info.index)
        for name, points in members.items():
            row = np.flatnonzero(first[name]["time"] == snap.time)
            check(row.size == 1, f"{name}: no single row at the snapshot time {snap.time} s")
            for column, values in (("x", snap["position"][:, 0]), ("y", snap["position"][:, 1]),
                                   ("velocity_x", snap["velocity"][:, 0]), ("velocity_y", snap["velocity"][:, 1]),
                                   ("pressure", snap["pressure"]), ("density", snap["density"]),
                                   ("temperature", snap["temperature"])):
                mean = float(f"{sum(values[points].tolist()) / len(points):.10g}")
                written = first[name][column][row[0]]
                check(mean == written, f"{name} {column} at t = {snap.time} s: {written} in probes.csv, "
                      f"{mean} from the snapshot")


def test_free_surface_velocity(runs):
    scene = reader.Run(runs.spall).scene
    spall, no_spall = (reader.Run(d).probes()["free_surface"] for d in (runs.spall, runs.no_spall))
    for name, surface in (("spall", spall), ("no_spall", no_spall)):
        u, t = surface["velocity_y"], surface["time"]
        check(u[0] == -VELOCITY, f"{name}: the free surface starts at {u[0]} m/s, not -{VELOCITY}")
        arrival = surface_arrival(surface)
        expected = scene["target_height"] / (scene["sound_speed"] + scene["hugoniot_slope"] * VELOCITY)
        check(abs(arrival - expected) < 0.03 * expected,
              f"{name}: the shock reaches the free surface at {arrival * 1e9:.1f} ns, U_s says {expected * 1e9:.1f} ns")
        plateau = np.median(u[(t >= arrival + 10e-9) & (t <= arrival + 100e-9)])
        check(abs(plateau - VELOCITY) < 0.15 * VELOCITY,
              f"{name}: free surface at {plateau:.1f} m/s after the shock reflects, expected about +{VELOCITY}")
    # The spall signal: with spall the surface is pulled back by 2 sigma_s / (rho0 c0), the acoustic
    # relation (test_spall checks it to 0.1 GPa in its own run), without it all the way.
    late = spall["time"] > surface_arrival(spall) + 10e-9
    plateau = np.median(spall["velocity_y"][late & (spall["time"] < surface_arrival(spall) + 100e-9)])
    strength = scene["density"] * scene["sound_speed"] * (plateau - spall["velocity_y"][late].min()) / 2
    check(abs(strength - scene["spall_strength"]) < 0.1e9,
          f"spall on: the pullback gives {strength / 1e9:.3f} GPa, spall_strength is "
          f"{scene['spall_strength'] / 1e9:.3f} GPa")
    late = no_spall["time"] > surface_arrival(no_spall) + 10e-9
    check(no_spall["velocity_y"][late].min() < -0.5 * VELOCITY,
          f"spall off: the free surface is pulled back only to {no_spall['velocity_y'][late].min():.1f} m/s")


# --- damage -----------------------------------------------------------------------------------------

def test_damage(runs):
    spall = reader.Run(runs.spall)
    damage = [spall.snapshot(info.index)["damage"] for info in spall.snapshots()]
    for info, values in zip(spall.snapshots(), damage):
        check(np.all((values >= 0.0) & (values <= 1.0)), f"{info.path}: damage outside [0, 1]")
        with h5py.File(info.path, "r") as f:
            check("failure_J" in f["restart"], f"{info.path}: no /restart/failure_J with spall on")
    check(not damage[0].any(), "damage at t = 0")
    check(np.any(damage[-1] == 1.0), "spall on: no point separated")
    check(all(np.all(later >= earlier) for earlier, later in zip(damage, damage[1:])), "a failed point healed")
    # The points that fail lie around the spall plane, 0.4 mm (the flyer's thickness) below the free surface.
    y0 = spall.snapshot(0)["position"][:, 1]
    failed = damage[-1] > 0
    plane = spall.scene["target_height"] - spall.scene["flyer_height"]
    check(abs(np.median(y0[failed]) - plane) < 0.1e-3, f"the failed points start around y = "
          f"{np.median(y0[failed]) * 1e3:.3f} mm, the spall plane is at {plane * 1e3:.3f} mm")
    check(np.all(spall.snapshot(0)["body"][failed] == 1), "flyer points failed")

    no_spall = reader.Run(runs.no_spall)
    for info in no_spall.snapshots():
        snapshot = reader.Snapshot(info.path)
        check("damage" in snapshot.fields, f"{info.path}: no /particles/damage with spall off")
        check(not snapshot["damage"].any(), f"{info.path}: damage with spall off")
        with h5py.File(info.path, "r") as f:
            check("failure_J" not in f["restart"], f"{info.path}: /restart/failure_J with spall off")


# --- restart ----------------------------------------------------------------------------------------

def test_restart_reproduces_outputs(runs):
    check("restarted at 300 ns" in runs.restart_stdout,
          f"the restart did not say where it began: {runs.restart_stdout}")
    for name in ("probes.csv", "regions.csv", "conservation.csv"):
        original, again = runs.spall / name, runs.restarted / name
        check(again.stat().st_mtime_ns > original.stat().st_mtime_ns, f"the restart did not rewrite {name}")
        check(original.read_bytes() == again.read_bytes(), f"{name} after a restart from {RESTART_SNAPSHOT} differs "
              "from the run's own")
    last, last_again = reader.Run(runs.spall).snapshot(), reader.Run(runs.restarted).snapshot()
    check(last.path.name == last_again.path.name, f"last snapshots {last.path.name} and {last_again.path.name}")
    for name in last.fields:
        check(np.array_equal(last[name], last_again[name], equal_nan=True),
              f"/particles/{name} of the last snapshot differs after the restart")


# --- the reader and the plots -----------------------------------------------------------------------

def test_reader_probes(runs):
    with open(runs.spall / "probes.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    for name, columns in reader.Run(runs.spall).probes().items():
        own = [row for row in rows if row["probe"] == name]
        for column, values in columns.items():
            written = np.array([row[column] for row in own], dtype=str if column == "probe" else float)
            check(np.array_equal(values, written), f"probes()['{name}']['{column}'] differs from probes.csv")
        check(columns["count"].dtype.kind == "i", "count is not an integer column")
    with pytest.raises(PostError, match="no probe.NAME keys"):
        reader.Run(runs.no_probes).probes()
    # A run stopped while it wrote a row: the row is left out with a note.
    torn = runs.tmp / "torn"
    torn.mkdir()
    shutil.copy(runs.spall / "scene.txt", torn)
    text = (runs.spall / "probes.csv").read_text()
    (torn / "probes.csv").write_text(text + text.splitlines()[-1][:30])
    check(len(reader.Run(torn).probes()["spall_plane"]["time"]) == len(rows) // 2, "the torn row was kept")


def test_probe_plot(runs):
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
        build_parser().parse_args(["probe", "--help"])
    for option in ("--probes", "--quantity", "--time-range", "--target-frame"):
        check(option in out.getvalue(), f"mpmshock-plot probe --help lacks {option}: {out.getvalue()}")
    done = expect_png(["probe", runs.spall], runs.spall / "probe_velocity_y.png")
    check(str(runs.spall / "probe_velocity_y.png") in done.stdout, f"the written path is not printed: {done.stdout}")
    out = runs.tmp / "probe_two.png"
    expect_png(["probe", runs.spall, runs.no_spall, "--probes", "free_surface", "--target-frame",
                "--time-range", "150ns,420ns", "-o", out], out)
    out = runs.tmp / "probe_pressure.png"
    expect_png(["probe", runs.spall, "--quantity", "pressure", "--probes", "spall_plane", "-o", out], out)
    out = runs.tmp / "damage.png"
    expect_png(["field", runs.spall, "--color", "damage", "--body", "target", "-o", out], out)

    done = plot("probe", runs.no_probes, "-o", runs.tmp / "none.png")
    check(done.returncode == 1, f"probe plot of a run without probes: exit {done.returncode}")
    lines = done.stderr.strip().splitlines()
    check(len(lines) == 1 and "no probe.NAME keys" in lines[0] and lines[0].startswith("mpmshock-plot probe: error:"),
          f"probe plot of a run without probes: stderr is not one error line: {done.stderr}")
    done = plot("probe", runs.spall, runs.no_probes, "-o", runs.tmp / "none.png")
    check(done.returncode == 1 and "no probe.NAME keys" in done.stderr and "Traceback" not in done.stderr,
          f"a run without probes among several: exit {done.returncode}, {done.stderr}")
    done = plot("probe", runs.spall, "--probes", "rear_surface")
    check(done.returncode == 1 and "no probe 'rear_surface'" in done.stderr and "free_surface" in done.stderr,
          f"unknown probe: exit {done.returncode}, {done.stderr}")
