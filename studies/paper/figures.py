"""The 13 figures of Xu et al. from the campaign's runs, drawn by the mpmshock-plot functions.

Each figure's title names the case and the resolution (cell size, points per cell, shape function,
column width) and says 'quick' for a quick campaign. Where a figure has a temperature panel and the
case has the paper model's temperature (its run made with `paper_temperature = on`, or a run of its
own with `temperature_model = paper` in DIR/runs/<case>-paperT), that temperature is drawn
too: the same colour, dashed (dotted where the energy-model curve is already dashed), or a field
panel of its own with the same colour scale.
"""

import json

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from mpmshock_post import timeseries
from mpmshock_post.compare import plot_compare
from mpmshock_post.errors import PostError
from mpmshock_post.field import plot_field, robust_limits
from mpmshock_post.hist import central_range, plot_histograms, region_values
from mpmshock_post.labels import case_label, run_labels
from mpmshock_post.local import local_quantity
from .runs import PAPER_SUFFIX, POROSITY_CASES, VELOCITY_CASES, VOID_SIZE_CASES
from mpmshock_post.reader import PaperTemperatureRun, Run, has_paper_temperature
from mpmshock_post.stats import moments
from mpmshock_post.style import COLORS, save_figure
from mpmshock_post.units import LENGTH_FACTOR, TIME, quantity

DPI = 110
TILE_DPI = 80  # field panels are 8 inches at their longest: three in a row stay under 3000 pixels
NS = 1e-9
PAPER_T = "paper T model"
ALL_REGIONS = ("B800", "B400", "B100", "T800", "T400", "T100")
BOTTOM_REGIONS = ("B800", "B400", "B100")
# Fig. 6: "the size of particle velocity is denoted by the length of arrow timed by 50", in the
# paper's units of um and ns: an arrow is 50 ns of the point's motion, 0.05 um per m/s.
ARROW_UM_PER_MPS = 50 * NS * LENGTH_FACTOR
FIG6_VOID_UM = (510.0, 280.0)  # the paper's void "around the position (510 um, 280 um)"
FIG13_DENSITY_OFFSETS = {"delta1.1": 0.01, "delta1.4": 0.1, "delta1.7": 0.15}  # g/cm3, as its caption


class CampaignRuns:
    """The finished runs of DIR/runs: each case's energy-model run and, where made, its paper-model run."""

    def __init__(self, runs_dir, quick):
        self.runs_dir = runs_dir
        self.quick = quick

    def energy(self, case):
        return Run(self.runs_dir / case)

    def paper(self, case):
        """The case's run read with the paper model's temperature: its own paper-model run where one
        was made, else its energy-model run where that reports both (paper_temperature = on)."""
        for path, reader in ((self.runs_dir / (case + PAPER_SUFFIX), Run), (self.runs_dir / case, PaperTemperatureRun)):
            try:
                if json.loads((path / "summary.json").read_text()).get("exit_code") == 0 and (
                        reader is Run or has_paper_temperature(path)):
                    return reader(path)
            except (OSError, ValueError, PostError):
                pass
        return None


# --- titles -----------------------------------------------------------------------------------------

def _joined(values):
    return "/".join(dict.fromkeys(values))


def resolution(scenes, quick):
    """'h 20 µm, 2×2 points per cell, bspline2, width 1 mm (quick)'; values that differ between the
    scenes are listed in order, e.g. 'h 5/10/20 µm'."""
    h = _joined(f"{s['cell_size'] * 1e6:g}" for s in scenes)
    ppc = _joined(f"{s['particles_per_cell']:g}×{s['particles_per_cell']:g}" for s in scenes)
    width = _joined(f"{s['width'] * 1e3:g}" for s in scenes)
    text = f"h {h} µm, {ppc} points per cell, {_joined(s['shape_function'] for s in scenes)}, width {width} mm"
    return text + (" — QUICK (reduced resolution and width)" if quick else "")


def title(number, what, runs, quick, case=None):
    case = case or case_label(runs[0].scene)
    return f"Fig. {number}: {what} — {case}\n{resolution([run.scene for run in runs], quick)}"


# --- the paper's temperature drawn over the energy model's ------------------------------------------

def _axis_labelled(fig, label, which="y"):
    for ax in fig.axes:
        if (ax.get_ylabel() if which == "y" else ax.get_xlabel()) == label:
            return ax
    raise PostError(f"no panel labelled {label}")


