"""mpmshock-converge: run a scene at successive refinements and estimate the discretisation error.

    mpmshock-converge SCENE --out DIR [--levels N] [--refine KEY] [--values V1,V2,...]
                      [--window T0 T1] [--at T] [--regions R1,R2,...] [--set key=value]...
                      [--seeds N] [--exact region:quantity=value ...]

Refinement (level 0 is the scene's own value):
    cell_size           halved each level (ratio 2)
    particles_per_cell  doubled each level (2, 4, 8: the point spacing halves, ratio 2)
    cfl                 halved each level (the time step halves)
    av                  av_linear and av_quadratic scaled together by 1/2 each level
    --values V1,V2,...  explicit values of the key, coarsest first (units allowed: 20um,10um);
                        for av they are the scale factors of both coefficients

The measure of resolution h (what goes to zero) is the value itself, 1/value for
particles_per_cell. Each run goes to DIR/level_K (DIR/level_K_seed_S with --seeds N > 1, seeds
S = the scene's seed, +1, ...), with output_dir set by --set; a run is reused when its summary.json
shows exit_code 0 and its scene.txt matches what would be run (every key, output_dir aside).

Quantities, per region: density_mean, density_std, pressure_mean, pressure_std, temperature_mean,
temperature_std, velocity_y_mean, every macro_* column of regions.csv, and arrival_time, the first
time the region's pressure_mean reaches half its plateau value (linear interpolation between
samples), for regions that see a shock: a plateau pressure of at least a tenth of the highest mean
pressure any region reaches. Each is taken as its plateau: the mean of the samples in the window
(default: the second half of the run, [t_end/2, t_end]), or, with --at T, its value at T
(linear interpolation). arrival_time uses the window's plateau pressure either way.

Error estimate: Richardson extrapolation from the three finest levels with the observed order
p (r = h1/h2 = h2/h3: p = log(|f2 - f1| / |f3 - f2|) / log r; unequal ratios: the p that solves
(f2 - f1)/(f3 - f2) = (h1^p - h2^p)/(h2^p - h3^p)); f_inf = f3 + (f3 - f2)/((h2/h3)^p - 1), and each
level's discretisation error estimate is |f_k - f_inf|. When the order cannot be observed (fewer
than 3 levels, differences that change sign, p outside [0.5, 4]) the estimate falls back to the
formal order 1 without extrapolating: f_inf is the finest value and the finest level's estimate is
the largest difference between successive levels (coarser levels add their distance to the finest);
observed_order is then empty and the .md says why.

With --seeds N > 1 each level's value is the mean over the seeds, and its sampling scatter is the
standard error of that mean (std / sqrt(N)). The csv's error_estimate is the discretisation estimate
combined in quadrature with that standard error; the .md shows the two separately.

Outputs: DIR/convergence.csv (level, cell_size, points, steps, wall_seconds, region, quantity, value,
extrapolated, error_estimate, observed_order; points and steps are the mean over seeds, wall_seconds
their sum), DIR/convergence.md (tables per region, cost per level, and with --exact the true error
of each level against the estimate) and DIR/cost.png (error estimate against wall time).
"""

import argparse
import csv
import json
import math
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import PostError, argument_type
from .reader import Run
from .scene import Scene
from .resolve import mpmshock_binary, resolved_scene, scene_differences
from .units import parse_quantity, parse_time

CSV_COLUMNS = ("level", "cell_size", "points", "steps", "wall_seconds", "region", "quantity", "value",
               "extrapolated", "error_estimate", "observed_order")
REGION_QUANTITIES = ("density_mean", "density_std", "pressure_mean", "pressure_std", "temperature_mean",
                     "temperature_std", "velocity_y_mean")
ARRIVAL = "arrival_time"
ORDER_RANGE = (0.5, 4.0)
SHOCK_FRACTION = 0.1    # a region sees a shock when its plateau pressure is this share of the highest
WITHIN_FACTOR = 3.0     # the .md's verdict: a true error within this multiple of the estimate
MIN_LEVELS = 2          # one level has no error estimate; two give the fallback, three an observed order


