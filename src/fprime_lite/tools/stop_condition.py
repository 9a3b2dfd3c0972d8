"""Conditions that end a run early: ``KEY OP VALUE`` over the values a run's reports publish.

A report resource's ``progress()`` (the figures the progress bar shows) is the vocabulary: the
detumble report publishes ``rate_deg_s``, the attitude report ``mode`` and ``spin_settled_for_s``,
and so on. ``fprime-lite run --stop-when 'spin_settled_for_s >= 300'`` or a campaign's
``stop_when: [...]`` ends the run at the first check (once per simulated second) at which every
condition of the list holds. ``OP`` is one of ``>= <= > < == !=``; ``VALUE`` a number, or a word
compared as text (``mode == POINTING``). A key no report publishes (yet) does not hold.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["StopCondition", "parse_stop_condition", "StopConditionError", "CHECK_INTERVAL_S", "holds_all"]

#: Simulated seconds between two evaluations of the conditions.
CHECK_INTERVAL_S = 1.0

_OPS = {">=": lambda a, b: a >= b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
        "<": lambda a, b: a < b, "==": lambda a, b: a == b, "!=": lambda a, b: a != b}
_FORM = re.compile(r"^\s*([A-Za-z_]\w*)\s*(>=|<=|==|!=|>|<)\s*([^\s<>=!]\S*)\s*$")


class StopConditionError(FprimeLiteError, ValueError):
    """A condition that cannot be read; the message says what to write."""


@dataclass(frozen=True)
class StopCondition:
    """``key op value``; ``value`` a float, or a str for ``==`` / ``!=`` against a word."""

    key: str
    op: str
    value: float | str
    text: str

    def holds(self, values: dict) -> bool:
        if self.key not in values:
            return False
        got = values[self.key]
        if isinstance(self.value, str):
            name = getattr(got, "name", got)
            return _OPS[self.op](str(name), self.value)
        if isinstance(got, bool) or not isinstance(got, (int, float)) or not math.isfinite(got):
            return False
        return _OPS[self.op](float(got), self.value)


def parse_stop_condition(text: object) -> StopCondition:
    """``'KEY OP VALUE'`` → :class:`StopCondition`; :class:`StopConditionError` saying why not."""
    example = "e.g. 'spin_settled_for_s >= 300' or 'mode == POINTING'"
    if not isinstance(text, str):
        raise StopConditionError(f"a stop condition is text KEY OP VALUE, got {type(text).__name__} — {example}")
    m = _FORM.match(text)
    if m is None:
        raise StopConditionError(f"{text!r} is not KEY OP VALUE with OP one of {' '.join(_OPS)} — {example}")
    key, op, raw = m.groups()
    try:
        value: float | str = float(raw)
    except ValueError:
        if not re.fullmatch(r"[A-Za-z_]\w*", raw):
            raise StopConditionError(f"{text!r}: the value is a number or a word — {example}") from None
        if op not in ("==", "!="):
            raise StopConditionError(f"{text!r}: a word compares only with == or != — {example}") from None
        value = raw
    if isinstance(value, float) and not math.isfinite(value):
        raise StopConditionError(f"{text!r}: the value must be finite — {example}")
    return StopCondition(key, op, value, f"{key} {op} {raw}")


def holds_all(conditions, values: dict) -> bool:
    """True when ``conditions`` is not empty and every one holds on ``values``."""
    return bool(conditions) and all(c.holds(values) for c in conditions)
