"""The example HeaterController driven end to end through the port harness."""

import importlib.util
import math
import pathlib
import sys

import pytest

from fprime_lite import CmdResponse, ParamValid, Severity, Time, TimeBase

_PATH = pathlib.Path(__file__).parents[2] / "examples" / "heater_controller.py"
_spec = importlib.util.spec_from_file_location("heater_controller", _PATH)
heater = importlib.util.module_from_spec(_spec)
sys.modules[_spec.name] = heater  # dataclass-based structs need their module registered
_spec.loader.exec_module(heater)


@pytest.fixture
def h(fprime_harness):
    harness = fprime_harness(heater.HeaterController("heater", base_id=0x2000),
                             test_time=Time(TimeBase.TB_WORKSTATION_TIME, 0, 100, 0))
    harness.load_parameters()
    return harness


def reading(celsius, valid=True):
    return heater.TemperatureReading(celsius=celsius, valid=valid)


def test_disabled_controller_reads_nothing(h):
    h.invoke("run", 0)
    h.assert_from_port_history_size(0)
    h.assert_events_size(0)


def test_heater_cycles_with_hysteresis(h):
    h.send_command("SET_ENABLED", True, cmd_seq=7)
    h.assert_cmd_response(0, "SET_ENABLED", CmdResponse.OK, cmd_seq=7)
    temperatures = iter([19.0, 17.5, 18.5, 20.0, 19.0])
    h.set_port_handler("temperatureGet", lambda: reading(next(temperatures)))
    for _ in range(5):
        h.invoke("run", 0)
        h.advance_time(1)
    # 19.0 is inside the band (18..20): stays off; 17.5 < 18 turns on; 18.5 stays on;
    # 20.0 >= setpoint turns off; 19.0 stays off.
    assert [c.args for c in h.from_port("heaterSet")] == [(True,), (False,)]
    h.assert_event("HeaterOn", 0, 17.5)
    h.assert_event("HeaterOff", 0, 20.0)
    assert h.tlm_values("Temperature") == [19.0, 17.5, 18.5, 20.0, 19.0]
    # State is "on change": OFF, ON, OFF.
    assert h.tlm_values("State") == [heater.HeaterState.OFF, heater.HeaterState.ON, heater.HeaterState.OFF]
    assert h.events[0].time == Time(TimeBase.TB_WORKSTATION_TIME, 0, 101, 0)
    assert h.events[0].severity == Severity.ACTIVITY_LO
    assert h.text_events[0].text == "(heater) HeaterOn: Heater on at 17.5 C"


def test_sensor_failure_is_throttled_and_switches_off(h):
    h.send_command("SET_ENABLED", True)
    h.set_port_return("temperatureGet", reading(float("nan"), valid=False))
    for _ in range(5):
        h.invoke("run", 0)
    h.assert_event_count("SensorFailed", 3)
    h.set_port_return("temperatureGet", reading(15.0))
    h.invoke("run", 0)
    h.set_port_return("temperatureGet", reading(float("nan"), valid=False))
    h.invoke("run", 0)
    h.assert_event_count("SensorFailed", 4)  # a good read cleared the throttle
    assert h.from_port("heaterSet")[-1].args == (False,)


def test_parameters_load_set_and_save(h):
    assert h.component.SETPOINT.validity == ParamValid.DEFAULT
    h.param_set("SETPOINT", 25.0)
    h.load_parameters()
    assert h.component.SETPOINT.value == 25.0
    assert h.component.SETPOINT.validity == ParamValid.VALID
    h.param_set("HYSTERESIS", 0.0)
    h.param_send("HYSTERESIS", cmd_seq=3)
    h.assert_cmd_response(0, "HYSTERESIS_PRM_SET", CmdResponse.OK, cmd_seq=3)
    h.send_command("SET_ENABLED", True)
    h.assert_cmd_response(1, "SET_ENABLED", CmdResponse.VALIDATION_ERROR)
    h.assert_event("EnableRefused", 0, 0.0)
    h.param_save("SETPOINT")
    assert h.saved_params == [("SETPOINT", h.component.param_id("SETPOINT"), 25.0)]


def test_disabling_switches_heater_off(h):
    h.send_command("SET_ENABLED", True)
    h.set_port_return("temperatureGet", reading(10.0))
    h.invoke("run", 0)
    h.send_command("SET_ENABLED", False)
    assert [c.args for c in h.from_port("heaterSet")] == [(True,), (False,)]
    off = h.events_named("HeaterOff")[0][0]
    assert math.isnan(off)
