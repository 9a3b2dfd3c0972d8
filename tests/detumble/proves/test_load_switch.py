"""LoadSwitch as flown, on the simulated electrical system."""

import pytest

from detumble.drivers.spacecraft import SimulatedSpacecraft
from detumble.proves.load_switch import LoadSwitch
from fprime_lite import CmdResponse, Severity
from fprime_lite.model.fw_types import On, Success


@pytest.fixture
def rig(fprime_harness, make_craft):
    craft = make_craft()
    h = fprime_harness(LoadSwitch("face0LoadSwitch", craft, "face0", base_id=0x10030000))
    h.set_port_return("loadSwitchStateChanged", Success.SUCCESS)
    return h, craft


def test_flight_ids(rig):
    """LS-ID-001: StatusChanged is event 1, IsOn event 2, channel IsOn 0, opcodes TURN_ON 0, TURN_OFF 1, GET_IS_ON 2."""
    h, _ = rig
    c = h.component
    assert c.event_id("StatusChanged") == 0x10030001 and c.event_id("IsOn") == 0x10030002
    assert c.channel_id("IsOn") == 0x10030000
    assert [(d.name, d.opcode) for d in c.spec.commands] == [("TURN_ON", 0), ("TURN_OFF", 1), ("GET_IS_ON", 2)]


def test_turn_off_and_on_switch_the_simulated_load(rig):
    """LS-CMD-001: TURN_OFF opens the EPS switch (face board load gone, coil de-energised), tells the
    face's devices, logs StatusChanged(OFF) and writes IsOn; TURN_ON closes it again."""
    h, craft = rig
    craft.set_coil_level(0, 100)
    load_on = craft.power.switched_load_w()
    h.send_command("TURN_OFF", cmd_seq=1)
    h.assert_cmd_response(0, "TURN_OFF", CmdResponse.OK, cmd_seq=1)
    assert not craft.load_switch("face0") and craft.coil_level(0) == 0
    assert craft.power.switched_load_w() == pytest.approx(load_on - craft.scenario.power.loads.face_board_w)
    h.assert_event("StatusChanged", 0, On.OFF)
    assert h.events[0].severity == Severity.ACTIVITY_HI
    assert [c.args for c in h.from_port("loadSwitchStateChanged")] == [(On.OFF,)] * 3
    assert h.tlm_values("IsOn") == [On.OFF]
    with pytest.raises(RuntimeError, match="unpowered"):
        craft.set_coil_level(0, 50)
    h.send_command("TURN_ON")
    assert craft.load_switch("face0")
    h.assert_event("StatusChanged", 1, On.ON)
    assert h.tlm_values("IsOn") == [On.OFF, On.ON]


def test_no_change_no_event(rig):
    """LS-CMD-002: turning on a switch that is on does nothing (no event, no notification), as flown."""
    h, _ = rig
    h.send_command("TURN_ON")
    h.invoke("turnOn")
    h.assert_cmd_response(0, "TURN_ON", CmdResponse.OK)
    h.assert_events_size(0)
    h.assert_from_port_size("loadSwitchStateChanged", 0)


def test_get_is_on_and_ports(rig):
    """LS-CMD-003: GET_IS_ON logs IsOn(state); the turnOff / turnOn ports switch like the commands."""
    h, craft = rig
    h.send_command("GET_IS_ON")
    h.assert_event("IsOn", 0, On.ON)
    h.invoke("turnOff")
    assert not craft.load_switch("face0")
    h.send_command("GET_IS_ON")
    h.assert_event("IsOn", 1, On.OFF)


def test_bad_arguments(make_craft):
    """LS-ARG-001: an unknown switch or a non-spacecraft is refused with a message naming the choices."""
    craft = make_craft()
    with pytest.raises(ValueError, match="payloadBattery"):
        LoadSwitch("x", craft, "face7")
    with pytest.raises(TypeError, match="SimulatedSpacecraft"):
        LoadSwitch("x", object(), "face0")
    assert isinstance(craft, SimulatedSpacecraft)
