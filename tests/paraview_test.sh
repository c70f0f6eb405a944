#!/usr/bin/env bash
# ParaView reads what mpmshock writes: a small 2D and a small 3D run (with the grid) opened by
# ParaView's own XDMF reader, every field of every snapshot against the HDF5 files
# (scripts/check-xdmf-in-paraview.py). Registered only where pvpython is installed.
# usage: paraview_test.sh MPMSHOCK PVPYTHON SOURCE_DIR
set -euo pipefail
binary=$1
pvpython=$2
src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(--set "end_time=20 ns" --set "snapshot_interval=10 ns" --set snapshot_grid=on --set symmetry=off
        --set skip_unreached=off --quiet --force)
"$binary" "$src/configs/default.scene" --set output_dir="$work/run2d" --set cell_size=20um "${common[@]}"
"$binary" "$src/configs/default.scene" --set output_dir="$work/run3d" --set dimension=3 --set width=100um \
  --set depth=100um --set target_height=200um --set flyer_height=200um --set cell_size=20um --set porosity=1 "${common[@]}"
"$pvpython" --force-offscreen-rendering "$src/scripts/check-xdmf-in-paraview.py" "$work/run2d" "$work/run3d"
