"""Reading an mpmshock run directory; everything stays in SI units.

    run = Run("output/paper_base")
    run.scene["porosity"]            # 1.03
    b800 = run.regions()["B800"]     # column -> numpy array, e.g. b800["pressure_mean"] in Pa
    surface = run.probes()["free_surface"]   # probes.csv: surface["velocity_y"] in m/s
    snap = run.snapshot(time=750e-9)
    rho = snap["density"]            # kg/m3, one value per material point
    region_stats(snap, "B800")       # the regions.csv row, recomputed from the snapshot
    run.dimension, snap.dimension    # 2 (plane strain) or 3 (a column periodic in x and z)

The CSV time series convert to pandas and xarray where those are installed (they are optional:
nothing else here imports them):

    run.regions().to_pandas()        # DataFrame: columns time, region, count, density_mean, ... (SI)
    run.regions().to_xarray()        # Dataset with dims (time, region); units in each variable's attrs
    run.probes().to_xarray()         # dims (time, probe)
    run.conservation().to_pandas()   # DataFrame indexed by time

A run made with `paper_temperature = on` holds the paper model's temperature beside the energy
model's; `PaperTemperatureRun(path)` reads it as a `temperature_model = paper` run reads, with the
paper model's numbers in the temperature columns and fields:

    paper = PaperTemperatureRun("output/paper_base")
    paper.regions()["B800"]["temperature_mean"]   # regions.csv paper_temperature_mean

In 3D (`dimension = 3`) positions and velocities are N x 3 (x, y, z), the deformation and velocity
gradients 3 x 3, extensive quantities whole (kg, m3) rather than per metre of depth, and voids()
has a z column (sphere centres); everything else reads as in 2D.

Snapshots are read lazily: opening one reads its attributes, and each dataset is read the first
time it is asked for. Datasets and groups the reader does not know are ignored, so files from a
newer simulator (restart data, grid fields) still read.
"""

import csv
import importlib
import io
import json
import re
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import NamedTuple

import h5py
import numpy as np

from .errors import PostError
from .local import local_quantity
from .regions import region_points, region_stats, target_top
from .scene import Scene
from .units import conservation_unit, csv_unit

__all__ = ["NamedSeries", "PaperTemperatureRun", "Run", "Snapshot", "SnapshotInfo", "TimeSeries",
           "has_paper_temperature", "local_quantity", "region_points", "region_stats", "target_top", "void_count"]

_SNAPSHOT_NAME = re.compile(r"^snapshot_(\d+)\.h5$")


def _text(value):
    """HDF5 string attributes come back as str or bytes depending on how they were written."""
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def _read_csv(path):
    """Header and rows (lists of strings) of a CSV file the simulator wrote.

    A run killed while it wrote a row leaves that last row cut short (no line end, or too few
    fields): it is dropped with a one-line note on stderr, never plotted as a number cut in half.
    """
    try:
        with open(path, newline="") as f:
            text = f.read()
    except FileNotFoundError:
        raise PostError(f"{path} not found (did the run start in this directory?)") from None
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        raise PostError(f"{path} is empty")
    header, body = rows[0], rows[1:]
    if body and (not text.endswith("\n") or len(body[-1]) != len(header)):
        print(f"mpmshock-plot: note: {path}: its last row is incomplete (a run stopped while writing it); "
              "it is left out", file=sys.stderr)
        body = body[:-1]
    for k, row in enumerate(body):
        if len(row) != len(header):
            raise PostError(f"{path}:{k + 2}: {len(row)} fields where the header has {len(header)}")
    return header, body


def _columns(path, header, rows, text_columns=(), int_columns=()):
    """Column name -> numpy array; text columns stay strings, counts become ints, the rest floats."""
    out = {}
    for i, name in enumerate(header):
        values = [row[i] for row in rows]
        if name in text_columns:
            out[name] = np.array(values, dtype=str)
            continue
        try:
            out[name] = np.array(values, dtype=int if name in int_columns else float)
        except ValueError:
            raise PostError(f"{path}: column '{name}' holds a value that is not a number") from None
    return out


