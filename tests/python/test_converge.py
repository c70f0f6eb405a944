"""mpmshock-converge: the Richardson logic on sequences with a known limit, and one real study of a
solid impact whose shocked state is known exactly (mpmshock_post.hugoniot).

    /usr/bin/python3 -m pytest tests/python/test_converge.py [--mpmshock BUILD/src/mpmshock]

The end-to-end study (about 10 s on 2 cores) is a hydrodynamic (plasticity off, so the exact
Rankine-Hugoniot state applies) solid impact at 1000 m/s, 60 um wide, 1 mm bodies, 200 ns, at
cell sizes 20, 10 and 5 um. Its checked quantity is the plateau density of the paper's region B400
(bottom 100 um 400 um) over the tool's default window, the second half of the run (100-200 ns:
after the shock has left the region, before the release from the free surface returns). Measured
2026-12-06 at a solid scene's automatic cfl 0.8: 3168.87, 3172.42, 3174.05 kg/m3 against the exact
3174.52; observed order 1.12, extrapolated 3175.44, error estimate of the finest level 1.39 against
a true error 0.47 (3.0x), extrapolated error 0.92 (2026-11, at cfl 0.6 with unequally cut steps:
3171.87, 3173.44, 3173.94; order 1.65, extrapolated error 0.338).

Why not the shock arrival time: the regions are fixed in the lab and the unshocked target flows
into them at v, one row of points at a time, so a region's mean pressure steps each time a row
enters. The half-plateau crossing then carries an error of about half a point spacing over the
shock speed, whose sign depends on the phase of the rows: +0.54, -0.21, +0.09 ns in B400 and
+1.02, -0.75, +0.02 ns in a 100 um region (20, 10, 5 um cells). The tool sees the sign changes and
falls back to its conservative estimate, which the test checks still covers the true error.
"""

import csv
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import SCRIPTS
from mpmshock_post import converge, hugoniot
from mpmshock_post.converge import Estimate, Level, Result, half_rise_time, plan_levels, richardson
from mpmshock_post.scene import Scene, parse_region
from mpmshock_post.resolve import resolved_scene, scene_differences
from mpmshock_post.units import parse_length, parse_quantity, parse_time

CONVERGE = SCRIPTS / "mpmshock-converge"
HEADER = ["level", "cell_size", "points", "steps", "wall_seconds", "region", "quantity", "value",
          "extrapolated", "error_estimate", "observed_order"]

SOLID_SCENE = """\
# Solid hydrodynamic impact: the exact shocked state is the Rankine-Hugoniot one (physics-notes 3).
velocity = 1000 m/s
porosity = 1
plasticity = off
width = 80 um
target_height = 1 mm
flyer_height = 1 mm
cell_size = 20 um
end_time = 200 ns
sample_interval = 1 ns
snapshot_interval = 0
region.B400 = bottom 100 um 400 um
region.R300 = bottom 300 um 100 um
"""


# --- Richardson extrapolation and the observed order ------------------------------------------------

@pytest.mark.parametrize("p", (1.0, 1.5, 2.0, 3.0))
def test_exact_power_law_gives_its_order_and_limit(p):
    h = [2.0, 1.0, 0.5]
    f = [2.5 + 0.3 * x ** p for x in h]
    est = richardson(f, h)
    assert est.note == ""
    assert est.order == pytest.approx(p, rel=1e-9)
    assert est.extrapolated == pytest.approx(2.5, rel=1e-9)
    assert est.errors == pytest.approx([abs(v - 2.5) for v in f], rel=1e-6)


def test_closed_form_order():
    """p = log(|f2 - f1| / |f3 - f2|) / log r with r = 2."""
    f = [10.0, 7.0, 6.0]
    est = richardson(f, [4.0, 2.0, 1.0])
    assert est.order == pytest.approx(math.log(3.0) / math.log(2.0), rel=1e-12)
    assert est.extrapolated == pytest.approx(6.0 - 1.0 / (3.0 - 1.0), rel=1e-12)


