"""Framework data types that ports and parameters share across components (F´'s ``Fw`` module).

Defined once here so that every component uses the same types and a dictionary never holds two
definitions of ``Fw.Success`` or ``Fw.TimeIntervalValue``.
"""

from __future__ import annotations

from fprime_lite.model.types import U8, U32, FwEnum, Struct

__all__ = ["Success", "TimeIntervalValue", "On"]


class Success(FwEnum, namespace="Fw", rep=U8):
    """F´ ``Fw.Success``: the outcome of an operation."""

    SUCCESS = 0
    FAILURE = 1


class TimeIntervalValue(Struct, namespace="Fw"):
    """F´ ``Fw.TimeIntervalValue``: a duration of ``seconds`` s plus ``useconds`` µs."""

    seconds: U32
    useconds: U32

    @property
    def total_us(self) -> int:
        """The duration in microseconds."""
        return self.seconds * 1_000_000 + self.useconds

    @classmethod
    def from_us(cls, microseconds: int) -> "TimeIntervalValue":
        """The interval of ``microseconds`` µs (must be ≥ 0), normalised (``useconds < 1e6``)."""
        if microseconds < 0:
            raise ValueError(f"a time interval cannot be negative: {microseconds} us")
        return cls(seconds=microseconds // 1_000_000, useconds=microseconds % 1_000_000)


class On(FwEnum, namespace="Fw"):
    """F´ ``Fw.On``: a switch state."""

    OFF = 0
    ON = 1
