"""Hand-written scene text as the simulator reads it: values with units to SI, the defaults that
`mpmshock --keys` lists, and the resolved scene that a run of SCENE with --set overrides would get.

The simulator stays the authority: these functions only predict what it will do, so that a tool
can tell whether an existing run directory already holds a requested run (src/scene.cpp and
src/units.cpp are what they follow). Anything they cannot parse is reported as 'unknown', and a
caller then runs the simulator rather than guess.
"""

import os
import re
import subprocess
from decimal import Decimal, InvalidOperation
from pathlib import Path

from .errors import PostError
from .scene import parse_region
from .units import plain_spacing

ROOT = Path(__file__).resolve().parents[2]  # the repository this package lives in

# value_SI = number * factor, the factors of src/units.cpp (exact powers of ten).
_UNIT_FACTORS = {
    "m": "1", "cm": "1e-2", "mm": "1e-3", "um": "1e-6", "µm": "1e-6", "nm": "1e-9",
    "s": "1", "ms": "1e-3", "us": "1e-6", "µs": "1e-6", "ns": "1e-9", "ps": "1e-12",
    "m/s": "1", "km/s": "1e3", "mm/us": "1e3", "um/ns": "1e3", "cm/us": "1e4",
    "Pa": "1", "kPa": "1e3", "MPa": "1e6", "GPa": "1e9", "bar": "1e5", "kbar": "1e8", "Mbar": "1e11",
    "kg/m3": "1", "kg/m^3": "1", "g/cm3": "1e3", "g/cm^3": "1e3", "g/cc": "1e3",
    "K": "1", "J/(kg K)": "1", "J/kg/K": "1", "J/(kg*K)": "1", "W/(m K)": "1", "W/m/K": "1",
    "J/kg": "1", "kJ/kg": "1e3", "MJ/kg": "1e6",
}
# ASCII digits and spaces, as the simulator's parser takes them (after plain_spacing).
_NUMBER = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$", re.ASCII)


def mpmshock_binary():
    """The simulator: $MPMSHOCK, else build/src/mpmshock of the repository this package lives in."""
    return Path(os.environ.get("MPMSHOCK") or ROOT / "build/src/mpmshock")


def parse_value(text):
    """SI float from '50 um', '50um', '1.2e-6' (a bare number is SI; any Unicode space and the Greek
    mu read as the simulator reads them: units.plain_spacing); a tuple of them from a
    comma-separated list of quantities ('250 ns, 750 ns': snapshot_times); any other text (a word
    such as 'on' or 'musl', a region spec) comes back stripped, as a str."""
    if "," in text:
        items = tuple(parse_value(item) for item in text.split(","))
        return items if all(isinstance(item, float) for item in items) else text.strip()
    match = _NUMBER.match(plain_spacing(text))
    if not match or (match.group(2) and match.group(2) not in _UNIT_FACTORS):
        return text.strip()
    try:
        number = Decimal(match.group(1))
    except InvalidOperation:
        return text.strip()
    unit = match.group(2)
    return float(number * Decimal(_UNIT_FACTORS[unit])) if unit else float(number)


def read_scene_text(text):
    """key -> value text of a scene file's lines, as src/scene.cpp reads them ('#' comments,
    LF, CRLF or CR line ends, 'key = value')."""
    entries = {}
    for line in re.split(r"\r\n|\r|\n", text.lstrip("\ufeff")):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        key, sep, value = line.partition("=")
        if not sep:
            raise PostError(f"scene line '{line}' is not 'key = value'")
        entries[key.strip()] = value.strip()
    return entries


