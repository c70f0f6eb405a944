"""mpmshock-plot KIND RUN_DIR... [options]: the paper's figures from mpmshock run directories.

Each kind is a subcommand with its own --help. Bad input (a missing directory, an unknown region,
no snapshot near a time) ends with one line on stderr and exit status 1; usage errors exit 2.
"""

import argparse
import os
import sys
from pathlib import Path

import matplotlib
import numpy as np

from . import timeseries
from .compare import plot_compare
from .errors import PostError, argument_type
from .field import plot_field, slice_points
from .hist import moments_table, plot_histograms
from .probes import PROBE_QUANTITIES, plot_probes
from .reader import Run
from .style import FORMATS, save_figure
from .units import parse_length, parse_time

_UNITS = ("Units as in the paper: density g/cm3, pressure GPa, temperature K, velocity m/s, "
          "time ns, length um, squared rotation/divergence/strain rate 1/ns^2.")


def _list(text):
    return [item.strip() for item in text.split(",") if item.strip()]


_argument = argument_type


def _numbers(count, what):
    def numbers(text):
        values = [float(v) for v in text.split(",")]
        if len(values) != count:
            raise PostError(f"{what} needs {count} comma-separated numbers, got '{text}'")
        return values
    numbers.__name__ = what
    return numbers


def _positive_int(text):
    value = int(text)
    if value < 1:
        raise PostError(f"{text} is not a positive whole number")
    return value


def _positive_float(text):
    value = float(text)
    if not value > 0:
        raise PostError(f"{text} is not a positive number")
    return value


def _colormap(name):
    if name not in matplotlib.colormaps:
        raise PostError(f"no matplotlib colour map '{name}' (e.g. turbo, viridis, inferno, coolwarm)")
    return name


def _slice(text):
    """('z', metres) from 'z=50um', 'z=0.05mm' or 'z=5e-5' (a bare number is in metres)."""
    axis, sep, value = text.partition("=")
    if not sep or axis.strip() != "z":
        raise PostError(f"slice '{text}': give z=VALUE, e.g. z=50um (only slices at a plane of constant z, "
                        "drawn in the x-y plane, are supported)")
    return "z", parse_length(value)


def _times(text):
    return [parse_time(t) for t in _list(text)]


def _time_range(text):
    times = _times(text)
    if len(times) != 2 or times[0] >= times[1]:
        raise PostError(f"time range '{text}' needs T0,T1 with T0 < T1, e.g. 0ns,600ns")
    return times


