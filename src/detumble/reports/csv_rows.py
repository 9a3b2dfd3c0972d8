"""A ``csv.writer`` for the run reports' 1 Hz rows that skips the csv module's per-character scan.

``csv.writer(fh, lineterminator="\\n").writerow(row)`` converts each field with ``str`` (``None``
becomes empty), then copies it character by character, looking each one up among the delimiter, the
quote character and the line terminator to decide whether the field needs quotes. The reports'
rows are numbers and plain words (``repr`` of floats, ``f"{x:.4f}"``, an enum name), which never
do: :class:`FastCsvWriter` joins the ``str`` of each field with commas and checks the finished line
once (C-speed scans) for anything the csv module would treat specially — a quote, a carriage return
or line feed, a comma inside a field (more commas than separators), the text ``None`` (a ``None``
field, which csv writes empty) or a row of one empty field (written ``""``). Such a row is handed to
the csv module itself, so every row comes out byte for byte as ``csv.writer`` writes it.

:class:`FormattedCsvWriter` also formats the numbers of some columns (``format(x, ".4f")``, the text
``f"{x:.4f}"`` gives) where it writes the row: a run report hands it the raw numbers, so that with
``fprime-lite run``'s writer process the formatting is done by the writer, not by the flight's process.
"""

from __future__ import annotations

import csv
import functools
from typing import TextIO

__all__ = ["FastCsvWriter", "FormattedCsvWriter", "formatted_csv_writer"]


class FastCsvWriter:
    """``writerow`` as ``csv.writer(file, lineterminator="\\n")``'s (the default dialect), the same bytes."""

    __slots__ = ("_write", "_csv")

    def __init__(self, file: TextIO) -> None:
        self._write = file.write
        self._csv = csv.writer(file, lineterminator="\n")

    def writerow(self, row: list | tuple) -> None:
        """Write ``row`` (a list or tuple of fields) as one CSV line."""
        line = ",".join(map(str, row))
        if (line.count(",") == len(row) - 1 and '"' not in line and "\n" not in line and "\r" not in line
                and "None" not in line and (line or len(row) != 1)):
            self._write(line + "\n")
        else:  # a field the csv module quotes or converts specially: let it write the row
            self._csv.writerow(row)


class FormattedCsvWriter(FastCsvWriter):
    """:class:`FastCsvWriter` that formats column ``i`` with ``formats[i]`` (a format spec such as ``".4f"``;
    None or past the end: written as is). A field that is a ``str`` is written as is in every column (the
    header, an empty cell, ``"nan"``), so ``writerow([x])`` with ``formats=(".4f",)`` writes ``f"{x:.4f}"``
    and ``writerow([""])`` an empty cell.

    A row of as many fields as formats is first formatted by one ``str.format`` of a template
    (``"{:.6f},{!s},…"``); a text in a formatted column (which ``format`` refuses) or a line the csv module
    would write otherwise (the checks of :class:`FastCsvWriter`) takes the field-by-field path."""

    __slots__ = ("_formats", "_template")

    def __init__(self, file: TextIO, formats: tuple) -> None:
        super().__init__(file)
        self._formats = tuple(formats)
        self._template = ",".join("{!s}" if spec is None else "{:" + spec + "}" for spec in self._formats)

    def writerow(self, row: list | tuple) -> None:
        """Format the numbers of the formatted columns, then write ``row`` as :class:`FastCsvWriter` does."""
        n = len(row)
        if n == len(self._formats) and n > 1:
            try:
                line = self._template.format(*row)
            except (ValueError, TypeError):  # a text (or None) in a formatted column
                pass
            else:
                if (line.count(",") == n - 1 and '"' not in line and "\n" not in line and "\r" not in line
                        and "None" not in line):
                    self._write(line + "\n")
                    return
        if n > len(self._formats):
            specs = self._formats + (None,) * (n - len(self._formats))
        else:
            specs = self._formats
        super().writerow([v if s is None or type(v) is str else format(v, s) for v, s in zip(row, specs, strict=False)])


def formatted_csv_writer(formats) -> functools.partial:
    """A row-writer factory (``factory(file)``, as ``open_row_stream`` takes) for :class:`FormattedCsvWriter`
    with ``formats``; picklable, so the writer process can make it."""
    return functools.partial(FormattedCsvWriter, formats=tuple(formats))
