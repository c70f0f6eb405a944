"""accuracy-study: mpmshock's accuracy study, run through mpmshock-converge and written up as
docs/accuracy.md with its figures docs/accuracy_*.png.

    accuracy-study [--out DIR] [--only PART[,PART]] [--quick] [--docs DIR]

Parts, run in this order (all four by default):
    solid        solid plates (porosity 1, plasticity off) at 500, 1000, 2000 m/s against the exact
                 Rankine-Hugoniot state; cell sizes 20, 10, 5 um; bspline2, gimp, bilinear; 1, 2, 3
                 points per cell; one plasticity-on series
    porous       delta 1.03, 1.1, 1.4 at 1000 m/s, voids of 20 um radius, cells r/2, r/4, r/8, several
                 void layouts (seeds), against the full-compaction Hugoniot and their own limit
    sensitivity  delta 1.1 at one cell size: artificial viscosity, cfl and flip_fraction varied
    answer       the paper's base case in a reduced column at 20, 10, 5 um: the cell size and
                 core-minutes the full geometry needs for 1, 3, 10 % in pressure, 10 and 50 K in T

Every run goes to DIR/PART/SERIES/level_K[_seed_S] (default DIR: build/accuracy-study), with the
series' convergence.csv, convergence.md and cost.png beside them; a finished run whose scene
matches is reused (mpmshock-converge's rule), and a run another series already holds is copied
instead of run again. The report and figures go to the repository's docs/ for a full study, else
(with --quick or --only) to DIR/docs, unless --docs says where.

--quick runs a smaller study (fewer speeds, shapes, seeds, coarser cells) as a smoke test; its
numbers are not the study's.

The error estimates are mpmshock-converge's (mpmshock_post.converge): Richardson extrapolation from
the three finest levels with the observed order, or its conservative fallback.
"""

import argparse
import json
import math
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import converge, hugoniot
from .errors import PostError
from .reader import Run
from .scene_input import ROOT, key_defaults, mpmshock_binary, parse_value, read_scene_text, requested_scene

PARTS = ("solid", "porous", "sensitivity", "answer")
REGION = "plateau"
UM, NS = 1e-6, 1e-9
QUANTITIES = ("density_mean", "macro_density", "pressure_mean", "macro_normal_stress", "temperature_mean",
              "temperature_std")
EXTRA = ("velocity_y_std", "velocity_x_std")   # measured here: not among mpmshock-converge's quantities
COPIED_FROM = "COPIED_FROM"   # marks a run directory copied from another series' identical run
MADE_BY = "MADE_BY"           # the pinned binary (OUT/bin/mpmshock-SHA) that made a run


# --- what the study runs -------------------------------------------------------------------------

@dataclass
class Series:
    """One mpmshock-converge study: a scene, the refined key's values (coarsest first), seeds, the
    plateau window, the exact answers where known, and labels for the report."""

    part: str
    name: str
    scene: dict                      # scene key -> value text
    values: list                     # refined values, coarsest first (SI; scale factors for av)
    window: tuple                    # plateau window (t0, t1) [s]
    refine: str = "cell_size"
    seeds: int = 1
    sets: list = field(default_factory=list)
    exact: dict = field(default_factory=dict)   # quantity -> exact value (SI)
    info: dict = field(default_factory=dict)


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
        if quantity in self.results:
            return self.results[quantity].values[k]
        return self.extras[quantity][k]

    @property
    def h(self):
        return [c.cell_size for c in self.costs]

    def point_steps(self, k):
        return sum(s["material_points"] * s["steps"] for s in self.summaries[k])

    def wall(self, k):
        return sum(s["wall_seconds"] for s in self.summaries[k])


@dataclass
class Failure:
    """A series whose runs did not all finish."""

    series: Series
    message: str


def scene_text(entries):
    return "".join(f"{key} = {value}\n" for key, value in entries.items())


def _um(x):
    return f"{x / UM:g} um"


def _ns(x):
    return f"{x / NS:g} ns"


def band_deviator(run_dir, spec):
    """Band means at the last snapshot: s_yy (the deviatoric yy stress, Pa), the von Mises
    stress and the plastic strain."""
    from .scene import parse_region
    region = parse_region(spec)
    snap = Run(run_dir).snapshot(-1)
    y = snap["position"][:, 1]
    inside = (y >= region.y1) & (y <= region.y2)
    sigma = snap["stress"][inside]
    dev = sigma - np.eye(3) * (np.trace(sigma, axis1=1, axis2=2) / 3.0)[:, None, None]
    return dict(s_yy=float(dev[:, 1, 1].mean()),
                von_mises=float(np.sqrt(1.5 * np.einsum("nij,nij->n", dev, dev)).mean()),
                plastic_strain=float(snap["plastic_strain"][inside].mean()))


def release_speed(state, material):
    """Eulerian sound speed of the shocked state on the code's Mie-Gruneisen EOS (the speed of the
    head of a release wave into material at rest): c^2 = V^2 (P dP/dE - dP/dV|E)."""
    J, E, V0 = state.J, state.energy, 1.0 / material.density
    d = 1e-6
    dP_dJ = (hugoniot.mie_gruneisen_pressure(J + d, E, material)
             - hugoniot.mie_gruneisen_pressure(J - d, E, material)) / (2 * d)
    P = hugoniot.mie_gruneisen_pressure(J, E, material)
    V = J * V0
    return math.sqrt(V * V * (P * material.gruneisen_gamma * material.density - dP_dJ / V0))


def plateau_window(state, material, height, y2, lag, end_time):
    """(t0, t1, t_release) for a band ending at y2 in a target of the given height.

    t0: the front (lab speed Us - v) has passed y2 + lag, lag covering the smeared shock at the
    coarsest cell and the compaction zone. t1: end_time, or earlier where the release from the top
    free surface could reach y2: the shock meets the top (which moves down at v) at H / Us, and the
    release comes back at 1.1 c (the EOS sound speed, 10 % allowed for the elastic release), less
    the same lag. Whole nanoseconds."""
    t_top = height / state.shock_speed
    y_top = height - state.velocity * t_top
    c = release_speed(state, material)
    t_release = t_top + (y_top - y2) / (1.1 * c)
    t0 = math.ceil((y2 + lag) / state.front_speed / NS - 1e-6) * NS
    t1 = math.floor(min(end_time, t_release - lag / c) / NS + 1e-6) * NS
    if not t1 - t0 >= 10e-9:
        raise PostError(f"plateau window [{t0 / NS:g}, {t1 / NS:g}] ns is too short")
    return t0, t1, t_release


@dataclass
class Plan:
    """Sizes of the study (full or quick)."""

    quick: bool
    solid_speeds: tuple = (500.0, 1000.0, 2000.0)
    solid_cells: tuple = (20e-6, 10e-6, 5e-6)
    solid_extra_cell: float = 2.5e-6       # a fourth level for bspline2, ppc 2, 1000 m/s
    solid_shapes: tuple = ("bspline2", "gimp", "bilinear")
    solid_ppc: tuple = (1, 2, 3)
    solid_width: float = 60e-6
    solid_height: float = 1e-3
    solid_end: float = 200e-9
    solid_band: tuple = (100e-6, 400e-6)
    porous_deltas: tuple = (1.03, 1.1, 1.4)
    porous_seeds: dict = field(default_factory=lambda: {1.03: 3, 1.1: 3, 1.4: 2})
    porous_shapes_at: float = 1.1              # porosity at which gimp and bilinear also run
    porous_shape_seeds: dict = field(default_factory=lambda: {"bilinear": 2, "gimp": 1})
    void_radius: float = 20e-6
    porous_cells: tuple = (10e-6, 5e-6, 2.5e-6)
    porous_width: float = 200e-6
    # delta 1.4 at r/2 cannot reach its porosity within the simulator's 0.5 % in 200 um (one void is
    # 1 % of the body; 1.41011, 1.40969, 1.39171 for seeds 1-3): 240 um can (0.02-0.04 %)
    porous_width_for: dict = field(default_factory=lambda: {1.4: 240e-6})
    porous_height: float = 600e-6
    porous_end_fraction: float = 0.85          # end_time = this x H / Us (the shock stays in the target)
    sensitivity_delta: float = 1.1
    sensitivity_cell: float = 5e-6
    sensitivity_seeds: int = 2
    sensitivity_av: tuple = (2.0, 1.0, 0.5, 0.25)
    sensitivity_cfl: tuple = (0.45, 0.3, 0.2, 0.1)
    sensitivity_flip: tuple = (1.0, 0.99, 0.95)
    answer_cells: tuple = (20e-6, 10e-6, 5e-6)
    answer_check_cells: tuple = (20e-6, 10e-6, 5e-6, 2.5e-6)
    answer_width: float = 500e-6
    answer_height: float = 1.5e-3
    answer_end: float = 250e-9
    answer_seeds: int = 3
    answer_anchor: bool = True                 # run the full geometry once at the coarsest cell

    @classmethod
    def make(cls, quick):
        if not quick:
            return cls(quick=False)
        return cls(quick=True, solid_speeds=(1000.0,), solid_extra_cell=None, solid_shapes=("bspline2", "bilinear"),
                   solid_ppc=(2,), porous_deltas=(1.1,), porous_seeds={1.1: 2}, porous_shape_seeds={},
                   porous_cells=(10e-6, 5e-6), sensitivity_cell=10e-6,
                   sensitivity_seeds=1, sensitivity_av=(2.0, 1.0, 0.5), sensitivity_cfl=(0.45, 0.3, 0.15),
                   sensitivity_flip=(1.0, 0.95), answer_cells=(40e-6, 20e-6, 10e-6),
                   answer_check_cells=(40e-6, 20e-6, 10e-6), answer_width=400e-6, answer_seeds=1, answer_anchor=False)


def solid_series(plan, material):
    series = []
    y1, y2 = plan.solid_band
    for v in plan.solid_speeds:
        exact = hugoniot.solid_shock(v, material)
        t0, t1, t_release = plateau_window(exact, material, plan.solid_height, y2, 4 * plan.solid_cells[0],
                                           plan.solid_end)
        scene = {"velocity": f"{v:g} m/s", "porosity": "1", "plasticity": "off", "width": _um(plan.solid_width),
                 "target_height": _um(plan.solid_height), "flyer_height": _um(plan.solid_height),
                 "end_time": _ns(t1), "sample_interval": "1 ns", "snapshot_interval": "0",
                 f"region.{REGION}": f"band {_um(y1)} {_um(y2)}"}
        truth = {"density_mean": exact.density, "macro_density": exact.density, "pressure_mean": exact.pressure,
                 "macro_normal_stress": exact.pressure, "temperature_mean": exact.temperature}
        info = dict(velocity=v, exact=exact, t_release=t_release)
        combos = [(shape, 2) for shape in plan.solid_shapes]
        combos += [("bspline2", ppc) for ppc in plan.solid_ppc if ppc != 2]
        if v == 1000.0:
            combos += [(shape, ppc) for shape in plan.solid_shapes if shape != "bspline2"
                       for ppc in plan.solid_ppc if ppc != 2]
        for shape, ppc in combos:
            scene_k = dict(scene, shape_function=shape, particles_per_cell=str(ppc))
            series.append(Series("solid", f"v{v:g}_{shape}_ppc{ppc}", scene_k, list(plan.solid_cells), (t0, t1),
                                 exact=truth, info=dict(info, shape=shape, ppc=ppc, plasticity="off")))
        if v == 1000.0 and plan.solid_extra_cell:
            scene_k = dict(scene, shape_function="bspline2", particles_per_cell="2")
            series.append(Series("solid", "v1000_bspline2_ppc2_fine", scene_k,
                                 [*plan.solid_cells, plan.solid_extra_cell], (t0, t1), exact=truth,
                                 info=dict(info, shape="bspline2", ppc=2, plasticity="off", fine=True)))
        if v == 1000.0 and not plan.quick:
            scene_k = dict(scene, shape_function="bspline2", particles_per_cell="2", plasticity="on")
            series.append(Series("solid", "v1000_bspline2_ppc2_plastic", scene_k, list(plan.solid_cells), (t0, t1),
                                 exact=truth, info=dict(info, shape="bspline2", ppc=2, plasticity="on")))
    return series


