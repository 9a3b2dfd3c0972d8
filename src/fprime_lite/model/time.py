"""F´ time values, time intervals and the clocks that produce them.

A :class:`Time` is F´'s ``Fw::Time``: ``{time_base U16, context U8, seconds U32, useconds U32}``,
serialized in that order (11 bytes). Times of the same base compare and subtract; times of
different bases are incomparable (F´'s ``INCOMPARABLE``), which here raises ``ValueError`` unless one
side is ``TB_DONT_CARE``.

A :class:`TimeInterval` is a non-negative duration ``{seconds, useconds}``.

Clocks hold the one simulated time of a deployment as an integer number of **microseconds**; the
scheduler advances it and every event and channel is stamped from it.
"""

from __future__ import annotations

import operator
import struct
import time as _wall
from typing import Any

from fprime_lite.model.errors import SerializationError
from fprime_lite.model.types import _U8, _U16, _U32, FwEnum, FwType, _short

__all__ = ["TimeBase", "Time", "TimeInterval", "TIME", "Clock", "SimulatedClock", "WallClock",
           "US_PER_S"]

US_PER_S = 1_000_000


class TimeBase(FwEnum, rep=_U16):
    """F´ time bases (``TimeBase`` enum of the framework)."""

    TB_NONE = 0
    TB_PROC_TIME = 1
    TB_WORKSTATION_TIME = 2
    TB_DONT_CARE = 0xFFFF


class Time:
    """An F´ time stamp; ``seconds`` and ``useconds`` are normalised (``useconds < 1e6``).

    Treat a Time as immutable: the clock hands the same object to every caller at one instant.
    ``total_us`` (µs since the base's epoch) is a plain attribute because every event and channel
    reads it.

    Arithmetic: ``Time + TimeInterval -> Time``, ``Time - Time -> TimeInterval`` (the later time must
    be on the left), ``Time - TimeInterval -> Time``.
    """

    __slots__ = ("time_base", "context", "total_us")  # total_us: µs since the base's epoch

    def __init__(self, time_base: int = TimeBase.TB_NONE, context: int = 0,
                 seconds: int = 0, useconds: int = 0):
        if seconds < 0 or useconds < 0:
            raise ValueError(f"time cannot be negative: {seconds} s {useconds} us")
        self.time_base = time_base
        self.context = context
        self.total_us = seconds * US_PER_S + useconds

    @classmethod
    def from_us(cls, microseconds: int, time_base: int = TimeBase.TB_WORKSTATION_TIME,
                context: int = 0) -> "Time":
        """The time ``microseconds`` after the base's epoch."""
        if microseconds < 0:
            raise ValueError(f"time cannot be negative: {microseconds} us")
        t = cls.__new__(cls)
        t.time_base = time_base
        t.context = context
        t.total_us = microseconds
        return t

    @property
    def seconds(self) -> int:
        return self.total_us // US_PER_S

    @property
    def useconds(self) -> int:
        return self.total_us % US_PER_S

    def to_float(self) -> float:
        """Seconds since the base's epoch, as a float."""
        return self.total_us / US_PER_S

    def _comparable(self, other: "Time") -> None:
        a, b = self.time_base, other.time_base
        if a != b and TimeBase.TB_DONT_CARE not in (a, b):
            known = TimeBase._value2member_map_
            raise ValueError(
                f"cannot compare times of different bases ({TimeBase(a).name if a in known else a}"
                f" and {TimeBase(b).name if b in known else b})")

    def __eq__(self, other):
        if not isinstance(other, Time):
            return NotImplemented
        return (self.time_base, self.context, self.total_us) == (other.time_base, other.context, other.total_us)

    def __hash__(self):
        return hash((self.time_base, self.context, self.total_us))

    def __lt__(self, other):
        if not isinstance(other, Time):
            return NotImplemented
        self._comparable(other)
        return self.total_us < other.total_us

    def __le__(self, other):
        if not isinstance(other, Time):
            return NotImplemented
        self._comparable(other)
        return self.total_us <= other.total_us

    def __gt__(self, other):
        if not isinstance(other, Time):
            return NotImplemented
        self._comparable(other)
        return self.total_us > other.total_us

    def __ge__(self, other):
        if not isinstance(other, Time):
            return NotImplemented
        self._comparable(other)
        return self.total_us >= other.total_us

    def __add__(self, other):
        if isinstance(other, TimeInterval):
            return Time.from_us(self.total_us + other._us, self.time_base, self.context)
        return NotImplemented

    def __sub__(self, other):
        if isinstance(other, TimeInterval):
            if other._us > self.total_us:
                raise ValueError(f"{self} minus {other} would be before the epoch")
            return Time.from_us(self.total_us - other._us, self.time_base, self.context)
        if isinstance(other, Time):
            self._comparable(other)
            if other.total_us > self.total_us:
                raise ValueError(f"{other} is later than {self}; subtract the earlier time")
            return TimeInterval.from_us(self.total_us - other.total_us)
        return NotImplemented

    def __repr__(self):
        base = self.time_base
        base_name = TimeBase(base).name if base in TimeBase._value2member_map_ else str(base)
        return f"Time({base_name}, {self.context}, {self.seconds}, {self.useconds})"

    def __str__(self):
        return f"{self.seconds}.{self.useconds:06d}"


