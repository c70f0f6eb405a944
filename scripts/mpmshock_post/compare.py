"""One or more region-averaged quantities from several runs on shared axes: the paper's Fig. 7, 8
(void size), 12 (impact velocity) and 13 (porosity). Legends name what differs between the scenes."""

import numpy as np

from .errors import PostError
from .labels import common_case_label, run_labels
from .style import (COLORS, LINESTYLES, MARKERS, add_resolution_note, keep_min_span, mark_every, missing_reason,
                    note_missing, panel_figure, short_ticks, time_axis)
from .timeseries import in_time_range, select_regions
from .units import TIME, quantity

_COLUMNS_WITH_STD = ("density", "pressure", "temperature", "velocity_x", "velocity_y")
COMPARABLE = _COLUMNS_WITH_STD + ("rot2", "div2", "strain_rate2")


def column_of(name):
    """regions.csv column for a quantity name: 'density' -> density_mean, 'density_std' stays."""
    stds = tuple(f"{q}_std" for q in _COLUMNS_WITH_STD)
    if name in COMPARABLE:
        return f"{name}_mean"
    if name in stds:
        return name
    raise PostError(f"cannot compare '{name}' (choose from {', '.join(COMPARABLE + stds)})")


def plot_compare(runs, quantities=("density",), regions=(), labels=None, trange=None, logy=False, title=None,
                 offsets=None):
    """A panel per quantity; a colour per run, a line style per region (default: the first run's
    first region). `offsets`: quantity -> one shift per run in display units, added to its curves
    and noted in the panel (the paper's Fig. 13 moves the density of delta 1.1, 1.4, 1.7 up).
    The default title names the region(s) and what the runs share (compare_title); the footer
    states their resolution."""
    columns = [column_of(name) for name in quantities]
    regions = list(regions) or list(select_regions(runs[0], ()))[:1]
    labels = list(labels) if labels else run_labels(runs)
    if len(labels) != len(runs):
        raise PostError(f"{len(labels)} labels given for {len(runs)} runs")
    offsets = offsets or {}
    for name, shifts in offsets.items():
        if name not in quantities or len(shifts) != len(runs):
            raise PostError(f"offsets for '{name}' need one value per run and a panel of that quantity")
    series = [select_regions(run, regions) for run in runs]

    # The legend takes a panel of its own: beside one or two panels, under three or more.
    fig, axes = panel_figure(len(quantities), ncols=len(quantities) + 1 if len(quantities) <= 2 else 2,
                             panel_size=(5.0, 3.6))
    for ax, name, column in zip(axes, quantities, columns):
        base = name[:-len("_std")] if name.endswith("_std") else name
        q = quantity(base)
        drawn = False
        shown = []   # (region, rows drawn) of every run
        shifts = offsets.get(name, [0.0] * len(runs))
        for i, (label, by_region) in enumerate(zip(labels, series)):
            for j, region in enumerate(regions):
                data = in_time_range(by_region[region], trange)
                shown.append((region, data))
                values = data[column] * q.factor + shifts[i]
                if np.all(np.isnan(values)):
                    continue
                ax.plot(data["time"] * TIME.factor, values, color=COLORS[i % len(COLORS)],
                        linestyle=LINESTYLES[j % len(LINESTYLES)], marker=MARKERS[i % len(MARKERS)],
                        markersize=4, markevery=mark_every(len(values)),
                        label=label if len(regions) == 1 else f"{label}, {region}")
                drawn = True
        if not drawn:
            note_missing(ax, missing_reason(base, [run.scene for run in runs], shown))
        elif logy:
            ax.set_yscale("log")
        else:
            short_ticks(ax)
            if column.endswith("_mean"):
                keep_min_span(ax, base)
        if any(shifts):
            moved = [f"{label} +{shift:g}" for label, shift in zip(labels, shifts) if shift]
            ax.text(0.98, 0.02, "moved up: " + ", ".join(moved), transform=ax.transAxes, ha="right",
                    va="bottom", fontsize=7, color="gray")
        ax.set_ylabel(q.label("Std " if name.endswith("_std") else ""))
        time_axis(ax)
    handles, legend_labels = axes[0].get_legend_handles_labels()
    axes[-1].legend(handles, legend_labels, loc="center", fontsize=8,
                    title=f"region {regions[0]}" if len(regions) == 1 else None)
    fig.suptitle(title if title is not None else compare_title(runs, regions))
    add_resolution_note(fig, [run.scene for run in runs], labels)
    return fig


def compare_title(runs, regions):
    """'2 runs, region B800: δ=1.2, r=15 µm': the region(s) and the paper's keys the runs share
    (the legend names those that differ)."""
    where = f"region{'s' if len(regions) > 1 else ''} {', '.join(regions)}"
    common = common_case_label(runs)
    return f"{len(runs)} runs, {where}" + (f": {common}" if common else "")
