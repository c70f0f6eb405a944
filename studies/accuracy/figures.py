"""The accuracy study's figures (docs/accuracy_*.png): errors against cell size and cost, porous
plateaus against h/r, the sensitivity to the numerical parameters, the paper's base case and its
cost, and the plateau windows. Each takes the series' Outcomes and the path of the PNG.

Part of the study in studies/accuracy/ of the checkout, run as `studies/accuracy/accuracy-study`;
sections.py places them in the report.
"""

import math

import numpy as np

from mpmshock_post.reader import Run

from .formats import RELATIVE, unit_of
from .measure import plateau
from .plan import NS, REGION, UM

SHAPE_COLORS = {"bspline2_domain": "tab:purple", "bspline2": "tab:blue", "gimp": "tab:green", "bilinear": "tab:red"}
PPC_STYLES = {1: ":", 2: "-", 3: "--"}


def _porous_style(o):
    """Colour, line style, markers, label and h/r shift of a porous series: the shape's colour, solid
    lines and dots for the main shape and the other shapes; where a comparison changes more than the
    shape (the main shape without volumetric smoothing) the same colour dashed, open squares, and h/r
    shifted by 4 % so that its error bars stand beside the main shape's."""
    info = o.series.info
    comparison = info.get("comparison")
    color = SHAPE_COLORS[info["shape"]]
    style = dict(color=color, linestyle="-", marker="o", mfc=color)
    if comparison and comparison.scene:
        style.update(linestyle="--", marker="s", mfc="none")
    return style, info.get("label", info["shape"]), 1.04 if comparison and comparison.scene else 1.0


def _figure(nrows, ncols, size=(3.3, 2.6)):
    """A grid of panels and, below it, a strip for the shared legend (fig.legend_strip)."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=(size[0] * ncols, size[1] * nrows + 0.9), layout="constrained")
    grid = fig.add_gridspec(nrows + 1, ncols, height_ratios=[size[1]] * nrows + [0.6])
    axes = np.array([[fig.add_subplot(grid[r, c]) for c in range(ncols)] for r in range(nrows)])
    strip = fig.add_subplot(grid[nrows, :])
    strip.axis("off")
    fig.legend_strip = strip
    return fig, axes


def _cell_axis(ax, cells_um):
    """Log x axis labelled at the cell sizes themselves, without minor tick labels."""
    import matplotlib.ticker
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(sorted(cells_um)))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{c:g}" for c in sorted(cells_um)]))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())


def _legend(fig, handles, labels, ncol):
    fig.legend_strip.legend(handles, labels, loc="center", ncol=ncol, fontsize=7, frameon=False)


def _legend_of_all(fig, axes, ncol):
    """One legend for every panel: each label once, with the first panel's handle that has it."""
    handles, labels = [], []
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(handle)
                labels.append(label)
    _legend(fig, handles, labels, ncol)


def _save(fig, path):
    fig.savefig(path, dpi=90)
    return path


def _error_scale(quantity, exact):
    """Plotted error: % of the exact value, or K."""
    return (100.0 / abs(exact), "%") if RELATIVE.get(quantity) else (1.0, unit_of(quantity))


SOLID_PLOTTED = ("pressure_mean", "macro_normal_stress", "density_mean", "temperature_mean")


def _solid_label(o):
    return f"{o.series.info['shape']} ppc {o.series.info['ppc']}"


def figure_solid_h(solid, path):
    """|error| of the solid plateaus against cell size, a column per speed, a row per quantity."""
    speeds = sorted({o.series.info["velocity"] for o in solid})
    fig, axes = _figure(len(SOLID_PLOTTED), len(speeds))
    for col, v in enumerate(speeds):
        for row, q in enumerate(SOLID_PLOTTED):
            ax = axes[row, col]
            for o in (o for o in solid if o.series.info["velocity"] == v):
                scale, unit = _error_scale(q, o.series.exact[q])
                errors = np.abs(np.array(o.results[q].values) - o.series.exact[q]) * scale
                hs = np.array(o.h) / UM
                keep = errors > 0
                ax.loglog(hs[keep], errors[keep], marker="o", ms=3, color=SHAPE_COLORS[o.series.info["shape"]],
                          linestyle=PPC_STYLES[o.series.info["ppc"]], label=_solid_label(o))
            h = np.array([min(min(o.h) for o in solid) / UM, max(max(o.h) for o in solid) / UM])
            ax.set_title(f"{q}, {v:g} m/s", fontsize=8)
            ax.set_xlabel("cell size (um)", fontsize=7)
            ax.set_ylabel(f"|error| ({unit})", fontsize=7)
            ax.tick_params(labelsize=6)
            lo, hi = ax.get_ylim()
            for p, ls in ((1, (0, (1, 3))), (2, (0, (4, 4)))):
                ref = hi * 0.5 * (h / h[-1]) ** p
                ax.loglog(h, ref, color="gray", lw=0.6, linestyle=ls, label=f"slope {p}")
            ax.set_ylim(lo, hi)
            _cell_axis(ax, sorted({c / UM for o in solid for c in o.h}))   # after loglog, which resets the ticks
    _legend_of_all(fig, axes, 6 if len(speeds) > 1 else 2)   # one narrow column: two
    return _save(fig, path)


