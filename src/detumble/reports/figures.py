"""What the application's plots share: ``truth.csv`` read for plotting, and a figure saved whole.

:func:`read_truth` is used by :mod:`.plots` and :mod:`.power_budget`; :func:`save_figure` by every
module that draws a PNG (:mod:`.plots`, :mod:`.power_budget`, :mod:`.attitude_report`).
"""
from __future__ import annotations

import csv
import math
import os
import pathlib

__all__ = ["read_truth", "save_figure", "MAX_PLOT_POINTS"]

#: ``truth.csv`` rows kept for a plot at the most (every ``k``-th row, and the last).
MAX_PLOT_POINTS = 4000


def read_truth(path: pathlib.Path, max_points: int | None = MAX_PLOT_POINTS) -> dict[str, list]:
    """Columns of ``truth.csv`` (numbers as floats, empty cells NaN, ``strategy`` as text),
    decimated to at most ``max_points`` rows (memory stays flat; None keeps every row)."""
    with open(path, encoding="utf-8") as f:
        rows = sum(1 for _ in f) - 1
    stride = 1 if max_points is None else max(1, math.ceil(rows / max_points))
    columns: dict[str, list] = {}
    with open(path, encoding="utf-8", newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        for name in header:
            columns[name] = []
        for i, row in enumerate(reader):
            if i % stride == 0 or i == rows - 1:
                for name, value in zip(header, row, strict=True):
                    columns[name].append(value)
    for name in list(columns):
        if name != "strategy":
            columns[name] = [float(v) if v != "" else math.nan for v in columns[name]]
    return columns


def save_figure(fig, path: pathlib.Path) -> pathlib.Path:
    """Write ``fig`` to ``path`` as a PNG (110 dpi, tight), under a temporary name first: a reader never
    sees half a file. Returns ``path``."""
    tmp = path.with_name(f".{path.stem}.part.png")
    fig.savefig(tmp, dpi=110, bbox_inches="tight")
    os.replace(tmp, path)
    return path