def _optional_module(name, debian_package, wanted_by):
    """pandas or xarray, imported only when a conversion asks for it; a PostError naming the
    package to install where it is missing."""
    try:
        return importlib.import_module(name)
    except ImportError:
        raise PostError(f"{wanted_by} needs {name}, which is not installed: on Debian "
                        f"'sudo apt-get install {debian_package}' (for /usr/bin/python3), elsewhere "
                        f"'pip install {name}'; the reader itself needs only numpy") from None


def _known_units(columns, unit_of):
    """Column -> SI unit for the columns whose unit is known."""
    units = {name: unit_of(name) for name in columns}
    return {name: unit for name, unit in units.items() if unit is not None}


def _set_units(dataset, units):
    for name, unit in units.items():
        if name in dataset.variables:
            dataset[name].attrs["units"] = unit


class NamedSeries(dict):
    """regions.csv by region or probes.csv by probe: name -> {column -> array}, names in file
    order, SI units; a dict, with conversions to pandas and xarray.

    `key` is the name column ('region' or 'probe'), `units` column -> SI unit, `source` the CSV."""

    def __init__(self, series, key, units, source):
        super().__init__(series)
        self.key, self.units, self.source = key, dict(units), Path(source)

    def _quantities(self):
        """The numeric columns, in file order (all but time and the name column)."""
        first = next(iter(self.values()), {})
        return [column for column in first if column not in ("time", self.key)]

    def to_pandas(self):
        """A DataFrame as the CSV is laid out: one row per name per sample, ordered by time and then
        by name in file order, with the columns time, region (or probe) and the quantities in SI;
        df.attrs["units"] maps column -> unit."""
        pd = _optional_module("pandas", "python3-pandas", f"{type(self).__name__}.to_pandas()")
        columns = ["time", self.key, *self._quantities()]
        stacked = {column: np.concatenate([series[column] for series in self.values()]) if self else np.empty(0)
                   for column in columns}
        order = np.argsort(stacked["time"], kind="stable")  # stable: names stay in file order at each time
        frame = pd.DataFrame({column: values[order] for column, values in stacked.items()})
        frame.attrs["units"] = {column: self.units[column] for column in columns if column in self.units}
        return frame

    def to_xarray(self):
        """A Dataset with dims (time, region) or (time, probe): one variable per quantity, its SI
        unit in attrs["units"]. Times missing for a name (a row cut off at the end of a killed run)
        are NaN there, and then counts are floats."""
        xr = _optional_module("xarray", "python3-xarray", f"{type(self).__name__}.to_xarray()")
        names = list(self)
        times = np.unique(np.concatenate([series["time"] for series in self.values()])) if self else np.empty(0)
        data = {column: (("time", self.key), self._on_grid(column, times)) for column in self._quantities()}
        dataset = xr.Dataset(data, coords={"time": times, self.key: np.array(names, dtype=str)},
                             attrs={"source": str(self.source)})
        _set_units(dataset, self.units)
        return dataset

    def _on_grid(self, column, times):
        """The column as a (time, name) array on the shared times."""
        if all(len(series["time"]) == len(times) for series in self.values()):
            # every name at every time, as the simulator writes: the column keeps its type (ints for count)
            return np.stack([series[column] for series in self.values()], axis=1)
        table = np.full((len(times), len(self)), np.nan)
        for j, series in enumerate(self.values()):
            table[np.searchsorted(times, series["time"]), j] = series[column]
        return table


class TimeSeries(dict):
    """conservation.csv: column -> array, SI units (per metre of depth in 2D); a dict, with
    conversions to pandas and xarray indexed by time. `units`: column -> SI unit."""

    def __init__(self, columns, units, source):
        super().__init__(columns)
        self.units, self.source = dict(units), Path(source)

    def to_pandas(self):
        """A DataFrame indexed by time, one column per other column of the CSV; df.attrs["units"]
        maps column (and the index, 'time') -> unit."""
        pd = _optional_module("pandas", "python3-pandas", "TimeSeries.to_pandas()")
        frame = pd.DataFrame({column: values for column, values in self.items() if column != "time"},
                             index=pd.Index(self["time"], name="time"))
        frame.attrs["units"] = dict(self.units)
        return frame

    def to_xarray(self):
        """A Dataset with the dim time, one variable per other column, units in attrs["units"]."""
        xr = _optional_module("xarray", "python3-xarray", "TimeSeries.to_xarray()")
        dataset = xr.Dataset({column: ("time", values) for column, values in self.items() if column != "time"},
                             coords={"time": self["time"]}, attrs={"source": str(self.source)})
        _set_units(dataset, self.units)
        return dataset