class TimeInterval:
    """A non-negative duration: ``{seconds U32, useconds U32}``, normalised."""

    __slots__ = ("_us",)

    def __init__(self, seconds: int = 0, useconds: int = 0):
        us = seconds * US_PER_S + useconds
        if us < 0:
            raise ValueError(f"a time interval cannot be negative: {seconds} s {useconds} us")
        self._us = us

    @classmethod
    def from_us(cls, microseconds: int) -> "TimeInterval":
        if microseconds < 0:
            raise ValueError(f"a time interval cannot be negative: {microseconds} us")
        t = cls.__new__(cls)
        t._us = microseconds
        return t

    @property
    def seconds(self) -> int:
        return self._us // US_PER_S

    @property
    def useconds(self) -> int:
        return self._us % US_PER_S

    @property
    def total_us(self) -> int:
        return self._us

    def to_float(self) -> float:
        return self._us / US_PER_S

    def __eq__(self, other):
        return isinstance(other, TimeInterval) and self._us == other._us

    def __hash__(self):
        return hash(self._us)

    def __lt__(self, other):
        if not isinstance(other, TimeInterval):
            return NotImplemented
        return self._us < other._us

    def __le__(self, other):
        if not isinstance(other, TimeInterval):
            return NotImplemented
        return self._us <= other._us

    def __gt__(self, other):
        if not isinstance(other, TimeInterval):
            return NotImplemented
        return self._us > other._us

    def __ge__(self, other):
        if not isinstance(other, TimeInterval):
            return NotImplemented
        return self._us >= other._us

    def __add__(self, other):
        if isinstance(other, TimeInterval):
            return TimeInterval.from_us(self._us + other._us)
        return NotImplemented

    def __repr__(self):
        return f"TimeInterval({self.seconds}, {self.useconds})"


_TIME_STRUCT = struct.Struct(">HBII")
_PACK_TIME = _TIME_STRUCT.pack


