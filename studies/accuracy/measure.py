"""The accuracy study's measurements beyond mpmshock-converge's: plateau means of single runs, the
band's deviatoric stress, the order the true errors show, the cell size a target error needs, and
the simulator's throughput over the study's runs.

Part of the study in studies/accuracy/ of the checkout, run as `studies/accuracy/accuracy-study`;
report.py and sections.py write these numbers up.
"""

import math

import numpy as np

from mpmshock_post import converge
from mpmshock_post.errors import PostError
from mpmshock_post.reader import Run

from .plan import MAIN_SHAPE, REGION

QUANTITIES = ("density_mean", "macro_density", "pressure_mean", "macro_normal_stress", "temperature_mean",
              "temperature_std")
EXTRA = ("velocity_y_std", "velocity_x_std")   # measured here: not among mpmshock-converge's quantities
LARGE_RUN = 1e5   # material points from which a run's point-steps/s is the throughput (not overhead)


def plateau(run_dir, quantity, window):
    """The plateau mean of one run's band (regions.csv column `quantity`) over the window."""
    columns = Run(run_dir).regions()[REGION]
    return converge.sample(columns[quantity], columns["time"], window, None)


def extra_quantity(run_dir, quantity, window):
    """A plateau mean of a regions.csv column mpmshock-converge does not measure (velocity std)."""
    columns = Run(run_dir).regions()[REGION]
    times = columns["time"]
    return converge.sample(columns[quantity], times, converge.run_window(times, window), None)


def measure_single(run, window):
    """The plateau mean of every quantity of one run (a reader.Run)."""
    columns = run.regions()[REGION]
    return {q: converge.sample(columns[q], columns["time"], window, None) for q in QUANTITIES}


def band_deviator(run_dir):
    """Band means at the last snapshot: s_yy (the deviatoric yy stress, Pa), the von Mises
    stress and the plastic strain."""
    run = Run(run_dir)
    region = run.scene.regions[REGION]
    snap = run.snapshot(-1)
    y = snap["position"][:, 1]
    inside = (y >= region.y1) & (y <= region.y2)
    sigma = snap["stress"][inside]
    dev = sigma - np.eye(3) * (np.trace(sigma, axis1=1, axis2=2) / 3.0)[:, None, None]
    return dict(s_yy=float(dev[:, 1, 1].mean()),
                von_mises=float(np.sqrt(1.5 * np.einsum("nij,nij->n", dev, dev)).mean()),
                plastic_strain=float(snap["plastic_strain"][inside].mean()))


def exact_order(errors, hs):
    """Order the true errors of the two finest levels show: log(|e1|/|e2|) / log(h1/h2); None when
    the errors change sign or vanish."""
    e1, e2 = errors[-2], errors[-1]
    if e1 == 0 or e2 == 0 or e1 * e2 < 0:
        return None
    return math.log(abs(e1) / abs(e2)) / math.log(hs[-2] / hs[-1])


def needed_resolution(result, hs, target, relative):
    """The coarsest tested h whose discretisation estimate (and every finer one's) meets the target;
    beyond the finest, h_f (target / e_f)^(1/p) with the observed order (1 in the fallback).
    Returns (h, estimated error at h, how)."""
    est = result.estimate
    scale = abs(est.extrapolated) if relative else 1.0
    if not (math.isfinite(scale) and scale > 0):
        return None, math.nan, "no estimate"
    errors = [e / scale for e in est.errors]
    for k in range(len(errors)):
        if all(e <= target for e in errors[k:]):
            return hs[k], errors[k], "measured"
    p = est.order if math.isfinite(est.order) else 1.0
    h = hs[-1] * (target / errors[-1]) ** (1.0 / p) if errors[-1] > 0 else hs[-1]
    how = f"extrapolated (order {p:.2f})" if math.isfinite(est.order) else "extrapolated (fallback order 1)"
    return h, target, how


def nice_cell(h, width):
    """The largest cell size <= h that divides the width into whole cells, from 1-2-2.5-4-5-8 steps."""
    candidates = sorted({m * 10.0 ** e for e in range(-8, -3) for m in (1, 1.25, 2, 2.5, 4, 5, 8)}, reverse=True)
    for c in candidates:
        if c <= h * (1 + 1e-9) and abs(width / c - round(width / c)) < 1e-6:
            return c
    return h


def study_rate(study, fallback):
    """Median point-steps/s of the study's MAIN_SHAPE runs (the shape whose cost the answer gives) of
    at least LARGE_RUN points, their threads, the share of steps on fewer threads, the number of runs
    and the quartiles; the answer's finest runs (`fallback`, an Outcome) where there are none. Porous
    runs with volumetric smoothing off (a comparison; the answer's runs have it on) do not count."""
    runs = []
    for run_dir, s in study.all_runs().items():
        try:
            scene = Run(run_dir).scene
            shape = scene["shape_function"]
        except (PostError, KeyError):
            continue
        if scene.get("porosity", 1) > 1 and scene.get("volumetric_smoothing") == "off":
            continue
        if shape == MAIN_SHAPE and s.get("material_points", 0) >= LARGE_RUN and s.get("exit_code") == 0:
            runs.append(s)
    if not runs:
        runs = fallback.summaries[-1]
    rates = [s["point_steps_per_second"] for s in runs]
    threads = max(s["threads"] for s in runs)
    fewer = sum(s["steps_with_fewer_threads"] for s in runs) / sum(s["steps"] for s in runs)
    return float(np.median(rates)), threads, fewer, len(runs), tuple(np.percentile(rates, [25, 75]))