def test_unequal_ratios():
    h = [1.0, 0.6, 0.25]
    f = [1.0 - 0.4 * x ** 1.7 for x in h]
    est = richardson(f, h)
    assert est.order == pytest.approx(1.7, rel=1e-8)
    assert est.extrapolated == pytest.approx(1.0, rel=1e-8)


def test_only_the_three_finest_levels_count():
    h = [40.0, 20.0, 10.0, 5.0]
    f = [123.0] + [7.0 + 0.01 * x ** 2 for x in h[1:]]   # a wild coarsest level
    est = richardson(f, h)
    assert est.order == pytest.approx(2.0, rel=1e-9)
    assert est.extrapolated == pytest.approx(7.0, rel=1e-9)


def test_noisy_first_order_sequence_is_bracketed():
    """f = f0 + C h + noise: the estimate of the finest level covers its true error (3x) in every
    draw whose order is observed, and the extrapolation helps on average."""
    rng = np.random.default_rng(7)
    h = np.array([20.0, 10.0, 5.0])
    observed, bracketed = 0, 0
    for _ in range(200):
        f = 100.0 + 0.2 * h + rng.normal(0.0, 0.02, 3)   # noise a fifth of the finest level's error
        est = richardson(f, h)
        true = abs(f[-1] - 100.0)
        if est.note == "":
            observed += 1
            bracketed += true <= 3.0 * est.errors[-1]
        else:
            assert true <= 3.0 * est.errors[-1]   # the fallback is conservative
    assert observed > 150
    assert bracketed >= 0.95 * observed


def test_non_monotone_differences_fall_back():
    est = richardson([1.0, 3.0, 2.0], [4.0, 2.0, 1.0])
    assert math.isnan(est.order)
    assert "not monotone" in est.note and est.note.startswith("fallback")
    assert est.extrapolated == 2.0
    assert est.errors == [1.0 + 2.0, 1.0 + 2.0, 2.0]   # largest successive difference, plus distance to the finest


@pytest.mark.parametrize("p", (0.2, 6.0))
def test_order_outside_range_falls_back(p):
    h = [4.0, 2.0, 1.0]
    f = [1.0 + x ** p for x in h]
    est = richardson(f, h)
    assert math.isnan(est.order) and "outside [0.5, 4]" in est.note
    assert est.extrapolated == f[-1]
    assert est.errors[-1] == pytest.approx(max(abs(f[1] - f[0]), abs(f[2] - f[1])))


def test_order_outside_range_with_unequal_ratios_falls_back():
    h = [1.0, 0.6, 0.25]
    est = richardson([1.0 + x ** 6 for x in h], h)
    assert math.isnan(est.order) and "outside" in est.note


def test_two_levels_fall_back_one_level_has_no_estimate():
    est = richardson([5.0, 4.0], [2.0, 1.0])
    assert "fewer than 3 levels" in est.note and est.errors == [2.0, 1.0]
    assert math.isnan(richardson([5.0], [1.0]).errors[0])


def test_missing_values_and_constant_sequences():
    est = richardson([1.0, math.nan, 2.0], [4.0, 2.0, 1.0])
    assert math.isnan(est.extrapolated) and est.note == "no value at every level"
    est = richardson([3.0, 3.0, 3.0], [4.0, 2.0, 1.0])
    assert est.extrapolated == 3.0 and est.errors == [0.0, 0.0, 0.0] and "no change" in est.note


def test_seed_scatter_combines_in_quadrature():
    result = Result("R", "density_mean", [1.0, 2.0], [0.0, 4.0], Estimate(2.0, math.nan, [1.0, 3.0]))
    assert result.combined_error(0) == 1.0
    assert result.combined_error(1) == 5.0


# --- levels, arrival times, scene matching ----------------------------------------------------------

def fake_resolve(base):
    """A stand-in for the simulator's resolution: the base scene with plain-number overrides."""
    def resolve(extra):
        scene = dict(base)
        for override in extra:
            key, _, value = override.partition("=")
            try:
                scene[key] = float(value)
            except ValueError:
                scene[key] = value
        return scene
    return resolve


