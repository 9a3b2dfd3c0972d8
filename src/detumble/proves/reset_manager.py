"""ResetManager as flown: cold and warm resets of the flight computer, by command or by port.

COLD_RESET / WARM_RESET (or a call on ``coldReset`` / ``warmReset``) log INITIATE_COLD_RESET /
INITIATE_WARM_RESET, call ``prepareForReboot`` (the ModeManager sets its clean-shutdown flag) and
pull the simulated flight computer's reset line (:meth:`SimulatedSpacecraft.request_reset`): the
deployment re-initialises every flight component, re-reads the saved parameter file and starts up
again, while the plant keeps flying. As in flight the command is never answered — the processor
resets before a response can leave (the flight handler's EXECUTION_ERROR after ``sys_reboot`` is
unreachable). A warm reset restarts the software in the same way (the simulation does not model
the difference in what the RP2350 preserves).
"""

from __future__ import annotations

from fprime_lite import Event, OutputPort, PassiveComponent, Severity, sync_command, sync_input

from detumble.drivers.ports import Signal
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["ResetManager"]


class ResetManager(PassiveComponent):
    """Resets the flight computer of ``spacecraft`` (instance ``resetManager``)."""

    @sync_command()
    def COLD_RESET(self):
        self.defer_command_response()  # never answered: the processor resets
        self._reset("cold")

    @sync_command()
    def WARM_RESET(self):
        self.defer_command_response()
        self._reset("warm")

    INITIATE_COLD_RESET = Event(Severity.ACTIVITY_HI, "Initiating cold reset", id=0)
    INITIATE_WARM_RESET = Event(Severity.ACTIVITY_HI, "Initiating warm reset", id=1)

    @sync_input(Signal)
    def coldReset(self) -> None:
        self._reset("cold")

    @sync_input(Signal)
    def warmReset(self) -> None:
        self._reset("warm")

    prepareForReboot = OutputPort(Signal)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft

    def _reset(self, kind: str) -> None:
        (self.INITIATE_COLD_RESET if kind == "cold" else self.INITIATE_WARM_RESET)()
        if self.is_connected("prepareForReboot", 0):
            self.prepareForReboot[0]()
        self.spacecraft.request_reset(kind)
