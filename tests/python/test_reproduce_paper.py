"""studies/paper/reproduce-paper: which runs each figure needs, valid quick scenes, the reuse / resume /
fresh decision on fake run directories, and one end-to-end campaign on tiny scenes (all 13
figures, paper.md) that a failing case stops with its name and log.

    OMP_WAIT_POLICY=PASSIVE /usr/bin/python3 -m pytest -q tests/python/test_reproduce_paper.py
"""

import csv
import json
import os
import shutil
import subprocess

import pytest

from conftest import STUDIES, simulate
from paper import runs as paper_runs
from paper.campaign import build_parser
from paper.runs import (FIGURE_CASES, PlannedRun, cases_for, command, decide, plan_runs,
                                     quick_overrides)
from mpmshock_post.resolve import default_scene

REPRODUCE = STUDIES / "paper/reproduce-paper"
PAPER_SCENES = STUDIES / "paper/scenes"
CASES = sorted(path.stem for path in PAPER_SCENES.glob("*.scene"))

# A 200 um column of 200 um plates with a few 25 um voids: a run to 1.3 us in a fraction of a second,
# with the paper's regions and 50 ns snapshots, standing in for every case of the campaign.
TINY_SCENE = """velocity = 1000 m/s
porosity = 1.15
void_radius = 25 um
void_radius_spread = 5 um
width = 200 um
target_height = 200 um
flyer_height = 200 um
cell_size = 20 um
end_time = 1.3 us
sample_interval = 10 ns
snapshot_interval = 50 ns
region.B800 = bottom 100 um 800 um
region.B400 = bottom 100 um 400 um
region.B100 = bottom 100 um 100 um
region.T800 = top 800 um
region.T400 = top 400 um
region.T100 = top 100 um
"""


def reproduce(*args, scenes=None):
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    if scenes is not None:
        env["REPRODUCE_PAPER_SCENES"] = str(scenes)
    return subprocess.run([str(REPRODUCE), *map(str, args)], capture_output=True, text=True, env=env)


@pytest.fixture(scope="module")
def defaults(mpmshock):
    return default_scene(mpmshock)


def test_every_case_has_a_scene_and_a_figure():
    needed = {case for cases in FIGURE_CASES.values() for case in cases}
    assert needed == set(CASES), f"figures need {sorted(needed)}, studies/paper/scenes has {CASES}"


def test_cases_follow_the_figures():
    assert cases_for([1, 2, 3, 4, 5, 6]) == ["base"]
    assert cases_for([7]) == ["void_r25", "base", "void_r100"]
    assert cases_for([9, 10, 11]) == ["delta1.4"]
    assert cases_for([12]) == ["delta1.4_v500", "delta1.4", "delta1.4_v1500", "delta1.4_v2000"]
    assert cases_for([12, 13]) == ["delta1.4_v500", "delta1.4", "delta1.4_v1500", "delta1.4_v2000",
                                   "delta1.01", "delta1.02", "delta1.1", "delta1.7"]
    assert build_parser().parse_args(["--out", "x", "--fig", "13,2,2"]).fig == [2, 13]
    for bad in ("14", "0", "a", ""):
        with pytest.raises(SystemExit):
            build_parser().parse_args(["--out", "x", "--fig", bad])
    with pytest.raises(SystemExit):
        build_parser().parse_args(["--out", "x", "--temperature-models", "paper"])


def test_plan_names_and_overrides(tmp_path):
    both = plan_runs(["base", "delta1.4"], ["energy", "paper"], tmp_path, quick=True, combined=True)
    assert [run.name for run in both] == ["base", "delta1.4"]
    assert all("paper_temperature=on" in run.overrides for run in both)
    alone = plan_runs(["base"], ["energy"], tmp_path, quick=True, combined=True)
    assert "paper_temperature=on" not in alone[0].overrides
    runs = plan_runs(["base", "delta1.4"], ["energy", "paper"], tmp_path, quick=True)
    names = [run.name for run in runs]
    assert names[:2] == ["base", "delta1.4"], names
    if paper_runs.QUICK_PAPER_T_CASES is None:
        assert names[2:] == ["base-paperT", "delta1.4-paperT"], names
    assert "temperature_model=paper" in runs[-1].overrides
    assert "temperature_model=paper" not in runs[0].overrides
    assert runs[0].log == tmp_path / "base.log"
    full = plan_runs(["base"], ["energy"], tmp_path, quick=False)
    assert full[0].overrides == []
    alone = command(full[0], "mpmshock", "fresh", None, 2)
    assert alone[0] == "mpmshock" and alone[-2:] == ["--threads", "2"], alone
    spread = command(full[0], "mpmshock", "resume", "s.h5", 1, ranks=2)
    assert spread[:6] == ["mpirun", "-q", "--bind-to", "none", "-np", "2"] and spread[6:9] == ["mpmshock", "--restart", "s.h5"]


