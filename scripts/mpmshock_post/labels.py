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
# Keys whose automatic value is another key's: named only where some run sets them apart.
_FOLLOWS = {"flyer_velocity": "velocity", "target_velocity": "velocity", "flyer_porosity": "porosity"}
# Keys that describe the voids: they say nothing about a solid run (porosity 1, or no voids laid out).
_VOID_KEYS = ("void_radius", "void_radius_spread", "void_min_gap", "void_overlap", "seed")


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


def is_solid(scene, void_count=None):
    """A run without voids: porosity 1 (or less), or no void laid out (`void_count`, the rows of
    voids.csv, 0: a porosity too close to 1 for one void); None: unknown, the porosity decides."""
    return float(scene.get("porosity", 1.0)) <= 1.0 or void_count == 0


def case_label(scene, void_count=None):
    """The case as the paper names it: 'δ=1.03, r=50 µm, v=1000 m/s'; a solid run has no void
    radius: 'δ=1, v=1000 m/s', or 'δ=1.001 (no voids), v=...' when none could be laid out."""
    solid = is_solid(scene, void_count)
    parts = []
    for key in _PAPER_KEYS:
        if key not in scene or (solid and key in _VOID_KEYS):
            continue
        text = format_key(scene, key)
        if key == "porosity" and solid and float(scene[key]) > 1.0:
            text += " (no voids)"
        parts.append(text)
    # Two materials, the laboratory frame (issue 29): the flyer's and target's, as the scene names them.
    flyer, target = scene.get("flyer_material", "scene"), scene.get("target_material", "scene")
    if flyer != target:
        parts.append(f"{flyer} on {target}".replace("scene", "the scene's material"))
    if "target_velocity" in scene and scene.get("target_velocity") != scene.get("velocity"):
        target = float(scene["target_velocity"])
        parts.append("target at rest" if target == 0.0 else f"target {0.0 - target:g} m/s")
    if float(scene.get("window_height", 0.0)) > 0.0:
        parts.append(f"{scene.get('window_material', 'lif')} window")
    return ", ".join(parts)


def run_void_count(run):
    """The run's void count (reader.Run.void_count), None for an object that cannot tell."""
    return run.void_count() if hasattr(run, "void_count") else None


def run_case_label(run):
    """case_label of a reader.Run, with its void count."""
    return case_label(run.scene, run_void_count(run))


def resolution_parts(scene):
    """The resolution of a run, from its scene, in pieces a caption joins or wraps: 'cell 10 µm',
    '2 × 2 points per cell', 'bspline2 shape functions'."""
    parts = []
    if isinstance(scene.get("cell_size"), float):
        parts.append(f"cell {scene['cell_size'] * 1e6:.4g} µm")
    per_axis = scene.get("particles_per_cell")
    if isinstance(per_axis, float):
        parts.append(" × ".join([f"{per_axis:g}"] * scene.dimension) + " points per cell")
    if isinstance(scene.get("shape_function"), str):
        parts.append(f"{scene['shape_function']} shape functions")
    return parts


def resolution_label(scene):
    """'cell 10 µm, 2 × 2 points per cell, bspline2 shape functions' ('resolution not stated' for a
    scene without those keys)."""
    return ", ".join(resolution_parts(scene)) or "resolution not stated in the scene"


def common_case_label(runs):
    """The paper's keys (δ, r, v) that are the same in every run, as case_label writes them; the
    void radius only when every run has voids."""
    first = runs[0].scene
    solid = any(is_solid(run.scene, run_void_count(run)) for run in runs)
    same = [key for key in _PAPER_KEYS if key in first and not (solid and key in _VOID_KEYS)
            and all(key in run.scene and run.scene[key] == first[key] for run in runs)]
    return ", ".join(format_key(first, key) for key in same)


def _names_the_case(key):
    return key not in _NOT_THE_CASE and not key.startswith(_NOT_THE_CASE_PREFIXES)


def run_labels(runs):
    """One legend entry per run, naming the scene keys whose values differ between the runs, the
    paper's δ, r and v first and at most three; a key missing from some scenes (written by another
    simulator version) is skipped. A single run gets its case label; runs of one and the same
    scene get their directory names."""
    if len(runs) == 1:
        return [run_case_label(runs[0]) or runs[0].name]
    common = [key for key in runs[0].scene if _names_the_case(key) and all(key in run.scene for run in runs)]
    differing = [key for key in common if len({repr(run.scene[key]) for run in runs}) > 1
                 and not all(run.scene.get(key) == run.scene.get(_FOLLOWS.get(key)) for run in runs)]
    differing.sort(key=lambda key: key not in _PAPER_KEYS)  # stable: file order otherwise
    if not differing:
        return [run.name for run in runs]
    shown, hidden = differing[:_MOST_KEYS_IN_A_LABEL], len(differing) - _MOST_KEYS_IN_A_LABEL
    more = f" (+{hidden} more)" if hidden > 0 else ""
    labels = []
    for run in runs:
        solid = is_solid(run.scene, run_void_count(run))
        label = ", ".join(format_key(run.scene, key) for key in shown if not (solid and key in _VOID_KEYS))
        labels.append(label + more if label else run.name)
    return labels
