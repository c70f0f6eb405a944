"""The post-processing tools on a tiny 3D run (dimension = 3, a column periodic in x and z): the
reader gives N x 3 positions and voids with z, the field plot draws the slice of points at a plane
of constant z (and refuses --slice for a 2D run), every other mpmshock-plot kind works, and the
XDMF index names datasets that exist with the dimensions it states.

    python3 -m pytest tests/python/test_3d_post.py [--mpmshock BUILD/src/mpmshock]
"""

import argparse
import contextlib
import csv
import io
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

import test_xdmf
from conftest import SCRIPTS, simulate
from mpmshock_post import PostError, cli, reader
from mpmshock_post.field import default_slice_z, plot_field, slice_points

PLOT = SCRIPTS / "mpmshock-plot"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

# A 60 x 100 x 60 um target hit by its mirror image: 4790 points, 56 spheres, half a second.
WIDTH, DEPTH, HEIGHT, CELL, PPC = 60e-6, 60e-6, 100e-6, 10e-6, 2
SPACING = CELL / PPC
SCENE_3D = f"""\
dimension = 3
velocity = 1000 m/s
porosity = 1.2
void_radius = 8 um
width = {WIDTH * 1e6:g} um
depth = {DEPTH * 1e6:g} um
target_height = {HEIGHT * 1e6:g} um
flyer_height = {HEIGHT * 1e6:g} um
cell_size = {CELL * 1e6:g} um
particles_per_cell = {PPC}
end_time = 30 ns
sample_interval = 5 ns
snapshot_interval = 15 ns
snapshot_grid = on
region.L50 = bottom 0 um 50 um
region.T30 = top 30 um
region.IMPACT = band -20 um 20 um
probe.free_surface = surface
probe.p1 = point 30um 50um 30um
output_dir = unused
"""


def plot(*args, in_process=False):
    """mpmshock-plot ARGS through the script (a fresh interpreter), or in this process (faster:
    matplotlib is imported once), with the same exit status, stdout and stderr."""
    if not in_process:
        return subprocess.run([sys.executable, str(PLOT)] + [str(a) for a in args], capture_output=True, text=True)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            status = cli.main([str(a) for a in args])
        except SystemExit as e:  # usage errors
            status = e.code
    return subprocess.CompletedProcess(args, status, out.getvalue(), err.getvalue())


def expect_image(args, path, magic=PNG_MAGIC, in_process=True):
    done = plot(*args, in_process=in_process)
    assert done.returncode == 0, f"mpmshock-plot {' '.join(map(str, args))}: exit {done.returncode}\n{done.stderr}"
    data = path.read_bytes()
    assert data.startswith(magic) and len(data) > 1024, f"{path}: not an image of {magic!r}"
    return done


def expect_error(args, *patterns, status=1, in_process=True):
    done = plot(*args, in_process=in_process)
    assert done.returncode == status, f"mpmshock-plot {' '.join(map(str, args))}: exit {done.returncode}, " \
                                      f"expected {status}\n{done.stdout}{done.stderr}"
    for pattern in patterns:
        assert pattern in done.stderr, f"mpmshock-plot {' '.join(map(str, args))}: no '{pattern}' in: {done.stderr}"
    assert "Traceback" not in done.stderr, done.stderr
    return done


def numpy_slab(position, z0, depth=DEPTH, spacing=SPACING):
    """The points with z0 - a/2 <= z < z0 + a/2, z periodic with period `depth`."""
    dz = (position[:, 2] - z0 + depth / 2) % depth - depth / 2
    return (dz >= -spacing / 2) & (dz < spacing / 2)


