"""TlmPacketizer: downlinks telemetry in fixed packets declared by the topology.

F´'s ``Svc.TlmPacketizer`` (instance ``tlmSend`` of CdhCore where a deployment packetizes, as
PROVES's flight software and F´'s Ref do), with the ground interface of F´'s
``Svc/TlmPacketizer/TlmPacketizer.fpp`` before telemetry sections: commands ``SET_LEVEL`` (opcode 0)
and ``SEND_PKT`` (1); events ``NoChan`` (0), ``LevelSet`` (1), ``MaxLevelExceed`` (2),
``PacketSent`` (3), ``PacketNotFound`` (4); channel ``SendLevel`` (0).

A packet is ``U16 FW_PACKET_PACKETIZED_TLM (4) | U16 packet id | Time (11 bytes) | values…``: every
member channel has a fixed slot of its type's largest serialized size, in the packet's declared
order, with no channel ids (the ground finds the layout in the dictionary's
``telemetryPacketSets``). ``TlmRecv`` copies a channel's bytes into the slot of every packet holding
it, marks those packets updated and stamps them with the write's time. On each ``Run`` tick every
updated packet whose group is at most the send level (or that ``SEND_PKT`` requested) is sent once
(F´'s default ``PACKET_UPDATE_ON_CHANGE``), stamped with the time of its latest write. A channel in
no packet and not omitted gives one ``NoChan`` warning (per channel); omitted channels are dropped
silently. ``TlmGet`` reads a channel's slot back, as F´'s does (the slot's full width).

The packet list comes from the topology's ``telemetry_packets`` (:func:`packet_list`); the instance
gets it through :meth:`TlmPacketizer.set_packet_list`, F´'s ``setPacketList(list, omitted,
startLevel)``.

Differences from F´:
- The channel table is a dict, with no hash table or missing-channel table to run out of
  (F´ asserts when they fill); ``NoChan`` is still given once per channel.
- A write larger than the channel's slot (which F´ cannot receive) is refused, counted in
  :attr:`TlmPacketizer.rejected_writes` and reported, never raised to the writer.
- Not yet: F´'s newer telemetry sections (``ENABLE_SECTION``, ``ENABLE_GROUP``, ``FORCE_GROUP``,
  ``CONFIGURE_GROUP_RATES``, channels ``GroupConfigs``/``SectionEnabled``, several ``PktSend`` ports).
"""

from __future__ import annotations

import struct
import threading
from dataclasses import dataclass
from typing import Any

from fprime_lite.model.commands import CmdResponse, async_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Com, Ping, Sched, Tlm
from fprime_lite.model.ports import OutputPort, async_input, guarded_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.time import TIME
from fprime_lite.model.types import (U32, AliasType, ArrayType, BoolType, EnumType, FloatType, FwType,
                                     IntType, StringType, StructType)
from fprime_lite.svc.tlm_chan import TlmGet, TlmValid
from fprime_lite.wire.packets import TLM_PACKET_MAX, Apid

__all__ = ["PacketSpec", "TlmPacketizer", "max_serialized_size", "packet_list"]

_HEADER = struct.Struct(">HH")  # FwPacketDescriptorType, FwTlmPacketizeIdType
_TIME_AT = _HEADER.size


def max_serialized_size(fw_type: FwType) -> int:
    """The largest number of bytes a value of ``fw_type`` serializes to (a string: U16 length plus
    its bound), which is the width of its slot in a packet."""
    if isinstance(fw_type, (IntType, FloatType, BoolType)):
        return int(fw_type.size)
    if isinstance(fw_type, StringType):
        return 2 + fw_type.size
    if isinstance(fw_type, AliasType):
        return max_serialized_size(fw_type.target)
    if isinstance(fw_type, EnumType):
        return int(fw_type.rep.size)
    if isinstance(fw_type, StructType):
        return sum(max_serialized_size(t) for _, t in fw_type.members)
    if isinstance(fw_type, ArrayType):
        return fw_type.size * max_serialized_size(fw_type.elem)
    if fw_type.kind == "time":
        return TIME.size
    raise TypeError(f"no serialized size known for F´ type {fw_type.name}")


@dataclass(frozen=True)
class PacketSpec:
    """One packet: its id and group (F´'s "level") and its channels as ``(id, slot size)``."""

    name: str
    id: int
    group: int
    channels: tuple[tuple[int, int], ...]