def overlay_paper_temperature(fig, paper_series, stat="mean"):
    """Draws each paper-model series over the energy-model line of the same legend label, in its
    colour, dashed (dotted where that line is dashed), and adds one legend entry saying so.
    paper_series: line label -> that run's regions.csv columns of the same region."""
    if not paper_series:
        return
    ax = _axis_labelled(fig, quantity("temperature").label("Std " if stat == "std" else ""))
    styles = set()
    for line in list(ax.get_lines()):
        series = paper_series.get(line.get_label())
        if series is not None:
            style = "--" if line.get_linestyle() == "-" else ":"
            ax.plot(series["time"] * TIME.factor, series[f"temperature_{stat}"], color=line.get_color(),
                    linestyle=style, linewidth=1.2)
            styles.add(style)
    legend_ax = fig.axes[-1]
    old = legend_ax.get_legend()
    handles, labels = fig.axes[0].get_legend_handles_labels()
    for style, text in (("--", "same colour"), (":", "beside a dashed curve")):
        if style in styles:
            handles.append(Line2D([], [], color="gray", linestyle=style))
            labels.append(f"{PAPER_T}, {text}")
    legend_ax.legend(handles, labels, loc="center", fontsize=8, title=old.get_title().get_text() if old else None)


def _region_overlay(runs, case, regions):
    paper = runs.paper(case)
    if paper is None:
        return {}
    series = paper.regions()
    return {region: series[region] for region in regions if region in series}


def _compare_overlay(runs, cases, labels, regions):
    """Line label -> paper-model series, with plot_compare's labels: the run's, or 'label, region'."""
    pairs = {}
    for case, label in zip(cases, labels):
        paper = runs.paper(case)
        if paper is not None:
            series = paper.regions()
            for region in regions:
                pairs[label if len(regions) == 1 else f"{label}, {region}"] = series[region]
    return pairs


def floor_log_axes(fig, below=3.0):
    """Log axes start `below` times under the smallest value after each curve's peak: the first
    samples, before the shock reaches a domain, are zero or tiny and would take decades of the axis."""
    for ax in fig.axes:
        if ax.get_yscale() != "log":
            continue
        tails = [line.get_ydata()[np.nanargmax(line.get_ydata()):] for line in ax.get_lines() if len(line.get_ydata())]
        positive = [tail[tail > 0] for tail in tails]
        lows = [tail.min() for tail in positive if tail.size]
        if lows:
            ax.set_ylim(bottom=min(lows) / below)
    return fig


# --- composing field panels into one figure ---------------------------------------------------------

def _pixels(fig):
    fig.set_dpi(TILE_DPI)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())


def _pad(image, height, width):
    out = np.full((height, width, 4), 255, dtype=np.uint8)
    out[:image.shape[0], :image.shape[1]] = image
    return out


def tile(figures, ncols, heading):
    """One figure of several, rendered side by side in rows of `ncols`, under a heading."""
    images = [_pixels(fig) for fig in figures]
    rows = []
    for start in range(0, len(images), ncols):
        row = images[start:start + ncols]
        height = max(image.shape[0] for image in row)
        rows.append(np.hstack([_pad(image, height, image.shape[1]) for image in row]))
    width = max(row.shape[1] for row in rows)
    full = np.vstack([_pad(row, row.shape[0], width) for row in rows])
    heading_px = 22 * (heading.count("\n") + 1) + 16
    height = full.shape[0] + heading_px
    fig = Figure(figsize=(width / DPI, height / DPI), dpi=DPI)  # saved at DPI: one pixel per rendered pixel
    ax = fig.add_axes([0, 0, 1, full.shape[0] / height])
    ax.imshow(full, interpolation="none")
    ax.axis("off")
    fig.text(0.5, 1 - 8 / height, heading, ha="center", va="top", fontsize=10)
    return fig


def _shared_limits(snapshots, name, unit=None):
    values = np.concatenate([local_quantity(s, name)[s["body"] == 1] for s in snapshots]) * quantity(name, unit).factor
    return robust_limits(values)


def _field_panels(energy, paper, time, panels, window, **options):
    """plot_field figures of `panels` (letter, quantity, extra options) at `time`, plus the paper
    model's temperature with the energy model's colour scale where that run exists."""
    snapshot = energy.snapshot(time=time)
    paper_snapshot = paper.snapshot(time=time) if paper is not None else None
    figures, t_ns = [], f"t = {snapshot.time / NS:.4g} ns"
    temperature_limits = _shared_limits([s for s in (snapshot, paper_snapshot) if s], "temperature")
    for letter, name, extra in panels:
        clim = temperature_limits if name == "temperature" else None
        label = f"({letter}) {name.replace('_', ' ')}, {t_ns}"
        if name == "temperature" and paper is not None:
            label += ", energy T model"
        figures.append(plot_field(snapshot, color=name, window_um=window, body="target", clim=clim, title=label,
                                  **{**options, **extra}))
    if paper_snapshot is not None:
        letter = chr(ord(panels[-1][0]) + 1)
        figures.append(plot_field(paper_snapshot, color="temperature", window_um=window, body="target",
                                  clim=temperature_limits, title=f"({letter}) temperature, {t_ns}, {PAPER_T}",
                                  **options))
    return figures