class UsageError(PostError):
    """A request that no run could honour (a count, a path, a refinement the scene cannot take):
    the command line reports it as argparse reports its own, with exit 2."""


# --- the refinement plan ----------------------------------------------------------------------------

@dataclass
class Level:
    """One refinement level: the refined value, the resolution measure h and the --set overrides."""

    index: int
    value: float
    measure: float
    overrides: list
    runs: list = field(default_factory=list)   # (seed, Path) of each run of the level


def _format(value):
    """A number for --set: integers without a decimal point, floats exactly (repr)."""
    return str(int(value)) if float(value).is_integer() and abs(value) < 1e15 else repr(float(value))


def _base_value(refine, key, base):
    if key not in base:
        raise UsageError(f"--refine {refine}: {key} is not a key of the resolved scene (mpmshock --keys lists them)")
    value = base[key]
    if not isinstance(value, float):
        # A word where a number was expected: there is no number to halve, so the levels must be named.
        raise UsageError(f"--refine {refine}: the scene's {key} is '{value}', not a number to refine from; "
                         f"give the levels with --values V1,V2,... (coarsest first"
                         f"{', the scale factors of av_linear and av_quadratic' if refine == 'av' else ''})")
    return value


def plan_levels(refine, values, count, resolve):
    """The levels of a study, coarsest first. `resolve(overrides)` is the resolved scene of the
    study's scene with these extra --set overrides (resolved_scene): the simulator converts the
    values given with units (--values 20um,10um) and names the base value of the refined key."""
    base = resolve([])
    if refine == "av":
        a1, a2 = (_base_value(refine, k, base) for k in ("av_linear", "av_quadratic"))
        try:
            scales = [float(v) for v in values] if values else [0.5 ** k for k in range(count)]
        except ValueError:
            raise UsageError(f"--refine av --values {','.join(values)}: give plain scale factors") from None
        return [Level(k, s, s, [f"av_linear={_format(a1 * s)}", f"av_quadratic={_format(a2 * s)}"])
                for k, s in enumerate(scales)]
    _base_value(refine, refine, base)   # the key exists and holds a number
    if values is None:
        step = {"cell_size": 0.5, "cfl": 0.5, "particles_per_cell": 2.0}.get(refine)
        if step is None:
            raise UsageError(f"--refine {refine}: give its levels with --values (known refinements: "
                             "cell_size, particles_per_cell, cfl, av)")
        texts = [_format(base[refine] * step ** k) for k in range(count)]
    else:
        texts = list(values)
    measure = (lambda v: 1.0 / v) if refine == "particles_per_cell" else (lambda v: v)
    levels = []
    for k, text in enumerate(texts):
        value = _base_value(refine, refine, resolve([f"{refine}={text}"]))
        levels.append(Level(k, value, measure(value), [f"{refine}={_format(value)}"]))
    return levels


def refined_keys(refine):
    return ("av_linear", "av_quadratic") if refine == "av" else (refine,)


# --- running or reusing ---------------------------------------------------------------------------

def run_directory(out, level, seed, seeds):
    return out / (f"level_{level.index}_seed_{seed}" if seeds > 1 else f"level_{level.index}")


def reusable(run_dir, requested):
    """True when run_dir holds a finished run (exit_code 0) of exactly the requested scene."""
    try:
        summary = json.loads((run_dir / "summary.json").read_text())
        resolved = Scene((run_dir / "scene.txt").read_text(), str(run_dir / "scene.txt"))
    except (OSError, ValueError, PostError):
        return False
    return (summary.get("exit_code") == 0 and (run_dir / "regions.csv").is_file()
            and not scene_differences(resolved, requested))


def simulate(binary, scene, overrides, run_dir):
    """Runs mpmshock into run_dir; returns the wall time, or raises PostError with its message."""
    command = [str(binary), str(scene)]
    for override in [*overrides, f"output_dir={run_dir}"]:
        command += ["--set", override]
    command += ["--quiet", "--force"]
    started = time.monotonic()
    try:
        done = subprocess.run(command, capture_output=True, text=True)
    except OSError as e:
        raise PostError(f"cannot run {binary}: {e}") from None
    if done.returncode != 0:
        tail = "\n".join((done.stderr or done.stdout).strip().splitlines()[-5:])
        raise PostError(f"{' '.join(command)} exited {done.returncode}:\n{tail}")
    return time.monotonic() - started


