"""The exact shocked state of the symmetric impact, solid or porous, as mpmshock's laws define it.

Flyer and target are mirror images moving at +v and -v, so the impact plane stays at rest and the
particle-velocity jump in each body is u_p = v (physics-notes section 3). SI units throughout;
J = V/V0 is the specific volume over that of the solid at rest.

Solid (physics-notes 3): Us = c0 + s u_p, rho = rho0 Us / (Us - u_p), P = rho0 Us u_p, E = u_p^2 / 2.

Porous, full compaction: the body starts at rho00 = rho0 / delta (V00 = delta V0) with P = E = 0,
and the shocked material is solid at J < 1 on the code's Mie-Gruneisen EOS (include/mpmshock/eos.hpp)
    P = P_H(J) + gamma0 rho0 (E - E_H(J)),   E_H = P_H (V0 - V) / 2,   gamma rho constant,
with the Rankine-Hugoniot energy jump from the porous state E = P (V00 - V) / 2. Eliminating E,
    P(J) = P_H(J) (1 - gamma0 (1 - J) / 2) / (1 - gamma0 (delta - J) / 2),
and J is the root of u_p^2 = P (V00 - V) = v^2. delta = 1 gives back the solid Hugoniot.

Temperatures are those the code computes from (J, E) (src/temperature.cpp):
T = T_H(J) + (E - E_H(J)) / c_v, with T_H tabulated from the Walsh-Christian equation exactly as
the C++ does (RK4, 4096 intervals of 8 substeps, linear interpolation). In tension (J >= 1) the
reference curve is the linear branch of P_H, on which the equation has no shock-heating term:
T_H = T0 exp(gamma0 (1 - J)), the isentrope. On the solid Hugoniot E = E_H, so T = T_H.

    from mpmshock_post import hugoniot
    material = hugoniot.default_material()            # the simulator's defaults (mpmshock --keys)
    material = hugoniot.Material.from_scene(run.scene)  # or a run's resolved scene
    hugoniot.solid_shock(1000.0, material).pressure     # 1.806e10 Pa
    hugoniot.porous_shock(1000.0, 1.4, material)
"""

from dataclasses import dataclass
from functools import lru_cache
import math

from .errors import PostError
from .resolve import default_scene


@dataclass(frozen=True)
class Material:
    """The constants of the EOS and the temperature model; names are the scene keys."""

    density: float               # rho0, solid reference density [kg/m3]
    sound_speed: float           # c0 [m/s]
    hugoniot_slope: float        # s (the paper's lambda)
    gruneisen_gamma: float       # gamma0 at rho0; gamma rho is held constant
    specific_heat: float         # c_v [J/(kg K)]
    initial_temperature: float   # T0 [K]

    @classmethod
    def from_scene(cls, scene, body="target"):
        """From a mapping of scene keys to SI floats: a run's resolved scene (reader.Run(...).scene)
        or resolve.default_scene(); the material of `body` ("target" or "flyer"): the bare keys',
        or the material.NAME.KEY values of the material it names."""
        name = scene.get(f"{body}_material", "scene")
        prefix = "" if name == "scene" else f"material.{name}."
        law = scene.get(prefix + "equation_of_state", "mie_gruneisen")
        if law != "mie_gruneisen":
            raise PostError(f"the {body}'s equation of state is {law}: these closed forms are Mie-Grüneisen's "
                            "(the simulator's --check prints the impact state of any)")
        try:
            return cls(**{field: float(scene[prefix + field]) for field in cls.__dataclass_fields__})
        except KeyError as e:
            raise PostError(f"the scene has no key {e}, which the shocked state needs") from None

    @property
    def bulk_modulus(self):
        """K0 = rho0 c0^2 [Pa]."""
        return self.density * self.sound_speed ** 2


def default_material(binary=None):
    """The simulator's default material: its resolved empty scene ($MPMSHOCK or mpmshock on PATH)."""
    return Material.from_scene(default_scene(binary))


# --- the equation of state (include/mpmshock/eos.hpp) -----------------------------------------------

def pole(material):
    """The Us-up Hugoniot's pole: P_H diverges at eta = 1 - J = 1/s."""
    return 1.0 - 1.0 / material.hugoniot_slope


