"""DetumbleManager: parameter validation and visible faults (issue #16).

Time is the harness's test time; ``tick`` runs the component once and advances 20 ms (50 Hz).
Rates in deg/s, fields in gauss.
"""

from __future__ import annotations

import math

import pytest

from detumble.components.detumble_manager import DetumbleManager
from detumble.components.types import (DetumbleMode, DetumbleState, MagneticField, Result, Success, SystemMode,
                                       TimeIntervalValue)
from fprime_lite import CmdResponse, ParamValid, Severity, Time, TimeBase

BASE = 0x1005A000
TICK_US = 20_000
START = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1000, 0)
COILS = ("xPlus", "xMinus", "yPlus", "yMinus", "zMinus")
STARTS = [f"{c}Start" for c in COILS]
STOPS = [f"{c}Stop" for c in COILS]
#: Every flight parameter with a physical bound (the enums, shapes and the axis have none).
BOUNDED = ("BDOT_MAX_THRESHOLD", "DEADBAND_UPPER_THRESHOLD", "DEADBAND_LOWER_THRESHOLD", "GAIN",
           "X_TURNS", "Y_TURNS", "Z_TURNS",
           *(f"{coil}_{what}" for coil in ("X_PLUS", "X_MINUS", "Y_PLUS", "Y_MINUS")
             for what in ("VOLTAGE", "RESISTANCE", "LENGTH", "WIDTH")),
           "Z_MINUS_VOLTAGE", "Z_MINUS_RESISTANCE", "Z_MINUS_DIAMETER")


class Plant:
    """Stub providers: 10 deg/s (B-dot) and a field changing linearly at −1 mG/s on each axis."""

    def __init__(self, h):
        self.h = h
        self.gyro_fault: Exception | None = None

    def angular(self, unit):
        if self.gyro_fault is not None:
            raise self.gyro_fault
        return Result(10.0, Success.SUCCESS)

    def field(self):
        t = self.h.test_time
        s = (t.total_us - START.total_us) / 1e6
        return Result(MagneticField(x=0.2 - 1e-3 * s, y=-0.1 - 1e-3 * s, z=0.35 - 1e-3 * s, timestamp=t),
                      Success.SUCCESS)


def make(fprime_harness, params=None):
    comp = DetumbleManager("detumbleManager", base_id=BASE)
    h = fprime_harness(comp, test_time=START, unconnected=("dipoleMomentGet",))
    for port in STARTS + STOPS:
        h.set_port_return(port, Success.SUCCESS)
    h.set_port_return("getSystemMode", SystemMode.NORMAL)
    plant = Plant(h)
    h.set_port_handler("angularVelocityMagnitudeGet", plant.angular)
    h.set_port_handler("magneticFieldGet", plant.field)
    h.set_port_return("magneticFieldSamplingPeriodGet",
                      Result(TimeIntervalValue(seconds=0, useconds=10_000), Success.SUCCESS))
    for name, value in (params or {}).items():
        h.param_set(name, value)
    h.load_parameters()
    h.plant = plant
    return h


def tick(h, n=1):
    for _ in range(n):
        h.invoke("run", 0)
        h.advance_time(useconds=TICK_US)


def run_until(h, state, limit=200):
    for _ in range(limit):
        if h.component.state == state:
            return
        tick(h)
    raise AssertionError(f"never reached {state.name}; in {h.component.state.name}")


def started_levels(h, since):
    return [c.args[0] for c in h.port_calls[since:] if c.port.endswith("Start")]


@pytest.fixture
def h(fprime_harness):
    return make(fprime_harness)


def set_raw(h, name, value):
    """PRM_SET ``name`` to ``value`` as the ground would (serialised with the parameter's type)."""
    decl = h.component.spec.param(name)
    h.send_raw_command(h.component.opcode(f"{name}_PRM_SET"), decl.type.serialize(value))


# --- validation ---------------------------------------------------------------------------------

def test_huge_coil_diameter_is_refused_and_bdot_keeps_driving(h):
    """PRM-016-1 (#16 finding 1): Z_MINUS_DIAMETER_PRM_SET 1e308 answers VALIDATION_ERROR with a
    ParamSetRefused event, the diameter stays 0.05755 m, and the next B-dot cycle drives the coils
    without a handler fault (before: OK, then an OverflowError on every cycle, coils never on)."""
    set_raw(h, "Z_MINUS_DIAMETER", 1e308)
    h.assert_cmd_response(0, "Z_MINUS_DIAMETER_PRM_SET", CmdResponse.VALIDATION_ERROR)
    assert h.component.Z_MINUS_DIAMETER.value == 0.05755
    assert h.events_named("ParamSetRefused") == [("Z_MINUS_DIAMETER", "1e+308 is above the maximum 1.0")]
    h.assert_no_event("ZMinusDiameterParamSet")
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    since = len(h.port_calls)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    tick(h)
    assert any(level != 0 for level in started_levels(h, since))
    assert h.component.handler_faults == 0


@pytest.mark.parametrize("name", BOUNDED)
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, -1.0, 1e308])
def test_every_bounded_parameter_refuses_non_finite_and_out_of_range(h, name, bad):
    """PRM-016-2: NaN, ±inf, a negative value and 1e308 are refused for every dimension, turns
    count, voltage, resistance, threshold and the gain: VALIDATION_ERROR, the event, no change."""
    before = h.component.params[name].value
    set_raw(h, name, bad)
    h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)
    assert h.component.params[name].value == before
    assert [e.name for e in h.events] == ["ParamSetRefused"] and h.events[0].args[0] == name
    assert h.events[0].severity == Severity.WARNING_LO


