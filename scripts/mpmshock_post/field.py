"""A snapshot coloured by a local quantity, optionally with velocity arrows: the paper's Fig. 1, 3, 6.

Every material point is drawn as a square of its current area (sqrt of its volume per metre of
depth), so compressed material looks continuous and voids show as gaps, and the scatter is
rasterized so that 200k points stay fast and small in PDF/SVG as well.
"""

import numpy as np
from matplotlib.figure import Figure

from .errors import PostError
from .labels import case_label
from .local import local_quantity
from .units import LENGTH_FACTOR, TIME, quantity

_BODIES = {"flyer": 0, "target": 1}
_MARGINS_IN = dict(left=0.9, right=1.4, bottom=0.6, top=0.7)  # room for ticks, colourbar, title
_ARROWS_ACROSS = 20  # arrows along the window's width: readable, yet they follow the voids
# Quantities with a fixed range: damage is 0 or 1, and a few failed points must not set the scale.
_FIXED_LIMITS = {"damage": (0.0, 1.0)}


def _axes_size(width_um, height_um, longest_in=8.0):
    """Axes size in inches with the window's aspect ratio, so that 1 um is as long in x as in y."""
    if height_um >= width_um:
        return longest_in * width_um / height_um, longest_in
    return longest_in, longest_in * height_um / width_um


def _select(snapshot, body, window_um):
    """Indices of the points of the chosen body inside the window (um), and the window itself."""
    xy = snapshot["position"] * LENGTH_FACTOR
    keep = np.ones(len(xy), dtype=bool)
    if body != "all":
        keep &= snapshot["body"] == _BODIES[body]
    if not keep.any():
        raise PostError(f"{snapshot.path} has no {body} points")
    if window_um is None:
        x0, x1 = xy[keep, 0].min(), xy[keep, 0].max()
        y0, y1 = xy[keep, 1].min(), xy[keep, 1].max()
    else:
        x0, x1, y0, y1 = window_um
        if x1 <= x0 or y1 <= y0:
            raise PostError(f"window {x0:g},{x1:g},{y0:g},{y1:g} um: need X0 < X1 and Y0 < Y1")
    # Points just outside still reach into the window with their squares.
    pad = 2.0 * np.sqrt(np.median(snapshot["volume"])) * LENGTH_FACTOR
    keep &= (xy[:, 0] >= x0 - pad) & (xy[:, 0] <= x1 + pad) & (xy[:, 1] >= y0 - pad) & (xy[:, 1] <= y1 + pad)
    if not keep.any():
        raise PostError(f"no {'' if body == 'all' else body + ' '}points in the window "
                        f"x {x0:g}..{x1:g} um, y {y0:g}..{y1:g} um at t = {snapshot.time * TIME.factor:g} ns")
    return np.flatnonzero(keep), (x0, x1, y0, y1)


def _arrow_sample(xy, window, n_across):
    """One point per square bin of a coarse grid over the window, for evenly spread arrows."""
    x0, x1, y0, _ = window
    spacing = (x1 - x0) / n_across
    bins = np.floor((xy - [x0, y0]) / spacing).astype(np.int64)
    _, first = np.unique(bins, axis=0, return_index=True)
    return first, spacing


def _draw_arrows(ax, xy, velocity, window, arrow_scale, key_xy):
    """Velocity arrows; `arrow_scale` in um of arrow per m/s. By default a typical speed (the 90th
    percentile, rounded) is 0.8 arrow spacings long, so that the jets at collapsing voids stand out
    without every other arrow shrinking to a dot."""
    sample, spacing = _arrow_sample(xy, window, _ARROWS_ACROSS)
    u = velocity[sample]
    speed = np.hypot(u[:, 0], u[:, 1])
    reference = float(f"{np.percentile(speed, 90):.1g}")
    if arrow_scale is None:
        arrow_scale = 0.8 * spacing / max(reference, 1e-30)
    arrows = ax.quiver(xy[sample, 0], xy[sample, 1], u[:, 0], u[:, 1], angles="xy", scale_units="xy",
                       scale=1.0 / arrow_scale, width=0.003, color="black")
    if reference > 0:  # the key sits in the margin above the colour bar, clear of title and data
        ax.quiverkey(arrows, *key_xy, reference, f"{reference:g} m/s", labelpos="E",
                     coordinates="figure", fontproperties={"size": 8})


