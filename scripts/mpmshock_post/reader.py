"""Reading an mpmshock run directory; everything stays in SI units.

    run = Run("output/paper_base")
    run.scene["porosity"]            # 1.03
    b800 = run.regions()["B800"]     # column -> numpy array, e.g. b800["pressure_mean"] in Pa
    surface = run.probes()["free_surface"]   # probes.csv: surface["velocity_y"] in m/s
    snap = run.snapshot(time=750e-9)
    rho = snap["density"]            # kg/m3, one value per material point
    region_stats(snap, "B800")       # the regions.csv row, recomputed from the snapshot
    run.dimension, snap.dimension    # 2 (plane strain) or 3 (a column periodic in x and z)

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

__all__ = ["PaperTemperatureRun", "Run", "Snapshot", "SnapshotInfo", "has_paper_temperature", "local_quantity", "region_points", "region_stats", "target_top"]

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

    def regions(self):
        """Region name -> {column -> array} from regions.csv, regions in file order, SI units."""
        path = self.path / "regions.csv"
        header, rows = _read_csv(path)
        if header[:2] != ["time", "region"]:
            raise PostError(f"{path}: header should start with 'time,region', got '{','.join(header[:2])}'")
        names = list(dict.fromkeys(row[1] for row in rows))
        return {name: _columns(path, header, [row for row in rows if row[1] == name], text_columns=("region",),
                                 int_columns=("count",))
                for name in names}

    def probes(self):
        """Probe name -> {column -> array} from probes.csv (time, count, x, y, velocity_x,
        velocity_y, pressure, density, temperature: means over the probe's points, SI units),
        probes in file order."""
        path = self.path / "probes.csv"
        if not path.is_file() and not any(key.startswith("probe.") for key in self.scene):
            raise PostError(f"{self.path} has no probes.csv: the scene has no probe.NAME keys "
                            "(e.g. 'probe.free_surface = surface' or 'probe.p1 = point 20um 600um')")
        header, rows = _read_csv(path)
        if header[:2] != ["time", "probe"]:
            raise PostError(f"{path}: header should start with 'time,probe', got '{','.join(header[:2])}'")
        names = list(dict.fromkeys(row[1] for row in rows))
        return {name: _columns(path, header, [row for row in rows if row[1] == name], text_columns=("probe",),
                               int_columns=("count",))
                for name in names}

    def conservation(self):
        """Column -> array from conservation.csv (time, step, dt, mass, momenta, energies)."""
        path = self.path / "conservation.csv"
        return _columns(path, *_read_csv(path), int_columns=("step",))

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

    def regions(self):
        return {name: self._swapped(series) for name, series in super().regions().items()}

    def probes(self):
        return {name: self._swapped(series) for name, series in super().probes().items()}

    def _open_snapshot(self, path):
        return Snapshot(path, aliases={"temperature": "paper_temperature"})

    def __repr__(self):
        return f"PaperTemperatureRun({str(self.path)!r})"