def packet_list(topology: Any, packet_set: dict) -> tuple[list[PacketSpec], list[int]]:
    """``(packets, omitted channel ids)`` of one dictionary-shaped packet set (``name``, ``members``:
    ``[{name, id, group, members: [channel names]}]``, ``omitted``), resolved against the channels
    of ``topology``'s instances. Raises ValueError naming an unknown channel."""
    channels: dict[str, tuple[int, FwType]] = {}
    for instance in topology.instances.values():
        component = instance.component
        for ch in component.spec.channels:
            channels[f"{instance.qualified_name}.{ch.name}"] = (component.base_id + ch.local_id, ch.type)

    def lookup(name: str) -> tuple[int, FwType]:
        try:
            return channels[name]
        except KeyError:
            raise ValueError(f"packet set {packet_set['name']}: no channel {name!r} in the topology") from None

    packets = []
    for packet in packet_set["members"]:
        members = tuple((chan_id, max_serialized_size(t)) for chan_id, t in map(lookup, packet["members"]))
        packets.append(PacketSpec(packet["name"], packet["id"], packet["group"], members))
    return packets, [lookup(name)[0] for name in packet_set["omitted"]]


class _Buffer:
    """One packet being filled: its bytes, the time of its latest write and its send flags."""

    __slots__ = ("spec", "data", "time", "updated", "requested")

    def __init__(self, spec: PacketSpec):
        self.spec = spec
        size = _HEADER.size + TIME.size + sum(n for _, n in spec.channels)
        self.data = bytearray(size)
        _HEADER.pack_into(self.data, 0, Apid.FW_PACKET_PACKETIZED_TLM, spec.id)
        self.time: Any = None  # the Time of the latest write
        self.updated = False
        self.requested = False


