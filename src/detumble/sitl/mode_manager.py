"""Simulated ModeManager: the spacecraft-level mode (NORMAL / SAFE_MODE) the detumble app obeys.

A passive stand-in for the PROVES ``Components.ModeManager`` (which is active and also watches
voltage, watchdog and comm timeouts — none of that is simulated). It keeps the one thing the
detumble application depends on: the current :class:`~detumble.components.types.SystemMode`, queried through
``getMode`` and pushed to listeners through ``modeChanged`` on every transition. Names follow the
flight component: commands ``FORCE_SAFE_MODE`` / ``EXIT_SAFE_MODE``, events ``EnteringSafeMode``,
``ExitingSafeMode``, ``ManualSafeModeEntry``, ``ExternalFaultDetected``,
``CommandValidationFailed``, channels ``CurrentMode`` (U8: 1 = SAFE_MODE, 2 = NORMAL) and
``SafeModeEntryCount``.

Ports: ``getMode() -> SystemMode``; ``modeChanged[i](mode)`` (output array of
:data:`MODE_CHANGED_PORTS`; unconnected indices are skipped); ``forceSafeMode()`` (another component
forces safe mode: ExternalFaultDetected); ``run(context)`` writes ``CurrentMode``.
"""

from __future__ import annotations

from fprime_lite import (Channel, CmdResponse, Event, OutputPort, PassiveComponent, PortType, Sched,
                         Severity, String, sync_command, sync_input)
from fprime_lite.model.types import U8, U32

from detumble.components.types import GetSystemMode, SystemMode, SystemModeChanged

__all__ = ["ModeManager", "ForceSafeMode", "MODE_CHANGED_PORTS"]

#: Number of ``modeChanged`` output indices.
MODE_CHANGED_PORTS = 2

#: Another component asks for safe mode (flight: ``Fw.Signal``).
ForceSafeMode = PortType("Fw.Signal")


class ModeManager(PassiveComponent):
    """Holds the system mode. ``initial_mode`` defaults to NORMAL."""

    # --- ports ---------------------------------------------------------------------------------

    modeChanged = OutputPort(SystemModeChanged, size=MODE_CHANGED_PORTS)

    @sync_input(GetSystemMode)
    def getMode(self) -> SystemMode:
        """The current system mode."""
        return self.mode

    @sync_input(ForceSafeMode)
    def forceSafeMode(self) -> None:
        """Another component forces safe mode (ExternalFaultDetected)."""
        if self.mode != SystemMode.SAFE_MODE:
            self.ExternalFaultDetected()
        self.enter_safe_mode("External component request")

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """Write CurrentMode (the flight 1 Hz housekeeping)."""
        self.CurrentMode.write(int(self.mode))

    # --- commands ------------------------------------------------------------------------------

    @sync_command()
    def FORCE_SAFE_MODE(self):
        """Enter safe mode (OK also when already in safe mode: nothing changes then)."""
        if self.mode != SystemMode.SAFE_MODE:
            self.ManualSafeModeEntry()
        self.enter_safe_mode("Ground command")

    @sync_command()
    def EXIT_SAFE_MODE(self):
        """Return to NORMAL; refused (VALIDATION_ERROR, CommandValidationFailed) when not in safe mode."""
        if self.mode != SystemMode.SAFE_MODE:
            self.CommandValidationFailed("EXIT_SAFE_MODE", "Not currently in safe mode")
            return CmdResponse.VALIDATION_ERROR
        self.exit_safe_mode()
        return CmdResponse.OK

    # --- events and channels -------------------------------------------------------------------

    EnteringSafeMode = Event(Severity.WARNING_HI, "ENTERING SAFE MODE: {}", reason=String(100))
    ExitingSafeMode = Event(Severity.ACTIVITY_HI, "Exiting safe mode")
    ManualSafeModeEntry = Event(Severity.ACTIVITY_HI, "Safe mode entry commanded manually")
    ExternalFaultDetected = Event(Severity.WARNING_HI, "External fault detected - external component forced safe mode")
    CommandValidationFailed = Event(Severity.WARNING_LO, "Command {} failed: {}", cmdName=String(50),
                                    reason=String(100))

    #: Current system mode as U8 (SAFE_MODE = 1, NORMAL = 2), written on every change and by ``run``.
    CurrentMode = Channel(U8)
    #: How many times safe mode was entered.
    SafeModeEntryCount = Channel(U32)

    def __init__(self, name: str, *, base_id: int = 0, initial_mode: SystemMode = SystemMode.NORMAL):
        super().__init__(name, base_id=base_id)
        self.mode = SystemMode(initial_mode)
        self.safe_mode_entries = 0

    # --- API (also for scenarios and tests) ----------------------------------------------------

    def enter_safe_mode(self, reason: str = "Simulation request") -> bool:
        """Enter SAFE_MODE (EnteringSafeMode(reason), modeChanged). False if already there."""
        if self.mode == SystemMode.SAFE_MODE:
            return False
        reason = str(reason).encode("utf-8")[:100].decode("utf-8", "ignore")
        self.mode = SystemMode.SAFE_MODE
        self.safe_mode_entries += 1
        self.EnteringSafeMode(reason)
        self._publish()
        self.SafeModeEntryCount.write(self.safe_mode_entries)
        return True

    def exit_safe_mode(self) -> bool:
        """Return to NORMAL (ExitingSafeMode, modeChanged). False if not in safe mode."""
        if self.mode != SystemMode.SAFE_MODE:
            return False
        self.mode = SystemMode.NORMAL
        self.ExitingSafeMode()
        self._publish()
        return True

    def _publish(self) -> None:
        self.CurrentMode.write(int(self.mode))
        out = self.modeChanged
        for i in range(len(out)):
            if self.is_connected("modeChanged", i):
                out[i](self.mode)
