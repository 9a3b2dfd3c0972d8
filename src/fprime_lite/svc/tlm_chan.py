"""TlmChan: keeps the latest value of every telemetry channel and sends the new ones each tick.

F´'s ``Svc.TlmChan`` (instance ``tlmSend`` in F´'s CdhCore subtopology). Every component's
``tlmOut`` connects to ``TlmRecv``, which stores the latest value and time tag per channel id. On
each ``Run`` tick (a rate-group member), every channel written since the previous tick is sent out
of ``PktSend``, packed into ``FW_PACKET_TELEM`` packets of at most
:data:`~fprime_lite.wire.packets.TLM_PACKET_MAX` bytes: ``U16 descriptor | {U32 id | Time | value}…``.
Channels are sent in the order they were first received (deterministic). ``TlmGet`` reads the
latest stored value of one channel.

Serialised at downlink: a channel write of a component whose ``tlmOut`` connects straight to
``TlmRecv`` reaches :meth:`TlmChan.store_tlm_value` with the value and its type's packer rather than
the packed bytes (:mod:`fprime_lite.model.telemetry`); the store keeps value, packer and time and
packs only the value it downlinks (once a tick) or hands out through ``TlmGet``. The bytes are
those the write would have packed: only immutable values are stored this way.

Differences from F´: the channel store is a dict and has no fixed hash table to run out of; a
single record larger than a packet (which F´ cannot hold in a ComBuffer) is sent alone in its own
packet and counted in :attr:`TlmChan.oversize_records`.
"""

from __future__ import annotations

import logging
import struct

from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.fw_ports import Com, Ping, Sched, Tlm
from fprime_lite.wire.packets import TLM_PACKET_MAX, Apid
from fprime_lite.model.ports import OutputPort, PortType, async_input, guarded_input, sync_input
from fprime_lite.model.time import TIME
from fprime_lite.model.types import U32, FwEnum

__all__ = ["TlmChan", "TlmGet", "TlmValid"]

log = logging.getLogger("fprime_lite")

_U32 = struct.Struct(">I")
_HEADER = struct.pack(">H", Apid.FW_PACKET_TELEM)


class TlmValid(FwEnum, namespace="Fw"):
    """Whether a telemetry read found a value (F´ ``Fw.TlmValid``)."""

    VALID = 0
    INVALID = 1


#: Read the latest value of channel ``id``: returns ``(TlmValid, Time | None, bytes | None)``.
TlmGet = PortType("Fw.TlmGet", returns=tuple, id=U32)


