"""The runs behind studies/paper/reproduce-paper: which cases each figure of Xu et al. needs, the quick
settings, and whether a run directory is reused, resumed from its last snapshot or run afresh.

A case is a scene file studies/paper/scenes/<case>.scene; it runs into DIR/runs/<case>/ with the energy
temperature model (the simulator's default). The paper's temperature model changes no step of a run,
only the temperature it reports, so where the simulator has the scene key `paper_temperature` that
one run reports both models (`paper_temperature = on`, read back as the paper model's run by
reader.PaperTemperatureRun); with an older simulator the paper model runs again into
DIR/runs/<case>-paperT/ with `temperature_model = paper`.

A campaign longer than one sitting keeps its finished runs' records (--records DIR: each run's
scene, summary and CSV time series, a few hundred kB, without its snapshots, saved as each run
finishes) and starts the next sitting from them: a run missing from DIR/runs is taken from its
record, and is then reused as finished. The figures and comparison rows that read the time series
need nothing more; a case whose snapshots a requested figure reads (Fig. 1, 3, 6 and 11) runs
instead.
"""

import json
import os
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from mpmshock_post import converge
from mpmshock_post.errors import PostError
from mpmshock_post.reader import Run
from mpmshock_post.resolve import resolved_scene, scene_differences

HERE = Path(__file__).resolve().parent

# The figures of the paper and the cases (scene stems) each one draws, in legend order.
VOID_SIZE_CASES = ("void_r25", "base", "void_r100")
VELOCITY_CASES = ("delta1.4_v500", "delta1.4", "delta1.4_v1500", "delta1.4_v2000")
POROSITY_CASES = ("delta1.01", "delta1.02", "delta1.1", "delta1.4", "delta1.7")
FIGURE_CASES = {1: ("base",), 2: ("base",), 3: ("base",), 4: ("base",), 5: ("base",), 6: ("base",),
                7: VOID_SIZE_CASES, 8: VOID_SIZE_CASES, 9: ("delta1.4",), 10: ("delta1.4",), 11: ("delta1.4",),
                12: VELOCITY_CASES, 13: POROSITY_CASES}
FIGURES = tuple(FIGURE_CASES)
# The figures whose plots read snapshots (fields, histograms), not only the time series.
SNAPSHOT_FIGURES = (1, 3, 6, 11)

# --quick: the same bodies (5 mm + 5 mm), end times, outputs and physics, on a coarser grid and a
# narrower column. 20 um cells are the shipped base config's resolution (docs/accuracy.md: plateau
# pressure within 10 %, mean temperature within 50 K at delta 1.03); the 10 um voids of the delta 1.4
# family are then half a cell in radius, so those curves show trends, not converged values. cfl 0.45
# takes a third fewer steps and moves results by under 1 % (docs/accuracy.md); every hard case holds
# at it (docs/stability.md). The delta 1.03 cases keep a 1 mm column
# (per body 75 voids of 25 um, 18 of 50 um, 5 of 100 um); the cases with 10 um voids hold 80
# (delta 1.01) to 3300 (delta 1.7) per body in 0.5 mm. The whole quick campaign, both temperature
# models, took 5 minutes on the shared 2-core machine (--jobs 1), 3 GB of runs.
QUICK_SETTINGS = ("cell_size=20um", "cfl=0.45")
QUICK_WIDTH = {"base": "1mm", "void_r25": "1mm", "void_r100": "1mm"}
QUICK_DEFAULT_WIDTH = "0.5mm"
# Cases that also run with the paper's temperature model in quick mode (None: all of them).
QUICK_PAPER_T_CASES = None

TEMPERATURE_MODELS = ("energy", "paper")
PAPER_SUFFIX = "-paperT"
_RESUMABLE_EXITS = (130, 143)  # stopped by SIGINT / SIGTERM with a final snapshot


def scenes_dir():
    """studies/paper/scenes, or $REPRODUCE_PAPER_SCENES (the tests put tiny scenes there)."""
    return Path(os.environ.get("REPRODUCE_PAPER_SCENES") or HERE / "scenes")


def cases_for(figures):
    """The cases the figures need, each once, in figure order."""
    return list(dict.fromkeys(case for number in figures for case in FIGURE_CASES[number]))