def test_plan_levels():
    base = {"cell_size": 40e-6, "particles_per_cell": 2.0, "cfl": 0.3, "av_linear": 0.2, "av_quadratic": 2.0,
            "sample_interval": 1e-8, "update_scheme": "musl"}
    cells = plan_levels("cell_size", None, 3, fake_resolve(base))
    assert [lv.value for lv in cells] == [40e-6, 20e-6, 10e-6]
    assert cells[2].overrides == ["cell_size=1e-05"]
    ppc = plan_levels("particles_per_cell", None, 3, fake_resolve(base))
    assert [lv.overrides for lv in ppc] == [["particles_per_cell=2"], ["particles_per_cell=4"], ["particles_per_cell=8"]]
    assert [lv.measure for lv in ppc] == [0.5, 0.25, 0.125]
    assert [lv.value for lv in plan_levels("cfl", None, 2, fake_resolve(base))] == [0.3, 0.15]
    av = plan_levels("av", None, 3, fake_resolve(base))
    assert av[2].overrides == ["av_linear=0.05", "av_quadratic=0.5"] and av[2].measure == 0.25
    explicit = plan_levels("cell_size", ["3e-05", "1.5e-05"], 2, fake_resolve(base))
    assert [lv.measure for lv in explicit] == [30e-6, 15e-6]
    with pytest.raises(converge.PostError, match="--values"):
        plan_levels("sample_interval", None, 3, fake_resolve(base))
    # A word has no number to halve, and a key the scene lacks is named as such.
    with pytest.raises(converge.UsageError, match=r"update_scheme is 'musl'.*--values"):
        plan_levels("update_scheme", None, 3, fake_resolve(base))
    with pytest.raises(converge.UsageError, match="not a key"):
        plan_levels("no_such_key", None, 3, fake_resolve(base))


def test_values_with_units_are_the_simulators(study):
    """--values 20um,10um: the simulator converts the values (mpmshock --resolve), not the tool."""
    resolve = lambda extra: resolved_scene(study["scene"], extra, study["binary"])   # noqa: E731
    levels = plan_levels("cell_size", ["20um", "10 um"], 2, resolve)
    assert [lv.value for lv in levels] == [20e-6, 10e-6]
    assert [lv.overrides for lv in levels] == [["cell_size=2e-05"], ["cell_size=1e-05"]]
    with pytest.raises(converge.PostError, match="furlongs|unit"):
        plan_levels("cell_size", ["5 furlongs"], 1, resolve)


def test_half_rise_time():
    t = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    p = np.array([0.0, 0.0, 4.0, 10.0, 10.0])
    assert half_rise_time(t, p, 10.0) == pytest.approx(2.0 + (5.0 - 4.0) / 6.0)
    assert math.isnan(half_rise_time(t, p, 100.0))         # never reached
    assert math.isnan(half_rise_time(t, p + 10.0, 10.0))   # already there at the start


def test_parse_quantity_units():
    """--exact values: SI or a display unit of the package."""
    assert parse_quantity("49.9ns") == pytest.approx(49.9e-9, rel=1e-15) and parse_quantity("1.2e-6") == 1.2e-6
    assert parse_quantity("18.06 GPa") == pytest.approx(18.06e9) and parse_quantity("3.174 g/cm3") == pytest.approx(3174.0)
    assert parse_quantity("487.7 K") == 487.7 and parse_quantity("1.2 km/s") == 1200.0
    for bad in ("on", "5 furlongs", "GPa"):
        with pytest.raises(converge.PostError):
            parse_quantity(bad)


MICRO_SIGN, GREEK_MU = "\u00b5", "\u03bc"
SPACES = ("\u00a0", "\u2009", "\u202f", "\u3000")   # no-break, thin, narrow no-break, ideographic


