"""What the accuracy study runs: its sizes (Plan, full or --quick), the series of each part and the
scenes they start from, and the plateau window of each case.

The study lives in studies/accuracy/ of the checkout and is run as `studies/accuracy/accuracy-study`
(see study.py); this module only decides what to run. A series is one mpmshock-converge study (one
scene, one refined key); run.py runs it, report.py writes up what it measured.

The study composes its scenes itself, as key = value text (`scene_text`); the one hand-written scene
it starts from, configs/paper_base.scene (part 4), it reads only through the simulator's own
resolution (mpmshock --resolve: mpmshock_post.resolve), and it changes that scene's keys with --set.
"""

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

from mpmshock_post import converge, hugoniot
from mpmshock_post.errors import PostError

ROOT = Path(__file__).resolve().parents[2]   # the checkout
PAPER_SCENE = ROOT / "configs" / "paper_base.scene"

PARTS = ("solid", "porous", "sensitivity", "answer")
REGION = "plateau"
UM, NS = 1e-6, 1e-9


@dataclass
class Series:
    """One mpmshock-converge study: a scene, the refined key's values (coarsest first), seeds, the
    plateau window, the exact answers where known, and labels for the report.

    `scene` is the study's own keys (key -> value text). Without a `base` they are the whole scene
    file of the series; with one (a hand-written scene such as configs/paper_base.scene) the series'
    scene file is a copy of the base and these keys override it with --set."""

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
    base: Path = None                # the hand-written scene that `scene` overrides, if any

    def scene_file_text(self):
        """The text of the series' scene file (study.scene): the composed scene, or the base copied."""
        return self.base.read_text() if self.base else scene_text(self.scene)

    @property
    def overrides(self):
        """The --set overrides of every run of the series (before the refined key's)."""
        own = [f"{key}={value}" for key, value in self.scene.items()] if self.base else []
        return [*self.sets, *own]


@dataclass(frozen=True)
class Comparison:
    """A porous series beside the main shape's at Plan.porous_shapes_at: a shape function and the
    scene keys it sets beyond the main series' (key -> value text), its label in the report's tables,
    findings and figures, a slug for its series (and run directory) name, its number of layouts, and
    the template block (accuracy.md.in) that says what it is, if any."""

    label: str
    shape: str
    seeds: int
    scene: tuple = ()                # ((key, value text), ...) set beyond the main series' keys
    slug: str = None                 # the series name's tail (d1.1_SLUG); default: the shape
    note: str = None                 # template block describing it (filled with label, main_shape)

    @classmethod
    def of_shape(cls, shape, seeds):
        """Another shape function, at its own automatic cfl, with nothing else changed."""
        return cls(shape, shape, seeds)

    def with_seeds(self, seeds):
        return replace(self, seeds=seeds)

    @property
    def name(self):
        return self.slug or self.shape

    @property
    def keys_text(self):
        """Its extra scene keys as `key = value` text ('' where it is only another shape)."""
        return ", ".join(f"{key} = {value}" for key, value in self.scene)


def scene_text(entries):
    """A scene file of key = value lines."""
    return "".join(f"{key} = {value}\n" for key, value in entries.items())


def _um(x):
    return f"{x / UM:g} um"


def _ns(x):
    return f"{x / NS:g} ns"


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
    solid_extra_cell: float = 2.5e-6       # a fourth level for the main shape, ppc 2, 1000 m/s
    solid_shapes: tuple = ("bspline2_domain", "bspline2", "gimp", "bilinear")   # the main shape first
    solid_ppc: tuple = (1, 2, 3)
    # 4 cells at the coarsest 20 um: the narrowest periodic column bspline2_domain's 4 x 4 stencil
    # allows (bspline2, gimp and bilinear need 3)
    solid_width: float = 80e-6
    solid_height: float = 1e-3
    solid_end: float = 200e-9
    solid_band: tuple = (100e-6, 400e-6)
    porous_deltas: tuple = (1.03, 1.1, 1.4)
    porous_seeds: dict = field(default_factory=lambda: {1.03: 3, 1.1: 3, 1.4: 2})
    porous_shapes_at: float = 1.1              # porosity at which the comparisons also run
    # the comparisons beside the main shape and their layouts (seeds 1, 2, ... as the main shape's):
    # the main shape without volumetric smoothing (the porous default until 2026-12-05), bspline2 (the
    # default shape until 2026-12-05) and bilinear (the paper's cells) with 2, gimp with 1
    porous_comparisons: tuple = field(default_factory=lambda: (
        SMOOTHING_OFF, Comparison.of_shape("bspline2", 2), Comparison.of_shape("gimp", 1),
        Comparison.of_shape("bilinear", 2)))
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
    # the main shape's automatic cfl (MAIN_CFL) and around it: can the step grow?
    sensitivity_cfl: tuple = (0.9, 0.8, 0.6, 0.3)
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
        return cls(quick=True, solid_speeds=(1000.0,), solid_extra_cell=None,
                   solid_shapes=("bspline2_domain", "bilinear"), solid_ppc=(2,), porous_deltas=(1.1,),
                   porous_seeds={1.1: 2},
                   porous_comparisons=(SMOOTHING_OFF.with_seeds(1), Comparison.of_shape("bspline2", 1)),
                   porous_cells=(10e-6, 5e-6), sensitivity_cell=10e-6,
                   sensitivity_seeds=1, sensitivity_av=(2.0, 1.0, 0.5), sensitivity_cfl=(0.8, 0.6, 0.3),
                   sensitivity_flip=(1.0, 0.95), answer_cells=(40e-6, 20e-6, 10e-6),
                   answer_check_cells=(40e-6, 20e-6, 10e-6), answer_width=400e-6, answer_seeds=1, answer_anchor=False)


