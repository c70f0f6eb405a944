"""The reader's CSV series as pandas and xarray tables, and the package's one version number.

regions.csv, probes.csv and conservation.csv convert with .to_pandas() and .to_xarray() to tables
holding the very numbers the numpy reader gives, in SI with their units; without pandas or xarray
the conversion says which Debian package to install, and nothing but a conversion imports them.

    /usr/bin/python3 -m pytest tests/python/test_post_tables.py [--mpmshock BUILD/src/mpmshock]
"""

import importlib.util
import os
import re
import shutil
import subprocess
import sys
import tomllib
import warnings

import numpy as np
import pytest

import mpmshock_post
from conftest import ROOT, SCRIPTS, simulate
from mpmshock_post import PostError, reader

needs_tables = pytest.mark.skipif(not (importlib.util.find_spec("pandas") and importlib.util.find_spec("xarray")),
                                  reason="pandas and xarray are not installed (python3-pandas, python3-xarray)")


@pytest.fixture(scope="module")
def run_dir(mpmshock, tiny_scene, tmp_path_factory):
    """A tiny run with a surface probe and a point probe."""
    out = tmp_path_factory.mktemp("tables") / "run"
    simulate(mpmshock, tiny_scene, out, "probe.free_surface=surface", "probe.p1=point 100um 150um")
    return out


@needs_tables
def test_regions_to_pandas(run_dir):
    regions = reader.Run(run_dir).regions()
    frame = regions.to_pandas()
    names = list(regions)
    samples = len(regions[names[0]]["time"])
    assert list(frame.columns[:2]) == ["time", "region"]
    assert list(frame.columns[2:]) == [c for c in regions[names[0]] if c not in ("time", "region")]
    assert len(frame) == samples * len(names), "one row per region per sample"
    # ordered as regions.csv: by time, the regions in file order at each time
    assert list(frame["region"][:len(names)]) == names
    assert np.all(np.diff(frame["time"].to_numpy()) >= 0)
    for name in names:
        rows = frame[frame["region"] == name]
        for column, values in regions[name].items():
            assert np.array_equal(rows[column].to_numpy(), values, equal_nan=column != "region"), (name, column)
    assert frame["count"].dtype.kind == "i"
    assert frame.attrs["units"]["pressure_mean"] == "Pa" and frame.attrs["units"]["time"] == "s"
    assert frame.attrs["units"]["rot2_mean"] == "1/s2" and frame.attrs["units"]["density_std"] == "kg/m3"


@needs_tables
def test_regions_to_xarray(run_dir):
    regions = reader.Run(run_dir).regions()
    data = regions.to_xarray()
    names = list(regions)
    assert dict(data.sizes) == {"time": len(regions[names[0]]["time"]), "region": len(names)}
    assert list(data["region"].values) == names
    assert np.array_equal(data["time"].values, regions[names[0]]["time"])
    for name in names:
        for column, values in regions[name].items():
            if column in ("time", "region"):
                continue
            assert data[column].dims == ("time", "region")
            assert np.array_equal(data[column].sel(region=name).values, values, equal_nan=True), (name, column)
    assert data["count"].dtype.kind == "i", "counts stay whole numbers when every region has every time"
    assert data["pressure_mean"].attrs["units"] == "Pa" and data["temperature_std"].attrs["units"] == "K"
    assert data["macro_density"].attrs["units"] == "kg/m3" and data["time"].attrs["units"] == "s"
    assert data["count"].attrs["units"] == ""
    b800 = data.sel(region="B800")
    assert float(b800["density_mean"].isel(time=-1)) == regions["B800"]["density_mean"][-1]


@needs_tables
def test_torn_regions_to_xarray(run_dir, tmp_path):
    """A run killed mid-sample lacks its last rows for some regions: NaN there, not a shifted table."""
    torn = tmp_path / "torn"
    shutil.copytree(run_dir, torn)
    lines = (torn / "regions.csv").read_text().splitlines(keepends=True)
    (torn / "regions.csv").write_text("".join(lines[:-2]))  # the last sample without its last two regions
    regions = reader.Run(torn).regions()
    data = regions.to_xarray()
    last_two = list(regions)[-2:]
    assert np.isnan(data["density_mean"].sel(region=last_two).isel(time=-1).values).all()
    assert not np.isnan(data["density_mean"].sel(region=list(regions)[0]).values).any()
    kept = data["density_mean"].sel(region=last_two[0]).values[:-1]
    assert np.array_equal(kept, regions[last_two[0]]["density_mean"])


