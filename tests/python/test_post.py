"""The post-processing tools on a tiny run: every mpmshock-plot kind makes a real image, bad input
exits non-zero with a message, and the reader gives back what the simulator wrote, down to the
region averages recomputed from the last snapshot.

    python3 -m pytest tests/python [--mpmshock BUILD/src/mpmshock]
"""

import contextlib
import csv
import io
import shutil
import subprocess
import sys

import h5py
import numpy as np

from conftest import SCRIPTS, simulate
from mpmshock_post import PostError, reader
from mpmshock_post.compare import plot_compare
from mpmshock_post.cli import build_parser
from mpmshock_post.labels import run_labels
from mpmshock_post.stats import moments
from mpmshock_post.timeseries import plot_means
from mpmshock_post.units import parse_time

PLOT = SCRIPTS / "mpmshock-plot"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
KINDS = ("timeseries", "std", "dissipation", "field", "hist", "compare")


def check(condition, message):
    assert condition, message


def plot(*args, interpreter=True):
    command = ([sys.executable] if interpreter else []) + [str(PLOT)] + [str(a) for a in args]
    return subprocess.run(command, capture_output=True, text=True)


def expect_image(args, path, magic):
    """mpmshock-plot ARGS exits 0 and writes PATH, starting with MAGIC and bigger than 1 kB."""
    done = plot(*args)
    check(done.returncode == 0, f"mpmshock-plot {' '.join(map(str, args))}: exit {done.returncode}\n{done.stderr}")
    check(path.is_file(), f"mpmshock-plot {' '.join(map(str, args))}: no {path}; stdout: {done.stdout}")
    data = path.read_bytes()
    check(data.startswith(magic), f"{path} does not start with {magic!r}")
    check(len(data) > 1024, f"{path} has only {len(data)} bytes")
    return done


def expect_error(args, pattern):
    """mpmshock-plot ARGS exits non-zero with PATTERN in a message and no traceback."""
    done = plot(*args)
    check(done.returncode != 0, f"mpmshock-plot {' '.join(map(str, args))}: exit 0, expected an error")
    check(pattern in done.stderr, f"mpmshock-plot {' '.join(map(str, args))}: stderr lacks '{pattern}': {done.stderr}")
    check("Traceback" not in done.stderr, f"mpmshock-plot {' '.join(map(str, args))}: traceback:\n{done.stderr}")


# --- the command line -------------------------------------------------------------------------------

def test_help(ctx):
    done = plot("--help", interpreter=False)  # through the shebang: checks the executable bit too
    check(done.returncode == 0, f"mpmshock-plot --help: exit {done.returncode}: {done.stderr}")
    for kind in KINDS:
        check(kind in done.stdout, f"mpmshock-plot --help does not list '{kind}'")
        out = io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
            build_parser().parse_args([kind, "--help"])
        check("usage: mpmshock-plot " + kind in out.getvalue(), f"mpmshock-plot {kind} --help: {out.getvalue()}")


def test_series_kinds(ctx):
    for kind in ("timeseries", "std", "dissipation"):
        out = ctx.tmp / f"{kind}.png"
        expect_image([kind, ctx.run, "--regions", "B800,B100,T800", "-o", out], out, PNG_MAGIC)


def test_default_output_name(ctx):
    done = expect_image(["timeseries", ctx.run], ctx.run / "timeseries.png", PNG_MAGIC)
    check(str(ctx.run / "timeseries.png") in done.stdout, f"the written path is not printed: {done.stdout}")


def test_field(ctx):
    out = ctx.tmp / "field.png"
    expect_image(["field", ctx.run, "--time", "60ns", "--color", "pressure", "--arrows",
                  "--window", "0,200,-100,200", "-o", out], out, PNG_MAGIC)
    out = ctx.tmp / "field_target.png"
    expect_image(["field", ctx.run, "--snapshot", "0", "--body", "target", "--color", "temperature",
                  "-o", out], out, PNG_MAGIC)


