"""EventManager: filters events and sends each one to the ground as its own packet.

F´'s ``Svc.EventManager`` (instance ``events`` in F´'s CdhCore subtopology). Every component's
``logOut`` connects to ``LogRecv``; each event that passes the filters leaves ``PktSend`` as one
``FW_PACKET_LOG`` packet ``U16 descriptor | U32 id | Time | arguments`` — one event per packet,
because fprime-gds 4.4.1 decodes only the first event of a log packet.

Filters, as in F´:

- a severity filter per severity (``SET_EVENT_FILTER``): ``ENABLED`` means events of that
  severity are *sent*; by default every severity is enabled except ``DIAGNOSTIC``;
- an id filter (``SET_ID_FILTER``) of up to :data:`ID_FILTER_SIZE` event ids that are *not* sent;
- ``FATAL`` events pass every filter and are also announced on ``FatalAnnounce``.

Difference from F´: ``LogRecv`` is **sync** and sends the packet on the caller's thread. F´'s
``LogRecv`` is sync too but hands the event to the component's own thread through an internal
queue (``loqQueue``), which can drop events when full. Sending directly means events are never
reordered or dropped for lack of queue room. ``EventsDropped`` therefore counts the events that
could not be sent at all (invalid severity, a packet larger than :data:`EVENT_PACKET_MAX`, an
unserializable time tag). Events stopped by the filters are counted separately, in
:attr:`EventManager.filtered_by_severity` and :attr:`EventManager.filtered_by_id`.

Event times in simulated time: F´ stamps each event when it is emitted, and on hardware time passes
between two emissions. Under a simulated clock every handler runs in zero time, so the events of
one command (dispatched, the component's own, completed) would share one stamp and a ground
system that orders or deduplicates by time shows them out of order or as one. ``LogRecv`` (called
synchronously at emission) therefore sends an event emitted at the same instant as the previous
one 1 µs after it: stamps are strictly increasing in emission order and never more than the
number of events of that instant in µs late (``distinct_times=False`` keeps the raw stamps).
"""

from __future__ import annotations

import logging

from fprime_lite.model.commands import CmdResponse, async_command, sync_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.errors import SerializationError
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Com, FatalEvent, Log, Ping, Sched
from fprime_lite.wire.packets import encode_event
from fprime_lite.model.ports import OutputPort, async_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.time import Time
from fprime_lite.model.types import BOOL, U8, U32, U64, FwEnum

__all__ = ["EventManager", "FilterSeverity", "Enabled", "ID_FILTER_SIZE", "EVENT_PACKET_MAX",
           "DEFAULT_SEVERITY_FILTER"]

log = logging.getLogger("fprime_lite")

#: How many event ids the id filter holds (F´ ``TELEM_ID_FILTER_SIZE``).
ID_FILTER_SIZE = 25
#: Largest event packet sent, descriptor included (F´ ``FW_COM_BUFFER_MAX_SIZE``).
EVENT_PACKET_MAX = 512


class FilterSeverity(FwEnum, namespace="Svc.EventManager", rep=U8):
    """The severities a filter can be set for (F´ ``Svc.EventManager.FilterSeverity``; no FATAL)."""

    WARNING_HI = 0
    WARNING_LO = 1
    COMMAND = 2
    ACTIVITY_HI = 3
    ACTIVITY_LO = 4
    DIAGNOSTIC = 5


class Enabled(FwEnum, namespace="Svc.EventManager", rep=U8):
    """Filter state (F´ ``Svc.EventManager.Enabled``; note ENABLED is 0)."""

    ENABLED = 0
    DISABLED = 1


_TO_SEVERITY = {fs: Severity[fs.name] for fs in FilterSeverity}

#: Severity filter defaults (F´ ``EventManagerCfg.hpp``): True means the severity is sent.
DEFAULT_SEVERITY_FILTER = {
    Severity.WARNING_HI: True,
    Severity.WARNING_LO: True,
    Severity.COMMAND: True,
    Severity.ACTIVITY_HI: True,
    Severity.ACTIVITY_LO: True,
    Severity.DIAGNOSTIC: False,
}


