"""reproduce-paper: the simulations and figures of Xu et al., "Simulation study of shock reaction on
porous material", with one command (studies/paper/reproduce-paper --help).

Runs every case of studies/paper/scenes the chosen figures need (paper_runs.py: reused when finished,
resumed when interrupted), draws DIR/fig01.png ... fig13.png (paper_figures.py), writes
DIR/comparison.csv (paper_comparison.py) and DIR/paper.md with the machine, the wall times and
everything embedded.
"""

import argparse
import csv
import datetime
import os
import platform
import shlex
import subprocess
import sys
import time
from pathlib import Path

import matplotlib

from mpmshock_post.errors import PostError, argument_type
from .figures import CAPTIONS, CampaignRuns, make_figures, resolution
from .runs import (FIGURES, QUICK_DEFAULT_WIDTH, QUICK_PAPER_T_CASES, QUICK_SETTINGS, QUICK_WIDTH,
                         FIGURE_CASES, SNAPSHOT_FIGURES, TEMPERATURE_MODELS, cases_for, execute_all, plan_runs,
                         say, seed_from_record)
from mpmshock_post.reader import Run
from mpmshock_post.resolve import default_scene, mpmshock_binary


def _figures(text):
    numbers = [int(item) for item in text.split(",") if item.strip()]
    wrong = [n for n in numbers if n not in FIGURES]
    if not numbers or wrong:
        raise PostError(f"--fig takes figure numbers 1 to 13, comma-separated (got '{text}')")
    return sorted(set(numbers))


def _models(text):
    models = [item.strip() for item in text.split(",") if item.strip()]
    if not models or any(m not in TEMPERATURE_MODELS for m in models):
        raise PostError(f"--temperature-models takes energy and/or paper, comma-separated (got '{text}')")
    if "energy" not in models:
        raise PostError("--temperature-models must include energy: the figures are drawn from those runs")
    return list(dict.fromkeys(models))


def _jobs(text):
    jobs = int(text)
    if jobs < 1:
        raise PostError(f"--jobs and --ranks take a whole number >= 1 (got '{text}')")
    return jobs


def quick_text():
    widths = ", ".join(f"{case} {width}" for case, width in QUICK_WIDTH.items())
    paper_t = "all cases" if QUICK_PAPER_T_CASES is None else "only " + ", ".join(QUICK_PAPER_T_CASES)
    return (f"--quick runs the same cases, 5 mm bodies and end times with {', '.join(QUICK_SETTINGS)} and a "
            f"narrower column ({widths}, the others {QUICK_DEFAULT_WIDTH}); the paper temperature model runs for "
            f"{paper_t}.")


def build_parser():
    parser = argparse.ArgumentParser(
        prog="reproduce-paper",
        description="Runs the cases of studies/paper/scenes/*.scene and draws the 13 figures of Xu et al., 'Simulation "
        "study of shock reaction on porous material', as DIR/fig01.png ... fig13.png, with DIR/comparison.csv "
        "and DIR/paper.md. Runs go to DIR/runs/<case> (energy temperature model) and DIR/runs/<case>-paperT "
        "(temperature_model = paper), logs to DIR/runs/<name>.log; a finished run of the same scene is reused, "
        "an interrupted one resumes from its last snapshot. The simulator is $MPMSHOCK or build/src/mpmshock.",
        epilog=quick_text() + " It took 5 to 6 minutes and 3 GB on the project's shared 2-core machine (the "
        "budget is 15 minutes); "
        "--jobs 2 is faster there. The full campaign (studies/paper/scenes as written: 5 and 10 um cells, 2 mm wide) "
        "takes 9 to 11 hours there on 2 MPI ranks, one run per case for both temperature models (docs/reproducing-the-paper.md): "
        "--records carries it over several sittings.")
    parser.add_argument("--out", required=True, type=Path, metavar="DIR", help="output directory")
    parser.add_argument("--quick", action="store_true", help="reduced resolution and width (see below)")
    parser.add_argument("--fig", type=argument_type(_figures), default=list(FIGURES), metavar="N[,N...]",
                        help="only these figures, and only the runs they need (default: all 13)")
    parser.add_argument("--jobs", type=argument_type(_jobs), default=1, metavar="J",
                        help="runs at once, each on max(1, cores // (J R)) threads (default 1)")
    parser.add_argument("--ranks", type=argument_type(_jobs), default=1, metavar="R",
                        help="MPI ranks per run, through mpirun (default 1: no MPI); the results are the same bits")
    parser.add_argument("--records", type=Path, metavar="RECORDS",
                        help="keep each finished run's record (scene, summary, CSVs: no snapshots) in RECORDS as "
                        "it finishes, and take a run missing from DIR/runs from its record there, as finished: a "
                        "campaign longer than one sitting goes on from the last (a case whose snapshots a requested "
                        "figure reads, for Fig. 1, 3, 6 and 11, runs instead)")
    parser.add_argument("--layouts", type=Path, metavar="LAYOUTS",
                        help="runs or records of other void layouts of the cases, named CASE_seedN (such as "
                        "studies/paper/records/layouts, made with --set seed=N): each comparison row that a case with layouts "
                        "gives a number for alone notes the mean +- standard error over its layouts and how many "
                        "SE the paper's value lies from it (studies/paper/paper-layouts)")
    parser.add_argument("--temperature-models", type=argument_type(_models), default=list(TEMPERATURE_MODELS),
                        metavar="energy,paper", help="temperature models to run (default both; paper needs the "
                        "scene key temperature_model and is skipped with a message where mpmshock lacks it)")
    return parser


def machine():
    model = platform.processor() or "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{os.cpu_count()} cores (nproc {len(os.sched_getaffinity(0))}), {model}"