def limiting_compression(material):
    """The smallest J the simulator admits (eos.hpp): 2 % of the way from the pole toward J = 1."""
    J_pole = pole(material)
    return J_pole + 0.02 * (1.0 - J_pole)


def hugoniot_pressure(J, material):
    """P_H = rho0 c0^2 eta / (1 - s eta)^2 in compression, rho0 c0^2 eta in tension [Pa]."""
    eta = 1.0 - J
    if eta <= 0.0:
        return material.bulk_modulus * eta
    return material.bulk_modulus * eta / (1.0 - material.hugoniot_slope * eta) ** 2


def hugoniot_energy(J, material):
    """E_H = P_H (V0 - V) / 2 per unit mass [J/kg]."""
    return 0.5 * hugoniot_pressure(J, material) * (1.0 - J) / material.density


def mie_gruneisen_pressure(J, E, material):
    """P = P_H(J) + gamma0 rho0 (E - E_H(J)) [Pa] (gamma/V = gamma0/V0)."""
    return hugoniot_pressure(J, material) + material.gruneisen_gamma * material.density * (E - hugoniot_energy(J, material))


# --- the temperature model (src/temperature.cpp) ------------------------------------------------------

class HugoniotTemperature:
    """T_H(J) tabulated as src/temperature.cpp does: the Walsh-Christian equation in J,
    dT_H/dJ = c0^2 s (1 - J)^2 / (c_v [(s - 1) - s J]^3) - gamma0 T_H,  T_H(1) = T0,
    integrated by RK4 from J = 1 down to J_min, the limiting compression, 2 % short of the pole."""

    SUBSTEPS = 8

    def __init__(self, material, intervals=4096):
        self.material = material
        self.J_min = limiting_compression(material)
        self.dJ = (1.0 - self.J_min) / intervals
        self.table = self._integrate(intervals)

    def _slope(self, J, T):
        m = self.material
        d = (m.hugoniot_slope - 1.0) - m.hugoniot_slope * J
        e = 1.0 - J
        return m.sound_speed ** 2 * m.hugoniot_slope * e * e / (m.specific_heat * d * d * d) - m.gruneisen_gamma * T

    def _integrate(self, intervals):
        T = self.material.initial_temperature
        table = [T]
        h = -self.dJ / self.SUBSTEPS
        for k in range(1, intervals + 1):
            J = 1.0 - (k - 1) * self.dJ
            for _ in range(self.SUBSTEPS):
                k1 = self._slope(J, T)
                k2 = self._slope(J + 0.5 * h, T + 0.5 * h * k1)
                k3 = self._slope(J + 0.5 * h, T + 0.5 * h * k2)
                k4 = self._slope(J + h, T + h * k3)
                T += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
                J += h
            table.append(T)
        return table

    def hugoniot_temperature(self, J):
        """T_H(J) [K]: the isentrope T0 exp(gamma0 (1 - J)) in tension (J >= 1), infinite past the
        table's end near the pole."""
        if J >= 1.0:
            return self.material.initial_temperature * math.exp(self.material.gruneisen_gamma * (1.0 - J))
        if not J >= self.J_min:
            return math.inf
        u = (1.0 - J) / self.dJ
        k = int(u)
        if k + 1 >= len(self.table):
            return self.table[-1]
        return self.table[k] + (u - k) * (self.table[k + 1] - self.table[k])

    def temperature(self, J, E):
        """T = T_H(J) + (E - E_H(J)) / c_v [K], the code's temperature of a state."""
        return self.hugoniot_temperature(J) + (E - hugoniot_energy(J, self.material)) / self.material.specific_heat


@lru_cache(maxsize=8)
def hugoniot_temperature_table(material):
    """The T_H table of a material, built once (about 0.1 s)."""
    return HugoniotTemperature(material)


