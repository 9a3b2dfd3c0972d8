"""Ina219Manager as flown: system and solar rails of the simulated electrical system."""

import pytest

from detumble.proves.ina219_manager import CURRENT_LSB_A, VOLTAGE_LSB_V, Ina219Manager
from fprime_lite import CmdResponse, Severity


@pytest.fixture
def rig(fprime_harness, make_craft):
    craft = make_craft()
    craft.clock.set_us(60_000_000)   # one minute of flight: the EPS has stepped
    h = fprime_harness(Ina219Manager("ina219SysManager", craft, "system", base_id=0x10039000))
    h.set_test_time(craft.now())
    return h, craft


def test_system_rail_reads_bus_voltage_load_current_and_power(rig):
    """INA-SYS-001: voltageGet / currentGet / powerGet return the bus voltage, the load current and
    their product, quantised to 4 mV and 0.1 mA, and write Voltage / Current / Power."""
    h, craft = rig
    eps = craft.power
    v, i, p = h.invoke("voltageGet"), h.invoke("currentGet"), h.invoke("powerGet")
    assert v == pytest.approx(eps.bus_v, abs=VOLTAGE_LSB_V / 2)
    assert i == pytest.approx(eps.load_w / eps.bus_v, abs=CURRENT_LSB_A / 2)
    assert p == pytest.approx(v * i)
    assert h.tlm_values("Voltage") == [v] and h.tlm_values("Current") == [i] and h.tlm_values("Power") == [p]


def test_solar_rail(make_craft, fprime_harness):
    """INA-SOL-001: the solar INA219 reads the array output (0 in eclipse)."""
    craft = make_craft()
    craft.clock.set_us(10_000_000)
    h = fprime_harness(Ina219Manager("ina219SolManager", craft, "solar"))
    p = h.invoke("powerGet")
    assert p == pytest.approx(craft.power.solar_w, rel=1e-3, abs=1e-3)
    assert (p == 0.0) == craft.power.eclipse


@pytest.mark.parametrize("command, event, port", [("GetVoltage", "VoltageReading", "voltageGet"),
                                                  ("GetCurrent", "CurrentReading", "currentGet"),
                                                  ("GetPower", "PowerReading", "powerGet")])
def test_commands_log_the_reading(rig, command, event, port):
    """INA-CMD-001: GetVoltage / GetCurrent / GetPower log the reading (ACTIVITY_LO) and answer OK."""
    h, _ = rig
    h.send_command(command, cmd_seq=2)
    h.assert_cmd_response(0, command, CmdResponse.OK, cmd_seq=2)
    h.assert_event(event, 0, h.invoke(port))
    assert h.events[0].severity == Severity.ACTIVITY_LO


def test_not_ready_returns_zero_with_a_throttled_warning(rig):
    """INA-NR-001: a device that is not ready returns 0 and logs DeviceNotReady (WARNING_HI, throttled 5)."""
    h, _ = rig
    h.send_command("SIM_SET_NOT_READY", True)
    for _ in range(8):
        assert h.invoke("voltageGet") == 0.0
    h.assert_event_count("DeviceNotReady", 5)
    assert h.events_named("DeviceNotReady") and h.events[0].severity == Severity.WARNING_HI
    h.send_command("SIM_SET_NOT_READY", False)
    assert h.invoke("voltageGet") > 6.0


def test_needs_a_power_model(make_craft, default_scenario):
    """INA-ARG-001: a scenario without an electrical system or an unknown rail is refused clearly."""
    import dataclasses
    craft = make_craft(dataclasses.replace(default_scenario, power=dataclasses.replace(default_scenario.power,
                                                                                        enabled=False)))
    with pytest.raises(ValueError, match="power.enabled"):
        Ina219Manager("x", craft, "system")
    with pytest.raises(ValueError, match="rail"):
        Ina219Manager("x", make_craft(), "battery")