@pytest.fixture(scope="module")
def runs(mpmshock, tiny_scene, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("post3d")
    scene = tmp / "tiny_3d.scene"
    scene.write_text(SCENE_3D)
    context = argparse.Namespace(tmp=tmp, scene=str(scene), run=tmp / "run3d", run2d=tmp / "run2d")
    simulate(mpmshock, context.scene, context.run)
    simulate(mpmshock, tiny_scene, context.run2d, "end_time=20ns", "snapshot_interval=10ns", "region.T30=top 30um")
    return context


# --- the reader -------------------------------------------------------------------------------------

def test_reader_3d(runs):
    run = reader.Run(runs.run)
    summary = run.summary()
    assert run.dimension == 3 and summary["dimension"] == 3
    assert run.scene.depth == pytest.approx(DEPTH, rel=1e-12) and run.scene.point_spacing == pytest.approx(SPACING)
    assert [info.index for info in run.snapshots()] == [0, 1, 2]
    for snapshot in (run.snapshot(0), run.snapshot()):
        n = snapshot.particle_count
        assert snapshot.dimension == 3
        assert n == summary["material_points"] * (2 if summary["symmetry"] else 1)
        assert snapshot["position"].shape == (n, 3) and snapshot["velocity"].shape == (n, 3)
        for name in ("stress", "deformation_gradient", "velocity_gradient"):
            assert snapshot[name].shape == (n, 3, 3), f"{name}: {snapshot[name].shape}"
        assert snapshot["density"].shape == (n,)
        z = snapshot["position"][:, 2]
        assert z.min() >= 0.0 and z.max() < DEPTH, f"z from {z.min()} to {z.max()} m, depth {DEPTH} m"
    # Whole, not per metre: the initial volumes add up to the plates' volume over the porosity.
    first = run.snapshot(0)
    plates = WIDTH * DEPTH * 2 * HEIGHT
    assert first["volume"].sum() == pytest.approx(plates / summary["porosity"], rel=1e-6)
    voids = run.voids()
    assert list(voids) == ["body", "x", "y", "z", "radius"]
    assert len(voids["radius"]) == summary["voids"] > 0
    assert np.all((voids["z"] >= 0) & (voids["z"] < DEPTH)), voids["z"]
    assert set(voids["body"]) == {"flyer", "target"}
    conservation = run.conservation()
    assert "momentum_z" in conservation and len(conservation["momentum_z"]) == len(conservation["time"])
    # 2D is unchanged: dimension 2, N x 2, voids without z.
    run2d = reader.Run(runs.run2d)
    assert run2d.dimension == 2 and run2d.snapshot().dimension == 2 and run2d.scene.depth is None
    assert run2d.snapshot()["position"].shape[1] == 2 and "z" not in run2d.voids()


def test_voids_are_the_holes_in_the_lattice(runs):
    """voids.csv's spheres, periodic in x and z, are exactly the lattice points missing at t = 0:
    the lattice (i + 1/2, j + 1/2, k + 1/2) a of each plate less the points within a radius of a
    centre of its body gives the snapshot's points."""
    run = reader.Run(runs.run)
    voids = run.voids()
    nx, ny, nz = (round(length / SPACING) for length in (WIDTH, HEIGHT, DEPTH))
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    cell = np.stack([(i.ravel() + 0.5) * SPACING, (j.ravel() + 0.5) * SPACING, (k.ravel() + 0.5) * SPACING], axis=1)
    expected = []
    for body, y0 in (("target", 0.0), ("flyer", -HEIGHT)):
        lattice = cell + [0.0, y0, 0.0]
        mine = voids["body"] == body
        keep = np.ones(len(lattice), dtype=bool)
        for x, y, z, r in zip(voids["x"][mine], voids["y"][mine], voids["z"][mine], voids["radius"][mine]):
            d = np.abs(lattice - [x, y, z])
            d[:, 0] = np.minimum(d[:, 0], WIDTH - d[:, 0])
            d[:, 2] = np.minimum(d[:, 2], DEPTH - d[:, 2])
            keep &= (d ** 2).sum(axis=1) >= r * r
        expected.append(lattice[keep])
    expected = np.concatenate(expected)
    got = run.snapshot(0)["position"]
    assert len(got) == len(expected), f"{len(got)} points at t = 0, the lattice less the spheres leaves {len(expected)}"
    as_set = {tuple(p) for p in np.round(expected / SPACING * 2).astype(int)}
    assert as_set == {tuple(p) for p in np.round(got / SPACING * 2).astype(int)}, \
        "the points at t = 0 are not the lattice less the spheres of voids.csv"


def test_region_stats_match_csv_3d(runs):
    """The 3D rotation, divergence and strain rate (and the rest) recomputed from the last snapshot
    equal regions.csv's row."""
    run = reader.Run(runs.run)
    snapshot = run.snapshot()
    for name, columns in run.regions().items():
        row = np.flatnonzero(np.isclose(columns["time"], snapshot.time, rtol=1e-9, atol=0))
        assert row.size == 1, f"no single {name} row at t = {snapshot.time} s"
        stats = reader.region_stats(snapshot, name)
        assert stats["count"] == columns["count"][row[0]] > 0, name
        for column, value in stats.items():
            written = columns[column][row[0]]
            base = column.rsplit("_", 1)[0]
            scale = max(abs(stats.get(base + "_mean", value)), stats.get(base + "_std", 0.0), abs(value))
            assert abs(value - written) <= 1e-9 * scale, f"{name} {column}: {value!r} from the snapshot, {written!r}"
    L = snapshot["velocity_gradient"]
    assert np.any(L[:, 2, :] != 0) or np.any(L[:, :, 2] != 0), "no z component in L: the 3D terms are untested"


# --- the field plot's slice -------------------------------------------------------------------------

def test_field_slice(runs):
    run = reader.Run(runs.run)
    snapshot = run.snapshot()
    position = snapshot["position"]
    z0 = 32.5e-6  # a plane of initial point centres, (k + 1/2) a
    out = runs.tmp / "slice.png"
    done = expect_image(["field", runs.run, "--slice", "z=32.5um", "--color", "pressure", "-o", out], out,
                        in_process=False)
    count = int(numpy_slab(position, z0).sum())
    assert 0 < count < len(position) / 5, f"{count} of {len(position)} points in a slab one point thick"
    assert f"slice z = 32.5 µm ± 2.5 µm" in done.stdout, done.stdout
    assert f": {count} of {len(position)} points" in done.stdout, f"expected {count} points:\n{done.stdout}"
    # The same plane in metres and in mm.
    for value in ("z=3.25e-5", "z=0.0325mm"):
        done = expect_image(["field", runs.run, "--slice", value, "-o", out], out)
        assert f": {count} of {len(position)} points" in done.stdout, f"--slice {value}:\n{done.stdout}"
    # The default: mid-depth (30 um, between two layers) moved to the layer above, 32.5 um.
    assert default_slice_z(snapshot) == pytest.approx(z0, abs=1e-12)
    done = expect_image(["field", runs.run, "-o", out], out)
    assert "slice z = 32.5 µm" in done.stdout and f": {count} of" in done.stdout, done.stdout

    # The API: the selection is the numpy one, only points near the plane, and the figure draws them.
    for z in (z0, 0.0, 20e-6, DEPTH):
        slab = slice_points(snapshot, z)
        assert np.array_equal(slab.inside, numpy_slab(position, z)), f"slice at z = {z}"
        dz = (position[slab.inside, 2] - z + DEPTH / 2) % DEPTH - DEPTH / 2
        assert np.all(np.abs(dz) <= SPACING / 2), f"a point {np.abs(dz).max()} m from the plane z = {z}"
    fig = plot_field(snapshot, color="density", slice_z=z0)
    drawn = fig.axes[0].collections[0].get_offsets()
    assert len(drawn) == count, f"the figure draws {len(drawn)} points, the slab holds {count}"
    assert np.allclose(np.sort(np.asarray(drawn)[:, 0]), np.sort(position[numpy_slab(position, z0), 0] * 1e6))
    # At t = 0 a slice on a layer is that whole layer and nothing else.
    first = run.snapshot(0)
    layer = np.isclose(first["position"][:, 2], z0, rtol=0, atol=1e-12)
    assert np.array_equal(slice_points(first, z0).inside, layer)


def test_field_slice_refused(runs):
    out = runs.tmp / "refused.png"
    expect_error(["field", runs.run2d, "--slice", "z=10um", "-o", out], "--slice", "2D run", "3D runs",
                 in_process=False)
    assert not out.exists()
    with pytest.raises(PostError, match="2D run"):
        slice_points(reader.Run(runs.run2d).snapshot(), 10e-6)
    expect_error(["field", runs.run, "--slice", "z=50", "-o", out], "outside the column", "z=30um")
    expect_error(["field", runs.run, "--slice", "x=10um", "-o", out], "z=VALUE", status=2)
    expect_error(["field", runs.run, "--slice", "z=ten", "-o", out], "length 'ten'", status=2)
    expect_error(["field", runs.run2d, "--color", "velocity_z", "-o", out], "velocity_z needs a 3D run")


def test_field_options_3d(runs):
    out = runs.tmp / "arrows.png"
    expect_image(["field", runs.run, "--time", "15ns", "--color", "speed", "--arrows", "--body", "target",
                  "--window", "0,60,0,100", "--slice", "z=2.5um", "-o", out], out)
    for color in ("velocity_z", "rot2", "temperature"):
        out = runs.tmp / f"field_{color}.png"
        expect_image(["field", runs.run, "--color", color, "--true-size", "-o", out], out)
    out = runs.tmp / "field.svg"
    expect_image(["field", runs.run, "-o", out], out, b"<?xml")
    # 2D field plots are unchanged: no slice line.
    out = runs.tmp / "field2d.png"
    done = expect_image(["field", runs.run2d, "-o", out], out)
    assert "slice" not in done.stdout, done.stdout


def test_other_kinds_3d(runs):
    for kind in ("timeseries", "std", "dissipation"):
        out = runs.tmp / f"{kind}.png"
        expect_image([kind, runs.run, "-o", out], out)
    out = runs.tmp / "hist.png"
    done = expect_image(["hist", runs.run, "--region", "L50", "--times", "15ns,30ns", "-o", out], out)
    assert sum(line.split()[1] == "velocity_y" for line in done.stdout.splitlines()[2:] if line.split()) == 2
    out = runs.tmp / "compare.png"
    expect_image(["compare", runs.run, runs.run2d, "--quantity", "density,pressure", "--regions", "T30", "-o", out],
                 out)
    out = runs.tmp / "probe.png"
    expect_image(["probe", runs.run, "-o", out], out)
    probes = reader.Run(runs.run).probes()
    assert set(probes) == {"free_surface", "p1"} and np.all(probes["p1"]["count"] == 1)


# --- the XDMF index ---------------------------------------------------------------------------------

def test_xdmf_3d(mpmshock, runs):
    """The index of a 3D run continued by a restart: an XYZ point cloud of N x 3 positions, vectors
    of 3 and tensors of 3 x 3 (or 9) components, and a 3D co-rectilinear grid of (nz, ny, nx) nodes
    matching /grid's attributes; every dataset it names exists with the dimensions it states."""
    run_dir = runs.tmp / "xdmf3d"
    simulate(mpmshock, runs.scene, run_dir)
    subprocess.run([mpmshock, "--restart", str(run_dir / "snapshot_00002.h5"), "--quiet", "--set", "end_time=45ns"],
                   check=True, stdout=subprocess.DEVNULL, env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))
    test_xdmf.failures.clear()
    root = ET.parse(run_dir / "snapshots.xdmf").getroot()
    collections = root.findall("./Domain/Grid")
    assert [c.get("Name") for c in collections] == ["particles", "grid"]
    files = sorted(p.name for p in run_dir.glob("snapshot_*.h5"))
    assert files == [f"snapshot_{i:05d}.h5" for i in range(4)], files
    components = {"Scalar": [()], "Vector": [(3,)], "Tensor": [(3, 3), (9,)]}
    for collection in collections:
        steps = collection.findall("Grid")
        assert [s.get("Name").split()[0] for s in steps] == files
        for step in steps:
            file_name = step.get("Name").split()[0]
            with h5py.File(run_dir / file_name, "r") as f:
                count = int(f.attrs["particle_count"])
                assert int(f.attrs["dimension"]) == 3
                nodes = tuple(int(n) for n in f["grid"].attrs["nodes"])
                origin, spacing = f["grid"].attrs["origin"], float(f["grid"].attrs["spacing"])
                grid_fields = sorted(f["grid"])
            context = f"{file_name} {collection.get('Name')}"
            topology = step.find("Topology")
            geometry = step.find("Geometry")
            items = geometry.findall("DataItem")
            if collection.get("Name") == "particles":
                assert topology.get("TopologyType") == "Polyvertex" and int(topology.get("NumberOfElements")) == count
                assert geometry.get("GeometryType") == "XYZ" and len(items) == 1
                assert test_xdmf.check_data_item(items[0], str(run_dir), context) == (count, 3)
                assert len(step.findall("Attribute")) >= 14
            else:
                assert grid_fields == ["mass", "velocity_x", "velocity_y", "velocity_z"], grid_fields
                nx, ny, nz = nodes
                assert topology.get("TopologyType") == "3DCoRectMesh"
                assert test_xdmf.dims(topology.get("Dimensions")) == (nz, ny, nx), (topology.get("Dimensions"), nodes)
                assert geometry.get("GeometryType") == "ORIGIN_DXDYDZ" and len(items) == 2
                stated_origin = [float(v) for v in items[0].text.split()]
                stated_spacing = [float(v) for v in items[1].text.split()]
                # x and z origins are both 0, so the origin reads the same in x, y, z or z, y, x order.
                assert sorted(stated_origin) == pytest.approx(sorted(origin), abs=1e-15)
                assert stated_spacing == pytest.approx([spacing] * 3, rel=1e-12)
            for attribute in step.findall("Attribute"):
                kind = attribute.get("AttributeType")
                shape = test_xdmf.check_data_item(attribute.find("DataItem"), str(run_dir),
                                                  f"{context} {attribute.get('Name')}")
                leading = (count,) if collection.get("Name") == "particles" else (nodes[2], nodes[1], nodes[0])
                assert any(tuple(shape) == leading + c for c in components[kind]), \
                    f"{context} {attribute.get('Name')}: {kind} of shape {shape}"
    assert not test_xdmf.failures, "\n".join(test_xdmf.failures)
    # The reader reads the restarted run's snapshots and finds the new one.
    run = reader.Run(run_dir)
    assert run.snapshot().time == pytest.approx(45e-9) and run.snapshot().dimension == 3
    with open(run_dir / "regions.csv", newline="") as f:
        assert next(csv.reader(f))[:2] == ["time", "region"]