class TlmChan(ActiveComponent):
    """F´'s telemetry channel store (``Svc.TlmChan``).

    Args:
        name: instance name (``tlmSend`` in F´'s CdhCore).
        base_id: unused by TlmChan itself (it has no commands, events or channels).
        queue_size: depth of the message queue (Run ticks and pings).
        packet_max: largest packet built, descriptor included.
    """

    PktSend = OutputPort(Com)
    pingOut = OutputPort(Ping)

    def __init__(self, name: str = "tlmSend", *, base_id: int = 0, queue_size: int = 10,
                 packet_max: int = TLM_PACKET_MAX):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        if packet_max < len(_HEADER) + 4 + TIME.size:
            raise ValueError(f"{name}: packet_max {packet_max} cannot hold one telemetry record")
        self.packet_max = packet_max
        #: channel id -> (time, value, packer) of its latest write, a new tuple for every write;
        #: ``value`` is F´ bytes when ``packer`` is None, else the Python value ``packer`` packs.
        self._latest: dict[int, tuple] = {}
        #: channel id -> the ``_latest`` entry sent last; an entry not identical to it is new.
        self._sent: dict[int, tuple] = {}
        self.packets_sent = 0
        self.records_sent = 0
        self.oversize_records = 0
        self.rejected_writes = 0

    #: The input port whose writers may hand over values instead of bytes (see store_tlm_value).
    deferred_tlm_input = "TlmRecv"

    @property
    def deferred_tlm_table(self) -> str | None:
        """The attribute naming the dict :meth:`store_tlm_value` assigns ``(time, value, pack)`` to,
        which a channel's generated writer assigns to itself (``fprime_lite.model.telemetry``); None
        when a subclass overrides ``store_tlm_value``, whose every call must then happen."""
        return "_latest" if type(self).store_tlm_value is TlmChan.store_tlm_value else None

    @sync_input(Tlm)
    def TlmRecv(self, chan_id: int, time, value: bytes) -> None:
        """Store the latest ``value`` (F´ bytes) and ``time`` of channel ``chan_id`` (never raises).

        Safe from any thread without the component lock: the store is one dict assignment, which
        CPython makes atomic, and ``Run`` works on a copy of the store. Every telemetry write of the
        deployment comes through here, so it is kept to that one assignment.
        """
        # Only the latest value of each channel is downlinked, so the record is built at Run time.
        if type(value) is not bytes or type(chan_id) is not int or not 0 <= chan_id <= 0xFFFFFFFF:
            try:
                value = bytes(value)
                _U32.pack(chan_id)
            except Exception as exc:  # noqa: BLE001 - a bad write is counted and reported, never raised to the writer
                self.rejected_writes += 1
                self.report_fault("TlmRecv", exc)
                return
        self._latest[chan_id] = (time, value, None)

    def store_tlm_value(self, chan_id: int, time, value, pack) -> None:
        """What ``TlmRecv`` does for a write whose bytes are ``pack(value)``, packed when needed.

        Called by channel writes connected to ``TlmRecv`` (never by a port of another type): the id
        is a channel's own, the value already checked against its type, ``pack`` the type's packer.
        """
        self._latest[chan_id] = (time, value, pack)

    @guarded_input(TlmGet)
    def TlmGet(self, chan_id: int) -> tuple:
        """``(TlmValid.VALID, time, value bytes)`` of channel ``chan_id``, or ``(INVALID, None, None)``."""
        entry = self._latest.get(chan_id)
        if entry is None:
            return TlmValid.INVALID, None, None
        time, value, pack = entry
        return TlmValid.VALID, time, value if pack is None else pack(value)

    @async_input(Sched)
    def Run(self, context: int) -> None:
        """Send every channel written since the last tick, in packets of at most ``packet_max``."""
        sent = self._sent
        records = []
        # The bytes of each time stamp, packed once a tick: channels written at one instant share
        # its Time (keyed by identity: the entries hold every time alive until Run returns).
        time_bytes: dict[int, bytes] = {}
        for chan_id, entry in self._latest.copy().items():  # a copy: writers may add channels meanwhile
            if sent.get(chan_id) is entry:
                continue
            sent[chan_id] = entry
            time, value, pack = entry
            try:
                stamp = time_bytes.get(id(time))
                if stamp is None:
                    stamp = time_bytes[id(time)] = TIME.serialize(time)
                records.append(_U32.pack(chan_id) + stamp + (value if pack is None else pack(value)))
            except Exception as exc:  # noqa: BLE001 - a bad time stamp is counted and reported, never raised
                self.rejected_writes += 1
                self.report_fault(f"Run: channel 0x{chan_id:X}", exc)
        if not records:
            return
        for packet in self._pack(records):
            if self.is_connected("PktSend", 0):
                self.PktSend[0](packet, 0)
            self.packets_sent += 1
        self.records_sent += len(records)

    def _pack(self, records: list[bytes]) -> list[bytes]:
        packets = []
        parts = [_HEADER]
        size = header = len(_HEADER)
        packet_max = self.packet_max
        for record in records:
            n = len(record)
            if size + n > packet_max and size > header:  # size > header: the packet holds a record
                packets.append(b"".join(parts))
                parts = [_HEADER]
                size = header
            if header + n > packet_max:
                self.oversize_records += 1
                log.warning("%s: a record of %d bytes does not fit a %d-byte packet; sending it alone",
                            self.name, n, packet_max)
            parts.append(record)
            size += n
        if size > header:
            packets.append(b"".join(parts))
        return packets

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    @property
    def channel_ids(self) -> list[int]:
        """Ids of every channel stored so far, in order of first write."""
        return list(self._latest)
