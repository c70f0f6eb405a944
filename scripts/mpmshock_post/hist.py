"""Distributions of local density, pressure, temperature and velocity in one region at chosen
times, each with the Gaussian of the same mean and deviation drawn over it (paper Fig. 11)."""

import numpy as np

from .errors import PostError
from .labels import case_label
from .local import has_quantity, local_quantity
from .reader import void_count
from .regions import region_points
from .stats import moments
from .style import COLORS, add_resolution_note, note_missing, panel_figure, thermal_off
from .units import TIME, quantity

QUANTITIES = ("density", "pressure", "temperature", "velocity_x", "velocity_y")


def region_values(snapshot, region, name):
    """Display-unit values of one quantity at the region's points (NaN-free; empty if unavailable)."""
    points = region_points(snapshot, region)
    if points.size == 0:
        raise PostError(f"region '{region}' holds no material points at t = {snapshot.time * TIME.factor:g} ns")
    if not has_quantity(snapshot, name):
        return np.empty(0)
    values = local_quantity(snapshot, name)[points] * quantity(name).factor
    return values[np.isfinite(values)]


def distribution_moments(snapshots, region):
    """Rows (time in s, quantity, count, mean, std, skewness, excess kurtosis), display units."""
    rows = []
    for snapshot in snapshots:
        for name in QUANTITIES:
            values = region_values(snapshot, region, name)
            rows.append((snapshot.time, name, values.size) + moments(values))
    return rows


def moments_table(snapshots, region):
    """distribution_moments as a text table, saying which kurtosis it is."""
    lines = [f"# region {region}: moments over all its points, display units; "
             "kurtosis is the EXCESS kurtosis (0 for a Gaussian)",
             f"{'time_ns':>9} {'quantity':<12} {'unit':<6} {'count':>7} {'mean':>12} {'std':>12} "
             f"{'skewness':>10} {'excess_kurtosis':>16}"]
    for time, name, count, mean, std, skewness, kurtosis in distribution_moments(snapshots, region):
        lines.append(f"{time * TIME.factor:9.4g} {name:<12} {quantity(name).unit:<6} {count:7d} {mean:12.5g} "
                     f"{std:12.5g} {skewness:10.4g} {kurtosis:16.4g}")
    return "\n".join(lines)


def central_range(values):
    lo, hi = np.percentile(values, [0.5, 99.5])
    return (lo, hi) if hi > lo else (lo - 0.5, hi + 0.5)


def _gaussian(x, mean, std):
    return np.exp(-0.5 * ((x - mean) / std) ** 2) / (std * np.sqrt(2.0 * np.pi))


def plot_histograms(snapshots, region, bins=50, title=None, run_name=None):
    """One panel per quantity, one histogram (probability density) per snapshot time: x in the
    quantity's display unit, y in its inverse (cm³/g for density). The footer states the run's
    resolution."""
    fig, axes = panel_figure(len(QUANTITIES), ncols=3)
    for ax, name in zip(axes, QUANTITIES):
        q = quantity(name)
        samples = [region_values(snapshot, region, name) for snapshot in snapshots]
        finite = [values for values in samples if values.size]
        if not finite:
            note_missing(ax, "thermal model off" if thermal_off(name, [s.scene for s in snapshots]) else "no data")
            ax.set_xlabel(q.label())
            continue
        # Shared bin edges, so that the times compare bin by bin, over the central 99% of the
        # points: hot spots at collapsed voids lie ten deviations out and would squeeze the bulk of
        # the distribution into a few bins. The moments still use every point.
        edges = np.histogram_bin_edges(np.concatenate(finite), bins=bins,
                                       range=central_range(np.concatenate(finite)))
        x = np.linspace(edges[0], edges[-1], 400)
        for i, (snapshot, values) in enumerate(zip(snapshots, samples)):
            if not values.size:
                continue
            color = COLORS[i % len(COLORS)]
            mean, std, skewness, kurtosis = moments(values)
            # Normalised by all points, not only those inside the drawn range, so that the
            # histogram and the Gaussian are both densities of the whole region.
            weights = np.full(values.size, 1.0 / (values.size * (edges[1] - edges[0])))
            ax.hist(values, bins=edges, weights=weights, histtype="step", color=color,
                    label=f"{snapshot.time * TIME.factor:.4g} ns: S={skewness:.2f}, K={kurtosis:.2f}")
            if std > 0:
                ax.plot(x, _gaussian(x, mean, std), color=color, linestyle="--", linewidth=1)
        ax.set_xlabel(q.label())
        ax.set_ylabel(density_label(q))
        ax.legend(fontsize=7, loc="upper right")
    axes[-1].text(0.05, 0.5, f"region {region}\n\nsolid: histogram of the local values\n"
                  "dashed: Gaussian of the same mean\nand standard deviation\n\n"
                  "S: skewness\nK: excess kurtosis (0 for a Gaussian)\n"
                  "(over all points; the axes show\nthe central 99% of them)",
                  transform=axes[-1].transAxes, va="center", fontsize=9)
    scene = snapshots[0].scene
    if title is None:
        case = case_label(scene, void_count(snapshots[0].path.parent)) if scene is not None else ""
        title = ": ".join(part for part in (run_name, case) if part)
    fig.suptitle(title)
    add_resolution_note(fig, [scene])
    return fig


def density_label(q):
    """The y label of a histogram of q normalised to unit area: 'probability density (cm$^3$/g)'."""
    inverse = q.inverse_unit()
    return f"probability density ({inverse})" if inverse else "probability density"
