"""F´ packets: what crosses the ground link inside a frame.

Every packet starts with a ``U16`` descriptor (``ComCfg.Apid``) and then:

- command (``FW_PACKET_COMMAND``): ``U32 opcode | arguments``
- telemetry (``FW_PACKET_TELEM``): one or more ``U32 id | Time (11 bytes) | value``
- event (``FW_PACKET_LOG``): exactly one ``U32 id | Time | arguments`` — fprime-gds 4.4.1 decodes
  only the first event of a log packet, so events are never batched.

The ``ComCfg.Apid`` constants keep the names fprime-gds looks up (``FW_PACKET_COMMAND`` …); the GDS
refuses to encode commands for a dictionary that spells them otherwise.
"""

from __future__ import annotations

import struct

from fprime_lite.model.errors import SerializationError
from fprime_lite.model.time import TIME, Time
from fprime_lite.model.types import FwEnum, U16

__all__ = ["Apid", "encode_command", "decode_command", "encode_event", "decode_event",
           "encode_telemetry", "decode_telemetry", "TLM_PACKET_MAX"]

_U16 = struct.Struct(">H")
_U32 = struct.Struct(">I")
_CMD_HEADER = struct.Struct(">HI")

#: Largest telemetry packet TlmChan builds (bytes, descriptor included), as F´'s ComBuffer.
TLM_PACKET_MAX = 512


class Apid(FwEnum, namespace="ComCfg", rep=U16, default="FW_PACKET_UNKNOWN"):
    """Packet descriptors (``ComCfg.Apid``), with fprime-gds's spelling."""

    FW_PACKET_COMMAND = 0
    FW_PACKET_TELEM = 1
    FW_PACKET_LOG = 2
    FW_PACKET_FILE = 3
    FW_PACKET_PACKETIZED_TLM = 4
    FW_PACKET_DP = 5
    FW_PACKET_IDLE = 6
    FW_PACKET_HAND = 0xFE
    FW_PACKET_UNKNOWN = 0xFF
    SPP_IDLE_PACKET = 0x7FF


def encode_command(opcode: int, args: bytes = b"") -> bytes:
    return _CMD_HEADER.pack(Apid.FW_PACKET_COMMAND, opcode) + args


def decode_command(packet: bytes) -> tuple[int, bytes]:
    """``(opcode, argument bytes)`` of a command packet; SerializationError if it is not one."""
    if len(packet) < _CMD_HEADER.size:
        raise SerializationError(f"command packet of {len(packet)} bytes is shorter than its 6-byte header")
    descriptor, opcode = _CMD_HEADER.unpack_from(packet)
    if descriptor != Apid.FW_PACKET_COMMAND:
        raise SerializationError(f"packet descriptor {descriptor} is not FW_PACKET_COMMAND (0)")
    return opcode, bytes(packet[_CMD_HEADER.size:])


def encode_event(event_id: int, time: Time, args: bytes) -> bytes:
    return _U16.pack(Apid.FW_PACKET_LOG) + _U32.pack(event_id) + TIME.serialize(time) + args


def decode_event(packet: bytes) -> tuple[int, Time, bytes]:
    """``(id, time, argument bytes)`` of an event packet."""
    descriptor, = _U16.unpack_from(packet) if len(packet) >= 2 else (None,)
    if descriptor != Apid.FW_PACKET_LOG:
        raise SerializationError(f"packet descriptor {descriptor} is not FW_PACKET_LOG (2)")
    if len(packet) < 2 + 4 + TIME.size:
        raise SerializationError(f"event packet of {len(packet)} bytes is too short")
    event_id, = _U32.unpack_from(packet, 2)
    time, end = TIME.deserialize(packet, 6)
    return event_id, time, bytes(packet[end:])


def encode_telemetry(records: list[tuple[int, Time, bytes]]) -> bytes:
    """One telemetry packet holding ``(id, time, value bytes)`` records back to back."""
    parts = [_U16.pack(Apid.FW_PACKET_TELEM)]
    for channel_id, time, value in records:
        parts.append(_U32.pack(channel_id))
        parts.append(TIME.serialize(time))
        parts.append(value)
    return b"".join(parts)


def decode_telemetry(packet: bytes, value_size) -> list[tuple[int, Time, bytes]]:
    """Split a telemetry packet; ``value_size(id, data, offset)`` returns where that value ends."""
    descriptor, = _U16.unpack_from(packet) if len(packet) >= 2 else (None,)
    if descriptor != Apid.FW_PACKET_TELEM:
        raise SerializationError(f"packet descriptor {descriptor} is not FW_PACKET_TELEM (1)")
    records = []
    offset = 2
    while offset < len(packet):
        if offset + 4 > len(packet):
            raise SerializationError(f"telemetry packet truncated at offset {offset}")
        channel_id, = _U32.unpack_from(packet, offset)
        time, start = TIME.deserialize(packet, offset + 4)
        end = value_size(channel_id, packet, start)
        records.append((channel_id, time, bytes(packet[start:end])))
        offset = end
    return records