def _truth(exact):
    """The exact answer of each measured quantity: the shocked state's density, pressure (as both
    the points' pressure and the normal stress) and temperature."""
    return {"density_mean": exact.density, "macro_density": exact.density, "pressure_mean": exact.pressure,
            "macro_normal_stress": exact.pressure, "temperature_mean": exact.temperature}


# The shape the study's porous, sensitivity and answer parts run, and the solid part's points-per-cell,
# fourth-level and strength series: the simulator's default since 2026-12-05 (bspline2 at cfl 0.3
# until then), run at its automatic cfl (the study never sets cfl, but in the cfl series). Every
# part takes the automatic av_linear too (0.6 where every body is solid, 0.2 where one is porous).
MAIN_SHAPE = "bspline2_domain"
# MAIN_SHAPE's automatic cfl (mpmshock --keys: 0.6 with bspline2_domain, 0.3 with the other shapes):
# the default setting of the sensitivity part's cfl series. study.py checks it against the simulator.
MAIN_CFL = 0.6
# Every shape the study may run, in the order its tables list them: the main shape first.
SHAPES = tuple(dict.fromkeys((MAIN_SHAPE, "bspline2_domain", "bspline2", "gimp", "bilinear")))
# The porous comparison of volumetric smoothing: the main shape with it off, the default of porous
# scenes until 2026-12-05 (since then `auto`, on where a body is porous: every other porous run).
SMOOTHING_OFF = Comparison(f"{MAIN_SHAPE} (smoothing off)", MAIN_SHAPE, 2, (("volumetric_smoothing", "off"),),
                           slug=f"{MAIN_SHAPE}_nosmooth", note="porous.smoothing_off")


# --- part 1: solid plates -------------------------------------------------------------------------

def solid_series(plan, material):
    """Solid plates at each speed against the exact Rankine-Hugoniot state: every shape function at
    2 points per cell, the main shape at the other counts (all shapes at 1000 m/s), a fourth level and
    a plasticity-on series (both the main shape's) at 1000 m/s. av_linear and cfl are the simulator's
    automatic values (not set)."""
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
        truth = _truth(exact)
        info = dict(velocity=v, exact=exact, t_release=t_release)
        combos = [(shape, 2) for shape in plan.solid_shapes]
        combos += [(MAIN_SHAPE, ppc) for ppc in plan.solid_ppc if ppc != 2]
        if v == 1000.0:
            combos += [(shape, ppc) for shape in plan.solid_shapes if shape != MAIN_SHAPE
                       for ppc in plan.solid_ppc if ppc != 2]
        for shape, ppc in combos:
            scene_k = dict(scene, shape_function=shape, particles_per_cell=str(ppc))
            series.append(Series("solid", f"v{v:g}_{shape}_ppc{ppc}", scene_k, list(plan.solid_cells), (t0, t1),
                                 exact=truth, info=dict(info, shape=shape, ppc=ppc, plasticity="off")))
        if v == 1000.0 and plan.solid_extra_cell:
            scene_k = dict(scene, shape_function=MAIN_SHAPE, particles_per_cell="2")
            series.append(Series("solid", f"v1000_{MAIN_SHAPE}_ppc2_fine", scene_k,
                                 [*plan.solid_cells, plan.solid_extra_cell], (t0, t1), exact=truth,
                                 info=dict(info, shape=MAIN_SHAPE, ppc=2, plasticity="off", fine=True)))
        if v == 1000.0 and not plan.quick:
            scene_k = dict(scene, shape_function=MAIN_SHAPE, particles_per_cell="2", plasticity="on")
            series.append(Series("solid", f"v1000_{MAIN_SHAPE}_ppc2_plastic", scene_k, list(plan.solid_cells),
                                 (t0, t1), exact=truth, info=dict(info, shape=MAIN_SHAPE, ppc=2, plasticity="on")))
    return series


# --- part 2: porous bodies ------------------------------------------------------------------------