def porous_scene(plan, delta, material, velocity=1000.0):
    """The porous column of one porosity, its window and its exact full-compaction state."""
    exact = hugoniot.porous_shock(velocity, delta, material)
    r = plan.void_radius
    y1, y2 = 2 * r, 8 * r
    end = math.floor(plan.porous_end_fraction * plan.porous_height / exact.shock_speed / NS + 1e-6) * NS
    t0, t1, t_release = plateau_window(exact, material, plan.porous_height, y2, 4 * plan.porous_cells[0] + 2 * r, end)
    scene = {"velocity": f"{velocity:g} m/s", "porosity": f"{delta:g}", "void_radius": _um(r),
             "width": _um(plan.porous_width_for.get(delta, plan.porous_width)), "target_height": _um(plan.porous_height),
             "flyer_height": _um(plan.porous_height), "end_time": _ns(end), "sample_interval": "1 ns",
             "snapshot_interval": "0", f"region.{REGION}": f"band {_um(y1)} {_um(y2)}"}
    truth = {"density_mean": exact.density, "macro_density": exact.density, "pressure_mean": exact.pressure,
             "macro_normal_stress": exact.pressure, "temperature_mean": exact.temperature}
    return scene, (t0, t1), truth, dict(delta=delta, exact=exact, t_release=t_release, end=end)


def porous_series(plan, material):
    series = []
    for delta in plan.porous_deltas:
        scene, window, truth, info = porous_scene(plan, delta, material)
        shapes = [("bspline2", plan.porous_seeds[delta])]
        if delta == plan.porous_shapes_at:
            shapes += list(plan.porous_shape_seeds.items())
        for shape, seeds in shapes:
            scene_k = dict(scene) if shape == "bspline2" else dict(scene, shape_function=shape)
            series.append(Series("porous", f"d{delta:g}_{shape}", scene_k, list(plan.porous_cells), window,
                                 seeds=seeds, exact=truth, info=dict(info, shape=shape)))
    return series


def sensitivity_series(plan, material):
    """One single-level series per setting, so that a setting whose run fails costs only itself."""
    scene, window, truth, info = porous_scene(plan, plan.sensitivity_delta, material)
    common = dict(seeds=plan.sensitivity_seeds, sets=[f"cell_size={converge._format(plan.sensitivity_cell)}"],
                  exact=truth)
    series = []
    for param, refine, values, label, default in (("av", "av", plan.sensitivity_av, "av scale", 1.0),
                                                   ("cfl", "cfl", plan.sensitivity_cfl, "cfl", 0.3),
                                                   ("flip", "flip_fraction", plan.sensitivity_flip, "flip_fraction", 1.0)):
        for value in values:
            series.append(Series("sensitivity", f"{param}_{value:g}", scene, [value], window, refine=refine,
                                 info=dict(info, param=param, label=label, default=default, value=value), **common))
    return series


def paper_scene_path():
    return ROOT / "configs" / "paper_base.scene"


def answer_scene(plan, material):
    """The paper's base case (configs/paper_base.scene) in a reduced column."""
    entries = read_scene_text(paper_scene_path().read_text())
    entries.pop("output_dir", None)
    full_end = parse_value(entries["end_time"])
    delta = float(entries.get("porosity", "1.03"))
    velocity = parse_value(entries.get("velocity", "1000 m/s"))
    r = parse_value(entries.get("void_radius", "50 um"))
    exact = hugoniot.porous_shock(velocity, delta, material)
    y1, y2 = 2 * r, 10 * r
    t0, t1, t_release = plateau_window(exact, material, plan.answer_height, y2, 4 * plan.answer_cells[0] + 2 * r,
                                       plan.answer_end)
    entries.update({"width": _um(plan.answer_width), "target_height": _um(plan.answer_height),
                    "flyer_height": _um(plan.answer_height), "end_time": _ns(plan.answer_end),
                    "sample_interval": "1 ns", "snapshot_interval": "0",
                    f"region.{REGION}": f"band {_um(y1)} {_um(y2)}"})
    truth = {"density_mean": exact.density, "macro_density": exact.density, "pressure_mean": exact.pressure,
             "macro_normal_stress": exact.pressure, "temperature_mean": exact.temperature}
    info = dict(delta=delta, velocity=velocity, void_radius=r, exact=exact, full_end=full_end, t_release=t_release,
                band=(y1, y2))
    return Series("answer", "reduced", entries, list(plan.answer_cells), (t0, t1), seeds=plan.answer_seeds,
                  exact=truth, info=info)


# --- running ----------------------------------------------------------------------------------------

class Study:
    """Runs series one after another (one mpmshock at a time) and keeps what they ran."""

    def __init__(self, out, binary, log=sys.stderr):
        self.out, self.binary, self.log = out, binary, log
        self.defaults = key_defaults(binary)
        self.material = hugoniot.Material.from_scene(self.defaults)
        self.finished = {}       # scene text -> [run directories of finished runs]
        self.adopted = set()     # run directories copied from another series' run
        self.ran = set()         # run directories this invocation ran
        self.started = time.monotonic()

    def say(self, text):
        print(f"accuracy-study: {text}", file=self.log, flush=True)

    def _args(self, series, directory, scene_path):
        t0, t1 = series.window
        argv = [str(scene_path), "--out", str(directory), "--refine", series.refine,
                "--values", ",".join(converge._format(v) for v in series.values), "--regions", REGION,
                "--window", f"{t0 / NS:.12g}ns", f"{t1 / NS:.12g}ns", "--seeds", str(series.seeds)]
        for override in series.sets:
            argv += ["--set", override]
        args = converge.build_parser().parse_args(argv)
        converge.check_arguments(args)
        return args

    def _planned_runs(self, levels, args):
        """(level, seed, run_dir, requested scene) of each run, as converge.run_levels names them."""
        first = int(requested_scene(args.scene, args.set).get("seed", self.defaults.get("seed", 1)))
        for level in levels:
            for seed in range(first, first + args.seeds):
                overrides = [*args.set, *level.overrides] + ([f"seed={seed}"] if args.seeds > 1 else [])
                yield level, seed, converge.run_directory(args.out, level, seed, args.seeds), \
                    requested_scene(args.scene, overrides)

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
        for _, _, run_dir, requested in self._planned_runs(levels, args):
            if converge.reusable(run_dir, requested, self.defaults):
                continue
            if candidates is None:
                candidates = self._candidates(text, args.out)
            for candidate in candidates:
                if candidate != run_dir and converge.reusable(candidate, requested, self.defaults):
                    if run_dir.exists():
                        shutil.rmtree(run_dir)
                    shutil.copytree(candidate, run_dir, ignore=shutil.ignore_patterns(COPIED_FROM))
                    (run_dir / COPIED_FROM).write_text(f"{candidate}\n")
                    self.adopted.add(run_dir)
                    self.say(f"{run_dir} copied from {candidate}")
                    break

    def run(self, series):
        directory = self.out / series.part / series.name
        directory.mkdir(parents=True, exist_ok=True)
        text = scene_text(series.scene)
        scene_path = directory / "study.scene"
        if not scene_path.is_file() or scene_path.read_text() != text:
            scene_path.write_text(text)
        args = self._args(series, directory, scene_path)
        levels = converge.plan_levels(args.refine, args.values, args.levels,
                                      requested_scene(args.scene, args.set), self.defaults)
        self._adopt(text, levels, args)
        before = {run_dir: _mtime(run_dir) for _, _, run_dir, _ in self._planned_runs(levels, args)}
        self.say(f"series {series.part}/{series.name}")
        try:
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
            converge.run_levels(levels, args, self.binary, self.defaults, log=self.log)
        except PostError:
            if self.binary.is_file():
                raise
            self.wait_for_binary()
            for level in levels:
                level.runs.clear()
            converge.run_levels(levels, args, self.binary, self.defaults, log=self.log)

    def check(self, scene, cell_size, extra=()):
        """(material points, step lower bound, end time) that `mpmshock SCENE --check` prints."""
        self.wait_for_binary()
        command = [str(self.binary), str(scene), "--check", "--set", f"cell_size={converge._format(cell_size)}"]
        for override in extra:
            command += ["--set", override]
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            raise PostError(f"{' '.join(command)} exited {done.returncode}: {done.stderr.strip()}")
        points = re.search(r"^material points: (\d+)", done.stdout, re.M)
        steps = re.search(r"at least (\d+) steps to ", done.stdout)
        if not (points and steps):
            raise PostError(f"{' '.join(command)}: no point or step count in\n{done.stdout}")
        return int(points.group(1)), int(steps.group(1))

    def run_single(self, scene, overrides, run_dir):
        """One run outside a convergence series (the full-geometry anchor), reused when finished."""
        requested = requested_scene(scene, overrides)
        if converge.reusable(run_dir, requested, self.defaults):
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


def _mtime(run_dir):
    try:
        return (run_dir / "summary.json").stat().st_mtime_ns
    except OSError:
        return None


def extra_quantity(run_dir, quantity, window):
    """A plateau mean of a regions.csv column mpmshock-converge does not measure (velocity std)."""
    columns = Run(run_dir).regions()[REGION]
    times = columns["time"]
    return converge.sample(columns[quantity], times, converge.run_window(times, window), None)


# --- numbers for the report ---------------------------------------------------------------------------

RELATIVE = {"density_mean": True, "macro_density": True, "pressure_mean": True, "macro_normal_stress": True,
            "macro_pressure": True, "temperature_mean": False, "temperature_std": False,
            "velocity_y_std": False, "velocity_x_std": False}
LABEL = {"density_mean": "density_mean", "macro_density": "macro_density", "pressure_mean": "pressure_mean",
         "macro_normal_stress": "macro_normal_stress", "temperature_mean": "temperature_mean",
         "temperature_std": "temperature_std", "velocity_y_std": "velocity_y_std", "velocity_x_std": "velocity_x_std"}
SHAPE_COLORS = {"bspline2": "tab:blue", "gimp": "tab:green", "bilinear": "tab:red"}
PPC_STYLES = {1: ":", 2: "-", 3: "--"}
SPEED_MARKERS = {500.0: "v", 1000.0: "o", 2000.0: "^"}


def display(quantity, value):
    """SI value in the report's units (g/cm3 shown as kg/m3, GPa, K, m/s)."""
    if "pressure" in quantity or "stress" in quantity:
        return f"{value * 1e-9:.4g} GPa"
    if "density" in quantity:
        return f"{value:.5g} kg/m3"
    if "temperature" in quantity:
        return f"{value:.4g} K"
    return f"{value:.3g} m/s"


def unit_value(quantity, value, digits=4):
    """The number alone in the report's units."""
    if "pressure" in quantity or "stress" in quantity:
        return f"{value * 1e-9:.{digits}g}"
    return f"{value:.{digits}g}"


