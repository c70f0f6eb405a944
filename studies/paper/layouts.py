"""paper-layouts CASE=DIR [CASE=DIR ...]: how much the void layout alone moves the paper's numbers.

Each DIR is a finished run of a paper case (studies/paper/scenes/CASE.scene) with its own `seed`: runs of
one case with different seeds are layouts of the same sample, as a new sample would be in an
experiment. For each case this prints, in Markdown,
- B800's late-window means per layout (the last 300 ns, as comparison.csv's 'steady' values),
  with B800's own porosity at t = 0 and the full-compaction Hugoniot temperature at it;
- every number comparison.csv gives for that case alone, per layout, with the mean, the standard
  error of the mean over the layouts (SE) and the range.
The SE is the error a single-layout number carries beside docs/accuracy.md's discretisation error:
the paper's numbers come from one layout each.

reproduce-paper --layouts DIR puts the same spread into comparison.csv (with_layouts): DIR holds
records or runs named CASE_seedN (studies/paper/records/layouts), and each row that the campaign's CASE run
gives a number for alone gets, in its note, the mean +- SE over its layouts and how many SE the
paper's value lies from that mean.
"""

import argparse
import math
import os
import re
import sys
import tempfile
from pathlib import Path

import numpy as np

from mpmshock_post.errors import PostError, argument_type
from .comparison import comparison_rows
from .measures import BOTTOM, CaseRun, NotMeasured
from .rows import fmt
from mpmshock_post.reader import PaperTemperatureRun, has_paper_temperature
from mpmshock_post.scene import Scene

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


# Scene keys that may differ between layouts of one case: the layout itself and where and how
# often a run writes its output (neither changes a region series).
LAYOUT_KEYS = ("seed", "output_dir", "snapshot_interval", "snapshot_times")


def layout_dirs(layouts_dir):
    """{case: [run or record directories]} of layouts_dir's CASE_seedN entries, by seed."""
    if not Path(layouts_dir).is_dir():
        raise PostError(f"--layouts {layouts_dir}: no such directory")
    found = {}
    for path in sorted(Path(layouts_dir).iterdir()):
        match = re.fullmatch(r"(.+)_seed(\d+)", path.name)
        if match and (path / "regions.csv").is_file():
            found.setdefault(match.group(1), []).append((int(match.group(2)), path))
    return {case: [path for _, path in sorted(entries)] for case, entries in found.items()}


def same_sample(campaign_dir, layout_dir):
    """PostError unless layout_dir ran the scene of campaign_dir with another seed only."""
    scenes = [Scene((d / "scene.txt").read_text(), str(d / "scene.txt")) for d in (campaign_dir, layout_dir)]
    keys = sorted(set(scenes[0]) | set(scenes[1]))
    differ = [k for k in keys if k not in LAYOUT_KEYS and scenes[0].get(k) != scenes[1].get(k)]
    if differ:
        raise PostError(f"{layout_dir}: not a layout of {campaign_dir}: its scene differs in "
                        + ", ".join(f"{k} ({scenes[1].get(k)} against {scenes[0].get(k)})" for k in differ))
    if scenes[0].get("seed", 1.0) == scenes[1].get("seed", 1.0):
        raise PostError(f"{layout_dir}: the same seed as {campaign_dir}: the same layout, not another")


def _paper_number(text):
    try:
        return float(text)
    except ValueError:
        return None


def with_layouts(rows, runs_dir, layouts_dir):
    """`rows` (comparison_rows of runs_dir) with the layout spread in the notes of every row that a
    case with layouts in layouts_dir gives a number for alone: 'over N void layouts (seeds ...):
    mean +- SE, range R[; the paper's value lies k SE from the mean]'. A row whose number needs
    several cases (a study row) or that a case run alone does not give the same is left as it is."""
    rows = [dict(r) for r in rows]
    for case, paths in layout_dirs(layouts_dir).items():
        campaign_dir = Path(runs_dir) / case
        if not (campaign_dir / "regions.csv").is_file():
            continue
        for path in paths:
            same_sample(campaign_dir, path)
        numbers = [numeric_rows(case, d) for d in [campaign_dir, *paths]]
        seeds = [f"{float(CaseRun(case, d).scene.get('seed', 1)):.0f}" for d in [campaign_dir, *paths]]
        for entry in rows:
            key = (entry["figure"], entry["quantity"], entry["unit"])
            ours = _paper_number(entry["mpmshock"])
            if ours is None or not all(key in n for n in numbers) or numbers[0][key] != ours:
                continue
            mean, se, width = spread([n[key] for n in numbers])
            text = (f"over {len(numbers)} void layouts (seeds {', '.join(seeds)}): {fmt(mean)} ± {fmt(se, 2)} "
                    f"{entry['unit']} (mean ± SE), range {fmt(width, 3)}").replace("  ", " ")
            paper = _paper_number(entry["paper"])
            if paper is not None and se > 0:
                text += f"; the paper's {fmt(paper)} lies {abs(paper - mean) / se:.1f} SE from that mean"
            entry["note"] = f"{entry['note']}; {text}" if entry["note"] else text
    return rows


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
