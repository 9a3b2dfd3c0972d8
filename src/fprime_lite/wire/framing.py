"""Framing of the ground link: the ``fprime`` and the CCSDS ``space-packet-space-data-link`` framings.

Both match what fprime-gds 4.4.1 speaks (``--framing-selection fprime`` and the default
``space-packet-space-data-link``); ``tests/data/gds/gds_notes.md`` §e has the byte layouts.

``fprime`` (symmetric: the same frame in both directions)::

    U32 0xDEADBEEF | U32 length | packet (length bytes) | U32 CRC-32 (zlib) of header + packet

CCSDS:

- uplink (ground to flight): one TC transfer frame per command, holding one or more Space
  Packets (type TC, APID = the packet's ``ComCfg.Apid`` descriptor)::

      5-byte TC header: version 0 | bypass | ctrl | SCID (10 bits) ; VCID (6) | frame length - 1 (10) ; seq 0
      Space Packet(s): 6-byte header | F´ packet (U16 descriptor first)
      U16 CRC-16-CCITT (poly 0x1021, init 0xFFFF) of header + packets

- downlink (flight to ground): fixed-size TM transfer frames (1024 bytes,
  ``ComCfg.TmFrameFixedSize``) carrying Space Packets (type TM) back to back. A packet may span
  frames; the First Header Pointer of each frame says where the first packet header in it starts
  (0x7FF: none does). The last frame of a batch is filled with an idle packet (APID 0x7FF)::

      6-byte TM header: version 0 | SCID (10) | VCID (3) | OCF 0 ; MC count ; VC count ; data field status (FHP)
      data field (frame size - 8 bytes)
      U16 CRC-16-CCITT of the frame before the CRC

Deframers are *streaming*: :meth:`UplinkDeframer.push` takes whatever bytes the socket delivered and
returns the complete packets found so far, plus a :class:`Dropped` record for each frame it
rejected (bad CRC, bad length, unknown descriptor). Bytes that cannot start a frame (the GDS's
``sitting well`` keep-alives, line noise) are skipped silently and counted in
:attr:`UplinkDeframer.skipped_bytes`. Nothing a deframer is given makes it raise; its buffer never
holds more than one maximal frame.

Resynchronisation: a header that fails its checks, or a frame whose CRC fails, is dropped and the
search for the next start word / plausible header resumes one byte after its start, so valid frames
that were inside the bytes it claimed are delivered. A header whose claimed length never arrives
would hold the frames behind it: :meth:`UplinkDeframer.expire` (called by the link when the partial
frame has waited too long) and :meth:`UplinkDeframer.reset` (the connection is gone, so it can never
complete) abandon it as ``INCOMPLETE`` and deliver the complete frames found behind it. Bytes of
rejected frames that were not part of a delivered frame count in :attr:`UplinkDeframer.dropped_bytes`.
"""

from __future__ import annotations

import binascii
import enum
import struct
import zlib
from dataclasses import dataclass
from typing import Sequence, Union

from fprime_lite.wire.com_cfg import SPACECRAFT_ID, TM_FRAME_SIZE
from fprime_lite.wire.packets import Apid

__all__ = ["FprimeFraming", "CcsdsFraming", "Framing", "UplinkDeframer", "Dropped", "DropReason",
           "make_framing", "FRAMINGS", "crc16_ccitt", "SPACECRAFT_ID", "TM_FRAME_SIZE", "DEFAULT_VCID",
           "FPRIME_START_WORD", "FPRIME_MAX_PACKET", "IDLE_APID", "UPLINK_DESCRIPTORS"]

#: Virtual channel of both directions (fprime-gds ``--vcid`` default).
DEFAULT_VCID = 1
#: Start word of an ``fprime`` frame.
FPRIME_START_WORD = 0xDEADBEEF
#: Largest packet an ``fprime`` frame may carry (fprime-gds ``MAXIMUM_DATA_SIZE`` is 4096, exclusive).
FPRIME_MAX_PACKET = 4095
#: APID of CCSDS idle packets.
IDLE_APID = 0x7FF