def _marker_side_um(snapshot, points, true_size=False):
    """Side of each point's square: the larger extent of its deformed lattice cell, F applied to
    the initial square of side sqrt(V0), V0 = V/J. Squares of the current area would leave seams
    where the material is compressed along y but stretched along x; the cap at twice the initial
    spacing keeps strongly distorted points at collapsing voids from covering their neighbours.
    `true_size`: squares of the current area exactly, so that slits narrower than a point (voids
    not yet closed) stay visible as seams."""
    volume = snapshot["volume"][points]
    if true_size:
        return np.sqrt(volume) * LENGTH_FACTOR
    if "deformation_gradient" not in snapshot.fields:
        return 1.1 * np.sqrt(volume) * LENGTH_FACTOR
    F = snapshot["deformation_gradient"][points]
    J = F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0]
    extent = np.maximum(np.abs(F[:, 0, 0]) + np.abs(F[:, 0, 1]), np.abs(F[:, 1, 0]) + np.abs(F[:, 1, 1]))
    side0 = np.sqrt(volume / J)
    return 1.1 * side0 * np.clip(extent, 1.0, 2.0) * LENGTH_FACTOR  # 10% overlap hides anti-aliasing seams


def robust_limits(values):
    """Colour limits over the central 99% of the points: a few collapsing voids reach ten times
    the bulk pressure and would otherwise wash out the shocked material."""
    lo, hi = np.nanpercentile(values, [0.5, 99.5])
    return (lo, hi) if hi > lo else (lo - 0.5, hi + 0.5)


def plot_field(snapshot, color="density", arrows=False, arrow_scale=None, window_um=None, body="all",
               clim=None, cmap="turbo", title=None, run_name=None, unit=None, length_unit_um=1.0,
               true_size=False):
    """The material points of a snapshot coloured by `color` in the paper's units.

    window_um: (x0, x1, y0, y1) in um, default the whole chosen body; body: 'all', 'target' or
    'flyer'; clim: colour limits in display units (default: the central 99% of the points; 0 to 1
    for damage); arrow_scale: um of arrow per m/s; unit: another display unit for the colour
    (pressure in MPa as the paper's Fig. 1); length_unit_um: the axes' length unit in um (10 as
    the paper's Fig. 1); true_size: points drawn at their current area (see _marker_side_um).
    """
    q = quantity(color, unit)
    values = local_quantity(snapshot, color) * q.factor
    points, window_um = _select(snapshot, body, window_um)
    xy = snapshot["position"][points] * (LENGTH_FACTOR / length_unit_um)
    window = tuple(edge / length_unit_um for edge in window_um)
    values = values[points]
    if np.all(np.isnan(values)):
        raise PostError(f"{color} is NaN at every point of {snapshot.path}"
                        + (" (thermal = off in this run)" if color == "temperature" else ""))

    x0, x1, y0, y1 = window
    ax_w, ax_h = _axes_size(x1 - x0, y1 - y0)
    m = _MARGINS_IN
    fig_w, fig_h = ax_w + m["left"] + m["right"], ax_h + m["bottom"] + m["top"]
    fig = Figure(figsize=(fig_w, fig_h))
    ax = fig.add_axes([m["left"] / fig_w, m["bottom"] / fig_h, ax_w / fig_w, ax_h / fig_h])
    colorbar_ax = fig.add_axes([(m["left"] + ax_w + 0.15) / fig_w, m["bottom"] / fig_h, 0.18 / fig_w, ax_h / fig_h])
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")

    points_per_unit = ax_w * 72.0 / (x1 - x0)  # typographic points per displayed length unit
    sizes = (_marker_side_um(snapshot, points, true_size) / length_unit_um * points_per_unit) ** 2
    vmin, vmax = clim if clim is not None else _FIXED_LIMITS.get(color) or robust_limits(values)
    scatter = ax.scatter(xy[:, 0], xy[:, 1], c=values, s=sizes, marker="s", linewidths=0, cmap=cmap,
                         vmin=vmin, vmax=vmax, rasterized=True)
    extend = {(False, False): "neither", (True, False): "min", (False, True): "max", (True, True): "both"}
    fig.colorbar(scatter, cax=colorbar_ax, label=q.label(),
                 extend=extend[(bool(np.nanmin(values) < vmin), bool(np.nanmax(values) > vmax))])
    if arrows:
        key_xy = ((m["left"] + ax_w + 0.25) / fig_w, (m["bottom"] + ax_h + 0.12) / fig_h)
        scale = None if arrow_scale is None else arrow_scale / length_unit_um
        _draw_arrows(ax, xy, snapshot["velocity"][points], window, scale, key_xy)

    length = "µm" if length_unit_um == 1.0 else f"{length_unit_um:g} µm"
    ax.set_xlabel(f"$x$ ({length})")
    ax.set_ylabel(f"$y$ ({length})")
    if title is None:
        case = case_label(snapshot.scene) if snapshot.scene is not None else ""
        joiner = ": " if ax_w >= 4.0 else "\n"  # a narrow column: one item a line, clear of the arrow key
        title = joiner.join(part for part in (run_name, case) if part) + f"\nt = {snapshot.time * TIME.factor:.4g} ns"
    ax.set_title(title, fontsize=10, loc="left")
    return fig
