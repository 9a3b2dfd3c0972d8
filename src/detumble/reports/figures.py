"""What the application's plots share: ``truth.csv`` read for plotting, and a figure saved whole.

:func:`read_truth` is used by :mod:`.plots` and :mod:`.power_budget`; :func:`save_figure` by every
module that draws a PNG (:mod:`.plots`, :mod:`.power_budget`, :mod:`.attitude_report`).
"""
from __future__ import annotations

import csv
import math
import os
import pathlib

from fprime_lite.osal.atomic import open_temporary

__all__ = ["read_truth", "is_interval_mean", "save_figure", "MAX_PLOT_POINTS"]

#: ``truth.csv`` rows kept for a plot at the most (every ``k``-th row, and the last).
MAX_PLOT_POINTS = 4000


def is_interval_mean(column: str) -> bool:
    """True for a ``truth.csv`` column that holds a mean (or a share of time) over the interval since
    the previous row, rather than a value at the row's instant (docs/outputs.md)."""
    return column.startswith(("level_mean_", "on_", "m_mean_", "frac_")) or column.endswith("_w_mean")


def read_truth(path: pathlib.Path, max_points: int | None = MAX_PLOT_POINTS) -> dict[str, list]:
    """Columns of ``truth.csv`` (numbers as floats, empty cells NaN, ``strategy`` as text),
    decimated to at most ``max_points`` rows (memory stays flat; None keeps every row): every
    ``k``-th row and the last are kept, and a kept row's interval-mean columns (:func:`is_interval_mean`)
    hold the mean over the rows since the previous kept one, so the decimated means stay exact."""
    with open(path, encoding="utf-8") as f:
        rows = sum(1 for _ in f) - 1
    stride = 1 if max_points is None else max(1, math.ceil(rows / max_points))
    columns: dict[str, list] = {}
    with open(path, encoding="utf-8", newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        for name in header:
            columns[name] = []
        means = [k for k, name in enumerate(header) if is_interval_mean(name)] if stride > 1 else []
        sums = [0.0] * len(header)
        counts = [0] * len(header)
        for i, row in enumerate(reader):
            for k in means:
                if row[k] != "":
                    sums[k] += float(row[k])
                    counts[k] += 1
            if i % stride == 0 or i == rows - 1:
                for name, value in zip(header, row, strict=True):
                    columns[name].append(value)
                for k in means:
                    columns[header[k]][-1] = sums[k] / counts[k] if counts[k] else ""
                    sums[k], counts[k] = 0.0, 0
    for name in list(columns):
        if name != "strategy":
            columns[name] = [v if isinstance(v, float) else float(v) if v != "" else math.nan for v in columns[name]]
    return columns


def save_figure(fig, path: pathlib.Path) -> pathlib.Path:
    """Write ``fig`` to ``path`` as a PNG (110 dpi, tight), under a recognisable temporary name first
    (:func:`fprime_lite.osal.atomic.open_temporary`: a reader never sees half a file, and the next run
    removes what a killed one left). Returns ``path``."""
    fh, tmp = open_temporary(path, "wb")
    try:
        with fh:
            fig.savefig(fh, format="png", dpi=110, bbox_inches="tight")
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path