class TimeType(FwType):
    """The F´ serialization of :class:`Time`: U16 base, U8 context, U32 seconds, U32 useconds."""

    kind = "time"
    name = "Fw.Time"
    size = _TIME_STRUCT.size

    def check(self, value):
        if not isinstance(value, Time):
            raise SerializationError(f"Fw.Time expects a Time, got {value!r}")
        _U16.check(int(value.time_base))
        _U8.check(value.context)
        _U32.check(value.seconds)
        return value

    def serialize(self, value):
        if type(value) is Time:
            us = value.total_us
            try:
                return _PACK_TIME(value.time_base, value.context, us // US_PER_S, us % US_PER_S)
            except struct.error:
                pass  # out of range: let check() say which field
        value = self.check(value)
        return _TIME_STRUCT.pack(int(value.time_base), value.context, value.seconds, value.useconds)

    def deserialize(self, data, offset=0):
        end = offset + self.size
        if end > len(data):
            raise _short(data, offset, self.size, "Fw.Time")
        base, context, seconds, useconds = _TIME_STRUCT.unpack_from(data, offset)
        if useconds >= US_PER_S:
            raise SerializationError(f"cannot deserialize Fw.Time: useconds {useconds} ≥ 1000000")
        return Time(base, context, seconds, useconds), end

    @property
    def default(self):
        return Time()

    def json_ref(self):
        return {"name": "Fw.TimeValue", "kind": "qualifiedIdentifier"}

    def json_value(self, value):
        """A time as the ``Fw.TimeValue`` struct value the dictionary uses for defaults."""
        value = self.check(value)
        base = int(value.time_base)
        base_name = TimeBase(base).name if base in TimeBase._value2member_map_ else str(base)
        return {"timeBase": f"TimeBase.{base_name}", "timeContext": value.context,
                "seconds": value.seconds, "useconds": value.useconds}


TIME = TimeType()
setattr(Time, "__fprime_type__", TIME)


class Clock:
    """The one time source of a deployment: integer microseconds since its epoch.

    ``now()`` gives the current :class:`Time` in the clock's base and context.
    """

    def __init__(self, time_base: int = TimeBase.TB_WORKSTATION_TIME, context: int = 0,
                 epoch_us: int = 0):
        self.time_base = time_base
        self.context = context
        self.epoch_us = epoch_us

    def now_us(self) -> int:
        raise NotImplementedError

    def now(self) -> Time:
        return Time.from_us(self.epoch_us + self.now_us(), self.time_base, self.context)


def _config_property(slot: str, doc: str) -> Any:
    """A clock setting kept in ``slot``: read as a plain attribute, and setting it tells the
    clock (``_config_changed``) that the times it made before no longer hold."""
    def set_value(clock: Any, value: int) -> None:
        setattr(clock, slot, value)
        clock._config_changed()
    return property(operator.attrgetter(slot), set_value, doc=doc)


class SimulatedClock(Clock):
    """A clock that only moves when told to (the scheduler's, and the test harness's).

    ``now()`` hands every caller at one instant the same :class:`Time`, made once per instant:
    it is valid while ``current_us`` is the reading it was made at and ``epoch_us``,
    ``time_base`` and ``context`` keep their values (setting any of them, e.g. an RTC set that
    moves the epoch, makes the next ``now()`` build a new one and bumps :attr:`generation`).
    """

    _epoch_us: int
    _time_base: int
    _context: int

    def __init__(self, time_base: int = TimeBase.TB_WORKSTATION_TIME, context: int = 0,
                 epoch_us: int = 0, start_us: int = 0):
        self._now: Time | None = None
        self._now_at: int | None = None  # the current_us _now was made at; None: make a new one
        #: Bumped whenever ``epoch_us``, ``time_base`` or ``context`` is set: a cache of times made
        #: from this clock (the simulated spacecraft's) keys on it.
        self.generation = 0
        super().__init__(time_base, context, epoch_us)
        self.current_us = start_us

    def _config_changed(self) -> None:
        self._now_at = None
        self.generation += 1

    epoch_us = _config_property("_epoch_us", "µs of the time base's epoch at clock reading 0.")
    time_base = _config_property("_time_base", "The base of the times this clock gives.")
    context = _config_property("_context", "The context of the times this clock gives.")

    def now_us(self) -> int:
        return self.current_us

    def now(self) -> Time:
        if self._now_at == self.current_us:  # Time is immutable: every caller at this instant shares it
            return self._now  # type: ignore[return-value]
        current = self.current_us
        t = Time.__new__(Time)
        t.time_base = self._time_base
        t.context = self._context
        t.total_us = self._epoch_us + current
        self._now = t
        self._now_at = current
        return t

    def set_us(self, microseconds: int) -> None:
        if microseconds < self.current_us:
            raise ValueError(f"simulated time cannot go backwards ({microseconds} < {self.current_us} us)")
        self.current_us = microseconds

    def advance_us(self, microseconds: int) -> None:
        if microseconds < 0:
            raise ValueError(f"cannot advance time by a negative amount ({microseconds} us)")
        self.current_us += microseconds


class _NoClockReading:
    """Stands in for "the time port does not call a :class:`SimulatedClock`'s own ``now``": its
    ``_now_at`` never equals its ``current_us``, so a reader that tests for the clock's made Time of
    the present instant always makes the port call instead."""

    _now_at = None
    current_us = -1
    _now = None


#: The stand-in of :func:`simulated_clock_of` for a call that is not a SimulatedClock's ``now``.
NO_CLOCK_READING = _NoClockReading()


def simulated_clock_of(call: Any) -> SimulatedClock | _NoClockReading:
    """The :class:`SimulatedClock` whose own :meth:`SimulatedClock.now` ``call`` is (a bound method,
    e.g. a :class:`~fprime_lite.svc.time_source.TimeSource` connection), else :data:`NO_CLOCK_READING`.

    A reader that has the clock can take ``clock._now`` while ``clock._now_at == clock.current_us``:
    exactly what ``call()`` would return then, without the call.
    """
    clock = getattr(call, "__self__", None)
    if getattr(call, "__func__", None) is SimulatedClock.now and isinstance(clock, SimulatedClock):
        return clock
    return NO_CLOCK_READING


class WallClock(Clock):
    """Microseconds of the host's monotonic clock since the clock was made."""

    def __init__(self, time_base: int = TimeBase.TB_WORKSTATION_TIME, context: int = 0,
                 epoch_us: int = 0):
        super().__init__(time_base, context, epoch_us)
        self._start_ns = _wall.monotonic_ns()

    def now_us(self) -> int:
        return (_wall.monotonic_ns() - self._start_ns) // 1000