def porous_scene(plan, delta, material, velocity=1000.0):
    """The porous column of one porosity, its window and its exact full-compaction state."""
    exact = hugoniot.porous_shock(velocity, delta, material)
    r = plan.void_radius
    y1, y2 = 2 * r, 8 * r
    end = math.floor(plan.porous_end_fraction * plan.porous_height / exact.shock_speed / NS + 1e-6) * NS
    t0, t1, t_release = plateau_window(exact, material, plan.porous_height, y2, 4 * plan.porous_cells[0] + 2 * r, end)
    # The main shape, named (at its automatic cfl, not set) so that the study measures what it labels
    # whatever the simulator's default becomes.
    scene = {"shape_function": MAIN_SHAPE, "velocity": f"{velocity:g} m/s", "porosity": f"{delta:g}", "void_radius": _um(r),
             "width": _um(plan.porous_width_for.get(delta, plan.porous_width)), "target_height": _um(plan.porous_height),
             "flyer_height": _um(plan.porous_height), "end_time": _ns(end), "sample_interval": "1 ns",
             "snapshot_interval": "0", f"region.{REGION}": f"band {_um(y1)} {_um(y2)}"}
    return scene, (t0, t1), _truth(exact), dict(delta=delta, exact=exact, t_release=t_release, end=end)


def porous_series(plan, material):
    """Each porosity with the main shape over several void layouts; the comparisons (plan.porous_comparisons:
    the main shape without volumetric smoothing, bspline2, gimp, bilinear) at one porosity, each shape at
    its own automatic cfl. A comparison's info holds its Comparison ('comparison'; None for the main
    shape's) and its label ('label')."""
    series = []
    for delta in plan.porous_deltas:
        scene, window, truth, info = porous_scene(plan, delta, material)
        runs = [(Comparison(MAIN_SHAPE, MAIN_SHAPE, plan.porous_seeds[delta]), None)]
        if delta == plan.porous_shapes_at:
            runs += [(c, c) for c in plan.porous_comparisons]
        for c, comparison in runs:
            scene_k = dict(scene, shape_function=c.shape, **dict(c.scene))
            series.append(Series("porous", f"d{delta:g}_{c.name}", scene_k, list(plan.porous_cells), window,
                                 seeds=c.seeds, exact=truth,
                                 info=dict(info, shape=c.shape, label=c.label, comparison=comparison)))
    return series


# --- part 3: sensitivity to the numerical parameters --------------------------------------------------

def sensitivity_series(plan, material):
    """One single-level series per setting, so that a setting whose run fails costs only itself."""
    scene, window, truth, info = porous_scene(plan, plan.sensitivity_delta, material)
    common = dict(seeds=plan.sensitivity_seeds, sets=[f"cell_size={converge._format(plan.sensitivity_cell)}"],
                  exact=truth)
    series = []
    for param, refine, values, label, default in (("av", "av", plan.sensitivity_av, "av scale", 1.0),
                                                   ("cfl", "cfl", plan.sensitivity_cfl, "cfl", MAIN_CFL),
                                                   ("flip", "flip_fraction", plan.sensitivity_flip, "flip_fraction", 1.0)):
        for value in values:
            series.append(Series("sensitivity", f"{param}_{value:g}", scene, [value], window, refine=refine,
                                 info=dict(info, param=param, label=label, default=default, value=value), **common))
    return series


# --- part 4: the paper's base case ----------------------------------------------------------------------

def answer_scene(plan, material, paper):
    """The paper's base case (configs/paper_base.scene, whose resolved scene is `paper`) in a reduced
    column: the study's keys override the paper's scene."""
    full_end = paper["end_time"]
    delta, velocity, r = paper["porosity"], paper["velocity"], paper["void_radius"]
    exact = hugoniot.porous_shock(velocity, delta, material)
    y1, y2 = 2 * r, 10 * r
    t0, t1, t_release = plateau_window(exact, material, plan.answer_height, y2, 4 * plan.answer_cells[0] + 2 * r,
                                       plan.answer_end)
    reduced = {"shape_function": MAIN_SHAPE, "width": _um(plan.answer_width), "target_height": _um(plan.answer_height),
               "flyer_height": _um(plan.answer_height), "end_time": _ns(plan.answer_end),
               "sample_interval": "1 ns", "snapshot_interval": "0",
               f"region.{REGION}": f"band {_um(y1)} {_um(y2)}"}
    info = dict(delta=delta, velocity=velocity, void_radius=r, exact=exact, full_end=full_end, t_release=t_release,
                band=(y1, y2), paper=paper)
    return Series("answer", "reduced", reduced, list(plan.answer_cells), (t0, t1), seeds=plan.answer_seeds,
                  exact=_truth(exact), info=info, base=PAPER_SCENE)


def anchor_run(series, h0):
    """The full geometry of configs/paper_base.scene once at cell size h0 (the reduced series'
    coarsest), with the reduced series' band: (--set overrides, run directory name). It measures how
    many more steps the full run takes than the reduced runs predict."""
    y1, y2 = series.info["band"]
    overrides = [f"cell_size={converge._format(h0)}", f"shape_function={MAIN_SHAPE}", "snapshot_interval=0", "sample_interval=1ns",
                 f"region.{REGION}=band {_um(y1)} {_um(y2)}"]
    return overrides, f"full_{h0 / UM:g}um"
