"""How the accuracy study's report writes its numbers: each quantity in its unit (GPa, kg/m3, K, m/s),
errors relative (densities, pressures) or absolute (temperatures, velocities), orders, cell sizes and
markdown tables.

Part of the study in studies/accuracy/ of the checkout, run as `studies/accuracy/accuracy-study`.
"""

import math

from .plan import UM

# Whether a quantity's errors are stated relative to its value (else in its unit).
RELATIVE = {"density_mean": True, "macro_density": True, "pressure_mean": True, "macro_normal_stress": True,
            "macro_pressure": True, "temperature_mean": False, "temperature_std": False,
            "velocity_y_std": False, "velocity_x_std": False}


def unit_of(quantity):
    """The report's unit of a quantity."""
    if "pressure" in quantity or "stress" in quantity:
        return "GPa"
    if "density" in quantity:
        return "kg/m3"
    if "temperature" in quantity:
        return "K"
    return "m/s"


def unit_value(quantity, value, digits=4):
    """The number alone in the report's units."""
    if "pressure" in quantity or "stress" in quantity:
        return f"{value * 1e-9:.{digits}g}"
    return f"{value:.{digits}g}"


def error_text(quantity, error, reference=None, signed=True):
    """A relative error in % for densities and pressures, an absolute one in K (or m/s) otherwise."""
    if error is None or not math.isfinite(error):
        return "-"
    if RELATIVE.get(quantity, False):
        value = 100.0 * error / abs(reference)
        return f"{value:+.3g} %" if signed else f"{abs(value):.2g} %"
    return f"{error:+.3g} {unit_of(quantity)}" if signed else f"{abs(error):.2g} {unit_of(quantity)}"


def order_text(estimate):
    """The observed order, or why there is none (the fallback)."""
    if math.isfinite(estimate.order):
        return f"{estimate.order:.2f}"
    return "none: " + estimate.note.replace("fallback: ", "")


def order_or_dash(order):
    """An order of the true errors ('-' where there is none: the errors changed sign)."""
    return "-" if order is None else f"{order:.2f}"


def h_text(h):
    """A cell size (or any length) in um."""
    return f"{h / UM:.3g} um"


def cells_text(hs):
    """Cell sizes, comma-separated."""
    return ", ".join(h_text(h) for h in hs)


def md_table(header, rows):
    """A markdown table, as one text of lines."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows])
