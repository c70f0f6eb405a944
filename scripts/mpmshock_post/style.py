"""Shared look of the figures.

Figures are built with matplotlib.figure.Figure directly, not pyplot: no backend or global state is
involved, so the same functions serve the Agg command line and a notebook (which displays a
returned Figure itself).
"""

import math

from matplotlib.figure import Figure

from .labels import resolution_parts
from .units import TIME

COLORS = ["tab:blue", "tab:red", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:gray"]
MARKERS = ["o", "s", "^", "D", "v", "p", "h", "*"]
LINESTYLES = ["-", "--", ":", "-."]
FORMATS = ("png", "pdf", "svg")
# Smallest y span of a panel of region means, in display units: mean velocities of a symmetric
# impact stay within a few m/s of 0, and autoscaling would blow that noise up into oscillations.
MIN_SPAN = {"velocity_x": 50.0, "velocity_y": 50.0}


def panel_figure(n_panels, ncols, panel_size=(4.2, 3.2), legend_panel=True):
    """A grid of panels, row by row; with `legend_panel` one more cell is kept, axis off, for the
    legend, so that a shared legend does not cover any curve."""
    cells = n_panels + (1 if legend_panel else 0)
    nrows = math.ceil(cells / ncols)
    fig = Figure(figsize=(panel_size[0] * ncols, panel_size[1] * nrows), layout="constrained")
    axes = [fig.add_subplot(nrows, ncols, i + 1) for i in range(cells)]
    if legend_panel:
        axes[-1].axis("off")
    return fig, axes


FOOTER_FONTSIZE = 8
FOOTER_LINE_IN = 0.16     # height of a footer line in inches
_FOOTER_CHARS_PER_IN = 15  # 8 pt text: about 15 characters an inch


def _wrap(parts, width_in, lead=""):
    """`lead` and the comma-separated parts on as few lines as fit `width_in`; a part is never split."""
    room = max(20, int(width_in * _FOOTER_CHARS_PER_IN))
    lines = [lead + parts[0]]
    for part in parts[1:]:
        if len(lines[-1]) + 2 + len(part) > room:
            lines[-1] += ","
            lines.append("    " + part)
        else:
            lines[-1] += ", " + part
    return lines


def resolution_lines(scenes, names=None, width_in=8.0):
    """The footer lines that state the resolution of the runs (cell size, points per cell, shape
    function, from their scenes), wrapped to `width_in`: one statement when all runs share it, else
    one per run, named by `names`."""
    pieces = [resolution_parts(scene) if scene is not None else [] for scene in scenes]
    pieces = [p or ["resolution not stated in the scene"] for p in pieces]
    if all(p == pieces[0] for p in pieces):
        return _wrap(pieces[0], width_in, "resolution: ")
    names = list(names) if names else [f"run {i + 1}" for i in range(len(scenes))]
    lines = ["resolution:"]
    for name, parts in zip(names, pieces):
        lines += _wrap(parts, width_in, f"  {name}: ")
    return lines


def add_footer(fig, lines):
    """The lines at the foot of the figure, left-aligned in small grey type. A constrained-layout
    figure shrinks its panels to make room; a figure laid out by hand must leave a bottom margin of
    len(lines) * FOOTER_LINE_IN + 0.05 inches."""
    height_in = fig.get_figheight()
    footer_in = len(lines) * FOOTER_LINE_IN + 0.05
    engine = fig.get_layout_engine()
    if engine is not None and hasattr(engine, "set") and "rect" in engine.get():
        engine.set(rect=(0.0, footer_in / height_in, 1.0, 1.0 - footer_in / height_in))
    return fig.text(0.08 / fig.get_figwidth(), 0.04 / height_in, "\n".join(lines), ha="left", va="bottom",
                    fontsize=FOOTER_FONTSIZE, color="0.35", linespacing=1.2)


def add_resolution_note(fig, scenes, names=None):
    """add_footer with the resolution_lines of the runs' scenes."""
    return add_footer(fig, resolution_lines(scenes, names, fig.get_figwidth()))


def region_styles(names, specs):
    """Line style per region, after the paper's Fig. 2: one colour and marker per domain height,
    filled symbols and solid lines at the bottom, open symbols and dashed lines at the top."""
    styles, slot_of_height, taken = {}, {}, set()
    for name in names:
        spec = specs.get(name)
        height = spec.extent if spec else name
        kind = spec.kind if spec else "band"
        slot = slot_of_height.get(height)
        if slot is None or (slot, kind) in taken:
            slot = len(taken)
            slot_of_height.setdefault(height, slot)
        taken.add((slot, kind))
        color = COLORS[slot % len(COLORS)]
        styles[name] = dict(color=color, marker=MARKERS[slot % len(MARKERS)],
                            markerfacecolor="none" if kind == "top" else color,
                            linestyle="--" if kind == "top" else "-")
    return styles


def time_axis(ax):
    ax.set_xlabel(TIME.label())


def short_ticks(ax):
    """Squared rates in 1/ns^2 are of order 1e-5: a power-of-ten offset keeps the tick labels short."""
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4))


def keep_min_span(ax, name):
    """Widens the y axis about its middle to MIN_SPAN[name] where the data span less."""
    span = MIN_SPAN.get(name)
    lo, hi = ax.get_ylim()
    if span is not None and hi - lo < span:
        middle = 0.5 * (lo + hi)
        ax.set_ylim(middle - 0.5 * span, middle + 0.5 * span)


def mark_every(n_samples):
    """About 15 symbols per curve: enough to tell the regions apart, few enough to see the line."""
    return max(1, n_samples // 15)


def note_missing(ax, text):
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", color="gray")


def thermal_off(name, scenes):
    """True when a panel of `name` is empty because no run computed temperatures (thermal = off in
    every scene; a scene that is not known, None, does not say so)."""
    return name in ("temperature", "paper_temperature") and all(
        scene is not None and scene.get("thermal") == "off" for scene in scenes)


def missing_reason(name, scenes, samples):
    """What an empty panel of `name` says, truthfully. `samples`: (region, columns) pairs of the
    rows drawn (a regions.csv series cut to the time range). A region whose count is 0 in every
    row holds no material there: its means are NaN whatever the thermal model, so that is said
    first."""
    samples = list(samples)
    if all(len(columns["time"]) == 0 for _, columns in samples):
        return "no samples in this time range"
    empty = list(dict.fromkeys(region for region, columns in samples
                               if "count" in columns and len(columns["count"]) and not columns["count"].any()))
    if empty and len(empty) == len({region for region, _ in samples}):
        return f"no material in region{'s' if len(empty) > 1 else ''} {', '.join(empty)}"
    if thermal_off(name, scenes):
        return "thermal model off"
    return "no data"


def save_figure(fig, path, fmt, dpi):
    fig.savefig(path, format=fmt, dpi=dpi)
