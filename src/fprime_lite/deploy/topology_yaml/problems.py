"""The problems found while loading a topology, each ``file:line: what is wrong — what to do``.

Every stage adds to one :class:`Problems`; the loader raises them together at the end so the user
sees every mistake at once. :class:`Problems` also remembers what failed to build, so that later
stages skip whatever depends on it without reporting the same mistake twice.
"""

from __future__ import annotations

import pathlib
from typing import Any, Iterable

from fprime_lite.deploy.topology import TopologyError
from fprime_lite.deploy.topology_yaml.parse import MAX_PROBLEMS, Loc, YMap, kind
from fprime_lite.model.errors import did_you_mean

__all__ = ["Problems", "MAX_PROBLEMS", "unknown_key_message"]



class Problems:
    """An ordered list of located problems plus what has failed so far."""

    def __init__(self) -> None:
        self.items: list[str] = []
        #: Resources that could not be built (reported once); whatever uses them is skipped quietly.
        self.failed_resources: set[str] = set()
        #: Qualified instances that could not be built.
        self.failed_instances: set[str] = set()
        #: Modules whose include could not be read.
        self.failed_modules: set[str] = set()
        #: Problems past MAX_PROBLEMS, counted only.
        self.not_shown = 0
        self._first_not_shown = ""

    def __len__(self) -> int:
        return len(self.items) + self.not_shown

    def add(self, file: pathlib.Path, line: int | None, message: str) -> None:
        if isinstance(line, Loc):
            file = line.file  # the value came from this file (an included or extended one)
        if len(self.items) >= MAX_PROBLEMS:
            self.not_shown += 1
            if self.not_shown == 1:
                self._first_not_shown = f"{file}:{line if line is not None else '?'}"
            return
        self.items.append(f"{file}:{line if line is not None else '?'}: {message}")

    def extend(self, problems: Iterable[str]) -> None:
        """Add problems already located (``file:line: …``), e.g. those of a parsed file."""
        for problem in problems:
            if len(self.items) < MAX_PROBLEMS:
                self.items.append(problem)
            else:
                self.not_shown += 1
                if self.not_shown == 1:
                    self._first_not_shown = problem.split(": ", 1)[0]

    def check_keys(self, file: pathlib.Path, mapping: YMap, allowed: Iterable[str], what: str) -> None:
        allowed = sorted(allowed)
        for key in mapping:
            if key not in allowed:
                if len(self.items) >= MAX_PROBLEMS:  # counted only: spare the suggestion
                    self.add(file, mapping.key_lines.get(key), "")
                    continue
                self.add(file, mapping.key_lines.get(key), unknown_key_message(key, allowed, what))

    def expect_map(self, file: pathlib.Path, value: Any, line: int | None, what: str) -> YMap | None:
        if not isinstance(value, YMap):
            self.add(file, getattr(value, "line", line), f"{what} must be a mapping, got {kind(value)} — write "
                                                         f"it as indented 'key: value' lines")
            return None
        return value

    def already_reported(self, qualified: str) -> bool:
        """The instance failed to build, or its module's include failed: said once already."""
        return qualified in self.failed_instances or qualified.split(".", 1)[0] in self.failed_modules

    def error(self) -> TopologyError:
        """The problems so far as one error (the ones past MAX_PROBLEMS summarised)."""
        if self.not_shown:
            return TopologyError(self.items + [f"{self._first_not_shown}: {self.not_shown} more problem(s) not "
                                               f"shown — fix the ones above first"])
        return TopologyError(self.items)

    def raise_if_any(self) -> None:
        if len(self):
            raise self.error()


def _key(key: Any) -> str:
    return f"'{key}'" if isinstance(key, str) else repr(key)


def unknown_key_message(key: Any, allowed: Iterable[str], what: str) -> str:
    """``unknown key 'x' in WHAT — did you mean 'y'?`` (else the allowed keys): the message of a key
    that a mapping of the topology or of a campaign file may not have."""
    allowed = sorted(allowed)
    hint = did_you_mean(key, allowed, "allowed keys: " + ", ".join(allowed))
    return f"unknown key {_key(key)} in {what} — {hint}"
