"""The exact shocked states of mpmshock_post.hugoniot: the solid one against physics-notes section 3,
the porous one against its own jump conditions and the code's EOS, and delta = 1 against the solid.

    /usr/bin/python3 -m pytest tests/python/test_hugoniot_theory.py [--mpmshock BUILD/src/mpmshock]
"""

import math

import pytest

from mpmshock_post import PostError, hugoniot
from mpmshock_post.scene import Scene

SPEEDS = (250.0, 500.0, 1000.0, 1500.0, 2000.0, 3000.0)
POROSITIES = (1.03, 1.1, 1.4)

# physics-notes section 3: v -> (Us m/s, P Pa, rho kg/m3, T_H K), to the digits the table gives.
NOTES = {500.0: (6020.0, 8.127e9, 2944.6, 364.3),
         1000.0: (6690.0, 18.063e9, 3174.5, 487.7),
         2000.0: (8030.0, 43.362e9, 3595.5, 1104.4)}


@pytest.fixture(scope="module")
def material(mpmshock):
    return hugoniot.default_material(mpmshock)


def relative(a, b):
    return abs(a - b) / max(abs(a), abs(b))


def test_material_is_the_simulators_default(material):
    assert material == hugoniot.Material(density=2700.0, sound_speed=5350.0, hugoniot_slope=1.34,
                                         gruneisen_gamma=1.96, specific_heat=880.0, initial_temperature=300.0)


def test_material_from_a_resolved_scene(material):
    text = ("density = 2700 kg/m3\nsound_speed = 5350 m/s\nhugoniot_slope = 1.34\ngruneisen_gamma = 1.96\n"
            "specific_heat = 880 J/(kg K)\ninitial_temperature = 300 K\nvelocity = 1000 m/s\n")
    assert hugoniot.Material.from_scene(Scene(text, "test")) == material
    with pytest.raises(PostError, match="sound_speed"):
        hugoniot.Material.from_scene(Scene("density = 2700 kg/m3\n", "test"))


@pytest.mark.parametrize("v", sorted(NOTES))
def test_solid_matches_physics_notes(material, v):
    Us, P, rho, T_H = NOTES[v]
    state = hugoniot.solid_shock(v, material)
    assert state.shock_speed == pytest.approx(Us, rel=1e-12)
    assert state.front_speed == pytest.approx(Us - v, rel=1e-12)
    assert state.pressure == pytest.approx(P, rel=1e-12)
    assert abs(state.density - rho) <= 0.05
    assert abs(state.temperature - T_H) <= 0.05


@pytest.mark.parametrize("v", SPEEDS)
def test_solid_lies_on_the_codes_hugoniot(material, v):
    state = hugoniot.solid_shock(v, material)
    assert state.pressure == pytest.approx(hugoniot.hugoniot_pressure(state.J, material), rel=1e-12)
    assert state.energy == pytest.approx(hugoniot.hugoniot_energy(state.J, material), rel=1e-12)
    assert state.temperature == pytest.approx(hugoniot.hugoniot_temperature_table(material).hugoniot_temperature(state.J),
                                              rel=1e-12)


@pytest.mark.parametrize("v", SPEEDS)
def test_porosity_one_is_the_solid(material, v):
    solid, porous = hugoniot.solid_shock(v, material), hugoniot.porous_shock(v, 1.0, material)
    for name in ("J", "density", "pressure", "energy", "temperature", "shock_speed", "front_speed"):
        assert relative(getattr(porous, name), getattr(solid, name)) <= 1e-12, name


@pytest.mark.parametrize("delta", (1.0,) + POROSITIES)
@pytest.mark.parametrize("v", SPEEDS)
def test_porous_jump_conditions(material, v, delta):
    """Mass, momentum and energy across the shock, in the frame of the unshocked material, and the
    code's EOS in the shocked state."""
    s = hugoniot.porous_shock(v, delta, material)
    V00, V = 1.0 / s.initial_density, 1.0 / s.density
    assert s.initial_density == pytest.approx(material.density / delta, rel=1e-15)
    assert relative(s.initial_density * s.shock_speed, s.density * (s.shock_speed - v)) <= 1e-10   # mass
    assert relative(s.pressure, s.initial_density * s.shock_speed * v) <= 1e-10                     # momentum
    assert relative(s.energy, 0.5 * s.pressure * (V00 - V)) <= 1e-10                                # energy (Hugoniot)
    assert relative(s.energy, 0.5 * v * v) <= 1e-10                                                 # energy (= u_p^2/2)
    assert relative(s.pressure, hugoniot.mie_gruneisen_pressure(s.J, s.energy, material)) <= 1e-10  # EOS
    assert s.J < 1.0