def build_parser():
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-o", "--output", help="output file (default: KIND-based name in the first run "
                        "directory, or in the current directory if that is not writable)")
    common.add_argument("--format", choices=FORMATS, help="image format (default: from -o, else png)")
    common.add_argument("--title", help="figure title (default: run name and case)")
    common.add_argument("--dpi", type=_argument(_positive_int), default=150,
                        help="resolution of PNG output (default 150)")

    over_time = argparse.ArgumentParser(add_help=False)
    over_time.add_argument("--regions", type=_list, default=[],
                           help="comma-separated regions of regions.csv, e.g. B800,T800 (default: all)")
    over_time.add_argument("--trange", type=_argument(_time_range), metavar="T0,T1",
                           help="time window, e.g. 0ns,600ns")
    over_time.add_argument("--logy", action="store_true", help="logarithmic y axes")

    parser = argparse.ArgumentParser(
        prog="mpmshock-plot", description="Plots of mpmshock runs, after Xu et al., 'Simulation study "
        "of shock reaction on porous material'.", epilog=_UNITS + " Run 'mpmshock-plot KIND --help' "
        "for the options of a kind.")
    kinds = parser.add_subparsers(dest="kind", required=True, metavar="KIND")

    def kind(name, summary, parents, runs="one"):
        sub = kinds.add_parser(name, parents=parents, help=summary, description=summary, epilog=_UNITS)
        if runs == "one":
            sub.add_argument("run_dir", metavar="RUN_DIR", help="an mpmshock output directory")
        else:
            sub.add_argument("run_dirs", metavar="RUN_DIR", nargs="+", help="mpmshock output directories")
        return sub

    kind("timeseries", "mean density, pressure, temperature and particle velocity against time in "
         "the measured domains (paper Fig. 2, 9)", [common, over_time])
    kind("std", "standard deviations of density, pressure, temperature and particle velocity in the "
         "measured domains (paper Fig. 4)", [common, over_time])
    kind("dissipation", "mean squared rotation, divergence and strain rate in the measured domains "
         "(paper Fig. 5, 10)", [common, over_time])

    field = kind("field", "one snapshot coloured by a local quantity, optionally with velocity arrows "
                 "(paper Fig. 1, 3, 6); of a 3D run, the slice of points at a plane of constant z", [common])
    which = field.add_mutually_exclusive_group()
    which.add_argument("--snapshot", type=int, metavar="INDEX",
                       help="snapshot number NNNNN of snapshot_NNNNN.h5; negative counts from the end "
                       "(default: the last)")
    which.add_argument("--time", type=_argument(parse_time), metavar="T",
                       help="the snapshot nearest T, e.g. 750ns or 1.15us")
    field.add_argument("--color", default="density",
                       help="density, pressure, temperature, velocity_x, velocity_y, velocity_z (3D), speed, "
                       "rot2, div2, strain_rate2, plastic_strain, damage, ... (default density)")
    field.add_argument("--arrows", action="store_true", help="draw velocity arrows")
    field.add_argument("--arrow-scale", type=float, metavar="UM_PER_MPS",
                       help="arrow length in um per m/s of velocity (default: a typical speed is one "
                       "arrow spacing long)")
    field.add_argument("--window", type=_argument(_numbers(4, "window")), metavar="X0,X1,Y0,Y1",
                       help="part of the body to show, in um (default: all of it)")
    field.add_argument("--body", choices=("all", "target", "flyer", "window"), default="all",
                       help="which body to draw (default all)")
    field.add_argument("--clim", type=_argument(_numbers(2, "clim")), metavar="LO,HI",
                       help="colour limits in display units (default: the central 99%% of the points)")
    field.add_argument("--cmap", type=_argument(_colormap), default="turbo",
                       help="matplotlib colour map (default turbo)")
    field.add_argument("--unit", help="another unit for the colour: MPa for pressure (as the paper's "
                       "Fig. 1), kg/m3 for density (default: the paper's units)")
    field.add_argument("--length-unit", type=_argument(_positive_float), default=1.0, metavar="UM",
                       help="length unit of the axes in um, e.g. 10 as in the paper's Fig. 1 (default 1)")
    field.add_argument("--true-size", action="store_true",
                       help="draw each point as a square of its current area, so that unclosed slits "
                       "show (default: slightly enlarged squares that tile compressed material)")
    field.add_argument("--slice", type=_argument(_slice), metavar="z=Z",
                       help="3D runs only: draw the points within half a point spacing "
                       "a = cell_size / particles_per_cell of the plane z = Z, i.e. Z - a/2 <= z < Z + a/2 "
                       "periodic in z, in the x-y plane; Z with a unit (z=50um, z=0.05mm) or in metres "
                       "(default for 3D runs: mid-depth, moved to the nearest layer of initial points)")

    hist = kind("hist", "distributions of density, pressure, temperature and velocity in one region "
                "at given times, with the Gaussian of the same mean and deviation; prints skewness and "
                "excess kurtosis (paper Fig. 11)", [common])
    hist.add_argument("--region", "--regions", dest="region",
                      help="one region of the scene, e.g. B800, or a spec 'bottom 100um 800um' "
                      "(default: the first region)")
    hist.add_argument("--times", type=_argument(_times), metavar="T1,T2,...",
                      help="snapshot times, e.g. 1200ns,1250ns,1300ns (default: the last snapshot)")
    hist.add_argument("--bins", type=_argument(_positive_int), default=50, help="number of bins (default 50)")

    compare = kind("compare", "one or more region-averaged quantities from several runs on shared axes, "
                   "legends from what differs between the scenes (paper Fig. 7, 8, 12, 13)",
                   [common], runs="many")
    compare.add_argument("--quantity", "--quantities", dest="quantities", type=_list, default=["density"],
                         help="comma-separated: density, pressure, temperature, velocity_x, velocity_y, "
                         "rot2, div2, strain_rate2, or X_std (default density)")
    compare.add_argument("--regions", type=_list, default=[],
                         help="comma-separated regions (default: the first run's first region)")
    compare.add_argument("--labels", type=_list, help="comma-separated legend entries, one per run")
    compare.add_argument("--trange", type=_argument(_time_range), metavar="T0,T1", help="time window")
    compare.add_argument("--logy", action="store_true", help="logarithmic y axes")

    probe = kind("probe", "probe histories from probes.csv (probe.NAME scene keys): by default the "
                 "free-surface velocity against time, as a VISAR or PDV records it; several runs overlaid",
                 [common], runs="many")
    probe.add_argument("--probes", type=_list, default=[],
                       help="comma-separated probes of probes.csv, e.g. free_surface (default: all)")
    probe.add_argument("--quantity", choices=PROBE_QUANTITIES, default="velocity_y",
                       help="what to plot (default velocity_y, in m/s)")
    probe.add_argument("--trange", "--time-range", dest="trange", type=_argument(_time_range), metavar="T0,T1",
                       help="time window, e.g. 150ns,420ns")
    probe.add_argument("--labels", type=_list, help="comma-separated legend entries, one per run")
    probe.add_argument("--target-frame", action="store_true",
                       help="add the scene's velocity to u_y: the record of a target at rest (0 before "
                       "the shock arrives), as an experiment measures it")
    return parser