_U16 = struct.Struct(">H")
_U32 = struct.Struct(">I")
_FPRIME_HEADER = struct.Struct(">II")
_FPRIME_START = _U32.pack(FPRIME_START_WORD)
_SP_HEADER = struct.Struct(">HHH")
_TC_HEADER = struct.Struct(">HHB")
_TM_HEADER = struct.Struct(">HBBH")

_TC_HEADER_SIZE = 5
_TM_HEADER_SIZE = 6
_CRC16_SIZE = 2
_SP_HEADER_SIZE = 6
_FHP_NO_PACKET_START = 0x7FF
_SEQ_FLAGS_UNSEGMENTED = 0b11 << 14
_SEQ_COUNT_MODULO = 1 << 14


def crc16_ccitt(data: bytes | bytearray | memoryview) -> int:
    """CRC-16-CCITT as CCSDS uses it: polynomial 0x1021, initial value 0xFFFF, no reflection, no final XOR."""
    return binascii.crc_hqx(data, 0xFFFF)


class DropReason(enum.Enum):
    """Why an uplinked frame was dropped."""

    BAD_CRC = "bad CRC"
    BAD_LENGTH = "bad length"
    UNKNOWN_DESCRIPTOR = "unknown descriptor"
    INCOMPLETE = "never completed"


@dataclass(frozen=True)
class Dropped:
    """A rejected frame: why, how many bytes it claimed (or had), and what was wrong.

    ``value`` is the offending length for BAD_LENGTH, the packet descriptor (or -1 for a frame
    addressed elsewhere) for UNKNOWN_DESCRIPTOR, the received CRC for BAD_CRC, and the bytes that
    had arrived for INCOMPLETE.
    """

    reason: DropReason
    size: int
    value: int = 0


Deframed = Union[bytes, Dropped]


