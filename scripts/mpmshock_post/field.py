"""A snapshot coloured by a local quantity, optionally with velocity arrows: the paper's Fig. 1, 3, 6.

Every material point is drawn as a square of its current area (sqrt of its volume per metre of
depth), so compressed material looks continuous and voids show as gaps, and the scatter is
rasterized so that 200k points stay fast and small in PDF/SVG as well.

A 3D run (a column periodic in x and z) is shown as a slice in the x-y plane: the points whose z
lies within half a lattice spacing a = cell_size / particles_per_cell of the plane z = z0, i.e.
z0 - a/2 <= z < z0 + a/2 counted periodically in z, one layer of the initial lattice thick. By
default z0 is mid-depth, moved to the nearest plane of initial point centres ((k + 1/2) a), so
that the slice holds one whole layer rather than parts of two. Arrows show the in-plane velocity
(u_x, u_y); `speed` is |u| with u_z.
"""

import re
from typing import NamedTuple

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MultipleLocator

from .errors import PostError
from .labels import case_label
from .local import local_quantity
from .reader import void_count
from .style import FOOTER_LINE_IN, add_footer, resolution_lines
from .units import LENGTH_FACTOR, TIME, quantity

_BODIES = {"flyer": 0, "target": 1, "window": 2}
_MARGINS_IN = dict(left=0.9, right=1.4, bottom=0.6, top=0.15)  # room for ticks, colourbar; title and footer add theirs
_MIN_FIGURE_WIDTH_IN = 5.0   # a narrow column still gets a figure wide enough for its title
_TITLE_LINE_IN = 0.2         # a 10 pt title line
_TITLE_CHARS_PER_IN = 11     # 10 pt text: about 11 characters an inch
_ARROW_KEY_ROW_IN = 0.3      # between the axes and the title, for the arrow key
_DIGIT_IN = 0.09             # width of a digit of a 10 pt tick label
_TICK_GAP_IN = 0.15          # least blank between two x tick labels
_ARROWS_ACROSS = 20  # arrows along the window's width: readable, yet they follow the voids
# Quantities with a fixed range: damage is 0 or 1, and a few failed points must not set the scale.
_FIXED_LIMITS = {"damage": (0.0, 1.0)}


def _axes_size(width_um, height_um, longest_in=8.0):
    """Axes size in inches with the window's aspect ratio, so that 1 um is as long in x as in y."""
    if height_um >= width_um:
        return longest_in * width_um / height_um, longest_in
    return longest_in, longest_in * height_um / width_um


class Slice(NamedTuple):
    """The slab of a 3D snapshot that a field plot shows: z0 - half <= z < z0 + half, periodic in z."""
    z: float            # m, the plane
    half: float         # m, half the slab's thickness: half a lattice spacing
    depth: float        # m, the period in z
    inside: np.ndarray  # bool per point of the snapshot

    def describe(self):
        return f"slice z = {self.z * LENGTH_FACTOR:.4g} µm ± {self.half * LENGTH_FACTOR:.3g} µm"


def point_spacing(snapshot):
    """Spacing a of the initial material-point lattice in m: cell_size / particles_per_cell from
    the scene, else the edge of the median reference volume V / det F."""
    a = snapshot.scene.point_spacing if snapshot.scene is not None else None
    if a:
        return a
    volume = snapshot["volume"]
    if "deformation_gradient" in snapshot.fields:
        volume = volume / np.linalg.det(snapshot["deformation_gradient"])
    return float(np.median(volume)) ** (1.0 / snapshot.dimension)


def column_depth(snapshot):
    """z extent of a 3D column in m: the scene's depth (its width for 'auto')."""
    depth = snapshot.scene.depth if snapshot.scene is not None else None
    if not depth:
        raise PostError(f"{snapshot.path} states no scene, so the depth of its column is unknown")
    return depth


def default_slice_z(snapshot):
    """Mid-depth, moved to the nearest plane of initial point centres (k + 1/2) a (upwards on a
    tie), so that the default slice holds one whole lattice layer."""
    a, depth = point_spacing(snapshot), column_depth(snapshot)
    layers = max(1, int(round(depth / a)))
    return (min(int(np.floor(0.5 * depth / a + 1e-6)), layers - 1) + 0.5) * a


