"""ModeManager as flown: commands, events, channels, parameters, safe-mode reasons, low-battery and
command-loss transitions, load switches, persistence and unintended-reboot detection."""

import pytest

from detumble.components.types import SystemMode, SystemModeChanged
from detumble.proves.mode_manager import ModeManager, SafeModeReason
from detumble.proves.mode_manager import STATE_FILE_NAME
from fprime_lite import CmdResponse, PassiveComponent, Severity, sync_input
from fprime_lite.model.fw_types import TimeIntervalValue

BASE = 0x1000A000


@pytest.fixture
def h(fprime_harness):
    harness = fprime_harness(ModeManager("modeManager", base_id=BASE))
    harness.set_port_return("voltageGet", 7.9)
    return harness


def _run(h, n):
    for _ in range(n):
        h.invoke("run", 0)


def test_flight_ids():
    """MM-ID-001: opcodes, event, channel and parameter ids in the flight FPP declaration order."""
    mm = ModeManager("modeManager", base_id=BASE)
    assert [(c.name, c.opcode) for c in mm.spec.commands][:4] == [
        ("FORCE_SAFE_MODE", 0), ("EXIT_SAFE_MODE", 1), ("GET_CURRENT_MODE", 2), ("GET_SAFE_MODE_REASON", 3)]
    assert mm.event_id("EnteringSafeMode") == BASE and mm.event_id("CommandLossDetected") == BASE + 14
    assert [c.name for c in mm.spec.channels][:3] == ["CurrentMode", "SafeModeEntryCount", "CurrentSafeModeReason"]
    assert [p.name for p in mm.spec.params] == ["SafeModeEntryVoltage", "SafeModeRecoveryVoltage",
                                                "SafeModeDebounceSeconds", "SAFEMODE_SEQUENCE_FILE", "COMM_LOSS_TIME"]
    assert [int(r) for r in SafeModeReason] == list(range(7))


def test_parameter_defaults(h):
    """MM-PRM-001: the flight defaults: 6.7 V, 8.0 V, 10 s, /seq/enter_safe.bin, 3 days."""
    c = h.component
    assert c.SafeModeEntryVoltage.value == pytest.approx(6.7)
    assert c.SafeModeRecoveryVoltage.value == pytest.approx(8.0)
    assert c.SafeModeDebounceSeconds.value == 10
    assert c.SAFEMODE_SEQUENCE_FILE.value == "/seq/enter_safe.bin"
    assert c.COMM_LOSS_TIME.value == TimeIntervalValue(259200, 0)


def test_force_safe_mode_command(h):
    """MM-CMD-001: FORCE_SAFE_MODE enters safe mode with reason GROUND_COMMAND, turns every load switch
    off, notifies modeChanged and writes the channels."""
    h.send_command("FORCE_SAFE_MODE", cmd_seq=4)
    h.assert_cmd_response(0, "FORCE_SAFE_MODE", CmdResponse.OK, cmd_seq=4)
    assert h.invoke("getMode") == SystemMode.SAFE_MODE
    assert [e.name for e in h.events] == ["ManualSafeModeEntry", "EnteringSafeMode"]
    h.assert_event("EnteringSafeMode", 0, "Ground command")
    assert h.events[1].severity == Severity.WARNING_HI
    assert [c.args for c in h.from_port("modeChanged")] == [(SystemMode.SAFE_MODE,)]
    assert sorted(c.index for c in h.from_port("loadSwitchTurnOff")) == list(range(8))
    assert h.from_port("loadSwitchTurnOn") == []
    assert h.tlm_values("CurrentMode") == [1]
    assert h.tlm_values("SafeModeEntryCount") == [1]
    assert h.tlm_values("CurrentSafeModeReason") == [SafeModeReason.GROUND_COMMAND]
    assert [c.args for c in h.from_port("runSequence")] == [("/seq/enter_safe.bin",)]