class UplinkDeframer:
    """Turns a byte stream from the ground into F´ command and file packets (base class).

    ``push(data)`` returns, in stream order, each complete packet (``bytes``, starting with its
    U16 descriptor) and a :class:`Dropped` for each rejected frame.
    """

    #: Bytes before a frame can be recognised (the start of a header).
    _SYNC = 1

    def __init__(self):
        self._buf = bytearray()
        self._base = 0  # stream offset of _buf[0]
        self._quiet_until = 0  # no further drop reports for candidates starting before this offset
        self._pending: int | None = None  # stream offset of a frame started but not complete
        #: Bytes skipped because they could not start a frame (keep-alives, noise), in total.
        self.skipped_bytes = 0
        #: Bytes of rejected or abandoned frames that were not part of a delivered frame, in total.
        self.dropped_bytes = 0
        #: Frames accepted, in total.
        self.frames = 0
        #: Frames dropped, in total.
        self.dropped = 0

    @property
    def buffered(self) -> int:
        """Bytes held while waiting for the rest of a frame."""
        return len(self._buf)

    @property
    def pending_offset(self) -> int | None:
        """Stream offset of the frame that has started but not completed (None: no such frame).

        It changes when that frame completes or is dropped, so a caller can time how long one
        partial frame has been waiting."""
        return self._pending

    def push(self, data: bytes) -> list[Deframed]:
        """Add received bytes; return the packets and drops they completed."""
        self._buf += data
        return self._scan(abandon=0)

    def expire(self) -> list[Deframed]:
        """The partial frame has waited too long: drop it as INCOMPLETE, resynchronise one byte after
        its start and return what the bytes behind it complete (a later partial frame waits)."""
        return self._scan(abandon=1) if self._pending is not None else []

    def reset(self) -> list[Deframed]:
        """The connection is gone: no partial frame can complete. Drop each as INCOMPLETE, return the
        complete frames found behind them, and forget the rest (the next connection starts afresh)."""
        out = self._scan(abandon=-1)
        self._discard(0, len(self._buf))
        self._base += len(self._buf)
        self._buf.clear()
        self._quiet_until = self._base
        self._pending = None
        return out

    def _scan(self, abandon: int) -> list[Deframed]:
        """Deframe the buffer; abandon up to ``abandon`` partial frames (-1: all of them)."""
        buf = self._buf
        out: list[Deframed] = []
        pos = 0
        self._pending = None
        while True:
            start = self._find_start(buf, pos)
            if start < 0:
                keep = max(pos, len(buf) - (self._SYNC - 1))
                self._discard(pos, keep - pos)
                pos = keep
                break
            self._discard(pos, start - pos)
            pos = start
            step = self._try_frame(buf, pos, out)
            if step == 0:  # a frame has started but is not complete yet
                if abandon == 0:
                    self._pending = self._base + pos
                    break
                abandon -= 1
                have = len(buf) - pos
                self._drop(out, DropReason.INCOMPLETE, have, have, pos, have, suspect=True)
                step = 1
            elif step > 1:  # a whole frame with a good CRC: whatever came before was not its header
                self._quiet_until = min(self._quiet_until, self._base + pos)
            pos += step
        if pos:
            del buf[:pos]
            self._base += pos
        return out

    def _discard(self, at: int, count: int) -> None:
        """Account for ``count`` bytes at buffer offset ``at`` that are not part of a delivered frame:
        inside a rejected frame's span they are dropped, elsewhere skipped."""
        if count <= 0:
            return
        inside = min(count, max(0, self._quiet_until - (self._base + at)))
        self.dropped_bytes += inside
        self.skipped_bytes += count - inside

    def _drop(self, out: list, reason: DropReason, size: int, value: int, at: int, span: int,
              suspect: bool = False) -> None:
        """Report a rejected frame starting at buffer offset ``at``.

        ``suspect``: the frame failed its header or CRC check (or never completed), so its start may
        be noise and the deframer slides one byte on (that byte is accounted for here). Such a report
        is suppressed inside the span of the previous suspect one (a corrupted frame counts once, not
        once per false header found inside it). A frame whose CRC was good is always reported and
        its ``span`` bytes count as dropped.
        """
        if suspect:
            absolute = self._base + at
            if absolute < self._quiet_until:
                self._discard(at, 1)
                return
            self._quiet_until = absolute + max(span, 1)
            self._discard(at, 1)
        else:
            self.dropped_bytes += span
        self.dropped += 1
        out.append(Dropped(reason, size, value))

    # Subclasses: where the next frame may start (or -1); and, at a start, how many bytes to
    # consume (0: wait for more data), appending packets and drops to ``out``.
    def _find_start(self, buf: bytearray, pos: int) -> int:
        raise NotImplementedError

    def _try_frame(self, buf: bytearray, pos: int, out: list) -> int:
        raise NotImplementedError


#: Descriptors of the packets a ground system uplinks: commands and file packets.
UPLINK_DESCRIPTORS = frozenset({Apid.FW_PACKET_COMMAND, Apid.FW_PACKET_FILE})


def _uplink_packet_or_drop(packet: bytes, size: int, out: list, deframer: UplinkDeframer, at: int,
                           span: int) -> None:
    """Hand on a command or file packet; anything else the flight side cannot route is dropped."""
    if len(packet) < 2:
        deframer._drop(out, DropReason.BAD_LENGTH, size, len(packet), at, span)
        return
    descriptor = _U16.unpack_from(packet)[0]
    if descriptor not in UPLINK_DESCRIPTORS:
        deframer._drop(out, DropReason.UNKNOWN_DESCRIPTOR, size, descriptor, at, span)
        return
    deframer.frames += 1
    out.append(bytes(packet))