def void_count(run_dir):
    """How many voids the run laid out at t = 0: the rows of its voids.csv; None without the file."""
    try:
        with open(Path(run_dir) / "voids.csv") as f:
            return max(0, sum(1 for line in f if line.strip()) - 1)
    except OSError:
        return None


class Fields(Mapping):
    """The /particles datasets of one snapshot, read on first access and then kept."""

    def __init__(self, path, datasets, aliases=None):
        self._path = path
        self._datasets = datasets  # name -> (shape, units, description)
        self._aliases = aliases or {}  # name shown -> dataset read
        self._cache = {}

    def __getitem__(self, name):
        if name not in self._datasets:
            raise PostError(f"{self._path} has no dataset /particles/{name} "
                            f"(it has: {', '.join(self._datasets)})")
        if name not in self._cache:
            with h5py.File(self._path, "r") as f:
                self._cache[name] = f["particles"][self._aliases.get(name, name)][()]
        return self._cache[name]

    def __iter__(self):
        return iter(self._datasets)

    def __len__(self):
        return len(self._datasets)

    def shape(self, name):
        return self._datasets[name][0]

    def units(self, name):
        return self._datasets[name][1]

    def description(self, name):
        return self._datasets[name][2]


class Snapshot:
    """One snapshot_NNNNN.h5: `time` (s), `step`, `index`, `scene`, and the point `fields`."""

    def __init__(self, path, aliases=None):
        """`aliases`: dataset name shown -> dataset read, e.g. {"temperature": "paper_temperature"}."""
        self.path = Path(path)
        aliases = aliases or {}
        try:
            with h5py.File(self.path, "r") as f:
                attrs = {key: f.attrs[key] for key in f.attrs}
                group = f.get("particles")
                if not isinstance(group, h5py.Group):
                    raise PostError(f"{self.path} has no /particles group")
                datasets = {name: (item.shape, _text(item.attrs.get("units", "")),
                                   _text(item.attrs.get("description", "")))
                            for name, item in group.items() if isinstance(item, h5py.Dataset)}
        except OSError as e:
            raise PostError(f"cannot read snapshot {self.path}: {e}") from None
        if "time" not in attrs:
            raise PostError(f"{self.path} has no 'time' attribute: not an mpmshock snapshot?")
        self.time = float(attrs["time"])
        self.step = int(attrs.get("step", -1))
        match = _SNAPSHOT_NAME.match(self.path.name)
        self.index = int(attrs.get("snapshot", match.group(1) if match else -1))
        self.attrs = {key: _text(v) if isinstance(v, (bytes, str)) else v for key, v in attrs.items()}
        self.scene = Scene(self.attrs["scene"], f"{self.path}:/scene") if "scene" in attrs else None
        for shown, stored in aliases.items():
            if stored not in datasets:
                raise PostError(f"{self.path} has no dataset /particles/{stored}")
            datasets[shown] = datasets[stored]
        self.fields = Fields(self.path, datasets, aliases)

    def __getitem__(self, name):
        return self.fields[name]

    @property
    def dimension(self):
        """2 or 3: the file's `dimension` attribute; for files without it, the columns of
        /particles/position (2 in the files written before 3D runs)."""
        if "dimension" in self.attrs:
            return int(self.attrs["dimension"])
        if "position" in self.fields and len(self.fields.shape("position")) == 2:
            return int(self.fields.shape("position")[1])
        return self.scene.dimension if self.scene is not None else 2

    @property
    def particle_count(self):
        if "particle_count" in self.attrs:
            return int(self.attrs["particle_count"])
        return len(self.fields["id"])

    def __repr__(self):
        return f"Snapshot({str(self.path)!r}, time={self.time:g} s, step={self.step})"


