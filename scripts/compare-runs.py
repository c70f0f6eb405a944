#!/usr/bin/python3
"""Compares two mpmshock run directories bit for bit.

    scripts/compare-runs.py RUN_A RUN_B [--tolerance REL]

Compared: regions.csv, conservation.csv, voids.csv and scene.txt as text; every dataset of every
snapshot_NNNNN.h5 (under /particles, /restart and /grid) value by value; the file attributes time,
step and particle_count. Not compared: summary.json and the attributes that name the program
version, which differ between builds by design. With --tolerance, numbers may differ by that much
relative (for runs made on different machines, where fused multiply-adds change the last bits).

Exit 0 when the runs agree, 1 with one line per difference otherwise, 2 on bad arguments.
"""

import argparse
import math
import sys
from pathlib import Path

import h5py
import numpy as np

TEXT_FILES = ["regions.csv", "conservation.csv", "voids.csv", "scene.txt"]
SKIPPED_ATTRIBUTES = {"mpmshock_version", "scene"}  # the scene differs only in output_dir


def csv_differences(a, b, name, tolerance):
    lines_a = a.read_text().splitlines()
    lines_b = b.read_text().splitlines()
    if len(lines_a) != len(lines_b):
        return [f"{name}: {len(lines_a)} lines against {len(lines_b)}"]
    out = []
    for k, (la, lb) in enumerate(zip(lines_a, lines_b)):
        if la == lb:
            continue
        if name == "scene.txt" and la.startswith("output_dir") and lb.startswith("output_dir"):
            continue
        if tolerance > 0 and not cells_close(la, lb, tolerance):
            out.append(f"{name}:{k + 1}: '{la}' against '{lb}'")
        elif tolerance == 0:
            out.append(f"{name}:{k + 1}: '{la}' against '{lb}'")
        if len(out) >= 5:
            out.append(f"{name}: (further differences not listed)")
            break
    return out


def cells_close(la, lb, tolerance):
    ca, cb = la.split(","), lb.split(",")
    if len(ca) != len(cb):
        return False
    for x, y in zip(ca, cb):
        if x == y:
            continue
        try:
            fx, fy = float(x), float(y)
        except ValueError:
            return False
        if math.isnan(fx) and math.isnan(fy):
            continue
        if abs(fx - fy) > tolerance * max(abs(fx), abs(fy), 1e-300):
            return False
    return True


def dataset_differences(fa, fb, path, tolerance):
    out = []

    def visit(name, obj):
        if not isinstance(obj, h5py.Dataset):
            return
        full = f"{path}:/{name}"
        if name not in fb:
            out.append(f"{full}: missing in the second run")
            return
        va, vb = obj[()], fb[name][()]
        if va.shape != vb.shape:
            out.append(f"{full}: shape {va.shape} against {vb.shape}")
            return
        if tolerance > 0 and np.issubdtype(va.dtype, np.floating):
            same = np.isclose(va, vb, rtol=tolerance, atol=0.0, equal_nan=True)
        else:
            same = (va.view(np.uint8) == vb.view(np.uint8)) if va.dtype == vb.dtype else np.zeros(1, bool)
        if not np.all(same):
            out.append(f"{full}: {int(np.size(same) - np.count_nonzero(same))} values differ")

    fa.visititems(visit)
    for name in fb:
        if name not in fa:
            out.append(f"{path}:/{name}: missing in the first run")
    for key in ("time", "step", "particle_count"):
        if fa.attrs.get(key) != fb.attrs.get(key):
            out.append(f"{path}: attribute {key} {fa.attrs.get(key)} against {fb.attrs.get(key)}")
    return out


def compare(run_a, run_b, tolerance):
    out = []
    for name in TEXT_FILES:
        a, b = run_a / name, run_b / name
        if a.exists() != b.exists():
            out.append(f"{name}: exists in only one run")
        elif a.exists():
            out += csv_differences(a, b, name, tolerance)
    snaps_a = sorted(p.name for p in run_a.glob("snapshot_*.h5"))
    snaps_b = sorted(p.name for p in run_b.glob("snapshot_*.h5"))
    if snaps_a != snaps_b:
        out.append(f"snapshots: {snaps_a} against {snaps_b}")
    for name in sorted(set(snaps_a) & set(snaps_b)):
        with h5py.File(run_a / name, "r") as fa, h5py.File(run_b / name, "r") as fb:
            out += dataset_differences(fa, fb, name, tolerance)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_a", type=Path)
    parser.add_argument("run_b", type=Path)
    parser.add_argument("--tolerance", type=float, default=0.0, help="relative tolerance; 0 means bit for bit")
    args = parser.parse_args()
    for d in (args.run_a, args.run_b):
        if not d.is_dir():
            print(f"compare-runs: {d} is not a run directory", file=sys.stderr)
            return 2
    differences = compare(args.run_a, args.run_b, args.tolerance)
    for line in differences:
        print(line)
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