def key_defaults(binary=None):
    """key -> default of every scene key, from the table `mpmshock --keys` prints: SI floats, words
    as str ('auto' for grid_margin, the comma-separated default region names for region.NAME)."""
    binary = Path(binary or mpmshock_binary())
    try:
        done = subprocess.run([str(binary), "--keys"], capture_output=True, text=True, timeout=60)
    except OSError as e:
        raise PostError(f"cannot run {binary} --keys: {e}") from None
    if done.returncode != 0:
        raise PostError(f"{binary} --keys exited {done.returncode}: {done.stderr.strip()}")
    defaults = {}
    for line in done.stdout.splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if len(cells) >= 3 and cells[0].startswith("`") and cells[0].endswith("`"):
            defaults[cells[0].strip("`")] = parse_value(cells[2])
    if "density" not in defaults:
        raise PostError(f"{binary} --keys printed no key table")
    return defaults


def requested_scene(scene_path, overrides):
    """key -> value (SI float or str) that the scene file and the --set overrides name; overrides
    win, as in the simulator."""
    try:
        entries = read_scene_text(Path(scene_path).read_text(encoding="utf-8"))
    except OSError as e:
        raise PostError(f"cannot read scene {scene_path}: {e}") from None
    for override in overrides:
        key, sep, value = override.partition("=")
        if not sep:
            raise PostError(f"--set {override}: expected key=value")
        entries[key.strip()] = value.strip()
    return {key: parse_value(value) for key, value in entries.items()}


def _same(a, b):
    if isinstance(a, float) and isinstance(b, float):
        return a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b))
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) != isinstance(b, float):  # one time given as a list of one
        return _same((a,) if isinstance(a, float) else a, (b,) if isinstance(b, float) else b)
    return a == b


def scene_differences(resolved, requested, defaults, ignore=("output_dir",)):
    """Keys whose value in a resolved scene (a run's scene.txt, parsed) differs from what a run of
    the request would resolve to: the requested value where the request names the key, else the
    --keys default. Returns a list of 'key: have X, want Y' texts, empty when the run matches.

    `ignore` lists keys that only say where output goes. grid_margin, symmetry, cfl and depth =
    auto are derived from other keys (cell_size, velocity, end_time; the bodies and heat_conduction;
    dimension; width), which are compared, so their resolved values are not. Probes
    (probe.NAME, probe_interval) only add probes.csv, which nothing here reads: not compared."""
    differences = []
    keys = [key for key in dict.fromkeys([*defaults, *requested, *resolved])
            if key not in ignore and not key.startswith(("region.", "probe.")) and key != "probe_interval"]
    for key in keys:
        want = requested.get(key, defaults.get(key))
        if key in ("grid_margin", "symmetry", "cfl", "depth") and want == "auto":
            continue
        if key not in resolved and key in defaults and _same(want, defaults[key]):
            continue  # a run of an earlier simulator without this key, which behaved as its default
        have = resolved.get(key)
        if key not in defaults and key not in requested:
            differences.append(f"{key}: not a key this simulator knows")
        elif not _same(have, want):
            differences.append(f"{key}: have {have!r}, want {want!r}")
    differences += _region_differences(resolved, requested, defaults)
    return differences


def _region_differences(resolved, requested, defaults):
    have = {key: value for key, value in resolved.items() if key.startswith("region.")}
    want = {key: value for key, value in requested.items() if key.startswith("region.")}
    if not want:  # the simulator's default regions; --keys names them, the specs are its own
        names = [name.strip() for name in str(defaults.get("region.NAME", "")).split(",")]
        want_names = {f"region.{name}" for name in names if name}
        return [] if set(have) == want_names else [f"regions: have {sorted(have)}, want {sorted(want_names)}"]
    if set(have) != set(want):
        return [f"regions: have {sorted(have)}, want {sorted(want)}"]
    differences = []
    for key in want:
        try:
            a, b = parse_region(str(have[key])), parse_region(str(want[key]))
        except PostError as e:
            differences.append(f"{key}: {e}")
            continue
        if a.kind != b.kind or not all(_same(x, y) for x, y in zip((a.y1, a.y2, a.height), (b.y1, b.y2, b.height))):
            differences.append(f"{key}: have {have[key]!r}, want {want[key]!r}")
    return differences
