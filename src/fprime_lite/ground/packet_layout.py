"""Compiled layouts of telemetry packets: a whole packet decoded and written with a few C calls.

TlmChan sends, tick after tick, packets of the same channels in the same order, so the ground can
learn a packet's *layout* (its channel ids and their value types) once and then decode every packet
of that layout with one ``struct`` unpack and write its ``channels.csv`` lines with one
%-format (``%`` with the arguments gathered by one ``itemgetter``: it parses faster than
``str.format`` with numbered fields) — instead of a deserialization, a text conversion and a CSV row per channel update,
which made recording about a sixth of a run's wall time (issue 32).

A layout is only used when every value of the packet has a fixed size (no strings) and it is
checked on every use: the unpacked channel ids must equal the layout's, and each record's position
follows from the previous records' types, so equal ids mean the packet really has that layout.
Time stamps with ``useconds`` ≥ 10⁶ are left to the general decoder, which rejects them.

The text is the general decoder's to the byte (:class:`~fprime_lite.ground.downlink.GroundDecoder`):
integers as ``str``, floats as ``repr``; any other value (enums, bools, structs, arrays, channels
with a format string) is deserialized by its type and converted by the general decoder's own
function, then quoted as the ``csv`` module quotes a field.
"""

from __future__ import annotations

import json
import struct
from operator import itemgetter
from typing import Any, Callable

from fprime_lite.ground.wide_table import csv_field
from fprime_lite.model.time import TIME, US_PER_S
from fprime_lite.model.types import AliasType, ArrayType, BoolType, EnumType, FloatType, IntType, StructType

__all__ = ["TelemetryLayout", "LayoutCache", "fixed_size"]

#: ``U32 id | Time (U16 base, U8 context, U32 seconds, U32 useconds)`` of a record, big-endian
_RECORD_HEAD = "IHBII"
#: fields a record head adds to the unpacked tuple
_HEAD_FIELDS = 5


def _resolved(ftype):
    while isinstance(ftype, AliasType):
        ftype = ftype.target
    return ftype


def fixed_size(ftype) -> int | None:
    """Serialized size in bytes of every value of F´ type ``ftype``, or None when it varies (strings)."""
    ftype = _resolved(ftype)
    if isinstance(ftype, (IntType, FloatType, BoolType)):
        return ftype.size
    if isinstance(ftype, EnumType):
        return ftype.rep.size
    if ftype is TIME or getattr(ftype, "kind", None) == "time":
        return TIME.size
    if isinstance(ftype, StructType):
        sizes = [fixed_size(t) for _, t in ftype.members]
        return None if any(s is None for s in sizes) else sum(s for s in sizes if s is not None)
    if isinstance(ftype, ArrayType):
        elem = fixed_size(ftype.elem)
        return None if elem is None else elem * ftype.size
    return None