def _output_path(args, stem, run_dir):
    """-o as given (its suffix sets the format unless --format does), else STEM.FORMAT in the run
    directory, or in the current one where the run directory is read-only."""
    fmt = args.format
    if args.output:
        path = Path(args.output)
        suffix = path.suffix.lstrip(".").lower()
        if suffix in FORMATS:
            if fmt and fmt != suffix:
                raise PostError(f"-o {args.output} contradicts --format {fmt}")
            return path, suffix
        fmt = fmt or "png"
        return path.with_name(f"{path.name}.{fmt}"), fmt
    fmt = fmt or "png"
    folder = Path(run_dir) if os.access(run_dir, os.W_OK) else Path.cwd()
    return folder / f"{stem}.{fmt}", fmt


def _series(args):
    run = Run(args.run_dir)
    plot = {"timeseries": timeseries.plot_means, "std": timeseries.plot_stds,
            "dissipation": timeseries.plot_dissipation}[args.kind]
    fig = plot(run, regions=args.regions, trange=args.trange, logy=args.logy, title=args.title)
    return fig, args.kind, run.path


def _field(args):
    run = Run(args.run_dir)
    snapshot = run.snapshot(time=args.time) if args.time is not None else run.snapshot(args.snapshot)
    slice_z = None
    if args.slice is not None:
        if snapshot.dimension != 3:
            raise PostError(f"--slice {args.slice[0]}=...: {run.path} is a 2D run (dimension = 2, plane strain); "
                            "its points already lie in the x-y plane, --slice is for 3D runs (dimension = 3)")
        slice_z = args.slice[1]
    if snapshot.dimension == 3:
        slab = slice_points(snapshot, slice_z)
        print(f"{slab.describe()} (z0 - a/2 <= z < z0 + a/2, periodic in z): "
              f"{int(slab.inside.sum())} of {len(slab.inside)} points")
        a = 2.0 * slab.half
        layer = (np.floor(slab.z / a) + 0.5) * a  # the initial layer of points whose spacing holds z0
        if abs(slab.z - layer) > 0.25 * a:
            below, above = (layer, layer + a) if slab.z > layer else (layer - a, layer)
            print(f"note: z = {slab.z * 1e6:.4g} µm lies between the layers of points at "
                  f"{below % slab.depth * 1e6:.4g} and {above % slab.depth * 1e6:.4g} µm; the slice may hold "
                  f"parts of both (--slice z={layer * 1e6:.4g}um takes one whole layer)")
        slice_z = slab.z
    fig = plot_field(snapshot, color=args.color, arrows=args.arrows, arrow_scale=args.arrow_scale,
                     window_um=args.window, body=args.body, clim=args.clim, cmap=args.cmap,
                     title=args.title, run_name=run.name, unit=args.unit, length_unit_um=args.length_unit,
                     true_size=args.true_size, slice_z=slice_z)
    return fig, f"field_{args.color}_{snapshot.index:05d}", run.path


def _hist(args):
    run = Run(args.run_dir)
    region = args.region or next(iter(run.scene.regions), None)
    if region is None:
        raise PostError(f"the scene of {run.path} defines no region; give --region")
    snapshots = [run.snapshot(time=t) for t in args.times] if args.times else [run.snapshot()]
    print(moments_table(snapshots, region))
    fig = plot_histograms(snapshots, region, bins=args.bins, title=args.title, run_name=run.name)
    safe_region = "".join(c if c.isalnum() else "_" for c in region)
    return fig, f"hist_{safe_region}", run.path


def _compare(args):
    runs = [Run(path) for path in args.run_dirs]
    fig = plot_compare(runs, quantities=args.quantities, regions=args.regions, labels=args.labels,
                       trange=args.trange, logy=args.logy, title=args.title)
    return fig, "compare_" + "_".join(args.quantities), runs[0].path


def _probe(args):
    runs = [Run(path) for path in args.run_dirs]
    fig = plot_probes(runs, probes=args.probes, quantity_name=args.quantity, trange=args.trange,
                      labels=args.labels, target_frame=args.target_frame, title=args.title)
    return fig, f"probe_{args.quantity}", runs[0].path


_KINDS = {"timeseries": _series, "std": _series, "dissipation": _series, "field": _field, "hist": _hist,
          "compare": _compare, "probe": _probe}


def main(argv=None):
    matplotlib.use("Agg")  # files only, never a window
    args = build_parser().parse_args(argv)
    try:
        fig, stem, run_dir = _KINDS[args.kind](args)
        path, fmt = _output_path(args, stem, run_dir)
        save_figure(fig, path, fmt, args.dpi)
    except (PostError, OSError) as e:
        print(f"mpmshock-plot {args.kind}: error: {e}", file=sys.stderr)
        return 1
    print(f"wrote {path}")
    return 0
