"""Health: pings every monitored component and declares it late when it stops answering.

F´'s ``Svc.Health`` (a *queued* component; instance ``health`` in F´'s CdhCore). ``PingSend[i]``
connects to the ``pingIn`` of monitored component ``i`` and that component's ``pingOut`` back to
``PingReturn[i]``. On each ``Run`` tick Health first handles the ping answers queued since the
last tick, then, for every enabled entry:

- no ping outstanding: send a new one with a fresh key;
- ping outstanding for ``warn_cycles`` ticks: ``HLTH_PING_WARN`` (WARNING_HI) and the
  ``PingLateWarnings`` count; for ``fatal_cycles`` ticks: ``HLTH_PING_LATE`` (FATAL).

An answer with the wrong key is ``HLTH_PING_WRONG_KEY`` (FATAL). Finally the watchdog is stroked
on ``WdogStroke`` with a code that toggles 0/1. The cycle counting is F´'s exactly (a warning on
the tick the count *equals* ``warn_cycles``, FATAL when it equals ``fatal_cycles``).
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Sequence
from typing import Annotated

from fprime_lite.model.commands import CmdResponse, async_command
from fprime_lite.model.component import QueuedComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Ping, Sched
from fprime_lite.model.ports import OutputPort, PortType, async_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import U32, FwEnum, String

__all__ = ["Health", "PingEntry", "FwEnabled", "WatchDog", "HEALTH_PING_PORTS"]

#: Size of PingSend / PingReturn (F´ ``HealthPingPorts``).
HEALTH_PING_PORTS = 25

#: Stroke a hardware watchdog with a toggling code (F´ ``Svc.WatchDog``).
WatchDog = PortType("Svc.WatchDog", code=U32)


class FwEnabled(FwEnum, namespace="Fw", default="DISABLED"):
    """Enabled and disabled states (F´ ``Fw.Enabled``)."""

    DISABLED = 0
    ENABLED = 1


@dataclass
class PingEntry:
    """One monitored component: its name and thresholds in Run ticks (F´ ``PingEntry``)."""

    name: str
    warn_cycles: int
    fatal_cycles: int


@dataclass
class _Tracker:
    entry: PingEntry
    enabled: bool = True
    cycle_count: int = 0
    key: int = 0


class Health(QueuedComponent):
    """F´'s health monitor (``Svc.Health``).

    Args:
        name: instance name (``health`` in F´'s CdhCore).
        entries: the monitored components, in ``PingSend`` index order.
        base_id: added to the local opcodes (0–2), event ids (0–7) and channel id (0).
        queue_size: depth of the queue holding ping answers between ticks.
        watchdog_code: first code written to ``WdogStroke``.
    """

    PingSend = OutputPort(Ping, size=HEALTH_PING_PORTS)
    WdogStroke = OutputPort(WatchDog)

    @async_command(opcode=0)
    def HLTH_ENABLE(self, enable: FwEnabled):
        """Turn health checking on or off."""
        self.enabled = enable == FwEnabled.ENABLED
        self.HLTH_CHECK_ENABLE(enable)

    @async_command(opcode=1)
    def HLTH_PING_ENABLE(self, entry: Annotated[str, String(40)], enable: FwEnabled):
        """Ping (ENABLED) or ignore (DISABLED) one entry."""
        tracker = self._find(entry)
        if tracker is None:
            return CmdResponse.VALIDATION_ERROR
        tracker.enabled = enable == FwEnabled.ENABLED
        self.HLTH_CHECK_PING(enable, entry)

    @async_command(opcode=2)
    def HLTH_CHNG_PING(self, entry: Annotated[str, String(40)], warningValue: U32, fatalValue: U32):
        """Change one entry's warning and FATAL thresholds (ticks)."""
        tracker = self._find(entry)
        if tracker is None:
            return CmdResponse.VALIDATION_ERROR
        if warningValue > fatalValue:
            self.HLTH_PING_INVALID_VALUES(entry, warningValue, fatalValue)
            return CmdResponse.VALIDATION_ERROR
        tracker.entry.warn_cycles = warningValue
        tracker.entry.fatal_cycles = fatalValue
        self.HLTH_PING_UPDATED(entry, warningValue, fatalValue)

    HLTH_PING_WARN = Event(Severity.WARNING_HI, "Ping entry {} late warning", id=0,
                           args=[("entry", String(40))])
    HLTH_PING_LATE = Event(Severity.FATAL, "Ping entry {} did not respond", id=1,
                           args=[("entry", String(40))])
    HLTH_PING_WRONG_KEY = Event(Severity.FATAL, "Ping entry {} responded with wrong key 0x{x}", id=2,
                                args=[("entry", String(40)), ("badKey", U32)])
    HLTH_CHECK_ENABLE = Event(Severity.ACTIVITY_HI, "Health checking set to {}", id=3,
                              args=[("enabled", FwEnabled)])
    HLTH_CHECK_PING = Event(Severity.ACTIVITY_HI, "Health checking set to {} for {}", id=4,
                            args=[("enabled", FwEnabled), ("entry", String(40))])
    HLTH_CHECK_LOOKUP_ERROR = Event(Severity.WARNING_LO, "Couldn't find entry {}", id=5,
                                    args=[("entry", String(40))])
    HLTH_PING_UPDATED = Event(Severity.ACTIVITY_HI, "Health ping for {} changed to WARN {} FATAL {}", id=6,
                              args=[("entry", String(40)), ("warn", U32), ("fatal", U32)])
    HLTH_PING_INVALID_VALUES = Event(Severity.WARNING_HI,
                                     "Health ping for {} invalid values: WARN {} FATAL {}", id=7,
                                     args=[("entry", String(40)), ("warn", U32), ("fatal", U32)])

    PingLateWarnings = Channel(U32, id=0)

    def __init__(self, name: str = "health", entries: Sequence[PingEntry | tuple] = (), *, base_id: int = 0,
                 queue_size: int = HEALTH_PING_PORTS, watchdog_code: int = 0):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        self.enabled = True
        self.warnings = 0
        self._key = 0
        self._watchdog_code = watchdog_code
        self._trackers: list[_Tracker] = []
        self.set_ping_entries(entries)

    def set_ping_entries(self, entries) -> None:
        """Configure the monitored components (F´ ``setPingEntries``): ``PingEntry`` or tuples."""
        trackers = []
        for e in entries:
            e = e if isinstance(e, PingEntry) else PingEntry(*e)
            if not 0 < e.warn_cycles <= e.fatal_cycles:
                raise ValueError(f"{self.name}: ping entry {e.name!r} needs 0 < warn_cycles <= fatal_cycles, "
                                 f"got {e.warn_cycles} and {e.fatal_cycles}")
            trackers.append(_Tracker(PingEntry(e.name, e.warn_cycles, e.fatal_cycles)))
        if len(trackers) > HEALTH_PING_PORTS:
            raise ValueError(f"{self.name}: at most {HEALTH_PING_PORTS} ping entries, got {len(trackers)}")
        self._trackers = trackers

    @sync_input(Sched)
    def Run(self, context: int) -> None:
        """One health tick: handle answers, send or check pings, stroke the watchdog."""
        self.dispatch_all()
        if self.enabled:
            for index, tracker in enumerate(self._trackers):
                if not tracker.enabled:
                    continue
                if tracker.cycle_count == 0:
                    tracker.key = self._key
                    self._key = (self._key + 1) & 0xFFFFFFFF
                    if self.is_connected("PingSend", index):
                        self.PingSend[index](tracker.key)
                    tracker.cycle_count = 1
                    continue
                if tracker.cycle_count == tracker.entry.warn_cycles:
                    self.HLTH_PING_WARN(tracker.entry.name)
                    self.warnings = (self.warnings + 1) & 0xFFFFFFFF
                    self.PingLateWarnings.write(self.warnings)
                elif tracker.cycle_count == tracker.entry.fatal_cycles:
                    self.HLTH_PING_LATE(tracker.entry.name)
                tracker.cycle_count += 1
        if self.is_connected("WdogStroke", 0):
            self.WdogStroke[0](self._watchdog_code)
            self._watchdog_code = 1 - self._watchdog_code if self._watchdog_code in (0, 1) else 0

    @async_input(Ping, size=HEALTH_PING_PORTS, queue_full="drop")
    def PingReturn(self, port_num: int, key: int) -> None:
        """Answer of entry ``port_num``: the right key clears its count, a wrong key is FATAL."""
        if port_num >= len(self._trackers):
            return
        tracker = self._trackers[port_num]
        if key != tracker.key:
            self.HLTH_PING_WRONG_KEY(tracker.entry.name, key & 0xFFFFFFFF)
            return
        tracker.cycle_count = 0
        tracker.key = 0

    def _find(self, name: str) -> _Tracker | None:
        for tracker in self._trackers:
            if tracker.entry.name == name:
                return tracker
        self.HLTH_CHECK_LOOKUP_ERROR(name)
        return None

    @property
    def entries(self) -> list[PingEntry]:
        return [t.entry for t in self._trackers]
