"""ComDelay as flown: releases the radio's "ready to send" once every DIVIDER+1 rate-group ticks.

The flight downlink is throttled by holding the radio's com status: ``comStatusIn`` (from the
radio, after each packet) is remembered, and ``run`` (10 Hz) passes the held status on
``comStatusOut`` on the first of every ``DIVIDER`` + 1 ticks (default 299: every 30 s; the PROVES
suite sets 20: every 2.1 s) — once per status received, so the radio never gets a second
"go" for one packet. The first status is taken as held at start-up (the radio is idle). Changing
DIVIDER logs DividerSet(divider).

Ground interface (flight ``Components.ComDelay``, base id 0x1001E000): parameter DIVIDER (U16,
default 299) with DIVIDER_PRM_SET / DIVIDER_PRM_SAVE; event DividerSet.
"""

from __future__ import annotations

from fprime_lite import U16, Event, OutputPort, Param, PassiveComponent, Sched, Severity, sync_input
from fprime_lite.model.fw_types import Success

from detumble.drivers.ports import SuccessCondition

__all__ = ["ComDelay", "DEFAULT_DIVIDER"]

DEFAULT_DIVIDER = 299


class ComDelay(PassiveComponent):
    """Divides the rate-group tick into the radio's transmit opportunities (instance ``downlinkDelay``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    ticks: int
    held: bool
    status: Success

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """One tick: release the held com status on the first of every DIVIDER + 1 ticks."""
        if self.ticks == 0 and self.held:
            self.held = False
            if self.is_connected("comStatusOut", 0):
                self.comStatusOut[0](self.status)
        self.ticks = 0 if self.ticks >= self.DIVIDER.value else self.ticks + 1

    @sync_input(SuccessCondition)
    def comStatusIn(self, condition: Success) -> None:
        """The radio's latest com status, held until the next release."""
        self.status = Success(condition)
        self.held = True

    comStatusOut = OutputPort(SuccessCondition)

    DIVIDER = Param(U16, default=DEFAULT_DIVIDER, units="ticks")

    DividerSet = Event(Severity.ACTIVITY_HI, "Set divider to: {}", divider=U16)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.ticks = 0
        self.status = Success.SUCCESS
        self.held = True

    def parameter_updated(self, local_id: int) -> None:
        if local_id == self.DIVIDER.local_id:
            self.DividerSet(self.DIVIDER.value)
