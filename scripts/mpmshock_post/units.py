"""The paper's display units (g/cm3, GPa, K, m/s, ns, um); the reader stays in SI, plots convert here."""

import re
from decimal import Decimal, InvalidOperation
from typing import NamedTuple

from .errors import PostError


class Quantity(NamedTuple):
    symbol: str          # mathtext, as the paper's axes name it
    unit: str            # plain text, for tables and file names
    factor: float        # SI value * factor = displayed value
    unit_tex: str = ""   # mathtext form of the unit where it differs from the plain one

    def label(self, prefix=""):
        unit = self.unit_tex or self.unit
        return f"{prefix}{self.symbol}" + (f" ({unit})" if unit else "")

    def inverse_unit(self):
        """The unit of 1/quantity, as an axis writes it: g/cm3 -> cm³/g, m/s -> s/m, GPa -> GPa⁻¹,
        ns⁻² -> ns²; '' for a quantity without a unit."""
        unit = self.unit_tex or self.unit
        if not unit:
            return ""
        numerator, slash, denominator = unit.partition("/")
        if slash:
            return denominator if numerator == "1" else f"{denominator}/{numerator}"
        power = _NEGATIVE_POWER.fullmatch(unit)
        if power:
            return f"{power.group(1)}$^{{{power.group(2)}}}$"
        return f"{unit}$^{{-1}}$"


_NEGATIVE_POWER = re.compile(r"(.*)\$\^\{-(\d+)\}\$")  # 'ns$^{-2}$': the unit and the power

# Rotation, divergence and strain rate squared in 1/ns^2: the paper gives its Fig. 5 "in um and ns".
QUANTITIES = {
    "density": Quantity(r"$\rho$", "g/cm3", 1e-3, r"g/cm$^3$"),
    "pressure": Quantity("$P$", "GPa", 1e-9),
    "temperature": Quantity("$T$", "K", 1.0),
    "velocity_x": Quantity("$u_x$", "m/s", 1.0),
    "velocity_y": Quantity("$u_y$", "m/s", 1.0),
    "velocity_z": Quantity("$u_z$", "m/s", 1.0),  # 3D runs only
    "speed": Quantity("$|u|$", "m/s", 1.0),
    "rot2": Quantity(r"$\langle \mathrm{Rot}^2 \rangle$", "1/ns^2", 1e-18, r"ns$^{-2}$"),
    "div2": Quantity(r"$\langle \mathrm{Div}^2 \rangle$", "1/ns^2", 1e-18, r"ns$^{-2}$"),
    "strain_rate2": Quantity(r"$\langle \dot\varepsilon^2 \rangle$", "1/ns^2", 1e-18, r"ns$^{-2}$"),
    "plastic_strain": Quantity(r"$\varepsilon_p$", "", 1.0),
    "internal_energy": Quantity("$E$", "kJ/g", 1e-6),
    "viscous_pressure": Quantity("$q$", "GPa", 1e-9),
    "damage": Quantity("damage $D$", "", 1.0),  # 0 intact ... 1 separated in tension (spall = on)
}

# Other display units a plot may ask for, per quantity: unit -> factor (the paper's Fig. 1 is in MPa).
_OTHER_UNITS = {"pressure": {"MPa": 1e-6, "Pa": 1.0}, "density": {"kg/m3": 1.0}}

TIME = Quantity("$t$", "ns", 1e9)
LENGTH_FACTOR = 1e6  # m -> um

# SI units of the columns of regions.csv and probes.csv (docs/outputs.md), by the quantity a column
# holds: regions.csv's X_mean and X_std are in the unit of X; '' for counts.
_CSV_UNITS = {
    "time": "s", "count": "", "x": "m", "y": "m", "z": "m",
    "density": "kg/m3", "pressure": "Pa", "temperature": "K", "paper_temperature": "K",
    "velocity_x": "m/s", "velocity_y": "m/s", "velocity_z": "m/s",
    "rot2": "1/s2", "div2": "1/s2", "strain_rate2": "1/s2",
    "macro_density": "kg/m3", "macro_pressure": "Pa", "macro_normal_stress": "Pa",
}
# conservation.csv: extensive sums, per metre of depth in 2D (plane strain), whole in 3D.
_CONSERVATION_UNITS = {
    2: {"mass": "kg/m", "momentum": "kg/s", "energy": "J/m"},
    3: {"mass": "kg", "momentum": "kg m/s", "energy": "J"},
}


def csv_unit(column):
    """SI unit of a regions.csv or probes.csv column ('pressure_std' -> 'Pa'); None if unknown
    (a column from a newer simulator)."""
    for suffix in ("_mean", "_std"):
        if column.endswith(suffix) and column[:-len(suffix)] in _CSV_UNITS:
            return _CSV_UNITS[column[:-len(suffix)]]
    return _CSV_UNITS.get(column)


