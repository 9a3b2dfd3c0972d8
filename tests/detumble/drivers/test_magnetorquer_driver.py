"""Simulated DRV2605 magnetorquer drivers: ports, commands, telemetry, plant coupling, faults."""

import dataclasses

import pytest

from detumble.sim.scenario import SpacecraftConfig
from detumble.drivers.magnetorquer_driver import (DRIVER_FACES, MagnetorquerDriver, SimDriverFault,
                                                  driver_instance_name, make_magnetorquer_drivers)
from detumble.components.types import StartMagnetorquer, StopMagnetorquer, Success
from fprime_lite import CmdResponse, OutputPort, PassiveComponent, Severity

XY_MAX = 96 * 0.053 * 0.045 * 3.3 / 13      # A·m², X/Y coil at full drive
Z_MAX = 153 * 3.141592653589793 * (0.05755 / 2) ** 2 * 3.3 / 150.7


@pytest.fixture
def rig(fprime_harness, make_craft):
    craft = make_craft()
    h = fprime_harness(MagnetorquerDriver("drv2605Face0Manager", craft, 0, base_id=0x3000))
    return h, craft


@pytest.mark.parametrize("face, axis, sign, m_max", [
    (0, 0, +1, XY_MAX), (1, 0, -1, XY_MAX), (2, 1, +1, XY_MAX), (3, 1, -1, XY_MAX), (5, 2, -1, Z_MAX)])
def test_positive_level_gives_a_dipole_along_the_face_normal(fprime_harness, make_craft, face, axis, sign, m_max):
    """Minus faces are mounted mirrored: +level on X−/Y−/Z− gives a −X/−Y/−Z dipole."""
    craft = make_craft()
    h = fprime_harness(MagnetorquerDriver(driver_instance_name(face), craft, face))
    assert h.invoke("start", 127) == Success.SUCCESS
    m = craft.plant.m_coils_B
    assert m[axis] == pytest.approx(sign * m_max, rel=1e-12)
    assert [m[i] for i in range(3) if i != axis] == [0.0, 0.0]
    assert h.invoke("start", -64) == Success.SUCCESS
    assert craft.plant.m_coils_B[axis] == pytest.approx(-sign * m_max * 64 / 127, rel=1e-12)
    assert h.invoke("stop") == Success.SUCCESS
    assert craft.plant.m_coils_B == (0.0, 0.0, 0.0)
    assert h.tlm_values("DriveLevel") == [127, -64, 0]


def test_drive_level_channel_is_on_change(rig):
    h, craft = rig
    for _ in range(3):
        h.invoke("start", 50)
    assert h.tlm_values("DriveLevel") == [50]
    assert craft.coil_level(0) == 50 and h.component.level == 50


def test_level_set_by_the_driver_applies_from_now(rig):
    h, craft = rig
    craft.clock.set_us(40_000)
    h.invoke("start", 127)
    assert craft.plant.t_ns == 40_000_000  # synced before applying
    assert craft.plant.m_coils_B[0] == pytest.approx(XY_MAX)


def test_start_and_stop_commands(rig):
    h, craft = rig
    h.send_command("START", 100, cmd_seq=1)
    h.assert_cmd_response(0, "START", CmdResponse.OK, cmd_seq=1)
    assert craft.coil_level(0) == 100
    h.send_command("STOP", cmd_seq=2)
    h.assert_cmd_response(1, "STOP", CmdResponse.OK, cmd_seq=2)
    assert craft.coil_level(0) == 0


def test_start_command_refuses_minus_128(rig):
    h, craft = rig
    h.send_command("START", 100)
    h.send_command("START", -128)
    h.assert_cmd_response(1, "START", CmdResponse.VALIDATION_ERROR)
    h.assert_event("InvalidDriveLevel", 0, -128)
    assert craft.coil_level(0) == 0  # a refused level leaves the coil safe (off)


@pytest.mark.parametrize("bad", [128, -128, 1000, 1.5, 3.0, True, None, "127", float("nan")])
def test_bad_levels_fail_without_raising_and_switch_the_coil_off(rig, bad):
    h, craft = rig
    h.invoke("start", 80)
    assert h.invoke("start", bad) == Success.FAILURE
    assert craft.coil_level(0) == 0
    assert h.events[-1].name == "InvalidDriveLevel"
    assert h.events[-1].severity == Severity.WARNING_LO


def test_not_ready_fails_throttled_and_keeps_the_coil_off(rig):
    h, craft = rig
    h.invoke("start", 90)
    h.send_command("SIM_SET_FAULT", SimDriverFault.NOT_READY)
    h.assert_cmd_response(0, "SIM_SET_FAULT", CmdResponse.OK)
    h.assert_event("SimFaultSet", 0, SimDriverFault.NOT_READY)
    assert craft.coil_level(0) == 0  # the safe state, at once
    for _ in range(7):
        assert h.invoke("start", 90) == Success.FAILURE
        assert craft.coil_level(0) == 0
    assert h.invoke("stop") == Success.FAILURE
    h.assert_event_count("DeviceNotReady", 5)
    h.send_command("START", 10)
    h.assert_cmd_response(1, "START", CmdResponse.EXECUTION_ERROR)
    h.component.set_fault(SimDriverFault.NONE)
    assert h.invoke("start", 90) == Success.SUCCESS
    assert craft.coil_level(0) == 90
    h.component.set_fault(SimDriverFault.NOT_READY)
    h.invoke("stop")
    h.assert_event_count("DeviceNotReady", 6)  # throttle cleared by the good drive