def run_levels(levels, args, binary, log=sys.stderr):
    """Runs (or reuses) every level and seed, one run at a time, with one line each on log."""
    first_seed = int(resolved_scene(args.scene, args.set, binary)["seed"])
    label = args.refine
    for level in levels:
        for seed in range(first_seed, first_seed + args.seeds):
            overrides = [*args.set, *level.overrides] + ([f"seed={seed}"] if args.seeds > 1 else [])
            run_dir = run_directory(args.out, level, seed, args.seeds)
            requested = resolved_scene(args.scene, [*overrides, f"output_dir={run_dir}"], binary)
            seed_text = f" seed {seed}" if args.seeds > 1 else ""
            if reusable(run_dir, requested):
                wall = json.loads((run_dir / "summary.json").read_text()).get("wall_seconds", float("nan"))
                print(f"mpmshock-converge: level {level.index} {label} = {level.value:g}{seed_text}: "
                      f"reused {run_dir} (ran in {wall:.2f} s)", file=log, flush=True)
            else:
                wall = simulate(binary, args.scene, overrides, run_dir)
                print(f"mpmshock-converge: level {level.index} {label} = {level.value:g}{seed_text}: "
                      f"{wall:.2f} s", file=log, flush=True)
            level.runs.append((seed, run_dir))


# --- measuring a run ------------------------------------------------------------------------------

def window_mask(times, window):
    t0, t1 = window
    tolerance = 1e-9 * max(abs(t1), 1e-30)
    mask = (times >= t0 - tolerance) & (times <= t1 + tolerance)
    if not mask.any():
        raise PostError(f"no sample in the window [{t0 * 1e9:g}, {t1 * 1e9:g}] ns "
                        f"(samples from {times[0] * 1e9:g} to {times[-1] * 1e9:g} ns)")
    return mask


def run_window(times, window):
    """The requested window, or the second half of the run."""
    return tuple(window) if window else (0.5 * times[-1], times[-1])


def sample(series, times, window, at):
    """Plateau mean over the window, or the value at time `at` (linear interpolation)."""
    if at is None:
        return float(np.mean(series[window_mask(times, window)]))
    if not times[0] <= at <= times[-1]:
        raise PostError(f"--at {at * 1e9:g} ns lies outside the run ({times[0] * 1e9:g} to {times[-1] * 1e9:g} ns)")
    return float(np.interp(at, times, series))


def half_rise_time(times, pressure, plateau):
    """First time the series reaches plateau / 2, interpolated between samples; NaN if it starts
    there or never does."""
    half = 0.5 * plateau
    above = np.flatnonzero(pressure >= half)
    if above.size == 0 or above[0] == 0:
        return math.nan
    i = above[0]
    return float(times[i - 1] + (half - pressure[i - 1]) / (pressure[i] - pressure[i - 1]) * (times[i] - times[i - 1]))


def measure_run(run_dir, regions, window, at):
    """{(region, quantity): value} of one run."""
    series = Run(run_dir).regions()
    missing = [name for name in regions or () if name not in series]
    if missing:
        raise PostError(f"{run_dir}/regions.csv has no region {', '.join(missing)} (it has {', '.join(series)})")
    names = regions or list(series)
    highest = max(float(np.nanmax(columns["pressure_mean"])) for columns in series.values())
    values = {}
    for name in names:
        columns, times = series[name], series[name]["time"]
        span = run_window(times, window)
        quantities = [q for q in REGION_QUANTITIES if q in columns] + sorted(c for c in columns if c.startswith("macro_"))
        for quantity in quantities:
            values[(name, quantity)] = sample(columns[quantity], times, span, at)
        plateau = float(np.mean(columns["pressure_mean"][window_mask(times, span)]))
        sees_shock = highest > 0 and plateau >= SHOCK_FRACTION * highest
        values[(name, ARRIVAL)] = half_rise_time(times, columns["pressure_mean"], plateau) if sees_shock else math.nan
    return values


