"""Simulated reaction-wheel drivers: ports, commands, channels, limits, every fault and event."""

import math

import pytest

from detumble.components.types import Success, WheelMode, WheelTorqueSet
from detumble.sim.scenario import load_scenario
from detumble.drivers.reaction_wheel_driver import (ReactionWheelDriver, SimWheelFault, make_reaction_wheel_drivers,
                                                    wheel_instance_name)
from fprime_lite import CmdResponse, OutputPort, PassiveComponent, Severity

SURREY = load_scenario("surrey", settings=["initial.rate.omega_rad_s=[0, 0, 0]"])
U_MAX, H_MAX = 1e-3, 0.1  # N m, N m s (the coursework wheel)


@pytest.fixture
def rig(fprime_harness, make_craft):
    craft = make_craft(SURREY)
    h = fprime_harness(ReactionWheelDriver("reactionWheel0", craft, 0, base_id=0x5000))
    return h, craft


def test_torque_port_drives_the_plant_wheel_and_the_body_reacts(rig):
    """RWD-001: torqueSet(u) spins wheel 0 (momentum u t after t s) and the body the other way."""
    h, craft = rig
    assert h.invoke("torqueSet", 5e-4) == Success.SUCCESS
    craft.clock.set_us(2_000_000)
    craft.sync()
    value, condition = h.invoke("wheelStateGet")
    assert condition == Success.SUCCESS and value.mode == WheelMode.TORQUE
    assert value.momentum == pytest.approx(1e-3, rel=1e-12) and value.torque == 5e-4
    assert craft.plant.omega_BN_B[0] < 0.0
    assert value.timestamp.total_us == craft.clock.now().total_us
    assert h.tlm_values("Command") == [5e-4] and h.tlm_values("Mode") == [WheelMode.TORQUE]


def test_run_writes_speed_momentum_and_torque(rig):
    h, craft = rig
    h.invoke("torqueSet", -2e-4)
    craft.clock.set_us(1_000_000)
    craft.sync()
    h.invoke("run", 0)
    speed, h_w, u, _ = craft.wheel_sample(0)
    assert h.tlm_values("Momentum") == [pytest.approx(-2e-4, rel=1e-12)]
    assert h.tlm_values("Speed") == [pytest.approx(speed, rel=1e-12)] and speed < 0
    assert h.tlm_values("Torque") == [-2e-4]


def test_torque_beyond_the_limit_is_clipped_with_a_throttled_event(rig):
    """RWD-002: |u| > max_torque: SUCCESS, the plant applies u_max, TorqueSaturated (throttle 5,
    cleared by an in-range command)."""
    h, craft = rig
    for _ in range(7):
        assert h.invoke("torqueSet", 3e-3) == Success.SUCCESS
    craft.clock.set_us(100_000)
    craft.sync()
    assert craft.plant.wheel_torques_nm[0] == U_MAX
    h.assert_event_count("TorqueSaturated", 5)
    h.assert_event("TorqueSaturated", 0, 3e-3, U_MAX)
    h.invoke("torqueSet", 1e-4)
    h.invoke("torqueSet", -3e-3)
    h.assert_event_count("TorqueSaturated", 6)


def test_momentum_limit_event_from_run(rig):
    """RWD-003: a wheel held at its momentum limit reports MomentumSaturated (WARNING_HI) from run."""
    h, craft = rig
    h.invoke("torqueSet", U_MAX)
    craft.clock.set_us(int(1.2 * H_MAX / U_MAX * 1e6))  # 120 s: full after 100 s
    h.invoke("run", 0)
    assert h.tlm_values("Momentum")[-1] == pytest.approx(H_MAX, rel=1e-12)
    h.assert_event("MomentumSaturated", 0, pytest.approx(H_MAX, rel=1e-12), H_MAX)
    assert [e for e in h.events if e.name == "MomentumSaturated"][0].severity == Severity.WARNING_HI