def test_micro_sign_greek_mu_and_unicode_spaces():
    """Both micro characters for every micro unit, and any Unicode space as a space, in the units the
    tools read from a command line, as src/units.cpp reads scenes; Arabic-Indic digits and a line
    separator are refused, as the simulator refuses them."""
    for mu in (MICRO_SIGN, GREEK_MU):
        assert parse_quantity(f"50 {mu}m") == 50e-6 and parse_quantity(f"50{mu}m") == 50e-6
        assert parse_quantity(f"2 {mu}s") == 2e-6 and parse_time(f"1.2{mu}s") == 1.2e-6
        assert parse_length(f"50 {mu}m") == 50e-6
        assert parse_region(f"bottom 100 {mu}m 400{mu}m") == parse_region("bottom 100 um 400 um")
    for space in SPACES:
        assert parse_quantity(f"50{space}um") == 50e-6 and parse_quantity(f"1.2{space}km/s") == 1200.0
        assert parse_time(f"60{space}ns") == 60e-9 and parse_length(f"5{space}mm") == 5e-3
        assert parse_region(f"band{space}40{space}{GREEK_MU}m 160{space}um") == parse_region("band 40 um 160 um")
    for refused in ("\u0665\u0660 um", "5\u2028um"):
        with pytest.raises(converge.PostError):
            parse_quantity(refused)


# --- the command line and a real study --------------------------------------------------------------

def converge_cli(binary, *args):
    return subprocess.run([sys.executable, str(CONVERGE), *map(str, args)], capture_output=True, text=True,
                          env=dict(os.environ, MPMSHOCK=str(binary), OMP_WAIT_POLICY="PASSIVE"))


@pytest.fixture(scope="module")
def study(mpmshock, tmp_path_factory):
    """The solid study at 20, 10, 5 um, with the exact B400 density handed to --exact."""
    tmp = tmp_path_factory.mktemp("converge")
    scene = tmp / "solid.scene"
    scene.write_text(SOLID_SCENE)
    material = hugoniot.default_material(mpmshock)
    exact = hugoniot.solid_shock(1000.0, material)
    arrival = hugoniot.bottom_region_arrival_time(exact, 100e-6, 400e-6)
    out = tmp / "study"
    command = [scene, "--out", out, "--exact", f"B400:density_mean={exact.density!r}", f"B400:arrival_time={arrival!r}"]
    done = converge_cli(mpmshock, *command)
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(open(out / "convergence.csv")))
    return dict(out=out, scene=scene, command=command, first=done, rows=rows, exact=exact, arrival=arrival,
                binary=mpmshock)


def rows_of(study, region, quantity):
    rows = [r for r in study["rows"] if r["region"] == region and r["quantity"] == quantity]
    assert [int(r["level"]) for r in rows] == [0, 1, 2]
    return rows


def test_csv_header_and_levels(study):
    with open(study["out"] / "convergence.csv", newline="") as f:
        assert next(csv.reader(f)) == HEADER
    rows = rows_of(study, "B400", "density_mean")
    assert [float(r["cell_size"]) for r in rows] == [20e-6, 10e-6, 5e-6]
    for k, r in enumerate(rows):
        summary = json.loads((study["out"] / f"level_{k}" / "summary.json").read_text())
        assert int(r["points"]) == summary["material_points"] and int(r["steps"]) == summary["steps"]
        assert float(r["wall_seconds"]) == summary["wall_seconds"]
    assert int(rows[2]["points"]) == 16 * int(rows[0]["points"])
    quantities = {r["quantity"] for r in study["rows"] if r["region"] == "R300"}
    with open(study["out"] / "level_0" / "regions.csv", newline="") as f:
        macro = {name for name in next(csv.reader(f)) if name.startswith("macro_")}
    assert quantities == {"density_mean", "density_std", "pressure_mean", "pressure_std", "temperature_mean",
                          "temperature_std", "velocity_y_mean", "arrival_time"} | macro
    progress = [line for line in study["first"].stderr.splitlines() if line.startswith("mpmshock-converge: level")]
    assert len(progress) == 3 and "cell_size = 5e-06" in progress[2]


