"""The scene a run of SCENE with --set overrides would get, as the simulator itself resolves it.

`mpmshock --resolve SCENE --set key=value ...` prints every key in SI, in the form of a run's
scene.txt; these functions run it and read the answer with scene.Scene, so that the package never
parses a hand-written scene or converts its units itself: the simulator is the one authority.

The simulator is $MPMSHOCK, else the `mpmshock` on PATH (`cmake --install` puts the commands beside
it and sets $MPMSHOCK for them).
"""

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from .errors import PostError
from .scene import Scene, parse_region


def mpmshock_binary():
    """The simulator: $MPMSHOCK, else `mpmshock` on PATH; PostError if neither names one."""
    named = os.environ.get("MPMSHOCK") or shutil.which("mpmshock")
    if not named:
        raise PostError("no mpmshock binary: set $MPMSHOCK to it, or put it on PATH")
    return Path(named)


def _run(binary, arguments, what):
    binary = Path(binary or mpmshock_binary())
    try:
        done = subprocess.run([str(binary), *arguments], capture_output=True, text=True, timeout=120)
    except (OSError, subprocess.SubprocessError) as e:
        raise PostError(f"cannot run {binary} {what}: {e}") from None
    if done.returncode != 0:
        message = (done.stderr or done.stdout).strip().splitlines()
        raise PostError(f"{binary} {what} exited {done.returncode}: {message[-1] if message else ''}")
    return done.stdout


def resolved_scene(scene_path, overrides=(), binary=None):
    """Scene (key -> SI float, tuple or str) that a run of scene_path with these --set overrides
    would resolve to; a bad key or value is the simulator's own error, as a PostError."""
    arguments = ["--resolve", str(scene_path)]
    for override in overrides:
        arguments += ["--set", override]
    text = _run(binary, arguments, f"--resolve {scene_path}")
    return Scene(text, f"mpmshock --resolve {scene_path}")


def default_scene(binary=None):
    """The resolved scene of an empty scene file: every key at its default (derived keys such as
    cfl = auto resolved as a run of the defaults would)."""
    with tempfile.TemporaryDirectory(prefix="mpmshock-defaults-") as folder:
        empty = Path(folder) / "empty.scene"
        empty.write_text("# every key at its default\n")   # a file of nothing is refused as a mistake
        return resolved_scene(empty, (), binary)


def _same(a, b):
    if isinstance(a, float) and isinstance(b, float):
        return a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b))
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b


def scene_differences(have, want, ignore=("output_dir",)):
    """Keys whose value differs between two resolved scenes (a run's scene.txt and the resolved
    request): a list of 'key: have X, want Y' texts, empty when the run is the one requested.

    `ignore` lists keys that only say where output goes. Probes (probe.NAME, probe_interval) only
    add probes.csv, which the tools do not read: not compared. A key that only one side has (a run
    of an older simulator) is a difference: the run is made again rather than guessed equal."""
    differences = []
    keys = [key for key in dict.fromkeys([*want, *have])
            if key not in ignore and not key.startswith(("region.", "probe.")) and key != "probe_interval"]
    for key in keys:
        if key not in have or key not in want:
            differences.append(f"{key}: have {have.get(key, '(absent)')!r}, want {want.get(key, '(absent)')!r}")
        elif not _same(have[key], want[key]):
            differences.append(f"{key}: have {have[key]!r}, want {want[key]!r}")
    return differences + _region_differences(have, want)


def _region_differences(have, want):
    have_regions = {key: value for key, value in have.items() if key.startswith("region.")}
    want_regions = {key: value for key, value in want.items() if key.startswith("region.")}
    if set(have_regions) != set(want_regions):
        return [f"regions: have {sorted(have_regions)}, want {sorted(want_regions)}"]
    differences = []
    for key in want_regions:
        a, b = parse_region(str(have_regions[key])), parse_region(str(want_regions[key]))
        if a.kind != b.kind or not all(_same(x, y) for x, y in zip((a.y1, a.y2, a.height), (b.y1, b.y2, b.height))):
            differences.append(f"{key}: have {have_regions[key]!r}, want {want_regions[key]!r}")
    return differences