class TelemetryLayout:
    """How to decode and write one telemetry packet layout (see the module docstring).

    ``channels``: ``(id, name, F´ type, format template or None)`` of each record in packet order;
    ``text_of(value, template)``: the general decoder's text of a decoded value; ``cells_of(name,
    value)``: the wide table's cells of a decoded value of channel ``name`` (remembered with it).
    """

    #: raw values remembered per other value of a layout
    SEEN_MAX = 256

    def __init__(self, channels: list[tuple[int, str, Any, str | None]],
                 text_of: Callable[[Any, str | None], str],
                 cells_of: Callable[[str, Any], list[str]] = lambda _name, _value: []):
        fmt = [">H"]
        id_index: list[int] = []
        usec_index: list[int] = []
        #: (tuple index of the raw bytes, name, F´ type, template) of the other values
        complex_: list[tuple[int, str, Any, str | None]] = []
        #: (name, positions in the number cells) of the plain numbers (a struct's members in order)
        simple: list[tuple[str, list[int]]] = []
        #: tuple index of each plain number, in cell order
        numbers: list[int] = []
        #: tuple indices of the floats written as JSON (they must be finite: json.dumps writes NaN)
        json_floats: list[int] = []
        #: the lines as a %-format (the one format per packet: %-formatting parses faster than
        #: str.format's numbered fields) and what each of its conversions takes, in order: a field of
        #: the unpacked tuple ("f", i), a number cell ("#", k) or another value's text ("@", j)
        line_format: list[str] = []
        refs: list[tuple[str, int]] = []
        index = 1
        for _, name, ftype, fmt_template in channels:
            size = fixed_size(ftype)
            if size is None:
                raise ValueError(f"channel {name} has no fixed size")
            base = _resolved(ftype)
            id_index.append(index)
            usec_index.append(index + 4)
            value_index = index + _HEAD_FIELDS
            line_format.append(f"%d.%06d,{name.replace('%', '%%')},")
            refs += [("f", index + 3), ("f", index + 4)]
            if fmt_template is None and isinstance(base, (IntType, FloatType)):
                fmt.append(_RECORD_HEAD + base._struct.format[1:])
                line_format.append("%s\n")
                refs.append(("#", len(numbers)))
                simple.append((name, [len(numbers)]))
                numbers.append(value_index)
                index = value_index + 1
            elif fmt_template is None and isinstance(base, StructType) and base._fixed is not None and base.members:
                # numbers only: unpacked in place, written as json.dumps writes the struct (finite floats)
                fmt.append(_RECORD_HEAD + base._fixed.format[1:])
                members = []
                for k, (member, mtype) in enumerate(base.members):
                    # quoted as csv quotes the field (it has '"'), '%' escaped for the %-format
                    members.append(json.dumps(member).replace('"', '""').replace("%", "%%") + ": %s")
                    refs.append(("#", len(numbers) + k))
                    if isinstance(_resolved(mtype), FloatType):
                        json_floats.append(value_index + k)
                line_format.append('"{' + ", ".join(members) + '}"\n')
                simple.append((name, list(range(len(numbers), len(numbers) + len(base.members)))))
                numbers.extend(range(value_index, value_index + len(base.members)))
                index = value_index + len(base.members)
            else:
                fmt.append(_RECORD_HEAD + f"{size}s")
                line_format.append("%s\n")
                refs.append(("@", len(complex_)))
                complex_.append((value_index, name, ftype, fmt_template))
                index = value_index + 1
        self.line_format = "".join(line_format)
        # the arguments in line_format's order, from (*fields, *texts, *cells); three a record at least,
        # so the getter always gives a tuple
        self._line_args = itemgetter(*(i if kind == "f" else index + i if kind == "@" else index + len(complex_) + i
                                       for kind, i in refs))
        self.struct = struct.Struct("".join(fmt))
        self.size = self.struct.size
        self.ids = tuple(cid for cid, *_ in channels)
        self._ids_of = itemgetter(*id_index, 0)  # the descriptor (field 0, = 1) makes it a tuple also for one
        self._usecs_of = itemgetter(*usec_index, 0)
        self._numbers_of = itemgetter(*numbers, 0) if numbers else None  # the descriptor's cell is left unused
        # with the descriptor the getter gives a tuple also for one float
        self._json_floats = itemgetter(*json_floats, 0) if json_floats else None
        self.simple = simple
        #: (name, index of its value) of the other values
        self.complex = [(name, j) for j, (_, name, _, _) in enumerate(complex_)]
        self.records = len(channels)
        self._text_of = text_of
        self._cells_of = cells_of
        #: per other value: its raw bytes → (value, CSV field, wide cells) for the values seen (enums,
        #: flags and modes repeat; decoded once each, at most SEEN_MAX kept)
        self._decoders: list[tuple[int, str, Any, str | None, dict[bytes, tuple[Any, str, list[str]]]]] = [
            (value_index, name, ftype, fmt_template, {}) for value_index, name, ftype, fmt_template in complex_]

    def decode(self, packet: bytes) -> tuple[str, list[str], list[list[str]]] | None:
        """``(the packet's channels.csv lines, the number cells, each other value's wide cells)``, or
        None when the packet does not have this layout (or has a time stamp the general decoder must
        judge). Raises :class:`~fprime_lite.model.errors.SerializationError` for a value its type rejects.

        Each number is formatted once (``str``: ``repr`` for a float), for both files."""
        if len(packet) != self.size:
            return None
        fields = self.struct.unpack(packet)
        if self._ids_of(fields)[:-1] != self.ids or max(self._usecs_of(fields)) >= US_PER_S:
            return None
        if self._json_floats is not None:
            total = sum(self._json_floats(fields))  # NaN or ±inf when one is (or when they overflow)
            if total - total != 0.0:
                return None
        cells = list(map(str, self._numbers_of(fields))) if self._numbers_of is not None else []
        texts: list[str] = []
        wide: list[list[str]] = []
        for value_index, name, ftype, fmt_template, seen in self._decoders:
            raw = fields[value_index]
            known = seen.get(raw)
            if known is None:
                value = ftype.deserialize(raw)[0]
                known = (value, csv_field(self._text_of(value, fmt_template)), self._cells_of(name, value))
                if len(seen) < self.SEEN_MAX:
                    seen[raw] = known
            texts.append(known[1])
            wide.append(known[2])
        return self.line_format % self._line_args((*fields, *texts, *cells)), cells, wide


class LayoutCache:
    """The layouts seen so far, found by a packet's length and first channel id (a few per key)."""

    #: layouts kept per (length, first id); more are rare (TlmChan's packets repeat)
    PER_KEY = 4

    def __init__(self) -> None:
        self._layouts: dict[tuple[int, bytes], list[TelemetryLayout]] = {}

    def candidates(self, packet: bytes) -> list[TelemetryLayout]:
        return self._layouts.get((len(packet), packet[2:6]), [])

    def add(self, packet: bytes, layout: TelemetryLayout) -> None:
        kept = self._layouts.setdefault((len(packet), packet[2:6]), [])
        kept.insert(0, layout)
        del kept[self.PER_KEY:]