def figure_solid_cost(solid, path):
    """|error| of the solid plateaus at 1000 m/s against the wall time of the run."""
    at = [o for o in solid if o.series.info["velocity"] == 1000.0]
    fig, axes = _figure(1, len(SOLID_PLOTTED), size=(3.4, 2.9))
    for col, q in enumerate(SOLID_PLOTTED):
        ax = axes[0, col]
        for o in at:
            scale, unit = _error_scale(q, o.series.exact[q])
            errors = np.abs(np.array(o.results[q].values) - o.series.exact[q]) * scale
            walls = np.array([o.wall(k) for k in range(len(o.levels))])
            keep = (errors > 0) & (walls > 0)
            ax.loglog(walls[keep], errors[keep], marker="o", ms=3, color=SHAPE_COLORS[o.series.info["shape"]],
                      linestyle=PPC_STYLES[o.series.info["ppc"]], label=_solid_label(o))
        ax.set_title(f"{q}, 1000 m/s", fontsize=8)
        ax.set_xlabel("wall time of the run (s, 2 cores)", fontsize=7)
        ax.set_ylabel(f"|error| ({unit})", fontsize=7)
        ax.tick_params(labelsize=6)
    _legend_of_all(fig, axes, 5)
    return _save(fig, path)


POROUS_PLOTTED = ("macro_normal_stress", "pressure_mean", "macro_density", "density_mean", "temperature_mean")


def figure_porous(porous, r, path):
    """Porous plateaus against h/r (r the void radius): seed means, single layouts, limits, full compaction."""
    import matplotlib.ticker
    deltas = sorted({o.series.info["delta"] for o in porous})
    fig, axes = _figure(len(POROUS_PLOTTED), len(deltas), size=(3.3, 2.3))
    for col, delta in enumerate(deltas):
        for row, q in enumerate(POROUS_PLOTTED):
            ax = axes[row, col]
            for o in (o for o in porous if o.series.info["delta"] == delta):
                res = o.results[q]
                style, label, shift = _porous_style(o)
                color = style["color"]
                hr = np.array(o.h) / r * shift
                factor = 1e-9 if unit_of(q) == "GPa" else 1.0
                ax.errorbar(hr, np.array(res.values) * factor, yerr=np.array(res.standard_errors) * factor,
                            ms=3, capsize=2, label=f"{label} (seed mean)", **style)
                for k, paths in enumerate(o.run_dirs):
                    for path_ in paths:
                        ax.plot(hr[k], plateau(path_, q, o.series.window) * factor, ".", color=color, ms=2, alpha=0.5)
                if math.isfinite(res.estimate.order):
                    ax.plot([hr[-1] / 2], [res.estimate.extrapolated * factor], "*", color=color, ms=7,
                            label="extrapolated (observed order)")
                exact = o.series.exact.get(q)
            if exact is not None:
                ax.axhline(exact * factor, color="k", lw=0.8, linestyle="--", label="full-compaction Hugoniot")
            ax.set_xscale("log")
            ax.set_xticks([0.0625, 0.125, 0.25, 0.5, 1.0])
            ax.set_xticklabels(["1/16", "1/8", "1/4", "1/2", "1"])
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())   # a narrow range labels them
            ax.set_xlim(hr[-1] / 2.8, hr[0] * 1.4)
            ax.set_title(f"{q}, delta {delta:g}", fontsize=8)
            ax.set_xlabel("h / r", fontsize=7)
            ax.set_ylabel(unit_of(q), fontsize=7)
            ax.tick_params(labelsize=6)
    _legend_of_all(fig, axes, 4 if len(deltas) > 1 else 1)   # one narrow column: one
    return _save(fig, path)


SENSITIVITY_PLOTTED = ("macro_normal_stress", "pressure_mean", "macro_density", "temperature_mean", "temperature_std",
                       "velocity_y_std")


