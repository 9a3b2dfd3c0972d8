"""Scenario keys of issue 12: --set can add schema keys; rate vectors; saturation choices; frames."""

import math
import re

import pytest

from detumble.sim.plant import Plant
from detumble.sim.runner import make_law
from detumble.sim.scenario import SCHEMA, ScenarioError, load_scenario, parse_scenario


def test_set_adds_a_rate_vector_replacing_magnitude_and_axis():
    """SC-101: case_a gives magnitude + axis; --set initial.rate.omega_deg_s=[...] adds the vector
    and drops the alternatives it replaces, so the result validates (it did not before)."""
    sc = load_scenario("case_a", settings=["initial.rate.omega_deg_s=[1, -2, 3]"])
    assert sc.omega_BN_B0 == pytest.approx(tuple(math.radians(x) for x in (1, -2, 3)))
    sc = load_scenario("case_a", settings=["initial.rate.omega_rad_s=[0.1, 0.2, 0.3]"])
    assert sc.omega_BN_B0 == (0.1, 0.2, 0.3)
    back = load_scenario("surrey", settings=["initial.rate.magnitude_deg_s=5", "initial.rate.axis=[0, 0, 1]"])
    assert back.omega_BN_B0 == pytest.approx((0.0, 0.0, math.radians(5)))


def test_set_adds_whole_sections_known_to_the_schema():
    """SC-102: a star tracker and reaction wheels can be added to a scenario that has none."""
    sc = load_scenario("default", settings=["spacecraft.reaction_wheels.model=cubesat_1u",
                                            "sensors.star_tracker.noise_about_boresight_arcsec=40"])
    assert len(sc.spacecraft.reaction_wheels) == 3 and sc.spacecraft.reaction_wheels[2].max_torque_nm == 4e-3
    assert sc.star_tracker.noise_about_boresight_arcsec == 40.0
    sc = load_scenario("case_a", settings=["spacecraft.actuators.saturation=scale", "control.saturation=clip",
                                            "orbit.radius_km=7000"])
    assert sc.spacecraft.actuator_saturation == "scale" and sc.control.saturation == "clip"
    assert sc.orbit.altitude_km == pytest.approx(7000 - 6378.1366)


def test_set_still_rejects_unknown_keys_and_lists_what_may_be_added():
    with pytest.raises(ScenarioError, match=re.escape("has no key 'star_trackr' at sensors (keys there: "
                                                      "magnetometer, gyro, accelerometer); keys that can be added "
                                                      "there: star_tracker")):
        load_scenario("default", settings=["sensors.star_trackr.rate_hz=1"])


def test_every_schema_key_is_accepted_by_the_validator():
    """SC-103: the --set schema and the validator agree: no schema key is rejected as unknown (keys
    that depend on another choice - rods, a TLE orbit - are tried in a scenario that makes it)."""
    def leaves(node, path=()):
        for k, v in node.items():
            if isinstance(v, dict):
                yield from leaves(v, path + (k,))
            else:
                yield path + (k,)
    contexts = (("default", ()), ("case_a", ()), ("default", ("orbit.type=tle",)))
    for path in leaves(SCHEMA):
        messages = []
        for name, extra in contexts:
            try:
                load_scenario(name, settings=[*extra, ".".join(path) + "=0"])
                break
            except ScenarioError as exc:
                messages.append(str(exc))
                if "unknown key" not in str(exc):
                    break
        else:
            raise AssertionError((path, messages))


def test_dipole_saturation_clip_versus_scale():
    """SC-104: per-axis clipping keeps each axis at its limit (direction changes); whole-vector
    scaling keeps the direction. Both for the actuators and for the plant-only laws."""
    clip = Plant(load_scenario("case_a"))
    scale = Plant(load_scenario("case_a", settings=["spacecraft.actuators.saturation=scale"]))
    for p in (clip, scale):
        p.apply_dipole_B((0.4, 0.1, -0.05))
    assert clip.m_coils_B == (0.2, 0.1, -0.05)
    assert scale.m_coils_B == pytest.approx((0.2, 0.05, -0.025))
    assert clip.m_commanded_B == scale.m_commanded_B == (0.4, 0.1, -0.05)
    law_clip = make_law("kopt", clip, gain=1.0, saturation="clip")
    law_scale = make_law("kopt", clip, gain=1.0)
    for law in (law_clip, law_scale):
        law.update((2e-5, 0.0, 1e-5), 0.0)
    m_clip = law_clip.update((2e-5, 3e-6, 1e-5), 0.05)
    m_scale = law_scale.update((2e-5, 3e-6, 1e-5), 0.05)
    assert m_clip[1] == -0.2 and abs(m_scale[1]) == 0.2
    assert abs(m_clip[0]) == 0.0 and m_scale[0] == 0.0


def test_attitude_relative_to_the_orbit_frame():
    """SC-105: initial.attitude.frame: orbit makes the quaternion q_BO."""
    q = (math.cos(0.3), math.sin(0.3), 0.0, 0.0)
    sc = load_scenario("surrey", settings=[f"initial.attitude.quaternion=[{q[0]!r}, {q[1]!r}, 0, 0]"])
    assert Plant(sc).q_BO == pytest.approx(q, abs=1e-15)


@pytest.mark.parametrize("text, message", [
    ("orbit:\n  altitude_km: 400\n  radius_km: 7000\n", "give either altitude_km or radius_km"),
    ("orbit:\n  radius_km: 6000\n", "is inside the Earth"),
    ("field:\n  model: orbit_constant\n", "needs the field in the orbit frame"),
    ("integrator_substeps: 0\n", "whole number of RK4 sub-steps"),
    ("initial:\n  rate:\n    omega_rad_s: [1, 2, 3]\n    omega_deg_s: [1, 2, 3]\n", "give one of omega_deg_s"),
    ("sensors:\n  star_tracker:\n    dropout_probability: 2\n", "is a probability"),
    ("sensors:\n  star_tracker:\n    boresight_B: [0, 0, 0]\n", "must not be the zero vector"),
    ("spacecraft:\n  actuators:\n    saturation: squash\n", "expected one of: clip, scale"),
])
def test_new_keys_reject_bad_values(text, message):
    with pytest.raises(ScenarioError, match=message):
        parse_scenario(text)


def test_integrator_substeps_split_the_step():
    """SC-106: with 5 sub-steps of 0.01 s a 0.05 s dynamics step reproduces a 0.01 s plant (1e-13)."""
    a = Plant(load_scenario("surrey", settings=["dynamics_step_s=0.05", "integrator_substeps=5",
                                                  "control.period_s=0.05"]))
    b = Plant(load_scenario("surrey", settings=["dynamics_step_s=0.01"]))
    a.advance_to(2.0)
    b.advance_to(2.0)
    assert a.q_BN == pytest.approx(b.q_BN, abs=1e-12)
