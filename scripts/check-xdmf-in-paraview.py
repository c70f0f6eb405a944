"""Opens a run's snapshots.xdmf with ParaView's own reader and checks that every time step and
field arrives with the values of the HDF5 files, in 2D and 3D (points, and the grid of a run with
snapshot_grid = on). Needs ParaView (Debian: python3-paraview); CTest's `paraview_xdmf` runs it on a
2D and a 3D run when pvpython is installed (tests/paraview_test.sh), and `test_xdmf` checks the
XDMF's structure without ParaView.

usage: pvpython --force-offscreen-rendering scripts/check-xdmf-in-paraview.py RUN_DIR [RUN_DIR ...]
"""
import os
import sys

import h5py
import numpy as np
from paraview import servermanager as sm
from paraview.simple import Delete, XDMFReader
from vtk.numpy_interface import dataset_adapter as dsa
from vtk.util.numpy_support import vtk_to_numpy

POINT_SCALARS = ("density", "pressure", "temperature", "internal_energy", "plastic_strain", "viscous_pressure",
                 "mass", "volume", "id", "body")
TENSORS = ("stress", "deformation_gradient", "velocity_gradient")   # row-major in file and XDMF alike


def leaves(d):
    if d.IsA("vtkMultiBlockDataSet"):
        for i in range(d.GetNumberOfBlocks()):
            yield from leaves(d.GetBlock(i))
    else:
        yield d


def rows(array, count):
    """An (N, k) view of a per-point array, whatever shape ParaView or h5py gives it."""
    return np.asarray(array).reshape(count, -1)


def point_fields(leaf, w, p, name, problems):
    count = p["position"].shape[0]
    dim = p["position"].shape[1]
    expect = {"position": (rows(w.Points, count)[:, :dim], p["position"][:]),
              "velocity": (rows(w.PointData["velocity"], count)[:, :dim], p["velocity"][:])}
    for field in TENSORS:
        # VTK's own components, in the file's (row-major) order ...
        raw = vtk_to_numpy(leaf.GetPointData().GetArray(field))
        expect[field] = (rows(raw, count), rows(p[field][:], count))
        if dim == 3:
            # ... and ParaView's numpy layer, which reads 9 components as column-major: the transpose
            # (docs/output-format.md tells users to swap the axes of F and L there).
            expect[f"{field} (numpy layer)"] = (rows(np.asarray(w.PointData[field]), count),
                                                rows(np.swapaxes(p[field][:], 1, 2), count))
    for field in POINT_SCALARS:
        expect[field] = (rows(w.PointData[field], count)[:, 0], p[field][:])
    if dim == 2 and np.abs(rows(w.PointData["velocity"], count)[:, 2]).max() != 0:
        problems.append(f"{name}: velocity z of a 2D run is not zero")
    return expect


def grid_fields(leaf, w, g, name, problems):
    dim = len(g.attrs["nodes"])
    nodes = tuple(int(n) for n in g.attrs["nodes"])
    want = nodes if dim == 3 else (nodes[0], nodes[1], 1)
    if tuple(leaf.GetDimensions()) != want:
        problems.append(f"{name}: grid dimensions {leaf.GetDimensions()} != {want}")
    components = ["velocity_x", "velocity_y"] + (["velocity_z"] if dim == 3 else [])
    velocity = np.stack([g[c][:].ravel() for c in components], axis=1)
    origin, stored = leaf.GetPoint(0), g.attrs["origin"]
    if any(abs(origin[a] - stored[a]) > 1e-9 for a in (range(3) if dim == 3 else (1,))):
        problems.append(f"{name}: grid origin {origin} != {tuple(stored)}")
    count = velocity.shape[0]
    return {"grid mass": (rows(w.PointData["mass"], count)[:, 0], g["mass"][:].ravel()),
            "grid velocity": (rows(w.PointData["velocity"], count)[:, :dim], velocity)}


def check(run):
    reader = XDMFReader(FileNames=[os.path.join(run, "snapshots.xdmf")])
    times = list(reader.TimestepValues)
    files = sorted(f for f in os.listdir(run) if f.startswith("snapshot_") and f.endswith(".h5"))
    problems = []
    if len(times) != len(files):
        problems.append(f"{run}: {len(times)} time steps for {len(files)} snapshot files")
    grids = 0
    for time, name in zip(times, files):
        reader.UpdatePipeline(time)
        with h5py.File(os.path.join(run, name), "r") as f:
            if abs(f.attrs["time"] - time) > 1e-15:
                problems.append(f"{name}: time {time} in ParaView, {f.attrs['time']} in the file")
            for leaf in leaves(sm.Fetch(reader)):
                w = dsa.WrapDataObject(leaf)
                if leaf.GetClassName() == "vtkUnstructuredGrid":
                    expect = point_fields(leaf, w, f["particles"], name, problems)
                else:
                    expect = grid_fields(leaf, w, f["grid"], name, problems)
                    grids += 1
                for field, (seen, stored) in expect.items():
                    if seen.shape != stored.shape:
                        problems.append(f"{name} {field}: shape {seen.shape} in ParaView, {stored.shape} in the file")
                    elif not np.array_equal(seen, stored, equal_nan=True):
                        # ParaView keeps point coordinates in single precision.
                        tolerance = 1e-6 * np.abs(stored).max() if field == "position" else 0.0
                        if np.abs(seen - stored).max() > tolerance:
                            problems.append(f"{name} {field}: values differ by up to {np.abs(seen - stored).max()}")
        print(f"{run}/{name}: t = {time:.4g} s checked")
    Delete(reader)
    return problems, len(files), grids


failed = False
for run in sys.argv[1:]:
    problems, snapshots, grids = check(run)
    if problems:
        print("\n".join(problems))
        failed = True
    else:
        print(f"ParaView reads all {snapshots} snapshots of {run} with every field as stored"
              + (f" ({grids} grids)" if grids else ""))
sys.exit(1 if failed or len(sys.argv) < 2 else 0)
