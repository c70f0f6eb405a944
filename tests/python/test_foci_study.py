"""studies/foci/foci-study: one row per variant from the run's snapshots (extremes over the whole
run), a finished run reused when its scene.txt matches the request, and a request that changed
(another snapshot interval) run again. The column is cut to 10 um cells and 10 ns to take seconds."""

import os
import subprocess
import sys

from conftest import STUDIES

STUDY = STUDIES / "foci" / "foci-study"


def table(out, *args):
    done = subprocess.run([sys.executable, str(STUDY), "--out", str(out), *args], capture_output=True, text=True,
                          env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"), check=True)
    return [line for line in done.stdout.splitlines() if line.startswith("| short |")]


def test_rows_and_reuse(mpmshock, tmp_path):
    variant = "short:cell_size=10um,end_time=10ns"
    rows = table(tmp_path, variant)
    assert len(rows) == 1
    cells = [c.strip() for c in rows[0].strip("|").split("|")]
    steps = int(cells[1])
    assert steps > 10
    low, high = (float(x) for x in cells[2].split()[0].split(".."))
    assert low <= 0.0 < high  # the points' pressures over the run: the shock's and the release's
    assert float(cells[4].split()[0]) >= 0.0
    assert float(cells[5].split()[0]) > 0.9  # |v_y| at least the impact speed, km/s
    snapshot = tmp_path / "short" / "snapshot_00000.h5"
    stamp = snapshot.stat().st_mtime_ns
    assert table(tmp_path, variant) == rows  # the same request: reused, not run again
    assert snapshot.stat().st_mtime_ns == stamp
    table(tmp_path, "--snapshots", "2.5", variant)  # another request: run again
    assert snapshot.stat().st_mtime_ns != stamp