def quick_overrides(case):
    return [*QUICK_SETTINGS, f"width={QUICK_WIDTH.get(case, QUICK_DEFAULT_WIDTH)}"]


def run_name(case, model):
    return case + (PAPER_SUFFIX if model == "paper" else "")


@dataclass
class PlannedRun:
    """One simulator run of the campaign: a case with one temperature model."""

    case: str
    model: str
    scene: Path
    overrides: list
    run_dir: Path

    @property
    def name(self):
        return self.run_dir.name

    @property
    def log(self):
        return self.run_dir.with_name(self.name + ".log")

    @property
    def record(self):
        """The wall time this script measured for the run (JSON), beside the log."""
        return self.run_dir.with_name(self.name + ".json")


def plan_runs(cases, models, runs_dir, quick, combined=False):
    """The runs of `cases` for the temperature `models`. `combined` (the simulator has the key
    paper_temperature): the energy-model runs report the paper model too, and no run is repeated
    for it."""
    runs = []
    both = combined and "paper" in models
    for model in models:
        if both and model == "paper":
            continue
        for case in cases:
            if model == "paper" and quick and QUICK_PAPER_T_CASES is not None and case not in QUICK_PAPER_T_CASES:
                continue
            scene = scenes_dir() / f"{case}.scene"
            if not scene.is_file():
                raise PostError(f"no scene for case '{case}': {scene} is missing")
            overrides = quick_overrides(case) if quick else []
            if model == "paper":
                overrides.append("temperature_model=paper")
            elif both:
                overrides.append("paper_temperature=on")
            runs.append(PlannedRun(case, model, scene, overrides, runs_dir / run_name(case, model)))
    return runs


# What a run's record keeps: everything but its snapshots (and the voids, which nothing here reads).
RECORD_FILES = ("scene.txt", "summary.json", "regions.csv", "conservation.csv", "probes.csv")


def save_record(run, records_dir):
    """Copies a finished run's record into records_dir/<name>/ (and its timing, beside); returns
    whether there was one to save."""
    if not (run.run_dir / "summary.json").is_file() or not (run.run_dir / "regions.csv").is_file():
        return False
    kept = records_dir / run.name
    kept.mkdir(parents=True, exist_ok=True)
    for name in RECORD_FILES:
        if (run.run_dir / name).is_file():
            shutil.copyfile(run.run_dir / name, kept / name)
    if run.record.is_file():
        shutil.copyfile(run.record, records_dir / run.record.name)
    return True


def seed_from_record(run, records_dir):
    """A run that DIR/runs lacks, made from its record in records_dir where there is one; returns
    whether it was."""
    kept = records_dir / run.name
    if (run.run_dir / "summary.json").exists() or not (kept / "summary.json").is_file():
        return False
    run.run_dir.mkdir(parents=True, exist_ok=True)
    for name in RECORD_FILES:
        if (kept / name).is_file():
            shutil.copyfile(kept / name, run.run_dir / name)
    if (records_dir / run.record.name).is_file():
        shutil.copyfile(records_dir / run.record.name, run.record)
    return True


def last_snapshot(run_dir):
    try:
        snapshots = Run(run_dir).snapshots()
    except PostError:
        return None
    return snapshots[-1].path if snapshots else None


def decide(run, binary):
    """('reuse', None) for a finished run of the same scene; ('resume', SNAPSHOT) for a run of the
    same scene that stopped early (killed, or SIGINT / SIGTERM) and left snapshots; else
    ('fresh', None). A run that failed (exit 3) runs afresh, and fails again with its message."""
    requested = resolved_scene(run.scene, [*run.overrides, f"output_dir={run.run_dir}"], binary)
    if converge.reusable(run.run_dir, requested):
        return "reuse", None
    try:
        same_scene = not scene_differences(Run(run.run_dir).scene, requested)
    except PostError:
        return "fresh", None
    summary_file = run.run_dir / "summary.json"
    try:
        exit_code = json.loads(summary_file.read_text()).get("exit_code") if summary_file.is_file() else None
    except (OSError, ValueError):
        exit_code = None
    snapshot = last_snapshot(run.run_dir)
    if same_scene and snapshot is not None and exit_code in (None, *_RESUMABLE_EXITS):
        return "resume", snapshot
    return "fresh", None