class SnapshotInfo(NamedTuple):
    index: int    # the NNNNN of snapshot_NNNNN.h5
    time: float   # s
    path: Path


class Run:
    """An mpmshock output directory: scene, region time series, probes, conservation, voids, snapshots."""

    def __init__(self, path):
        self.path = Path(path)
        if not self.path.is_dir():
            raise PostError(f"run directory '{path}' not found")
        scene_file = self.path / "scene.txt"
        if scene_file.is_file():
            self.scene = Scene(scene_file.read_text(), str(scene_file))
        else:  # scene.txt deleted or not yet copied along: every snapshot carries the scene too
            snapshots = self.snapshots()
            self.scene = Snapshot(snapshots[0].path).scene if snapshots else None
            if self.scene is None:
                raise PostError(f"'{path}' is not an mpmshock run directory: no scene.txt and no snapshot")

    @property
    def name(self):
        return self.path.resolve().name

    @property
    def dimension(self):
        """2 (plane strain) or 3 (a column periodic in x and z), from the scene."""
        return self.scene.dimension

    def _named_series(self, path, key):
        """NamedSeries of a CSV whose rows are (time, KEY, ...): KEY value -> columns."""
        header, rows = _read_csv(path)
        if header[:2] != ["time", key]:
            raise PostError(f"{path}: header should start with 'time,{key}', got '{','.join(header[:2])}'")
        names = list(dict.fromkeys(row[1] for row in rows))
        series = {name: _columns(path, header, [row for row in rows if row[1] == name], text_columns=(key,),
                                 int_columns=("count",))
                  for name in names}
        return NamedSeries(series, key, _known_units(header, csv_unit), path)

    def regions(self):
        """NamedSeries from regions.csv: region name -> {column -> array}, regions in file order,
        SI units; .to_pandas() and .to_xarray() convert it."""
        return self._named_series(self.path / "regions.csv", "region")

    def probes(self):
        """NamedSeries from probes.csv: probe name -> {column -> array} (time, count, x, y,
        velocity_x, velocity_y, pressure, density, temperature: means over the probe's points, SI
        units), probes in file order; .to_pandas() and .to_xarray() convert it."""
        path = self.path / "probes.csv"
        if not path.is_file() and not any(key.startswith("probe.") for key in self.scene):
            raise PostError(f"{self.path} has no probes.csv: the scene has no probe.NAME keys "
                            "(e.g. 'probe.free_surface = surface' or 'probe.p1 = point 20um 600um')")
        return self._named_series(path, "probe")

    def conservation(self):
        """TimeSeries from conservation.csv: column -> array (time, step, dt, mass, momenta,
        energies; per metre of depth in 2D); .to_pandas() and .to_xarray() convert it."""
        path = self.path / "conservation.csv"
        header, rows = _read_csv(path)
        units = _known_units(header, lambda column: conservation_unit(column, self.dimension))
        return TimeSeries(_columns(path, header, rows, int_columns=("step",)), units, path)

    def void_count(self):
        """How many voids the run laid out (rows of voids.csv); None without voids.csv."""
        return void_count(self.path)

    def voids(self):
        """Column -> array from voids.csv, the initial layout: body ('flyer'/'target'), x, y,
        radius (m) of each cylindrical void in 2D; body, x, y, z, radius of each sphere in 3D."""
        path = self.path / "voids.csv"
        header, rows = _read_csv(path)
        expected = ["body", "x", "y", "radius"] if self.dimension == 2 else ["body", "x", "y", "z", "radius"]
        missing = [name for name in expected if name not in header]
        if missing:
            raise PostError(f"{path}: no column {', '.join(missing)} (header '{','.join(header)}'; a "
                            f"{self.dimension}D run writes '{','.join(expected)}')")
        return _columns(path, header, rows, text_columns=("body",))

    def summary(self):
        """summary.json as a dict (exit_code, steps, material_points, porosity, errors, ...)."""
        path = self.path / "summary.json"
        try:
            return json.loads(path.read_text())
        except FileNotFoundError:
            raise PostError(f"{path} not found (the run has not finished?)") from None
        except json.JSONDecodeError as e:
            raise PostError(f"{path}: {e}") from None

    def snapshots(self):
        """SnapshotInfo of every snapshot_NNNNN.h5, by index; .tmp and .xdmf files are skipped."""
        found = []
        for path in self.path.iterdir():
            match = _SNAPSHOT_NAME.match(path.name)
            if match:
                try:
                    with h5py.File(path, "r") as f:
                        time = float(f.attrs["time"])
                except (OSError, KeyError) as e:
                    raise PostError(f"cannot read the time of snapshot {path}: {e}") from None
                found.append(SnapshotInfo(int(match.group(1)), time, path))
        return sorted(found)

    def _open_snapshot(self, path):
        return Snapshot(path)

    def snapshot(self, index=None, time=None):
        """The snapshot with file number `index` (negative: from the end; default the last), or the
        one nearest `time` (s), which must lie within a tenth of the snapshot spacing."""
        infos = self.snapshots()
        if not infos:
            raise PostError(f"no snapshot_*.h5 in {self.path}")
        if time is not None:
            return self._open_snapshot(self._nearest(infos, time).path)
        if index is None or index < 0:
            position = -1 if index is None else index
            if -position > len(infos):
                raise PostError(f"{self.path} has only {len(infos)} snapshots, cannot take index {index}")
            return self._open_snapshot(infos[position].path)
        for info in infos:
            if info.index == index:
                return self._open_snapshot(info.path)
        raise PostError(f"{self.path} has no snapshot {index} (it has {infos[0].index} to {infos[-1].index})")

    def _nearest(self, infos, time):
        times = np.array([info.time for info in infos])
        nearest = int(np.argmin(np.abs(times - time)))
        spacing = np.median(np.diff(times)) if len(times) > 1 else abs(times[0])
        if abs(times[nearest] - time) > 0.1 * spacing + 1e-15:
            listed = ", ".join(f"{t * 1e9:g}" for t in times)
            raise PostError(f"no snapshot near t = {time * 1e9:g} ns in {self.path} (snapshots at {listed} ns)")
        return infos[nearest]

    def __repr__(self):
        return f"Run({str(self.path)!r})"