class FprimeDeframer(UplinkDeframer):
    """Streaming deframer of ``fprime`` frames carrying command and file packets."""

    _SYNC = 4

    def __init__(self, max_packet: int = FPRIME_MAX_PACKET):
        super().__init__()
        self.max_packet = max_packet

    def _find_start(self, buf, pos):
        return buf.find(_FPRIME_START, pos)

    def _try_frame(self, buf, pos, out):
        if len(buf) - pos < _FPRIME_HEADER.size:
            return 0
        length = _U32.unpack_from(buf, pos + 4)[0]
        if length > self.max_packet:
            # Either a false start word in noise or a corrupted length: slide one byte.
            self._drop(out, DropReason.BAD_LENGTH, _FPRIME_HEADER.size, length, pos, _FPRIME_HEADER.size,
                       suspect=True)
            return 1
        total = _FPRIME_HEADER.size + length + 4
        if len(buf) - pos < total:
            return 0
        end = pos + total - 4
        received = _U32.unpack_from(buf, end)[0]
        if zlib.crc32(memoryview(buf)[pos:end]) != received:
            self._drop(out, DropReason.BAD_CRC, total, received, pos, total, suspect=True)
            return 1  # the start word may have been noise: resynchronise byte by byte
        _uplink_packet_or_drop(bytes(buf[pos + _FPRIME_HEADER.size:end]), total, out, self, pos, total)
        return total


class CcsdsTcDeframer(UplinkDeframer):
    """Streaming deframer of CCSDS TC transfer frames holding Space Packets with command or file packets."""

    _SYNC = 2
    #: Smallest TC frame: header, a Space Packet with one data byte, CRC.
    MIN_FRAME = _TC_HEADER_SIZE + _SP_HEADER_SIZE + 1 + _CRC16_SIZE

    def __init__(self, scid: int = SPACECRAFT_ID, vcid: int = DEFAULT_VCID):
        super().__init__()
        self.scid = scid
        self.vcid = vcid
        # First header byte: version 00, bypass/ctrl free, reserved 00, the SCID's two high bits.
        self._scid_low = scid & 0xFF
        self._scid_high = (scid >> 8) & 0x3

    def _find_start(self, buf, pos):
        low = self._scid_low
        i = buf.find(low, pos + 1)
        while i >= 0:
            b0 = buf[i - 1]
            if b0 & 0xCC == 0 and b0 & 0x3 == self._scid_high:
                return i - 1
            i = buf.find(low, i + 1)
        return -1

    def _try_frame(self, buf, pos, out):
        if len(buf) - pos < _TC_HEADER_SIZE:
            return 0
        word1, word2, _ = _TC_HEADER.unpack_from(buf, pos)
        total = (word2 & 0x3FF) + 1
        if total < self.MIN_FRAME:
            self._drop(out, DropReason.BAD_LENGTH, _TC_HEADER_SIZE, total, pos, _TC_HEADER_SIZE, suspect=True)
            return 1
        if len(buf) - pos < total:
            return 0
        end = pos + total - _CRC16_SIZE
        received = _U16.unpack_from(buf, end)[0]
        if crc16_ccitt(memoryview(buf)[pos:end]) != received:
            self._drop(out, DropReason.BAD_CRC, total, received, pos, total, suspect=True)
            return 1
        vcid = (word2 >> 10) & 0x3F
        if vcid != self.vcid or word1 & 0x1000:  # another virtual channel, or a control (Type-C) frame
            self._drop(out, DropReason.UNKNOWN_DESCRIPTOR, total, -1, pos, total)
            return total
        self._space_packets(bytes(buf[pos + _TC_HEADER_SIZE:end]), total, out, pos)
        return total

    def _space_packets(self, field: bytes, total: int, out: list, at: int) -> None:
        offset = 0
        while offset < len(field):
            rest = len(field) - offset
            if rest < _SP_HEADER_SIZE:
                self._drop(out, DropReason.BAD_LENGTH, total, rest, at, rest)
                return
            ident, _, data_len = _SP_HEADER.unpack_from(field, offset)
            size = _SP_HEADER_SIZE + data_len + 1
            if size > rest:
                self._drop(out, DropReason.BAD_LENGTH, total, size, at, rest)
                return
            version, packet_type, apid = ident >> 13, (ident >> 12) & 1, ident & 0x7FF
            packet = field[offset + _SP_HEADER_SIZE:offset + size]
            offset += size
            if version != 0 or packet_type != 1:
                self._drop(out, DropReason.UNKNOWN_DESCRIPTOR, total, apid, at, size)
                continue
            if apid == IDLE_APID:
                continue
            if len(packet) >= 2 and _U16.unpack_from(packet)[0] != apid:
                self._drop(out, DropReason.UNKNOWN_DESCRIPTOR, total, _U16.unpack_from(packet)[0], at, size)
                continue
            _uplink_packet_or_drop(packet, total, out, self, at, size)