def test_quick_scenes_are_valid(mpmshock, defaults):
    """mpmshock --check accepts every case with the quick overrides (and the paper model where the
    simulator has it)."""
    for case in CASES:
        command = [mpmshock, str(PAPER_SCENES / f"{case}.scene"), "--check"]
        overrides = quick_overrides(case) + (["temperature_model=paper"] if "temperature_model" in defaults else [])
        for override in overrides:
            command += ["--set", override]
        done = subprocess.run(command, capture_output=True, text=True)
        assert done.returncode == 0, f"{' '.join(command)}: exit {done.returncode}\n{done.stdout}{done.stderr}"


@pytest.fixture(scope="module")
def finished_run(mpmshock, tmp_path_factory):
    """A finished tiny run of TINY_SCENE, as the campaign would have written it."""
    tmp = tmp_path_factory.mktemp("reuse")
    scene = tmp / "base.scene"
    scene.write_text(TINY_SCENE.replace("1.3 us", "100 ns"))
    simulate(mpmshock, str(scene), tmp / "runs/base")
    return PlannedRun("base", "energy", scene, [], tmp / "runs/base")


def variant(run, tmp_path, change=None):
    """A copy of the run's directory, changed by `change(run_dir)`."""
    copy = PlannedRun(run.case, run.model, run.scene, list(run.overrides), tmp_path / "runs" / run.name)
    shutil.copytree(run.run_dir, copy.run_dir)
    if change:
        change(copy.run_dir)
    return copy


def set_exit_code(code):
    def change(run_dir):
        summary = json.loads((run_dir / "summary.json").read_text())
        (run_dir / "summary.json").write_text(json.dumps({**summary, "exit_code": code}))
    return change


def test_reuse_resume_or_fresh(finished_run, mpmshock, tmp_path):
    assert decide(finished_run, mpmshock) == ("reuse", None)

    changed = variant(finished_run, tmp_path / "a")
    changed.overrides = ["velocity=1500"]
    assert decide(changed, mpmshock) == ("fresh", None), "a run of another scene must not be reused"

    killed = variant(finished_run, tmp_path / "b", lambda d: (d / "summary.json").unlink())
    action, snapshot = decide(killed, mpmshock)
    assert action == "resume" and snapshot == sorted(killed.run_dir.glob("snapshot_*.h5"))[-1], (action, snapshot)

    for code in (130, 143):
        action, snapshot = decide(variant(finished_run, tmp_path / f"c{code}", set_exit_code(code)), mpmshock)
        assert action == "resume" and snapshot is not None, (code, action)

    failed = variant(finished_run, tmp_path / "d", set_exit_code(3))
    assert decide(failed, mpmshock) == ("fresh", None), "a failed run (exit 3) is rerun, not resumed"

    def only_scene(run_dir):
        for path in run_dir.glob("snapshot_*.h5"):
            path.unlink()
        (run_dir / "summary.json").unlink()
    assert decide(variant(finished_run, tmp_path / "e", only_scene), mpmshock) == ("fresh", None)

    empty = PlannedRun("base", "energy", finished_run.scene, [], tmp_path / "none/base")
    assert decide(empty, mpmshock) == ("fresh", None)


def test_campaign_on_tiny_scenes(mpmshock, defaults, tmp_path):
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    for case in CASES:
        (scenes / f"{case}.scene").write_text(TINY_SCENE)
    out = tmp_path / "out"
    done = reproduce("--out", out, scenes=scenes)
    assert done.returncode == 0, done.stderr
    for number in range(1, 14):
        image = out / f"fig{number:02d}.png"
        assert image.is_file() and image.stat().st_size > 10_000, f"{image} missing or empty"
    page = (out / "paper.md").read_text()
    assert "![Fig. 13](fig13.png)" in page and "| `runs/base` |" in page, page
    with_paper = "temperature_model" in defaults
    combined = "paper_temperature" in defaults
    assert (out / "runs/base-paperT/summary.json").is_file() == (with_paper and not combined)
    assert with_paper or "skipping the paper temperature model" in done.stderr, done.stderr
    if combined:  # one run per case reports both models, and the comparison reads both
        assert "paper_temperature_mean" in (out / "runs/base/regions.csv").read_text().splitlines()[0]
        rows = list(csv.DictReader(open(out / "comparison.csv")))
        paper_t = [r for r in rows if "(paper T)" in r["quantity"] and r["mpmshock"] not in ("", "nan")]
        assert paper_t, "no paper-T row was measured from the combined runs"
        assert not any("not run: base-paperT" in r["note"] for r in rows)

    again = reproduce("--out", out, "--fig", "2", scenes=scenes)
    assert again.returncode == 0 and "base: reused" in again.stderr, again.stderr
    assert "started" not in again.stderr, again.stderr

    (scenes / "base.scene").write_text(TINY_SCENE + "no_such_key = 1\n")
    broken = reproduce("--out", out, "--fig", "2", "--temperature-models", "energy", scenes=scenes)
    assert broken.returncode != 0
    assert "case base failed" in broken.stderr and str(out / "runs/base.log") in broken.stderr, broken.stderr
    assert "no_such_key" in (out / "runs/base.log").read_text()