_PAPER_COLUMNS = {"temperature_mean": "paper_temperature_mean", "temperature_std": "paper_temperature_std",
                  "temperature": "paper_temperature"}


def has_paper_temperature(path):
    """Whether the run directory's regions.csv carries the paper model's temperature
    (paper_temperature = on)."""
    try:
        with open(Path(path) / "regions.csv") as f:
            return "paper_temperature_mean" in f.readline().strip().split(",")
    except OSError:
        return False


class PaperTemperatureRun(Run):
    """A run made with `paper_temperature = on`, read with the paper model's temperature
    (T_H(V) + W_p / c_v) in place of the energy model's: regions.csv's temperature_mean and _std,
    probes.csv's temperature and the snapshots' temperature are its paper_temperature columns and
    field. Every other column and field is the run's own: the dynamics do not depend on the model."""

    def __init__(self, path):
        super().__init__(path)
        if not has_paper_temperature(self.path):
            raise PostError(f"{self.path}/regions.csv has no paper_temperature_mean column: the run was not made "
                            "with paper_temperature = on")

    @staticmethod
    def _swapped(series):
        out = dict(series)
        for shown, stored in _PAPER_COLUMNS.items():
            if stored in series:
                out[shown] = series[stored]
        return out

    @staticmethod
    def _swapped_all(named):
        return NamedSeries({name: PaperTemperatureRun._swapped(series) for name, series in named.items()},
                           named.key, named.units, named.source)

    def regions(self):
        return self._swapped_all(super().regions())

    def probes(self):
        return self._swapped_all(super().probes())

    def _open_snapshot(self, path):
        return Snapshot(path, aliases={"temperature": "paper_temperature"})

    def __repr__(self):
        return f"PaperTemperatureRun({str(self.path)!r})"