def test_force_safe_mode_twice_changes_nothing(h):
    """MM-CMD-002: FORCE_SAFE_MODE in safe mode answers OK and does nothing."""
    h.send_command("FORCE_SAFE_MODE")
    h.clear_history()
    h.send_command("FORCE_SAFE_MODE")
    h.assert_cmd_response(0, "FORCE_SAFE_MODE", CmdResponse.OK)
    h.assert_events_size(0)
    h.assert_from_port_history_size(0)


def test_exit_safe_mode(h):
    """MM-CMD-003: EXIT_SAFE_MODE returns to NORMAL, clears the reason, turns the switches on."""
    h.send_command("FORCE_SAFE_MODE")
    h.clear_history()
    h.send_command("EXIT_SAFE_MODE")
    h.assert_cmd_response(0, "EXIT_SAFE_MODE", CmdResponse.OK)
    assert h.invoke("getMode") == SystemMode.NORMAL
    h.assert_event_count("ExitingSafeMode", 1)
    assert h.from_port("modeChanged")[0].args == (SystemMode.NORMAL,)
    assert len(h.from_port("loadSwitchTurnOn")) == 8
    assert h.tlm_values("CurrentMode") == [2]
    assert h.tlm_values("CurrentSafeModeReason") == [SafeModeReason.NONE]


def test_exit_safe_mode_in_normal_answers_ok_as_flown(h):
    """MM-CMD-004: the flight EXIT_SAFE_MODE handler exits unconditionally and answers OK."""
    h.send_command("EXIT_SAFE_MODE")
    h.assert_cmd_response(0, "EXIT_SAFE_MODE", CmdResponse.OK)
    h.assert_event_count("ExitingSafeMode", 1)
    assert h.component.mode == SystemMode.NORMAL


def test_get_current_mode_and_reason(h):
    """MM-CMD-005: GET_CURRENT_MODE and GET_SAFE_MODE_REASON log the readings."""
    h.send_command("GET_CURRENT_MODE")
    h.send_command("FORCE_SAFE_MODE")
    h.send_command("GET_CURRENT_MODE")
    h.send_command("GET_SAFE_MODE_REASON")
    h.assert_event("CurrentModeReading", 0, SystemMode.NORMAL)
    h.assert_event("CurrentModeReading", 1, SystemMode.SAFE_MODE)
    h.assert_event("CurrentSafeModeReasonReading", 0, SafeModeReason.GROUND_COMMAND)
    assert all(r.response == CmdResponse.OK for r in h.cmd_responses)


@pytest.mark.parametrize("reason, effective, text", [
    (SafeModeReason.NONE, SafeModeReason.EXTERNAL_REQUEST, "External component request"),
    (SafeModeReason.LORA, SafeModeReason.LORA, "LoRa communication fault"),
])
def test_force_safe_mode_port(h, reason, effective, text):
    """MM-PORT-001: forceSafeMode(reason) enters safe mode (NONE means EXTERNAL_REQUEST); a second
    request is ignored with SafeModeRequestIgnored."""
    h.invoke("forceSafeMode", reason)
    assert h.component.reason == effective
    assert [e.name for e in h.events] == ["ExternalFaultDetected", "EnteringSafeMode"]
    h.assert_event("EnteringSafeMode", 0, text)
    h.invoke("forceSafeMode", SafeModeReason.NONE)
    h.assert_event_count("SafeModeRequestIgnored", 1)
    assert h.component.safe_mode_entries == 1


