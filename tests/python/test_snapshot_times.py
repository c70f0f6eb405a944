"""snapshot_times: snapshots at listed times, beside or instead of snapshot_interval.

    /usr/bin/python3 -m pytest tests/python/test_snapshot_times.py [--mpmshock BUILD/src/mpmshock]

A paper-scale run needs snapshots at a few times (the paper's 250, 750 and 1150 ns) and not every
50 ns (5 GB for the base case at 10 um cells). The tiny porous scene (tests/data) to 60 ns with
snapshot_interval = 0 and snapshot_times = 25 ns, 40 ns writes the first, the two listed and the
last; with an interval of 20 ns as well a time both name (40 ns) is one snapshot. A restart from
the 25 ns snapshot continues identically. Three runs of about a second.
"""

import shutil
import subprocess

import pytest

from conftest import simulate
from mpmshock_post.reader import Run


def snapshot_times_ns(run_dir):
    return [round(info.time * 1e9, 6) for info in Run(run_dir).snapshots()]


@pytest.fixture(scope="module")
def runs(mpmshock, tiny_scene, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("snapshot_times")
    listed, both = tmp / "listed", tmp / "both"
    simulate(mpmshock, tiny_scene, listed, "snapshot_interval=0", "snapshot_times=25 ns, 40ns")
    simulate(mpmshock, tiny_scene, both, "snapshot_interval=20ns", "snapshot_times=25 ns, 40ns")
    return dict(tmp=tmp, listed=listed, both=both)


def test_listed_times(runs):
    assert snapshot_times_ns(runs["listed"]) == [0.0, 25.0, 40.0, 60.0]
    assert "snapshot_times = 2.5e-08 s, 4e-08 s" in (runs["listed"] / "scene.txt").read_text()


def test_listed_beside_interval(runs):
    assert snapshot_times_ns(runs["both"]) == [0.0, 20.0, 25.0, 40.0, 60.0]


def test_restart_from_a_listed_snapshot(runs, mpmshock):
    restarted = runs["tmp"] / "restarted"
    shutil.copytree(runs["listed"], restarted)
    done = subprocess.run([mpmshock, "--restart", str(restarted / "snapshot_00001.h5"), "--force", "--quiet"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert (restarted / "regions.csv").read_bytes() == (runs["listed"] / "regions.csv").read_bytes()
    assert snapshot_times_ns(restarted) == [0.0, 25.0, 40.0, 60.0]


@pytest.mark.parametrize("value, words", [("40 ns, 25 ns", "must increase"), ("25 ns, 0 s", "must be > 0"),
                                          ("25 ns, fast", "'fast'")])
def test_bad_lists(runs, mpmshock, tiny_scene, value, words):
    scene = runs["tmp"] / "bad.scene"
    text = open(tiny_scene).read()
    scene.write_text(text + f"snapshot_times = {value}\n")
    line = len(text.splitlines()) + 1
    done = subprocess.run([mpmshock, str(scene), "--check"], capture_output=True, text=True)
    assert done.returncode == 2
    assert f"bad.scene:{line}" in done.stderr and "snapshot_times" in done.stderr and words in done.stderr


def test_times_after_the_end_warn(mpmshock, tiny_scene):
    done = subprocess.run([mpmshock, tiny_scene, "--check", "--set", "snapshot_times=25ns, 1us"],
                          capture_output=True, text=True)
    assert done.returncode == 0
    assert "snapshot_times: 1 of them after end_time" in done.stdout + done.stderr