class Framing:
    """One framing: how packets are framed for the downlink, and the uplink's deframer."""

    #: The name used on the command line (``--framing``).
    name = ""
    #: The matching ``fprime-gds --framing-selection``.
    gds_name = ""

    def frame_downlink(self, packets: Sequence[bytes]) -> list[bytes]:
        """The frames that carry ``packets`` (F´ packets, descriptor first) to the ground."""
        raise NotImplementedError

    def frame_uplink(self, packet: bytes) -> bytes:
        """One packet framed as the ground sends it (for tests and ground-side tools)."""
        raise NotImplementedError

    def uplink_deframer(self) -> UplinkDeframer:
        """A new streaming deframer of what the ground sends."""
        raise NotImplementedError


class FprimeFraming(Framing):
    """fprime-gds ``--framing-selection fprime``: one frame per packet, both directions."""

    name = "fprime"
    gds_name = "fprime"

    def frame_downlink(self, packets: Sequence[bytes]) -> list[bytes]:
        return [self.frame(p) for p in packets]

    def frame_uplink(self, packet: bytes) -> bytes:
        return self.frame(packet)

    @staticmethod
    def frame(packet: bytes) -> bytes:
        if len(packet) > FPRIME_MAX_PACKET:
            raise ValueError(f"a packet of {len(packet)} bytes does not fit an fprime frame "
                             f"(at most {FPRIME_MAX_PACKET})")
        head = _FPRIME_HEADER.pack(FPRIME_START_WORD, len(packet)) + packet
        return head + _U32.pack(zlib.crc32(head))

    def uplink_deframer(self) -> FprimeDeframer:
        return FprimeDeframer()


