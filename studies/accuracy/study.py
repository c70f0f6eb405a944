"""accuracy-study: mpmshock's accuracy study, run through mpmshock-converge and written up as
docs/accuracy.md with its figures docs/accuracy_*.png.

    studies/accuracy/accuracy-study [--out DIR] [--only PART[,PART]] [--quick] [--docs DIR]

Parts, run in this order (all four by default):
    solid        solid plates (porosity 1, plasticity off) at 500, 1000, 2000 m/s against the exact
                 Rankine-Hugoniot state; cell sizes 20, 10, 5 um; the main shape, bspline2, gimp,
                 bilinear; 1, 2, 3 points per cell; one plasticity-on series
    porous       delta 1.03, 1.1, 1.4 at 1000 m/s, voids of 20 um radius, cells r/2, r/4, r/8, several
                 void layouts (seeds), against the full-compaction Hugoniot and their own limit;
                 bspline2, gimp, bilinear and the main shape with volumetric_smoothing = off
                 beside the main shape at delta 1.1
    sensitivity  delta 1.1 at one cell size: artificial viscosity, cfl (0.3 to 0.9) and
                 flip_fraction varied
    answer       the paper's base case in a reduced column at 20, 10, 5 um: the cell size and
                 core-minutes the full geometry needs for 1, 3, 10 % in pressure, 10 and 50 K in T

Every run goes to DIR/PART/SERIES/level_K[_seed_S] (default DIR: build/accuracy-study), with the
series' convergence.csv, convergence.md and cost.png beside them; a finished run whose scene
matches is reused (mpmshock-converge's rule), and a run another series already holds is copied
instead of run again. The report and figures go to the repository's docs/ for a full study, else
(with --quick or --only) to DIR/docs, unless --docs says where.

The main shape is MAIN_SHAPE in plan.py: bspline2_domain, the simulator's default shape function,
at its automatic cfl (0.6); every run takes the automatic av_linear (0.6 where every body is solid,
0.2 where one is porous) and the automatic volumetric_smoothing (on where a body is porous) but in
one porous comparison. bspline2 at cfl 0.3, with volumetric smoothing off, was the default until
2026-12-05.

--quick runs a smaller study (fewer speeds, shapes, seeds, coarser cells) as a smoke test; its
numbers are not the study's.

The error estimates are mpmshock-converge's (mpmshock_post.converge): Richardson extrapolation from
the three finest levels with the observed order, or its conservative fallback. The simulator is
$MPMSHOCK, else mpmshock on PATH, else the checkout's build/src/mpmshock.
"""

# The study lives in studies/accuracy/ of the checkout: this module is its command line (the entry
# script accuracy-study calls main); plan.py says what runs, run.py runs it, report.py and
# sections.py write it up, with the prose of accuracy.md.in.

import argparse
import sys
import time
from pathlib import Path

from mpmshock_post.errors import PostError
from mpmshock_post.resolve import mpmshock_binary

from . import plan as planning
from .plan import PAPER_SCENE, PARTS, ROOT, Plan
from .report import Report, write_document
from .run import Study, binary_fingerprint, pin_binary
from .sections import answer_section, porous_section, sensitivity_section, solid_section


def conduct(parts, plan, study, report):
    """Runs the parts in order, each part's series one after another, and writes their sections."""
    if "solid" in parts:
        solid = study.run_all(planning.solid_series(plan, study.material))
        if solid:
            solid_section(report, solid)
    if "porous" in parts:
        porous = study.run_all(planning.porous_series(plan, study.material))
        if porous:
            porous_section(report, porous)
    if "sensitivity" in parts:
        check_main_cfl(study)
        sensitivity = study.run_all(planning.sensitivity_series(plan, study.material))
        sensitivity_section(report, sensitivity, [f for f in study.failures if f.series.part == "sensitivity"])
    if "answer" in parts:
        paper = study.resolve(PAPER_SCENE)
        reduced = study.run_all([planning.answer_scene(plan, study.material, paper)])
        if reduced:
            o = reduced[0]
            anchor = None
            if plan.answer_anchor:
                overrides, name = planning.anchor_run(o.series, o.h[0])
                anchor = study.run_single(PAPER_SCENE, overrides, study.out / "answer" / name)
            answer_section(report, o, anchor)


def check_main_cfl(study):
    """The sensitivity part marks plan.MAIN_CFL as the default of its cfl series: a PostError where
    the simulator's automatic cfl for the main shape is another (a changed default)."""
    auto = study.defaults([f"shape_function={planning.MAIN_SHAPE}"])["cfl"]
    if not abs(auto - planning.MAIN_CFL) <= 1e-9:
        raise PostError(f"the simulator's automatic cfl for {planning.MAIN_SHAPE} is {auto:g}, not "
                        f"plan.MAIN_CFL = {planning.MAIN_CFL:g} (the sensitivity part's default): update plan.py")


def build_parser():
    parser = argparse.ArgumentParser(prog="accuracy-study", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 2)[2])
    parser.add_argument("--out", type=Path, help="directory for the runs (default build/accuracy-study, "
                        "build/accuracy-study-quick with --quick)")
    parser.add_argument("--only", help="comma-separated parts to run: " + ", ".join(PARTS))
    parser.add_argument("--quick", action="store_true", help="a small study for a smoke test")
    parser.add_argument("--docs", type=Path, help="where accuracy.md and its figures go (default: docs/ for a "
                        "full study of every part, else OUT/docs)")
    return parser


def main(argv=None):
    args = build_parser().parse_args(argv)
    started = time.monotonic()
    try:
        parts = PARTS if not args.only else [p.strip() for p in args.only.split(",") if p.strip()]
        unknown = [p for p in parts if p not in PARTS]
        if unknown or not parts:
            raise PostError(f"--only {args.only}: unknown part {', '.join(unknown) or '(none)'} "
                            f"(parts: {', '.join(PARTS)})")
        parts = [p for p in PARTS if p in parts]
        plan = Plan.make(args.quick)
        out = (args.out or ROOT / ("build/accuracy-study-quick" if args.quick else "build/accuracy-study")).resolve()
        full = not args.quick and list(parts) == list(PARTS)
        docs = (args.docs or (ROOT / "docs" if full else out / "docs")).resolve()
        out.mkdir(parents=True, exist_ok=True)
        docs.mkdir(parents=True, exist_ok=True)
        binary = pin_binary(mpmshock_binary(), out)
        study = Study(out, binary)
        fingerprint = binary_fingerprint(binary)
        report = Report(docs, plan, study)
        conduct(parts, plan, study, report)
        path = write_document(report, parts, time.monotonic() - started, fingerprint)
    except PostError as e:
        print(f"accuracy-study: error: {e}", file=sys.stderr)
        return 1
    print(path)
    for figure in report.figures:
        print(figure)
    failures = study.failures
    return 1 if failures and not args.quick and any(f.series.part != "sensitivity" for f in failures) else 0