def unit_of(quantity):
    if "pressure" in quantity or "stress" in quantity:
        return "GPa"
    if "density" in quantity:
        return "kg/m3"
    if "temperature" in quantity:
        return "K"
    return "m/s"


def error_text(quantity, error, reference=None, signed=True):
    """A relative error in % for densities and pressures, an absolute one in K (or m/s) otherwise."""
    if error is None or not math.isfinite(error):
        return "-"
    if RELATIVE.get(quantity, False):
        value = 100.0 * error / abs(reference)
        return f"{value:+.3g} %" if signed else f"{abs(value):.2g} %"
    return f"{error:+.3g} {unit_of(quantity)}" if signed else f"{abs(error):.2g} {unit_of(quantity)}"


def order_text(estimate):
    """The observed order, or why there is none (the fallback)."""
    if math.isfinite(estimate.order):
        return f"{estimate.order:.2f}"
    return "none: " + estimate.note.replace("fallback: ", "")


def exact_order(errors, hs):
    """Order the true errors of the two finest levels show: log(|e1|/|e2|) / log(h1/h2); None when
    the errors change sign or vanish."""
    e1, e2 = errors[-2], errors[-1]
    if e1 == 0 or e2 == 0 or e1 * e2 < 0:
        return None
    return math.log(abs(e1) / abs(e2)) / math.log(hs[-2] / hs[-1])


def needed_resolution(result, hs, target, relative):
    """The coarsest tested h whose discretisation estimate (and every finer one's) meets the target;
    beyond the finest, h_f (target / e_f)^(1/p) with the observed order (1 in the fallback).
    Returns (h, estimated error at h, how)."""
    est = result.estimate
    scale = abs(est.extrapolated) if relative else 1.0
    if not (math.isfinite(scale) and scale > 0):
        return None, math.nan, "no estimate"
    errors = [e / scale for e in est.errors]
    for k in range(len(errors)):
        if all(e <= target for e in errors[k:]):
            return hs[k], errors[k], "measured"
    p = est.order if math.isfinite(est.order) else 1.0
    h = hs[-1] * (target / errors[-1]) ** (1.0 / p) if errors[-1] > 0 else hs[-1]
    how = f"extrapolated (order {p:.2f})" if math.isfinite(est.order) else "extrapolated (fallback order 1)"
    return h, target, how


def nice_cell(h, width):
    """The largest cell size <= h that divides the width into whole cells, from 1-2-2.5-4-5-8 steps."""
    candidates = sorted({m * 10.0 ** e for e in range(-8, -3) for m in (1, 1.25, 2, 2.5, 4, 5, 8)}, reverse=True)
    for c in candidates:
        if c <= h * (1 + 1e-9) and abs(width / c - round(width / c)) < 1e-6:
            return c
    return h


def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]


def h_text(h):
    return f"{h / UM:.3g} um"


def seeds_text(outcome):
    n = outcome.series.seeds
    return f"{n} void layout{'s' if n > 1 else ''} (seeds {', '.join(str(1 + s) for s in range(n))})"


# --- figures --------------------------------------------------------------------------------------

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


def _all_legend_entries(axes):
    handles, labels = [], []
    for ax in np.ravel(axes):
        for hnd, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(hnd)
                labels.append(lab)
    return handles, labels


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
            _cell_axis(ax, sorted({c / UM for o in solid for c in o.h}))
            ax.set_title(f"{q}, {v:g} m/s", fontsize=8)
            ax.set_xlabel("cell size (um)", fontsize=7)
            ax.set_ylabel(f"|error| ({unit})", fontsize=7)
            ax.tick_params(labelsize=6)
            lo, hi = ax.get_ylim()
            for p, ls in ((1, (0, (1, 3))), (2, (0, (4, 4)))):
                ref = hi * 0.5 * (h / h[-1]) ** p
                ax.loglog(h, ref, color="gray", lw=0.6, linestyle=ls, label=f"slope {p}")
            ax.set_ylim(lo, hi)
    _legend(fig, *_all_legend_entries(axes), 6)
    return _save(fig, path)


def figure_solid_cost(solid, path):
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
    _legend(fig, *_all_legend_entries(axes), 5)
    return _save(fig, path)


POROUS_PLOTTED = ("macro_normal_stress", "pressure_mean", "macro_density", "density_mean", "temperature_mean")


def figure_porous(porous, r, path):
    deltas = sorted({o.series.info["delta"] for o in porous})
    fig, axes = _figure(len(POROUS_PLOTTED), len(deltas), size=(3.3, 2.3))
    for col, delta in enumerate(deltas):
        for row, q in enumerate(POROUS_PLOTTED):
            ax = axes[row, col]
            for o in (o for o in porous if o.series.info["delta"] == delta):
                res = o.results[q]
                hr = np.array(o.h) / r
                factor = 1e-9 if unit_of(q) == "GPa" else 1.0
                color = SHAPE_COLORS[o.series.info["shape"]]
                ax.errorbar(hr, np.array(res.values) * factor, yerr=np.array(res.standard_errors) * factor,
                            marker="o", ms=3, color=color, capsize=2, label=f"{o.series.info['shape']} (seed mean)")
                for k, paths in enumerate(o.run_dirs):
                    for path_ in paths:
                        ax.plot(hr[k], _plateau(path_, q, o.series.window) * factor, ".", color=color, ms=2, alpha=0.5)
                if math.isfinite(res.estimate.order):
                    ax.plot([hr[-1] / 2], [res.estimate.extrapolated * factor], "*", color=color, ms=7,
                            label="extrapolated (observed order)")
                exact = o.series.exact.get(q)
            if exact is not None:
                ax.axhline(exact * factor, color="k", lw=0.8, linestyle="--", label="full-compaction Hugoniot")
            ax.set_xscale("log")
            ax.set_xticks([0.0625, 0.125, 0.25, 0.5, 1.0])
            ax.set_xticklabels(["1/16", "1/8", "1/4", "1/2", "1"])
            ax.set_xlim(hr[-1] / 2.8, hr[0] * 1.4)
            ax.set_title(f"{q}, delta {delta:g}", fontsize=8)
            ax.set_xlabel("h / r", fontsize=7)
            ax.set_ylabel(unit_of(q), fontsize=7)
            ax.tick_params(labelsize=6)
    _legend_of_all(fig, axes, 4)
    return _save(fig, path)


def _plateau(run_dir, quantity, window):
    columns = Run(run_dir).regions()[REGION]
    return converge.sample(columns[quantity], columns["time"], window, None)


SENSITIVITY_PLOTTED = ("macro_normal_stress", "pressure_mean", "macro_density", "temperature_mean", "temperature_std",
                       "velocity_y_std")