def slice_points(snapshot, z=None):
    """The Slice of a 3D snapshot at the plane z (m; default: default_slice_z). 2D snapshots
    have no slices: their points already lie in the x-y plane."""
    if snapshot.dimension != 3:
        raise PostError(f"{snapshot.path} is from a 2D run (plane strain): its points lie in the x-y plane "
                        "already, a z slice needs a 3D run (dimension = 3)")
    a, depth = point_spacing(snapshot), column_depth(snapshot)
    if z is None:
        z = default_slice_z(snapshot)
    elif not 0.0 <= z <= depth:
        raise PostError(f"slice z = {z:g} m ({z * LENGTH_FACTOR:g} µm) lies outside the column, which spans z "
                        f"from 0 to {depth * LENGTH_FACTOR:g} µm (a bare number is in metres: write e.g. "
                        f"z={0.5 * depth * LENGTH_FACTOR:g}um)")
    half = 0.5 * a
    dz = np.mod(snapshot["position"][:, 2] - z + 0.5 * depth, depth) - 0.5 * depth
    return Slice(float(z), half, depth, (dz >= -half) & (dz < half))


def _select(snapshot, body, window_um, slab=None):
    """Indices of the points of the chosen body (and slab, in 3D) inside the window (um), and the
    window itself."""
    xy = snapshot["position"][:, :2] * LENGTH_FACTOR
    keep = np.ones(len(xy), dtype=bool) if slab is None else slab.inside.copy()
    if body != "all":
        keep &= snapshot["body"] == _BODIES[body]
    if not keep.any():
        where = "" if slab is None else f" in the {slab.describe()}"
        raise PostError(f"{snapshot.path} has no {'' if body == 'all' else body + ' '}points{where}")
    if window_um is None:
        x0, x1 = xy[keep, 0].min(), xy[keep, 0].max()
        y0, y1 = xy[keep, 1].min(), xy[keep, 1].max()
    else:
        x0, x1, y0, y1 = window_um
        if x1 <= x0 or y1 <= y0:
            raise PostError(f"window {x0:g},{x1:g},{y0:g},{y1:g} um: need X0 < X1 and Y0 < Y1")
    # Points just outside still reach into the window with their squares.
    pad = 2.0 * np.median(snapshot["volume"]) ** (1.0 / snapshot.dimension) * LENGTH_FACTOR
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
    speed = np.hypot(u[:, 0], u[:, 1])  # in the plane of the plot
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
    not yet closed) stay visible as seams. In 3D the initial cube has side cbrt(V0); its extent in
    x and y includes what F turns out of z, and its true size is the area of its deformed x-y face."""
    volume = snapshot["volume"][points]
    if snapshot.dimension == 3:
        if "deformation_gradient" not in snapshot.fields:
            return (1.0 if true_size else 1.1) * np.cbrt(volume) * LENGTH_FACTOR
        F = snapshot["deformation_gradient"][points]
        side0 = np.cbrt(volume / np.linalg.det(F))
        if true_size:
            in_plane = np.abs(F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0])
            return side0 * np.sqrt(in_plane) * LENGTH_FACTOR
        extent = np.maximum(np.abs(F[:, 0, :]).sum(axis=1), np.abs(F[:, 1, :]).sum(axis=1))
        return 1.1 * side0 * np.clip(extent, 1.0, 2.0) * LENGTH_FACTOR
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
               true_size=False, slice_z=None):
    """The material points of a snapshot coloured by `color` in the paper's units.

    window_um: (x0, x1, y0, y1) in um, default the whole chosen body; body: 'all', 'target' or
    'flyer'; clim: colour limits in display units (default: the central 99% of the points; 0 to 1
    for damage); arrow_scale: um of arrow per m/s; unit: another display unit for the colour
    (pressure in MPa as the paper's Fig. 1); length_unit_um: the axes' length unit in um (10 as
    the paper's Fig. 1); true_size: points drawn at their current area (see _marker_side_um);
    slice_z: in 3D, the plane z (m) whose slab of points is drawn (see slice_points; default
    mid-depth); refused for a 2D snapshot.
    """
    q = quantity(color, unit)
    values = local_quantity(snapshot, color) * q.factor
    slab = slice_points(snapshot, slice_z) if snapshot.dimension == 3 or slice_z is not None else None
    points, window_um = _select(snapshot, body, window_um, slab)
    xy = snapshot["position"][points, :2] * (LENGTH_FACTOR / length_unit_um)
    window = tuple(edge / length_unit_um for edge in window_um)
    values = values[points]
    if np.all(np.isnan(values)):
        raise PostError(f"{color} is NaN at every point of {snapshot.path}"
                        + (" (thermal = off in this run)" if color == "temperature" else ""))

    x0, x1, y0, y1 = window
    ax_w, ax_h = _axes_size(x1 - x0, y1 - y0)
    m = _MARGINS_IN
    fig_w = max(ax_w + m["left"] + m["right"], _MIN_FIGURE_WIDTH_IN)
    title_room_in = fig_w - m["left"] - 0.1  # the title starts at the axes' left edge
    if title is None:
        title = _default_title(snapshot, run_name, slab, title_room_in)
    footer = resolution_lines([snapshot.scene], width_in=fig_w)
    bottom = m["bottom"] + len(footer) * FOOTER_LINE_IN + 0.05
    title_pad_in = _ARROW_KEY_ROW_IN if arrows else 0.08
    top = m["top"] + title_pad_in + _TITLE_LINE_IN * len(title.splitlines())
    fig_h = ax_h + bottom + top
    fig = Figure(figsize=(fig_w, fig_h))
    ax = fig.add_axes([m["left"] / fig_w, bottom / fig_h, ax_w / fig_w, ax_h / fig_h])
    colorbar_ax = fig.add_axes([(m["left"] + ax_w + 0.15) / fig_w, bottom / fig_h, 0.18 / fig_w, ax_h / fig_h])
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.xaxis.set_major_locator(MultipleLocator(_tick_step(x0, x1, ax_w)))

    points_per_unit = ax_w * 72.0 / (x1 - x0)  # typographic points per displayed length unit
    sizes = (_marker_side_um(snapshot, points, true_size) / length_unit_um * points_per_unit) ** 2
    vmin, vmax = clim if clim is not None else _FIXED_LIMITS.get(color) or robust_limits(values)
    scatter = ax.scatter(xy[:, 0], xy[:, 1], c=values, s=sizes, marker="s", linewidths=0, cmap=cmap,
                         vmin=vmin, vmax=vmax, rasterized=True)
    extend = {(False, False): "neither", (True, False): "min", (False, True): "max", (True, True): "both"}
    fig.colorbar(scatter, cax=colorbar_ax, label=q.label(),
                 extend=extend[(bool(np.nanmin(values) < vmin), bool(np.nanmax(values) > vmax))])
    if arrows:
        key_xy = ((m["left"] + ax_w + 0.25) / fig_w, (bottom + ax_h + 0.12) / fig_h)
        scale = None if arrow_scale is None else arrow_scale / length_unit_um
        _draw_arrows(ax, xy, snapshot["velocity"][points, :2], window, scale, key_xy)

    length = "µm" if length_unit_um == 1.0 else f"{length_unit_um:g} µm"
    ax.set_xlabel(f"$x$ ({length})")
    ax.set_ylabel(f"$y$ ({length})")
    ax.set_title(title, fontsize=10, loc="left", pad=title_pad_in * 72.0)
    add_footer(fig, footer)
    return fig


def _tick_step(x0, x1, ax_w):
    """The x tick spacing, in display length units: the smallest of 1, 2, 2.5, 5 x 10^k that
    leaves a blank of _TICK_GAP_IN between the labels on axes ax_w inches wide (about 10 ticks on
    a wide window, one or two on a narrow column), halved where no tick would be left."""
    characters = max(len(f"{round(x):d}") for x in (x0, x1)) + (2 if x1 - x0 < 10.0 else 0)  # '-150', '2.5'
    least = max((characters * _DIGIT_IN + _TICK_GAP_IN) * (x1 - x0) / ax_w, (x1 - x0) / 10.0)
    decade = 10.0 ** np.floor(np.log10(least))
    step = next(decade * m for m in (1.0, 2.0, 2.5, 5.0, 10.0) if decade * m >= least)
    while np.floor(x1 / step) * step < x0:  # no multiple of the step inside the window
        step /= 2.0
    return step


def _shown_length(text):
    """Characters a mathtext string shows: '$\\delta$=1.2' shows 5."""
    return len(re.sub(r"\\[A-Za-z]+", "x", text).replace("$", "").replace("{", "").replace("}", ""))


def _default_title(snapshot, run_name, slab, room_in):
    """'run: δ=1.2, r=15 µm, v=1000 m/s' over 't = 60 ns' (, the 3D slice); an item gets a line of
    its own where its line would not fit `room_in` inches."""
    case = case_label(snapshot.scene, void_count(snapshot.path.parent)) if snapshot.scene is not None else ""
    when = [f"t = {snapshot.time * TIME.factor:.4g} ns"] + ([slab.describe()] if slab is not None else [])
    room = int(room_in * _TITLE_CHARS_PER_IN)
    lines = []
    for items, joiner in (([part for part in (run_name, case) if part], ": "), (when, ", ")):
        joined = joiner.join(items)
        lines += [joined] if _shown_length(joined) <= room else items
    return "\n".join(line for line in lines if line)
