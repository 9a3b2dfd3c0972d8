"""ModeManager as flown: the PROVES ``Components.ModeManager`` ground interface and behaviour.

The spacecraft-level mode (NORMAL / SAFE_MODE), why it is in safe mode (``SafeModeReason``), and
the automatic transitions of the flight component:

* **low battery** — every ``run`` (1 Hz) reads the system voltage through ``voltageGet``; after
  ``SafeModeDebounceSeconds`` consecutive readings below ``SafeModeEntryVoltage`` (or with the port
  unconnected: no reading is a fault) it enters safe mode with reason LOW_BATTERY
  (AutoSafeModeEntry, then EnteringSafeMode). In safe mode *for LOW_BATTERY only*,
  ``SafeModeDebounceSeconds`` consecutive readings above ``SafeModeRecoveryVoltage`` return it to
  NORMAL (AutoSafeModeExit). Other reasons need EXIT_SAFE_MODE.
* **command loss** — ``packetRouted`` (a packet reached the router) resets a seconds counter that
  every ``run`` increments; when it reaches ``COMM_LOSS_TIME`` seconds it logs CommandLossDetected,
  enters safe mode with reason COMMAND_LOSS and calls ``stopWatchdog`` (the flight last resort: the
  hardware watchdog then power-cycles the board). It fires once until the next packet.
* **entering safe mode** turns every connected ``loadSwitchTurnOff[i]`` off and notifies
  ``modeChanged``; **leaving** it turns every connected ``loadSwitchTurnOn[i]`` on (the reference
  deployment connects indices 0–5, the face switches; the payload switches stay off).
* **persistence** — mode, entry count, reason and a clean-shutdown flag live in ``mode_state.bin``
  on the simulated flash (``spacecraft.flash_dir``). At start-up the state is restored; a NORMAL
  state without the clean-shutdown flag (``prepareForReboot`` was not called before the reset) is an
  unintended reboot: UnintendedRebootDetected and safe mode with reason SYSTEM_FAULT.

Ground interface (flight ids: events, channels, parameters and opcodes in FPP declaration order):
commands FORCE_SAFE_MODE, EXIT_SAFE_MODE, GET_CURRENT_MODE, GET_SAFE_MODE_REASON; the flight
events and their formats; channels CurrentMode (U8: 1 SAFE_MODE, 2 NORMAL), SafeModeEntryCount,
CurrentSafeModeReason; parameters SafeModeEntryVoltage, SafeModeRecoveryVoltage,
SafeModeDebounceSeconds, SAFEMODE_SEQUENCE_FILE, COMM_LOSS_TIME. Deviations from the flight code
are listed in ``docs/components/mode_manager.md``.
"""

from __future__ import annotations

import os
import struct

from fprime_lite import (F32, I32, U8, U32, Channel, CmdResponse, Event, FwEnum, OutputPort, Param,
                         PassiveComponent, PortType, Sched, Severity, String, sync_command, sync_input)
from fprime_lite.model.fw_ports import CmdResponsePort, CmdSeqIn
from fprime_lite.model.fw_types import TimeIntervalValue
from fprime_lite.osal.atomic import atomic_write_bytes

from detumble.components.types import GetSystemMode, SystemMode, SystemModeChanged
from detumble.drivers.ports import Signal, VoltageGet

__all__ = ["ModeManager", "SafeModeReason", "ForceSafeModeWithReason", "MODE_CHANGED_PORTS",
           "LOAD_SWITCH_PORTS", "STATE_FILE_NAME"]

#: Number of ``modeChanged`` output indices (flight: 1).
MODE_CHANGED_PORTS = 1
#: Number of ``loadSwitchTurnOn`` / ``loadSwitchTurnOff`` indices (6 faces + 2 payload switches).
LOAD_SWITCH_PORTS = 8
#: The persisted state's file name in the simulated flash (flight: ``/mode_state.bin``).
STATE_FILE_NAME = "mode_state.bin"

_STATE = struct.Struct("<BIBB")  # mode, safe-mode entry count, reason, clean-shutdown flag


class SafeModeReason(FwEnum, namespace="Components"):
    """Why the spacecraft is in safe mode (flight ``Components.SafeModeReason``)."""

    NONE = 0
    LOW_BATTERY = 1
    SYSTEM_FAULT = 2
    GROUND_COMMAND = 3
    EXTERNAL_REQUEST = 4
    LORA = 5
    COMMAND_LOSS = 6


#: Another component forces safe mode with a reason (NONE means EXTERNAL_REQUEST).
ForceSafeModeWithReason = PortType("Components.ForceSafeModeWithReason", reason=SafeModeReason)

