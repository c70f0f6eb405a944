"""temperature_model = paper: T = T_H(V) + W_p / c_v, beside the default energy model.

    /usr/bin/python3 -m pytest tests/python/test_temperature_model.py [--mpmshock BUILD/src/mpmshock]

The paper model is a diagnostic: the same run with either model must step identically, only the
temperatures differ. What the paper model adds is W_p, the plastic work turned to heat, which each
point accumulates; with isotropic linear hardening the work of yielding to a plastic strain eps_p is
I(eps_p) = sigma_Y0 eps_p + E_p eps_p^2 / 2 per unit volume whatever the path, so W_p per unit mass
lies between I / rho_max and I / rho_min over the densities the point went through. The case is a
solid plate impact at +-1000 m/s (40 um column, 1 mm bodies, 10 um cells, 2 x 2 points per cell,
to 120 ns: the plateau has formed and no release has come back), and a hydrodynamic porous one
(delta 1.1, no strength) where W_p is zero and the paper model gives T_H(J) exactly. Each case
also runs once with `paper_temperature = on`, which must report both models from the one run:
the energy model's outputs unchanged and the paper model's in its extra columns. About 8 s.

The solid plate runs the porous scenes' A1 = 0.2: at a solid scene's default 0.6 the start-up
heating of the impact (docs/method.md, "Choosing A1") lifts this band, 100-400 um from the plane at
10 um cells, to 509.6 K (T_H 487.7 K), beyond the 15 K within which the models' check holds them.
"""

import shutil
import subprocess

import h5py
import numpy as np
import pytest

from conftest import simulate
from mpmshock_post.hugoniot import default_material, hugoniot_temperature_table

SOLID = """\
velocity = 1000 m/s
porosity = 1
width = 40 um
target_height = 1 mm
flyer_height = 1 mm
cell_size = 10 um
end_time = 120 ns
snapshot_interval = 60 ns
region.plateau = band 100 um 400 um
av_linear = 0.2
probe.top = surface
probe.inside = point 20 um 300 um
"""
POROUS = """\
velocity = 1000 m/s
porosity = 1.1
void_radius = 20 um
plasticity = off
width = 0.1 mm
target_height = 0.4 mm
flyer_height = 0.4 mm
cell_size = 10 um
end_time = 60 ns
snapshot_interval = 0 s
"""
TEMPERATURE_COLUMNS = ("temperature_mean", "temperature_std")


def read_csv(path):
    header, *rows = path.read_text().splitlines()
    names = header.split(",")
    return names, [row.split(",") for row in rows]


