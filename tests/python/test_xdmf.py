"""The XDMF index of a run, continued by a restart: well-formed XML, one time step per snapshot
with the snapshot's time, and every HDF5 dataset it names exists with the shape it states
(hyperslabs within bounds).

    python3 -m pytest tests/python/test_xdmf.py [--mpmshock BUILD/src/mpmshock]
"""
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py

failures = []


def fail(message):
    failures.append(message)
    print("FAILED:", message, file=sys.stderr)


def dims(text):
    return tuple(int(d) for d in text.split())


def check_data_item(item, run_dir, context):
    """Checks one DataItem (recursing into hyperslabs and functions); returns its dimensions."""
    stated = dims(item.get("Dimensions", ""))
    kind = item.get("ItemType", "Uniform")
    if kind == "HyperSlab":
        spec, source = list(item)
        start_stride_count = [int(v) for v in spec.text.split()]
        rank = len(start_stride_count) // 3
        start, stride, count = (start_stride_count[k * rank:(k + 1) * rank] for k in range(3))
        shape = check_data_item(source, run_dir, context)
        if tuple(count) != stated:
            fail(f"{context}: hyperslab count {count} != Dimensions {stated}")
        for axis in range(rank):
            last = start[axis] + stride[axis] * (count[axis] - 1)
            if not 0 <= last < shape[axis]:
                fail(f"{context}: hyperslab reaches index {last} of axis {axis} of a {shape} dataset")
        return stated
    if kind == "Function":
        # JOIN($0, ..., $k) interlaces k + 1 terms of equal size: the stated size is (k + 1) times that.
        terms = item.get("Function").count(",") + 1
        sizes = {math.prod(check_data_item(child, run_dir, context)) for child in item}
        if len(sizes) != 1 or terms * sizes.pop() != math.prod(stated):
            fail(f"{context}: function {item.get('Function')} of Dimensions {stated} does not fit its arguments")
        return stated
    if item.get("Format") == "XML":
        values = item.text.split()
        if len(values) != math.prod(stated):
            fail(f"{context}: inline data has {len(values)} values for Dimensions {stated}")
        return stated
    if item.get("Format") != "HDF":
        fail(f"{context}: unexpected DataItem format {item.get('Format')}")
        return stated
    file_name, dataset = item.text.strip().split(":", 1)
    path = os.path.join(run_dir, file_name)
    if not os.path.exists(path):
        fail(f"{context}: {file_name} does not exist")
        return stated
    with h5py.File(path, "r") as f:
        if dataset not in f:
            fail(f"{context}: {file_name} has no dataset {dataset}")
            return stated
        shape = f[dataset].shape
        if shape != stated:
            fail(f"{context}: {file_name}:{dataset} has shape {shape}, the XDMF states {stated}")
        precision = int(item.get("Precision", "4"))
        if f[dataset].dtype.itemsize != precision:
            fail(f"{context}: {dataset} has {f[dataset].dtype.itemsize}-byte values, the XDMF states {precision}")
    return shape


def test_xdmf_of_a_restarted_run(mpmshock, tiny_scene, tmp_path):
    binary, scene = mpmshock, tiny_scene
    failures.clear()
    if True:
        run_dir = str(tmp_path / "run")
        subprocess.run([binary, scene, "--quiet", "--set", "output_dir=" + run_dir, "--set", "snapshot_grid=on",
                        "--set", "end_time=40ns", "--set", "snapshot_interval=20ns"], check=True,
                       stdout=subprocess.DEVNULL)
        # Continued by a restart, whose index must keep listing the earlier snapshots and grids.
        subprocess.run([binary, "--restart", os.path.join(run_dir, "snapshot_00002.h5"), "--quiet",
                        "--set", "end_time=60ns"], check=True, stdout=subprocess.DEVNULL)
        tree = ET.parse(os.path.join(run_dir, "snapshots.xdmf"))  # raises on malformed XML
        root = tree.getroot()
        collections = root.findall("./Domain/Grid")
        names = [c.get("Name") for c in collections]
        if names != ["particles", "grid"]:
            fail(f"top-level grids {names}, expected particles and grid")
        snapshots = sorted(n for n in os.listdir(run_dir) if n.startswith("snapshot_") and n.endswith(".h5"))
        for collection in collections:
            steps = collection.findall("Grid")
            if [s.get("Name").split()[0] for s in steps] != snapshots:
                fail(f"{collection.get('Name')}: time steps {[s.get('Name') for s in steps]} != files {snapshots}")
            times = [float(s.find("Time").get("Value")) for s in steps]
            if times != sorted(times):
                fail(f"{collection.get('Name')}: times not increasing: {times}")
            for step, time in zip(steps, times):
                file_name = step.get("Name").split()[0]
                with h5py.File(os.path.join(run_dir, file_name), "r") as f:
                    if abs(f.attrs["time"] - time) > 1e-15:
                        fail(f"{file_name}: XDMF time {time} != snapshot time {f.attrs['time']}")
                    count = int(f.attrs["particle_count"])
                topology = step.find("Topology")
                if collection.get("Name") == "particles" and int(topology.get("NumberOfElements")) != count:
                    fail(f"{file_name}: Polyvertex of {topology.get('NumberOfElements')} points, file has {count}")
                geometry_items = step.find("Geometry").findall("DataItem")
                for k, item in enumerate(geometry_items):
                    check_data_item(item, run_dir, f"{file_name} geometry item {k}")
                attributes = step.findall("Attribute")
                if collection.get("Name") == "particles" and len(attributes) < 14:
                    fail(f"{file_name}: only {len(attributes)} point fields listed")
                for attribute in attributes:
                    kind = attribute.get("AttributeType")
                    shape = check_data_item(attribute.find("DataItem"), run_dir,
                                            f"{file_name} attribute {attribute.get('Name')}")
                    components = {"Scalar": (), "Vector": (3,), "Tensor": (3, 3), "Matrix": (4,)}[kind]
                    if tuple(shape[len(shape) - len(components):]) != components:
                        fail(f"{file_name} {attribute.get('Name')}: {kind} with shape {shape}")
    assert not failures, f"{len(failures)} check(s) failed:\n" + "\n".join(failures)
