"""Opens a run's snapshots.xdmf with ParaView's own reader and checks that every time step and
field arrives with the values of the HDF5 files. Needs ParaView (Debian: paraview, python3-paraview);
not part of CTest, which checks the XDMF's structure without ParaView.

usage: pvpython --force-offscreen-rendering scripts/check-xdmf-in-paraview.py RUN_DIR
"""
import os
import sys

import h5py
import numpy as np
from paraview import servermanager as sm
from paraview.simple import XDMFReader
from vtk.numpy_interface import dataset_adapter as dsa

run = sys.argv[1]
reader = XDMFReader(FileNames=[os.path.join(run, "snapshots.xdmf")])
times = list(reader.TimestepValues)
files = sorted(f for f in os.listdir(run) if f.startswith("snapshot_") and f.endswith(".h5"))
problems = []
if len(times) != len(files):
    problems.append(f"{len(times)} time steps for {len(files)} snapshot files")


def leaves(d):
    if d.IsA("vtkMultiBlockDataSet"):
        for i in range(d.GetNumberOfBlocks()):
            yield from leaves(d.GetBlock(i))
    else:
        yield d


for time, name in zip(times, files):
    reader.UpdatePipeline(time)
    with h5py.File(os.path.join(run, name), "r") as f:
        if abs(f.attrs["time"] - time) > 1e-15:
            problems.append(f"{name}: time {time} in ParaView, {f.attrs['time']} in the file")
        for leaf in leaves(sm.Fetch(reader)):
            w = dsa.WrapDataObject(leaf)
            if leaf.GetClassName() == "vtkUnstructuredGrid":
                p = f["particles"]
                expect = {
                    "position": (np.asarray(w.Points)[:, :2], p["position"][:]),
                    "velocity": (np.asarray(w.PointData["velocity"])[:, :2], p["velocity"][:]),
                    "stress": (np.asarray(w.PointData["stress"]).reshape(-1, 9), p["stress"][:].reshape(-1, 9)),
                    "deformation_gradient": (np.asarray(w.PointData["deformation_gradient"]),
                                             p["deformation_gradient"][:].reshape(-1, 4)),
                    "velocity_gradient": (np.asarray(w.PointData["velocity_gradient"]),
                                          p["velocity_gradient"][:].reshape(-1, 4)),
                }
                for field in ("density", "pressure", "temperature", "internal_energy", "plastic_strain",
                              "viscous_pressure", "mass", "volume", "id", "body"):
                    expect[field] = (np.asarray(w.PointData[field]), p[field][:])
                if np.abs(np.asarray(w.PointData["velocity"])[:, 2]).max() != 0:
                    problems.append(f"{name}: velocity z is not zero")
            else:
                g = f["grid"]
                ny, nx = g["mass"].shape
                if tuple(leaf.GetDimensions()) != (nx, ny, 1):
                    problems.append(f"{name}: grid dimensions {leaf.GetDimensions()} != {(nx, ny, 1)}")
                velocity = np.stack([g["velocity_x"][:].ravel(), g["velocity_y"][:].ravel()], axis=1)
                expect = {"grid mass": (np.asarray(w.PointData["mass"]), g["mass"][:].ravel()),
                          "grid velocity": (np.asarray(w.PointData["velocity"])[:, :2], velocity)}
                origin = leaf.GetPoint(0)
                if abs(origin[1] - g.attrs["origin"][1]) > 1e-9:
                    problems.append(f"{name}: grid origin {origin} != {g.attrs['origin']}")
            for field, (seen, stored) in expect.items():
                if seen.shape != stored.shape:
                    problems.append(f"{name} {field}: shape {seen.shape} in ParaView, {stored.shape} in the file")
                elif not np.array_equal(seen, stored, equal_nan=True):
                    # ParaView keeps point coordinates in single precision.
                    tolerance = 1e-6 * np.abs(stored).max() if field == "position" else 0.0
                    if np.abs(seen - stored).max() > tolerance:
                        problems.append(f"{name} {field}: values differ by up to {np.abs(seen - stored).max()}")
    print(f"{name}: t = {time:.4g} s checked")

if problems:
    print("\n".join(problems))
    sys.exit(1)
print(f"ParaView reads all {len(files)} snapshots with every field as stored")
