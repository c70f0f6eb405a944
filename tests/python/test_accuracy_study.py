"""studies/accuracy/accuracy-study: its helpers (the package `accuracy` under studies/), its report
template, and a smoke test of the quick solid part end to end.

    /usr/bin/python3 -m pytest tests/python/test_accuracy_study.py [--mpmshock BUILD/src/mpmshock]

The smoke test runs `accuracy-study --quick --only solid` into a temporary directory, with the
binary under test as $MPMSHOCK: solid plates at 1000 m/s, the study's main shape (plan.MAIN_SHAPE,
bspline2_domain) and bilinear, cell sizes 20, 10, 5 um (six runs, about 10 s on 2 cores), then once
more to check that every run is reused. It checks that the document and its figures are written with
their tables, and one reference number: the main shape's plateau pressure at 5 um lies within 1 % of
the exact Rankine-Hugoniot 18.063 GPa (measured 2026-12-05 with bspline2_domain: -0.002 %; bspline2
2026-11: +0.03 %).
"""

import csv
import math
import os
import subprocess
import sys

import pytest

from accuracy import measure, plan, report
from conftest import STUDIES
from mpmshock_post import hugoniot
from mpmshock_post.converge import Estimate, Result
from mpmshock_post.errors import PostError

STUDY = STUDIES / "accuracy/accuracy-study"
PNG = b"\x89PNG\r\n\x1a\n"


# --- helpers ------------------------------------------------------------------------------------------

def test_needed_resolution_measured_and_extrapolated():
    h = [20e-6, 10e-6, 5e-6]
    result = Result("plateau", "pressure_mean", [10.4, 10.1, 10.025],
                    [0.0, 0.0, 0.0], Estimate(10.0, 2.0, [0.4, 0.1, 0.025]))
    assert measure.needed_resolution(result, h, 0.05, True)[0] == 20e-6       # 4 % at 20 um
    cell, error, how = measure.needed_resolution(result, h, 0.01, True)
    assert cell == 10e-6 and error == pytest.approx(0.01) and how == "measured"
    cell, error, how = measure.needed_resolution(result, h, 0.0025 / 4, True)  # 4x finer than the finest
    assert cell == pytest.approx(2.5e-6) and "extrapolated (order 2.00)" in how
    fallback = Result("plateau", "temperature_mean", [500.0, 520.0, 510.0], [0, 0, 0],
                      Estimate(510.0, math.nan, [30.0, 30.0, 20.0], "fallback: not monotone"))
    cell, _, how = measure.needed_resolution(fallback, h, 10.0, False)
    assert cell == pytest.approx(2.5e-6) and "fallback order 1" in how


def test_nice_cell_divides_the_width():
    assert measure.nice_cell(4.1e-6, 2e-3) == pytest.approx(4e-6)
    assert measure.nice_cell(3.5e-6, 2e-3) == pytest.approx(2.5e-6)
    assert measure.nice_cell(20e-6, 2e-3) == pytest.approx(20e-6)


def test_exact_order():
    assert measure.exact_order([4.0, 2.0, 1.0], [4.0, 2.0, 1.0]) == pytest.approx(1.0)
    assert measure.exact_order([4.0, 2.0, -1.0], [4.0, 2.0, 1.0]) is None


def test_plateau_window_ends_before_the_release():
    material = hugoniot.Material(2700.0, 5350.0, 1.34, 1.96, 880.0, 300.0)
    state = hugoniot.solid_shock(2000.0, material)
    t0, t1, t_release = plan.plateau_window(state, material, 1e-3, 400e-6, 80e-6, 200e-9)
    assert t0 == pytest.approx(80e-9)                  # (400 + 80) um at 6030 m/s, rounded up
    assert t1 < t_release < 200e-9                     # the release would come before 200 ns
    assert t1 == round(t1 / 1e-9) * 1e-9
    with pytest.raises(PostError, match="too short"):
        plan.plateau_window(state, material, 0.5e-3, 400e-6, 80e-6, 200e-9)


