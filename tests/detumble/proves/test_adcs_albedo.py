"""ADCSLS-006…009: the ADCS component's on-board albedo correction (SUN_ALBEDO_CORRECTION; control.albedo)."""

from __future__ import annotations

import math
import random

import pytest

from detumble.components.attitude_types import AlbedoUnavailableReason, AngularVelocity, Ephemeris
from detumble.components.types import MagneticField, Result
from detumble.control.albedo import AlbedoCorrector
from detumble.control.geomagnetic import dipole_field_N
from detumble.proves.adcs import ADCS, EARTH_RADIUS_M
from fprime_lite import CmdResponse, Time, TimeBase
from fprime_lite.model.fw_types import Success
from fprime_lite.svc.health import FwEnabled
from tests.detumble.control.test_albedo import _scene as albedo_scene

START = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1000, 0)
E = 133_000.0
EARTH_ANGLE = 0.7


def _unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def _mul(c, v):
    return tuple(sum(c[i][j] * v[j] for j in range(3)) for i in range(3))


def _angle_deg(a, b):
    return math.degrees(math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(_unit(a), _unit(b), strict=True))))))


def _scene(seed=10, elevation_deg=50.0):
    """control.albedo's test scene (the Sun, a position 500 km up whose zenith is ``elevation_deg`` from it, an
    attitude, the true Sun in B, the six noise-free readings with a = 0.3) in lux, the field in B (gauss) the
    on-board dipole model's at that position."""
    sun_N, r_N, _, c, s_B, _, readings = albedo_scene(random.Random(seed), elevation_deg)
    field_B = tuple(1e4 * b for b in _mul(c, dipole_field_N(r_N, EARTH_ANGLE)))
    return sun_N, r_N, field_B, s_B, [E * r for r in readings]


def make(fprime_harness, scene, *, ephemeris=True, field=True, gyro=True, enable=True):
    """An ADCS on ``scene`` with the ports given connected and SUN_ALBEDO_CORRECTION set; returns the harness and
    a dict whose values the handlers read (``field``: a MagneticField or None for a failing magnetometer)."""
    sun_N, r_N, field_B, _, lux = scene
    comp = ADCS("adcs", base_id=0x1004C000)
    h = fprime_harness(comp, test_time=START)
    for i in range(6):
        h.set_port_handler("visibleLightGet", (lambda i=i: Result(lux[i], Success.SUCCESS)), index=i)
    state = {"ephemeris": Ephemeris(*r_N, 0.0, 0.0, 0.0, EARTH_ANGLE, *sun_N),
             "field": MagneticField(*field_B, START)}
    h.set_port_handler("ephemerisGet", lambda: Result(state["ephemeris"], Success.SUCCESS))
    if not ephemeris:
        comp.output_port("ephemerisGet").disconnect(0)
    if not field:
        comp.output_port("magneticFieldGet").disconnect(0)
    h.set_port_handler("magneticFieldGet", lambda: (
            Result(MagneticField(0.0, 0.0, 0.0, START), Success.FAILURE) if state["field"] is None
            else Result(state["field"], Success.SUCCESS)))
    if not gyro:
        comp.output_port("angularVelocityGet").disconnect(0)
    h.set_port_handler("angularVelocityGet", lambda: Result(AngularVelocity(0.0, 0.0, 0.0), Success.SUCCESS))
    h.load_parameters()
    if enable:
        h.send_command("SUN_ALBEDO_CORRECTION_PRM_SET", FwEnabled.ENABLED)
        h.assert_cmd_response(0, "SUN_ALBEDO_CORRECTION_PRM_SET", CmdResponse.OK)
    return h, state


def test_the_albedo_is_taken_out_of_the_published_vector(fprime_harness):
    """ADCSLS-006: with the Earth's light (a = 0.3, the Sun 50° above the horizon) on the faces the uncorrected
    vector is degrees off; enabled, SunVector (and sunVectorGet) is the true Sun to 0.01° with SunVectorRaw the
    uncorrected one and AlbedoCorrected 1, the field from the on-board dipole model; DISABLED (the default):
    SunVector is the raw vector, AlbedoCorrected 0."""
    scene = _scene()
    s_B = scene[3]
    h, _ = make(fprime_harness, scene)
    h.invoke("run", 0)
    raw, published = h.tlm_values("SunVectorRaw")[-1], h.tlm_values("SunVector")[-1]
    assert _angle_deg(raw, s_B) > 3.0
    assert _angle_deg(published, s_B) < 0.01
    assert h.tlm_values("AlbedoCorrected")[-1] == 1
    got = h.component.sunVectorGet().value
    assert got.valid and _angle_deg((got.x, got.y, got.z), s_B) < 0.01
    h.assert_no_event("AlbedoCorrectionUnavailable")
    off, _ = make(fprime_harness, scene, enable=False)
    assert off.component.SUN_ALBEDO_CORRECTION.value == FwEnabled.DISABLED
    off.invoke("run", 0)
    assert list(off.tlm_values("SunVector")[-1]) == pytest.approx(list(raw), abs=1e-12)
    assert off.tlm_values("AlbedoCorrected")[-1] == 0