def test_stuck_driver_keeps_its_level(rig):
    h, craft = rig
    h.invoke("start", -70)
    h.component.set_fault(SimDriverFault.STUCK)
    assert h.invoke("stop") == Success.FAILURE
    assert h.invoke("start", 5) == Success.FAILURE
    assert h.invoke("start", 500) == Success.FAILURE
    assert craft.coil_level(0) == -70
    h.send_command("STOP")
    h.assert_cmd_response(0, "STOP", CmdResponse.EXECUTION_ERROR)


def test_stop_fails_keeps_the_coil_on_and_answers_failure(rig):
    """Actuator Health: STOP_FAILS — starts still drive the coil; a stop leaves it at its level and
    answers FAILURE (so the manager can see it)."""
    h, craft = rig
    h.component.set_fault(SimDriverFault.STOP_FAILS)
    assert h.invoke("start", 60) == Success.SUCCESS and craft.coil_level(0) == 60
    assert h.invoke("stop") == Success.FAILURE
    assert craft.coil_level(0) == 60
    h.assert_event_count("DeviceNotReady", 1)


def test_latched_output_is_caught_by_the_read_back(rig):
    """Actuator Health: LATCHED — the device acknowledges writes but its output keeps the level it had;
    the read-back answers FAILURE with DriveReadbackMismatch (WARNING_HI) instead of a false SUCCESS."""
    h, craft = rig
    h.invoke("start", 127)
    h.component.set_fault(SimDriverFault.LATCHED)
    assert h.invoke("stop") == Success.FAILURE
    assert h.invoke("start", 20) == Success.FAILURE
    assert craft.coil_level(0) == 127
    h.assert_event("DriveReadbackMismatch", 0, 127, 0)
    h.assert_event("DriveReadbackMismatch", 1, 127, 20)
    assert h.component.spec.event("DriveReadbackMismatch").severity == Severity.WARNING_HI
    h.component.set_fault(SimDriverFault.NONE)
    assert h.invoke("stop") == Success.SUCCESS and craft.coil_level(0) == 0


@pytest.mark.parametrize("port, args", [("stop", ()), ("start", (0,))])
def test_recommanding_the_carried_level_acts_as_a_full_drive(rig, port, args):
    """Re-commanding the level the coil already carries takes a short cut; it must leave what a
    full drive leaves: DriveLevel sent once (a fresh driver's coil is at 0 but the channel has not
    sent it yet), and both throttles cleared (here DriveReadbackMismatch, tripped by a LATCHED
    output that kept the coil at 0)."""
    h, craft = rig
    assert craft.coil_level(0) == 0
    assert h.invoke(port, *args) == Success.SUCCESS
    assert h.tlm_values("DriveLevel") == [0]
    h.component.set_fault(SimDriverFault.LATCHED)
    for level in range(1, 8):
        assert h.invoke("start", level) == Success.FAILURE
    h.assert_event_count("DriveReadbackMismatch", 5)  # throttled after 5
    h.component.set_fault(SimDriverFault.NONE)
    for _ in range(2):
        assert h.invoke(port, *args) == Success.SUCCESS
    assert h.tlm_values("DriveLevel") == [0]
    h.component.set_fault(SimDriverFault.LATCHED)
    assert h.invoke("start", 9) == Success.FAILURE
    h.assert_event_count("DriveReadbackMismatch", 6)  # reported again: the throttle was cleared


def test_a_plant_exception_is_a_failed_drive(rig, monkeypatch):
    h, craft = rig

    def broken(face, level):
        raise RuntimeError("boom")

    monkeypatch.setattr(craft, "set_coil_level", broken)
    assert h.invoke("start", 3) == Success.FAILURE
    h.assert_event_count("DeviceNotReady", 1)
    # reported twice: the drive, then the switch-off that should have made the coil safe
    assert h.component.handler_faults == 2
    assert h.events_named("HandlerFault") == [("coil x_plus drive", "RuntimeError: boom")] * 2


def test_a_plant_exception_switches_the_coil_off(rig, monkeypatch):
    h, craft = rig
    assert h.invoke("start", 3) == Success.SUCCESS and craft.coil_level(0) == 3
    real = craft.set_coil_level

    def broken_unless_off(face, level):
        if level:
            raise RuntimeError("boom")
        real(face, level)

    monkeypatch.setattr(craft, "set_coil_level", broken_unless_off)
    assert h.invoke("start", 5) == Success.FAILURE
    assert craft.coil_level(0) == 0 and h.tlm_values("DriveLevel")[-1] == 0
    assert h.events_named("HandlerFault") == [("coil x_plus drive", "RuntimeError: boom")]