def test_plot_options_for_the_paper(finished_run):
    """The options the paper's figures need from the plotting modules: pressure in MPa, lengths in
    10 um, points at their true size, a minimum span for mean velocities, offsets in a comparison."""
    from mpmshock_post import PostError, reader
    from mpmshock_post.compare import plot_compare
    from mpmshock_post.field import plot_field
    from mpmshock_post.timeseries import plot_means
    from mpmshock_post.units import quantity

    assert quantity("pressure", "MPa").factor == 1e-6 and quantity("pressure", "GPa").factor == 1e-9
    with pytest.raises(PostError, match="cannot be shown in 'MPa'"):
        quantity("temperature", "MPa")

    run = reader.Run(finished_run.run_dir)
    fig = plot_field(run.snapshot(), color="pressure", unit="MPa", length_unit_um=10.0, true_size=True, body="target")
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert "$P$ (MPa)" in labels and "$y$ (10 µm)" in labels, labels
    top = run.snapshot()["position"][:, 1].max() * 1e6 / 10.0
    assert abs(fig.axes[0].get_ylim()[1] - top) < 1e-9, (fig.axes[0].get_ylim(), top)

    means = plot_means(run, regions=["B100"])
    u_x = next(ax for ax in means.axes if ax.get_ylabel() == "$u_x$ (m/s)")  # a few m/s of noise about 0
    assert u_x.get_ylim()[1] - u_x.get_ylim()[0] >= 50.0, u_x.get_ylim()

    shifted = plot_compare([run, run], quantities=["density"], labels=["a", "b"], offsets={"density": [0.0, 0.1]})
    a, b = shifted.axes[0].get_lines()[:2]
    assert abs((b.get_ydata() - a.get_ydata()).mean() - 0.1) < 1e-12
    with pytest.raises(PostError, match="one value per run"):
        plot_compare([run, run], quantities=["density"], offsets={"density": [0.1]})


def test_records_carry_a_campaign_to_the_next_sitting(tmp_path):
    """--records keeps each finished run's scene, summary and CSVs; a later campaign in a new DIR
    takes the runs from them as finished, draws the figures of the time series from them, and says
    so; a case whose snapshots a requested figure reads runs instead."""
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    for case in CASES:
        (scenes / f"{case}.scene").write_text(TINY_SCENE)
    records = tmp_path / "records"
    first = reproduce("--out", tmp_path / "first", "--fig", "7,12", "--records", records, scenes=scenes)
    assert first.returncode == 0, first.stderr
    for case in ("void_r25", "base", "void_r100", "delta1.4_v500", "delta1.4", "delta1.4_v1500", "delta1.4_v2000"):
        kept = {p.name for p in (records / case).iterdir()}  # probes.csv where the scene has probes
        assert {"scene.txt", "summary.json", "regions.csv", "conservation.csv"} <= kept <= set(paper_runs.RECORD_FILES)
        assert (records / f"{case}.json").is_file()
    assert not list(records.rglob("*.h5"))

    later = tmp_path / "later"
    again = reproduce("--out", later, "--fig", "7,12", "--records", records, scenes=scenes)
    assert again.returncode == 0, again.stderr
    assert "base: taken from its record" in again.stderr and "base: reused" in again.stderr, again.stderr
    assert "started" not in again.stderr, again.stderr
    assert not list((later / "runs").rglob("*.h5"))
    for number in (7, 12):
        assert (later / f"fig{number:02d}.png").stat().st_size > 10_000
    rows = [r for r in csv.DictReader(open(later / "comparison.csv")) if r["figure"] in ("Fig 7", "Fig 12")]
    assert rows and not any(r["note"].startswith("not run") for r in rows), rows
    # The runs' wall times are the ones the first sitting measured.
    assert json.loads((later / "runs/base.json").read_text()) == json.loads((records / "base.json").read_text())

    # A record is kept as soon as its run finishes: a sitting whose last run fails keeps the others'.
    (scenes / "void_r100.scene").write_text(TINY_SCENE + "porosity = 0.5\n")
    broken_records = tmp_path / "broken-records"
    broken = reproduce("--out", tmp_path / "broken", "--fig", "7", "--records", broken_records, scenes=scenes)
    assert broken.returncode != 0 and "void_r100" in broken.stderr, broken.stderr
    assert "void_r25: record kept" in broken.stderr and "base: record kept" in broken.stderr, broken.stderr
    assert sorted(p.name for p in broken_records.iterdir()) == ["base", "base.json", "void_r25", "void_r25.json"]
    (scenes / "void_r100.scene").write_text(TINY_SCENE)

    # Fig. 3 reads the base case's snapshots: in a new DIR that case runs, its record notwithstanding.
    fresh = tmp_path / "fresh"
    drawn = reproduce("--out", fresh, "--fig", "3", "--records", records, scenes=scenes)
    assert drawn.returncode == 0, drawn.stderr
    assert "base: started (fresh)" in drawn.stderr and "taken from its record" not in drawn.stderr, drawn.stderr
    assert (fresh / "fig03.png").is_file() and list((fresh / "runs/base").glob("snapshot_*.h5"))
