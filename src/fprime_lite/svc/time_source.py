"""TimeSource: answers every component's time request from the deployment's clock.

F´'s ``Svc.PosixTime`` / ``Svc.LinuxTime``: every component's ``timeCaller`` connects to
``timeGetPort``, which returns ``clock.now()`` — an :class:`~fprime_lite.model.time.Time` in the clock's
time base and context. With a :class:`~fprime_lite.model.time.SimulatedClock` (the default in a
deterministic deployment) the time is whatever the scheduler has advanced it to.
"""

from __future__ import annotations

from fprime_lite.model.component import PassiveComponent
from fprime_lite.model.fw_ports import TimeGet
from fprime_lite.model.ports import sync_input
from fprime_lite.model.time import Clock, Time

__all__ = ["TimeSource"]


class TimeSource(PassiveComponent):
    """The time source of a deployment.

    Args:
        name: instance name (``posixTime`` / ``linuxTime`` in F´ deployments).
        clock: the :class:`~fprime_lite.model.time.Clock` whose ``now()`` is returned.
        base_id: unused (TimeSource has no commands, events or channels).
    """

    def __init__(self, name: str, clock: Clock, *, base_id: int = 0):
        if not isinstance(clock, Clock):
            raise TypeError(f"{name}: clock must be a fprime_lite.model.time.Clock, got {clock!r}")
        super().__init__(name, base_id=base_id)
        self.clock = clock
        # The handler is exactly ``clock.now()``: let connections call the clock directly. Every
        # event and channel is stamped through this port, several times per rate-group tick.
        self.input_port("timeGetPort").entries[0] = clock.now

    @sync_input(TimeGet)
    def timeGetPort(self) -> Time:
        """The clock's current time."""
        return self.clock.now()
