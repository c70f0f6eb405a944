"""Region averages against time, from regions.csv: the paper's Fig. 2 and 9 (means), Fig. 4
(standard deviations) and Fig. 5 and 10 (mean squared rotation, divergence and strain rate)."""

import numpy as np

from .errors import select_named
from .labels import run_case_label
from .style import (add_resolution_note, keep_min_span, mark_every, missing_reason, note_missing, panel_figure,
                    region_styles, short_ticks, time_axis)
from .units import TIME, quantity

STATE = ("density", "pressure", "temperature", "velocity_x", "velocity_y")
DISSIPATION = ("rot2", "div2", "strain_rate2")


def select_regions(run, names):
    """The requested regions' series from regions.csv (all of them when `names` is empty)."""
    return select_named(run.regions(), names, run.path / "regions.csv", "region")


def in_time_range(columns, trange):
    """Rows of a region's series with trange[0] <= t <= trange[1] (s); all rows without a range."""
    if trange is None:
        return columns
    keep = (columns["time"] >= trange[0]) & (columns["time"] <= trange[1])
    return {key: values[keep] for key, values in columns.items()}


def plot_region_series(run, quantities, stat, regions=(), trange=None, logy=False, title=None):
    """One panel per quantity, one curve per region, of the regions.csv column `<quantity>_<stat>`;
    the footer states the run's resolution."""
    series = select_regions(run, regions)
    styles = region_styles(series, run.scene.regions)
    fig, axes = panel_figure(len(quantities), ncols=3 if len(quantities) > 3 else 2)
    prefix = "Std " if stat == "std" else ""
    for ax, name in zip(axes, quantities):
        q = quantity(name)
        drawn = False
        shown = {region: in_time_range(columns, trange) for region, columns in series.items()}
        for region, columns in shown.items():
            values = columns[f"{name}_{stat}"] * q.factor
            if np.all(np.isnan(values)):
                continue
            ax.plot(columns["time"] * TIME.factor, values, label=region, markersize=4,
                    markevery=mark_every(len(values)), **styles[region])
            drawn = True
        if not drawn:
            note_missing(ax, missing_reason(name, [run.scene], shown.items()))
        if logy and drawn:
            ax.set_yscale("log")
        else:
            short_ticks(ax)
            if stat == "mean":
                keep_min_span(ax, name)
        ax.set_ylabel(q.label(prefix))
        time_axis(ax)
    handles, labels = axes[0].get_legend_handles_labels()
    axes[-1].legend(handles, labels, loc="center", title="measured domain")
    fig.suptitle(title if title is not None else f"{run.name}: {run_case_label(run)}".rstrip(": "))
    add_resolution_note(fig, [run.scene])
    return fig


def plot_means(run, **options):
    """Mean density, pressure, temperature and particle velocity (paper Fig. 2 and 9)."""
    return plot_region_series(run, STATE, "mean", **options)


def plot_stds(run, **options):
    """Their standard deviations over the domain (paper Fig. 4)."""
    return plot_region_series(run, STATE, "std", **options)


def plot_dissipation(run, **options):
    """Mean squared rotation, divergence and strain rate (paper Fig. 5 and 10)."""
    return plot_region_series(run, DISSIPATION, "mean", **options)

