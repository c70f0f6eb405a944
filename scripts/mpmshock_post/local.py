"""Local quantities of every material point of a snapshot, under the names regions.csv uses (SI).

The velocity gradient is stored as L[i][j] = dv_i/dx_j; from it the paper's local rotation,
divergence and strain rate (section IV A): Rot = dv_y/dx - dv_x/dy, Div = dv_x/dx + dv_y/dy, and
D : D with D = sym(L) in the plane. In 3D (L 3 x 3) they are what src/regions.cpp averages: Rot^2
= |curl v|^2, Div = tr L and D : D over all nine components; speed is |v| with v_z, and velocity_z
is there too.
"""

import numpy as np

from .errors import PostError


def rotation2(L):
    """(dv_y/dx - dv_x/dy)^2: circulation, the paper's measure of turbulence dissipation; in 3D
    the squared vorticity |curl v|^2."""
    if L.shape[1] == 3:
        a, b = L[:, 2, 1] - L[:, 1, 2], L[:, 0, 2] - L[:, 2, 0]
        c = L[:, 1, 0] - L[:, 0, 1]
        return a * a + b * b + c * c
    return (L[:, 1, 0] - L[:, 0, 1]) ** 2


def divergence2(L):
    """(dv_x/dx + dv_y/dy)^2 (3D: + dv_z/dz): the rate of volume change, compression and cavitation."""
    if L.shape[1] == 3:
        div = L[:, 0, 0] + L[:, 1, 1] + L[:, 2, 2]
        return div * div
    return (L[:, 0, 0] + L[:, 1, 1]) ** 2


def strain_rate2(L):
    """D : D = D_xx^2 + D_yy^2 + 2 D_xy^2, the squared norm of the in-plane strain rate (3D: with
    D_zz^2 + 2 D_yz^2 + 2 D_zx^2)."""
    D_xy = 0.5 * (L[:, 0, 1] + L[:, 1, 0])
    if L.shape[1] == 3:
        D_yz, D_zx = 0.5 * (L[:, 1, 2] + L[:, 2, 1]), 0.5 * (L[:, 2, 0] + L[:, 0, 2])
        return (L[:, 0, 0] * L[:, 0, 0] + L[:, 1, 1] * L[:, 1, 1] + L[:, 2, 2] * L[:, 2, 2]
                + 2.0 * D_xy * D_xy + 2.0 * D_yz * D_yz + 2.0 * D_zx * D_zx)
    return L[:, 0, 0] ** 2 + L[:, 1, 1] ** 2 + 2.0 * D_xy ** 2


def _speed(velocity):
    if velocity.shape[1] == 3:
        return np.sqrt(velocity[:, 0] ** 2 + velocity[:, 1] ** 2 + velocity[:, 2] ** 2)
    return np.hypot(velocity[:, 0], velocity[:, 1])


def _velocity_z(snapshot):
    velocity = snapshot["velocity"]
    if velocity.shape[1] < 3:
        raise PostError(f"velocity_z needs a 3D run; {snapshot.path} is 2D (its points move in x and y only)")
    return velocity[:, 2]


# name -> (the dataset it needs, how to compute it)
_DERIVED = {
    "velocity_x": ("velocity", lambda s: s["velocity"][:, 0]),
    "velocity_y": ("velocity", lambda s: s["velocity"][:, 1]),
    "velocity_z": ("velocity", _velocity_z),
    "speed": ("velocity", lambda s: _speed(s["velocity"])),
    "rot2": ("velocity_gradient", lambda s: rotation2(s["velocity_gradient"])),
    "div2": ("velocity_gradient", lambda s: divergence2(s["velocity_gradient"])),
    "strain_rate2": ("velocity_gradient", lambda s: strain_rate2(s["velocity_gradient"])),
}


def _scalar_datasets(fields):
    return [n for n in fields if len(fields.shape(n)) == 1 and n not in ("id", "body")]


def has_quantity(snapshot, name):
    """Whether the snapshot holds what `name` needs (older or trimmed files may lack a dataset)."""
    if name == "velocity_z":
        return "velocity" in snapshot.fields and snapshot.fields.shape("velocity")[1:] == (3,)
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