def write_comparison(out, quick, layouts=None):
    try:
        from .comparison import comparison_rows, write_comparison_csv
        from .layouts import with_layouts
    except ImportError as e:
        say(f"comparison.csv skipped: studies/paper/comparison.py is not usable yet ({e})")
        return
    rows = comparison_rows(runs_dir=out / "runs", quick=quick)
    if layouts is not None:
        rows = with_layouts(rows, out / "runs", layouts)
    write_comparison_csv(rows, out / "comparison.csv")
    say(f"wrote {out / 'comparison.csv'}")


def _cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(value) for value in row) + " |" for row in rows]
    return lines


def run_rows(planned, records):
    rows = []
    for run in planned:
        record = records.get(run.name, {})
        summary = Run(run.run_dir).summary()
        wall = record.get("wall_seconds")
        rows.append([f"`runs/{run.name}`", run.case, run.model, resolution([Run(run.run_dir).scene], False),
                     summary.get("material_points"), summary.get("steps"),
                     f"{wall:.1f}" if wall is not None else "?", record.get("action", "?")])
    return rows


def write_markdown(out, argv, quick, binary, planned, records, elapsed, figure_paths):
    version = subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip()
    total_runs = sum(r.get("wall_seconds") or 0.0 for r in records.values() if r.get("action") != "reused")
    lines = ["# Xu et al., *Simulation study of shock reaction on porous material*, rerun by mpmshock"
             + (" (quick)" if quick else ""), "",
             f"- command: `{' '.join(['studies/paper/reproduce-paper', *map(shlex.quote, argv)])}`",
             f"- date: {datetime.datetime.now().isoformat(timespec='seconds')}",
             f"- machine: {machine()}",
             f"- simulator: {version} (`{binary}`)",
             f"- wall time of this command: {elapsed:.0f} s, of which simulator runs {total_runs:.0f} s "
             "(reused runs not counted)", ""]
    if quick:
        lines += [quick_text(), ""]
    lines += ["## Runs", "", "Wall time as this script measured it (for a resumed run, its last segment).", ""]
    lines += _table(["run", "case", "T model", "resolution", "points", "steps", "wall (s)", "how"],
                    run_rows(planned, records))
    lines += ["", "## Figures", ""]
    for path in figure_paths:
        number = int(path.stem[3:])
        lines += [f"### Fig. {number}", "", f"![Fig. {number}]({path.name})", "", CAPTIONS[number], ""]
    comparison = out / "comparison.csv"
    if comparison.is_file():
        with open(comparison, newline="") as f:
            rows = list(csv.reader(f))
        lines += ["## Comparison with the paper", ""] + _table(rows[0], rows[1:]) + [""]
    (out / "paper.md").write_text("\n".join(lines) + "\n")
    say(f"wrote {out / 'paper.md'}")


def main(argv=None):
    matplotlib.use("Agg")
    argv = sys.argv[1:] if argv is None else argv
    args = build_parser().parse_args(argv)
    started = time.monotonic()
    try:
        binary = mpmshock_binary()
        if not os.access(binary, os.X_OK):
            raise PostError(f"no mpmshock binary at {binary}: build it (scripts/build.sh) or set $MPMSHOCK")
        defaults = default_scene(binary)
        models = args.temperature_models
        if "paper" in models and "temperature_model" not in defaults:
            say(f"skipping the paper temperature model: {binary} has no scene key temperature_model "
                "(mpmshock --keys); the figures show the energy model only")
            models = ["energy"]
        if "paper" in models and args.quick and QUICK_PAPER_T_CASES is not None:
            say("quick: the paper temperature model runs only for " + ", ".join(QUICK_PAPER_T_CASES))
        if args.layouts is not None and not args.layouts.is_dir():  # before hours of runs, not after
            raise PostError(f"--layouts {args.layouts}: no such directory")
        out = args.out.resolve()
        (out / "runs").mkdir(parents=True, exist_ok=True)
        combined = "paper_temperature" in defaults
        if "paper" in models and combined:
            say("each run reports both temperature models (paper_temperature = on): no run is repeated for the "
                "paper model")
        planned = plan_runs(cases_for(args.fig), models, out / "runs", args.quick, combined)
        say(f"{len(planned)} runs for figure(s) {','.join(map(str, args.fig))}" + (" (quick)" if args.quick else ""))
        if args.records is not None:
            drawn_from_snapshots = {case for n in args.fig if n in SNAPSHOT_FIGURES for case in FIGURE_CASES[n]}
            for run in planned:
                if run.case not in drawn_from_snapshots and seed_from_record(run, args.records.resolve()):
                    say(f"{run.name}: taken from its record in {args.records} (no snapshots)")
        records = execute_all(planned, binary, args.jobs, args.ranks,
                              args.records.resolve() if args.records is not None else None)
        say(f"runs done after {time.monotonic() - started:.0f} s")

        made = make_figures(args.fig, CampaignRuns(out / "runs", args.quick), out)
        say(f"figures {', '.join(p.name for p in made)} written after {time.monotonic() - started:.0f} s")
        compared = True
        try:
            write_comparison(out, args.quick, args.layouts)
        except Exception as e:  # another engineer's module: report, finish the page, exit non-zero
            say(f"comparison.csv failed: {type(e).__name__}: {e}")
            compared = False
        figure_paths = sorted(out.glob("fig[0-9][0-9].png"))
        write_markdown(out, argv, args.quick, binary, planned, records, time.monotonic() - started, figure_paths)
    except (PostError, OSError) as e:
        print(f"reproduce-paper: error: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("reproduce-paper: interrupted; the same command resumes the runs from their last snapshots",
              file=sys.stderr)
        return 130
    say(f"done in {time.monotonic() - started:.0f} s: {out}")
    return 0 if compared else 1
