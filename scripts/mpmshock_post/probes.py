"""Probe histories from probes.csv: by default the free-surface velocity against time, the record a
VISAR or PDV gives of a plate impact, with the spall pullback after the shock reflects.

A probe (scene key `probe.NAME = surface` or `point X Y`) follows the same material points through
the run; every row of probes.csv is the mean over them. The simulator moves both bodies toward
y = 0 at `velocity`, so a target's free surface starts at -velocity; `target_frame` adds
`velocity` to u_y, giving the record of a target at rest (0 before the shock arrives, about twice
the particle velocity after it).
"""

import numpy as np
from matplotlib.figure import Figure

from .errors import PostError, select_named
from .labels import run_case_label, run_labels
from .style import COLORS, LINESTYLES, MARKERS, add_resolution_note, mark_every, note_missing, thermal_off, time_axis
from .timeseries import in_time_range
from .units import TIME, quantity

PROBE_QUANTITIES = ("velocity_y", "velocity_x", "pressure", "density", "temperature")


def select_probes(run, names):
    """The requested probes' series from probes.csv (all of them when `names` is empty)."""
    return select_named(run.probes(), names, run.path / "probes.csv", "probe")


def _all_surface(runs, names):
    return all(str(run.scene.get(f"probe.{name}", "")).split()[:1] == ["surface"] for run in runs for name in names)


def plot_probes(runs, probes=(), quantity_name="velocity_y", trange=None, labels=None, target_frame=False,
                title=None):
    """One panel of `quantity_name` against time: every probe of every run a curve. One run: a
    colour per probe. Several runs: a colour per run (legend from what differs between the scenes,
    or `labels`), a line style per probe; `probes` (default: all of the first run's) must exist in
    every run. The footer states the runs' resolution."""
    if quantity_name not in PROBE_QUANTITIES:
        raise PostError(f"probes.csv has no quantity '{quantity_name}' (choose from {', '.join(PROBE_QUANTITIES)})")
    if target_frame and quantity_name != "velocity_y":
        raise PostError("--target-frame shifts velocity_y only")
    runs = list(runs)
    names = list(probes) or list(select_probes(runs[0], ()))
    series = [select_probes(run, names) for run in runs]
    labels = list(labels) if labels else run_labels(runs)
    if len(labels) != len(runs):
        raise PostError(f"{len(labels)} labels given for {len(runs)} runs")

    fig = Figure(figsize=(7.5, 4.0), layout="constrained")
    ax = fig.add_subplot()
    q = quantity(quantity_name)
    single = len(runs) == 1
    drawn = False
    for i, (run, label, by_probe) in enumerate(zip(runs, labels, series)):
        # The target's own speed (velocity, or target_velocity where the scene sets its frame).
        shift = float(run.scene.get("target_velocity", run.scene.get("velocity", 0.0))) if target_frame else 0.0
        for j, name in enumerate(names):
            data = in_time_range(by_probe[name], trange)
            values = (data[quantity_name] + shift) * q.factor
            if values.size == 0 or np.all(np.isnan(values)):
                continue
            style = j if single else i
            ax.plot(data["time"] * TIME.factor, values, color=COLORS[style % len(COLORS)],
                    linestyle="-" if single else LINESTYLES[j % len(LINESTYLES)],
                    marker=MARKERS[style % len(MARKERS)], markersize=4, markevery=mark_every(len(values)),
                    label=name if single else (label if len(names) == 1 else f"{label}, {name}"))
            drawn = True
    if not drawn:
        note_missing(ax, "thermal model off" if thermal_off(quantity_name, [run.scene for run in runs])
                     else "no data in this time range")
    windowed = [float(run.scene.get("window_height", 0.0)) > 0.0 for run in runs]
    if quantity_name == "velocity_y" and _all_surface(runs, names):
        # With a window on the target the surface probe follows the sample-window interface.
        prefix = ("sample-window interface velocity " if all(windowed)
                  else "free-surface velocity " if not any(windowed) else "surface velocity ")
    else:
        prefix = ""
    ax.set_ylabel(prefix + q.label() + (", target at rest" if target_frame else ""))
    time_axis(ax)
    handles, legend_labels = ax.get_legend_handles_labels()
    legend_title = "probe" if single else (f"probe {names[0]}" if len(names) == 1 else None)
    if handles:  # beside the axes, clear of the traces
        ax.legend(handles, legend_labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                  fontsize=8, title=legend_title)
    if title is None and single:
        title = f"{runs[0].name}: {run_case_label(runs[0])}".rstrip(": ")
    if title is not None:
        fig.suptitle(title)
    add_resolution_note(fig, [run.scene for run in runs], labels)
    return fig
