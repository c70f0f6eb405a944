"""Shared set-up of the Python tests: the mpmshock binary and the runs they examine.

The binary is --mpmshock PATH (CTest passes the one it built), else $MPMSHOCK, else build/src/mpmshock
of the checkout. The fixture also exports it as $MPMSHOCK, which the package's tools read
(mpmshock_post.resolve). The package mpmshock_post is found through pytest.ini's pythonpath
(scripts/), as `pip install -e scripts` would install it; the studies through studies/.
"""

import argparse
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = ROOT / "scripts"
STUDIES = ROOT / "studies"


def pytest_addoption(parser):
    parser.addoption("--mpmshock", help="the mpmshock binary (default: $MPMSHOCK or build/src/mpmshock)")
    parser.addoption("--scene", help="a scene that runs in about a second (default: tests/data/tiny_porous.scene)")


@pytest.fixture(scope="session")
def mpmshock(request):
    binary = request.config.getoption("--mpmshock") or os.environ.get("MPMSHOCK") or ROOT / "build/src/mpmshock"
    if not Path(binary).is_file():
        pytest.fail(f"no mpmshock binary at {binary}: build it (scripts/build.sh) or pass --mpmshock PATH")
    os.environ["MPMSHOCK"] = str(binary)
    return str(binary)


@pytest.fixture(scope="session")
def tiny_scene(request):
    return str(request.config.getoption("--scene") or ROOT / "tests/data/tiny_porous.scene")


def simulate(binary, scene, out_dir, *overrides):
    command = [binary, scene, "--set", f"output_dir={out_dir}", "--quiet", "--force"]
    for override in overrides:
        command += ["--set", override]
    done = subprocess.run(command, capture_output=True, text=True, env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))
    if done.returncode != 0:
        pytest.fail(f"{' '.join(command)} exited {done.returncode}:\n{done.stdout}{done.stderr}")


@pytest.fixture(scope="session")
def ctx(mpmshock, tiny_scene, tmp_path_factory):
    """Two tiny runs, at 1000 and 1500 m/s, and a scratch directory."""
    tmp = tmp_path_factory.mktemp("post")
    context = argparse.Namespace(tmp=tmp, run=tmp / "run", run_fast=tmp / "run_fast")
    simulate(mpmshock, tiny_scene, context.run)
    simulate(mpmshock, tiny_scene, context.run_fast, "velocity=1500")
    return context
