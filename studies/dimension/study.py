"""dimension-study: studies/dimension/dimension.scene in 2D (cylindrical voids, plane strain) and 3D
(spherical voids) at equal porosity and void radius, at two resolutions each, and a markdown table
of the plateau (pressure, density, mean temperature and its spread across points) and the cost.

Each number is the mean of the plateau region's samples at 100 and 110 ns; its accuracy is the
change from cells of r/2 to cells of r/4 (the coarse run is the finer's check, not a result).
Finished runs in --out are reused (summary.json with exit code 0), so an interrupted study goes on
(give a new --out when --set changes).
"""

import argparse
import csv
import json
import subprocess
import sys
import time
from pathlib import Path

from mpmshock_post.errors import PostError
from mpmshock_post.resolve import mpmshock_binary

SCENE = Path(__file__).resolve().parent / "dimension.scene"
POROSITIES = (1.1, 1.4)
CELLS_UM = (10, 5)  # the default pair; --cells chooses another
WIDTH_2D = "2 mm"
WIDTH_3D = "0.2 mm"
TIMES = (100e-9, 110e-9)
QUANTITIES = (("pressure_mean", "pressure (GPa)", 1e-9), ("density_mean", "density (g/cm3)", 1e-3),
              ("temperature_mean", "temperature (K)", 1.0), ("temperature_std", "T spread across points (K)", 1.0))


def run_name(dimension, porosity, cell_um):
    return f"{dimension}d_delta{porosity}_h{cell_um:g}um"


def settings(dimension, porosity, cell_um, out, extra):
    width = WIDTH_2D if dimension == 2 else WIDTH_3D
    return [f"dimension={dimension}", f"porosity={porosity}", f"cell_size={cell_um} um", f"width={width}",
            f"depth={WIDTH_3D}", *extra, f"output_dir={out}"]


def run(binary, dimension, porosity, cell_um, root, extra, say):
    out = root / run_name(dimension, porosity, cell_um)
    summary = out / "summary.json"
    if summary.exists() and json.loads(summary.read_text()).get("exit_code") == 0:
        say(f"{out.name}: reused")
        return out
    command = [str(binary), str(SCENE), "--force", "--quiet"]
    for s in settings(dimension, porosity, cell_um, out, extra):
        command += ["--set", s]
    say(f"{out.name}: running")
    started = time.monotonic()
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise PostError(f"{out.name}: mpmshock exited {result.returncode}: {result.stderr.strip()}")
    say(f"{out.name}: finished in {time.monotonic() - started:.0f} s")
    return out


def plateau(out):
    """Quantity -> mean of the plateau region's rows at TIMES."""
    rows = [r for r in csv.DictReader(open(out / "regions.csv")) if r["region"] == "plateau"
            and any(abs(float(r["time"]) - t) < 1e-12 for t in TIMES)]
    if len(rows) != len(TIMES):
        raise PostError(f"{out}: regions.csv lacks the plateau at {TIMES}")
    return {q: sum(float(r[q]) for r in rows) / len(rows) for q, _, _ in QUANTITIES}


def table(root, cells_um):
    change = f"change from {cells_um[0]:g} to {cells_um[1]:g} um cells"
    lines = [f"| porosity | quantity | 2D | 2D {change} | 3D | 3D {change} | 3D - 2D | 3D - 2D at {cells_um[0]:g} um |",
             "|---|---|---|---|---|---|---|---|"]
    costs = ["| run | points (simulated) | steps | wall time (s) | point-steps/s (M) |", "|---|---|---|---|---|"]
    for porosity in POROSITIES:
        values = {}
        for dimension in (2, 3):
            for cell in cells_um:
                out = root / run_name(dimension, porosity, cell)
                values[dimension, cell] = plateau(out)
                s = json.loads((out / "summary.json").read_text())
                costs.append(f"| {out.name} | {s['material_points']} | {s['steps']} | {s['wall_seconds']:.1f} | "
                             f"{s['point_steps_per_second'] / 1e6:.2f} |")
        coarse, fine = cells_um
        for q, label, scale in QUANTITIES:
            cells = [f"{porosity}", label]
            for dimension in (2, 3):
                f, c = values[dimension, fine][q] * scale, values[dimension, coarse][q] * scale
                cells += [f"{f:.4g}", f"{f - c:+.3g} ({100 * (f - c) / c:+.1f} %)"]
            for cell in (fine, coarse):
                d2, d3 = values[2, cell][q] * scale, values[3, cell][q] * scale
                cells.append(f"{d3 - d2:+.3g} ({100 * (d3 - d2) / d2:+.1f} %)")
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n", "\n".join(costs) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="dimension-study", description=__doc__.split("\n\n")[0],
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("--out", required=True, type=Path, metavar="DIR", help="output directory")
    parser.add_argument("--cells", default=",".join(str(c) for c in CELLS_UM), metavar="COARSE,FINE",
                        help="the two cell sizes in um (default %(default)s: r/2 and r/4)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a scene key for every run (repeatable), e.g. --set spall=on")
    args = parser.parse_args(argv)
    say = lambda text: print(f"dimension-study: {text}", file=sys.stderr, flush=True)  # noqa: E731
    try:
        cells_um = tuple(float(c) for c in args.cells.split(","))
        if len(cells_um) != 2 or not cells_um[0] > cells_um[1] > 0:
            raise PostError(f"--cells {args.cells}: give COARSE,FINE in um, coarse first")
        binary = mpmshock_binary()
        args.out.mkdir(parents=True, exist_ok=True)
        for porosity in POROSITIES:
            for cell in cells_um:
                for dimension in (2, 3):
                    run(binary, dimension, porosity, cell, args.out.resolve(), args.set, say)
        plateau_table, cost_table = table(args.out.resolve(), cells_um)
        extra = f", with {', '.join(args.set)}" if args.set else ""
        text = (f"## Plateau at 100-110 ns (region y = 100-250 um, 1000 m/s, r = 20 um{extra}; "
                f"values at {cells_um[1]:g} um cells)\n\n{plateau_table}\n"
                f"## Cost\n\n{cost_table}")
        (args.out / "dimension-study.md").write_text(text)
        print(text)
    except PostError as e:
        print(f"dimension-study: error: {e}", file=sys.stderr)
        return 2
    return 0
