"""Running the accuracy study's series: each through mpmshock-converge's functions (plan the levels,
run or reuse every level and seed, measure the plateaus), one simulator at a time, with runs that
another series already holds copied rather than run again, and one pinned binary for the whole study.

Part of the study in studies/accuracy/ of the checkout, run as `studies/accuracy/accuracy-study`
(study.py); plan.py says what to run, report.py writes it up.

A finished run is reused when its resolved scene (scene.txt) is the one requested, as the simulator
resolves it (`mpmshock --resolve`, mpmshock_post.resolve): mpmshock-converge's rule.
"""

import hashlib
import json
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mpmshock_post import converge, hugoniot
from mpmshock_post.errors import PostError
from mpmshock_post.reader import Run
from mpmshock_post.resolve import default_scene, resolved_scene

from .measure import EXTRA, extra_quantity
from .plan import NS, REGION, Series

COPIED_FROM = "COPIED_FROM"   # marks a run directory copied from another series' identical run
MADE_BY = "MADE_BY"           # the pinned binary (OUT/bin/mpmshock-SHA) that made a run


@dataclass
class Outcome:
    """A series after running: mpmshock-converge's levels, costs and results, and per-level run
    facts (summaries, the extra quantities)."""

    series: Series
    levels: list
    costs: list
    results: dict                    # quantity -> converge.Result
    summaries: list                  # per level: [summary dict of each seed's run]
    extras: dict                     # quantity -> [mean over seeds per level]
    run_dirs: list                   # per level: [run directory of each seed]

    def value(self, quantity, k):
        """The seed mean of a quantity at level k."""
        if quantity in self.results:
            return self.results[quantity].values[k]
        return self.extras[quantity][k]

    @property
    def h(self):
        """The cell size of each level, coarsest first."""
        return [c.cell_size for c in self.costs]

    def point_steps(self, k):
        """Material points x steps of level k, summed over its seeds."""
        return sum(s["material_points"] * s["steps"] for s in self.summaries[k])

    def wall(self, k):
        """Wall time of level k in s, summed over its seeds."""
        return sum(s["wall_seconds"] for s in self.summaries[k])


@dataclass
class Failure:
    """A series whose runs did not all finish."""

    series: Series
    message: str


