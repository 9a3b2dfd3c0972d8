"""PowerMonitor as flown: energy integration from the INA219 ports."""

import pytest

from detumble.proves.power_monitor import PowerMonitor
from fprime_lite import CmdResponse, Time


@pytest.fixture
def h(fprime_harness):
    h = fprime_harness(PowerMonitor("powerMonitor", base_id=0x10038000))
    h.set_port_return("sysPowerGet", 3.0)
    h.set_port_return("solPowerGet", 1.5)
    for port in ("sysVoltageGet", "sysCurrentGet", "solVoltageGet", "solCurrentGet"):
        h.set_port_return(port, 1.0)
    h.set_test_time(Time.from_us(1_000_000_000))
    return h


def _runs(h, n, dt_s=1.0):
    for _ in range(n):
        h.invoke("run", 0)
        h.advance_time(int(dt_s), int(round((dt_s % 1) * 1e6)))


def test_integrates_consumption_and_generation(h):
    """PM-RUN-001: after 1 + 3600 runs 1 s apart, consumption = (3.0 + 1.5) W x 1 h = 4500 mWh (the
    flight sums both rails) and generation = 1500 mWh, within F32 rounding; all six ports are read."""
    _runs(h, 3601)
    assert h.component.total_power_mwh == pytest.approx(4500.0, rel=1e-4)
    assert h.component.total_generation_mwh == pytest.approx(1500.0, rel=1e-4)
    assert h.tlm_values("TotalPowerConsumption")[-1] == pytest.approx(4500.0, rel=1e-4)
    assert h.tlm_values("TotalPowerGenerated")[0] == 0.0
    assert len(h.from_port("sysVoltageGet")) == 3601 and len(h.from_port("solCurrentGet")) == 3601


def test_long_gaps_and_insane_readings_are_skipped(h):
    """PM-RUN-002: an interval of 10 s or more is not credited; a power outside 0..1000 W is skipped."""
    _runs(h, 2, dt_s=12.0)
    assert h.component.total_power_mwh == 0.0
    h.set_port_return("sysPowerGet", 5000.0)
    _runs(h, 3)
    assert h.component.total_power_mwh == 0.0
    assert h.component.total_generation_mwh > 0.0


def test_commands(h):
    """PM-CMD-001: RESET_TOTAL_POWER, RESET_TOTAL_GENERATION and GET_TOTAL_POWER as flown."""
    _runs(h, 11)
    h.send_command("GET_TOTAL_POWER", cmd_seq=1)
    h.assert_cmd_response(0, "GET_TOTAL_POWER", CmdResponse.OK, cmd_seq=1)
    h.assert_event("TotalPowerConsumptionReading", 0, pytest.approx(4.5 * 10 / 3.6, rel=1e-4))
    h.send_command("RESET_TOTAL_POWER")
    h.send_command("RESET_TOTAL_GENERATION")
    assert h.component.total_power_mwh == 0.0 and h.component.total_generation_mwh == 0.0
    h.assert_event_count("TotalPowerReset", 1)
    h.assert_event_count("TotalGenerationReset", 1)
