"""Rate groups: call their members in order, with a context each, once per cycle.

Both kinds keep F´'s ActiveRateGroup telemetry and slip detection: ``RgMaxTime`` (longest cycle,
µs of wall-clock execution), ``RgCycleSlips`` and the ``RateGroupCycleSlip`` event. A slip is
counted when a cycle starts before the previous one finished: a cycle still queued when the next
arrives, or a cycle whose members took, in the deployment's clock, at least the group's period.

A member that raises does not stop the group: the fault becomes a throttled ``RateGroupMemberFault``
(WARNING_HI) event and the ``RgMemberFaults`` count, and the next member runs (an fprime-lite
addition: in C++ such a fault would be an assertion).
"""

from __future__ import annotations

import logging
import time as _wall
from typing import TYPE_CHECKING, Any

from fprime_lite.model.component import ActiveComponent, PassiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Cycle, Ping, Sched
from fprime_lite.model.ports import OutputPort, OutputPortArray, async_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.time import Time
from fprime_lite.model.types import String, U32

__all__ = ["ActiveRateGroup", "PassiveRateGroup", "RateGroupBase"]

log = logging.getLogger("fprime_lite")


class RateGroupBase:
    """The cycle logic shared by both rate-group kinds (mixed into a component class)."""

    MAX_MEMBERS = 25  # F´ ActiveRateGroupOutputPorts: 10 in F´'s default config, 25 in PROVES's
    RateGroupMemberOut = OutputPort(Sched, size=MAX_MEMBERS)

    RateGroupStarted = Event(Severity.DIAGNOSTIC, "Rate group started.")
    RateGroupCycleSlip = Event(Severity.WARNING_HI, "Rate group cycle slipped on cycle {}", cycle=U32,
                               throttle=5)
    RateGroupMemberFault = Event(Severity.WARNING_HI, "Rate group member {} raised: {}", member=U32,
                                 error=String(80), throttle=5)

    RgMaxTime = Channel(U32, format="{} us", wall_clock=True)
    RgCycleSlips = Channel(U32)
    RgMemberFaults = Channel(U32)

    if TYPE_CHECKING:  # provided by the component class the mixin is combined with
        name: str

        def output_port(self, name: str) -> OutputPortArray: ...

        def get_time(self) -> Time: ...

        timeCaller: Any
        _clock: Any
        _clock_now: Any

    def _setup(self, contexts, period_us: int | None) -> None:
        contexts = list(contexts)
        if len(contexts) > self.MAX_MEMBERS:
            raise ValueError(f"{self.name}: at most {self.MAX_MEMBERS} members, got {len(contexts)}")
        self.contexts = contexts + [0] * (self.MAX_MEMBERS - len(contexts))
        self.period_us = period_us
        self.cycles = 0
        self.slips = 0
        self.member_faults = 0
        self.max_time_us = 0
        self._member_port = self.output_port("RateGroupMemberOut")
        self._members: list = []
        self._members_version = -1
        self._started = False
        self._pending = 0

    def _cycle(self, cycle_start: Time) -> None:
        if not self._started:
            self._started = True
            self.RateGroupStarted()
        wall0 = _wall.perf_counter()
        port = self._member_port
        if port.version != self._members_version:
            self._members = [(i, port.calls[i], self.contexts[i]) for i in range(self.MAX_MEMBERS)
                             if port.targets[i] is not None]
            self._members_version = port.version
        for i, call, context in self._members:
            try:
                call(context)
            except Exception as exc:  # a member fault must not stop the group
                self.member_faults += 1
                log.exception("%s: member %d raised", self.name, i)
                self.RateGroupMemberFault(i, f"{type(exc).__name__}: {exc}"[:80])
                self.RgMemberFaults.write(self.member_faults)
        elapsed_us = int((_wall.perf_counter() - wall0) * 1e6)
        if elapsed_us > self.max_time_us:
            self.max_time_us = elapsed_us
        # One time read stamps RgMaxTime and ends the cycle: both are this instant. get_time's
        # shortcut written out (the clock's Time of this instant, when the time port is its clock).
        clock = self._clock
        if self.timeCaller[0] is self._clock_now and clock._now_at == clock.current_us:
            now = clock._now
        else:
            now = self.get_time()
        self.RgMaxTime.write(self.max_time_us, now)
        # As F´'s ActiveRateGroup: the cycle's time is measured from the driver's cycle start.
        overran = (self.period_us is not None and cycle_start.time_base == now.time_base
                   and now.total_us - cycle_start.total_us >= self.period_us)
        if overran or self._pending > 0:
            self._slip()
        elif self.RateGroupCycleSlip.count:
            self.RateGroupCycleSlip.count -= 1  # as F´: each good cycle lets one more slip be reported
        self.cycles += 1

    def _slip(self) -> None:
        self.slips += 1
        self.RateGroupCycleSlip(self.cycles)
        self.RgCycleSlips.write(self.slips)


class ActiveRateGroup(RateGroupBase, ActiveComponent):
    """F´'s ActiveRateGroup: ``CycleIn`` is queued; members run when the group is dispatched.

    In a deterministic deployment a cycle that finds the group idle runs at once, as the
    top-priority rate-group thread would (``run_when_idle``, decision 0004). ``PingIn`` answers
    health pings on ``PingOut``, as F´'s does.

    Args:
        contexts: the context passed to member ``i`` (up to ten).
        period_us: the group's period, for slip detection in the deployment's clock.
    """

    PingOut = OutputPort(Ping)

    def __init__(self, name: str, *, base_id: int = 0, queue_size: int = 10, contexts=(),
                 period_us: int | None = None):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        self._setup(contexts, period_us)

    # run_when_idle: in a deterministic deployment an idle group runs its cycle as soon as the
    # driver posts it, as a top-priority rate-group thread would (decision 0004).
    @async_input(Cycle, queue_full="drop", run_when_idle=True)
    def CycleIn(self, cycle_start: Time) -> None:
        self._pending = len(self._queue._heap)  # cycles still waiting behind this one
        self._cycle(cycle_start)

    @async_input(Ping)
    def PingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("PingOut", 0):
            self.PingOut[0](key)


class PassiveRateGroup(RateGroupBase, PassiveComponent):
    """F´'s PassiveRateGroup: members run on the caller's thread when ``CycleIn`` is called."""

    def __init__(self, name: str, *, base_id: int = 0, contexts=(), period_us: int | None = None):
        super().__init__(name, base_id=base_id)
        self._setup(contexts, period_us)
        self._running = False

    @sync_input(Cycle)
    def CycleIn(self, cycle_start: Time) -> None:
        if self._running:  # re-entered from inside a member: the previous cycle has not finished
            self._slip()
            return
        self._running = True
        try:
            self._cycle(cycle_start)
        finally:
            self._running = False
