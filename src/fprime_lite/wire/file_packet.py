"""F´ file packets (``Fw::FilePacket``) and the CFDP checksum that closes a file transfer.

A file crosses the ground link as a run of packets, each behind the ``U16`` descriptor
``FW_PACKET_FILE`` (3) and a header ``U8 type | U32 sequence index``:

- START (0): ``U32 file size | U8 n | n bytes source path | U8 m | m bytes destination path``
- DATA (1): ``U32 byte offset | U16 n | n bytes of the file``
- END (2): ``U32 CFDP checksum of the whole file``
- CANCEL (3): nothing more

This is the layout fprime-gds 4.4.1 encodes for uplink and decodes from the downlink. The
checksum is CFDP's modular checksum: every byte is added into a big-endian 32-bit word at the
position its file offset gives it (offset mod 4), and the words are summed mod 2**32.

:func:`decode_file_packet` never raises on bad bytes: it returns a :class:`FilePacketError` saying
what is wrong, for the receiving component to report.
"""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass

from fprime_lite.wire.packets import Apid

__all__ = ["FilePacketType", "StartPacket", "DataPacket", "EndPacket", "CancelPacket", "FilePacketError",
           "encode_file_packet", "decode_file_packet", "CfdpChecksum", "cfdp_checksum", "MAX_PATH_BYTES"]

_DESCRIPTOR = struct.pack(">H", Apid.FW_PACKET_FILE)
_HEADER = struct.Struct(">BI")
_START = struct.Struct(">I")
_DATA = struct.Struct(">IH")
_END = struct.Struct(">I")

#: Longest path a START packet can carry (its length is a U8).
MAX_PATH_BYTES = 255


class FilePacketType(enum.IntEnum):
    """``Fw::FilePacket::Type``."""

    START = 0
    DATA = 1
    END = 2
    CANCEL = 3


@dataclass(frozen=True)
class StartPacket:
    sequence: int
    file_size: int
    source: str
    destination: str
    type = FilePacketType.START


@dataclass(frozen=True)
class DataPacket:
    sequence: int
    offset: int
    data: bytes
    type = FilePacketType.DATA


@dataclass(frozen=True)
class EndPacket:
    sequence: int
    checksum: int
    type = FilePacketType.END


@dataclass(frozen=True)
class CancelPacket:
    sequence: int
    type = FilePacketType.CANCEL


FilePacket = StartPacket | DataPacket | EndPacket | CancelPacket


@dataclass(frozen=True)
class FilePacketError:
    """Why some bytes are not a file packet (returned, not raised)."""

    reason: str


def _path(text: str, what: str) -> bytes:
    raw = text.encode("utf-8")
    if len(raw) > MAX_PATH_BYTES:
        raise ValueError(f"{what} path is {len(raw)} bytes; a file packet holds at most {MAX_PATH_BYTES}")
    return bytes([len(raw)]) + raw


def encode_file_packet(packet: FilePacket, *, descriptor: bool = True) -> bytes:
    """The bytes of ``packet``, behind the ``FW_PACKET_FILE`` descriptor unless ``descriptor=False``."""
    head = _HEADER.pack(int(packet.type), packet.sequence)
    if isinstance(packet, StartPacket):
        body = (_START.pack(packet.file_size) + _path(packet.source, "source")
                + _path(packet.destination, "destination"))
    elif isinstance(packet, DataPacket):
        if len(packet.data) > 0xFFFF:
            raise ValueError(f"a data packet holds at most 65535 bytes, got {len(packet.data)}")
        body = _DATA.pack(packet.offset, len(packet.data)) + packet.data
    elif isinstance(packet, EndPacket):
        body = _END.pack(packet.checksum)
    elif isinstance(packet, CancelPacket):
        body = b""
    else:
        raise TypeError(f"not a file packet: {packet!r}")
    return (_DESCRIPTOR if descriptor else b"") + head + body


def _read_path(data: bytes, pos: int, what: str) -> tuple[str, int, str | None]:
    """``(path, next position, None)``, or ``("", pos, problem)``."""
    if pos >= len(data):
        return "", pos, f"START packet ends before its {what} path length"
    n = data[pos]
    raw = data[pos + 1:pos + 1 + n]
    if len(raw) != n:
        return "", pos, f"START packet's {what} path says {n} bytes but {len(raw)} remain"
    try:
        return raw.decode("utf-8"), pos + 1 + n, None
    except UnicodeDecodeError:
        return "", pos, f"START packet's {what} path is not UTF-8"


def decode_file_packet(data: bytes, *, descriptor: bool = False) -> FilePacket | FilePacketError:
    """Decode one file packet; ``descriptor=True`` when ``data`` starts with ``FW_PACKET_FILE``."""
    data = bytes(data)
    if descriptor:
        if data[:2] != _DESCRIPTOR:
            return FilePacketError(f"descriptor {data[:2].hex() or 'missing'} is not FW_PACKET_FILE (0003)")
        data = data[2:]
    if len(data) < _HEADER.size:
        return FilePacketError(f"{len(data)} bytes is shorter than a file packet header (5 bytes)")
    kind, sequence = _HEADER.unpack_from(data)
    pos = _HEADER.size
    if kind == FilePacketType.START:
        if len(data) < pos + _START.size:
            return FilePacketError("START packet too short for its file size")
        (size,) = _START.unpack_from(data, pos)
        source, pos, problem = _read_path(data, pos + _START.size, "source")
        if problem is None:
            destination, pos, problem = _read_path(data, pos, "destination")
        if problem is not None:
            return FilePacketError(problem)
        return StartPacket(sequence, size, source, destination)
    if kind == FilePacketType.DATA:
        if len(data) < pos + _DATA.size:
            return FilePacketError("DATA packet too short for its offset and size")
        offset, n = _DATA.unpack_from(data, pos)
        chunk = data[pos + _DATA.size:pos + _DATA.size + n]
        if len(chunk) != n:
            return FilePacketError(f"DATA packet says {n} bytes but carries {len(chunk)}")
        return DataPacket(sequence, offset, chunk)
    if kind == FilePacketType.END:
        if len(data) < pos + _END.size:
            return FilePacketError("END packet too short for its checksum")
        return EndPacket(sequence, _END.unpack_from(data, pos)[0])
    if kind == FilePacketType.CANCEL:
        return CancelPacket(sequence)
    return FilePacketError(f"unknown file packet type {kind}")


class CfdpChecksum:
    """CFDP modular checksum, fed chunk by chunk with each chunk's file offset."""

    __slots__ = ("value",)

    def __init__(self, value: int = 0):
        self.value = value

    def update(self, data: bytes, offset: int) -> None:
        lead = offset % 4
        padded = bytes(lead) + bytes(data)
        padded += bytes(-len(padded) % 4)
        words = struct.unpack(f">{len(padded) // 4}I", padded)
        self.value = (self.value + sum(words)) & 0xFFFFFFFF


def cfdp_checksum(data: bytes) -> int:
    """The CFDP checksum of a whole file's bytes."""
    checksum = CfdpChecksum()
    checksum.update(data, 0)
    return checksum.value