@pytest.mark.parametrize("fault, reason", [
    ("no ephemeris port", AlbedoUnavailableReason.NO_EPHEMERIS),
    ("ephemeris not finite", AlbedoUnavailableReason.NO_EPHEMERIS),
    ("no magnetometer port", AlbedoUnavailableReason.NO_MAGNETOMETER),
    ("magnetometer fails", AlbedoUnavailableReason.NO_MAGNETOMETER),
    ("magnetometer stale", AlbedoUnavailableReason.MAGNETOMETER_STALE),
    ("sub-satellite point dark", AlbedoUnavailableReason.EARTH_DARK),
])
def test_a_missing_input_falls_back_to_the_raw_vector_with_an_event(fprime_harness, fault, reason):
    """ADCSLS-007: without an ephemeris (port, or not finite), a magnetometer reading (port, a failed read), with a
    sample older than SUN_FIELD_MAX_AGE, or with the sub-satellite point dark, the raw vector is published (valid,
    AlbedoCorrected 0) and AlbedoCorrectionUnavailable(reason) logged, throttled at 5 over 7 runs; nothing raises."""
    scene = _scene(elevation_deg=-20.0) if fault == "sub-satellite point dark" else _scene()
    h, state = make(fprime_harness, scene, ephemeris=fault != "no ephemeris port",
                    field=fault != "no magnetometer port")
    if fault == "ephemeris not finite":
        state["ephemeris"] = Ephemeris(math.nan, 0.0, 0.0, 0.0, 0.0, 0.0, EARTH_ANGLE, 1.0, 0.0, 0.0)
    elif fault == "magnetometer fails":
        state["field"] = None
    elif fault == "magnetometer stale":
        h.advance_time(3)  # the sample stays stamped START; SUN_FIELD_MAX_AGE 2 s
    for _ in range(7):
        h.invoke("run", 0)
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx(list(h.tlm_values("SunVectorRaw")[-1]), abs=1e-12)
    assert h.tlm_values("AlbedoCorrected")[-1] == 0 and h.tlm_values("SunVectorValid")[-1] == 1
    h.assert_event_count("AlbedoCorrectionUnavailable", 5)
    h.assert_event("AlbedoCorrectionUnavailable", 0, reason)
    h.assert_no_event("HandlerFault")


def test_the_event_is_rearmed_and_a_port_fault_never_leaves_the_rate_group(fprime_harness):
    """ADCSLS-008: a stale magnetometer for 6 runs (5 events), a fresh sample (corrected: the throttle re-armed),
    stale again (one more event); a magnetometer port that raises: the raw vector is still published, the fault
    reported (HandlerFault), the run returns."""
    scene = _scene()
    h, state = make(fprime_harness, scene)
    h.advance_time(3)
    for _ in range(6):
        h.invoke("run", 0)
    h.assert_event_count("AlbedoCorrectionUnavailable", 5)
    state["field"] = MagneticField(*scene[2], h.test_time)
    h.invoke("run", 0)
    assert h.tlm_values("AlbedoCorrected")[-1] == 1
    h.advance_time(3)
    h.invoke("run", 0)
    h.assert_event_count("AlbedoCorrectionUnavailable", 6)

    def broken():
        raise RuntimeError("bus error")

    h.set_port_handler("magneticFieldGet", broken)
    published = len(h.tlm_values("SunVector")), len(h.tlm_values("AlbedoCorrected"))
    h.invoke("run", 0)
    assert (len(h.tlm_values("SunVector")), len(h.tlm_values("AlbedoCorrected"))) == (published[0] + 1,
                                                                                      published[1] + 1)
    assert h.tlm_values("AlbedoCorrected")[-1] == 0
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx(list(h.tlm_values("SunVectorRaw")[-1]), abs=1e-12)
    assert h.events_named("HandlerFault")


def test_the_albedo_model_is_a_ground_parameter(fprime_harness):
    """ADCSLS-009: SUN_ALBEDO_MODEL acts from the next run (a model of 0.4 against a 0.3 Earth leaves the vector
    off by more than 0.3°, back at 0.3 within 0.01°); outside [0, 0.95] or not finite it is refused. (A scene where
    a face sees both the Sun and the Earth: elsewhere too much albedo taken out only darkens faces that see the
    Earth alone.) The correction reads the faces with the component's SUN_LIT_FRACTION, as the raw vector does."""
    scene = _scene()
    s_B = scene[3]
    h, _ = make(fprime_harness, scene)
    h.send_command("SUN_ALBEDO_MODEL_PRM_SET", 0.4)
    h.assert_cmd_response(1, "SUN_ALBEDO_MODEL_PRM_SET", CmdResponse.OK)
    h.invoke("run", 0)
    assert _angle_deg(h.tlm_values("SunVector")[-1], s_B) > 0.3
    h.send_command("SUN_ALBEDO_MODEL_PRM_SET", 0.3)
    h.invoke("run", 0)
    assert _angle_deg(h.tlm_values("SunVector")[-1], s_B) < 0.01
    for k, bad in enumerate((-0.1, 0.96, math.nan)):
        h.send_command("SUN_ALBEDO_MODEL_PRM_SET", bad)
        h.assert_cmd_response(3 + k, "SUN_ALBEDO_MODEL_PRM_SET", CmdResponse.VALIDATION_ERROR)
    assert h.component.SUN_ALBEDO_MODEL.value == 0.3
    # the correction reads the faces with the component's SUN_LIT_FRACTION, as the raw vector does
    sun_N, r_N, field_B, _, lux = scene
    h.send_command("SUN_LIT_FRACTION_PRM_SET", 0.3)
    h.invoke("run", 0)
    want = AlbedoCorrector(0.3, EARTH_RADIUS_M).estimate(
        lux, E, 0.0, r_N=r_N, sun_N=sun_N, field_B=field_B, field_N=dipole_field_N(r_N, EARTH_ANGLE),
        omega_B=(0.0, 0.0, 0.0), lit_fraction=0.3)
    default = AlbedoCorrector(0.3, EARTH_RADIUS_M).estimate(
        lux, E, 0.0, r_N=r_N, sun_N=sun_N, field_B=field_B, field_N=dipole_field_N(r_N, EARTH_ANGLE),
        omega_B=(0.0, 0.0, 0.0))
    assert _angle_deg(want.direction, default.direction) > 1.0
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx(list(want.direction), abs=1e-9)