class TlmPacketizer(ActiveComponent):
    """F´'s packetizing telemetry store (``Svc.TlmPacketizer``).

    Args:
        name: instance name (``tlmSend`` in CdhCore).
        base_id: added to the local ids of its commands, events and channel.
        queue_size: depth of the message queue (Run ticks, commands, pings).
        packet_max: largest packet allowed, descriptor included (F´'s ``FW_COM_BUFFER_MAX_SIZE``).
    """

    PktSend = OutputPort(Com)
    pingOut = OutputPort(Ping)

    NoChan = Event(Severity.WARNING_LO, "Telemetry ID 0x{x} not packetized", id=0, args=[("Id", U32)])
    LevelSet = Event(Severity.ACTIVITY_HI, "Telemetry send level to {}", id=1, args=[("id", U32)])
    MaxLevelExceed = Event(Severity.WARNING_LO, "Requested send level {} higher than max packet level of {}",
                           id=2, args=[("level", U32), ("max", U32)])
    PacketSent = Event(Severity.ACTIVITY_LO, "Sent packet ID {}", id=3, args=[("id", U32)])
    PacketNotFound = Event(Severity.WARNING_LO, "Could not find packet ID {}", id=4, args=[("id", U32)])

    SendLevel = Channel(U32, id=0)

    def __init__(self, name: str = "tlmSend", *, base_id: int = 0, queue_size: int = 10,
                 packet_max: int = TLM_PACKET_MAX):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        self.packet_max = packet_max
        self._buffers: list[_Buffer] = []
        #: channel id -> [(buffer, offset, size)] of every slot it fills; None for an omitted channel
        self._slots: dict[int, list | None] = {}
        self._missing: set[int] = set()
        self._fill_lock = threading.Lock()  # F´'s m_lock: TlmRecv runs on the writers' threads
        self.start_level = 0
        self.max_level = 0
        self.configured = False
        self.packets_sent = 0
        self.rejected_writes = 0

    def set_packet_list(self, packets: list[PacketSpec], omitted: list[int], start_level: int) -> None:
        """Lay out ``packets`` (F´'s ``setPacketList``): ``omitted`` channels are dropped silently,
        packets of group <= ``start_level`` are sent. Raises ValueError for a packet larger than
        :attr:`packet_max`, a repeated packet id or more than one slot for a channel in one packet."""
        ids = [p.id for p in packets]
        if len(set(ids)) != len(ids):
            raise ValueError(f"{self.name}: packet ids repeat: {sorted(i for i in ids if ids.count(i) > 1)}")
        buffers: list[_Buffer] = []
        placed: dict[int, list] = {}
        for spec in packets:
            buffer = _Buffer(spec)
            if len(buffer.data) > self.packet_max:
                raise ValueError(f"{self.name}: packet {spec.name} (id {spec.id}) is {len(buffer.data)} bytes, "
                                 f"more than the {self.packet_max} a Com buffer holds — split it")
            offset = _TIME_AT + TIME.size
            seen = set()
            for chan_id, size in spec.channels:
                if chan_id in seen:
                    raise ValueError(f"{self.name}: packet {spec.name} lists channel 0x{chan_id:X} twice")
                seen.add(chan_id)
                placed.setdefault(chan_id, []).append((buffer, offset, size))
                offset += size
            buffers.append(buffer)
        slots: dict[int, list | None] = dict(placed)
        for chan_id in omitted:
            slots.setdefault(chan_id, None)
        self._buffers, self._slots = buffers, slots
        self.start_level = start_level
        self.max_level = max((p.group for p in packets), default=0)
        self.configured = True

    @sync_input(Tlm)
    def TlmRecv(self, chan_id: int, time, value: bytes) -> None:
        """Copy ``value`` into the slot of every packet holding channel ``chan_id`` (never raises)."""
        if chan_id not in self._slots:
            if chan_id not in self._missing:
                self._missing.add(chan_id)
                self.NoChan(chan_id)
            return
        slots = self._slots[chan_id]
        if slots is None:  # omitted
            return
        n = len(value)
        for buffer, _, size in slots:
            if n > size:
                self.rejected_writes += 1
                self.report_fault("TlmRecv", ValueError(
                    f"channel 0x{chan_id:X}: {n} bytes do not fit its {size}-byte slot in packet {buffer.spec.name}"))
                return
        with self._fill_lock:
            for buffer, offset, _ in slots:
                buffer.data[offset:offset + n] = value
                buffer.time = time
                buffer.updated = True

    @guarded_input(TlmGet)
    def TlmGet(self, chan_id: int) -> tuple:
        """``(VALID, time, slot bytes)`` of channel ``chan_id`` once written, else ``(INVALID, None, None)``."""
        slots = self._slots.get(chan_id)
        if not slots:
            return TlmValid.INVALID, None, None
        buffer, offset, size = slots[0]
        if buffer.time is None:
            return TlmValid.INVALID, None, None
        return TlmValid.VALID, buffer.time, bytes(buffer.data[offset:offset + size])

    @async_input(Sched)
    def Run(self, context: int) -> None:
        """Send every updated packet whose group is at most the send level, or that was requested."""
        if not self.is_connected("PktSend", 0):
            return
        to_send = []
        with self._fill_lock:
            for buffer in self._buffers:
                if buffer.updated and (buffer.spec.group <= self.start_level or buffer.requested):
                    buffer.updated = buffer.requested = False
                    to_send.append((bytes(buffer.data), buffer.time))
        for data, time in to_send:
            try:
                packet = data[:_TIME_AT] + TIME.serialize(time) + data[_TIME_AT + TIME.size:]
            except Exception as exc:  # noqa: BLE001 - a bad time stamp is reported, never raised to the rate group
                self.report_fault("Run", exc)
                continue
            self.PktSend[0](packet, 0)
            self.packets_sent += 1

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    @async_command(opcode=0)
    def SET_LEVEL(self, level: U32):
        """Send packets of group <= ``level`` from now on."""
        self.start_level = level
        if level > self.max_level:
            self.MaxLevelExceed(level, self.max_level)
        self.SendLevel.write(level)
        self.LevelSet(level)

    @async_command(opcode=1)
    def SEND_PKT(self, id: U32):  # noqa: A002 - F´'s argument name
        """Send packet ``id`` at the next tick whatever its group."""
        for buffer in self._buffers:
            if buffer.spec.id == id:
                with self._fill_lock:
                    buffer.updated = buffer.requested = True
                    buffer.time = self.get_time()
                self.PacketSent(id)
                return CmdResponse.OK
        self.PacketNotFound(id)
        return CmdResponse.VALIDATION_ERROR
