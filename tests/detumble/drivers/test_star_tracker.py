"""Simulated star tracker component: port, commands, channels, no-solution and every fault."""

import math

import pytest

from detumble.components.types import Success
from detumble.sim.frames import attitude_error_rad
from detumble.sim.scenario import load_scenario
from detumble.sim.star_tracker import ARCSEC
from detumble.drivers.star_tracker import SimStarTrackerFault, StarTracker
from fprime_lite import CmdResponse

# case A slowed to 1 deg/s so that the tracker (2 deg/s limit) has solutions; 4 Hz updates
SLOW = load_scenario("case_a", settings=["initial.rate.magnitude_deg_s=1", "sensors.star_tracker.rate_hz=4"])


@pytest.fixture
def rig(fprime_harness, make_craft):
    craft = make_craft(SLOW)
    return fprime_harness(StarTracker("starTracker", craft, base_id=0x7000)), craft


def test_attitude_port_returns_a_noisy_held_solution(rig):
    """STD-001: attitudeGet gives q_BN within a few sigma of the truth, stamped with the image time
    (the 4 Hz grid), held between updates."""
    h, craft = rig
    craft.clock.set_us(1_100_000)
    value, condition = h.invoke("attitudeGet")
    assert condition == Success.SUCCESS and value.valid
    assert value.timestamp.total_us == craft.time_of(1_000_000_000).total_us
    craft.sync()
    assert attitude_error_rad((value.q0, value.q1, value.q2, value.q3), craft.plant.q_BN) < \
        5 * 70 * ARCSEC + math.radians(1.0) * 0.1 + 1e-9  # noise + 0.1 s of 1 deg/s motion since the image


def test_run_writes_attitude_and_solution_count(rig):
    h, craft = rig
    for k in range(3):
        craft.clock.set_us(250_000 * (k + 1))
        h.invoke("run", 0)
    assert len(h.tlm_values("Attitude")) == 3 and all(v.valid for v in h.tlm_values("Attitude"))
    assert h.tlm_values("Solutions") == [1, 2, 3]


def test_get_attitude_command_logs_the_solution(rig):
    h, craft = rig
    h.send_command("GET_ATTITUDE", cmd_seq=2)
    h.assert_cmd_response(0, "GET_ATTITUDE", CmdResponse.OK, cmd_seq=2)
    assert h.events[-1].name == "AttitudeData" and len(h.events[-1].args) == 4


def test_no_solution_above_the_rate_limit(fprime_harness, make_craft):
    """STD-002: at 30 deg/s (above max_rate_deg_s) there is no solution: FAILURE, valid false,
    NoSolution throttled at 5; GET_ATTITUDE answers EXECUTION_ERROR."""
    craft = make_craft(load_scenario("case_a", settings=["sensors.star_tracker.rate_hz=4"]))
    h = fprime_harness(StarTracker("starTracker", craft))
    for k in range(7):
        craft.clock.set_us(250_000 * (k + 1))
        value, condition = h.invoke("attitudeGet")
        assert condition == Success.FAILURE and not value.valid
    h.assert_event_count("NoSolution", 5)
    h.send_command("GET_ATTITUDE")
    h.assert_cmd_response(0, "GET_ATTITUDE", CmdResponse.EXECUTION_ERROR)


def test_fail_fault(rig):
    h, craft = rig
    h.send_command("SIM_SET_FAULT", SimStarTrackerFault.FAIL)
    h.assert_cmd_response(0, "SIM_SET_FAULT", CmdResponse.OK)
    h.assert_event("SimFaultSet", 0, SimStarTrackerFault.FAIL)
    for _ in range(6):
        assert h.invoke("attitudeGet").condition == Success.FAILURE
    h.assert_event_count("AttitudeReadFailed", 5)
    h.invoke("run", 0)
    assert h.tlm_values("Attitude") == []
    h.component.set_fault(SimStarTrackerFault.NONE)
    assert h.invoke("attitudeGet").condition == Success.SUCCESS


def test_nan_fault_succeeds_with_nan(rig):
    h, craft = rig
    h.component.set_fault(SimStarTrackerFault.NAN)
    value, condition = h.invoke("attitudeGet")
    assert condition == Success.SUCCESS and math.isnan(value.q0) and value.valid


def test_frozen_fault_repeats_the_old_solution(rig):
    """STD-003: FROZEN returns the solution held when it was set, as valid, with its old stamp."""
    h, craft = rig
    craft.clock.set_us(500_000)
    before, _ = h.invoke("attitudeGet")
    h.component.set_fault(SimStarTrackerFault.FROZEN)
    craft.clock.set_us(3_000_000)
    value, condition = h.invoke("attitudeGet")
    assert condition == Success.SUCCESS and value == before
    h.component.set_fault(SimStarTrackerFault.NONE)
    fresh, _ = h.invoke("attitudeGet")
    assert fresh.timestamp.total_us > before.timestamp.total_us


def test_needs_a_star_tracker_in_the_scenario(make_craft):
    with pytest.raises(ValueError, match="has no star tracker"):
        StarTracker("starTracker", make_craft())


def test_a_good_read_rearms_the_throttled_events(rig, monkeypatch):
    """STD-007: a valid solution re-arms NoSolution and a read that works re-arms
    AttitudeReadFailed: each throttled event is logged five times again in the next bad spell."""
    h, craft = rig
    real = craft.star_tracker_sample
    q, _, stamp = real()
    monkeypatch.setattr(craft, "star_tracker_sample", lambda: (q, False, stamp))
    for _ in range(7):
        assert h.invoke("attitudeGet").condition == Success.FAILURE
    h.assert_event_count("NoSolution", 5)
    monkeypatch.setattr(craft, "star_tracker_sample", real)
    assert h.invoke("attitudeGet").condition == Success.SUCCESS
    monkeypatch.setattr(craft, "star_tracker_sample", lambda: (q, False, stamp))
    for _ in range(7):
        h.invoke("attitudeGet")
    h.assert_event_count("NoSolution", 10)
    h.component.set_fault(SimStarTrackerFault.FAIL)
    for _ in range(6):
        h.invoke("attitudeGet")
    h.component.set_fault(SimStarTrackerFault.NONE)
    h.invoke("attitudeGet")  # works (no solution, but the read itself succeeded)
    h.component.set_fault(SimStarTrackerFault.FAIL)
    for _ in range(6):
        h.invoke("attitudeGet")
    h.assert_event_count("AttitudeReadFailed", 10)
