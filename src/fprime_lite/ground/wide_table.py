"""``channels_wide.csv``: the downlinked telemetry as one column per channel, for pandas.

``channels.csv`` keeps the telemetry as the ground receives it (one row per channel update with the
time the channel was written, the value as text). The wide table has one row per downlink — each
moment the ground received telemetry packets (a TlmChan ``Run`` tick) — and one column per scalar:
a struct channel becomes one column per member (``…MagneticField.x``), an array one per element
(``…Vec.0``), an enum its constant's name, a time its seconds (float). A column heading carries the
channel's ``units`` in brackets (``…AngularVelocityMagnitude [deg/s]``; time members ``[s]``).
Each row holds every channel's latest value received so far (empty until the channel's first
update), as a ground display would show them at that moment; a channel's own write time is in
``channels.csv``.

    pandas.read_csv("runs/…/channels_wide.csv", index_col="t_s")

Columns ``t_s`` (seconds of the reception since the start of the run) and ``time`` (the reception
time as seconds in the deployment's time base: Unix seconds for workstation time) come first. Rows
are streamed: memory stays flat.
"""
from __future__ import annotations

import csv
import enum
import io
from typing import Any, Callable

from fprime_lite.model.time import Time

__all__ = ["WideTelemetryTable", "scalar_columns", "csv_field", "csv_cell"]


def scalar_columns(ftype) -> list[tuple[str, Callable[[Any], Any], bool]]:
    """``(suffix, extract, is_time)`` for each scalar a value of F´ type ``ftype`` holds."""
    target = getattr(ftype, "target", None)
    if getattr(ftype, "kind", None) != "struct" and target is not None:  # an alias: its target's columns
        return scalar_columns(target)
    members = getattr(ftype, "members", None)
    if getattr(ftype, "kind", None) == "struct" and members is not None:
        out = []
        for name, t in members:
            for suffix, get, is_time in scalar_columns(t):
                out.append((f".{name}{suffix}", _member(name, get), is_time))
        return out
    if getattr(ftype, "kind", None) == "array":
        out = []
        for i in range(ftype.size):
            for suffix, get, is_time in scalar_columns(ftype.elem):
                out.append((f".{i}{suffix}", _element(i, get), is_time))
        return out
    return [("", _leaf, _is_time_type(ftype))]


def _is_time_type(ftype) -> bool:
    return getattr(ftype, "kind", None) == "time"


def _member(name, get):
    return lambda v: get(getattr(v, name))


def _element(i, get):
    return lambda v: get(v[i])


def _leaf(v):
    if isinstance(v, enum.Enum):
        return v.name
    if isinstance(v, Time):
        return v.total_us / 1e6
    if isinstance(v, bool):
        return int(v)
    return v


_SPECIAL = frozenset(',"\r\n')
_field_buffer = io.StringIO()
_field_writer = csv.writer(_field_buffer, lineterminator="\n")


def csv_field(text: str) -> str:
    """``text`` as the ``csv`` module writes it as one field (not the only one) of a row."""
    if _SPECIAL.isdisjoint(text):
        return text
    _field_buffer.seek(0)
    _field_buffer.truncate()
    _field_writer.writerow([text, ""])
    return _field_buffer.getvalue()[:-2]  # the row without its trailing ",\n"


def csv_cell(value) -> str:
    """A column value (what :func:`scalar_columns`' extractors give) as ``csv`` writes it in a row."""
    if type(value) is str:
        return csv_field(value)
    return str(value)  # floats as repr, ints as str: what csv writes for them


class WideTelemetryTable:
    """Streams decoded channels into a wide CSV (see the module docstring).

    ``channels`` maps channel name → ``(F´ type, units or None)`` in the column order wanted.
    """

    def __init__(self, file, channels: dict[str, tuple[Any, str | None]], start: Time | None = None):
        self._csv = csv.writer(file, lineterminator="\n")
        self._columns: dict[str, list[tuple[int, Callable]]] = {}
        header = ["t_s", "time"]
        for name, (ftype, units) in channels.items():
            slots = []
            for suffix, get, is_time in scalar_columns(ftype):
                unit = "s" if is_time else units
                header.append(f"{name}{suffix}" + (f" [{unit}]" if unit else ""))
                slots.append((len(header) - 1, get))
            self._columns[name] = slots
        self._csv.writerow(header)
        self._file = file
        #: the row being filled, each cell already as its CSV text (a value is formatted once per
        #: update, not once per row it stays in)
        self._row: list[str] = [""] * len(header)
        self._time_us: int | None = None
        self._first_us: int | None = start.total_us if start is not None else None

    def add(self, time: Time, name: str, value: Any) -> None:
        """One channel update received at ``time`` (reception times do not go backwards)."""
        row = self.at(time)
        for index, get in self._columns.get(name, ()):
            row[index] = csv_cell(get(value))

    def slots(self, name: str) -> list[tuple[int, Callable]]:
        """``(column index, extract)`` of each column of channel ``name`` (none for an unknown one)."""
        return self._columns.get(name, [])

    def at(self, time: Time) -> list[str]:
        """The row of updates received at ``time`` (after :meth:`add`'s rules), to set columns in
        through :meth:`slots` (each as :func:`csv_cell` text): what :meth:`add` does for many updates
        of one reception at once."""
        us = time.total_us
        if self._time_us is not None and us != self._time_us:
            self._flush()
        if self._first_us is None:
            self._first_us = us
        self._time_us = us
        return self._row

    def _flush(self) -> None:
        row, time_us, first_us = self._row, self._time_us, self._first_us
        assert time_us is not None and first_us is not None  # a row is flushed after a sample set them
        row[0] = f"{(time_us - first_us) / 1e6:.6f}"
        row[1] = f"{time_us / 1e6:.6f}"
        self._file.write(",".join(row) + "\n")

    def close(self) -> None:
        if self._time_us is not None:
            self._flush()
            self._time_us = None