def test_low_battery_enters_after_the_debounce_and_recovers(h):
    """MM-VOLT-001: SafeModeDebounceSeconds consecutive readings below SafeModeEntryVoltage enter
    LOW_BATTERY safe mode (AutoSafeModeEntry with the voltage); a good reading restarts the count;
    as many readings above SafeModeRecoveryVoltage leave it (AutoSafeModeExit)."""
    h.set_port_return("voltageGet", 6.5)
    _run(h, 9)
    h.set_port_return("voltageGet", 7.0)   # one good sample: the debounce starts again
    _run(h, 1)
    h.set_port_return("voltageGet", 6.5)
    _run(h, 9)
    assert h.component.mode == SystemMode.NORMAL
    _run(h, 1)
    assert h.component.mode == SystemMode.SAFE_MODE and h.component.reason == SafeModeReason.LOW_BATTERY
    h.assert_event("AutoSafeModeEntry", 0, SafeModeReason.LOW_BATTERY, pytest.approx(6.5))
    h.assert_event("EnteringSafeMode", 0, "Low battery voltage")
    h.set_port_return("voltageGet", 7.9)   # above entry, below recovery: stays
    _run(h, 20)
    assert h.component.mode == SystemMode.SAFE_MODE
    h.set_port_return("voltageGet", 8.1)
    _run(h, 9)
    assert h.component.mode == SystemMode.SAFE_MODE
    _run(h, 1)
    assert h.component.mode == SystemMode.NORMAL
    h.assert_event("AutoSafeModeExit", 0, pytest.approx(8.1))
    assert h.tlm_values("CurrentSafeModeReason")[-1] == SafeModeReason.NONE


def test_no_auto_recovery_for_other_reasons(h):
    """MM-VOLT-002: a GROUND_COMMAND safe mode stays however good the voltage."""
    h.send_command("FORCE_SAFE_MODE")
    h.set_port_return("voltageGet", 8.4)
    _run(h, 30)
    assert h.component.mode == SystemMode.SAFE_MODE
    h.assert_no_event("AutoSafeModeExit")


def test_unconnected_voltage_is_a_fault(fprime_harness):
    """MM-VOLT-003: no voltage reading counts as low voltage (never a fake good value)."""
    mm = ModeManager("modeManager", base_id=BASE)
    h = fprime_harness(mm)
    mm.output_port("voltageGet").targets[0] = None
    _run(h, 10)
    h.assert_event("AutoSafeModeEntry", 0, SafeModeReason.LOW_BATTERY, 0.0)


def test_thresholds_are_parameters(h):
    """MM-PRM-002: SafeModeEntryVoltage and SafeModeDebounceSeconds set by PRM_SET take effect."""
    h.param_set("SafeModeEntryVoltage", 8.0)
    h.param_set("SafeModeDebounceSeconds", 3)
    h.load_parameters()
    _run(h, 3)   # 7.9 V < 8.0 V for 3 s
    assert h.component.reason == SafeModeReason.LOW_BATTERY


def test_command_loss(h):
    """MM-CL-001: COMM_LOSS_TIME seconds without packetRouted: CommandLossDetected(duration), safe
    mode COMMAND_LOSS, stopWatchdog; once only until a packet arrives; packetRouted restarts it."""
    h.param_set("COMM_LOSS_TIME", TimeIntervalValue(5, 0))
    h.load_parameters()
    _run(h, 4)
    h.invoke("packetRouted")
    _run(h, 4)
    assert h.component.mode == SystemMode.NORMAL
    _run(h, 1)
    h.assert_event("CommandLossDetected", 0, 5)
    assert h.component.reason == SafeModeReason.COMMAND_LOSS
    h.assert_event("EnteringSafeMode", 0, "Loss of contact with ground")
    h.assert_from_port_size("stopWatchdog", 1)
    _run(h, 10)
    h.assert_event_count("CommandLossDetected", 1)


def test_sequence_completion_events(h):
    """MM-SEQ-001: completeSequence logs SafeModeSequenceCompleted or SafeModeSequenceFailed(response)."""
    h.invoke("completeSequence", 1, 0, CmdResponse.OK)
    h.invoke("completeSequence", 1, 0, CmdResponse.EXECUTION_ERROR)
    h.assert_event_count("SafeModeSequenceCompleted", 1)
    h.assert_event("SafeModeSequenceFailed", 0, CmdResponse.EXECUTION_ERROR)