@pytest.mark.parametrize("delta", (1.0,) + POROSITIES)
def test_pressure_grows_with_speed(material, delta):
    pressures = [hugoniot.porous_shock(v, delta, material).pressure for v in SPEEDS]
    assert all(a < b for a, b in zip(pressures, pressures[1:])), pressures


@pytest.mark.parametrize("delta", POROSITIES)
@pytest.mark.parametrize("v", SPEEDS)
def test_porous_is_hotter_and_less_dense(material, v, delta):
    solid, porous = hugoniot.solid_shock(v, material), hugoniot.porous_shock(v, delta, material)
    assert porous.temperature > solid.temperature
    assert porous.density < solid.density
    assert porous.pressure < solid.pressure


def test_more_porous_is_hotter(material):
    temperatures = [hugoniot.porous_shock(1000.0, delta, material).temperature for delta in (1.0,) + POROSITIES]
    assert all(a < b for a, b in zip(temperatures, temperatures[1:])), temperatures


def test_temperature_table_reproduces_the_code(material):
    """T_H = T0 at J = 1, the isentrope T0 exp(gamma0 (1 - J)) in tension, infinite past the table;
    T = T_H on the Hugoniot."""
    table = hugoniot.hugoniot_temperature_table(material)
    assert table.hugoniot_temperature(1.0) == 300.0
    assert table.hugoniot_temperature(1.05) == pytest.approx(300.0 * math.exp(1.96 * -0.05), rel=1e-15)
    assert math.isinf(table.hugoniot_temperature(0.5 * table.J_min))
    assert table.J_min == pytest.approx(1.0 - 0.98 / 1.34, rel=1e-15)
    J = 0.85
    assert table.temperature(J, hugoniot.hugoniot_energy(J, material)) == table.hugoniot_temperature(J)
    assert table.temperature(J, hugoniot.hugoniot_energy(J, material) + 880.0) == pytest.approx(
        table.hugoniot_temperature(J) + 1.0, rel=1e-12)


def test_arrival_time_in_a_bottom_region(material):
    """A thin region is reached when the front is there; a thick one when half its mass is shocked."""
    state = hugoniot.porous_shock(1000.0, 1.4, material)
    assert hugoniot.bottom_region_arrival_time(state, 300e-6, 1e-12) == pytest.approx(300e-6 / state.front_speed, rel=1e-8)
    t = hugoniot.bottom_region_arrival_time(state, 300e-6, 100e-6)
    y_front = state.front_speed * t
    shocked, unshocked = state.density * (y_front - 300e-6), state.initial_density * (400e-6 - y_front)
    assert shocked == pytest.approx(unshocked, rel=1e-12)


def test_bad_input(material):
    with pytest.raises(PostError, match="porosity"):
        hugoniot.porous_shock(1000.0, 0.9, material)
    with pytest.raises(PostError, match="velocity"):
        hugoniot.porous_shock(0.0, 1.1, material)


def test_material_of_a_body_that_names_one():
    """A body that names a material (target_material = copper) takes its material.NAME.KEY values,
    as scene.txt lists them; one that does not, the bare keys'."""
    scene = {"target_material": "copper", "flyer_material": "scene", "density": 2700.0, "sound_speed": 5350.0,
             "hugoniot_slope": 1.34, "gruneisen_gamma": 1.96, "specific_heat": 880.0, "initial_temperature": 300.0,
             "material.copper.density": 8930.0, "material.copper.sound_speed": 3940.0,
             "material.copper.hugoniot_slope": 1.489, "material.copper.gruneisen_gamma": 2.02,
             "material.copper.specific_heat": 383.0, "material.copper.initial_temperature": 300.0}
    assert hugoniot.Material.from_scene(scene).density == 8930.0
    assert hugoniot.Material.from_scene(scene).hugoniot_slope == 1.489
    assert hugoniot.Material.from_scene(scene, "flyer").density == 2700.0
    with pytest.raises(PostError, match="material.copper.specific_heat"):
        del scene["material.copper.specific_heat"]
        hugoniot.Material.from_scene(scene)