def test_porous_comparisons_include_the_main_shape_without_smoothing():
    """The main shape with volumetric_smoothing = off (the porous default until 2026-12-05) runs beside
    the comparison shapes at delta 1.1, at the main shape's cells, with 2 layouts (1 with --quick)."""
    material = hugoniot.Material(2700.0, 5350.0, 1.34, 1.96, 880.0, 300.0)
    for quick, seeds in ((False, 2), (True, 1)):
        p = plan.Plan.make(quick)
        series = {s.name: s for s in plan.porous_series(p, material)}
        main, off = series[f"d1.1_{plan.MAIN_SHAPE}"], series[f"d1.1_{plan.MAIN_SHAPE}_nosmooth"]
        assert off.scene == dict(main.scene, volumetric_smoothing="off")
        assert "volumetric_smoothing" not in main.scene and off.values == main.values == list(p.porous_cells)
        assert off.seeds == seeds and off.window == main.window
        assert main.info["comparison"] is None and off.info["comparison"].note == "porous.smoothing_off"
        assert off.info["label"] == f"{plan.MAIN_SHAPE} (smoothing off)" and off.info["shape"] == plan.MAIN_SHAPE
        others = {s.info["shape"] for s in series.values() if s.info["comparison"] and not s.info["comparison"].scene}
        assert others == ({"bspline2"} if quick else {"bspline2", "gimp", "bilinear"})
    assert plan.Plan.make(False).porous_cells == (10e-6, 5e-6, 2.5e-6)
    note = report.Prose()("porous.smoothing_off", label="x (smoothing off)", main_shape=plan.MAIN_SHAPE)
    assert "`volumetric_smoothing = off`" in note and "2026-12-05" in note
    assert '"Volumetric smoothing where a body is porous"' in note and "(method.md)" in note


def test_template_fills_blocks_and_names_the_parts():
    prose = report.Prose()
    layouts = prose("layouts", count=2, plural="s", seeds="1, 2")
    assert layouts == "2 void layouts (seeds 1, 2)"
    choice = prose("choices.sensitivity", delta="1.1", h="5 um", seeds=2)
    assert "\\" not in choice and "\n" not in choice and "the finest h at which 9 settings x the layouts" in choice
    assert [report.anchor(prose.heading(part)) for part in plan.PARTS] == [
        "1-solid-plates-against-the-exact-rankine-hugoniot-state", "2-porous-bodies-convergence-under-void-resolution",
        "3-sensitivity-to-the-numerical-parameters", "4-the-papers-base-case-what-resolution-at-what-cost"]
    with pytest.raises(KeyError, match="no value for 'seeds'"):
        prose("layouts", count=2, plural="s")


# --- the quick solid study ----------------------------------------------------------------------------

def study_cli(binary, *args):
    return subprocess.run([sys.executable, str(STUDY), *map(str, args)], capture_output=True, text=True,
                          env=dict(os.environ, MPMSHOCK=str(binary), OMP_WAIT_POLICY="PASSIVE"))


@pytest.fixture(scope="module")
def quick(mpmshock, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("accuracy")
    args = ["--quick", "--only", "solid", "--out", tmp / "runs", "--docs", tmp / "docs"]
    done = study_cli(mpmshock, *args)
    assert done.returncode == 0, done.stderr
    return dict(tmp=tmp, args=args, first=done, binary=mpmshock)


def test_document_and_figures(quick):
    docs = quick["tmp"] / "docs"
    text = (docs / "accuracy.md").read_text()
    assert "Quick mode" in text and "## 1. Solid plates against the exact Rankine-Hugoniot state" in text
    assert "## 2. Porous" not in text and "## The answer" not in text   # --only solid
    for quantity in ("pressure_mean", "macro_normal_stress", "density_mean", "temperature_mean"):
        assert f"### {quantity}" in text
        table = text.split(f"### {quantity}", 1)[1].split("\n\n")[1].splitlines()
        assert table[0].startswith("| speed | shape | ppc | error 20 um | error 10 um | error 5 um |")
        assert {row.split("|")[2].strip() for row in table[2:]} == {plan.MAIN_SHAPE, "bilinear"}
    assert "## Findings" in text and "## Run time" in text and "## The plateaus" in text
    for name in ("solid_h", "solid_cost", "windows"):
        assert f"(accuracy_{name}.png)" in text
        assert (docs / f"accuracy_{name}.png").read_bytes().startswith(PNG)
    printed = quick["first"].stdout.split()
    assert str(docs / "accuracy.md") in printed


def test_main_shape_pressure_is_near_the_exact_state(quick):
    rows = list(csv.DictReader(open(quick["tmp"] / f"runs/solid/v1000_{plan.MAIN_SHAPE}_ppc2/convergence.csv")))
    pressure = [r for r in rows if r["region"] == "plateau" and r["quantity"] == "pressure_mean"]
    assert [float(r["cell_size"]) for r in pressure] == [20e-6, 10e-6, 5e-6]
    exact = hugoniot.solid_shock(1000.0, hugoniot.default_material(quick["binary"])).pressure
    assert abs(float(pressure[-1]["value"]) / exact - 1.0) < 0.01


def test_rerun_reuses_every_run(quick):
    done = study_cli(quick["binary"], *quick["args"])
    assert done.returncode == 0, done.stderr
    assert done.stderr.count("reused") == 6, done.stderr
    assert "(0 runs made" in (quick["tmp"] / "docs" / "accuracy.md").read_text()


def test_bad_part_is_refused(quick):
    done = study_cli(quick["binary"], "--only", "solid,liquid", "--out", quick["tmp"] / "x")
    assert done.returncode == 1 and "unknown part liquid" in done.stderr and "Traceback" not in done.stderr