class Study:
    """Runs series one after another (one mpmshock at a time) and keeps what they ran."""

    def __init__(self, out, binary, log=sys.stderr):
        self.out, self.binary, self.log = out, binary, log
        self.material = hugoniot.Material.from_scene(default_scene(binary))
        self.finished = {}       # scene text -> [run directories of finished runs]
        self.adopted = set()     # run directories copied from another series' run
        self.ran = set()         # run directories this invocation ran
        self.failures = []       # Failure of every series that did not finish
        self._defaults = {}      # --set overrides -> resolved scene of defaults (Study.defaults)
        self.started = time.monotonic()

    def say(self, text):
        print(f"accuracy-study: {text}", file=self.log, flush=True)

    def resolve(self, scene, overrides=()):
        """The resolved scene (SI) of a run of `scene` with these --set overrides, as this study's
        binary resolves it."""
        return resolved_scene(scene, overrides, self.binary)

    def defaults(self, overrides=()):
        """The resolved scene of a scene file that sets nothing but these --set overrides: every
        other key at its default, automatic keys (cfl, av_linear) resolved as such a run would."""
        key = tuple(overrides)
        if key not in self._defaults:
            with tempfile.TemporaryDirectory(prefix="accuracy-defaults-") as folder:
                empty = Path(folder) / "defaults.scene"
                empty.write_text("# every key at its default\n")   # a file of nothing is refused
                self._defaults[key] = self.resolve(empty, key)
        return self._defaults[key]

    def _args(self, series, directory, scene_path):
        t0, t1 = series.window
        argv = [str(scene_path), "--out", str(directory), "--refine", series.refine,
                "--values", ",".join(converge._format(v) for v in series.values), "--regions", REGION,
                "--window", f"{t0 / NS:.12g}ns", f"{t1 / NS:.12g}ns", "--seeds", str(series.seeds)]
        for override in series.overrides:
            argv += ["--set", override]
        args = converge.build_parser().parse_args(argv)
        converge.check_arguments(args)
        return args

    def _first_seed(self, args):
        return int(self.resolve(args.scene, args.set)["seed"])

    def _run_directories(self, levels, args):
        """(level, seed, run_dir, overrides) of each run, as converge.run_levels names them."""
        first = self._first_seed(args)
        for level in levels:
            for seed in range(first, first + args.seeds):
                overrides = [*args.set, *level.overrides] + ([f"seed={seed}"] if args.seeds > 1 else [])
                yield level, seed, converge.run_directory(args.out, level, seed, args.seeds), overrides

    def _planned_runs(self, levels, args):
        """(run_dir, requested scene) of each run, the request resolved as converge.run_levels does."""
        for _, _, run_dir, overrides in self._run_directories(levels, args):
            yield run_dir, self.resolve(args.scene, [*overrides, f"output_dir={run_dir}"])

    def _candidates(self, text, own):
        """Run directories of other series with the same scene file: this invocation's, and those
        an earlier invocation left (found by their study.scene)."""
        found = list(self.finished.get(text, []))
        for scene_path in sorted(self.out.glob("*/*/study.scene")):
            if scene_path.parent != own and scene_path.read_text() == text:
                found += sorted(p for p in scene_path.parent.glob("level_*") if p.is_dir())
        return list(dict.fromkeys(found))

    def _adopt(self, text, levels, args):
        """Copies a finished run of the same request from another series instead of running it; the
        copy carries COPIED_FROM so that the run time is counted once."""
        candidates = None
        for run_dir, requested in self._planned_runs(levels, args):
            if converge.reusable(run_dir, requested):
                continue
            if candidates is None:
                candidates = self._candidates(text, args.out)
            for candidate in candidates:
                if candidate != run_dir and converge.reusable(candidate, requested):
                    if run_dir.exists():
                        shutil.rmtree(run_dir)
                    shutil.copytree(candidate, run_dir, ignore=shutil.ignore_patterns(COPIED_FROM))
                    (run_dir / COPIED_FROM).write_text(f"{candidate}\n")
                    self.adopted.add(run_dir)
                    self.say(f"{run_dir} copied from {candidate}")
                    break

    def run(self, series):
        """Runs (or reuses, or copies) every level and seed of a series and measures it: its
        Outcome, with convergence.csv, convergence.md and cost.png written beside the runs; a
        Failure where a run did not finish."""
        directory = self.out / series.part / series.name
        directory.mkdir(parents=True, exist_ok=True)
        text = series.scene_file_text()
        scene_path = directory / "study.scene"
        if not scene_path.is_file() or scene_path.read_text() != text:
            scene_path.write_text(text)
        args = self._args(series, directory, scene_path)
        before = {}
        try:
            levels = converge.plan_levels(args.refine, args.values, args.levels,
                                          lambda extra: self.resolve(args.scene, [*args.set, *extra]))
            self._adopt(text, levels, args)
            before = {run_dir: _mtime(run_dir) for _, _, run_dir, _ in self._run_directories(levels, args)}
            self.say(f"series {series.part}/{series.name}")
            self._run_levels(levels, args)
        except PostError as e:
            self.say(f"series {series.part}/{series.name} failed: {e}")
            return Failure(series, str(e))
        finally:
            for run_dir, stamp in before.items():
                if _mtime(run_dir) != stamp:
                    self.ran.add(run_dir)
                    self.adopted.discard(run_dir)
                    (run_dir / COPIED_FROM).unlink(missing_ok=True)
                    (run_dir / MADE_BY).write_text(f"{self.binary.name}\n")
        self.finished.setdefault(text, []).extend(path for level in levels for _, path in level.runs)
        results = converge.collect(levels, [REGION], args.window, None)
        costs = [converge.level_cost(level) for level in levels]
        exact = {(REGION, q): v for q, v in series.exact.items()}
        converge.write_csv(directory / "convergence.csv", results, costs)
        (directory / "convergence.md").write_text(converge.markdown(args, levels, costs, results, exact))
        converge.plot_cost(directory / "cost.png", results, costs)
        summaries = [[Run(path).summary() for _, path in level.runs] for level in levels]
        extras = {q: [float(np.mean([extra_quantity(path, q, args.window) for _, path in level.runs]))
                      for level in levels] for q in EXTRA}
        return Outcome(series, levels, costs, {r.quantity: r for r in results}, summaries, extras,
                       [[path for _, path in level.runs] for level in levels])

    def run_all(self, series_list):
        """The Outcome of every series that finished, in order; the others go to self.failures."""
        done = []
        for series in series_list:
            result = self.run(series)
            (self.failures if isinstance(result, Failure) else done).append(result)
        return done

    def wait_for_binary(self, seconds=300):
        """The simulator may be rebuilt while the study runs: wait for it to reappear."""
        waited = 0
        while not self.binary.is_file() and waited < seconds:
            if waited == 0:
                self.say(f"{self.binary} is missing (being rebuilt?): waiting up to {seconds} s")
            time.sleep(5)
            waited += 5
        if not self.binary.is_file():
            raise PostError(f"no mpmshock binary at {self.binary}")

    def _run_levels(self, levels, args):
        """converge.run_levels, once more after a wait when the binary vanished under it."""
        self.wait_for_binary()
        try:
            converge.run_levels(levels, args, self.binary, log=self.log)
        except PostError:
            if self.binary.is_file():
                raise
            self.wait_for_binary()
            for level in levels:
                level.runs.clear()
            converge.run_levels(levels, args, self.binary, log=self.log)

    def _check_output(self, scene, cell_size, extra=()):
        self.wait_for_binary()
        command = [str(self.binary), str(scene), "--check", "--set", f"cell_size={converge._format(cell_size)}"]
        for override in extra:
            command += ["--set", override]
        return command, subprocess.run(command, capture_output=True, text=True)

    def check(self, scene, cell_size, extra=()):
        """(simulated material points, step lower bound) that `mpmshock SCENE --check` prints at this
        cell size: with symmetry on, the target's points alone (the flyer is their mirror image)."""
        command, done = self._check_output(scene, cell_size, extra)
        if done.returncode != 0:
            raise PostError(f"{' '.join(command)} exited {done.returncode}: {done.stderr.strip()}")
        points = (re.search(r"^symmetry: on: the target's (\d+) points are simulated", done.stdout, re.M)
                  or re.search(r"^material points: (\d+)", done.stdout, re.M))
        steps = re.search(r"at least (\d+) steps to ", done.stdout)
        if not (points and steps):
            raise PostError(f"{' '.join(command)}: no point or step count in\n{done.stdout}")
        return int(points.group(1)), int(steps.group(1))

    def voids_per_body(self, scene, cell_size):
        """The target's void count that `mpmshock SCENE --check` prints at this cell size (None if
        it prints none)."""
        _, done = self._check_output(scene, cell_size)
        found = re.search(r"target: .*?(\d+) voids", done.stdout)
        return int(found.group(1)) if found else None

    def run_single(self, scene, overrides, run_dir):
        """One run outside a convergence series (the full-geometry anchor), reused when finished."""
        requested = self.resolve(scene, [*overrides, f"output_dir={run_dir}"])
        if converge.reusable(run_dir, requested):
            self.say(f"{run_dir}: reused")
        else:
            self.say(f"{run_dir}: running")
            self.wait_for_binary()
            wall = converge.simulate(self.binary, scene, overrides, run_dir)
            self.ran.add(run_dir)
            (run_dir / MADE_BY).write_text(f"{self.binary.name}\n")
            self.say(f"{run_dir}: {wall:.1f} s")
        return Run(run_dir)

    def all_runs(self):
        """Every distinct run of the study (copies left out): run_dir -> summary."""
        found = {}
        for summary_path in sorted(self.out.glob("*/*/*/summary.json")) + sorted(self.out.glob("*/*/summary.json")):
            run_dir = summary_path.parent
            if (run_dir / COPIED_FROM).exists():
                continue
            try:
                found[run_dir] = json.loads(summary_path.read_text())
            except (OSError, ValueError):
                pass
        return found

    def made_by(self):
        """Binary name -> number of the study's runs it made ('unrecorded' for runs without MADE_BY)."""
        makers = {}
        for run_dir in self.all_runs():
            try:
                maker = (run_dir / MADE_BY).read_text().strip()
            except OSError:
                maker = "unrecorded"
            makers[maker] = makers.get(maker, 0) + 1
        return makers