def test_run_writes_the_channels(h):
    """MM-TLM-001: run writes CurrentMode, CurrentSafeModeReason and SafeModeEntryCount."""
    _run(h, 2)
    assert h.tlm_values("CurrentMode") == [2, 2]
    assert h.tlm_values("CurrentSafeModeReason") == [SafeModeReason.NONE] * 2
    assert h.tlm_values("SafeModeEntryCount") == [0, 0]


class _Flash:
    def __init__(self, path):
        self.flash_dir = str(path)


def test_persistence_clean_and_unintended_reboots(fprime_harness, tmp_path):
    """MM-PERS-001: the state survives a restart; without prepareForReboot a NORMAL restart is an
    unintended reboot (SYSTEM_FAULT); a safe mode is restored as such; prepareForReboot avoids it."""
    flash = _Flash(tmp_path)
    h1 = fprime_harness(ModeManager("modeManager", base_id=BASE, spacecraft=flash))
    h1.load_parameters()                      # first boot: no file, NORMAL
    assert (tmp_path / STATE_FILE_NAME).exists()
    h1.invoke("prepareForReboot")
    h1.assert_event_count("PreparingForReboot", 1)

    h2 = fprime_harness(ModeManager("modeManager", base_id=BASE, spacecraft=flash))
    h2.load_parameters()                      # clean reboot: NORMAL, switches on
    assert h2.component.mode == SystemMode.NORMAL
    h2.assert_no_event("UnintendedRebootDetected")
    assert len(h2.from_port("loadSwitchTurnOn")) == 8

    h3 = fprime_harness(ModeManager("modeManager", base_id=BASE, spacecraft=flash))
    h3.load_parameters()                      # h2 never prepared: unintended
    h3.assert_event_count("UnintendedRebootDetected", 1)
    assert h3.component.reason == SafeModeReason.SYSTEM_FAULT
    assert h3.component.safe_mode_entries == 1

    h4 = fprime_harness(ModeManager("modeManager", base_id=BASE, spacecraft=flash))
    h4.load_parameters()                      # restored in safe mode
    assert h4.component.mode == SystemMode.SAFE_MODE
    h4.assert_event("EnteringSafeMode", 0, "State restored from persistent storage")
    assert h4.component.safe_mode_entries == 1


def test_corrupt_state_file(fprime_harness, tmp_path):
    """MM-PERS-002: a state file of the wrong size is reported (StatePersistenceFailure) and ignored."""
    (tmp_path / STATE_FILE_NAME).write_bytes(b"xx")
    h = fprime_harness(ModeManager("modeManager", base_id=BASE, spacecraft=_Flash(tmp_path)))
    h.load_parameters()
    h.assert_event("StatePersistenceFailure", 0, "load-read", 2)
    assert h.component.mode == SystemMode.NORMAL


class _Listener(PassiveComponent):
    @sync_input(SystemModeChanged)
    def systemModeChanged(self, mode):
        self.seen.append(mode)

    def __init__(self, name):
        super().__init__(name)
        self.seen = []


def test_python_api_and_mode_changed_listener():
    """MM-API-001: enter/exit_safe_mode report whether anything changed; listeners hear every change."""
    mm = ModeManager("modeManager")
    assert mm.enter_safe_mode() is True  # nothing connected: fine
    assert mm.enter_safe_mode() is False
    listener = _Listener("detumbleManager")
    mm.output_port("modeChanged").connect(0, listener.input_port("systemModeChanged"))
    assert mm.exit_safe_mode() is True
    assert mm.exit_safe_mode() is False
    mm.enter_safe_mode(SafeModeReason.LOW_BATTERY)
    assert listener.seen == [SystemMode.NORMAL, SystemMode.SAFE_MODE]
    assert mm.safe_mode_entries == 2
