"""Epoch handling: UTC calendar epoch -> Julian date, decimal year, Earth rotation angle.

UTC is used as UT1 (|UT1 - UTC| < 0.9 s, a 0.004 deg error in Earth angle).
"""

from __future__ import annotations

import datetime as _dt
import math

_J2000_JD = 2451545.0


def parse_epoch(value) -> _dt.datetime:
    """Accept an ISO-8601 string (``2025-06-01T00:00:00Z``) or a ``datetime``; return aware UTC."""
    if isinstance(value, _dt.datetime):
        d = value
    elif isinstance(value, _dt.date):
        d = _dt.datetime(value.year, value.month, value.day)
    elif isinstance(value, str):
        text = value.strip()
        if text.endswith("Z") or text.endswith("z"):
            text = text[:-1] + "+00:00"
        d = _dt.datetime.fromisoformat(text)
    else:
        raise ValueError(f"expected an ISO-8601 UTC time such as '2025-06-01T00:00:00Z', got {value!r}")
    if d.tzinfo is None:
        d = d.replace(tzinfo=_dt.timezone.utc)
    return d.astimezone(_dt.timezone.utc)


def julian_date(epoch: _dt.datetime) -> float:
    """Julian date (UTC) of an aware datetime."""
    j2000 = _dt.datetime(2000, 1, 1, 12, tzinfo=_dt.timezone.utc)
    return _J2000_JD + (epoch - j2000).total_seconds() / 86400.0


def gmst_rad(jd_ut1: float) -> float:
    """Greenwich mean sidereal time (IAU 1982), radians in [0, 2 pi)."""
    d = jd_ut1 - _J2000_JD
    t = d / 36525.0
    deg = 280.46061837 + 360.98564736629 * d + 0.000387933 * t * t - t**3 / 38710000.0
    return math.radians(deg % 360.0)


def decimal_year(epoch: _dt.datetime, t: float = 0.0) -> float:
    """Decimal year of ``epoch + t`` seconds (as used by the WMM)."""
    d = epoch + _dt.timedelta(seconds=t)
    start = _dt.datetime(d.year, 1, 1, tzinfo=_dt.timezone.utc)
    end = _dt.datetime(d.year + 1, 1, 1, tzinfo=_dt.timezone.utc)
    return d.year + (d - start).total_seconds() / (end - start).total_seconds()
