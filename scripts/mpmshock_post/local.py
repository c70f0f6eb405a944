"""Local quantities of every material point of a snapshot, under the names regions.csv uses (SI).

The velocity gradient is stored as L[i][j] = dv_i/dx_j; from it the paper's local rotation,
divergence and strain rate (section IV A): Rot = dv_y/dx - dv_x/dy, Div = dv_x/dx + dv_y/dy, and
D : D with D = sym(L) in the plane.
"""

import numpy as np

from .errors import PostError


def rotation2(L):
    """(dv_y/dx - dv_x/dy)^2: circulation, the paper's measure of turbulence dissipation."""
    return (L[:, 1, 0] - L[:, 0, 1]) ** 2


def divergence2(L):
    """(dv_x/dx + dv_y/dy)^2: the rate of volume change, compression and cavitation."""
    return (L[:, 0, 0] + L[:, 1, 1]) ** 2


def strain_rate2(L):
    """D : D = D_xx^2 + D_yy^2 + 2 D_xy^2, the squared norm of the in-plane strain rate."""
    D_xy = 0.5 * (L[:, 0, 1] + L[:, 1, 0])
    return L[:, 0, 0] ** 2 + L[:, 1, 1] ** 2 + 2.0 * D_xy ** 2


# name -> (the dataset it needs, how to compute it)
_DERIVED = {
    "velocity_x": ("velocity", lambda s: s["velocity"][:, 0]),
    "velocity_y": ("velocity", lambda s: s["velocity"][:, 1]),
    "speed": ("velocity", lambda s: np.hypot(s["velocity"][:, 0], s["velocity"][:, 1])),
    "rot2": ("velocity_gradient", lambda s: rotation2(s["velocity_gradient"])),
    "div2": ("velocity_gradient", lambda s: divergence2(s["velocity_gradient"])),
    "strain_rate2": ("velocity_gradient", lambda s: strain_rate2(s["velocity_gradient"])),
}


def _scalar_datasets(fields):
    return [n for n in fields if len(fields.shape(n)) == 1 and n not in ("id", "body")]


def has_quantity(snapshot, name):
    """Whether the snapshot holds what `name` needs (older or trimmed files may lack a dataset)."""
    if name in _DERIVED:
        return _DERIVED[name][0] in snapshot.fields
    return name in _scalar_datasets(snapshot.fields)


def local_quantity(snapshot, name):
    """One value per material point: a derived quantity above, or any 1-D /particles dataset
    (density, pressure, temperature, plastic_strain, internal_energy, ...)."""
    if name in _DERIVED:
        return _DERIVED[name][1](snapshot)
    scalars = _scalar_datasets(snapshot.fields)
    if name in scalars:
        return snapshot[name]
    raise PostError(f"unknown local quantity '{name}' in {snapshot.path} "
                    f"(known: {', '.join(list(_DERIVED) + scalars)})")