def test_construction_checks_the_face(make_craft, default_scenario):
    craft = make_craft()
    with pytest.raises(ValueError, match="no coil on face 4"):
        MagnetorquerDriver("drv2605Face4Manager", craft, 4)
    rods = dataclasses.replace(default_scenario, spacecraft=SpacecraftConfig(actuator_type="rods"))
    with pytest.raises(ValueError, match="torque rods"):
        MagnetorquerDriver("drv2605Face0Manager", make_craft(rods), 0)


def test_reference_deployment_drivers(make_craft):
    drivers = make_magnetorquer_drivers(make_craft(), {f: 0x4000 + 0x100 * f for f in DRIVER_FACES})
    assert list(drivers) == ["drv2605Face0Manager", "drv2605Face1Manager", "drv2605Face2Manager",
                             "drv2605Face3Manager", "drv2605Face5Manager"]
    assert [d.face for d in drivers.values()] == [0, 1, 2, 3, 5]
    assert drivers["drv2605Face5Manager"].base_id == 0x4500


class _Manager(PassiveComponent):
    """Stands in for the DetumbleManager's coil outputs (same port types)."""

    xMinusStart = OutputPort(StartMagnetorquer)
    xMinusStop = OutputPort(StopMagnetorquer)


def test_connects_to_a_manager_using_the_detumble_port_types(make_craft):
    """The flight manager sends X− = −level for a +X dipole: through the real port connection the
    X− coil then pushes +X, as the X+ coil does for +level."""
    craft = make_craft()
    driver = MagnetorquerDriver("drv2605Face1Manager", craft, 1)
    manager = _Manager("detumbleManager")
    manager.output_port("xMinusStart").connect(0, driver.input_port("start"))
    manager.output_port("xMinusStop").connect(0, driver.input_port("stop"))
    assert manager.xMinusStart[0](-127) == Success.SUCCESS
    assert craft.plant.m_coils_B[0] == pytest.approx(XY_MAX)
    assert manager.xMinusStop[0]() == Success.SUCCESS
    assert craft.plant.m_coils_B[0] == 0.0


def test_face_power_off_stops_the_coil_and_the_driver_reports_it(rig):
    """DRV-PWR-001: with its face switch open the coil carries no current and start/stop fail with
    DeviceNotReady; after the switch closes the driver waits the 1 s settling time, then initialises
    the device (DeviceInitialized, flight id 8) and drives the coil again."""
    from fprime_lite.model.fw_types import On
    h, craft = rig
    assert h.component.event_id("DeviceInitialized") == 0x3000 + 8
    assert h.invoke("start", 100) == Success.SUCCESS
    craft.set_load_switch("face0", False)             # the switch's GPIO opens the face's rail…
    assert h.invoke("loadSwitchStateChanged", On.OFF) == Success.SUCCESS   # …and tells the driver
    assert craft.coil_level(0) == 0 and craft.plant.m_coils_B == (0.0, 0.0, 0.0)
    assert h.invoke("start", 100) == Success.FAILURE
    h.send_command("START", 100)
    h.assert_cmd_response(0, "START", CmdResponse.EXECUTION_ERROR)
    assert craft.coil_level(0) == 0
    h.assert_event_count("DeviceNotReady", 2)
    craft.set_load_switch("face0", True)
    h.invoke("loadSwitchStateChanged", On.ON)
    craft.clock.advance_us(999_000)
    assert h.invoke("start", 100) == Success.FAILURE   # still settling
    craft.clock.advance_us(1_000)
    assert h.invoke("start", 100) == Success.SUCCESS
    h.assert_event_count("DeviceInitialized", 1)
    assert craft.coil_level(0) == 100


class _Level(int):
    """An int subclass (not bool): a valid drive level that is not a plain ``int``."""


@pytest.mark.parametrize("level", [_Level(77), _Level(-127), _Level(0)])
def test_a_level_of_an_int_subclass_drives_as_its_plain_int(rig, level):
    """TICK-034: ``start`` is the one definition of a valid drive (the former ``_apply`` folded into it);
    a level that is an int subclass takes the general path and is driven as the plain int it stands for:
    the coil carries it, DriveLevel sends it as a plain int, the port answers SUCCESS and no event fires;
    the START command likewise."""
    h, craft = rig
    assert h.invoke("start", 5) == Success.SUCCESS
    assert h.invoke("start", level) == Success.SUCCESS
    assert craft.coil_level(0) == int(level)
    assert type(h.component.DriveLevel.last) is int and h.component.DriveLevel.last == int(level)
    assert h.tlm_values("DriveLevel") == [5, int(level)]
    h.assert_event_count("InvalidDriveLevel", 0)
    h.assert_event_count("DeviceNotReady", 0)
    h.send_command("START", _Level(33), cmd_seq=1)
    h.assert_cmd_response(0, "START", CmdResponse.OK, cmd_seq=1)
    assert craft.coil_level(0) == 33