def test_estimate_brackets_the_exact_density(study):
    """The plateau density of B400: the order is observed, the estimate covers the true error of the
    finest level within 3x without being 10x too large, and the exact value lies within the estimate of
    the extrapolation. The extrapolation is not closer than the finest level here: the observed order
    (1.12, 2026-12-06) is not yet the asymptotic one, and Richardson with it overshoots (3175.44 for the
    exact 3174.52; finest 3174.05). Until that day the study ran at cfl 0.6, where it was closer, but
    there the 1 ns samples cut the levels' steps by different shares (0.53, 0.69, 0.83 of the cfl step),
    so that sequence refined the Courant number with the cell (see the warning test below)."""
    rows = rows_of(study, "B400", "density_mean")
    exact = study["exact"].density
    finest, estimate = float(rows[2]["value"]), float(rows[2]["error_estimate"])
    extrapolated, order = float(rows[2]["extrapolated"]), rows[2]["observed_order"]
    true = abs(finest - exact)
    assert order != "" and 0.5 <= float(order) <= 4.0
    assert true <= 3.0 * estimate, f"true error {true} kg/m3, estimate {estimate}"
    assert estimate < 10.0 * true + 1e-6 * exact, f"estimate {estimate} kg/m3 for a true error {true}"
    assert abs(extrapolated - exact) <= estimate
    assert [float(r["value"]) for r in rows] == sorted(float(r["value"]) for r in rows)   # from below, monotone


def test_arrival_time_is_measured_and_the_fallback_covers_it(study):
    rows = rows_of(study, "B400", "arrival_time")
    values = [float(r["value"]) for r in rows]
    assert all(abs(v - study["arrival"]) < 2e-9 for v in values), values
    assert abs(values[-1] - study["arrival"]) <= 3.0 * float(rows[2]["error_estimate"])


