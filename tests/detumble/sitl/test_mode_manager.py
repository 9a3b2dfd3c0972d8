"""Simulated ModeManager: getMode, modeChanged, FORCE_SAFE_MODE / EXIT_SAFE_MODE, events, channels."""

import pytest

from detumble.sitl import ModeManager
from detumble.components.types import SystemMode, SystemModeChanged
from fprime_lite import CmdResponse, PassiveComponent, Severity, sync_input


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(ModeManager("modeManager", base_id=0x5000))


def test_starts_in_normal(h):
    assert h.invoke("getMode") == SystemMode.NORMAL
    assert ModeManager("m", initial_mode=SystemMode.SAFE_MODE).getMode() == SystemMode.SAFE_MODE


def test_force_safe_mode_command(h):
    h.send_command("FORCE_SAFE_MODE", cmd_seq=4)
    h.assert_cmd_response(0, "FORCE_SAFE_MODE", CmdResponse.OK, cmd_seq=4)
    assert h.invoke("getMode") == SystemMode.SAFE_MODE
    assert [e.name for e in h.events] == ["ManualSafeModeEntry", "EnteringSafeMode"]
    h.assert_event("EnteringSafeMode", 0, "Ground command")
    assert h.events[1].severity == Severity.WARNING_HI
    assert [c.args for c in h.from_port("modeChanged")] == [(SystemMode.SAFE_MODE,), (SystemMode.SAFE_MODE,)]
    assert h.tlm_values("CurrentMode") == [1]
    assert h.tlm_values("SafeModeEntryCount") == [1]


def test_force_safe_mode_twice_changes_nothing(h):
    h.send_command("FORCE_SAFE_MODE")
    h.clear_history()
    h.send_command("FORCE_SAFE_MODE")
    h.assert_cmd_response(0, "FORCE_SAFE_MODE", CmdResponse.OK)
    h.assert_events_size(0)
    h.assert_from_port_history_size(0)


def test_exit_safe_mode(h):
    h.send_command("FORCE_SAFE_MODE")
    h.clear_history()
    h.send_command("EXIT_SAFE_MODE")
    h.assert_cmd_response(0, "EXIT_SAFE_MODE", CmdResponse.OK)
    assert h.invoke("getMode") == SystemMode.NORMAL
    h.assert_event_count("ExitingSafeMode", 1)
    assert h.from_port("modeChanged")[0].args == (SystemMode.NORMAL,)
    assert h.tlm_values("CurrentMode") == [2]


def test_exit_safe_mode_refused_when_not_in_safe_mode(h):
    h.send_command("EXIT_SAFE_MODE")
    h.assert_cmd_response(0, "EXIT_SAFE_MODE", CmdResponse.VALIDATION_ERROR)
    h.assert_event("CommandValidationFailed", 0, "EXIT_SAFE_MODE", "Not currently in safe mode")
    h.assert_from_port_history_size(0)


def test_force_safe_mode_port_reports_an_external_fault(h):
    h.invoke("forceSafeMode")
    assert h.component.mode == SystemMode.SAFE_MODE
    assert [e.name for e in h.events] == ["ExternalFaultDetected", "EnteringSafeMode"]


def test_run_writes_current_mode(h):
    h.invoke("run", 0)
    h.invoke("run", 0)
    assert h.tlm_values("CurrentMode") == [2, 2]


def test_python_api_and_long_reasons(h):
    assert h.component.enter_safe_mode("x" * 300) is True
    assert h.events_named("EnteringSafeMode")[0] == ("x" * 100,)
    assert h.component.enter_safe_mode() is False
    assert h.component.exit_safe_mode() is True
    assert h.component.exit_safe_mode() is False
    assert h.component.safe_mode_entries == 1


class _Listener(PassiveComponent):
    @sync_input(SystemModeChanged)
    def systemModeChanged(self, mode):
        self.seen.append(mode)

    def __init__(self, name):
        super().__init__(name)
        self.seen = []


def test_unconnected_and_connected_mode_changed():
    mm = ModeManager("modeManager")
    mm.enter_safe_mode()  # nothing connected: fine
    listener = _Listener("detumbleManager")
    mm.output_port("modeChanged").connect(0, listener.input_port("systemModeChanged"))
    mm.exit_safe_mode()
    mm.enter_safe_mode()
    assert listener.seen == [SystemMode.NORMAL, SystemMode.SAFE_MODE]
