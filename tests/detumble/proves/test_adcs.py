"""ADCSLS-001…004: the PROVES ADCS light-sensor component (detumble.proves.adcs) and its Sun vector."""

from __future__ import annotations

import math

import pytest

from detumble.components.types import Result
from detumble.proves.adcs import ADCS
from fprime_lite import CmdResponse, Time, TimeBase
from fprime_lite.model.fw_types import Success

START = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1000, 0)
E = 133_000.0


def make(fprime_harness, lux):
    """An ADCS whose six sensors read ``lux[i]`` (None: the sensor fails)."""
    comp = ADCS("adcs", base_id=0x1004C000)
    h = fprime_harness(comp, test_time=START)
    for i in range(6):
        h.set_port_handler("visibleLightGet", (lambda i=i: Result(lux[i] if lux[i] is not None else 0.0,
                                                                  Success.SUCCESS if lux[i] is not None
                                                                  else Success.FAILURE)), index=i)
    h.load_parameters()
    return h


def test_flight_names_and_ids(fprime_harness):
    """ADCSLS-001: the flight's component (Components.ADCS), port run and visibleLightGet[6]; our channels and
    events numbered from the instance's base id 0x1004C000."""
    h = make(fprime_harness, [0.0] * 6)
    comp = h.component
    assert type(comp).__name__ == "ADCS" and len(comp.visibleLightGet) == 6
    assert comp.channel_id("SunVector") == 0x1004C000
    assert comp.event_id("SunVectorAcquired") == 0x1004C000


def test_run_reads_every_sensor_and_reports_the_sun_vector(fprime_harness):
    """ADCSLS-002: each run calls the six visibleLightGet ports; the Sun at (1, 1, −1)/√3 (three faces lit) is
    SunVector (1, 1, −1)/√3, SunVectorValid 1, LitFaces 3, SunVectorAcquired once; sunVectorGet answers it with
    the run's time; before the first run a vector that is not valid (SUCCESS: nothing seen yet is no failure)."""
    k = E / math.sqrt(3.0)
    h = make(fprime_harness, [k, 0.0, k, 0.0, 0.0, k])
    first = h.component.sunVectorGet()
    assert first.condition == Success.SUCCESS and not first.value.valid and first.value.litFaces == 0
    h.invoke("run", 0)
    h.invoke("run", 0)
    assert sorted(c.index for c in h.from_port("visibleLightGet")) == sorted(list(range(6)) * 2)
    s = 1.0 / math.sqrt(3.0)
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([s, s, -s])
    assert h.tlm_values("SunVectorValid")[-1] == 1 and h.tlm_values("LitFaces")[-1] == 3
    h.assert_event_count("SunVectorAcquired", 1)
    r = h.component.sunVectorGet()
    assert r.condition == Success.SUCCESS and r.value.valid and (r.value.x, r.value.y, r.value.z) == pytest.approx(
        (s, s, -s)) and r.value.timestamp == h.test_time


def test_eclipse_makes_the_vector_invalid_and_says_so(fprime_harness):
    """ADCSLS-003: all faces dark (eclipse): SunVectorLost once, SunVectorValid 0, LitFaces 0, the last valid
    direction kept; light again: SunVectorAcquired."""
    lux = [E, 0.0, 0.0, 0.0, 0.0, 0.0]
    h = make(fprime_harness, lux)
    h.invoke("run", 0)
    lux[0] = 0.0
    h.invoke("run", 0)
    h.invoke("run", 0)
    h.assert_event_count("SunVectorLost", 1)
    assert h.tlm_values("SunVectorValid")[-1] == 0 and h.tlm_values("LitFaces")[-1] == 0
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([1.0, 0.0, 0.0])
    assert not h.component.sunVectorGet().value.valid
    lux[4] = E
    h.invoke("run", 0)
    h.assert_event_count("SunVectorAcquired", 2)
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([0.0, 0.0, 1.0])


def test_a_failed_sensor_is_reported_and_counts_as_dark(fprime_harness):
    """ADCSLS-004: a sensor that fails logs LightSensorReadFailed(index) (throttled at 5) and its face is dark: a
    dark face failing leaves the Sun on X+ valid; a lit face failing (Sun on X+ and Y+, Y+ failed) leaves |s| = 0.71,
    not a full Sun on cosine detectors: not valid, the last valid direction kept."""
    lux = [E, 0.0, 0.0, None, 0.0, 0.0]
    h = make(fprime_harness, lux)
    for _ in range(7):
        h.invoke("run", 0)
    h.assert_event_count("LightSensorReadFailed", 5)
    assert h.events_named("LightSensorReadFailed")[0][0] == 3
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([1.0, 0.0, 0.0])
    assert h.tlm_values("SunVectorValid")[-1] == 1
    k = E / math.sqrt(2.0)
    lux[:4] = [k, 0.0, None, 0.0]
    h.invoke("run", 0)
    assert h.tlm_values("SunVectorValid")[-1] == 0 and h.tlm_values("LitFaces")[-1] == 1
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([1.0, 0.0, 0.0])


def test_lit_threshold_and_magnitude_tolerance_are_ground_parameters(fprime_harness):
    """ADCSLS-005: SUN_LIT_FRACTION and SUN_MAGNITUDE_TOLERANCE act from the next run: the Sun 2.3° from +Z (the
    side face at 4 % of full Sun) is read exactly at the default 2 % and as +Z (the dead zone) at 5 %; a Sun of 0.8
    full is valid at ±25 % and not at ±10 % (SunVectorLost); values out of range are refused (VALIDATION_ERROR)."""
    tilt = math.radians(2.3)
    h = make(fprime_harness, [E * math.sin(tilt), 0.0, 0.0, 0.0, E * math.cos(tilt), 0.0])
    h.invoke("run", 0)
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([math.sin(tilt), 0.0, math.cos(tilt)], abs=1e-12)
    h.send_command("SUN_LIT_FRACTION_PRM_SET", 0.05)
    h.assert_cmd_response(0, "SUN_LIT_FRACTION_PRM_SET", CmdResponse.OK)
    h.invoke("run", 0)
    assert list(h.tlm_values("SunVector")[-1]) == pytest.approx([0.0, 0.0, 1.0], abs=1e-12)
    h = make(fprime_harness, [0.0, 0.0, 0.0, 0.0, 0.8 * E, 0.0])
    h.invoke("run", 0)
    assert h.tlm_values("SunVectorValid")[-1] == 1
    h.send_command("SUN_MAGNITUDE_TOLERANCE_PRM_SET", 0.1)
    h.invoke("run", 0)
    assert h.tlm_values("SunVectorValid")[-1] == 0
    h.assert_event_count("SunVectorLost", 1)
    for k, (name, bad) in enumerate((("SUN_LIT_FRACTION", 0.0), ("SUN_LIT_FRACTION", 0.6),
                                     ("SUN_MAGNITUDE_TOLERANCE", 1.0), ("SUN_MAGNITUDE_TOLERANCE", math.nan))):
        h.send_command(f"{name}_PRM_SET", bad)
        h.assert_cmd_response(1 + k, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)
    assert h.component.SUN_MAGNITUDE_TOLERANCE.value == 0.1 and h.component.SUN_LIT_FRACTION.value == 0.02