def test_hist(ctx):
    out = ctx.tmp / "hist.png"
    done = expect_image(["hist", ctx.run, "--region", "B800", "--times", "30ns,60ns", "-o", out], out, PNG_MAGIC)
    check("excess kurtosis" in done.stdout.lower(), f"hist does not say which kurtosis: {done.stdout}")
    check(sum(line.split()[1] == "density" for line in done.stdout.splitlines()[2:] if line.split()) == 2,
          f"hist prints no density row per time:\n{done.stdout}")


def test_compare(ctx):
    out = ctx.tmp / "compare.png"
    expect_image(["compare", ctx.run, ctx.run_fast, "--quantity", "density,temperature", "--regions", "B800",
                  "-o", out], out, PNG_MAGIC)
    labels = run_labels([reader.Run(ctx.run), reader.Run(ctx.run_fast)])
    check(labels == ["$v$=1000 m/s", "$v$=1500 m/s"], f"compare legends should name only the velocity: {labels}")


def test_pdf_and_svg(ctx):
    out = ctx.tmp / "series.pdf"
    expect_image(["dissipation", ctx.run, "--format", "pdf", "-o", out], out, b"%PDF")
    out = ctx.tmp / "field.svg"
    expect_image(["field", ctx.run, "-o", out], out, b"<?xml")
    check(b"<svg" in out.read_bytes()[:2000], f"{out} is not SVG")


def panel_notes(fig):
    """The notes written on the panels that have no curve, panel by panel."""
    return [text.get_text() for ax in fig.axes for text in ax.texts]


def test_empty_panels_say_why(ctx, mpmshock, tiny_scene):
    """A region that holds no material (count 0, NaN means) is said to be empty, not 'thermal
    model off'; 'thermal model off' is for runs with thermal = off."""
    empty = ctx.tmp / "empty_region"
    simulate(mpmshock, tiny_scene, empty, "region.EMPTY=bottom 5 mm 1 mm", "region.B100=bottom 100 um 100 um")
    regions = reader.Run(empty).regions()
    check(not regions["EMPTY"]["count"].any() and np.isnan(regions["EMPTY"]["temperature_mean"]).all(),
          "the region above the target should hold no points")
    notes = panel_notes(plot_means(reader.Run(empty), regions=["EMPTY"]))
    check(notes == ["no material in region EMPTY"] * 5, f"panels of the empty region say {notes}")
    check(panel_notes(plot_means(reader.Run(empty), regions=["EMPTY", "B100"])) == [], "B100 has curves")
    notes = panel_notes(plot_compare([reader.Run(empty)] * 2, quantities=("temperature",), regions=["EMPTY"]))
    check(notes == ["no material in region EMPTY"], f"compare of the empty region says {notes}")
    out = ctx.tmp / "empty_region.png"
    expect_image(["timeseries", empty, "--regions", "EMPTY", "-o", out], out, PNG_MAGIC)

    cold = ctx.tmp / "thermal_off"
    simulate(mpmshock, tiny_scene, cold, "thermal=off")
    check(panel_notes(plot_means(reader.Run(cold), regions=["B800"])) == ["thermal model off"],
          "a thermal = off run should say so on its temperature panel only")
    check(panel_notes(plot_means(reader.Run(ctx.run), trange=(1.0, 2.0))) == ["no samples in this time range"] * 5,
          "a time range past the run should say so")


def test_errors(ctx):
    expect_error(["timeseries", ctx.run, "--regions", "B900"], "no region 'B900'")
    expect_error(["hist", ctx.run, "--region", "B900"], "no region 'B900'")
    expect_error(["std", ctx.tmp / "no_such_run"], "not found")
    expect_error(["field", ctx.run, "--time", "45ns"], "no snapshot near t = 45 ns")
    expect_error(["field", ctx.run, "--time", "45"], "with a unit")


# --- the reader -------------------------------------------------------------------------------------