class EventManager(ActiveComponent):
    """F´'s event manager (``Svc.EventManager``).

    Args:
        name: instance name (``events`` in F´'s CdhCore).
        base_id: added to the local opcodes (0, 2, 3), event ids (0–4) and channel id (0).
        queue_size: depth of the message queue.
        severity_filter: overrides of :data:`DEFAULT_SEVERITY_FILTER` (severity -> sent?).
    """

    PktSend = OutputPort(Com)
    FatalAnnounce = OutputPort(FatalEvent)
    pingOut = OutputPort(Ping)

    # Instance state, declared here so the command handlers above __init__ see the types.
    _severity_enabled: dict[Severity, bool]
    _filtered_ids: frozenset[int]
    id_filter_size: int

    # --- commands ------------------------------------------------------------------------------

    @sync_command(opcode=0)
    def SET_EVENT_FILTER(self, filterLevel: FilterSeverity, filterEnabled: Enabled):
        """Send (ENABLED) or stop (DISABLED) the events of one severity."""
        with self._lock:
            state = dict(self._severity_enabled)
            state[_TO_SEVERITY[filterLevel]] = filterEnabled == Enabled.ENABLED
            self._severity_enabled = state
        return CmdResponse.OK

    @async_command(opcode=2)
    def SET_ID_FILTER(self, ID: U32, idFilterEnabled: Enabled):
        """Stop (ENABLED) or resume (DISABLED) sending the event with id ``ID``."""
        if idFilterEnabled == Enabled.ENABLED:
            with self._lock:
                full = ID not in self._filtered_ids and len(self._filtered_ids) >= self.id_filter_size
                if not full:
                    self._filtered_ids = self._filtered_ids | {ID}
            if full:
                self.ID_FILTER_LIST_FULL(ID)
                return CmdResponse.EXECUTION_ERROR
            self.ID_FILTER_ENABLED(ID)
            return CmdResponse.OK
        with self._lock:
            found = ID in self._filtered_ids
            if found:
                self._filtered_ids = self._filtered_ids - {ID}
        if not found:
            self.ID_FILTER_NOT_FOUND(ID)
            return CmdResponse.EXECUTION_ERROR
        self.ID_FILTER_REMOVED(ID)
        return CmdResponse.OK

    @async_command(opcode=3)
    def DUMP_FILTER_STATE(self):
        """Report every severity filter, then every filtered id, as events."""
        severity_state = self._severity_enabled
        for fs in FilterSeverity:
            self.SEVERITY_FILTER_STATE(fs, severity_state[_TO_SEVERITY[fs]])
        for event_id in sorted(self._filtered_ids):
            self.ID_FILTER_ENABLED(event_id)

    # --- events --------------------------------------------------------------------------------

    SEVERITY_FILTER_STATE = Event(Severity.ACTIVITY_LO, "{} filter state. {}", id=0,
                                  args=[("severity", FilterSeverity), ("enabled", BOOL)])
    ID_FILTER_ENABLED = Event(Severity.ACTIVITY_HI, "ID {} is filtered.", id=1, args=[("ID", U32)])
    ID_FILTER_LIST_FULL = Event(Severity.WARNING_LO, "ID filter list is full. Cannot filter {} .", id=2,
                                args=[("ID", U32)])
    ID_FILTER_REMOVED = Event(Severity.ACTIVITY_HI, "ID filter ID {} removed.", id=3, args=[("ID", U32)])
    ID_FILTER_NOT_FOUND = Event(Severity.WARNING_LO, "ID filter ID {} not found.", id=4,
                                args=[("ID", U32)])

    # --- telemetry -----------------------------------------------------------------------------

    #: Events that could not be sent (F´ FwSizeType, U64).
    EventsDropped = Channel(U64, id=0, update="on change")

    def __init__(self, name: str = "events", *, base_id: int = 0, queue_size: int = 10,
                 severity_filter: dict | None = None, id_filter_size: int = ID_FILTER_SIZE,
                 distinct_times: bool = True):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        self.distinct_times = distinct_times
        self._last_raw: Time | None = None  # the stamp the last event was emitted with
        self._last_sent: Time | None = None  # the stamp it was sent with
        state = dict(DEFAULT_SEVERITY_FILTER)
        for severity, enabled in (severity_filter or {}).items():
            severity = Severity(severity)
            if severity == Severity.FATAL:
                raise ValueError(f"{name}: FATAL events cannot be filtered")
            state[severity] = bool(enabled)
        # Both filters are replaced whole (never mutated) so LogRecv can read them without a lock.
        self._severity_enabled = state
        self._filtered_ids = frozenset()
        self.id_filter_size = id_filter_size
        #: Events sent out of PktSend.
        self.events_sent = 0
        #: Events stopped by the severity filter.
        self.filtered_by_severity = 0
        #: Events stopped by the id filter.
        self.filtered_by_id = 0
        #: Events that could not be sent (the EventsDropped channel).
        self.dropped = 0

    # --- ports ---------------------------------------------------------------------------------

    @sync_input(Log)
    def LogRecv(self, event_id: int, time, severity, args: bytes) -> None:
        """Filter one event and send it as its own packet (never raises)."""
        try:
            severity = Severity(severity)
        except ValueError:
            self._drop(event_id, f"invalid severity {severity!r}")
            return
        if severity != Severity.FATAL:
            if not self._severity_enabled[severity]:
                self.filtered_by_severity += 1
                return
            if event_id in self._filtered_ids:
                self.filtered_by_id += 1
                return
        if self.distinct_times and isinstance(time, Time):
            time = self._distinct(time)
        try:
            packet = encode_event(event_id, time, bytes(args))
        except (SerializationError, TypeError, ValueError, AttributeError, OverflowError) as exc:
            self._drop(event_id, f"cannot encode it: {exc}")
            return
        if len(packet) > EVENT_PACKET_MAX:
            self._drop(event_id, f"its packet of {len(packet)} bytes exceeds {EVENT_PACKET_MAX} bytes")
        elif self.is_connected("PktSend", 0):
            self.PktSend[0](packet, 0)
            self.events_sent += 1
        if severity == Severity.FATAL and self.is_connected("FatalAnnounce", 0):
            self.FatalAnnounce[0](event_id)

    def _distinct(self, time: Time) -> Time:
        """``time``, or 1 µs after the last event's stamp when emitted at the same instant (or within
        the µs the previous instant's events already took)."""
        last_raw, last_sent = self._last_raw, self._last_sent
        sent = time
        if last_raw is not None and last_sent is not None \
                and time.time_base == last_sent.time_base and time.context == last_sent.context \
                and last_raw.total_us <= time.total_us <= last_sent.total_us:
            sent = Time.from_us(last_sent.total_us + 1, time.time_base, time.context)
        self._last_raw, self._last_sent = time, sent
        return sent

    @async_input(Sched, queue_full="drop")
    def run(self, context: int) -> None:
        """Rate-group tick: write EventsDropped."""
        self.EventsDropped.write(self.dropped)

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    # --- inspection ----------------------------------------------------------------------------

    def severity_enabled(self, severity: Severity) -> bool:
        """True when events of ``severity`` are sent (FATAL always is)."""
        severity = Severity(severity)
        return severity == Severity.FATAL or self._severity_enabled[severity]

    @property
    def filtered_ids(self) -> frozenset[int]:
        """The event ids the id filter stops."""
        return self._filtered_ids

    def _drop(self, event_id, why: str) -> None:
        self.dropped += 1
        log.warning("%s: dropped event %r: %s", self.name, event_id, why)
