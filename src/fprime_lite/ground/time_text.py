"""The ground's text of an F´ time stamp (``events.log``, ``channels.csv``'s JSON of a ``Time`` member).

UTC ISO 8601 with microseconds for workstation (Unix) time, ``seconds.useconds`` for any other base:
what ``datetime.fromtimestamp(seconds, utc).replace(microsecond=useconds).strftime(
"%Y-%m-%dT%H:%M:%S.%fZ")`` writes, without a ``datetime`` and a ``strftime`` per stamp (issue 32: they
were a few percent of the recorder). Unix time has no leap seconds, so a day is 86 400 s and the
time of day follows from ``seconds % 86400``; the date of each day is formatted once by ``strftime``.
"""

from __future__ import annotations

import datetime as _dt

from fprime_lite.model.time import TimeBase

__all__ = ["time_text"]

_WORKSTATION = int(TimeBase.TB_WORKSTATION_TIME)
_UTC = _dt.timezone.utc
#: day number since the Unix epoch → its date ``YYYY-MM-DD`` (at most ``_DATES_MAX`` kept)
_dates: dict[int, str] = {}
_DATES_MAX = 1024


def time_text(time_base: int, seconds: int, useconds: int) -> str:
    """The text of the time stamp ``(time_base, seconds, useconds)``; ``useconds`` < 10⁶ and
    ``seconds`` ≥ 0 (what ``Fw.Time``'s deserializer accepts)."""
    if time_base == _WORKSTATION:
        day, second_of_day = divmod(seconds, 86_400)
        date = _dates.get(day)
        if date is None:
            date = _dt.datetime.fromtimestamp(day * 86_400, _UTC).strftime("%Y-%m-%d")
            if len(_dates) >= _DATES_MAX:
                _dates.clear()
            _dates[day] = date
        hour, second_of_hour = divmod(second_of_day, 3_600)
        minute, second = divmod(second_of_hour, 60)
        return f"{date}T{hour:02d}:{minute:02d}:{second:02d}.{useconds:06d}Z"
    return f"{seconds}.{useconds:06d}"