def command(run, binary, action, snapshot, threads, ranks=1):
    """The simulator's command line; on `ranks` > 1 MPI ranks through mpirun (the outputs are the same
    bits as one process's: docs/cluster.md)."""
    launch = ["mpirun", "-q", "--bind-to", "none", "-np", str(ranks)] if ranks > 1 else []
    if action == "resume":
        start = [str(binary), "--restart", str(snapshot)]
    else:
        start = [str(binary), str(run.scene)]
        for override in [*run.overrides, f"output_dir={run.run_dir}"]:
            start += ["--set", override]
    return launch + start + ["--quiet", "--force", "--threads", str(threads)]


def say(text):
    print(f"reproduce-paper: {text}", file=sys.stderr, flush=True)


def execute(run, binary, threads, ranks=1):
    """Reuses, resumes or runs one case; returns its record (action, wall seconds) or raises
    PostError naming the case and its log (or, for a scene the simulator refuses, its message)."""
    try:
        action, snapshot = decide(run, binary)
    except PostError as e:
        run.log.parent.mkdir(parents=True, exist_ok=True)
        run.log.write_text(f"{e}\n")
        raise PostError(f"case {run.name} failed: its scene is refused; see its log {run.log}:\n{e}") from None
    if action == "reuse":
        record = read_record(run)
        wall = record.get("wall_seconds")
        say(f"{run.name}: reused ({run.run_dir}" + (f", ran in {wall:.1f} s)" if wall else ")"))
        return {**record, "action": "reused"}
    cmd = command(run, binary, action, snapshot, threads, ranks)
    say(f"{run.name}: started ({'resumed from ' + snapshot.name if action == 'resume' else 'fresh'})")
    run.run_dir.parent.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    with open(run.log, "a" if action == "resume" else "w") as log:
        log.write("$ " + " ".join(cmd) + "\n")
        log.flush()
        env = dict(os.environ)
        env.setdefault("OMP_WAIT_POLICY", "PASSIVE")  # spinning threads hurt on a shared machine (docs/running.md)
        if ranks > 1 and os.geteuid() == 0:  # Open MPI runs as root only when told
            env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
            env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        done = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    wall = time.monotonic() - started
    if done.returncode != 0:
        how = f"killed by signal {-done.returncode}" if done.returncode < 0 else f"exit {done.returncode}"
        raise PostError(f"case {run.name} failed (mpmshock {how}); see its log {run.log}")
    # A resumed run's time is that of its last segment: an interrupted one leaves no record.
    record = {"action": "resumed" if action == "resume" else "ran", "wall_seconds": wall,
              "threads": threads, "ranks": ranks, "command": cmd}
    run.record.write_text(json.dumps(record, indent=1) + "\n")
    say(f"{run.name}: finished in {wall:.1f} s")
    return record


def read_record(run):
    """What an earlier invocation measured; without it, the simulator's own summary time."""
    try:
        return json.loads(run.record.read_text())
    except (OSError, ValueError):
        pass
    try:
        return {"wall_seconds": Run(run.run_dir).summary().get("wall_seconds")}
    except PostError:
        return {}


def execute_all(runs, binary, jobs, ranks=1, records_dir=None):
    """Every run, `jobs` at a time, each on `ranks` MPI ranks of max(1, cores // (jobs ranks)) threads;
    name -> record. With records_dir, each finished run's record is saved there as soon as it
    finishes, so that a campaign stopped hours in keeps what it had done. After a failure the runs
    not yet started are cancelled, those under way finish, and the first failure is raised."""
    cores = len(os.sched_getaffinity(0))
    threads = max(1, cores // (jobs * ranks))
    records, failures = {}, []

    def run_and_keep(run):
        record = execute(run, binary, threads, ranks)
        if records_dir is not None and save_record(run, records_dir) and record.get("action") != "reused":
            say(f"{run.name}: record kept in {records_dir}")
        return record

    with ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(run_and_keep, run): run for run in runs}
        for future, run in futures.items():
            if future.cancelled():
                continue
            try:
                records[run.name] = future.result()
            except PostError as e:
                failures.append(e)
                for other in futures:
                    other.cancel()
    if failures:
        raise failures[0]
    return records
