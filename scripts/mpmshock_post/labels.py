"""Names of a case for titles and legends, from its resolved scene, in the paper's notation."""

# The keys the paper varies between cases (Fig. 7, 8, 12, 13): symbol, factor, display unit.
_PAPER_KEYS = {
    "porosity": (r"$\delta$", 1.0, ""),
    "void_radius": ("$r$", 1e6, "µm"),
    "velocity": ("$v$", 1.0, "m/s"),
}
# Other SI units, shown in the units the paper uses.
_DISPLAY_UNITS = {"m": (1e6, "µm"), "s": (1e9, "ns"), "Pa": (1e-9, "GPa")}
# Keys that say where and how a run was written, or that the simulator derives from the others
# (grid_margin follows from velocity and end_time): they do not name the physical case.
_NOT_THE_CASE = ("output_dir", "sample_interval", "snapshot_interval", "probe_interval", "grid_margin")
_NOT_THE_CASE_PREFIXES = ("region.", "probe.", "snapshot_")
_MOST_KEYS_IN_A_LABEL = 3


def format_key(scene, key):
    """'δ=1.4', 'r=10 µm', 'cell_size=20 µm', 'thermal=off'."""
    value = scene[key]
    if key in _PAPER_KEYS:
        symbol, factor, unit = _PAPER_KEYS[key]
    else:
        factor, unit = _DISPLAY_UNITS.get(scene.units.get(key, ""), (1.0, scene.units.get(key, "")))
        symbol = key
    if isinstance(value, float):
        value = f"{value * factor:.4g}"
    return f"{symbol}={value}" + (f" {unit}" if unit else "")


def case_label(scene):
    """The case as the paper names it: 'δ=1.03, r=50 µm, v=1000 m/s'."""
    return ", ".join(format_key(scene, key) for key in _PAPER_KEYS if key in scene)


def _names_the_case(key):
    return key not in _NOT_THE_CASE and not key.startswith(_NOT_THE_CASE_PREFIXES)


def run_labels(runs):
    """One legend entry per run, naming the scene keys whose values differ between the runs, the
    paper's δ, r and v first and at most three; a key missing from some scenes (written by another
    simulator version) is skipped. A single run gets its case label; runs of one and the same
    scene get their directory names."""
    if len(runs) == 1:
        return [case_label(runs[0].scene) or runs[0].name]
    common = [key for key in runs[0].scene if _names_the_case(key) and all(key in run.scene for run in runs)]
    differing = [key for key in common if len({repr(run.scene[key]) for run in runs}) > 1]
    differing.sort(key=lambda key: key not in _PAPER_KEYS)  # stable: file order otherwise
    if not differing:
        return [run.name for run in runs]
    shown, hidden = differing[:_MOST_KEYS_IN_A_LABEL], len(differing) - _MOST_KEYS_IN_A_LABEL
    more = f" (+{hidden} more)" if hidden > 0 else ""
    return [", ".join(format_key(run.scene, key) for key in shown) + more for run in runs]