def test_markdown_and_plot(study):
    text = (study["out"] / "convergence.md").read_text()
    assert "## Region B400" in text and "## Region R300" in text and "## Against exact values" in text
    exact_rows = [line for line in text.splitlines() if line.startswith("| B400 | density_mean |")]
    assert len(exact_rows) == 1 and "| yes |" in exact_rows[0]
    assert "second half of each run" in text
    assert (study["out"] / "cost.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_rerun_reuses_finished_levels(study):
    out = study["out"]
    stamps = [(out / f"level_{k}" / "summary.json").stat().st_mtime_ns for k in range(3)]
    done = converge_cli(study["binary"], *study["command"])
    assert done.returncode == 0, done.stderr
    assert done.stderr.count("reused") == 3, done.stderr
    assert [(out / f"level_{k}" / "summary.json").stat().st_mtime_ns for k in range(3)] == stamps
    # A level whose run failed is run again; the others stay.
    summary = out / "level_0" / "summary.json"
    summary.write_text(summary.read_text().replace('"exit_code": 0', '"exit_code": 3'))
    done = converge_cli(study["binary"], *study["command"])
    assert done.returncode == 0, done.stderr
    assert done.stderr.count("reused") == 2 and "level 0 cell_size = 2e-05: " in done.stderr
    assert json.loads(summary.read_text())["exit_code"] == 0


def test_scene_txt_must_match_the_request(study):
    resolved = Scene((study["out"] / "level_1" / "scene.txt").read_text(), "scene.txt")
    request = lambda *extra: resolved_scene(study["scene"], extra, study["binary"])   # noqa: E731
    assert scene_differences(resolved, request("cell_size=1e-05")) == []
    assert any(d.startswith("velocity") for d in scene_differences(resolved, request("cell_size=1e-05", "velocity=1.5 km/s")))
    assert any(d.startswith("cell_size") for d in scene_differences(resolved, request()))
    assert any(d.startswith("region") for d in scene_differences(
        resolved, request("cell_size=1e-05", "region.B400=bottom 100 um 300 um")))
    # A run of an older simulator, whose scene.txt lacks a key, is not taken for the request.
    older = Scene("\n".join(line for line in (study["out"] / "level_1" / "scene.txt").read_text().splitlines()
                            if not line.startswith("cfl")), "scene.txt")
    assert any(d.startswith("cfl") for d in scene_differences(older, request("cell_size=1e-05")))


def test_bad_input(study, tmp_path):
    done = converge_cli(study["binary"], study["scene"], "--out", tmp_path, "--set", "cell_size=5um")
    assert done.returncode == 1 and "sets cell_size itself" in done.stderr and "Traceback" not in done.stderr
    done = converge_cli(study["binary"], tmp_path / "missing.scene", "--out", tmp_path)
    assert done.returncode == 1 and "cannot open the scene file" in done.stderr and "Traceback" not in done.stderr
    done = converge_cli(study["binary"], study["scene"], "--out", study["out"], "--exact", "B400:nonsense=1")
    assert done.returncode == 1 and "B400:nonsense" in done.stderr
    done = converge_cli(study["binary"], study["scene"], "--out", tmp_path, "--window", "5", "10ns")
    assert done.returncode == 2


def test_usage_errors_exit_2_before_anything_runs(mpmshock, tmp_path):
    """Counts below what a study needs, an --out that is not a directory and a refinement of a key
    that holds a word: argparse-style usage errors (exit 2), nothing run or written. cfl = auto is
    refined from the number the simulator resolves it to."""
    scene = tmp_path / "auto.scene"
    scene.write_text(SOLID_SCENE + "cfl = auto\n")
    out = tmp_path / "out"

    def refused(*args, says):
        done = converge_cli(mpmshock, scene, *args)
        assert done.returncode == 2, (args, done.returncode, done.stderr)
        assert says in done.stderr and "Traceback" not in done.stderr, (args, done.stderr)
        assert not out.exists() and "mpmshock-converge: level" not in done.stderr
        return done.stderr

    for count in ("0", "-1", "1"):   # --levels 0 used to run 3 levels
        refused("--out", out, "--levels", count, says="a convergence study needs at least 2 levels")
    refused("--out", out, "--levels", "two", says="'two' is not a whole number")
    refused("--out", out, "--seeds", "0", says="--seeds")
    afile = tmp_path / "notes.txt"
    afile.write_text("keep me\n")
    refused("--out", afile, says=f"--out {afile} exists and is not a directory")
    refused("--out", afile / "study", says=f"lies in {afile}, which is not a directory")
    assert afile.read_text() == "keep me\n"
    message = refused("--out", out, "--refine", "update_scheme", says="--refine update_scheme: the scene's "
                      "update_scheme is 'musl'")
    assert "give the levels with --values" in message
    resolve = lambda extra: resolved_scene(scene, extra, mpmshock)   # noqa: E731
    assert [lv.value for lv in plan_levels("cfl", None, 2, resolve)] == [resolve([])["cfl"], resolve([])["cfl"] / 2]


def test_levels_whose_steps_are_cut_unequally_are_warned_of(study, tmp_path):
    """At a solid scene's cfl 0.8 the 1 ns samples cut every level's step alike (about 0.78 of the cfl
    step: a few steps per sample), so no warning; at cfl 0.6 the 20 um level takes two half steps per
    sample and the 5 um level nearly whole ones (0.53 against 0.83), and the tool says so."""
    shares = [json.loads((study["out"] / f"level_{k}" / "summary.json").read_text())["step_share"] for k in range(3)]
    assert max(shares) <= 1.1 * min(shares), shares
    assert "warning" not in study["first"].stderr and "Warning" not in (study["out"] / "convergence.md").read_text()
    done = converge_cli(study["binary"], study["scene"], "--out", tmp_path / "cfl06", "--set", "cfl=0.6")
    assert done.returncode == 0, done.stderr
    warning = [line for line in done.stderr.splitlines() if line.startswith("mpmshock-converge: warning:")]
    assert len(warning) == 1 and "Courant numbers differ" in warning[0], done.stderr
    assert "**Warning**" in (tmp_path / "cfl06" / "convergence.md").read_text()