@pytest.mark.parametrize("name", ["X_TURNS", "Z_MINUS_RESISTANCE", "Y_PLUS_VOLTAGE"])
def test_zero_turns_resistance_or_voltage_is_refused(h, name):
    """PRM-016-3: 0 turns, 0 ohm or 0 V (a coil that cannot make a dipole or a division by zero)
    is refused."""
    set_raw(h, name, 0.0)
    h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)


@pytest.mark.parametrize("name, value", [("COOLDOWN_DURATION", TimeIntervalValue(seconds=2 * 86400, useconds=0)),
                                         ("TORQUE_DURATION", TimeIntervalValue(seconds=3600, useconds=0)),
                                         ("TORQUE_DURATION", TimeIntervalValue(seconds=0, useconds=0))])
def test_durations_of_days_or_zero_torque_are_refused(h, name, value):
    """PRM-016-4: a cooldown over 600 s, a torque period over 60 s or of zero is refused."""
    set_raw(h, name, value)
    h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)
    h.assert_event_count("ParamSetRefused", 1)


def test_an_accepted_value_is_echoed_by_the_framework(h):
    """PRM-016-5: a value inside its range answers OK and is echoed (ParamSet event + Param channel)."""
    h.clear_history()
    set_raw(h, "GAIN", 5.0)
    h.assert_cmd_response(0, "GAIN_PRM_SET", CmdResponse.OK)
    assert [e.name for e in h.events] == ["GainParamSet"] and h.events[0].args == (5.0,)
    assert h.tlm_values("GainParam") == [5.0]


def test_an_invalid_parameter_file_value_loads_the_default_and_says_so(fprime_harness):
    """PRM-016-6: a PrmDb value of 1e308 m for Z_MINUS_DIAMETER (e.g. saved by an older build)
    is not used: the default 0.05755 m is, its validity is DEFAULT, and ParamDefaulted says why."""
    h = make(fprime_harness, params={"Z_MINUS_DIAMETER": 1e308, "GAIN": 4.0})
    assert h.component.Z_MINUS_DIAMETER.value == 0.05755
    assert h.component.Z_MINUS_DIAMETER.validity == ParamValid.DEFAULT
    assert h.component.GAIN.value == 4.0 and h.component.GAIN.validity == ParamValid.VALID
    assert h.events_named("ParamDefaulted") == [("Z_MINUS_DIAMETER", "1e+308 is above the maximum 1.0")]
    assert h.events[0].severity == Severity.WARNING_HI
    assert h.tlm_values("ZMinusDiameterParam") == [0.05755]


# --- faults in the cycle ------------------------------------------------------------------------

def test_a_fault_in_the_cycle_stops_the_coils_reports_and_retries(h):
    """FLT-016-1: after one B-dot cycle the gyro provider raises: on that tick the coils are
    commanded off, HandlerFault(run, RuntimeError: …) is emitted and HandlerFaults reads 1; once
    the provider answers again the next cycle reads it and drives again (never silence)."""
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    h.plant.gyro_fault = RuntimeError("gyro bus fault")
    since = len(h.port_calls)
    tick(h)  # the read raises
    assert [c.port for c in h.port_calls[since:] if c.port.endswith("Stop")] == STOPS
    assert h.events_named("HandlerFault") == [("run", "RuntimeError: gyro bus fault")]
    assert h.tlm_values("HandlerFaults") == [1]
    assert h.component.state == DetumbleState.COOLDOWN and h.component.handler_faults == 1
    h.plant.gyro_fault = None
    since = len(h.port_calls)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    tick(h)
    assert any(level != 0 for level in started_levels(h, since))
    assert h.component.handler_faults == 1


def test_repeated_faults_are_throttled_but_always_counted(h):
    """FLT-016-2: a fault on every cycle gives 10 HandlerFault events (the throttle) and a
    HandlerFaults channel that keeps counting (25 after 25 faults)."""
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.plant.gyro_fault = ValueError("stuck")
    faults = 0
    for _ in range(400):
        tick(h)
        faults = h.component.handler_faults
        if faults == 25:
            break
    assert faults == 25
    h.assert_event_count("HandlerFault", 10)
    assert h.tlm_values("HandlerFaults")[-1] == 25


@pytest.mark.parametrize("bad", [-1.0, math.nan, math.inf, 1e308])
def test_bdot_detumble_gain_is_bounded(fprime_harness, bad):
    """PRM-016-14: BDotDetumble's Gain refuses a negative (anti-damping), non-finite or huge value."""
    from detumble.components.bdot_detumble import BDotDetumble

    h = fprime_harness(BDotDetumble("bdotDetumble"))
    h.load_parameters()
    h.send_raw_command(h.component.opcode("GAIN_PRM_SET"), h.component.spec.param("Gain").type.serialize(bad))
    h.assert_cmd_response(0, "GAIN_PRM_SET", CmdResponse.VALIDATION_ERROR)
    assert h.component.Gain.value == 1.0 and h.events_named("ParamSetRefused")[0][0] == "Gain"