@needs_tables
def test_probes_tables(run_dir):
    probes = reader.Run(run_dir).probes()
    assert list(probes) == ["free_surface", "p1"]
    frame = probes.to_pandas()
    assert list(frame.columns[:3]) == ["time", "probe", "count"]
    assert len(frame) == sum(len(series["time"]) for series in probes.values())
    surface = frame[frame["probe"] == "free_surface"]
    assert np.array_equal(surface["velocity_y"].to_numpy(), probes["free_surface"]["velocity_y"])
    data = probes.to_xarray()
    assert data["velocity_y"].dims == ("time", "probe") and list(data["probe"].values) == ["free_surface", "p1"]
    assert np.array_equal(data["pressure"].sel(probe="p1").values, probes["p1"]["pressure"])
    units = {name: data[name].attrs["units"] for name in ("x", "velocity_y", "pressure", "density", "temperature")}
    assert units == {"x": "m", "velocity_y": "m/s", "pressure": "Pa", "density": "kg/m3", "temperature": "K"}


@needs_tables
def test_conservation_tables(run_dir):
    conservation = reader.Run(run_dir).conservation()
    frame = conservation.to_pandas()
    assert frame.index.name == "time"
    assert np.array_equal(frame.index.to_numpy(), conservation["time"])
    assert list(frame.columns) == [c for c in conservation if c != "time"]
    assert np.array_equal(frame["total_energy"].to_numpy(), conservation["total_energy"])
    assert frame["step"].dtype.kind == "i"
    data = conservation.to_xarray()
    assert data["total_energy"].dims == ("time",)
    assert np.array_equal(data["mass"].values, conservation["mass"])
    # a 2D run: extensive quantities per metre of depth
    assert (data["mass"].attrs["units"], data["momentum_x"].attrs["units"], data["kinetic_energy"].attrs["units"],
            data["dt"].attrs["units"]) == ("kg/m", "kg/s", "J/m", "s")
    assert frame.attrs["units"]["work_mismatch"] == "J/m"


def test_dict_behaviour_kept(run_dir):
    """The series are still the dicts the plots and scripts use."""
    run = reader.Run(run_dir)
    regions = run.regions()
    assert isinstance(regions, dict) and isinstance(regions["B800"], dict)
    assert isinstance(run.conservation(), dict)
    assert sorted(dict(regions)) == sorted(regions)


@pytest.mark.parametrize("module, package, convert", [
    ("pandas", "python3-pandas", lambda run: run.regions().to_pandas()),
    ("xarray", "python3-xarray", lambda run: run.probes().to_xarray()),
    ("pandas", "python3-pandas", lambda run: run.conservation().to_pandas()),
    ("xarray", "python3-xarray", lambda run: run.conservation().to_xarray()),
])
def test_missing_optional_package(run_dir, monkeypatch, module, package, convert):
    monkeypatch.setitem(sys.modules, module, None)  # import now raises ImportError
    with pytest.raises(PostError, match=re.escape(package)):
        convert(reader.Run(run_dir))


def test_nothing_else_imports_pandas(run_dir):
    """Reading and plotting run on numpy alone: no module of the package imports pandas or xarray."""
    code = f"""
import sys
import matplotlib
matplotlib.use("Agg")
from mpmshock_post import (cli, compare, field, hist, labels, local, probes, reader, regions, stats, style,
                           timeseries, units)
run = reader.Run({str(run_dir)!r})
run.regions(); run.probes(); run.conservation()
timeseries.plot_means(run); probes.plot_probes([run]); field.plot_field(run.snapshot())
hist.plot_histograms([run.snapshot()], "B800"); compare.plot_compare([run, run])
loaded = [name for name in ("pandas", "xarray") if name in sys.modules]
assert not loaded, f"imported {{loaded}}"
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=str(SCRIPTS)))
    assert done.returncode == 0, done.stderr


def test_one_version_number():
    text = (SCRIPTS / "mpmshock_post/_version.py").read_text()
    assert re.search(r'^__version__ = "0\.2\.0"$', text, re.M), text
    assert mpmshock_post.__version__ == "0.2.0"
    with open(SCRIPTS / "pyproject.toml", "rb") as f:
        project = tomllib.load(f)
    assert "version" not in project["project"] and project["project"]["dynamic"] == ["version"]
    assert project["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "mpmshock_post._version.__version__"}
    config = pytest.importorskip("setuptools.config.pyprojecttoml")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # setuptools calls [tool.setuptools] in pyproject.toml beta
        resolved = config.read_configuration(SCRIPTS / "pyproject.toml")
    assert resolved["project"]["version"] == mpmshock_post.__version__


def test_docs_say_no_sys_path():
    """The package docs send users to an installed package or PYTHONPATH, not to sys.path.insert."""
    for path in (SCRIPTS / "mpmshock_post/__init__.py", ROOT / "docs/postprocessing.md"):
        text = path.read_text()
        assert "sys.path.insert" not in text and "start Python in scripts" not in text, path
        assert "PYTHONPATH" in text, path