class CcsdsFraming(Framing):
    """fprime-gds ``--framing-selection space-packet-space-data-link`` (its default).

    Downlink state (Space Packet sequence counts per APID, master and virtual channel frame
    counts) lives in this object: use one per link and frame from one thread.

    Args:
        scid: spacecraft id of every frame (``ComCfg.SpacecraftId``).
        vcid: virtual channel of both directions (fprime-gds ``--vcid``, default 1).
        frame_size: bytes in every TM frame (``ComCfg.TmFrameFixedSize``).
    """

    name = "ccsds"
    gds_name = "space-packet-space-data-link"

    def __init__(self, scid: int = SPACECRAFT_ID, vcid: int = DEFAULT_VCID, frame_size: int = TM_FRAME_SIZE):
        if not 0 <= scid <= 0x3FF:
            raise ValueError(f"spacecraft id must fit 10 bits, got {scid}")
        if not 0 <= vcid <= 0x7:
            raise ValueError(f"a TM virtual channel id fits 3 bits, got {vcid}")
        if not _TM_HEADER_SIZE + _SP_HEADER_SIZE + 1 + _CRC16_SIZE <= frame_size <= 2048:
            raise ValueError(f"TM frame size {frame_size} is out of range")
        self.scid = scid
        self.vcid = vcid
        self.frame_size = frame_size
        self.field_size = frame_size - _TM_HEADER_SIZE - _CRC16_SIZE
        self._seq: dict[int, int] = {}
        self._uplink_seq: dict[int, int] = {}
        self._frame_count = 0

    # --- downlink -------------------------------------------------------------------------------

    def space_packet(self, packet: bytes, *, apid: int | None = None, telecommand: bool = False) -> bytes:
        """``packet`` in a Space Packet (APID = its descriptor unless given), with the next sequence count."""
        if not packet:
            raise ValueError("a Space Packet carries at least one byte")
        if len(packet) > 0x10000:
            raise ValueError(f"a packet of {len(packet)} bytes does not fit a Space Packet")
        if apid is None:
            apid = _U16.unpack_from(packet)[0] & 0x7FF if len(packet) >= 2 else 0
        counts = self._uplink_seq if telecommand else self._seq
        count = counts.get(apid, 0)
        counts[apid] = (count + 1) % _SEQ_COUNT_MODULO
        ident = (int(telecommand) << 12) | (apid & 0x7FF)
        return _SP_HEADER.pack(ident, _SEQ_FLAGS_UNSEGMENTED | count, len(packet) - 1) + packet

    def frame_downlink(self, packets: Sequence[bytes]) -> list[bytes]:
        """Pack ``packets`` (as Space Packets) into TM frames; the last frame is filled with idle data."""
        stream = bytearray()
        starts: list[int] = []
        for packet in packets:
            starts.append(len(stream))
            stream += self.space_packet(packet)
        if not starts:
            return []
        room = -len(stream) % self.field_size
        if room:
            if room < _SP_HEADER_SIZE + 1:  # no room for an idle packet: it spans one more frame
                room += self.field_size
            starts.append(len(stream))
            stream += self.space_packet(bytes(room - _SP_HEADER_SIZE), apid=IDLE_APID)
        frames = []
        next_start = 0
        for offset in range(0, len(stream), self.field_size):
            end = offset + self.field_size
            while next_start < len(starts) and starts[next_start] < offset:
                next_start += 1
            if next_start < len(starts) and starts[next_start] < end:
                fhp = starts[next_start] - offset
            else:
                fhp = _FHP_NO_PACKET_START
            frames.append(self._tm_frame(bytes(stream[offset:end]), fhp))
        return frames

    def _tm_frame(self, field: bytes, first_header_pointer: int) -> bytes:
        count = self._frame_count
        self._frame_count = (count + 1) % 256
        word1 = (self.scid << 4) | (self.vcid << 1)  # version 00, OCF flag 0
        status = (0b11 << 11) | first_header_pointer  # segment length id 11 (no sync flag), FHP
        body = _TM_HEADER.pack(word1, count, count, status) + field
        return body + _U16.pack(crc16_ccitt(body))

    # --- uplink ---------------------------------------------------------------------------------

    def frame_uplink(self, packet: bytes, vcid: int | None = None) -> bytes:
        """A TC frame holding ``packet`` in one Space Packet, as fprime-gds frames a command."""
        sp = self.space_packet(packet, telecommand=True)
        total = _TC_HEADER_SIZE + len(sp) + _CRC16_SIZE
        if total > 1024:
            raise ValueError(f"a TC frame of {total} bytes exceeds 1024")
        word1 = (1 << 13) | (self.scid & 0x3FF)  # version 00, bypass, Type-D
        word2 = (((self.vcid if vcid is None else vcid) & 0x3F) << 10) | (total - 1)
        body = _TC_HEADER.pack(word1, word2, 0) + sp
        return body + _U16.pack(crc16_ccitt(body))

    def uplink_deframer(self) -> CcsdsTcDeframer:
        return CcsdsTcDeframer(self.scid, self.vcid)


#: ``--framing`` name -> framing class.
FRAMINGS: dict[str, type[Framing]] = {"fprime": FprimeFraming, "ccsds": CcsdsFraming}


def make_framing(name: str) -> Framing:
    """The framing called ``name`` (``fprime`` or ``ccsds``; the fprime-gds names work too)."""
    for cls in FRAMINGS.values():
        if name in (cls.name, cls.gds_name):
            return cls()
    raise ValueError(f"unknown framing {name!r}; use one of {', '.join(FRAMINGS)}")