def test_regions_equal_csv(ctx):
    with open(ctx.run / "regions.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    series = reader.Run(ctx.run).regions()
    check(sorted(series) == sorted({row["region"] for row in rows}), f"regions {list(series)} differ from the CSV")
    for name, columns in series.items():
        own = [row for row in rows if row["region"] == name]
        for column, values in columns.items():
            written = np.array([row[column] for row in own], dtype=str if column == "region" else float)
            same = np.array_equal(values, written, equal_nan=column != "region")
            check(same, f"regions()['{name}']['{column}'] differs from regions.csv")


def _scale(stats, column):
    """The size of the values a column averages: a mean of velocities that cancel to 1e-14 m/s is
    only as exact as the velocities themselves, so compare it on the scale of mean and deviation."""
    for suffix in ("_mean", "_std"):
        if column.endswith(suffix) and column.replace(suffix, "_std") in stats:
            base = column[: -len(suffix)]
            return max(abs(stats[base + "_mean"]), stats[base + "_std"])
    return abs(stats[column])


def test_region_stats_match_csv(ctx):
    run = reader.Run(ctx.run)
    snapshot = run.snapshot()
    check(snapshot.time > 0, "the last snapshot is at t = 0: nothing to compare")
    worst = 0.0
    for name, columns in run.regions().items():
        row = np.flatnonzero(np.isclose(columns["time"], snapshot.time, rtol=1e-9, atol=0))
        check(row.size == 1, f"regions.csv has no single {name} row at the last snapshot's t = {snapshot.time} s")
        stats = reader.region_stats(snapshot, name)
        check(stats["count"] == columns["count"][row[0]],
              f"{name}: {stats['count']} points from the snapshot, {columns['count'][row[0]]} in regions.csv")
        check(stats["count"] > 0, f"{name} is empty at t = {snapshot.time} s: the comparison would be void")
        for column, value in stats.items():
            written = columns[column][row[0]]
            scale = _scale(stats, column)
            error = abs(value - written) / scale if scale > 0 else abs(value - written)
            check(error <= 1e-9, f"{name} {column} at t = {snapshot.time} s: snapshot gives {value!r}, "
                  f"regions.csv {written!r} (relative {error:.3g})")
            worst = max(worst, error)
    print(f"    largest relative difference snapshot vs regions.csv: {worst:.2g}")
    # A hand-written spec in um selects exactly the points of the scene's region in m.
    check(np.array_equal(reader.region_points(snapshot, "bottom 100 um 800um"), reader.region_points(snapshot, "B800")),
          "'bottom 100 um 800um' selects other points than B800 = bottom 1e-04 m 8e-04 m")


def test_summary_consistent_with_snapshots(ctx):
    run = reader.Run(ctx.run)
    summary = run.summary()
    first, last = run.snapshot(0), run.snapshot()
    for snapshot in (first, last):
        rows = len(snapshot["id"])
        check(snapshot.particle_count == rows,
              f"{snapshot.path}: particle_count {snapshot.particle_count}, {rows} rows")
        # symmetry = on simulates the target alone; the snapshots hold the whole impact
        whole = summary["material_points"] * (2 if summary["symmetry"] else 1)
        check(whole == rows, f"summary material_points {summary['material_points']} (symmetry "
              f"{summary['symmetry']}), {snapshot.path} has {rows} rows")
    # Porosity = solid area of both plates / area the points occupy at t = 0 (each point one lattice cell).
    scene = run.scene
    plates = scene["width"] * (scene["target_height"] + scene["flyer_height"])
    porosity = plates / first["volume"].sum()
    check(abs(porosity - summary["porosity"]) <= 1e-6 * porosity,
          f"porosity {porosity:.9g} from the t = 0 volumes, {summary['porosity']} in summary.json")
    check(first.scene == scene, "the snapshot's scene attribute differs from scene.txt")
    check(len(run.voids()["radius"]) == summary["voids"], "voids.csv rows differ from summary voids")
    conservation = run.conservation()
    with open(ctx.run / "conservation.csv", newline="") as f:
        header = next(csv.reader(f))
    check(list(conservation) == header, f"conservation() columns {list(conservation)} differ from {header}")


def test_reader_ignores_what_it_does_not_know(ctx):
    """Newer files may carry /restart or /grid groups and extra datasets, lack an optional dataset,
    and share the directory with .xdmf and .tmp files."""
    run_dir = ctx.tmp / "future_run"
    run_dir.mkdir()
    shutil.copy(ctx.run / "scene.txt", run_dir)
    snapshot = run_dir / "snapshot_00000.h5"
    shutil.copy(reader.Run(ctx.run).snapshot().path, snapshot)
    with h5py.File(snapshot, "a") as f:
        del f["particles/temperature"]
        f.require_group("restart").create_dataset("future_state", data=np.arange(3))
        f.require_group("future_group").create_dataset("mass", data=np.zeros((4, 4)))
        f["particles"].create_dataset("future_field", data=np.zeros(len(f["particles/id"])))
    (run_dir / "snapshot_00001.tmp").write_bytes(b"half-written")
    (run_dir / "snapshot_00001.h5.tmp").write_bytes(b"half-written")
    (run_dir / "snapshots.xdmf").write_text("<Xdmf/>")
    run = reader.Run(run_dir)
    check([info.index for info in run.snapshots()] == [0], f"snapshots(): {run.snapshots()}")
    stats = reader.region_stats(run.snapshot(), "B800")
    check(np.isnan(stats["temperature_mean"]) and stats["density_mean"] > 0,
          f"region_stats without a temperature dataset: {stats}")
    check("damage" in run.snapshot().fields, "an unknown dataset is not listed")
    try:
        run.snapshot()["temperature"]
        check(False, "reading a missing dataset did not raise")
    except PostError as e:
        check("temperature" in str(e), f"unclear message for a missing dataset: {e}")


def test_units_and_moments(ctx):
    check(parse_time("1200ns") == 1.2e-6 and parse_time("1.2us") == 1.2e-6 and parse_time("1.2e-6s") == 1.2e-6,
          "parse_time reads ns/us/s wrong")
    # A two-valued distribution +-1: skewness 0, kurtosis 1, excess kurtosis -2.
    mean, std, skewness, kurtosis = moments(np.array([-1.0, 1.0] * 50))
    check((mean, std, skewness, kurtosis) == (0.0, 1.0, 0.0, -2.0), f"moments(+-1) = {mean, std, skewness, kurtosis}")
    rng = np.random.default_rng(1)
    _, _, skewness, kurtosis = moments(rng.exponential(size=200_000))  # skewness 2, excess kurtosis 6
    check(abs(skewness - 2) < 0.1 and abs(kurtosis - 6) < 0.6, f"exponential: S={skewness}, K={kurtosis}")


def test_torn_last_row(ctx):
    """A run killed while writing regions.csv leaves half a row: it is left out with a note, and
    the plot is made from the complete rows."""
    torn = ctx.tmp / "torn"
    shutil.copytree(ctx.run, torn)
    text = (torn / "regions.csv").read_text()
    b800 = next(line for line in text.splitlines() if ",B800," in line)
    (torn / "regions.csv").write_text(text + b800[:37])  # a B800 row cut in its 4th number
    out = ctx.tmp / "torn.png"
    done = expect_image(["timeseries", torn, "-o", out], out, PNG_MAGIC)
    check("last row is incomplete" in done.stderr, f"no note about the torn row: {done.stderr}")
    check("Traceback" not in done.stderr, done.stderr)
    rows = reader.Run(torn).regions()["B800"]["time"]
    check(len(rows) == len(reader.Run(ctx.run).regions()["B800"]["time"]), "the torn row was kept")


def test_case_label_names_materials_frame_and_window():
    """A scene of named materials in the laboratory frame with a window says so in its label; the
    keys that follow another (flyer_velocity = velocity, ...) do not make legends differ."""
    from mpmshock_post import labels
    scene = {"porosity": 1.1, "void_radius": 25e-6, "velocity": 1000.0, "flyer_velocity": 1000.0,
             "target_velocity": 0.0, "flyer_material": "copper", "target_material": "aluminium",
             "window_height": 5e-4, "window_material": "lif"}
    label = labels.case_label(scene, void_count=3)
    assert "copper on aluminium" in label and "target at rest" in label and "lif window" in label, label
    plain = {"porosity": 1.1, "void_radius": 25e-6, "velocity": 1000.0, "flyer_velocity": 1000.0,
             "target_velocity": 1000.0, "flyer_material": "scene", "target_material": "scene", "window_height": 0.0}
    assert labels.case_label(plain, void_count=3) == r"$\delta$=1.1, $r$=25 µm, $v$=1000 m/s"
