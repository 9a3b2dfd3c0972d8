"""How applications extend the tools: command-line verbs and benchmark pieces found through
Python entry points, so that the framework never names an application.

An application declares, in its ``pyproject.toml``::

    [project.entry-points."fprime_lite.verbs"]
    sim = "detumble.sitl.cli:SIM_VERB"            # a Verb

    [project.entry-points."fprime_lite.bench"]
    detumble = "detumble.sitl.bench:DEPLOYMENT_PIECE"   # a BenchPiece

A verb parses its own arguments (``main(argv) -> exit status``); a bench piece measures with the
options of ``fprime-lite bench`` and returns its figures and the rows of the summary table.
"""
from __future__ import annotations

import argparse
from dataclasses import dataclass
from importlib.metadata import entry_points
from typing import Callable

__all__ = ["Verb", "BenchPiece", "PluginError", "verbs", "bench_pieces", "VERBS_GROUP", "BENCH_GROUP"]

VERBS_GROUP = "fprime_lite.verbs"
BENCH_GROUP = "fprime_lite.bench"


class PluginError(Exception):
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


def _load(group: str, kind: type) -> dict:
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
