"""The simulator's region averages (src/regions.cpp), recomputed from a snapshot.

A region is given as a name from the snapshot's scene ('B800'), a spec text ('bottom 100 um 800 um')
or a RegionSpec. Membership, means and population deviations follow the C++ code exactly, so that
region_stats(snapshot, name) reproduces the regions.csv row written at the snapshot's time.
"""

import numpy as np

from .errors import PostError
from .local import has_quantity, local_quantity
from .scene import RegionSpec, parse_region

_TARGET = 1  # the body dataset: 0 flyer, 1 target
_WITH_STD = ("density", "pressure", "temperature", "velocity_x", "velocity_y")
_MEAN_ONLY = ("rot2", "div2", "strain_rate2")


def resolve_region(snapshot, region):
    """RegionSpec for a name in the snapshot's scene, a spec text, or a RegionSpec."""
    if isinstance(region, RegionSpec):
        return region
    known = snapshot.scene.regions if snapshot.scene is not None else {}
    if region in known:
        return known[region]
    if region.split()[:1] in (["bottom"], ["top"], ["band"]):
        return parse_region(region)
    raise PostError(f"no region '{region}' in the scene of {snapshot.path} "
                    f"(regions: {', '.join(known) or 'none'}; or give 'bottom Y1 H', 'top H', 'band Y1 Y2')")


def target_top(snapshot):
    """Highest y of the target's points, the upper edge of the 'top' regions."""
    y = snapshot["position"][:, 1][snapshot["body"] == _TARGET]
    return y.max() if y.size else -np.inf


def region_points(snapshot, region):
    """Indices (storage order) of the material points inside the region."""
    spec = resolve_region(snapshot, region)
    y = snapshot["position"][:, 1]
    lo, hi = spec.bounds(target_top(snapshot))
    inside = (y >= lo) & (y <= hi)
    if spec.target_only:
        inside &= snapshot["body"] == _TARGET
    return np.flatnonzero(inside)


def region_stats(snapshot, region):
    """The regions.csv columns for this region (count, X_mean, X_std, rot2_mean, ...), SI units.
    Deviations are population ones (divide by the count); an empty region, or a quantity the
    snapshot does not hold (no temperature dataset), gives NaN, as the simulator writes it."""
    points = region_points(snapshot, region)
    stats = {"count": points.size}
    for name in _WITH_STD + _MEAN_ONLY:
        available = has_quantity(snapshot, name)
        values = local_quantity(snapshot, name)[points] if available else np.array([np.nan])
        stats[f"{name}_mean"] = values.mean() if values.size else np.nan
        if name in _WITH_STD:
            stats[f"{name}_std"] = values.std() if values.size else np.nan
    return stats