# --- the error estimate -----------------------------------------------------------------------------

@dataclass
class Estimate:
    """Richardson's answer for one quantity: extrapolated value, observed order (NaN: fallback),
    the discretisation error estimate of each level, and why a fallback was taken."""

    extrapolated: float
    order: float
    errors: list
    note: str = ""


def observed_order(f, h):
    """The order p that three levels f[0..2] at resolutions h[0..2] show, or a reason why none.
    Equal ratios r: p = log(|f1 - f0| / |f2 - f1|) / log r; otherwise p solves
    (f1 - f0) / (f2 - f1) = (h0^p - h1^p) / (h1^p - h2^p) (bisection: the right side grows with p)."""
    d1, d2 = f[1] - f[0], f[2] - f[1]
    if d1 == 0.0 and d2 == 0.0:
        return math.nan, "no change between levels"
    if d1 * d2 <= 0.0:
        return math.nan, "differences change sign (not monotone)"
    ratio = d1 / d2
    r1, r2 = h[0] / h[1], h[1] / h[2]
    if abs(r1 - r2) <= 1e-9 * r2:
        p = math.log(ratio) / math.log(r2)
    else:
        def shown(q):
            return (h[0] ** q - h[1] ** q) / (h[1] ** q - h[2] ** q)
        lo, hi = ORDER_RANGE
        if not shown(lo) <= ratio <= shown(hi):
            return math.nan, f"observed order outside [{lo:g}, {hi:g}] (difference ratio {ratio:.3g})"
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if shown(mid) < ratio else (lo, mid)
        p = 0.5 * (lo + hi)
    if not ORDER_RANGE[0] <= p <= ORDER_RANGE[1]:
        return math.nan, f"observed order {p:.3g} outside [{ORDER_RANGE[0]:g}, {ORDER_RANGE[1]:g}]"
    return p, ""


def richardson(values, measures):
    """Estimate for values f_k at resolutions h_k, coarsest first (see the module docstring)."""
    f, h = list(map(float, values)), list(map(float, measures))
    if not f or any(math.isnan(v) for v in f):
        return Estimate(math.nan, math.nan, [math.nan] * len(f), "no value at every level")
    note = "fewer than 3 levels"
    if len(f) >= 3:
        p, note = observed_order(f[-3:], h[-3:])
        if not note:
            extrapolated = f[-1] + (f[-1] - f[-2]) / ((h[-2] / h[-1]) ** p - 1.0)
            return Estimate(extrapolated, p, [abs(v - extrapolated) for v in f])
    spread = max((abs(b - a) for a, b in zip(f, f[1:])), default=math.nan)
    return Estimate(f[-1], math.nan, [abs(v - f[-1]) + spread for v in f], f"fallback: {note}")


# --- collecting the study -------------------------------------------------------------------------

@dataclass
class LevelCost:
    cell_size: float
    points: float
    steps: float
    wall_seconds: float
    step_share: float = 1.0   # the least over the level's runs (summary.json; 1 for runs older than it)


@dataclass
class Result:
    """Per (region, quantity): values and sampling standard errors per level, and the estimate."""

    region: str
    quantity: str
    values: list
    standard_errors: list
    estimate: Estimate

    def combined_error(self, k):
        return math.hypot(self.estimate.errors[k], self.standard_errors[k])


def level_cost(level):
    summaries = [Run(path).summary() for _, path in level.runs]
    scene = Run(level.runs[0][1]).scene
    return LevelCost(cell_size=float(scene["cell_size"]),
                     points=float(np.mean([s["material_points"] for s in summaries])),
                     steps=float(np.mean([s["steps"] for s in summaries])),
                     wall_seconds=float(sum(s["wall_seconds"] for s in summaries)),
                     step_share=float(min(s.get("step_share", 1.0) for s in summaries)))


# Steps cut to land on output times shorten a level's mean step (summary.json step_share); where the
# levels' shares differ by more than this factor, their Courant numbers differ too.
STEP_SHARE_SPREAD = 1.1