@pytest.fixture(scope="module")
def runs(mpmshock, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("temperature_model")
    out = {}
    for name, text in (("solid", SOLID), ("porous", POROUS)):
        scene = tmp / f"{name}.scene"
        scene.write_text(text)
        for model in ("energy", "paper"):
            out[name, model] = tmp / f"{name}_{model}"
            simulate(mpmshock, str(scene), out[name, model], f"temperature_model={model}")
        out[name, "both"] = tmp / f"{name}_both"
        simulate(mpmshock, str(scene), out[name, "both"], "paper_temperature=on")
    out["tmp"] = tmp
    return out


def last_snapshot(run):
    return sorted(run.glob("snapshot_*.h5"))[-1]


@pytest.mark.parametrize("case", ["solid", "porous"])
def test_same_dynamics(runs, case):
    """Only the temperatures differ: conservation.csv is byte for byte the same, and so is every
    regions.csv column but the two temperature columns; so are the snapshots' positions, velocities,
    energies and pressures."""
    energy, paper = runs[case, "energy"], runs[case, "paper"]
    assert (energy / "conservation.csv").read_bytes() == (paper / "conservation.csv").read_bytes()
    names, rows_e = read_csv(energy / "regions.csv")
    _, rows_p = read_csv(paper / "regions.csv")
    assert len(rows_e) == len(rows_p) > 0
    keep = [i for i, n in enumerate(names) if n not in TEMPERATURE_COLUMNS]
    differ = 0
    for a, b in zip(rows_e, rows_p):
        assert [a[i] for i in keep] == [b[i] for i in keep]
        differ += a[names.index("temperature_mean")] != b[names.index("temperature_mean")]
    assert differ > 0, "the two models gave the same temperatures everywhere"
    with h5py.File(last_snapshot(energy)) as fe, h5py.File(last_snapshot(paper)) as fp:
        for field in ("position", "velocity", "internal_energy", "pressure", "deformation_gradient"):
            assert np.array_equal(fe["particles"][field][()], fp["particles"][field][()]), field


def columns(path):
    """CSV column name -> the column's texts, as the simulator printed them."""
    names, rows = read_csv(path)
    return {name: [row[i] for row in rows] for i, name in enumerate(names)}


@pytest.mark.parametrize("case", ["solid", "porous"])
def test_paper_temperature_columns(runs, case):
    """paper_temperature = on: regions.csv holds every column of the energy-model run, printed the
    same, then paper_temperature_mean and _std equal to the paper-model run's temperature columns;
    the same for probes.csv's paper_temperature; conservation.csv is unchanged."""
    energy, paper, both = runs[case, "energy"], runs[case, "paper"], runs[case, "both"]
    assert (both / "conservation.csv").read_bytes() == (energy / "conservation.csv").read_bytes()
    e, p, b = (columns(run / "regions.csv") for run in (energy, paper, both))
    assert list(b) == list(e) + ["paper_temperature_mean", "paper_temperature_std"]
    for name in e:
        assert b[name] == e[name], name
    assert b["paper_temperature_mean"] == p["temperature_mean"]
    assert b["paper_temperature_std"] == p["temperature_std"]
    assert b["paper_temperature_mean"] != b["temperature_mean"]
    if case == "solid":
        e, p, b = (columns(run / "probes.csv") for run in (energy, paper, both))
        assert list(b) == list(e) + ["paper_temperature"]
        for name in e:
            assert b[name] == e[name], name
        assert b["paper_temperature"] == p["temperature"]


@pytest.mark.parametrize("case", ["solid", "porous"])
def test_paper_temperature_snapshot(runs, case):
    """The snapshot's paper_temperature is the paper-model run's temperature bit for bit, and its
    temperature the energy-model run's."""
    energy, paper, both = runs[case, "energy"], runs[case, "paper"], runs[case, "both"]
    with h5py.File(last_snapshot(energy)) as fe, h5py.File(last_snapshot(paper)) as fp, \
            h5py.File(last_snapshot(both)) as fb:
        assert np.array_equal(fb["particles/temperature"][()], fe["particles/temperature"][()])
        assert np.array_equal(fb["particles/paper_temperature"][()], fp["particles/temperature"][()])
        assert "paper_temperature" not in fe["particles"] and "paper_temperature" not in fp["particles"]


def test_paper_temperature_restart(runs, mpmshock):
    """A paper_temperature = on run restarted from its 60 ns snapshot writes the same regions.csv
    and probes.csv, and a restart of an energy-model run that asks for it is refused (its points
    hold no plastic heat: the key cannot change on restart)."""
    original = runs["solid", "both"]
    restarted = runs["tmp"] / "both_restarted"
    shutil.copytree(original, restarted)
    done = subprocess.run([mpmshock, "--restart", str(restarted / "snapshot_00001.h5"), "--force", "--quiet"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    for name in ("regions.csv", "probes.csv"):
        assert (restarted / name).read_bytes() == (original / name).read_bytes(), name
    done = subprocess.run([mpmshock, "--restart", str(runs["solid", "energy"] / "snapshot_00001.h5"), "--set",
                           "paper_temperature=on", "--set", f"output_dir={runs['tmp'] / 'refused'}", "--quiet"],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "paper_temperature" in done.stderr, done.stderr
    assert "cannot change on restart" in done.stderr, done.stderr


@pytest.mark.parametrize("override, words", [("temperature_model=paper", "temperature_model = energy"),
                                             ("heat_conduction=on", "heat_conduction"),
                                             ("thermal_softening=on", "thermal_softening"),
                                             ("thermal=off", "thermal = on")])
def test_paper_temperature_refuses(runs, mpmshock, override, words):
    """paper_temperature = on is refused where it would repeat the temperature or report one the run
    does not follow: the error names the file, the line and the key."""
    scene = runs["tmp"] / "both.scene"
    scene.write_text(SOLID + "paper_temperature = on\n")
    line = len(SOLID.splitlines()) + 1
    done = subprocess.run([mpmshock, str(scene), "--check", "--set", override], capture_output=True, text=True)
    assert done.returncode == 2
    assert f"both.scene:{line}" in done.stderr, done.stderr
    assert "paper_temperature" in done.stderr and words in done.stderr, done.stderr


def snapshot_state(run):
    with h5py.File(last_snapshot(run)) as f:
        p = f["particles"]
        F = p["deformation_gradient"][()]
        J = F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0]
        heat = f["restart/plastic_heat"][()] if "restart/plastic_heat" in f else None
        return dict(J=J, T=p["temperature"][()], eps_p=p["plastic_strain"][()] if "plastic_strain" in p else None,
                    heat=heat, y=p["position"][:, 1], density=p["density"][()])


def test_paper_temperature_is_hugoniot_plus_plastic_heat(runs, mpmshock):
    """The snapshot's temperature is T_H(J) + W_p / c_v, T_H from Python's own table."""
    material = default_material(mpmshock)
    table = hugoniot_temperature_table(material)
    s = snapshot_state(runs["solid", "paper"])
    expected = np.array([table.hugoniot_temperature(J) for J in s["J"]]) + s["heat"] / material.specific_heat
    assert np.max(np.abs(s["T"] - expected)) < 1e-6
    assert np.all(s["heat"] >= 0.0)


def test_plastic_heat_is_the_work_of_yielding(runs, mpmshock):
    """Per point, W_p lies within I(eps_p) / rho over the densities of a solid plate before any
    release (2700 kg/m3 at rest up to 1.04 x the Rankine-Hugoniot 3174.5 kg/m3 with the shock's
    overshoot); and the shocked points did yield (eps_p > 0.05: the uniaxial-strain shock to J = 0.85
    strains them plastically by about 0.1)."""
    material = default_material(mpmshock)
    s = snapshot_state(runs["solid", "paper"])
    sigma_y0, E, E_tan = 120e6, 69e9, 384e6
    E_p = E * E_tan / (E - E_tan)
    work = sigma_y0 * s["eps_p"] + 0.5 * E_p * s["eps_p"] ** 2  # J/m3
    shocked = s["eps_p"] > 0.05
    assert np.count_nonzero(shocked) > 1000
    rho_low, rho_high = material.density, 1.04 * 3174.5
    assert np.all(s["heat"] <= work / rho_low * (1 + 1e-9) + 1e-9)
    assert np.all(s["heat"][shocked] >= work[shocked] / rho_high)


def test_solid_plateau_models_close(runs):
    """Without voids there is no compaction heat: in the plateau band the paper model differs from
    the energy model only by the plastic work the Hugoniot's T_H already counts as shock heat
    (W_p / c_v ~ 10 K at 1000 m/s), and both lie within 15 K of T_H = 487.7 K."""
    def plateau(run):
        names, rows = read_csv(run / "regions.csv")
        col = names.index("temperature_mean")
        return np.mean([float(r[col]) for r in rows if r[1] == "plateau" and float(r[0]) >= 100e-9])
    energy, paper = plateau(runs["solid", "energy"]), plateau(runs["solid", "paper"])
    assert abs(energy - 487.7) < 15 and abs(paper - 487.7) < 15
    assert 0.0 < paper - energy < 15.0


def test_porous_hydrodynamic(runs, mpmshock):
    """No strength, no plastic work: the paper model is T_H(J) exactly, and leaves out the heat of
    compaction that the energy model counts, so every point that a void's collapse heated is colder."""
    material = default_material(mpmshock)
    table = hugoniot_temperature_table(material)
    paper = snapshot_state(runs["porous", "paper"])
    energy = snapshot_state(runs["porous", "energy"])
    assert np.all(paper["heat"] == 0.0)
    T_H = np.array([table.hugoniot_temperature(J) for J in paper["J"]])
    assert np.max(np.abs(paper["T"] - T_H)) < 1e-6
    heated = energy["T"] - paper["T"]
    assert np.mean(heated[energy["y"] > 0]) > 20.0  # compaction heat in the target, K


def test_restart_reads_plastic_heat(runs, mpmshock):
    """A paper-model run restarted from its 60 ns snapshot writes the same regions.csv."""
    original = runs["solid", "paper"]
    restarted = runs["tmp"] / "restarted"
    shutil.copytree(original, restarted)
    done = subprocess.run([mpmshock, "--restart", str(restarted / "snapshot_00001.h5"), "--force", "--quiet"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert (restarted / "regions.csv").read_bytes() == (original / "regions.csv").read_bytes()


@pytest.mark.parametrize("override, words", [("heat_conduction=on", "heat_conduction"),
                                             ("thermal_softening=on", "thermal_softening"),
                                             ("thermal=off", "thermal = on")])
def test_paper_model_refuses(runs, mpmshock, override, words):
    """The paper model does not count compaction heat, so it must not drive conduction or softening:
    the error names the scene file, the line and the key."""
    scene = runs["tmp"] / "paper_model.scene"
    scene.write_text(SOLID + "temperature_model = paper\n")
    line = len(SOLID.splitlines()) + 1
    done = subprocess.run([mpmshock, str(scene), "--check", "--set", override], capture_output=True, text=True)
    assert done.returncode == 2
    assert f"paper_model.scene:{line}" in done.stderr
    assert "temperature_model" in done.stderr and words in done.stderr


def test_paper_temperature_reader(runs):
    """reader.PaperTemperatureRun reads a paper_temperature = on run as the paper-model run reads:
    the same regions.csv temperatures, probes and snapshot temperature field, every other column
    the run's own; a run without the columns is refused."""
    from mpmshock_post.errors import PostError
    from mpmshock_post.reader import PaperTemperatureRun, Run, has_paper_temperature

    view, paper = PaperTemperatureRun(runs["solid", "both"]), Run(runs["solid", "paper"])
    for name, series in paper.regions().items():
        got = view.regions()[name]
        for column in series:
            assert np.array_equal(got[column], series[column], equal_nan=column != "region"), (name, column)
    for name, series in paper.probes().items():
        assert np.array_equal(view.probes()[name]["temperature"], series["temperature"])
    assert np.array_equal(view.snapshot()["temperature"], paper.snapshot()["temperature"])
    assert np.array_equal(view.snapshot()["density"], paper.snapshot()["density"])
    assert not has_paper_temperature(runs["solid", "energy"])
    with pytest.raises(PostError, match="paper_temperature = on"):
        PaperTemperatureRun(runs["solid", "energy"])