def figure_sensitivity(groups, path):
    """Plateaus against each numerical parameter (groups: param -> [Outcome per value])."""
    fig, axes = _figure(len(SENSITIVITY_PLOTTED), len(groups), size=(3.0, 2.0))
    for col, (param, group) in enumerate(groups.items()):
        values = [o.series.info["value"] for o in group]
        for row, q in enumerate(SENSITIVITY_PLOTTED):
            ax = axes[row, col]
            factor = 1e-9 if unit_of(q) == "GPa" else 1.0
            ax.plot(values, [o.value(q, 0) * factor for o in group], "o-", color="tab:blue", ms=3, label="layout mean")
            for value, o in zip(values, group):
                for p in o.run_dirs[0]:
                    ax.plot(value, plateau(p, q, o.series.window) * factor, ".", color="tab:gray", ms=3,
                            label="one layout")
            if param == "av":
                ax.set_xscale("log", base=2)
            ax.set_title(q, fontsize=8)
            ax.set_xlabel(group[0].series.info["label"], fontsize=7)
            ax.set_ylabel(unit_of(q), fontsize=7)
            ax.tick_params(labelsize=6)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    _legend(fig, list(unique.values()), list(unique.keys()), 2)
    return _save(fig, path)


def figure_windows(cases, path):
    """Band time series of the finest level (first seed) with the plateau window shaded."""
    fig, axes = _figure(2, len(cases), size=(2.6, 2.3))
    for col, (title, o) in enumerate(cases):
        run_dir = o.run_dirs[-1][0]
        columns = Run(run_dir).regions()[REGION]
        t = columns["time"] / NS
        t0, t1 = o.series.window
        for row, (qs, unit, factor) in enumerate(((("pressure_mean", "macro_normal_stress"), "GPa", 1e-9),
                                                   (("temperature_mean",), "K", 1.0))):
            ax = axes[row, col]
            for q, color in zip(qs, ("tab:blue", "tab:orange")):
                ax.plot(t, columns[q] * factor, color=color, lw=0.9, label=q)
                exact = o.series.exact.get(q)
                if exact is not None and (q == "macro_normal_stress" or row == 1):
                    ax.axhline(exact * factor, color="k", lw=0.7, linestyle="--", label="exact / full compaction")
            ax.axvspan(t0 / NS, t1 / NS, color="tab:green", alpha=0.15, label="plateau window")
            ax.set_title(f"{title}, h = {o.h[-1] / UM:g} um", fontsize=7)
            ax.set_xlabel("t (ns)", fontsize=7)
            ax.set_ylabel(unit, fontsize=7)
            ax.tick_params(labelsize=6)
    _legend_of_all(fig, axes, 5 if len(cases) > 1 else 2)   # one narrow column: two
    return _save(fig, path)


def figure_answer(o, table, path):
    """The reduced column's plateaus against cell size, and the full geometry's cost (table: the cost
    model's rows)."""
    fig, axes = _figure(1, 3, size=(3.4, 2.8))
    hs = np.array(o.h) / UM
    for ax, q in zip(axes[0, :2], ("pressure_mean", "temperature_mean")):
        res = o.results[q]
        factor = 1e-9 if unit_of(q) == "GPa" else 1.0
        ax.errorbar(hs, np.array(res.values) * factor, yerr=np.array(res.standard_errors) * factor, marker="o",
                    ms=3, capsize=2, label="seed mean, standard error")
        for k, paths in enumerate(o.run_dirs):
            for p in paths:
                ax.plot(hs[k], plateau(p, q, o.series.window) * factor, ".", color="tab:gray", ms=3,
                        label="one layout")
        ax.axhline(res.estimate.extrapolated * factor, color="tab:blue", lw=0.7, linestyle=":",
                   label="limit (extrapolated or finest)")
        ax.axhline(o.series.exact[q] * factor, color="k", lw=0.7, linestyle="--", label="full-compaction Hugoniot")
        _cell_axis(ax, hs)
        ax.set_xlabel("cell size (um)", fontsize=7)
        ax.set_ylabel(unit_of(q), fontsize=7)
        ax.set_title(f"{q}, reduced column", fontsize=8)
        ax.tick_params(labelsize=6)
    ax = axes[0, 2]
    ax.loglog([c["h"] / UM for c in table], [c["core_minutes"] for c in table], "o-")
    _cell_axis(ax, [c["h"] / UM for c in table])
    ax.set_xlabel("cell size (um)", fontsize=7)
    ax.set_ylabel("core-minutes, full geometry", fontsize=7)
    ax.set_title("cost of configs/paper_base.scene", fontsize=8)
    ax.tick_params(labelsize=6)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    _legend(fig, list(unique.values()), list(unique.keys()), 4)
    return _save(fig, path)