_REASON_TEXT = {
    SafeModeReason.LOW_BATTERY: "Low battery voltage",
    SafeModeReason.SYSTEM_FAULT: "System fault (unintended reboot)",
    SafeModeReason.GROUND_COMMAND: "Ground command",
    SafeModeReason.EXTERNAL_REQUEST: "External component request",
    SafeModeReason.LORA: "LoRa communication fault",
    SafeModeReason.COMMAND_LOSS: "Loss of contact with ground",
}


class ModeManager(PassiveComponent):
    """The flight mode manager.

    Args:
        name: instance name (``modeManager``).
        spacecraft: the simulated spacecraft whose flash holds ``mode_state.bin`` (None: no
            persistence, as in unit tests).
        initial_mode: the mode before any state is restored (NORMAL).
    """

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    _low_voltage_s: int

    # --- ports (flight order) ------------------------------------------------------------------

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """1 Hz: voltage monitoring, command-loss check, telemetry."""
        self._command_loss_s += 1
        voltage, valid = self._voltage()
        entry = self.SafeModeEntryVoltage.value
        recovery = self.SafeModeRecoveryVoltage.value
        debounce = self.SafeModeDebounceSeconds.value
        if self.mode == SystemMode.NORMAL:
            if not valid or voltage < entry:
                self._low_voltage_s += 1
                if self._low_voltage_s >= debounce:
                    self._run_safe_mode_sequence()
                    self.AutoSafeModeEntry(SafeModeReason.LOW_BATTERY, voltage if valid else 0.0)
                    self._enter_safe_mode(SafeModeReason.LOW_BATTERY)
                    self._low_voltage_s = 0
            else:
                self._low_voltage_s = 0
            self._recovery_s = 0
        else:
            if self.reason == SafeModeReason.LOW_BATTERY:
                if valid and voltage > recovery:
                    self._recovery_s += 1
                    if self._recovery_s >= debounce:
                        self._exit_safe_mode(automatic_voltage=voltage)
                        self._recovery_s = 0
                else:
                    self._recovery_s = 0
            self._low_voltage_s = 0
        self._command_loss_check()
        self.CurrentMode.write(int(self.mode))
        self.CurrentSafeModeReason.write(self.reason)
        self.SafeModeEntryCount.write(self.safe_mode_entries)

    @sync_input(CmdResponsePort)
    def completeSequence(self, opcode: int, cmd_seq: int, response: CmdResponse) -> None:
        """The safe-mode sequence finished."""
        if response == CmdResponse.OK:
            self.SafeModeSequenceCompleted()
        else:
            self.SafeModeSequenceFailed(response)

    @sync_input(ForceSafeModeWithReason)
    def forceSafeMode(self, reason: SafeModeReason) -> None:
        """Another component forces safe mode (NONE = EXTERNAL_REQUEST); ignored in safe mode."""
        if self.mode == SystemMode.SAFE_MODE:
            self.SafeModeRequestIgnored()
            return
        self.ExternalFaultDetected()
        reason = SafeModeReason(reason)
        self._run_safe_mode_sequence()
        self._enter_safe_mode(SafeModeReason.EXTERNAL_REQUEST if reason == SafeModeReason.NONE else reason)

    @sync_input(GetSystemMode)
    def getMode(self) -> SystemMode:
        """The current system mode."""
        return self.mode

    @sync_input(Signal)
    def prepareForReboot(self) -> None:
        """An intentional reboot follows: persist the state with the clean-shutdown flag set."""
        self.PreparingForReboot()
        self._save_state(clean=True, operation="shutdown")

    @sync_input(Signal)
    def packetRouted(self) -> None:
        """A packet reached the router: restart the command-loss timer."""
        self._command_loss_s = 0
        self._command_loss_latched = False

    modeChanged = OutputPort(SystemModeChanged, size=MODE_CHANGED_PORTS)
    runSequence = OutputPort(CmdSeqIn)
    loadSwitchTurnOn = OutputPort(Signal, size=LOAD_SWITCH_PORTS)
    loadSwitchTurnOff = OutputPort(Signal, size=LOAD_SWITCH_PORTS)
    voltageGet = OutputPort(VoltageGet)
    stopWatchdog = OutputPort(Signal)

    # --- commands ------------------------------------------------------------------------------

    @sync_command()
    def FORCE_SAFE_MODE(self):
        """Enter safe mode with reason GROUND_COMMAND (OK and nothing changes when already there)."""
        if self.mode == SystemMode.SAFE_MODE:
            return CmdResponse.OK
        self._run_safe_mode_sequence()
        self.ManualSafeModeEntry()
        self._enter_safe_mode(SafeModeReason.GROUND_COMMAND)
        return CmdResponse.OK

    @sync_command()
    def EXIT_SAFE_MODE(self):
        """Return to NORMAL, whatever the reason (the flight command always answers OK)."""
        self._exit_safe_mode()
        return CmdResponse.OK

    @sync_command()
    def GET_CURRENT_MODE(self):
        """Report the mode (CurrentModeReading)."""
        self.CurrentModeReading(self.mode)

    @sync_command()
    def GET_SAFE_MODE_REASON(self):
        """Report the safe-mode reason (CurrentSafeModeReasonReading)."""
        self.CurrentSafeModeReasonReading(self.reason)

    # --- events (flight order and formats) -----------------------------------------------------

    EnteringSafeMode = Event(Severity.WARNING_HI, "ENTERING SAFE MODE: {}", reason=String(100))
    ExitingSafeMode = Event(Severity.ACTIVITY_HI, "Exiting safe mode")
    ManualSafeModeEntry = Event(Severity.ACTIVITY_HI, "Safe mode entry commanded manually")
    ExternalFaultDetected = Event(Severity.WARNING_HI,
                                  "External fault detected - external component forced safe mode")
    StatePersistenceFailure = Event(Severity.WARNING_LO, "State persistence {} failed with status {}",
                                    operation=String(20), status=I32)
    AutoSafeModeEntry = Event(Severity.WARNING_HI, "AUTO SAFE MODE ENTRY: reason={} voltage={}V",
                              reason=SafeModeReason, voltage=F32)
    AutoSafeModeExit = Event(Severity.ACTIVITY_HI, "AUTO SAFE MODE EXIT: Voltage recovered to {}V", voltage=F32)
    UnintendedRebootDetected = Event(Severity.WARNING_HI, "UNINTENDED REBOOT DETECTED: Entering safe mode")
    PreparingForReboot = Event(Severity.ACTIVITY_HI, "Preparing for intentional reboot - setting clean shutdown flag")
    SafeModeSequenceCompleted = Event(Severity.ACTIVITY_HI, "Safe Mode Radio Sequence Completed")
    SafeModeSequenceFailed = Event(Severity.WARNING_LO, "Safe Mode Radio Sequence Failed: {}", response=CmdResponse)
    SafeModeRequestIgnored = Event(Severity.WARNING_LO, "SafeMode Request Ignored: Already in Safe Mode")
    CurrentModeReading = Event(Severity.ACTIVITY_LO, "Current mode: {}", mode=SystemMode)
    CurrentSafeModeReasonReading = Event(Severity.ACTIVITY_LO, "Current safe mode reason: {}", reason=SafeModeReason)
    CommandLossDetected = Event(Severity.WARNING_HI,
                                "Command loss detected after {} seconds without contact - entering safe mode",
                                duration=U32)

    # --- telemetry and parameters --------------------------------------------------------------

    #: 1 = SAFE_MODE, 2 = NORMAL.
    CurrentMode = Channel(U8)
    SafeModeEntryCount = Channel(U32)
    CurrentSafeModeReason = Channel(SafeModeReason)

    SafeModeEntryVoltage = Param(F32, default=6.7, units="V")
    SafeModeRecoveryVoltage = Param(F32, default=8.0, units="V")
    SafeModeDebounceSeconds = Param(U32, default=10, units="s")      # 1 Hz samples
    SAFEMODE_SEQUENCE_FILE = Param(String(200), default="/seq/enter_safe.bin")
    COMM_LOSS_TIME = Param(TimeIntervalValue, default=TimeIntervalValue(seconds=3 * 24 * 3600, useconds=0),
                           units="s, µs")

    def __init__(self, name: str, *, base_id: int = 0, spacecraft=None,
                 initial_mode: SystemMode = SystemMode.NORMAL):
        super().__init__(name, base_id=base_id)
        self.spacecraft = spacecraft
        self.mode = SystemMode(initial_mode)
        self.reason = SafeModeReason.NONE if self.mode == SystemMode.NORMAL else SafeModeReason.EXTERNAL_REQUEST
        self.safe_mode_entries = 0
        self._low_voltage_s = 0
        self._recovery_s = 0
        self._command_loss_s = 0
        self._command_loss_latched = False
        self._restored = False

    @property
    def state_path(self) -> str | None:
        """Where the state is persisted (None without a spacecraft)."""
        if self.spacecraft is None:
            return None
        return os.path.join(self.spacecraft.flash_dir, STATE_FILE_NAME)

    # --- start-up: restore the persisted state (the flight ``init``) ---------------------------

    def parameters_loaded(self) -> None:
        if not self._restored:
            self._restored = True
            self.restore_state()

    def restore_state(self) -> None:
        """Read ``mode_state.bin``; detect an unintended reboot; re-apply the mode to the switches."""
        path = self.state_path
        if path is None:
            return
        unintended = False
        try:
            with open(path, "rb") as fh:
                data = fh.read()
        except FileNotFoundError:
            data = None  # first boot: defaults, no warning
        except OSError as exc:
            self.StatePersistenceFailure("load-open", -(exc.errno or 1))
            data = None
        if data is not None and len(data) != _STATE.size:
            self.StatePersistenceFailure("load-read", len(data))
            data = None
        if data is not None:
            mode, count, reason, clean = _STATE.unpack(data)
            if mode in (SystemMode.SAFE_MODE, SystemMode.NORMAL) and reason in SafeModeReason._value2member_map_:
                self.mode, self.safe_mode_entries, self.reason = SystemMode(mode), count, SafeModeReason(reason)
                unintended = clean == 0 and self.mode == SystemMode.NORMAL
                if self.mode == SystemMode.SAFE_MODE:
                    self._switches("loadSwitchTurnOff")
                    self.EnteringSafeMode("State restored from persistent storage")
                else:
                    self._switches("loadSwitchTurnOn")
            else:
                self.StatePersistenceFailure("load-corrupt", mode)
                self.mode, self.safe_mode_entries, self.reason = SystemMode.NORMAL, 0, SafeModeReason.NONE
                self._switches("loadSwitchTurnOn")
        else:
            self._switches("loadSwitchTurnOn")
        if unintended:
            self.UnintendedRebootDetected()
            self._enter_safe_mode(SafeModeReason.SYSTEM_FAULT)
        self._save_state(clean=False, operation="save")

    # --- API (scenarios and tests) --------------------------------------------------------------

    def enter_safe_mode(self, reason: SafeModeReason = SafeModeReason.EXTERNAL_REQUEST) -> bool:
        """Enter SAFE_MODE with ``reason``; False (nothing happens) if already there."""
        if self.mode == SystemMode.SAFE_MODE:
            return False
        self._enter_safe_mode(SafeModeReason(reason))
        return True

    def exit_safe_mode(self) -> bool:
        """Return to NORMAL; False if not in safe mode."""
        if self.mode != SystemMode.SAFE_MODE:
            return False
        self._exit_safe_mode()
        return True

    # --- behaviour ------------------------------------------------------------------------------

    def _enter_safe_mode(self, reason: SafeModeReason) -> None:
        self.mode = SystemMode.SAFE_MODE
        self.safe_mode_entries += 1
        self.reason = reason
        self.EnteringSafeMode(_REASON_TEXT.get(reason, "Unknown"))
        self._switches("loadSwitchTurnOff")
        self.CurrentMode.write(int(self.mode))
        self.SafeModeEntryCount.write(self.safe_mode_entries)
        self.CurrentSafeModeReason.write(self.reason)
        self._notify()
        self._save_state(clean=False, operation="save")

    def _exit_safe_mode(self, automatic_voltage: float | None = None) -> None:
        self.mode = SystemMode.NORMAL
        self.reason = SafeModeReason.NONE
        if automatic_voltage is None:
            self.ExitingSafeMode()
        else:
            self.AutoSafeModeExit(automatic_voltage)
        self._switches("loadSwitchTurnOn")
        self.CurrentMode.write(int(self.mode))
        self.CurrentSafeModeReason.write(self.reason)
        self._notify()
        self._save_state(clean=False, operation="save")

    def _notify(self) -> None:
        for i in range(len(self.modeChanged)):
            if self.is_connected("modeChanged", i):
                self.modeChanged[i](self.mode)

    def _switches(self, port: str) -> None:
        calls = getattr(self, port)
        for i in range(LOAD_SWITCH_PORTS):
            if self.is_connected(port, i):
                calls[i]()

    def _voltage(self) -> tuple[float, bool]:
        if self.is_connected("voltageGet", 0):
            return float(self.voltageGet[0]()), True
        return 0.0, False  # no reading is a fault, never a fake good voltage

    def _run_safe_mode_sequence(self) -> None:
        if self.is_connected("runSequence", 0):
            self.runSequence[0](self.SAFEMODE_SEQUENCE_FILE.value)

    def _command_loss_check(self) -> None:
        limit = self.COMM_LOSS_TIME.value.seconds
        if self._command_loss_s >= limit and not self._command_loss_latched:
            self._command_loss_latched = True
            self.CommandLossDetected(min(self._command_loss_s, 2**32 - 1))
            self._run_safe_mode_sequence()
            self._enter_safe_mode(SafeModeReason.COMMAND_LOSS)
            if self.is_connected("stopWatchdog", 0):
                self.stopWatchdog[0]()

    def _save_state(self, *, clean: bool, operation: str) -> None:
        path = self.state_path
        if path is None:
            return
        try:
            atomic_write_bytes(path, _STATE.pack(int(self.mode), self.safe_mode_entries & 0xFFFFFFFF,
                                                 int(self.reason), 1 if clean else 0))
        except OSError as exc:
            self.StatePersistenceFailure(f"{operation}-write", -(exc.errno or 1))