def _mtime(run_dir):
    try:
        return (run_dir / "summary.json").stat().st_mtime_ns
    except OSError:
        return None


def pin_binary(binary, out, seconds=300):
    """A private copy of the simulator, OUT/bin/mpmshock-SHA, which every run of the study uses: the
    build may be replaced while the study runs (another engineer's rebuild), and one study should
    be one binary. Waits for the binary while it is missing (mid-rebuild)."""
    waited = 0
    while not Path(binary).is_file() and waited < seconds:
        time.sleep(5)
        waited += 5
    try:
        data = Path(binary).read_bytes()
    except OSError as e:
        raise PostError(f"no mpmshock binary at {binary}: {e}") from None
    pinned = out / "bin" / f"mpmshock-{hashlib.sha256(data).hexdigest()[:12]}"
    if not pinned.is_file():
        pinned.parent.mkdir(parents=True, exist_ok=True)
        partial = pinned.with_suffix(".partial")
        partial.write_bytes(data)
        partial.chmod(0o755)
        partial.replace(pinned)
    return pinned


def binary_fingerprint(binary):
    """(what `mpmshock --version` prints, the first 12 hex digits of the binary's sha256)."""
    try:
        digest = hashlib.sha256(Path(binary).read_bytes()).hexdigest()[:12]
    except OSError:
        digest = "missing"
    try:
        version = subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip()
    except OSError:
        version = "unknown"
    return version, digest
