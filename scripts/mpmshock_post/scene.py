"""The resolved scene (scene.txt, and the `scene` attribute of every snapshot) and its regions.

Each line is `key = value unit`: the value is a number in SI units followed by its unit, or a word.
Region definitions (`region.NAME = bottom 1e-04 m 8e-04 m`) are kept as text in the dict and also
parsed into RegionSpec objects, which mirror the simulator's measured domains.
"""

from dataclasses import dataclass
from decimal import Decimal, InvalidOperation

from .errors import PostError
from .units import plain_spacing

# Length units a hand-written region spec may use; the resolved scene always writes metres.
# Decimal, so that '800 um' is the very double 8e-04 that the scene's 'region.B800' holds.
_LENGTH_UNITS = {"m": Decimal(1), "mm": Decimal("1e-3"), "um": Decimal("1e-6"), "µm": Decimal("1e-6"),
                 "nm": Decimal("1e-9")}


@dataclass(frozen=True)
class RegionSpec:
    """A measured domain of the paper (physics-notes section 5); lengths in m.

    bottom: target points with y1 <= y <= y1 + height.
    top:    target points with y_top - height <= y <= y_top, y_top the highest target point.
    band:   points of either body with y1 <= y <= y2.
    """

    kind: str
    y1: float = 0.0
    y2: float = 0.0
    height: float = 0.0

    @property
    def target_only(self):
        return self.kind != "band"

    @property
    def extent(self):
        """Height of the domain, used to give domains of equal height the same colour."""
        return self.y2 - self.y1 if self.kind == "band" else self.height

    def bounds(self, y_top):
        """Lower and upper y of the domain, computed exactly as the simulator does (lo + h in double)."""
        if self.kind == "bottom":
            return self.y1, self.y1 + self.height
        if self.kind == "top":
            return y_top - self.height, y_top
        return self.y1, self.y2


def _lengths(tokens, text):
    """Numbers of a region spec, each optionally followed by a length unit ('100 um' or '100um'),
    in metres."""
    values, unit_given = [], True
    for token in tokens:
        if token in _LENGTH_UNITS:
            if unit_given:
                raise PostError(f"region '{text}': unit '{token}' does not follow a bare number")
            values[-1] *= _LENGTH_UNITS[token]
            unit_given = True
            continue
        number = token.rstrip("".join(_LENGTH_UNITS))  # the letters of m, mm, um, µm, nm
        unit = token[len(number):]
        try:
            values.append(Decimal(number) * _LENGTH_UNITS[unit] if unit else Decimal(number))
            unit_given = bool(unit)
        except (InvalidOperation, KeyError):
            raise PostError(f"region '{text}': '{token}' is not a length "
                            f"(a number, optionally with {', '.join(_LENGTH_UNITS)})") from None
    return [float(value) for value in values]


def parse_region(text):
    """RegionSpec from 'bottom Y1 H', 'top H' or 'band Y1 Y2' (metres unless a unit follows)."""
    tokens = plain_spacing(text).split()
    arity = {"bottom": 2, "top": 1, "band": 2}
    if not tokens or tokens[0] not in arity:
        raise PostError(f"region '{text}': expected 'bottom Y1 H', 'top H' or 'band Y1 Y2'")
    kind = tokens[0]
    values = _lengths(tokens[1:], text)
    if len(values) != arity[kind]:
        raise PostError(f"region '{text}': '{kind}' takes {arity[kind]} length(s), got {len(values)}")
    if kind == "bottom":
        return RegionSpec(kind, y1=values[0], height=values[1])
    if kind == "top":
        return RegionSpec(kind, height=values[0])
    return RegionSpec(kind, y1=values[0], y2=values[1])


class Scene(dict):
    """key -> float (SI), tuple of floats (a list such as snapshot_times) or str, in file order;
    `units[key]` is the unit text ('' for none)."""

    def __init__(self, text, source):
        super().__init__()
        self.source = source
        self.units = {}
        for number, line in enumerate(text.splitlines(), start=1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            key, sep, value = line.partition("=")
            if not sep:
                raise PostError(f"{source}:{number}: expected 'key = value', got '{line}'")
            key, value = key.strip(), value.strip()
            if "," in value:  # a list of quantities (snapshot_times): a tuple in SI
                items = [item.strip().partition(" ") for item in value.split(",")]
                try:
                    self[key] = tuple(float(number) for number, _, _ in items)
                    self.units[key] = items[0][2].strip()
                    continue
                except ValueError:
                    pass
            first, _, unit = value.partition(" ")
            try:
                self[key] = float(first)
                self.units[key] = unit.strip()
            except ValueError:
                self[key] = value
                self.units[key] = ""

    @property
    def dimension(self):
        """2 (plane strain) or 3 (a column periodic in x and z); 2 for scenes written before the
        simulator had 3D runs."""
        value = self.get("dimension", 2.0)
        if value not in (2.0, 3.0):
            raise PostError(f"{self.source}: dimension = {value}: expected 2 or 3")
        return int(value)

    @property
    def depth(self):
        """z extent of a 3D column in m (the resolved scene states it; 'auto' means the width);
        None in 2D, where extensive quantities are per metre of depth."""
        if self.dimension != 3:
            return None
        value = self.get("depth")
        return float(value) if isinstance(value, float) and value > 0 else float(self["width"])

    @property
    def point_spacing(self):
        """Spacing of the initial material-point lattice in m: cell_size / particles_per_cell
        (particles_per_cell counts points along each axis); None if the scene lacks cell_size."""
        if not isinstance(self.get("cell_size"), float):
            return None
        return self["cell_size"] / float(self.get("particles_per_cell", 2.0))

    @property
    def regions(self):
        """Region name -> RegionSpec, in the order the scene lists them."""
        specs = {}
        for key, value in self.items():
            if key.startswith("region."):
                try:
                    specs[key[len("region."):]] = parse_region(value)
                except PostError as e:
                    raise PostError(f"{self.source}: key '{key}': {e}") from None
        return specs
