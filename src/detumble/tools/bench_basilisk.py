"""The ``basilisk`` piece of ``fprime-lite bench``: the side-by-side comparison with Basilisk (issue #19).

The comparison is not part of the installed package: it lives in a checkout's
``benchmarks/basilisk/`` (run it alone with ``python benchmarks/bench_vs_basilisk.py``) and needs
Basilisk (``pip install -e '.[bsk]'``). This piece finds that folder beside ``src/`` — an
editable install of a checkout — and runs it; anywhere else it measures nothing and its row says
where the comparison is.
"""
from __future__ import annotations

import argparse
import importlib
import pathlib
import sys
from types import ModuleType

from fprime_lite.tools.plugins import BenchPiece

__all__ = ["BASILISK_PIECE", "NOT_IN_A_CHECKOUT", "comparison"]

#: ``benchmarks/`` of the checkout this package was installed from (editable install).
BENCHMARKS = pathlib.Path(__file__).resolve().parents[3] / "benchmarks"
NOT_IN_A_CHECKOUT = ("the Basilisk comparison is in a checkout's benchmarks/basilisk/: from a clone, "
                     "pip install -e '.[bsk]' and python benchmarks/bench_vs_basilisk.py")


def comparison() -> ModuleType | None:
    """The checkout's ``benchmarks/basilisk/bench.py`` as module ``basilisk.bench``, or None outside a checkout."""
    if not (BENCHMARKS / "basilisk" / "bench.py").is_file():
        return None
    if str(BENCHMARKS) not in sys.path:
        sys.path.insert(0, str(BENCHMARKS))
    return importlib.import_module("basilisk.bench")


def _measure(options: argparse.Namespace) -> dict:
    bench = comparison()
    if bench is None:
        return {"installed": False, "how_to_run": NOT_IN_A_CHECKOUT}
    return bench.piece_figures(options)


def _rows(figures: dict) -> list[tuple[str, str, str]]:
    bench = comparison()
    if bench is None or "how_to_run" in figures:
        return [("Basilisk side by side", f"not measured: {figures.get('how_to_run', NOT_IN_A_CHECKOUT)}", "")]
    return bench.piece_rows(figures)


#: The bench piece: ``basilisk`` in ``bench.json``.
BASILISK_PIECE = BenchPiece(name="basilisk", measure=_measure, rows=_rows)