# --- shocked states ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class ShockState:
    """The state behind the shock in one body of the symmetric impact at speed v.

    shock_speed is Us, measured relative to the unshocked material (into which it runs);
    front_speed = Us - v is the speed of the front in the lab frame, moving away from the impact
    plane (upward in the target, which moves down at v); the shocked material is at rest."""

    velocity: float         # v = u_p [m/s]
    porosity: float         # delta
    initial_density: float  # rho00 = rho0 / delta [kg/m3]
    J: float                # V / V0 of the shocked material
    density: float          # rho = rho0 / J [kg/m3]
    pressure: float         # P [Pa]
    energy: float           # specific internal energy jump E = u_p^2 / 2 [J/kg]
    temperature: float      # the code's T(J, E) [K]
    shock_speed: float      # Us, relative to the unshocked material [m/s]

    @property
    def front_speed(self):
        """Lab-frame speed of the front away from the impact plane, Us - v [m/s]."""
        return self.shock_speed - self.velocity


def solid_shock(velocity, material):
    """The Rankine-Hugoniot state of a solid body (physics-notes section 3)."""
    up = float(velocity)
    Us = material.sound_speed + material.hugoniot_slope * up
    J = (Us - up) / Us
    energy = 0.5 * up * up
    temperature = hugoniot_temperature_table(material).temperature(J, energy)
    return ShockState(velocity=up, porosity=1.0, initial_density=material.density, J=J,
                      density=material.density * Us / (Us - up), pressure=material.density * Us * up,
                      energy=energy, temperature=temperature, shock_speed=Us)


def compacted_pressure(J, porosity, material):
    """P on the porous Hugoniot at J, from the EOS and the energy jump E = P (V00 - V) / 2:
    P = P_H(J) (1 - gamma0 (1 - J) / 2) / (1 - gamma0 (delta - J) / 2) [Pa]."""
    g = 0.5 * material.gruneisen_gamma
    return hugoniot_pressure(J, material) * (1.0 - g * (1.0 - J)) / (1.0 - g * (porosity - J))


def _bisect(f, lo, hi):
    """The root of f in (lo, hi), f(lo) > 0 > f(hi), to the last bit of J."""
    while True:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            return mid
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid


def porous_shock(velocity, porosity, material):
    """The fully compacted shocked state of a body of porosity delta = rho0 / rho00 >= 1."""
    v, delta = float(velocity), float(porosity)
    if not delta >= 1.0:
        raise PostError(f"porosity {porosity}: must be >= 1 (rho_solid / rho_porous)")
    if not v > 0.0:
        raise PostError(f"velocity {velocity}: must be > 0")
    V0 = 1.0 / material.density
    V00 = delta * V0
    # P(J) grows without bound toward the Hugoniot's limit or, for high porosity, toward the J where
    # the thermal pressure of compaction diverges (gamma0 (delta - J) = 2): the root lies above both.
    J_low = max(limiting_compression(material), delta - 2.0 / material.gruneisen_gamma)

    def excess(J):  # u_p^2 - v^2 on the porous Hugoniot
        return compacted_pressure(J, delta, material) * (V00 - J * V0) - v * v

    J = _bisect(excess, J_low, 1.0)
    V = J * V0
    P = compacted_pressure(J, delta, material)
    energy = 0.5 * P * (V00 - V)
    temperature = hugoniot_temperature_table(material).temperature(J, energy)
    return ShockState(velocity=v, porosity=delta, initial_density=material.density / delta, J=J,
                      density=material.density / J, pressure=P, energy=energy, temperature=temperature,
                      shock_speed=V00 * math.sqrt(P / (V00 - V)))


def bottom_region_arrival_time(state, y1, height):
    """When the mean pressure of a 'bottom Y1 H' region of the target first reaches half the
    shocked pressure [s], with the shock leaving the impact plane at t = 0.

    The region is fixed in the lab; ahead of the front unshocked material (rho00, P = 0) flows in
    at v, behind it shocked material (rho, P) is at rest. Points have equal mass, so the mean is
    mass-weighted and reaches P/2 when the shocked mass equals the unshocked mass in the region:
    rho (y_s - y1) = rho00 (y1 + h - y_s), at the front position y_s = (Us - v) t."""
    rho, rho00 = state.density, state.initial_density
    y_half = y1 + height * rho00 / (rho + rho00)
    return y_half / state.front_speed
