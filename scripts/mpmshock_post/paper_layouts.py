"""paper-layouts CASE=DIR [CASE=DIR ...]: how much the void layout alone moves the paper's numbers.

Each DIR is a finished run of a paper case (configs/paper/CASE.scene) with its own `seed`: runs of
one case with different seeds are layouts of the same sample, as a new sample would be in an
experiment. For each case this prints, in Markdown,
- B800's late-window means per layout (the last 300 ns, as comparison.csv's 'steady' values),
  with B800's own porosity at t = 0 and the full-compaction Hugoniot temperature at it;
- every number comparison.csv gives for that case alone, per layout, with the mean, the standard
  error of the mean over the layouts (SE) and the range.
The SE is the error a single-layout number carries beside docs/accuracy.md's discretisation error:
the paper's numbers come from one layout each.
"""

import argparse
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

from .errors import PostError, argument_type
from .paper_comparison import comparison_rows
from .paper_measures import BOTTOM, CaseRun, NotMeasured
from .paper_rows import fmt
from .reader import PaperTemperatureRun, has_paper_temperature

LATE_COLUMNS = (("T, energy (K)", "temperature_mean"), ("density (g/cm3)", "density_mean"),
                ("pressure (GPa)", "pressure_mean"), ("<Rot^2> (1/ns^2)", "rot2_mean"),
                ("<Div^2> (1/ns^2)", "div2_mean"))


def case_and_dir(text):
    case, sep, path = text.partition("=")
    if not sep or not case or not path:
        raise PostError(f"'{text}': expected CASE=DIR, e.g. base=output/paper/runs/base")
    if not (Path(path) / "regions.csv").is_file():
        raise PostError(f"{path}: not a run directory (no regions.csv)")
    return case, Path(path)


def late_means(case, path):
    """{column label: value} of B800's late window, with the band's porosity and its Hugoniot T."""
    run = CaseRun(case, path)
    values = {"seed": f"{float(run.scene.get('seed', 1)):.0f}"}
    try:
        state = run.band_hugoniot(BOTTOM)
        values["B800 delta at t = 0"] = state.porosity
        values["Hugoniot T there (K)"] = state.temperature
    except NotMeasured:
        pass
    for label, column in LATE_COLUMNS:
        values[label] = run.late_mean(BOTTOM, column).mean
        if column == "temperature_mean" and has_paper_temperature(path):
            paper = CaseRun(case, path, run=PaperTemperatureRun(path))
            values["T, paper (K)"] = paper.late_mean(BOTTOM, "temperature_mean").mean
    return values


def numeric_rows(case, path):
    """{(figure, quantity, unit): value} of the comparison rows that a campaign holding only this
    run gives a number for, less the theory rows (the same for every layout)."""
    with tempfile.TemporaryDirectory() as tmp:
        os.symlink(path.resolve(), Path(tmp) / case)
        rows = comparison_rows(Path(tmp))
    numbers = {}
    for row in rows:
        if row["quantity"].startswith("theory:"):
            continue
        try:
            numbers[(row["figure"], row["quantity"], row["unit"])] = float(row["mpmshock"])
        except ValueError:
            continue
    return numbers


def spread(values):
    """(mean, SE, range) over the layouts; SE is nan for a single layout."""
    a = np.asarray(values, dtype=float)
    se = a.std(ddof=1) / math.sqrt(a.size) if a.size > 1 else math.nan
    return a.mean(), se, a.max() - a.min()


def case_tables(case, paths):
    """The Markdown of one case: its late-means table and its comparison numbers over the layouts."""
    lines = [f"### {case}: {len(paths)} layout{'s' if len(paths) > 1 else ''}", ""]
    per_layout = [late_means(case, path) for path in paths]
    labels = [key for key in per_layout[0] if key != "seed"]
    lines += ["| seed | " + " | ".join(labels) + " |", "|---" * (len(labels) + 1) + "|"]
    for values in per_layout:
        lines.append(f"| {values['seed']} | " + " | ".join(fmt(values.get(k)) for k in labels) + " |")
    if len(paths) > 1:
        cells = []
        for key in labels:
            mean, se, _ = spread([values[key] for values in per_layout])
            cells.append(f"{fmt(mean)} ± {fmt(se, 2)}")
        lines.append("| mean ± SE | " + " | ".join(cells) + " |")
    numbers = [numeric_rows(case, path) for path in paths]
    common = [key for key in numbers[0] if all(key in n for n in numbers[1:])]
    if common:
        lines += ["", "| figure | quantity | unit | " + " | ".join(f"seed {v['seed']}" for v in per_layout)
                  + " | mean | SE | range |", "|---" * (len(paths) + 6) + "|"]
        for key in common:
            values = [n[key] for n in numbers]
            mean, se, width = spread(values)
            lines.append(f"| {key[0]} | {key[1]} | {key[2]} | " + " | ".join(fmt(v) for v in values)
                         + f" | {fmt(mean)} | {fmt(se, 2)} | {fmt(width, 3)} |")
    return lines + [""]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="paper-layouts", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", type=argument_type(case_and_dir), metavar="CASE=DIR",
                        help="a finished run of the paper case CASE (any seed); give each layout once")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    by_case = {}
    for case, path in args.runs:
        by_case.setdefault(case, []).append(path)
    try:
        for case, paths in by_case.items():
            print("\n".join(case_tables(case, paths)))
    except (PostError, NotMeasured, OSError) as e:
        print(f"paper-layouts: {e}", file=sys.stderr)
        return 1
    return 0
