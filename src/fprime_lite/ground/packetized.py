"""Ground decoding of TlmPacketizer packets into channel updates, each packet's layout compiled once.

A ``Svc.TlmPacketizer`` packet (``U16 4 | U16 packet id | Time | slots…``, docs/ground.md "Packetized
telemetry") carries no channel ids: the ground finds its layout in the packet set (the dictionary's
``telemetryPacketSets``), each member channel in a slot as wide as its type's largest value. This
module compiles, once per packet of the set, one ``struct`` that unpacks the header, the time stamp
and every slot (numbers as numbers, other values as their slot's bytes), so a packet costs one
unpack and a few operations per slot, as TlmChan's compiled layouts do
(:mod:`fprime_lite.ground.packet_layout`).

A packet does not say which of its slots were written since the last one, so the recorder writes
a channel's update (with the packet's time stamp, the time of the packet's latest write) by the
channel's update policy, which the dictionary holds (``telemetryUpdate``):

- from its *home* packet only: the packet of lowest group (then lowest id) that holds it, the one
  that goes down whenever it is written (a channel in two packets is one update, not two);
- an ``always`` channel: every time its home packet arrives;
- an ``on change`` channel: when its slot's bytes differ from the last ones recorded, starting from
  the zeroed slot a packetizer starts with (so a slot never written is no update).

Where this gives other updates than TlmChan would (docs/outputs.md): an ``always`` channel written less
often than its home packet goes down repeats its value; one not yet written when its packet goes
down shows the zeroed slot (0); an ``on change`` channel whose first value is all zero bytes is not
seen until it changes.
"""

from __future__ import annotations

import struct
from typing import Any, Callable

from fprime_lite.model.errors import SerializationError
from fprime_lite.model.time import TIME, US_PER_S
from fprime_lite.model.types import AliasType, FloatType, IntType
from fprime_lite.svc.tlm_packetizer import max_serialized_size
from fprime_lite.wire.packets import Apid

__all__ = ["PacketizedLayout", "PacketizedDecoder"]

#: descriptor, packet id, then the time stamp (base, context, seconds, useconds), big-endian
_HEAD = ">HHHBII"
_HEAD_FIELDS = 6
#: other values remembered per slot (enums, flags and modes repeat)
_SEEN_MAX = 256


def _number_code(ftype: Any) -> str | None:
    """The struct code of a plain number type (after aliases), else None."""
    while isinstance(ftype, AliasType):
        ftype = ftype.target
    if isinstance(ftype, (IntType, FloatType)):
        return str(ftype._struct.format[1:])
    return None


class _Slot:
    """One recorded slot: where its value and bytes are, how it is written."""

    __slots__ = ("name", "field", "start", "end", "on_change", "last", "ftype", "template", "number", "seen")

    def __init__(self, name: str, field: int, start: int, size: int, on_change: bool, ftype: Any,
                 template: str | None, number: bool):
        self.name = name
        self.field = field  # index of its value (a number) or of its bytes in the unpacked tuple
        self.start, self.end = start, start + size
        self.on_change = on_change
        self.last = bytes(size)  # a packetizer's slots start zeroed
        self.ftype = ftype
        self.template = template
        self.number = number
        self.seen: dict[bytes, tuple[Any, str]] = {}


class PacketizedLayout:
    """The compiled layout of one packet of a packet set (see the module docstring)."""

    def __init__(self, packet_id: int, slots: list[tuple[str, Any, str | None, bool, bool]],
                 text_of: Callable[[Any, str | None], str]):
        """``slots``: ``(channel name, F´ type, format template or None, on change?, recorded from
        this packet?)`` of each member channel in the packet's order."""
        fmt = [_HEAD]
        offset = struct.calcsize(_HEAD)
        self.slots: list[_Slot] = []
        field = _HEAD_FIELDS
        for name, ftype, template, on_change, recorded in slots:
            size = max_serialized_size(ftype)
            code = _number_code(ftype) if template is None else None
            fmt.append(code if code is not None else f"{size}s")
            if recorded:
                self.slots.append(_Slot(name, field, offset, size, on_change, ftype, template, code is not None))
            field += 1
            offset += size
        self.id = packet_id
        self.struct = struct.Struct("".join(fmt))
        self.size = self.struct.size
        self._text_of = text_of

    def decode(self, packet: bytes) -> tuple[Any, list[tuple[str, Any, str]]]:
        """``(the packet's time stamp, [(channel, value, text)] of the updates to record)``; raises
        :class:`~fprime_lite.model.errors.SerializationError` for a packet of another length, a bad
        time stamp or a value its type rejects."""
        if len(packet) != self.size:
            raise SerializationError(f"packet {self.id} is {len(packet)} bytes, its layout {self.size}")
        fields = self.struct.unpack(packet)
        if fields[5] >= US_PER_S:
            raise SerializationError(f"packet {self.id}: time stamp useconds {fields[5]} out of range")
        time = TIME.deserialize(packet, 4)[0]
        out = []
        for slot in self.slots:
            if slot.on_change:
                raw = packet[slot.start:slot.end]
                if raw == slot.last:
                    continue
                slot.last = raw
            value = fields[slot.field]
            if slot.number:
                out.append((slot.name, value, repr(value) if type(value) is float else str(value)))
                continue
            known = slot.seen.get(value)
            if known is None:
                decoded = slot.ftype.deserialize(value)[0]
                known = (decoded, self._text_of(decoded, slot.template))
                if len(slot.seen) < _SEEN_MAX:
                    slot.seen[value] = known
            out.append((slot.name, known[0], known[1]))
        return time, out


class PacketizedDecoder:
    """The compiled layouts of one packet set (dictionary-shaped: ``name``, ``members``: ``[{name, id,
    group, members: [channel names]}]``, ``omitted``), with ``channels`` the decoder's channel table
    (id → ``(name, F´ type, template)``) and ``policies`` each channel's update policy by name."""

    def __init__(self, packet_set: dict, channels: dict[int, tuple[str, Any, str | None]],
                 policies: dict[str, str], text_of: Callable[[Any, str | None], str]):
        by_name = {name: (ftype, template) for name, ftype, template in channels.values()}
        home: dict[str, int] = {}
        for packet in sorted(packet_set["members"], key=lambda p: (p["group"], p["id"])):
            for name in packet["members"]:
                home.setdefault(name, packet["id"])
        self.layouts: dict[int, PacketizedLayout] = {}
        for packet in packet_set["members"]:
            slots = []
            for name in packet["members"]:
                if name not in by_name:
                    raise ValueError(f"packet set {packet_set['name']}: no channel {name!r} in the dictionary")
                ftype, template = by_name[name]
                slots.append((name, ftype, template, policies.get(name) == "on change", home[name] == packet["id"]))
            self.layouts[packet["id"]] = PacketizedLayout(packet["id"], slots, text_of)

    def decode(self, packet: bytes) -> tuple[Any, list[tuple[str, Any, str]]]:
        """What :meth:`PacketizedLayout.decode` gives for the packet's layout; SerializationError for
        a packet that is not a packetized one or whose id the set does not have."""
        if len(packet) < 4 or int.from_bytes(packet[:2], "big") != Apid.FW_PACKET_PACKETIZED_TLM:
            raise SerializationError("not a packetized telemetry packet")
        packet_id = int.from_bytes(packet[2:4], "big")
        layout = self.layouts.get(packet_id)
        if layout is None:
            raise SerializationError(f"packet id {packet_id} is not in the packet set")
        return layout.decode(packet)
