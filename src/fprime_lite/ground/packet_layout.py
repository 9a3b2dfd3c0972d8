"""Compiled layouts of telemetry packets: a whole packet decoded and written with a few C calls.

TlmChan sends, tick after tick, packets of the same channels in the same order, so the ground can
learn a packet's *layout* (its channel ids and their value types) once and then decode every packet
of that layout with one ``struct`` unpack and write its ``channels.csv`` lines with one
``str.format`` — instead of a deserialization, a text conversion and a CSV row per channel update,
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
    ``text_of(value, template)``: the general decoder's text of a decoded value.
    """

    def __init__(self, channels: list[tuple[int, str, Any, str | None]],
                 text_of: Callable[[Any, str | None], str]):
        fmt = [">H"]
        template: list[str] = []
        id_index: list[int] = []
        usec_index: list[int] = []
        #: (tuple index of the raw bytes, text argument index, name, F´ type, template) of the other values
        complex_: list[tuple[int, int, str, Any, str | None]] = []
        #: (name, tuple indices) of the plain numbers (a struct's members in order), for the wide table
        simple: list[tuple[str, list[int]]] = []
        #: tuple indices of the floats written as JSON (they must be finite: json.dumps writes NaN)
        json_floats: list[int] = []
        index = 1
        for _, name, ftype, fmt_template in channels:
            size = fixed_size(ftype)
            if size is None:
                raise ValueError(f"channel {name} has no fixed size")
            base = _resolved(ftype)
            id_index.append(index)
            usec_index.append(index + 4)
            value_index = index + _HEAD_FIELDS
            line_head = f"{{{index + 3}}}.{{{index + 4}:06d}},{name.replace('{', '{{').replace('}', '}}')},"
            if fmt_template is None and isinstance(base, (IntType, FloatType)):
                fmt.append(_RECORD_HEAD + base._struct.format[1:])
                value = f"{{{value_index}!r}}" if isinstance(base, FloatType) else f"{{{value_index}}}"
                simple.append((name, [value_index]))
            elif fmt_template is None and isinstance(base, StructType) and base._fixed is not None and base.members:
                # numbers only: unpacked in place, written as json.dumps writes the struct (finite floats)
                fmt.append(_RECORD_HEAD + base._fixed.format[1:])
                members = []
                for k, (member, mtype) in enumerate(base.members):
                    is_float = isinstance(_resolved(mtype), FloatType)
                    members.append(f"{json.dumps(member)}: {{{value_index + k}{'!r' if is_float else ''}}}")
                    if is_float:
                        json_floats.append(value_index + k)
                json_text = "{{" + ", ".join(members) + "}}"
                value = '"' + json_text.replace('"', '""') + '"'  # quoted as csv quotes it (it has '"')
                simple.append((name, list(range(value_index, value_index + len(base.members)))))
                index = value_index + len(base.members) - 1  # the record's last field
            else:
                fmt.append(_RECORD_HEAD + f"{size}s")
                value = f"{{@{len(complex_)}}}"  # renumbered below, after the unpacked fields
                complex_.append((value_index, len(complex_), name, ftype, fmt_template))
            template.append(line_head + value + "\n")
            index = max(index, value_index) + 1
        self.struct = struct.Struct("".join(fmt))
        self.size = self.struct.size
        self.ids = tuple(cid for cid, *_ in channels)
        self._ids_of = itemgetter(*id_index) if len(id_index) > 1 else (lambda v, i=id_index[0]: (v[i],))
        self._usecs_of = itemgetter(*usec_index) if len(usec_index) > 1 else (lambda v, i=usec_index[0]: (v[i],))
        text = "".join(template)
        for j in range(len(complex_)):
            text = text.replace(f"{{@{j}}}", f"{{{index + j}}}")
        self.template = text
        # with the descriptor (field 0, = 1) the getter gives a tuple also for one float
        self._json_floats = itemgetter(*json_floats, 0) if json_floats else None
        self.simple = simple
        self.complex = complex_
        self.records = len(channels)
        self._text_of = text_of
        #: per other value: its raw bytes → (value, CSV field) for the values seen (enums, flags and
        #: modes repeat; decoded once each, at most SEEN_MAX kept)
        self._decoders: list[tuple[int, Any, str | None, dict[bytes, tuple[Any, str]]]] = [
            (value_index, ftype, fmt_template, {}) for value_index, _, _, ftype, fmt_template in complex_]

    #: raw values remembered per other value of a layout
    SEEN_MAX = 256

    def decode(self, packet: bytes) -> tuple[tuple, list[Any], list[str]] | None:
        """``(unpacked fields, decoded other values, their CSV fields)`` of ``packet``, or None when
        the packet does not have this layout (or has a time stamp the general decoder must judge).
        Raises :class:`~fprime_lite.model.errors.SerializationError` for a value its type rejects."""
        if len(packet) != self.size:
            return None
        fields = self.struct.unpack(packet)
        if self._ids_of(fields) != self.ids or max(self._usecs_of(fields)) >= US_PER_S:
            return None
        if self._json_floats is not None:
            total = sum(self._json_floats(fields))  # NaN or ±inf when one is (or when they overflow)
            if total - total != 0.0:
                return None
        values: list[Any] = []
        texts: list[str] = []
        for value_index, ftype, fmt_template, seen in self._decoders:
            raw = fields[value_index]
            known = seen.get(raw)
            if known is None:
                value = ftype.deserialize(raw)[0]
                known = (value, csv_field(self._text_of(value, fmt_template)))
                if len(seen) < self.SEEN_MAX:
                    seen[raw] = known
            values.append(known[0])
            texts.append(known[1])
        return fields, values, texts

    def lines(self, fields: tuple, texts: list[str]) -> str:
        """The packet's ``channels.csv`` lines."""
        return self.template.format(*fields, *texts)


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