def _target_top_um(snapshot):
    return snapshot["position"][snapshot["body"] == 1, 1].max() * LENGTH_FACTOR


# --- the figures --------------------------------------------------------------------------------------

def fig01(runs):
    base, paper = runs.energy("base"), runs.paper("base")
    width_um = base.scene["width"] * LENGTH_FACTOR
    window = (0.0, width_um, 0.0, 2000.0)  # the shocked lower part of the target and what lies ahead
    panels = [("a", "pressure", {"unit": "MPa"}), ("b", "temperature", {})]
    figures = _field_panels(base, paper, 250 * NS, panels, window, length_unit_um=10.0)
    return tile(figures, len(figures), title(1, "pressure (MPa) and temperature (K) of the target, lengths in 10 µm",
                                             [base], runs.quick))


def fig02(runs):
    base = runs.energy("base")
    fig = timeseries.plot_means(base, regions=ALL_REGIONS, title=title(
        2, "mean density, pressure, temperature, particle velocity; B bottom, T top domains", [base], runs.quick))
    overlay_paper_temperature(fig, _region_overlay(runs, "base", ALL_REGIONS))
    return fig


def fig03(runs):
    base, paper = runs.energy("base"), runs.paper("base")
    snapshot = base.snapshot(time=1150 * NS)
    top = _target_top_um(snapshot)
    window = (0.0, base.scene["width"] * LENGTH_FACTOR, top - 700.0, top + 20.0)
    figures = _field_panels(base, paper, 1150 * NS, [("a", "temperature", {})], window)
    return tile(figures, len(figures), title(3, "temperature near the top free surface", [base], runs.quick))


def fig04(runs):
    base = runs.energy("base")
    fig = timeseries.plot_stds(base, regions=BOTTOM_REGIONS, title=title(
        4, "standard deviations in the bottom domains", [base], runs.quick))
    overlay_paper_temperature(fig, _region_overlay(runs, "base", BOTTOM_REGIONS), stat="std")
    return fig


def fig05(runs):
    base = runs.energy("base")
    return floor_log_axes(timeseries.plot_dissipation(base, regions=BOTTOM_REGIONS, logy=True, title=title(
        5, "mean squared rotation, divergence and strain rate", [base], runs.quick)))


def _window_around_void(run, size_um=(400.0, 300.0)):
    """x0, x1, y0, y1 (um) around the target void nearest the paper's (510, 280) um, inside the column."""
    width = run.scene["width"] * LENGTH_FACTOR
    x, y = FIG6_VOID_UM
    voids = run.voids()
    target = voids["body"] == "target"
    if target.any():
        vx, vy = voids["x"][target] * LENGTH_FACTOR, voids["y"][target] * LENGTH_FACTOR
        gap = np.abs(vx - x)
        nearest = np.argmin(np.hypot(np.minimum(gap, width - gap), vy - y))
        x, y = vx[nearest], vy[nearest]
    w = min(size_um[0], width)
    x0 = min(max(x - w / 2, 0.0), width - w)
    y0 = max(y - size_um[1] / 2, 0.0)
    return x0, x0 + w, y0, y0 + size_um[1]


def fig06(runs):
    base, paper = runs.energy("base"), runs.paper("base")
    panels = [("a", "density", {}), ("b", "pressure", {}), ("c", "temperature", {}),
              ("d", "speed", {"arrows": True, "arrow_scale": ARROW_UM_PER_MPS})]
    figures = _field_panels(base, paper, 750 * NS, panels, _window_around_void(base))
    return tile(figures, 3 if len(figures) > 4 else 2, title(
        6, "a portion near the bottom; (d) arrows 50 × the particle velocity (u in µm/ns × 50 ns)",
        [base], runs.quick))


def _compare_figure(runs, number, what, cases, quantities, regions=("B800",), logy=False, offsets=None):
    compared = [runs.energy(case) for case in cases]
    labels = run_labels(compared)
    fig = plot_compare(compared, quantities=quantities, regions=regions, labels=labels, logy=logy, offsets=offsets,
                       title=title(number, what, compared, runs.quick, case="region " + ", ".join(regions)))
    if "temperature" in quantities:
        overlay_paper_temperature(fig, _compare_overlay(runs, cases, labels, regions))
    return fig


def fig07(runs):
    return _compare_figure(runs, 7, "mean temperature for three mean void sizes at δ = 1.03", VOID_SIZE_CASES,
                           ["temperature"], regions=("B800", "T800"))


def fig08(runs):
    return floor_log_axes(_compare_figure(runs, 8, "mean squared rotation and divergence for three mean void sizes",
                                          VOID_SIZE_CASES, ["rot2", "div2"], logy=True))