def test_speed_port_and_command(rig):
    """RWD-004: speedSet / SET_SPEED put the wheel in SPEED mode and it reaches the set-point."""
    h, craft = rig
    assert h.invoke("speedSet", 50.0) == Success.SUCCESS
    h.send_command("SET_SPEED", 80.0, cmd_seq=3)
    h.assert_cmd_response(0, "SET_SPEED", CmdResponse.OK, cmd_seq=3)
    craft.clock.set_us(30_000_000)
    craft.sync()
    value, _ = h.invoke("wheelStateGet")
    assert value.mode == WheelMode.SPEED and value.speed == pytest.approx(80.0, abs=1e-6)
    assert h.tlm_values("Mode") == [WheelMode.SPEED]


def test_set_torque_command_and_validation(rig):
    h, craft = rig
    h.send_command("SET_TORQUE", 2e-4, cmd_seq=1)
    h.assert_cmd_response(0, "SET_TORQUE", CmdResponse.OK, cmd_seq=1)
    h.send_command("SET_TORQUE", float("nan"))
    h.assert_cmd_response(1, "SET_TORQUE", CmdResponse.VALIDATION_ERROR)
    h.assert_event_count("InvalidTorque", 1)
    assert craft.plant.wheels.command[0] == 0.0  # the safe state
    h.send_command("SET_SPEED", float("inf"))
    h.assert_cmd_response(2, "SET_SPEED", CmdResponse.VALIDATION_ERROR)
    h.assert_event_count("InvalidSpeed", 1)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), None, "1e-3", True])
def test_bad_torques_fail_without_raising(rig, bad):
    h, craft = rig
    h.invoke("torqueSet", 5e-4)
    assert h.invoke("torqueSet", bad) == Success.FAILURE
    assert craft.plant.wheels.command[0] == 0.0
    assert h.events[-1].name == "InvalidTorque"
    assert h.invoke("speedSet", bad) == Success.FAILURE
    assert h.events[-1].name == "InvalidSpeed"


def test_enable_disable_ports_and_commands(rig):
    """RWD-005: DISABLE stops the motor (the wheel coasts), refuses torque commands
    (WheelNotEnabled), ENABLE restores TORQUE mode at 0 N m; events only on a change."""
    h, craft = rig
    h.invoke("torqueSet", 5e-4)
    h.send_command("DISABLE", cmd_seq=4)
    h.assert_cmd_response(0, "DISABLE", CmdResponse.OK, cmd_seq=4)
    h.assert_event_count("WheelDisabled", 1)
    craft.clock.set_us(1_000_000)
    craft.sync()
    assert craft.plant.wheel_torques_nm[0] == 0.0
    assert h.invoke("torqueSet", 5e-4) == Success.FAILURE
    assert h.invoke("speedSet", 5.0) == Success.FAILURE
    h.assert_event_count("WheelNotEnabled", 2)
    assert h.invoke("enableSet", False) == Success.SUCCESS
    h.assert_event_count("WheelDisabled", 1)
    h.send_command("ENABLE")
    h.assert_cmd_response(1, "ENABLE", CmdResponse.OK)
    h.assert_event_count("WheelEnabled", 1)
    assert h.invoke("enableSet", True) == Success.SUCCESS
    h.assert_event_count("WheelEnabled", 1)
    assert h.tlm_values("Mode") == [WheelMode.TORQUE, WheelMode.DISABLED, WheelMode.TORQUE]
    assert h.invoke("torqueSet", 1e-4) == Success.SUCCESS


def test_not_ready_fault(rig):
    """RWD-006: NOT_READY switches the motor off at once; commands and reads fail with throttled
    DeviceNotReady / WheelReadFailed; clearing the fault restores service."""
    h, craft = rig
    h.invoke("torqueSet", 5e-4)
    h.send_command("SIM_SET_FAULT", SimWheelFault.NOT_READY)
    h.assert_cmd_response(0, "SIM_SET_FAULT", CmdResponse.OK)
    h.assert_event("SimFaultSet", 0, SimWheelFault.NOT_READY)
    craft.clock.set_us(500_000)
    craft.sync()
    assert craft.plant.wheel_torques_nm[0] == 0.0
    for _ in range(7):
        assert h.invoke("torqueSet", 1e-4) == Success.FAILURE
    h.assert_event_count("DeviceNotReady", 5)
    assert h.invoke("wheelStateGet").condition == Success.FAILURE
    h.invoke("run", 0)
    h.assert_event_count("WheelReadFailed", 2)
    assert h.tlm_values("Speed") == []
    h.send_command("ENABLE")
    h.assert_cmd_response(1, "ENABLE", CmdResponse.EXECUTION_ERROR)
    h.component.set_fault(SimWheelFault.NONE)
    assert h.invoke("torqueSet", 1e-4) == Success.FAILURE  # it lost power: ENABLE first
    h.assert_event_count("WheelNotEnabled", 1)
    assert h.invoke("enableSet", True) == Success.SUCCESS
    assert h.invoke("torqueSet", 1e-4) == Success.SUCCESS
    craft.clock.set_us(600_000)
    craft.sync()
    assert craft.plant.wheel_torques_nm[0] == 1e-4


