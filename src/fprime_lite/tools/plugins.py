"""How applications extend the tools: command-line verbs and benchmark pieces found through
Python entry points, so that the framework never names an application.

An application declares, in its ``pyproject.toml``::

    [project.entry-points."fprime_lite.verbs"]
    sim = "detumble.tools.cli:SIM_VERB"            # a Verb

    [project.entry-points."fprime_lite.bench"]
    detumble = "detumble.tools.bench:DEPLOYMENT_PIECE"   # a BenchPiece

    [project.entry-points."fprime_lite.plots"]
    detumble = "detumble.reports.plots:RUN_PLOTTER"        # a RunPlotter

A verb parses its own arguments (``main(argv) -> exit status``); a bench piece measures with the
options of ``fprime-lite bench`` and returns its figures and the rows of the summary table; a run
plotter draws the plots of a finished run from its folder (``fprime-lite plot RUN_DIR``,
``RunResult.plot()``) — the same plots the application's report resource draws when a run ends.
"""
from __future__ import annotations

import argparse
import pathlib
from dataclasses import dataclass
from importlib.metadata import entry_points
from typing import Callable, Protocol, TypeVar

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["Verb", "BenchPiece", "RunPlotter", "PluginError", "verbs", "bench_pieces", "run_plotters",
           "VERBS_GROUP", "BENCH_GROUP", "PLOTS_GROUP"]

VERBS_GROUP = "fprime_lite.verbs"
BENCH_GROUP = "fprime_lite.bench"
PLOTS_GROUP = "fprime_lite.plots"


class PluginError(FprimeLiteError):
    """An installed plug-in that cannot be loaded or is not what its group expects."""


@dataclass(frozen=True)
class Verb:
    """A ``fprime-lite NAME …`` verb that parses its own arguments."""

    name: str
    help: str
    main: Callable[[list[str]], int]


@dataclass(frozen=True)
class BenchPiece:
    """A measurement ``fprime-lite bench`` runs.

    ``measure(options)`` gets the bench's parsed options (``topology``, ``duration``) and returns
    JSON-able figures; ``rows(figures)`` gives the summary table's ``(figure, value, target)`` rows.
    """

    name: str
    measure: Callable[[argparse.Namespace], dict]
    rows: Callable[[dict], list[tuple[str, str, str]]]


@dataclass(frozen=True)
class RunPlotter:
    """Draws the plots of a finished run from the files in its folder.

    ``applies(run_dir) -> bool`` says whether the run has what it plots; ``plot(run_dir, out_dir)``
    draws into ``out_dir`` and returns the files written.
    """

    name: str
    applies: Callable[[pathlib.Path], bool]
    plot: Callable[[pathlib.Path, pathlib.Path], list[pathlib.Path]]


class _Named(Protocol):
    @property
    def name(self) -> str: ...


_P = TypeVar("_P", bound=_Named)


def _load(group: str, kind: type[_P]) -> dict[str, _P]:
    found = {}
    for ep in sorted(entry_points(group=group), key=lambda e: e.name):
        try:
            obj = ep.load()
        except Exception as exc:  # noqa: BLE001 - a broken plug-in is reported, not raised through
            raise PluginError(f"plug-in {ep.name!r} ({ep.value}) of {group} cannot be loaded: {exc} "
                              f"— reinstall the package that provides it") from None
        if not isinstance(obj, kind):
            raise PluginError(f"plug-in {ep.name!r} ({ep.value}) of {group} is a {type(obj).__name__}, "
                              f"not a {kind.__name__}")
        found[obj.name] = obj
    return found


def verbs() -> dict[str, Verb]:
    """The installed application verbs by name."""
    return _load(VERBS_GROUP, Verb)


def bench_pieces() -> dict[str, BenchPiece]:
    """The installed benchmark pieces by name."""
    return _load(BENCH_GROUP, BenchPiece)


def run_plotters() -> dict[str, RunPlotter]:
    """The installed run plotters by name."""
    return _load(PLOTS_GROUP, RunPlotter)
