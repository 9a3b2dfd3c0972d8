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
integers as ``str``, floats as ``repr`` (each kind through a cache of the texts of the values met:
telemetry repeats, and a lookup costs far less than ``repr``'s digit search); a struct of numbers and
time stamps (``Drv.MagneticField``) and an array of numbers (``Components.Vector3``) are unpacked in
place and written as ``json.dumps`` writes them, a time stamp as
:func:`~fprime_lite.ground.time_text.time_text`; any other value (enums, bools, other structs and
arrays, channels with a format string) is deserialized by its type and converted by the
general decoder's own function the first time its raw bytes are met, then quoted as the ``csv``
module quotes a field.
"""

from __future__ import annotations

import json
import re
import string
import struct
from operator import itemgetter
from typing import Any, Callable

from fprime_lite.ground.time_text import time_text
from fprime_lite.ground.wide_table import _SPECIAL, csv_field  # _SPECIAL: what csv_field quotes for
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


def _tuple_getter(indices: list[int]) -> Callable[[tuple], tuple]:
    """A function giving the items of a tuple at ``indices`` as a tuple (one index: that item twice,
    since ``itemgetter`` of one index gives the item itself; none: the empty tuple)."""
    if not indices:
        return lambda _fields: ()
    return itemgetter(*indices, *indices[:1]) if len(indices) == 1 else itemgetter(*indices)


class _IntTexts(dict):
    """int → its text (``str``), kept for the values met (telemetry repeats: counters, levels, modes);
    emptied when it holds ``LIMIT``."""

    LIMIT = 4096

    def __missing__(self, value: int) -> str:
        text = str(value)
        if len(self) >= self.LIMIT:
            self.clear()
        self[value] = text
        return text


class _FloatTexts(dict):
    """float → its text (``repr``), as :class:`_IntTexts`: looking a float up costs a hash and a
    comparison where ``repr`` runs the shortest round-trip digit search. Zeros are not kept (0.0 and
    -0.0 are equal keys with two texts), nor NaN (never equal to itself); only floats are looked up
    here (an int equal to a float would find the float's text)."""

    LIMIT = 4096

    def __missing__(self, value: float) -> str:
        text = repr(value)
        if value == value and value != 0.0:
            if len(self) >= self.LIMIT:
                self.clear()
            self[value] = text
        return text


class _Seen(dict):
    """Raw bytes of one other value of a layout → ``(its CSV field, its wide cells)``, decoded by
    its type the first time (enums, flags and modes repeat); at most ``limit`` kept."""

    def __init__(self, name: str, ftype, template: str | None, text_of, cells_of, limit: int):
        super().__init__()
        self.name, self.ftype, self.template = name, ftype, template
        self.text_of, self.cells_of, self.limit = text_of, cells_of, limit

    def __missing__(self, raw: bytes) -> tuple[str, list[str]]:
        value = self.ftype.deserialize(raw)[0]
        known = (csv_field(self.text_of(value, self.template)), self.cells_of(self.name, value))
        if len(self) < self.limit:
            self[raw] = known
        return known


def _percent_template(template: str, ftype) -> str | None:
    """``template`` (a channel's ``str.format`` template, one field) as a %-format giving the same text
    for every value of number type ``ftype``, without CSV quoting: ``{}`` of an int is ``%d``, ``{:.Nf}``
    of a float is ``%.Nf`` (both format through the same C conversion, NaN, infinities and -0.0
    included); None for any other template or a literal text with a character CSV quotes."""
    try:
        parts = list(string.Formatter().parse(template))
    except ValueError:
        return None
    fields = [(name, spec, conversion) for _, name, spec, conversion in parts if name is not None]
    literal = "".join(text for text, *_ in parts)
    if len(fields) != 1 or not _SPECIAL.isdisjoint(literal):
        return None
    name, spec, conversion = fields[0]
    if name not in ("", "0") or conversion is not None:
        return None
    if isinstance(ftype, IntType) and spec == "":
        conversion_text = "%d"
    elif isinstance(ftype, FloatType) and spec is not None and re.fullmatch(r"\.[0-9]{1,2}f", spec):
        conversion_text = "%" + spec
    else:
        return None
    return "".join(text.replace("%", "%%") + (conversion_text if name is not None else "")
                   for text, name, _, _ in parts)


def _is_time(ftype) -> bool:
    return ftype is TIME or getattr(ftype, "kind", None) == "time"


def _plain_struct(ftype) -> bool:
    """Whether a value of (resolved) type ``ftype`` is a struct of numbers and time stamps only."""
    return isinstance(ftype, StructType) and bool(ftype.members) and all(
        isinstance(_resolved(t), (IntType, FloatType)) or _is_time(_resolved(t)) for _, t in ftype.members)


_dict_getitem = dict.__getitem__
_first = itemgetter(0)
_second = itemgetter(1)


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
        #: (name, its cells) of the plain numbers and structs of numbers and times, a cell being a
        #: number's ("#", k) or a time stamp's ("T", j)
        simple_refs: list[tuple[str, list[tuple[str, int]]]] = []
        #: tuple index of each plain number, in the order its cell is first referenced
        numbers: list[int] = []
        #: whether each of ``numbers`` is a float (else an int)
        is_float: list[bool] = []
        #: tuple indices (base, seconds, useconds) of each time stamp member of a struct
        times: list[tuple[int, int, int]] = []
        #: tuple indices of the floats written as JSON (they must be finite: json.dumps writes NaN)
        json_floats: list[int] = []
        #: the lines as a %-format (the one format per packet: %-formatting parses faster than
        #: str.format's numbered fields) and what each of its conversions takes, in order: a field of
        #: the unpacked tuple ("f", i), a number cell ("#", k), another value's text ("@", j) or a time
        #: stamp's text ("t", j)
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
            percent = (_percent_template(fmt_template, base)
                       if fmt_template is not None and isinstance(base, (IntType, FloatType)) else None)
            if percent is not None:
                # a number with a simple format string: its text a %-conversion of the unpacked value,
                # its wide cell the number's
                fmt.append(_RECORD_HEAD + base._struct.format[1:])
                line_format.append(percent + "\n")
                refs.append(("f", value_index))
                simple_refs.append((name, [("#", len(numbers))]))
                numbers.append(value_index)
                is_float.append(isinstance(base, FloatType))
                index = value_index + 1
            elif fmt_template is None and isinstance(base, (IntType, FloatType)):
                fmt.append(_RECORD_HEAD + base._struct.format[1:])
                line_format.append("%s\n")
                refs.append(("#", len(numbers)))
                simple_refs.append((name, [("#", len(numbers))]))
                numbers.append(value_index)
                is_float.append(isinstance(base, FloatType))
                index = value_index + 1
            elif fmt_template is None and isinstance(base, ArrayType) and base._fixed is not None and base.size:
                # an array of numbers: unpacked in place, written as json.dumps writes its list (finite
                # floats), quoted when it has a comma (two elements or more)
                fmt.append(_RECORD_HEAD + base._fixed.format[1:])
                quote = '"' if base.size > 1 else ""
                line_format.append(quote + "[" + ", ".join(["%s"] * base.size) + "]" + quote + "\n")
                element_is_float = isinstance(_resolved(base.elem), FloatType)
                element_cells: list[tuple[str, int]] = []
                for k in range(base.size):
                    refs.append(("#", len(numbers)))
                    element_cells.append(("#", len(numbers)))
                    numbers.append(value_index + k)
                    is_float.append(element_is_float)
                    if element_is_float:
                        json_floats.append(value_index + k)
                simple_refs.append((name, element_cells))
                index = value_index + base.size
            elif fmt_template is None and _plain_struct(base):
                # numbers and time stamps only: unpacked in place, written as json.dumps writes the
                # struct (finite floats; a time stamp as its text)
                record_fmt = [_RECORD_HEAD]
                members = []
                member_cells: list[tuple[str, int]] = []
                index = value_index
                for member, mtype in base.members:
                    mtype = _resolved(mtype)
                    # quoted as csv quotes the field (it has '"'), '%' escaped for the %-format
                    key = json.dumps(member).replace('"', '""').replace("%", "%%")
                    if _is_time(mtype):
                        record_fmt.append("HBII")
                        members.append(key + ': ""%s""')
                        refs.append(("t", len(times)))
                        member_cells.append(("T", len(times)))
                        times.append((index, index + 2, index + 3))
                        usec_index.append(index + 3)
                        index += 4
                    else:
                        record_fmt.append(mtype._struct.format[1:])
                        members.append(key + ": %s")
                        refs.append(("#", len(numbers)))
                        member_cells.append(("#", len(numbers)))
                        numbers.append(index)
                        is_float.append(isinstance(mtype, FloatType))
                        if is_float[-1]:
                            json_floats.append(index)
                        index += 1
                fmt.append("".join(record_fmt))
                line_format.append('"{' + ", ".join(members) + '}"\n')
                simple_refs.append((name, member_cells))
            else:
                fmt.append(_RECORD_HEAD + f"{size}s")
                line_format.append("%s\n")
                refs.append(("@", len(complex_)))
                complex_.append((value_index, name, ftype, fmt_template))
                index = value_index + 1
        self.line_format = "".join(line_format)
        # the cells: the ints, then the floats (each kind through its own cache of texts), then the
        # time stamps' (a getter of one index gives it twice: see _tuple_getter)
        int_numbers = [i for i, f in zip(numbers, is_float, strict=True) if not f]
        float_numbers = [i for i, f in zip(numbers, is_float, strict=True) if f]
        int_cells = len(int_numbers) + (len(int_numbers) == 1)
        float_cells = len(float_numbers) + (len(float_numbers) == 1)
        int_positions = iter(range(int_cells))
        float_positions = iter(range(int_cells, int_cells + float_cells))
        cell_at = [next(float_positions) if f else next(int_positions) for f in is_float]

        def cell(kind: str, i: int) -> int:
            return cell_at[i] if kind == "#" else int_cells + float_cells + i

        n_cells = int_cells + float_cells + len(times)
        self.simple = [(name, [cell(kind, i) for kind, i in cells]) for name, cells in simple_refs]
        self._ints_of = _tuple_getter(int_numbers)
        self._floats_of = _tuple_getter(float_numbers)
        self._int_text = _IntTexts().__getitem__
        self._float_text = _FloatTexts().__getitem__
        self._times = times
        # the arguments in line_format's order, from (*fields, *texts, *cells, *time texts); three a
        # record at least, so the getter always gives a tuple
        offsets = {"f": 0, "@": index, "t": index + len(complex_) + n_cells}
        self._line_args = itemgetter(*(index + len(complex_) + cell(kind, i) if kind == "#" else offsets[kind] + i
                                       for kind, i in refs))
        self.struct = struct.Struct("".join(fmt))
        self.size = self.struct.size
        self.ids = tuple(cid for cid, *_ in channels)
        self._ids_of = itemgetter(*id_index, 0)  # the descriptor (field 0, = 1) makes it a tuple also for one
        self._usecs_of = itemgetter(*usec_index, 0)
        # with the descriptor the getter gives a tuple also for one float
        self._json_floats = itemgetter(*json_floats, 0) if json_floats else None
        #: (name, index of its value) of the other values
        self.complex = [(name, j) for j, (_, name, _, _) in enumerate(complex_)]
        self.records = len(channels)
        #: per other value: its raw bytes → (CSV field, wide cells) for the values seen (at most
        #: SEEN_MAX kept), looked up all at once
        self._seen = [_Seen(name, ftype, fmt_template, text_of, cells_of, self.SEEN_MAX)
                      for _, name, ftype, fmt_template in complex_]
        self._raws_of = _tuple_getter([value_index for value_index, *_ in complex_])

    def decode(self, packet: bytes) -> tuple[str, tuple[str, ...], list[list[str]]] | None:
        """``(the packet's channels.csv lines, the number and time cells, each other value's wide
        cells)``, or None when the packet does not have this layout (or has a time stamp the general
        decoder must judge). Raises :class:`~fprime_lite.model.errors.SerializationError` for a value
        its type rejects.

        Each number is formatted once (``str``: ``repr`` for a float), for both files; a number met
        before is not formatted again (:class:`_IntTexts`, :class:`_FloatTexts`)."""
        if len(packet) != self.size:
            return None
        fields = self.struct.unpack(packet)
        if self._ids_of(fields)[:-1] != self.ids or max(self._usecs_of(fields)) >= US_PER_S:
            return None
        if self._json_floats is not None:
            total = sum(self._json_floats(fields))  # NaN or ±inf when one is (or when they overflow)
            if total - total != 0.0:
                return None
        cells = (*map(self._int_text, self._ints_of(fields)), *map(self._float_text, self._floats_of(fields)))
        time_texts = []
        if self._times:
            time_cells = []
            for base_at, seconds_at, useconds_at in self._times:
                seconds, useconds = fields[seconds_at], fields[useconds_at]
                time_texts.append(time_text(fields[base_at], seconds, useconds))
                time_cells.append(repr((seconds * US_PER_S + useconds) / 1e6))  # Time.total_us / 1e6
            cells = (*cells, *time_cells)
        if self._seen:
            known = tuple(map(_dict_getitem, self._seen, self._raws_of(fields)))
            args = (*fields, *map(_first, known), *cells, *time_texts)
            wide = list(map(_second, known))
        else:
            args = (*fields, *cells, *time_texts)
            wide = []
        return self.line_format % self._line_args(args), cells, wide


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