def step_share_warnings(costs):
    """A line when the levels' steps were cut to land on output times by different shares: their
    Courant numbers then differ, so the sequence is not a refinement of the cell alone (a sample
    interval of a few steps cuts every level alike, about 0.8, and needs no warning)."""
    shares = [c.step_share for c in costs]
    if not shares or max(shares) <= STEP_SHARE_SPREAD * min(shares):
        return []
    listed = ", ".join(f"{s:.2f}" for s in shares)
    return [f"the levels' steps averaged {listed} of their cfl steps (cut to land on sample or snapshot times), "
            "so their Courant numbers differ and the sequence is not a refinement of the cell alone; a "
            "sample_interval (and snapshot_interval) of many steps at the coarsest level avoids it"]


def collect(levels, regions, window, at):
    """Results of every (region, quantity), in region order."""
    per_level = []   # per level: {(region, quantity): [value per seed]}
    for level in levels:
        seeds = [measure_run(path, regions, window, at) for _, path in level.runs]
        per_level.append({key: [s.get(key, math.nan) for s in seeds] for key in seeds[0]})
    results = []
    for key in per_level[0]:
        samples = [np.array(level.get(key, [math.nan])) for level in per_level]
        means = [float(np.mean(s)) for s in samples]
        errors = [float(np.std(s, ddof=1) / math.sqrt(s.size)) if s.size > 1 else 0.0 for s in samples]
        results.append(Result(*key, means, errors, richardson(means, [lv.measure for lv in levels])))
    return results


# --- outputs --------------------------------------------------------------------------------------

def _real(x):
    """Full precision for the csv ('nan' where there is no value)."""
    return repr(float(x))


def _whole(x):
    """Points and steps, means over seeds: whole numbers without '.0'."""
    return str(int(x)) if float(x).is_integer() else repr(float(x))


def write_csv(path, results, costs):
    """One row per level, region and quantity; observed_order is empty where the order could not be
    observed (the fallback)."""
    with open(path, "w", newline="") as f:
        out = csv.writer(f, lineterminator="\n")
        out.writerow(CSV_COLUMNS)
        for r in results:
            order = "" if math.isnan(r.estimate.order) else _real(r.estimate.order)
            for k, cost in enumerate(costs):
                out.writerow([k, _real(cost.cell_size), _whole(cost.points), _whole(cost.steps),
                              _real(cost.wall_seconds), r.region, r.quantity, _real(r.values[k]),
                              _real(r.estimate.extrapolated), _real(r.combined_error(k)), order])


def _g(x, digits=6):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}g}"


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(row) + " |" for row in rows]


def markdown(args, levels, costs, results, exact):
    seeds = args.seeds > 1
    what = (f"the value at t = {args.at * 1e9:g} ns" if args.at is not None else
            f"the plateau mean over [{args.window[0] * 1e9:g}, {args.window[1] * 1e9:g}] ns" if args.window else
            "the plateau mean over the second half of each run")
    lines = [f"# Convergence of {args.scene} under refinement of {args.refine}", "",
             f"Each quantity is {what}; arrival_time is when the region's mean pressure first reaches half "
             "its plateau. Extrapolated: Richardson from the three finest levels with the observed order; "
             "where no order in [0.5, 4] can be observed the finest value stands and its error estimate is the "
             "largest difference between successive levels (note: fallback)." +
             (f" {args.seeds} seeds per level: values are seed means; the discretisation estimate and the "
              "sampling standard error of the mean are shown apart, and the csv's error_estimate combines "
              "them in quadrature." if seeds else ""), "", "## Levels", ""]
    refined = [] if args.refine == "cell_size" else [args.refine]
    cost_rows = [[str(k), *([_g(lv.value)] if refined else []), _g(c.cell_size), _g(c.points), _g(c.steps),
                  f"{c.wall_seconds:.3g}", _g(c.points * c.steps * args.seeds, 3)]
                 for k, (lv, c) in enumerate(zip(levels, costs))]
    lines += _table(["level", *refined, "cell_size (m)", "points", "steps", "wall (s)", "point-steps"], cost_rows)
    lines += ["", "Values in SI units (kg/m3, Pa, K, m/s, s). Cost: wall seconds and point-steps of all the "
              "level's runs; points and steps are per run."]
    lines += [f"\n**Warning**, {w}." for w in step_share_warnings(costs)]
    for region in dict.fromkeys(r.region for r in results):
        header = ["quantity", *(f"level {k}" for k in range(len(levels))), "extrapolated",
                  "discretisation error (finest)" if seeds else "error estimate (finest)",
                  *(["sampling SE (finest)"] if seeds else []), "observed order", "note"]
        rows = [[r.quantity, *map(_g, r.values), _g(r.estimate.extrapolated), _g(r.estimate.errors[-1], 3),
                 *([_g(r.standard_errors[-1], 3)] if seeds else []), _g(r.estimate.order, 3), r.estimate.note]
                for r in results if r.region == region]
        lines += ["", f"## Region {region}", ""] + _table(header, rows)
    if exact:
        lines += ["", "## Against exact values", "",
                  f"True error |value - exact| of each level; 'within' means the finest level's true error is at most "
                  f"{WITHIN_FACTOR:g} times its error estimate.", ""]
        by_key = {(r.region, r.quantity): r for r in results}
        rows = []
        for (region, quantity), value in exact.items():
            r = by_key[(region, quantity)]
            true = [abs(v - value) for v in r.values]
            estimate = r.combined_error(len(levels) - 1)
            rows.append([region, quantity, _g(value), *(_g(t, 3) for t in true), _g(estimate, 3),
                         "yes" if true[-1] <= WITHIN_FACTOR * estimate else "NO",
                         _g(abs(r.estimate.extrapolated - value), 3)])
        lines += _table(["region", "quantity", "exact", *(f"true error {k}" for k in range(len(levels))),
                         "estimate (finest)", "within", "extrapolated error"], rows)
    return "\n".join(lines) + "\n"


