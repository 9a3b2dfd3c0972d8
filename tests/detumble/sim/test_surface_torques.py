"""Drag and solar-radiation-pressure torques (SIM-ENV-001…005; docs/studies/environment_torques.md)."""

import dataclasses
import math

import pytest

from detumble.sim.plant import Plant
from detumble.sim.scenario import ScenarioError, load_scenario
from detumble.sim.torques import (ATMOSPHERE_TABLE, SOLAR_PRESSURE_N_M2, BoxSurfaces, atmosphere_density)


def test_atmosphere_density_follows_the_table():
    """SIM-ENV-001: the band's base density at its base altitude, the exponential inside the band (420 km:
    3.725e-12 e^(−20/58.515)), and each band within 15 % of the next one's base (the table's own joins)."""
    assert atmosphere_density(400e3) == pytest.approx(3.725e-12, rel=1e-12)
    assert atmosphere_density(420e3) == pytest.approx(3.725e-12 * math.exp(-20.0 / 58.515), rel=1e-12)
    for (h0, rho0, scale), (h1, rho1, _) in zip(ATMOSPHERE_TABLE, ATMOSPHERE_TABLE[1:], strict=False):
        assert rho0 * math.exp(-(h1 - h0) / scale) == pytest.approx(rho1, rel=0.15)


def test_a_symmetric_box_feels_no_torque_and_an_offset_gives_the_lever_arm():
    """SIM-ENV-002: a cube about its centre of mass: zero drag and solar torque from any direction; with the centre
    of pressure offset d the torque is ``d × F`` with the closed-form force (flow along −x: F = −½ρC_D A v² x̂ on the
    +x face; Sun along +x, absorbing: F = −P A x̂); specular reflection adds ``2 ε c² P A`` along the normal."""
    cube = BoxSurfaces((0.1, 0.1, 0.1), (0.0, 0.0, 0.0))
    for d in ((1.0, 0.0, 0.0), (0.6, -0.48, 0.64), (-0.36, 0.48, 0.8)):
        assert max(abs(c) for c in cube.drag_torque(tuple(7600.0 * x for x in d), 4e-12)) < 1e-22
        assert max(abs(c) for c in cube.solar_torque(d, SOLAR_PRESSURE_N_M2)) < 1e-22
    box = BoxSurfaces((0.1, 0.1, 0.1135), (0.0, 0.0, 0.01), drag_coefficient=2.2)
    rho, v = 3.0e-12, 7600.0
    f = 0.5 * rho * 2.2 * 0.1 * 0.1135 * v * v
    assert box.drag_torque((v, 0.0, 0.0), rho) == pytest.approx((0.0, -0.01 * f, 0.0), rel=1e-12, abs=1e-24)
    p = SOLAR_PRESSURE_N_M2
    assert box.solar_torque((1.0, 0.0, 0.0), p) == pytest.approx((0.0, -0.01 * p * 0.01135, 0.0), rel=1e-12)
    shiny = BoxSurfaces((0.1, 0.1, 0.1135), (0.0, 0.0, 0.01), specular_reflectivity=0.5)
    assert shiny.solar_torque((1.0, 0.0, 0.0), p)[1] == pytest.approx(-0.01 * p * 0.01135 * (0.5 + 1.0), rel=1e-12)


def _plant(settings):
    sc = load_scenario("default", settings=["field.model=none", "spacecraft.gravity_gradient=false",
                                            "initial.rate.magnitude_deg_s=0", *settings])
    return Plant(sc, seed=1, implementation="python")


def test_the_plant_integrates_the_surface_torque_into_angular_momentum():
    """SIM-ENV-003: with drag and solar pressure the only torques (no field, no gravity gradient), the change in
    the inertial angular momentum over 200 steps equals the sum of the held torques × dt (in N) to 1e-6."""
    p = _plant(["spacecraft.surfaces.drag=true", "spacecraft.surfaces.solar_pressure=true",
                "spacecraft.surfaces.cp_offset_m=[0.01, -0.02, 0.03]"])
    from detumble.sim.vec import rotate_b_to_n
    h0 = p.total_angular_momentum_N()
    acc = [0.0, 0.0, 0.0]
    for _ in range(200):
        q = p.q_BN
        p.step_ns(20_000_000)
        t = rotate_b_to_n(q, p.surface_torque_B)
        acc = [a + 0.02 * c for a, c in zip(acc, t, strict=True)]
    dh = [a - b for a, b in zip(p.total_angular_momentum_N(), h0, strict=True)]
    assert max(abs(c) for c in acc) > 1e-10
    for i in range(3):
        assert dh[i] == pytest.approx(acc[i], rel=1e-6, abs=1e-16)


def test_solar_pressure_is_zero_in_the_earth_shadow():
    """SIM-ENV-004: over one orbit the solar torque is zero exactly while the spacecraft is in umbra and not zero
    outside it (the default orbit sees an eclipse)."""
    from detumble.sim.sun import in_umbra, sun_direction_N
    from detumble.sim.epoch import julian_date
    p = _plant(["spacecraft.surfaces.solar_pressure=true", "spacecraft.surfaces.cp_offset_m=[0.0, 0.0, 0.02]"])
    jd0 = julian_date(p.scenario.epoch)
    shadow = lit = 0
    for _ in range(60):
        t = p.t
        s, _ = sun_direction_N(jd0 + t / 86400.0)
        dark = in_umbra(p.r_N, s, p.scenario.orbit.earth_radius_m)
        p.step_ns(20_000_000)
        zero = p.surface_torque_B == (0.0, 0.0, 0.0)
        assert zero == dark
        shadow += dark
        lit += not dark
        p.advance_to(p.t + 100.0)
    assert shadow > 5 and lit > 5


def test_bad_surface_data_is_refused_with_its_key():
    """SIM-ENV-005: a zero edge or a reflectivity above 1 is refused naming the key."""
    with pytest.raises(ScenarioError, match="size_m"):
        load_scenario("default", settings=["spacecraft.surfaces.size_m=[0.1, 0.0, 0.1]"])
    with pytest.raises(ScenarioError, match="specular_reflectivity"):
        load_scenario("default", settings=["spacecraft.surfaces.specular_reflectivity=1.5"])
    assert dataclasses.asdict(load_scenario("default").spacecraft.surfaces)["drag"] is False