def conservation_unit(column, dimension):
    """SI unit of a conservation.csv column in a run of this dimension (2: per metre of depth);
    None if unknown."""
    extensive = _CONSERVATION_UNITS[dimension]
    if column in ("time", "dt"):
        return "s"
    if column == "step":
        return ""
    if column == "mass":
        return extensive["mass"]
    if column.startswith("momentum_"):
        return extensive["momentum"]
    if column.endswith("_energy") or column == "work_mismatch":
        return extensive["energy"]
    return None

# Every Unicode space (category Zs: no-break U+00A0, thin U+2009, narrow no-break U+202F, ...) as an
# ASCII space, and the Greek small letter mu U+03BC as the micro sign U+00B5 that the unit tables
# spell: they look the same, so a value written with them means the same (src/units.cpp,
# plain_spacing, reads scenes so).
_ZS_SPACES = "\u00a0\u1680" + "".join(map(chr, range(0x2000, 0x200B))) + "\u202f\u205f\u3000"
_PLAIN = str.maketrans({**dict.fromkeys(_ZS_SPACES, " "), "\u03bc": "\u00b5"})


def plain_spacing(text):
    """The text with every Unicode space as ' ' and the Greek mu as the micro sign."""
    return text.translate(_PLAIN)


_TIME_SUFFIXES = {"ns": "1e-9", "us": "1e-6", "µs": "1e-6", "ms": "1e-3", "s": "1"}
_TIME = re.compile(r"^\s*([-+0-9.eE]+)\s*(ns|us|µs|ms|s)\s*$")
_LENGTH_SUFFIXES = {"m": "1", "mm": "1e-3", "um": "1e-6", "µm": "1e-6", "nm": "1e-9"}
_LENGTH = re.compile(r"^\s*([-+0-9.eE]+)\s*(mm|um|µm|nm|m)?\s*$")


def quantity(name, unit=None):
    """Display units of a quantity; quantities without an entry are drawn in SI. `unit` asks for
    another unit than the paper's default (pressure in MPa, density in kg/m3)."""
    q = QUANTITIES.get(name, Quantity(name.replace("_", " "), "SI", 1.0))
    if unit is None or unit == q.unit:
        return q
    others = _OTHER_UNITS.get(name, {})
    if unit not in others:
        known = ", ".join([q.unit, *others])
        raise PostError(f"{name} cannot be shown in '{unit}' (units: {known})")
    return q._replace(unit=unit, factor=others[unit], unit_tex="")


def parse_time(text):
    """Seconds from '1200ns', '1.2us' or '1.2e-6s'; a bare number is refused as ambiguous."""
    match = _TIME.match(plain_spacing(text))
    if not match:
        raise PostError(f"time '{text}': give a number with a unit, e.g. 1200ns, 1.2us or 1.2e-6s")
    try:
        # In decimal, so that 1200ns is the same double as the 1.2e-06 s the simulator writes.
        return float(Decimal(match.group(1)) * Decimal(_TIME_SUFFIXES[match.group(2)]))
    except InvalidOperation:
        raise PostError(f"time '{text}': '{match.group(1)}' is not a number") from None


def parse_length(text):
    """Metres from '50um', '50 um', '0.05mm' or '5e-5' (a bare number is in metres, as in region
    specs and the resolved scene)."""
    match = _LENGTH.match(plain_spacing(text))
    if not match:
        raise PostError(f"length '{text}': give a number in metres or with a unit, e.g. 50um, 0.05mm or 5e-5")
    try:
        return float(Decimal(match.group(1)) * Decimal(_LENGTH_SUFFIXES[match.group(2) or "m"]))
    except InvalidOperation:
        raise PostError(f"length '{text}': '{match.group(1)}' is not a number") from None


# The units a known answer is written in on a command line (mpmshock-converge --exact): the display
# units above and SI. Scene values are the simulator's to convert (mpmshock --resolve), not these.
_QUANTITY_SUFFIXES = {**_TIME_SUFFIXES, **_LENGTH_SUFFIXES, "m/s": "1", "km/s": "1e3", "Pa": "1", "MPa": "1e6",
                      "GPa": "1e9", "kg/m3": "1", "g/cm3": "1e3", "K": "1", "J/kg": "1", "kJ/g": "1e6"}
_QUANTITY = re.compile(r"^\s*([-+0-9.eE]+)\s*(\S*)\s*$", re.ASCII)


def parse_quantity(text):
    """SI float from '49.9ns', '4.7 GPa', '2.75 g/cm3' or a bare SI number; the units are those
    the package displays (ns, um, m/s, GPa, MPa, g/cm3, K, kJ/g, ...) and SI."""
    match = _QUANTITY.match(plain_spacing(text))
    unit = match.group(2) if match else None
    if not match or (unit and unit not in _QUANTITY_SUFFIXES):
        known = ", ".join(_QUANTITY_SUFFIXES)
        raise PostError(f"'{text}': give a number in SI or with one of the units {known}")
    try:
        return float(Decimal(match.group(1)) * Decimal(_QUANTITY_SUFFIXES[unit] if unit else "1"))
    except InvalidOperation:
        raise PostError(f"'{text}': '{match.group(1)}' is not a number") from None