def plot_cost(path, results, costs):
    """Error estimate against wall time, log-log, one panel per quantity, one line per region."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    quantities = list(dict.fromkeys(r.quantity for r in results))
    columns = min(4, len(quantities))
    rows = math.ceil(len(quantities) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(3.6 * columns, 3.0 * rows), squeeze=False)
    walls = np.array([c.wall_seconds for c in costs])
    for ax, quantity in zip(axes.flat, quantities):
        drawn = False
        for r in (r for r in results if r.quantity == quantity):
            errors = np.array([r.combined_error(k) for k in range(len(costs))])
            keep = (errors > 0) & np.isfinite(errors) & (walls > 0)
            if keep.any():
                ax.loglog(walls[keep], errors[keep], "o-", label=r.region)
                drawn = True
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_title(quantity, fontsize=9)
        ax.set_xlabel("wall time (s)", fontsize=8)
        ax.set_ylabel("error estimate (SI)", fontsize=8)
        if drawn:
            ax.legend(fontsize=7)
        else:
            ax.text(0.5, 0.5, "no positive estimate", ha="center", va="center", transform=ax.transAxes)
    for ax in list(axes.flat)[len(quantities):]:
        ax.set_visible(False)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


# --- the command line -----------------------------------------------------------------------------

def _exact(text):
    target, sep, value = text.partition("=")
    region, colon, quantity = target.partition(":")
    if not (sep and colon and region and quantity):
        raise PostError(f"--exact '{text}': expected region:quantity=value, e.g. B400:arrival_time=49.9ns")
    return (region.strip(), quantity.strip()), parse_quantity(value)


def _values(text):
    """The values as written; the simulator converts them (plan_levels)."""
    values = [v.strip() for v in text.split(",")]
    if not values or not all(values):
        raise PostError(f"--values '{text}': expected comma-separated values (units allowed: 20um,10um)")
    return values


def _count(minimum, what):
    """An argparse type: a whole number of at least `minimum`; `what` says why that many."""
    def count(text):
        try:
            value = int(text)
        except ValueError:
            raise PostError(f"'{text}' is not a whole number") from None
        if value < minimum:
            raise PostError(f"{value}: {what}")
        return value
    return count


def build_parser():
    checked = argument_type
    parser = argparse.ArgumentParser(prog="mpmshock-converge", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 2)[2])
    parser.add_argument("scene", type=Path)
    parser.add_argument("--out", required=True, type=Path, help="directory for the levels and the reports")
    levels = _count(MIN_LEVELS, f"a convergence study needs at least {MIN_LEVELS} levels (2 give the fallback "
                    "estimate, 3 or more an observed order)")
    parser.add_argument("--levels", type=checked(levels), default=None,
                        help=f"number of levels, at least {MIN_LEVELS} (default 3; one level: --values V)")
    parser.add_argument("--refine", default="cell_size", help="cell_size (default), particles_per_cell, cfl, av, "
                        "or any numeric key with --values")
    parser.add_argument("--values", type=checked(_values), help="explicit values of the refined key, coarsest first")
    parser.add_argument("--window", nargs=2, type=checked(parse_time), metavar=("T0", "T1"),
                        help="plateau window, times with units (default: the second half of the run)")
    parser.add_argument("--at", type=checked(parse_time), help="take values at this time instead of a plateau")
    parser.add_argument("--regions", type=lambda t: [r.strip() for r in t.split(",") if r.strip()],
                        help="regions to report (default: all in regions.csv)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="scene override (repeatable)")
    parser.add_argument("--seeds", type=checked(_count(1, "a level needs at least 1 run")), default=1,
                        help="runs per level with seeds S, S+1, ... (default 1)")
    parser.add_argument("--exact", nargs="+", action="extend", type=checked(_exact), default=[],
                        metavar="REGION:QUANTITY=VALUE", help="known answers (SI, or with a unit) to check the estimate")
    return parser


def check_arguments(args):
    """Conflicts argparse cannot see; raises PostError."""
    if args.values is not None and args.levels is not None and args.levels != len(args.values):
        raise PostError(f"--levels {args.levels} but --values gives {len(args.values)} values")
    args.levels = len(args.values) if args.values is not None else (args.levels if args.levels is not None else 3)
    if args.window and not args.window[0] < args.window[1]:
        raise PostError("--window T0 T1 needs T0 < T1")
    taken = {*refined_keys(args.refine), "output_dir", *(["seed"] if args.seeds > 1 else [])}
    for override in args.set:
        key = override.partition("=")[0].strip()
        if key in taken:
            raise PostError(f"--set {override}: mpmshock-converge sets {key} itself"
                            + (" (give the levels with --values)" if key != "output_dir" else ""))


def check_out(out):
    """--out must be, or be creatable as, a directory: refused before anything runs, the path untouched."""
    existing = next((p for p in (out, *out.parents) if p.exists()), None)
    if existing is not None and not existing.is_dir():
        what = "exists and is not a directory" if existing == out else f"lies in {existing}, which is not a directory"
        raise UsageError(f"--out {out} {what}; give a directory for the levels and the reports")


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        check_out(args.out)
        check_arguments(args)
        binary = mpmshock_binary()
        if not binary.is_file():
            raise PostError(f"no mpmshock binary at {binary} (build it, or set $MPMSHOCK)")
        levels = plan_levels(args.refine, args.values, args.levels,
                             lambda extra: resolved_scene(args.scene, [*args.set, *extra], binary))
        try:
            args.out.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise PostError(f"--out {args.out}: cannot make the directory: {e.strerror}") from None
        run_levels(levels, args, binary)
        results = collect(levels, args.regions, args.window, args.at)
        exact = dict(args.exact)
        unknown = [f"{r}:{q}" for r, q in exact if not any(x.region == r and x.quantity == q for x in results)]
        if unknown:
            raise PostError(f"--exact names {', '.join(unknown)}, which the study does not measure")
        costs = [level_cost(level) for level in levels]
        for w in step_share_warnings(costs):
            print(f"mpmshock-converge: warning: {w}", file=sys.stderr)
        write_csv(args.out / "convergence.csv", results, costs)
        (args.out / "convergence.md").write_text(markdown(args, levels, costs, results, exact))
        plot_cost(args.out / "cost.png", results, costs)
    except UsageError as e:
        parser.error(str(e))   # usage and message, exit 2
    except PostError as e:
        print(f"mpmshock-converge: error: {e}", file=sys.stderr)
        return 1
    for name in ("convergence.csv", "convergence.md", "cost.png"):
        print(args.out / name)
    return 0