def figure_sensitivity(groups, path):
    fig, axes = _figure(len(SENSITIVITY_PLOTTED), len(groups), size=(3.0, 2.0))
    for col, (param, group) in enumerate(groups.items()):
        values = [o.series.info["value"] for o in group]
        for row, q in enumerate(SENSITIVITY_PLOTTED):
            ax = axes[row, col]
            factor = 1e-9 if unit_of(q) == "GPa" else 1.0
            ax.plot(values, [o.value(q, 0) * factor for o in group], "o-", color="tab:blue", ms=3, label="layout mean")
            for value, o in zip(values, group):
                for p in o.run_dirs[0]:
                    ax.plot(value, _plateau(p, q, o.series.window) * factor, ".", color="tab:gray", ms=3,
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
    _legend_of_all(fig, axes, 5)
    return _save(fig, path)


def figure_answer(o, table, path):
    fig, axes = _figure(1, 3, size=(3.4, 2.8))
    hs = np.array(o.h) / UM
    for ax, q in zip(axes[0, :2], ("pressure_mean", "temperature_mean")):
        res = o.results[q]
        factor = 1e-9 if unit_of(q) == "GPa" else 1.0
        ax.errorbar(hs, np.array(res.values) * factor, yerr=np.array(res.standard_errors) * factor, marker="o",
                    ms=3, capsize=2, label="seed mean, standard error")
        for k, paths in enumerate(o.run_dirs):
            for p in paths:
                ax.plot(hs[k], _plateau(p, q, o.series.window) * factor, ".", color="tab:gray", ms=3,
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


# --- the report, part by part -----------------------------------------------------------------------

class Report:
    """Collects the document's sections, the findings for its summary and the figures it links."""

    def __init__(self, docs, plan, study):
        self.docs, self.plan, self.study = docs, plan, study
        self.sections, self.findings, self.figures = [], [], []

    def figure(self, name, draw, *args):
        path = self.docs / f"accuracy_{name}.png"
        draw(*args, path)
        self.figures.append(path)
        return f"![{name}](accuracy_{name}.png)"


def _shape_key(o):
    order = {"bspline2": 0, "gimp": 1, "bilinear": 2}
    return (o.series.info.get("velocity", 0), order.get(o.series.info.get("shape"), 9), o.series.info.get("ppc", 0))


def solid_section(report, outcomes):
    standard = sorted((o for o in outcomes if o.series.info["plasticity"] == "off" and not o.series.info.get("fine")),
                      key=_shape_key)
    fine = [o for o in outcomes if o.series.info.get("fine")]
    plastic = [o for o in outcomes if o.series.info["plasticity"] == "on"]
    plan = report.plan
    s0 = standard[0].series
    cells = ", ".join(h_text(h) for h in standard[0].h)
    lines = ["## 1. Solid plates against the exact Rankine-Hugoniot state", "",
             f"Symmetric impact of solid plates (porosity 1, plasticity off, so that the hydrodynamic "
             f"Rankine-Hugoniot state of physics-notes section 3 is exact), column {h_text(plan.solid_width)} wide "
             f"(3 cells at 20 um: the narrowest column the simulator allows), bodies {plan.solid_height * 1e3:g} mm, "
             f"band region `{s0.scene['region.' + REGION]}` in the target, cell sizes {cells}. "
             "Each number is the band's plateau mean over the window below; the error is value - exact, relative "
             "for densities and pressures, in K for temperatures.", "",
             "| speed | exact rho (kg/m3) | exact P (GPa) | exact T (K) | end_time | plateau window | "
             "release would reach the band |", "|---|---|---|---|---|---|---|"]
    for v in sorted({o.series.info["velocity"] for o in standard}):
        o = next(o for o in standard if o.series.info["velocity"] == v)
        ex = o.series.info["exact"]
        lines.append(f"| {v:g} m/s | {ex.density:.5g} | {ex.pressure * 1e-9:.4g} | {ex.temperature:.4g} | "
                     f"{o.series.scene['end_time']} | {o.series.window[0] / NS:g}-{o.series.window[1] / NS:g} ns | "
                     f"{o.series.info['t_release'] / NS:.0f} ns |")
    lines += ["", "The window starts when the front (lab speed Us - v) has passed the top of the band by four "
              "coarse cells, and ends at end_time, which is chosen before the release from the top free surface "
              "(the shock meets the top at H/Us; the release returns at 1.1 times the EOS sound speed of the shocked "
              "state) could reach the band. The time series of every case are in the last figure of this document.",
              ""]
    # the error tables
    for q in SOLID_PLOTTED:
        header = ["speed", "shape", "ppc", *(f"error {h_text(h)}" for h in standard[0].h),
                  "order vs exact (finest pair)", "tool's observed order", "tool's estimate (finest)",
                  "estimate / true error", "extrapolated error"]
        rows = []
        for o in standard:
            ex = o.series.exact[q]
            res = o.results[q]
            errors = [v - ex for v in res.values]
            p = exact_order(errors, o.h)
            est = res.estimate.errors[-1]
            ratio = est / abs(errors[-1]) if errors[-1] else math.inf
            rows.append([f"{o.series.info['velocity']:g}", o.series.info["shape"], o.series.info["ppc"],
                         *(error_text(q, e, ex) for e in errors), "-" if p is None else f"{p:.2f}",
                         order_text(res.estimate), error_text(q, est, ex, signed=False), f"{ratio:.2g}",
                         error_text(q, res.estimate.extrapolated - ex, ex)])
        lines += [f"### {q}", ""] + md_table(header, rows) + [""]
    lines += ["'order vs exact' is log(|e(2h)| / |e(h)|) / log 2 from the true errors of the two finest levels "
              "('-' where they change sign); 'tool's observed order' is mpmshock-converge's, from the differences "
              "between the three levels, without knowing the answer; 'estimate / true error' below 1 means the tool "
              "underestimated the error of the finest level.", ""]
    lines.append(report.figure("solid_h", figure_solid_h, standard + fine))
    lines += ["", "*|error| of the plateau against cell size; colour: shape function; line: points per cell "
              "(dotted 1, solid 2, dashed 3); grey: slopes 1 and 2.*", ""]
    lines.append(report.figure("solid_cost", figure_solid_cost, standard + fine))
    lines += ["", "*|error| at 1000 m/s against the wall time of the run (both cores; the machine was shared, so "
              "times scatter by tens of per cent; point-steps are the steadier cost measure, tabled below).*", ""]
    # cost table at 1000 m/s
    at = [o for o in standard + fine if o.series.info["velocity"] == 1000.0]
    if at:
        rows = []
        for o in at:
            for k, h in enumerate(o.h):
                if o.series.info.get("fine") and k < len(o.h) - 1:
                    continue
                s = o.summaries[k][0]
                rows.append([o.series.info["shape"], o.series.info["ppc"], h_text(h), s["material_points"], s["steps"],
                             f"{s['material_points'] * s['steps']:.3g}", f"{s['wall_seconds']:.2f}",
                             f"{s['point_steps_per_second']:.3g}", f"{s['threads']} ({s['steps_with_fewer_threads']} "
                             f"steps on fewer)", f"{abs(s['energy_error']):.1e}"])
        lines += ["### Cost at 1000 m/s", ""] + md_table(
            ["shape", "ppc", "cell", "points", "steps", "point-steps", "wall (s)", "point-steps/s", "threads",
             "energy error"], rows) + [""]
    # the fourth level
    for o in fine:
        q_rows = []
        for q in SOLID_PLOTTED:
            ex = o.series.exact[q]
            res = o.results[q]
            errors = [v - ex for v in res.values]
            coarse = converge.richardson(res.values[:3], o.h[:3])
            q_rows.append([q, *(error_text(q, e, ex) for e in errors),
                           "-" if exact_order(errors[:3], o.h[:3]) is None else f"{exact_order(errors[:3], o.h[:3]):.2f}",
                           "-" if exact_order(errors, o.h) is None else f"{exact_order(errors, o.h):.2f}",
                           order_text(coarse), order_text(res.estimate),
                           f"{res.estimate.errors[-1] / abs(errors[-1]):.2g}" if errors[-1] else "-"])
        lines += ["### A fourth level (bspline2, 2 points per cell, 1000 m/s, down to 2.5 um)", "",
                  "Is the order the three standard levels show already the asymptotic one?", ""]
        lines += md_table(["quantity", *(f"error {h_text(h)}" for h in o.h), "order vs exact 20/10/5",
                           "order vs exact 10/5/2.5", "tool's order 20/10/5", "tool's order 10/5/2.5",
                           "tool's estimate / true (2.5 um)"], q_rows) + [""]
    # plasticity
    for o in plastic:
        off = next(x for x in standard if x.series.info["velocity"] == o.series.info["velocity"]
                   and x.series.info["shape"] == o.series.info["shape"] and x.series.info["ppc"] == o.series.info["ppc"])
        defaults = report.study.defaults
        sy0, Et, E = defaults["yield_stress"], defaults["tangent_modulus"], defaults["youngs_modulus"]
        Ep = E * Et / (E - Et)
        J = o.series.info["exact"].J
        y_hard = sy0 + Ep * (2.0 / 3.0) * abs(math.log(J))
        rows, deviators = [], []
        for k, h in enumerate(o.h):
            d_sigma = o.results["macro_normal_stress"].values[k] - off.results["macro_normal_stress"].values[k]
            d_p = o.results["pressure_mean"].values[k] - off.results["pressure_mean"].values[k]
            d_t = o.results["temperature_mean"].values[k] - off.results["temperature_mean"].values[k]
            d_rho = o.results["density_mean"].values[k] - off.results["density_mean"].values[k]
            dev = band_deviator(o.run_dirs[k][0], o.series.scene[f"region.{REGION}"])
            deviators.append(dev)
            rows.append([h_text(h), f"{o.results['macro_normal_stress'].values[k] * 1e-9:.4f}",
                         f"{off.results['macro_normal_stress'].values[k] * 1e-9:.4f}", f"{d_sigma * 1e-6:+.0f}",
                         f"{d_p * 1e-6:+.0f}", f"{(d_sigma - d_p) * 1e-6:+.0f}", f"{d_rho:+.2f}", f"{d_t:+.2f}",
                         f"{-dev['s_yy'] * 1e-6:.0f}", f"{dev['von_mises'] * 1e-6:.0f}", f"{dev['plastic_strain']:.3f}"])
        lines += ["### Strength on (plasticity = on, 1000 m/s, bspline2, 2 points per cell)", "",
                  f"With von Mises strength the normal stress across the band exceeds the pressure by (2/3) Y: "
                  f"{2 / 3 * sy0 * 1e-6:.0f} MPa at the initial yield stress {sy0 * 1e-6:.0f} MPa, about "
                  f"{2 / 3 * y_hard * 1e-6:.0f} MPa with the hardening (E_p = E E_tan/(E - E_tan) = "
                  f"{Ep * 1e-6:.0f} MPa) over the plastic strain (2/3)|ln J| = {2 / 3 * abs(math.log(J)):.3f} of "
                  "uniaxial compression. The Rankine-Hugoniot jump fixes the normal stress (rho0 Us u_p) rather than "
                  "the pressure, so strength mostly lowers the pressure at a nearly unchanged normal stress.", ""]
        lines += md_table(["cell", "sigma_n on (GPa)", "sigma_n off (GPa)", "sigma_n on-off (MPa)",
                           "P on-off (MPa)", "(sigma_n - P) on-off (MPa)", "rho on-off (kg/m3)", "T on-off (K)",
                           "-s_yy at the end (MPa)", "von Mises stress at the end (MPa)", "plastic strain"],
                          rows) + [""]
        finest = deviators[-1]
        lines += ["The last three columns are band means over the points of the final snapshot (t = end_time). "
                  + (f"**Not what the jump conditions expect:** the shocked plateau is not at the yield surface. "
                     f"Its von Mises stress is {finest['von_mises'] * 1e-6:.0f} MPa, below the initial yield stress "
                     f"{sy0 * 1e-6:.0f} MPa, and -s_yy = {-finest['s_yy'] * 1e-6:.0f} MPa instead of (2/3) Y = "
                     f"{2 / 3 * sy0 * 1e-6:.0f}-{2 / 3 * y_hard * 1e-6:.0f} MPa; the plastic strain, "
                     f"{finest['plastic_strain']:.3f}, exceeds the {2 / 3 * abs(math.log(J)):.3f} of a monotone "
                     "uniaxial compression: the points yielded more than a monotone compression needs, presumably back "
                     "and forth in the overshooting, ringing numerical shock, and the plateau is left elastically "
                     "unloaded below yield, so strength adds far less than (2/3) Y to the normal stress here (not "
                     "diagnosed further)."
                     if finest["von_mises"] < 0.9 * sy0 else
                     f"The plateau sits at the yield surface (von Mises {finest['von_mises'] * 1e-6:.0f} MPa)."), ""]
        report.findings.append(
            f"Solid with strength (plasticity on, 1000 m/s, bspline2): at {h_text(o.h[-1])} the normal stress "
            f"exceeds the pressure by {(rows and float(rows[-1][5])):+.0f} MPa more than without strength, not by "
            f"(2/3) Y = {2 / 3 * sy0 * 1e-6:.0f}-{2 / 3 * y_hard * 1e-6:.0f} MPa: the plateau ends below yield "
            f"(von Mises {finest['von_mises'] * 1e-6:.0f} MPa, plastic strain {finest['plastic_strain']:.3f} against "
            f"{2 / 3 * abs(math.log(J)):.3f} for monotone uniaxial compression).")
        res = o.results["macro_normal_stress"]
        lines += [f"Normal stress with strength: extrapolated {res.estimate.extrapolated * 1e-9:.4f} GPa "
                  f"(order {order_text(res.estimate)}), against rho0 Us u_p = "
                  f"{o.series.exact['macro_normal_stress'] * 1e-9:.4f} GPa of the hydrodynamic Hugoniot.", ""]
    # findings: per shape at 2 points per cell, the largest error at the finest cell and the orders
    for shape in ("bspline2", "gimp", "bilinear"):
        group = [o for o in standard if o.series.info["shape"] == shape and o.series.info["ppc"] == 2]
        if not group:
            continue
        parts = []
        for q in ("pressure_mean", "macro_normal_stress", "density_mean", "temperature_mean"):
            errors = [o.results[q].values[-1] - o.series.exact[q] for o in group]
            worst = max(range(len(group)), key=lambda i: abs(errors[i]))
            orders = [exact_order([v - o.series.exact[q] for v in o.results[q].values], o.h) for o in group]
            parts.append(f"{q} {error_text(q, errors[worst], group[worst].series.exact[q])} (orders "
                         + "/".join("-" if p is None else f"{p:.1f}" for p in orders) + ")")
        speeds = "/".join(f"{o.series.info['velocity']:g}" for o in group)
        report.findings.append(f"Solid, {shape}, 2 points per cell: the largest error at {h_text(group[0].h[-1])} over "
                               f"{speeds} m/s, with the order of the true errors from {h_text(group[0].h[-2])} to "
                               f"{h_text(group[0].h[-1])} at each speed ('-': the error changed sign): "
                               + "; ".join(parts) + ".")
    report.sections.append(lines)


def porous_section(report, outcomes):
    plan = report.plan
    r = plan.void_radius
    main = sorted((o for o in outcomes if o.series.info["shape"] == "bspline2"), key=lambda o: o.series.info["delta"])
    shapes = [o for o in outcomes if o.series.info["shape"] != "bspline2"]
    o0 = main[0]
    lines = ["## 2. Porous bodies: convergence under void resolution", "",
             f"Porosity delta = 1.03, 1.1, 1.4 at 1000 m/s; void radius r = {h_text(r)} for all (no spread, no "
             f"overlap, mirrored flyer: the simulator's defaults), cell sizes "
             f"{', '.join(h_text(h) for h in o0.h)} (h/r = {', '.join(f'1/{r / h:g}' for h in o0.h)}), column "
             f"{h_text(plan.porous_width)} wide" + "".join(
                 f" ({h_text(w)} at delta {d:g}: at h = r/2 one void is 1 % of a {h_text(plan.porous_width)} "
                 "column's body, and the simulator's 0.5 % tolerance on the achieved porosity could not be met "
                 "there)" for d, w in plan.porous_width_for.items() if d in plan.porous_deltas) +
             f", bodies {h_text(plan.porous_height)}, bspline2 with 2 points per cell. The band region runs from 2r to 8r above the impact plane. Several void layouts (seeds) per "
             "level separate the layout scatter (the standard error of the seed mean, 'SE') from the "
             "discretisation error ('disc.', mpmshock-converge's estimate from the seed means).", "",
             "| delta | voids per body | exact rho (kg/m3) | exact P (GPa) | exact T (K) | Us (m/s) | end_time | "
             "plateau window | layouts |", "|---|---|---|---|---|---|---|---|---|"]
    for o in main + shapes:
        ex = o.series.info["exact"]
        voids = [s["voids"] / 2 for s in o.summaries[-1]]
        lines.append(f"| {o.series.info['delta']:g}{'' if o in main else ' (' + o.series.info['shape'] + ')'} | "
                     f"{np.mean(voids):.0f} | {ex.density:.5g} | {ex.pressure * 1e-9:.4g} | {ex.temperature:.4g} | "
                     f"{ex.shock_speed:.0f} | {o.series.scene['end_time']} | "
                     f"{o.series.window[0] / NS:g}-{o.series.window[1] / NS:g} ns | {o.series.seeds} |")
    lines += ["", "'exact' is the full-compaction porous Hugoniot (mpmshock_post.hugoniot.porous_shock): all voids "
              "closed, the compacted solid on the code's Mie-Grüneisen EOS. end_time is 0.85 H/Us, so the front "
              "(which in the simulations runs somewhat ahead of the full-compaction speed) stays in the target; "
              "the window starts when the front has passed the band's top by four coarse cells and 2r.", "",
              "The quantities: `macro_density` and `macro_normal_stress` are per band area (voids and gaps count), "
              "which is what the porous Hugoniot's jump conditions speak of; `density_mean` and `pressure_mean` are "
              "the points' own values averaged over points, blind to any void left open between them.", ""]
    for o in main:
        rows = []
        for q in (*QUANTITIES,):
            res = o.results[q]
            ex = o.series.exact.get(q)
            limit = res.estimate.extrapolated
            rows.append([q, *(f"{unit_value(q, v)} ± {unit_value(q, se, 2)}" for v, se in
                              zip(res.values, res.standard_errors)),
                         unit_value(q, limit), order_text(res.estimate),
                         error_text(q, res.estimate.errors[-1], limit, signed=False),
                         error_text(q, res.standard_errors[-1], limit, signed=False),
                         "-" if ex is None else unit_value(q, ex),
                         "-" if ex is None else error_text(q, limit - ex, ex)])
        lines += [f"### delta {o.series.info['delta']:g} ({seeds_text(o)})", ""]
        lines += md_table(["quantity (units)", *(f"h/r = 1/{r / h:g}" for h in o.h), "limit", "order",
                           "disc. error (finest)", "SE (finest)", "full compaction", "limit - full compaction"],
                          rows) + [""]
    lines += ["Units: kg/m3, GPa, K. 'limit' is the Richardson extrapolation where an order is observed, else "
              "the finest value (fallback); '± x' is the standard error over the layouts.", ""]
    # resolution needed
    header = ["delta", *(f"{q} {t:g} %" for q in ("macro_normal_stress", "pressure_mean") for t in (1, 3, 10))]
    rows = []
    need = {}
    for o in main:
        row = [f"{o.series.info['delta']:g}"]
        for q in ("macro_normal_stress", "pressure_mean"):
            for t in (1, 3, 10):
                h, err, how = needed_resolution(o.results[q], o.h, t / 100.0, True)
                need[(o.series.info["delta"], q, t)] = (h, how)
                row.append("-" if h is None else (f"h/r = 1/{r / h:.2g} ({h_text(h)})" +
                                                  ("" if how == "measured" else f", {how}")))
        rows.append(row)
    lines += ["### The resolution each porosity needs", "",
              "The coarsest tested h/r whose estimated discretisation error (against the porosity's own limit) is "
              "within the target at that level and every finer one; where none is, the h/r that the observed "
              "order (or order 1 in the fallback) extrapolates to, beyond what was run. These are errors against "
              "the converged simulation, not against the full-compaction Hugoniot (the column 'limit - full "
              "compaction' above is that model difference), and they leave out the layout scatter (SE).", ""]
    lines += md_table(header, rows) + [""]
    # residual porosity
    rows = []
    for o in main:
        k = len(o.h) - 1
        rho_pts, rho_macro = o.results["density_mean"].values[k], o.results["macro_density"].values[k]
        ex = o.series.info["exact"]
        rows.append([f"{o.series.info['delta']:g}", h_text(o.h[k]), f"{rho_pts:.5g}", f"{rho_macro:.5g}",
                     f"{ex.density:.5g}", f"{100 * (rho_pts / rho_macro - 1):+.2f} %",
                     f"{100 * (rho_macro / ex.density - 1):+.2f} %", f"{100 * (rho_pts / ex.density - 1):+.2f} %"])
    lines += ["### Residual porosity: the points' density against the band's", "",
              "After the shock the band's mass over its area (`macro_density`) is below the points' own mean "
              "density (`density_mean`) by the voids still open between points; the points' density then overstates "
              "the compaction.", ""]
    lines += md_table(["delta", "cell", "density_mean", "macro_density", "full compaction",
                       "density_mean / macro_density - 1 (open voids)", "macro_density vs full compaction",
                       "density_mean vs full compaction"], rows) + [""]
    # shapes
    if shapes:
        delta = shapes[0].series.info["delta"]
        base = next(o for o in main if o.series.info["delta"] == delta)
        rows = []
        for o in [base] + shapes:
            for q in ("macro_normal_stress", "pressure_mean", "macro_density", "density_mean", "temperature_mean"):
                res = o.results[q]
                ref = base.results[q].estimate.extrapolated
                dist = [abs(v - ref) for v in res.values]
                trend = ("moves away from the bspline2 limit with refinement" if dist[-1] > dist[-2] > dist[0] or
                         dist[-1] > dist[0] * 1.5 else "")
                rows.append([o.series.info["shape"], o.series.seeds, q,
                             *(unit_value(q, v) for v in res.values), unit_value(q, res.estimate.extrapolated),
                             order_text(res.estimate), error_text(q, res.values[-1] - ref, ref), trend])
        lines += [f"### Shape functions at delta {delta:g}", "",
                  "The same column and layouts (seeds 1, 2, ...) with gimp and bilinear cells. The last columns "
                  "compare each finest value with the bspline2 limit.", ""]
        lines += md_table(["shape", "layouts", "quantity", *(f"h/r = 1/{r / h:g}" for h in base.h), "own limit",
                           "order", "finest - bspline2 limit", "trend"], rows) + [""]
        for o in shapes:
            away = [q for q in ("macro_normal_stress", "pressure_mean", "temperature_mean")
                    if abs(o.results[q].values[-1] - base.results[q].estimate.extrapolated) >
                    abs(o.results[q].values[0] - base.results[q].estimate.extrapolated)]
            if away:
                report.findings.append(
                    f"Porous delta {delta:g}, {o.series.info['shape']}: {', '.join(away)} end further from the "
                    f"bspline2 limit at h/r = 1/{r / o.h[-1]:g} than at 1/{r / o.h[0]:g}: refinement does not "
                    "help it there.")
    lines.append(report.figure("porous", figure_porous, main + shapes, r))
    lines += ["", "*Plateau values against h/r: large dots are seed means with their standard error, small dots "
              "single layouts, stars the Richardson limit where an order was observed; dashed: the full-compaction "
              "Hugoniot.*", ""]
    for o in main:
        d = o.series.info["delta"]
        q = "macro_normal_stress"
        res = o.results[q]
        text = ", ".join(f"{t} %: " + (f"h/r = 1/{r / need[(d, q, t)][0]:.2g}" if need[(d, q, t)][0] else "-") +
                         ("" if need[(d, q, t)][1] == "measured" else " (extrapolated)") for t in (1, 3, 10))
        ex = o.series.exact[q]
        rho = o.results["macro_density"]
        report.findings.append(
            f"Porous delta {d:g} (r = {h_text(r)}, {o.series.seeds} layouts): normal stress needs {text}; its limit "
            f"{res.estimate.extrapolated * 1e-9:.3g} GPa (order {order_text(res.estimate)}) is "
            f"{error_text(q, res.estimate.extrapolated - ex, ex)} from full compaction ({ex * 1e-9:.3g} GPa); "
            f"macro_density at h/r = 1/{r / o.h[-1]:g} is {error_text('macro_density', rho.values[-1] - o.series.exact['macro_density'], o.series.exact['macro_density'])} "
            f"from full compaction, density_mean {error_text('density_mean', o.results['density_mean'].values[-1] - o.series.exact['density_mean'], o.series.exact['density_mean'])}.")
    report.sections.append(lines)
    return need


def _sensitivity_groups(outcomes):
    """param -> [outcome per value, in the plan's order]."""
    groups = {}
    for o in outcomes:
        groups.setdefault(o.series.info["param"], []).append(o)
    return groups


def sensitivity_section(report, outcomes, failures):
    r = report.plan.void_radius
    h = report.plan.sensitivity_cell
    any_o = (outcomes or failures)[0]
    delta = any_o.series.info["delta"]
    lines = ["## 3. Sensitivity to the numerical parameters", "",
             f"delta {delta:g}, the porous column of part 2 at h = {h_text(h)} (h/r = 1/{r / h:g}), bspline2, "
             f"2 points per cell, {report.plan.sensitivity_seeds} void layouts (seeds 1-{report.plan.sensitivity_seeds}); "
             "one parameter varied at a time from the defaults (av_linear 0.2, av_quadratic 2, cfl 0.3, "
             "flip_fraction 1). Each value is the mean over the layouts (the same layouts for every setting, so "
             "the differences between settings are not layout scatter); in brackets the change from the default "
             "setting. 'layout spread' is half the range over the layouts at the default setting: a change well "
             "inside it would move with another choice of layouts. "
             f"h = {h_text(h)} rather than the finest {h_text(report.plan.porous_cells[-1])} of part 2: the eight "
             "extra settings would cost 8x more there (cfl 0.1 alone three runs' worth), beyond the study's budget.",
             "", "`flip_fraction` (new): the point velocity after each step is f times the FLIP update (the grid's "
             "velocity change added to the point's own velocity) plus (1 - f) times the PIC one (the grid velocity "
             "interpolated back); f = 1 keeps the total energy to round-off but also the point-to-point velocity "
             "noise, f < 1 damps that noise and turns its kinetic energy into heat.", ""]
    quantities = ("macro_density", "macro_normal_stress", "density_mean", "pressure_mean", "temperature_mean",
                  "temperature_std", "velocity_y_std")
    for param, group in _sensitivity_groups(outcomes).items():
        info = group[0].series.info
        values = [o.series.info["value"] for o in group]
        k0 = min(range(len(values)), key=lambda k: abs(values[k] - info["default"]))
        base_o = group[k0]
        spread = {}
        for q in quantities:
            per_seed = [_plateau(p, q, base_o.series.window) for p in base_o.run_dirs[0]]
            spread[q] = 0.5 * (max(per_seed) - min(per_seed))
        rows = []
        for k, o in enumerate(group):
            row = [f"{values[k]:g}" + (" (default)" if k == k0 else "")]
            for q in quantities:
                v, base = o.value(q, 0), base_o.value(q, 0)
                change = "" if k == k0 else (f" ({100 * (v - base) / abs(base):+.1f} %)" if RELATIVE[q]
                                             else f" ({v - base:+.1f})")
                row.append(unit_value(q, v) + change)
            row += [f"{o.wall(0):.1f}", f"{o.point_steps(0):.3g}", o.summaries[0][0]["steps"],
                    f"{max(abs(s['energy_error']) for s in o.summaries[0]):.1e}"]
            rows.append(row)
        rows.append(["layout spread", *(unit_value(q, spread[q], 2) for q in quantities), "", "", "", ""])
        energy = {values[k]: max(abs(x["energy_error"]) for x in o.summaries[0]) for k, o in enumerate(group)}
        leaky = {v: e for v, e in energy.items() if e > 1e-6}
        if leaky:
            report.findings.append(
                f"{info['label']}: the total energy is not conserved at " +
                ", ".join(f"{v:g} (relative error {e:.1e})" for v, e in leaky.items()) +
                f", against {energy[values[k0]]:.0e} at the default.")
        lines += [f"### {info['label']}" + (" (av_linear and av_quadratic scaled together from 0.2 / 2)"
                                            if param == "av" else ""), ""]
        lines += md_table([info["label"], *(f"{q} ({unit_of(q)})" for q in quantities),
                           "wall (s, all layouts)", "point-steps (all layouts)", "steps", "energy error (largest)"],
                          rows) + [""]
        # Findings: the same layouts run at every setting, so a change that every layout shows with one
        # sign, and that grows monotonically along the parameter, is the setting's; the layout spread
        # is the scale of what another choice of layouts would move.
        if len(group) > 1:
            effects = []
            for q in ("macro_normal_stress", "pressure_mean", "temperature_mean", "temperature_std", "velocity_y_std"):
                per_layout = {k: [_plateau(p, q, group[k].series.window) for p in group[k].run_dirs[0]]
                              for k in range(len(group))}
                base = per_layout[k0]
                far = max((k for k in range(len(group)) if k != k0),
                          key=lambda k: abs(np.mean(per_layout[k]) - np.mean(base)))
                diffs = [a - b for a, b in zip(per_layout[far], base)]
                change = float(np.mean(diffs))
                means = [np.mean(per_layout[k]) for k in range(len(group))]
                steps = np.diff(means)
                monotone = bool(np.all(steps > 0) or np.all(steps < 0))
                agree = all(d * change > 0 for d in diffs)
                size = 100 * change / abs(np.mean(base)) if RELATIVE[q] else change
                text = f"{size:+.1f} %" if RELATIVE[q] else f"{size:+.0f} {unit_of(q)}"
                effects.append((abs(size) / (1.0 if RELATIVE[q] else 10.0),
                                f"{q} {text} at {values[far]:g} ("
                                + ("every layout the same sign" if agree else "layouts disagree in sign")
                                + (", monotone in the parameter" if monotone else "") + ")"))
            report.findings.append(
                f"Sensitivity to {info['label']} (delta {delta:g}, h/r = 1/{r / h:g}, {values[0]:g} to "
                f"{values[-1]:g}; the largest change from the default, layout means): "
                + "; ".join(text for _, text in effects) + ".")
    if failures:
        lines += ["### Settings that did not finish", "",
                  "A setting counts as failed when any of its layouts stopped; the layouts that did finish are "
                  "shown for what they are worth.", ""]
        rows = []
        for f in failures:
            for run_dir in sorted((report.study.out / f.series.part / f.series.name).glob("level_0*")):
                try:
                    summary = Run(run_dir).summary()
                except PostError:
                    continue
                finished = summary.get("exit_code") == 0
                values = ([unit_value(q, _plateau(run_dir, q, f.series.window)) for q in quantities] if finished
                          else ["-"] * len(quantities))
                rows.append([f"{f.series.info['label']} = {f.series.info['value']:g}", run_dir.name.split("seed_")[-1],
                             summary.get("exit_code"), f"{summary.get('end_time', math.nan) / NS:.3g} ns",
                             summary.get("steps"), *values])
        lines += md_table(["setting", "seed", "exit code", "reached", "steps",
                           *(f"{q} ({unit_of(q)})" for q in quantities)], rows) + [""]
        for f in failures:
            message = f.message.splitlines()
            detail = next((line for line in message if "stopped" in line or "error" in line), message[-1] if message else "")
            lines += [f"- {f.series.info['label']} = {f.series.info['value']:g}: `{detail.strip()}`"]
            report.findings.append(f"Sensitivity: {f.series.info['label']} = {f.series.info['value']:g} did not "
                                   f"finish for every layout: {detail.strip()}")
        lines.append("")
    if outcomes:
        lines.append(report.figure("sensitivity", figure_sensitivity, _sensitivity_groups(outcomes)))
        lines += ["", "*Plateau values against each parameter: grey dots single layouts, blue their mean.*", ""]
    report.sections.append(lines)


# --- part 4: the answer --------------------------------------------------------------------------------

FULL_WIDTH_KEY = "width"


def answer_section(report, o, anchor):
    """Returns the one table's lines (for the top of the document); appends the details section."""
    study, plan = report.study, report.plan
    info = o.series.info
    r = info["void_radius"]
    full_scene = paper_scene_path()
    full_entries = read_scene_text(full_scene.read_text())
    full_width = parse_value(full_entries.get(FULL_WIDTH_KEY, "2 mm"))
    reduced_path = study.out / "answer" / o.series.name / "study.scene"
    checks = {h: study.check(full_scene, h) for h in plan.answer_check_cells}
    reduced_checks = {h: study.check(reduced_path, h) for h in o.h}
    ratio = {h: float(np.mean([s["steps"] for s in o.summaries[k]])) / reduced_checks[h][1] for k, h in enumerate(o.h)}
    rate, threads, fewer, rate_runs, quartiles = study_rate(study, o)

    # The full run goes on to 1.2 us, past the reflections: the anchor (the full geometry at the
    # coarsest cell) measures how many more steps that takes than the reduced runs' ratio predicts.
    anchor_factor = 1.0
    if anchor is not None:
        h0 = float(anchor.scene["cell_size"])
        lower0 = checks[min(checks, key=lambda c: abs(math.log(c / h0)))][1]
        ratio0 = ratio[min(ratio, key=lambda c: abs(math.log(c / h0)))]
        anchor_factor = anchor.summary()["steps"] / (lower0 * ratio0)

    def full_cost(h, corrected=True):
        match = next((c for c in checks if abs(c - h) <= 1e-9 * h), None)
        if match is not None:
            points, lower, how = *checks[match], "--check"
        else:
            ref = min(checks)
            points, lower = checks[ref][0] * (ref / h) ** 2, checks[ref][1] * (ref / h)
            how = f"--check at {h_text(ref)} scaled by h^-2 (points) and h^-1 (steps)"
        near = min(ratio, key=lambda c: abs(math.log(c / h)))
        steps = lower * ratio[near] * (anchor_factor if corrected else 1.0)
        point_steps = points * steps
        return dict(h=h, points=points, lower=lower, ratio=ratio[near], steps=steps, point_steps=point_steps,
                    core_minutes=threads * point_steps / rate / 60.0, how=how)

    targets = [("pressure_mean", t, True) for t in (1, 3, 10)] + \
              [("macro_normal_stress", t, True) for t in (1, 3, 10)] + \
              [("temperature_mean", t, False) for t in (10, 50)]
    table, rows = [], []
    for q, t, relative in targets:
        res = o.results[q]
        h, err, how = needed_resolution(res, o.h, t / 100.0 if relative else float(t), relative)
        if h is None:
            continue
        h_use = h if how == "measured" else nice_cell(h, full_width)
        cost = full_cost(h_use)
        table.append(dict(cost, quantity=q, target=t))
        err_text = (f"{100 * err:.2g} %" if relative else f"{err:.2g} K") if how == "measured" else "= target"
        rows.append([f"{t:g} {'%' if relative else 'K'}", q, f"{h_text(h_use)} (h/r = 1/{r / h_use:.3g})", "bspline2",
                     "2", err_text, how + ("" if how == "measured" else f": h = {h / UM:.2g} um, rounded down to a "
                                                                          "divisor of the width"),
                     f"{cost['points']:.3g}", f"{cost['steps']:.3g}", f"{cost['point_steps']:.2g}",
                     f"{cost['core_minutes']:.3g}", f"{cost['core_minutes'] / threads:.3g}"])
    one_table = md_table(["target", "quantity", "cell size", "shape", "ppc", "estimated error there", "how",
                          "points (full)", "steps (full)", "point-steps", "core-minutes", f"minutes on {threads} cores"],
                         rows)
    note = (f"Error: the discretisation error estimated by mpmshock-converge on the **reduced** column "
            f"({h_text(plan.answer_width)} wide, {plan.answer_height * 1e3:g} mm bodies, {plan.answer_end / NS:g} ns, "
            f"{o.series.seeds} void layouts), transferred to the paper's geometry "
            f"({full_entries.get('width')} wide, {full_entries.get('target_height')} bodies, to "
            f"{full_entries.get('end_time')}): it is assumed, not measured, that the error per level is the same "
            "there. It does not include the layout scatter (below), which in the full column with ~10 times the "
            "voids is smaller. Cost: points and steps of configs/paper_base.scene at that cell size (points from "
            "`mpmshock configs/paper_base.scene --check --set cell_size=H`; steps its lower bound times the ratio "
            "of actual to lower-bound steps measured in the reduced runs at the same cell size), divided by "
            f"{rate:.3g} point-steps/s: the median rate of the study's {rate_runs} bspline2 runs with at least "
            f"{LARGE_RUN:.0e} points (quartiles {quartiles[0]:.3g} and {quartiles[1]:.3g}; smaller runs are "
            f"dominated by the per-step overhead), on {threads} threads ({100 * fewer:.0f} % of their steps ran on "
            f"fewer, which the simulator chooses when they measure faster on the shared machine); core-minutes = "
            f"{threads} x minutes.")
    # details
    lines = ["## 4. The paper's base case: what resolution, at what cost", "",
             f"configs/paper_base.scene (delta {info['delta']:g}, r = {h_text(r)}, +-{info['velocity']:g} m/s, "
             f"bspline2, 2 points per cell) in a reduced column: {h_text(plan.answer_width)} wide, "
             f"{plan.answer_height * 1e3:g} mm target and flyer, to {plan.answer_end / NS:g} ns, cell sizes "
             f"{', '.join(h_text(h) for h in o.h)}, {o.series.seeds} void layouts per level, band "
             f"`{o.series.scene['region.' + REGION]}` (2r to 10r), plateau window "
             f"{o.series.window[0] / NS:g}-{o.series.window[1] / NS:g} ns. The full geometry cannot be afforded "
             "here; the reduced column holds only "
             f"{np.mean([s['voids'] for s in o.summaries[-1]]) / 2:.1f} voids per body (the full one "
             f"{checks_voids(study, full_scene, plan):s}), so the layout scatter is large and is shown apart.", ""]
    rows = []
    for q in QUANTITIES:
        res = o.results[q]
        limit = res.estimate.extrapolated
        rows.append([q, *(f"{unit_value(q, v)} ± {unit_value(q, se, 2)}" for v, se in zip(res.values, res.standard_errors)),
                     unit_value(q, limit), order_text(res.estimate),
                     *(error_text(q, e, limit, signed=False) for e in res.estimate.errors),
                     unit_value(q, o.series.exact[q]) if q in o.series.exact else "-"])
    lines += md_table(["quantity", *(h_text(h) for h in o.h), "limit", "order",
                       *(f"disc. error {h_text(h)}" for h in o.h), "full compaction"], rows)
    lines += ["", "Units kg/m3, GPa, K; '± x' the standard error over the layouts.", "", "### Cost model", ""]
    cost_rows = []
    for h in sorted(checks, reverse=True):
        c = full_cost(h)
        cost_rows.append([h_text(h), f"{c['points']:.4g}", f"{c['lower']:.4g}", f"{c['ratio']:.3g}",
                          f"{full_cost(h, corrected=False)['steps']:.4g}", f"{c['steps']:.4g}",
                          f"{c['point_steps']:.3g}", f"{c['core_minutes']:.3g}"])
    lines += md_table(["cell", "points (--check)", "steps, lower bound (--check)",
                       "actual / lower bound (reduced runs)", "steps from the reduced ratio",
                       f"steps x {anchor_factor:.3g} (anchor)", "point-steps", "core-minutes"], cost_rows) + [""]
    lines += [f"The --check step count is a lower bound from the time step at the start; shocks and collapsing "
              f"voids raise the fastest signal (artificial viscosity adds to it), so the reduced runs took "
              f"{', '.join(f'{ratio[h]:.2f}x' for h in o.h)} as many steps at {', '.join(h_text(h) for h in o.h)}. "
              f"The full run goes on to {full_entries.get('end_time')}, past the reflections from the free surfaces, "
              + (f"and took {anchor_factor:.3g} times the steps that ratio predicts where it was run (the anchor "
                 "below); that factor is applied at every cell size." if anchor is not None else
                 "and the ratio of the reduced runs' 250 ns is assumed for all of it (no anchor run).") +
              " Rows below 2.5 um (if the table needs them) scale the finest --check by h^-2 points and h^-1 "
              "steps.", ""]
    if anchor is not None:
        s = anchor.summary()
        h0 = float(anchor.scene["cell_size"])
        anchor_values = measure_single(anchor, o.series.window)
        lines += [f"### Check of the cost model: the full geometry at {h_text(h0)}", "",
                  f"configs/paper_base.scene was run once at {h_text(h0)} (snapshots off, one band region added):",
                  ""]
        c = full_cost(h0, corrected=False)
        lines += md_table(["", "predicted from the reduced runs", "measured"],
                          [["material points", f"{c['points']:.4g}", s["material_points"]],
                           ["steps", f"{c['steps']:.4g}", s["steps"]],
                           ["point-steps", f"{c['point_steps']:.3g}", f"{s['material_points'] * s['steps']:.3g}"],
                           ["wall (s)", f"{c['point_steps'] / rate:.3g}", f"{s['wall_seconds']:.3g}"],
                           ["point-steps/s", f"{rate:.3g}", f"{s['point_steps_per_second']:.3g} on {s['threads']} "
                            f"threads ({s['steps_with_fewer_threads']} of {s['steps']} steps on fewer)"]]) + [""]
        k0 = 0
        rows = []
        for q in ("pressure_mean", "macro_normal_stress", "temperature_mean", "density_mean", "macro_density"):
            res = o.results[q]
            rows.append([q, f"{unit_value(q, anchor_values[q])}",
                         f"{unit_value(q, res.values[k0])} ± {unit_value(q, res.standard_errors[k0], 2)}"])
        lines += [f"The same band and window in the full column (seed 1, {s['voids'] / 2:.0f} voids per body) and "
                  f"in the reduced one at the same cell size:", ""]
        lines += md_table(["quantity", f"full geometry, {h_text(h0)}", f"reduced, {h_text(h0)}, layout mean"],
                          rows) + [""]
        report.findings.append(
            f"Cost model check (configs/paper_base.scene at {h_text(h0)}, the full geometry, run once): the reduced "
            f"runs predicted {c['steps']:.0f} steps and {c['point_steps'] / rate:.0f} s; it took {s['steps']} steps "
            f"and {s['wall_seconds']:.0f} s ({s['point_steps_per_second']:.3g} point-steps/s). The step excess, "
            f"{anchor_factor:.2f}x, is applied to every cell size of the answer.")
    lines.append(report.figure("answer", figure_answer, o, [full_cost(h) for h in sorted(checks)]))
    lines += ["", "*Left and middle: the reduced column's plateau against cell size (grey: single layouts). "
              "Right: core-minutes of the full geometry at each cell size of the cost model.*", ""]
    report.sections.append(lines)
    for row in table:
        pass
    return one_table + ["", note, ""], dict(rate=rate, threads=threads, fewer=fewer, table=table)


LARGE_RUN = 1e5


def study_rate(study, fallback):
    """Median point-steps/s of the study's bspline2 runs of at least LARGE_RUN points, their threads,
    the share of steps on fewer threads, the number of runs and the quartiles; the answer's finest
    runs where there are none."""
    runs = []
    for run_dir, s in study.all_runs().items():
        try:
            shape = Run(run_dir).scene["shape_function"]
        except (PostError, KeyError):
            continue
        if shape == "bspline2" and s.get("material_points", 0) >= LARGE_RUN and s.get("exit_code") == 0:
            runs.append(s)
    if not runs:
        runs = fallback.summaries[-1]
    rates = [s["point_steps_per_second"] for s in runs]
    threads = max(s["threads"] for s in runs)
    fewer = sum(s["steps_with_fewer_threads"] for s in runs) / sum(s["steps"] for s in runs)
    return float(np.median(rates)), threads, fewer, len(runs), tuple(np.percentile(rates, [25, 75]))


def checks_voids(study, scene, plan):
    """'N voids per body' from --check of the full scene at the coarsest cell."""
    study.wait_for_binary()
    done = subprocess.run([str(study.binary), str(scene), "--check", "--set",
                           f"cell_size={converge._format(plan.answer_check_cells[0])}"], capture_output=True, text=True)
    found = re.search(r"target: .*?(\d+) voids", done.stdout)
    return f"{found.group(1)} voids per body" if found else "more voids"


def measure_single(run, window):
    columns = run.regions()[REGION]
    return {q: converge.sample(columns[q], columns["time"], window, None) for q in QUANTITIES}


# Hand-written reading of the full study of 2026-11-23. The tables and findings above it are
# regenerated on every run; these notes are not, so the document labels them with their date.
NOTES_WRITTEN_FOR = "the full study of 2026-11-23 (binaries mpmshock-c81f6e3cc7c5 and mpmshock-9ae2d714d59a)"
NOTES = """\
- **Solid plates, bspline2 with 2 points per cell (the defaults).** Plateau pressure and normal
  stress are within 0.4 % of the exact Rankine-Hugoniot state at 20 um and within 0.2 % from 10 um
  down (to 2.5 um), density within 0.06 % everywhere, at 500, 1000 and 2000 m/s. These errors are at the level of the plateau's own fluctuations, so
  most observed orders are not meaningful (the tool falls back, and says so); density converges at
  order about 1-2. Temperature is the exception: +1.4 K at 500 m/s but about +5 K at 1000 m/s and
  +14 K at 2000 m/s at 5 um, and not shrinking with refinement at the two higher speeds (+3.3 K at
  2.5 um, 1000 m/s). About 1 % of the shock's energy jump too much in the band; not diagnosed here.
- **gimp** is as good as bspline2 at 500 and 1000 m/s, but at 2000 m/s its pressure (+0.6 %) and
  temperature (-18 K) errors grow with refinement.
- **bilinear cells get worse with refinement** at 1000 and 2000 m/s (at 500 m/s their errors go
  up and down, -1.9, -0.3, -1.8 % in pressure): -3.6 % in pressure at
  1000 m/s and -8.2 % (and +195 K) at 2000 m/s at 5 um, with 2 points per cell; with 1 point per
  cell at 5 um the plateau collapses (-37 % in pressure). In the porous runs the same holds more
  strongly (delta 1.1: -40 % in pressure and a band density 6 % above full compaction at h/r = 1/8).
  The paper's 4-node cells are not a converging discretisation in this code; use them only to
  compare with the paper.
- **Points per cell.** With bspline2, 1, 2 and 3 points per cell give errors of the same size; the
  cost grows as ppc^2. The default 2 is a sound choice.
- **Strength** does not add (2/3) Y to the normal stress as the jump conditions predict: the
  plateau ends below yield with almost twice the plastic strain of a monotone compression, which
  suggests yielding back and forth in the overshooting numerical shock (see the strength table;
  not diagnosed further). Strength effects on the normal stress (~0.1 GPa)
  are below what this discretisation resolves.
- **Porous bodies converge** at order 1 to 1.6 in pressure and normal stress, and the temperature
  mean rises with refinement (void-collapse heating is resolved better) at order 0.9-2. At
  h/r = 1/8 the estimated discretisation error of the normal stress is 0.5 % (delta 1.03), 2.6 %
  (1.1) and 2.6 % (1.4); the layout scatter of a 200 um column (standard error 3-9 % over 2-3
  layouts) is larger than that. 1 % needs h/r = 1/8 at delta 1.03 but about 1/15-1/20 (1-1.4 um
  for 20 um voids) at 1.1 and 1.4, beyond what was run.
- **The converged porous plateaus are not the full-compaction Hugoniot**: normal stress -1.7 %
  (1.03), -10 % (1.1), -5 % (1.4); band density -0.1 to -1.2 % at h/r = 1/8, i.e. voids remain
  partly open in the window (the residual porosity table). The points' own density (density_mean)
  overstates the band's by 0.05 % (1.03), 0.3 % (1.1) and 1.5 % (1.4): at delta 1.4 it matches full
  compaction while the band is 1.2 % less dense. The windows are short (35-50 ns, bodies of 0.6 mm)
  and at delta 1.03 and 1.1 they start inside the relaxation from a first, nearly solid-Hugoniot
  pressure peak; at delta 1.4 the band's pressure swings between about 4 and 8 GPa inside the
  window (the plateau figure, one layout). These plateau means are therefore means over a
  stated window rather than steady states; taller bodies would give longer plateaus at H^2 the
  cost.
  The macro_density limit of delta 1.4 (+2.8 % above full compaction) is an extrapolation at order
  0.67 past physical bounds: read its finest value instead.
- **Sensitivity (delta 1.1, h/r = 1/4).** Artificial viscosity matters most for temperatures: each
  halving of both coefficients lowers the mean temperature by about 20 K and its spread by
  50-75 K, and raises the pressure by about 0.6 %. cfl from 0.1 to 0.45 moves pressures by under
  1 % and temperatures by under 3 K; 0.45 costs 32 % fewer steps than the default 0.3.
  flip_fraction < 1 damps the velocity noise (velocity_y std -35 % at 0.99, -55 % at 0.95) but
  heats the band (+59 K and +108 K) and does not conserve energy (relative error 2 % and 7 %). With
  the binary the study started with (c81f6e3cc7c5) the flip_fraction < 1 runs stopped at a
  negative temperature in the first 35 ns; the fix made during the study (commit 783448a, "PIC
  blend never cools a point") lets them finish, at that price in energy. All flip_fraction < 1
  runs in the tables are by 9ae2d714d59a; its other results are bit-identical to c81f6e3cc7c5's
  (checked on a porous and a solid run).
- **The paper's base case.** 3 % in plateau pressure needs 5 um cells (h/r = 1/10) and about 180
  core-minutes for the paper's geometry; the normal stress reaches 3 % at 10 um (about 24
  core-minutes), as does 10 K in mean temperature; 10 % and 50 K are reached at 20 um (about 3
  core-minutes, the configuration's own setting). 1 % is beyond the runs: the order 0.6 that the
  reduced column shows extrapolates to about 1.25 um and 1e4 core-minutes, to be read as an order
  of magnitude. The reduced column has 3 voids per body; its layout scatter (standard error
  0.75 GPa, 5 %) is as large as the largest discretisation error in the table, and the full column's
  scatter was not measured. The cost model under-predicted the full run's steps by 21 % from the
  reduced runs alone; that measured factor is in the table.
"""


# --- the document ---------------------------------------------------------------------------------

def choices(plan, parts):
    """What was chosen and why, for the parts that ran."""
    rows = []
    if "solid" in parts:
        rows += [["solid", f"column {h_text(plan.solid_width)}, bodies {plan.solid_height * 1e3:g} mm, end_time "
                  f"<= {plan.solid_end / NS:g} ns, cells {', '.join(h_text(h) for h in plan.solid_cells)}"
                  + (f" (+ {h_text(plan.solid_extra_cell)} for one series)" if plan.solid_extra_cell else ""),
                  "a plane shock needs no width: 60 um is 3 cells at 20 um, the narrowest column allowed; 1 mm "
                  "bodies hold a 300 um plateau band until the release from the free surfaces arrives; a 5 um "
                  "run costs ~3e7 point-steps, so the whole matrix of speeds, shapes and ppc is cheap"],
                 ["solid", "plasticity off (and one series on)",
                  "the exact Rankine-Hugoniot state is hydrodynamic; strength shifts the normal stress by (2/3) Y"]]
    if "porous" in parts:
        rows += [["porous", f"void radius {h_text(plan.void_radius)}, cells r/2, r/4, r/8, column "
                  f"{h_text(plan.porous_width)} ("
                  + ", ".join(f"{h_text(w)} at delta {d:g}" for d, w in plan.porous_width_for.items()) +
                  f"), bodies {h_text(plan.porous_height)}",
                  "r/8 is the finest affordable (about 1e5 points and 2000-4000 steps per run); 20 um voids put "
                  "r/8 at 2.5 um; the column holds 3 (delta 1.03) to 27 (delta 1.4) voids per body"],
                 ["porous", "seeds: " + ", ".join(f"delta {d:g}: {n}" for d, n in plan.porous_seeds.items()),
                  "the layout scatter is the error the seeds measure; delta 1.4 has the most voids (least scatter) "
                  "and the most steps, so it gets fewer layouts"],
                 ["porous", "band 2r-8r, end_time 0.85 H/Us",
                  "away from the impact plane's start-up transient; the shock stays in the target, so no release "
                  "from a free surface reaches the band"]]
    if "sensitivity" in parts:
        rows += [["sensitivity", f"delta {plan.sensitivity_delta:g}, h = {h_text(plan.sensitivity_cell)}, "
                  f"{plan.sensitivity_seeds} layouts",
                  "the finest h at which 9 settings x the layouts fit the budget; the default setting's runs are "
                  "those of part 2 (copied, not rerun)"]]
    if "answer" in parts:
        rows += [["answer", f"reduced column {h_text(plan.answer_width)} x {plan.answer_height * 1e3:g} mm, "
                  f"{plan.answer_end / NS:g} ns, {', '.join(h_text(h) for h in plan.answer_cells)}, "
                  f"{plan.answer_seeds} layouts",
                  "the paper's 2 mm x 5 mm to 1.2 us costs ~100x more per level; 250 ns lets the shock cross "
                  "the band and reach the top just at the end"],
                 ["answer", "cost in point-steps, one rate",
                  "wall times on the shared machine scatter by tens of per cent; points x steps does not"]]
    return md_table(["part", "choice", "why"], rows)


def run_time_section(study, parts, elapsed):
    runs = study.all_runs()
    rows, total_wall, total_ps = [], 0.0, 0.0
    for part in parts:
        mine = {d: s for d, s in runs.items() if d.relative_to(study.out).parts[0] == part}
        if not mine:
            continue
        wall = sum(s["wall_seconds"] for s in mine.values())
        ps = sum(s["material_points"] * s["steps"] for s in mine.values())
        total_wall += wall
        total_ps += ps
        rows.append([part, len(mine), f"{wall:.0f}", f"{ps:.3g}", f"{ps / wall:.3g}" if wall else "-"])
    rows.append(["all", sum(int(r[1]) for r in rows), f"{total_wall:.0f}", f"{total_ps:.3g}",
                 f"{total_ps / total_wall:.3g}" if total_wall else "-"])
    lines = ["## Run time", "",
             "Wall time of the simulator runs, summed as each run measured it (summary.json), copies counted once; "
             "2 cores, shared with other work, so a rerun will differ by tens of per cent.", ""]
    lines += md_table(["part", "runs", "wall (s)", "point-steps", "point-steps/s"], rows)
    makers = {}
    for run_dir in runs:
        try:
            maker = (run_dir / MADE_BY).read_text().strip()
        except OSError:
            maker = "unrecorded"
        makers[maker] = makers.get(maker, 0) + 1
    lines += ["", f"This generation of the document took {elapsed:.0f} s ({len(study.ran)} runs made, the rest "
              "reused from the cache). Runs by binary: " +
              ", ".join(f"{name} {count}" for name, count in sorted(makers.items())) + ".", ""]
    return lines, total_wall


def pin_binary(binary, out, seconds=300):
    """A private copy of the simulator, OUT/bin/mpmshock-SHA, which every run of the study uses: the
    build may be replaced while the study runs (another engineer's rebuild), and one study should
    be one binary. Waits for the binary while it is missing (mid-rebuild)."""
    import hashlib
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
    import hashlib
    try:
        digest = hashlib.sha256(Path(binary).read_bytes()).hexdigest()[:12]
    except OSError:
        digest = "missing"
    try:
        version = subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip()
    except OSError:
        version = "unknown"
    return version, digest


def write_document(report, parts, one_table, failures, elapsed, fingerprints, window_cases):
    study, plan = report.study, report.plan
    version, digest = fingerprints
    date = time.strftime("%Y-%m-%d")
    run_lines, total_wall = run_time_section(study, parts, elapsed)
    lines = ["# Accuracy of mpmshock: errors, orders and what resolution a result needs", "",
             f"*Generated by `scripts/accuracy-study`{' --quick' if plan.quick else ''} on {date} with {version} "
             f"(sha256 {digest}: the build as copied to `{_display_path(study.binary.parent)}` when this "
             f"generation started, so that a rebuild cannot change the binary under a running study; reused runs "
             f"keep the binary that made them, counted under Run time); do not edit by hand. The runs "
             f"({total_wall / 60:.0f} minutes of simulator wall time on 2 cores) are cached under "
             f"`{_display_path(study.out)}`; rerunning the script reuses every run whose resolved scene "
             "(scene.txt) still matches what the current build would run, and rewrites this file and its figures. "
             "A changed build that resolves scenes the same way reuses old runs: delete the cache after a change "
             "to the physics.*", ""]
    if plan.quick:
        lines += ["**Quick mode: a smoke test with fewer and coarser runs; these numbers are not the study's.**", ""]
    lines += ["Parts: " + ", ".join(f"[{p}](#{_anchor(p)})" for p in parts) + ".", "",
              "How to read the numbers: every value is the plateau mean of a band region over a time window (each "
              "case's band, window and the reasons for them are in its section, and the time series are in the "
              "last figure). 'error' against an exact answer is value - exact; 'disc. error' and 'estimate' are "
              "mpmshock-converge's discretisation error estimates from the study's own levels (Richardson "
              "extrapolation from the three finest levels with the observed order; 'order: none' marks its "
              "conservative fallback, with the reason); 'SE' is the standard error of the mean over void layouts. "
              "Every number names its cell size.", ""]
    if one_table:
        lines += ["## The answer: what the paper's base case needs", ""] + one_table
    lines += ["## Findings", "", "Computed from this run's tables:", ""] + [f"- {f}" for f in report.findings] + [""]
    if not plan.quick and list(parts) == list(PARTS):
        lines += ["## Reading the results", "",
                  f"*Written by hand for {NOTES_WRITTEN_FOR}. Unlike the rest of this document these notes are "
                  "not regenerated: after a rerun with another build, check them against the tables.*", "",
                  NOTES]
    lines += ["## What was chosen, and why", ""] + choices(plan, parts) + [""]
    for section in report.sections:
        lines += section
    if window_cases:
        lines += ["## The plateaus", "",
                  report.figure("windows", figure_windows, window_cases), "",
                  "*Band time series of the finest level (first layout): pressure_mean and macro_normal_stress "
                  "(top), temperature_mean (bottom), the plateau window shaded, the exact (solid) or "
                  "full-compaction (porous) value dashed.*", ""]
    if failures:
        lines += ["## Runs that did not finish", ""] + [f"- {f.series.part}/{f.series.name}: {f.message}"
                                                         for f in failures] + [""]
    lines += run_lines
    path = report.docs / "accuracy.md"
    path.write_text("\n".join(lines).rstrip() + "\n")
    return path


def _anchor(part):
    return {"solid": "1-solid-plates-against-the-exact-rankine-hugoniot-state",
            "porous": "2-porous-bodies-convergence-under-void-resolution",
            "sensitivity": "3-sensitivity-to-the-numerical-parameters",
            "answer": "4-the-papers-base-case-what-resolution-at-what-cost"}[part]


def _display_path(path):
    try:
        return str(Path(path).resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


# --- the command line -----------------------------------------------------------------------------

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
        failures, window_cases, one_table = [], [], None

        def run_all(series_list):
            done = []
            for series in series_list:
                result = study.run(series)
                (failures if isinstance(result, Failure) else done).append(result)
            return done

        if "solid" in parts:
            solid = run_all(solid_series(plan, study.material))
            if solid:
                solid_section(report, solid)
                window_cases += [(f"solid {o.series.info['velocity']:g} m/s", o) for o in solid
                                 if o.series.info["shape"] == "bspline2" and o.series.info["ppc"] == 2
                                 and o.series.info["plasticity"] == "off" and not o.series.info.get("fine")]
        if "porous" in parts:
            porous = run_all(porous_series(plan, study.material))
            if porous:
                porous_section(report, porous)
                window_cases += [(f"delta {o.series.info['delta']:g}", o) for o in porous
                                 if o.series.info["shape"] == "bspline2"]
        if "sensitivity" in parts:
            series = sensitivity_series(plan, study.material)
            sens = run_all(series)
            sens_failures = [f for f in failures if f.series.part == "sensitivity"]
            sensitivity_section(report, sens, sens_failures)
        if "answer" in parts:
            reduced = run_all([answer_scene(plan, study.material)])
            if reduced:
                o = reduced[0]
                anchor = None
                if plan.answer_anchor:
                    h0 = o.h[0]
                    y1, y2 = o.series.info["band"]
                    anchor = study.run_single(paper_scene_path(), [
                        f"cell_size={converge._format(h0)}", "snapshot_interval=0", "sample_interval=1ns",
                        f"region.{REGION}=band {_um(y1)} {_um(y2)}"], out / "answer" / f"full_{h0 / UM:g}um")
                one_table, _ = answer_section(report, o, anchor)
                window_cases.append(("paper base, reduced", o))
        elapsed = time.monotonic() - started
        path = write_document(report, parts, one_table, failures, elapsed,
                              fingerprint, window_cases)
    except PostError as e:
        print(f"accuracy-study: error: {e}", file=sys.stderr)
        return 1
    print(path)
    for figure in report.figures:
        print(figure)
    return 1 if failures and not args.quick and any(f.series.part != "sensitivity" for f in failures) else 0
