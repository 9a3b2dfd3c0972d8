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
"""

from __future__ import annotations

import csv
from typing import TextIO

__all__ = ["FastCsvWriter"]


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