def test_stuck_fault_keeps_the_last_command(rig):
    h, craft = rig
    h.invoke("torqueSet", -4e-4)
    h.component.set_fault(SimWheelFault.STUCK)
    assert h.invoke("torqueSet", 0.0) == Success.FAILURE
    assert h.invoke("enableSet", False) == Success.FAILURE
    h.send_command("SET_TORQUE", 0.0)
    h.assert_cmd_response(0, "SET_TORQUE", CmdResponse.EXECUTION_ERROR)
    craft.clock.set_us(1_000_000)
    craft.sync()
    assert craft.plant.wheel_torques_nm[0] == -4e-4
    assert h.invoke("wheelStateGet").condition == Success.SUCCESS  # it still reports


@pytest.mark.parametrize("fault", [SimWheelFault.READ_FAIL, SimWheelFault.READ_NAN])
def test_read_faults(rig, fault):
    h, craft = rig
    h.component.set_fault(fault)
    assert h.invoke("torqueSet", 1e-4) == Success.SUCCESS  # commands still reach the wheel
    value, condition = h.invoke("wheelStateGet")
    if fault == SimWheelFault.READ_FAIL:
        assert condition == Success.FAILURE
        h.assert_event_count("WheelReadFailed", 1)
    else:
        assert condition == Success.SUCCESS and math.isnan(value.speed) and math.isnan(value.momentum)


def test_a_plant_exception_is_a_failed_command(rig, monkeypatch):
    h, craft = rig

    def broken(i, u):
        raise RuntimeError("boom")

    monkeypatch.setattr(craft, "set_wheel_torque", broken)
    assert h.invoke("torqueSet", 1e-4) == Success.FAILURE
    h.assert_event_count("DeviceNotReady", 1)
    # reported twice: the command, then the zero torque that should have made the wheel safe
    assert h.component.handler_faults == 2
    assert [e[0] for e in h.events_named("HandlerFault")] == ["wheel 0 broken", "wheel 0 safing"]
    assert h.tlm_values("HandlerFaults") == [1, 2]


def test_construction_and_factory(make_craft):
    craft = make_craft(SURREY)
    drivers = make_reaction_wheel_drivers(craft, {i: 0x6000 + 0x100 * i for i in range(3)})
    assert list(drivers) == ["reactionWheel0", "reactionWheel1", "reactionWheel2"]
    assert drivers["reactionWheel2"].base_id == 0x6200 and wheel_instance_name(1) == "reactionWheel1"
    with pytest.raises(ValueError, match="no wheel 3"):
        ReactionWheelDriver("reactionWheel3", craft, 3)
    with pytest.raises(ValueError, match="no reaction wheels"):
        ReactionWheelDriver("reactionWheel0", make_craft(), 0)


class _Controller(PassiveComponent):
    """Stands in for an attitude controller's wheel outputs (the Drv port type)."""

    wheelTorque = OutputPort(WheelTorqueSet, size=3)


def test_connects_to_a_controller_through_the_port_type(make_craft):
    craft = make_craft(SURREY)
    drivers = make_reaction_wheel_drivers(craft)
    ctl = _Controller("controller")
    for i, d in enumerate(drivers.values()):
        ctl.output_port("wheelTorque").connect(i, d.input_port("torqueSet"))
    for i in range(3):
        assert ctl.wheelTorque[i](1e-4 * (i + 1)) == Success.SUCCESS
    craft.clock.set_us(1_000_000)
    craft.sync()
    assert craft.plant.wheel_momenta == pytest.approx((1e-4, 2e-4, 3e-4), rel=1e-12)