def fig09(runs):
    delta = runs.energy("delta1.4")
    fig = timeseries.plot_means(delta, regions=("B800", "T800"), title=title(
        9, "mean density, pressure, temperature, particle velocity", [delta], runs.quick))
    overlay_paper_temperature(fig, _region_overlay(runs, "delta1.4", ("B800", "T800")))
    return fig


def fig10(runs):
    delta = runs.energy("delta1.4")
    return floor_log_axes(timeseries.plot_dissipation(delta, regions=("B800",), logy=True, title=title(
        10, "mean squared rotation, divergence and strain rate", [delta], runs.quick)))


def fig11(runs):
    delta, paper = runs.energy("delta1.4"), runs.paper("delta1.4")
    times = [t * NS for t in (1200, 1250, 1300)]
    fig = plot_histograms([delta.snapshot(time=t) for t in times], "B800", title=title(
        11, "distributions in B800 at 1200, 1250, 1300 ns", [delta], runs.quick))
    if paper is not None:
        ax = _axis_labelled(fig, quantity("temperature").label(), which="x")
        samples = [region_values(paper.snapshot(time=t), "B800", "temperature") for t in times]
        edges = np.histogram_bin_edges(np.concatenate(samples), bins=50, range=central_range(np.concatenate(samples)))
        for i, (t, values) in enumerate(zip(times, samples)):
            _, _, skewness, kurtosis = moments(values)
            ax.hist(values, bins=edges, weights=np.full(values.size, 1.0 / (values.size * (edges[1] - edges[0]))),
                    histtype="step", color=COLORS[i % len(COLORS)], linestyle=":",
                    label=f"{PAPER_T} (dotted), {t / NS:.4g} ns: S={skewness:.2f}, K={kurtosis:.2f}")
        ax.legend(fontsize=6, loc="upper right")
    return fig


def fig12(runs):
    return _compare_figure(runs, 12, "mean density and temperature for four impact velocities, δ = 1.4",
                           VELOCITY_CASES, ["density", "temperature"])


def fig13(runs):
    offsets = {"density": [FIG13_DENSITY_OFFSETS.get(case, 0.0) for case in POROSITY_CASES]}
    return _compare_figure(runs, 13, "mean density and temperature for five porosities at 1000 m/s", POROSITY_CASES,
                           ["density", "temperature"], offsets=offsets)


CAPTIONS = {
    1: "Paper: pressure (MPa) and temperature (K) at 250 ns, delta 1.03, lengths in 10 um. Here: the lower "
       "2 mm of the target.",
    2: "Paper: mean density, pressure, temperature, particle velocity in B800/B400/B100 (filled symbols) and "
       "T800/T400/T100 (open symbols); first maximum 3.14 g/cm3, 16.7 GPa, 432 K at 250 ns, dip near 450 ns, "
       "top arrival near 800 ns, about 60 K left after release.",
    3: "Paper: temperature of the top portion at 1.15 us, with jets at the free surface.",
    4: "Paper: standard deviations in the bottom domains, rising fast and then decaying nearly exponentially.",
    5: "Paper: mean squared rotation, divergence and strain rate, decaying nearly exponentially to steady values.",
    6: "Paper: density, pressure, temperature and velocity field (arrows 50 x the particle velocity) at 750 ns, "
       "around a void near (510 um, 280 um). Here: the target void nearest that position in this layout.",
    7: "Paper: larger voids give a higher mean temperature at the same porosity (delta 1.03).",
    8: "Paper: the void size changes the transient of the squared rotation and divergence, not the steady values.",
    9: "Paper: at delta 1.4 the mean density and pressure fall after the first stage and the temperature rises "
       "faster.",
    10: "Paper: at delta 1.4, rotation dominates the transient dissipation; later the three are comparable.",
    11: "Paper: non-Gaussian distributions in B800 that change between 1200 and 1300 ns (dashed: the Gaussian "
        "of the same mean and deviation).",
    12: "Paper: the stronger the shock, the faster the density falls and the temperature rises (delta 1.4).",
    13: "Paper: mean density and temperature for delta 1.01 to 1.7 at 1000 m/s; the density of delta 1.1, 1.4, "
        "1.7 is moved up by 0.01, 0.1, 0.15 g/cm3 as in its left panel.",
}

FIGURE_MAKERS = {1: fig01, 2: fig02, 3: fig03, 4: fig04, 5: fig05, 6: fig06, 7: fig07, 8: fig08, 9: fig09,
                 10: fig10, 11: fig11, 12: fig12, 13: fig13}


def make_figures(numbers, runs, out_dir):
    """Writes DIR/figNN.png for each number; returns the paths."""
    paths = []
    for number in numbers:
        fig = FIGURE_MAKERS[number](runs)
        path = out_dir / f"fig{number:02d}.png"
        save_figure(fig, path, "png", DPI)
        paths.append(path)
    return paths
