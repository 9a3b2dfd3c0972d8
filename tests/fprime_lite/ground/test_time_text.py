"""The ground's time text without ``strftime`` per stamp is ``strftime``'s (issue 32).

TIMETEXT-001: random stamps over the whole U32 range of seconds, day and year boundaries and every
time base give what the ground wrote before (``datetime.fromtimestamp(...).strftime(...)`` for
workstation time, ``seconds.useconds`` otherwise); TIMETEXT-002: ``format_time`` of a ``Time``.
"""

import datetime as dt
import random

import pytest

from fprime_lite.ground.downlink import format_time
from fprime_lite.ground.time_text import time_text
from fprime_lite.model.time import Time, TimeBase


def _reference(time_base: int, seconds: int, useconds: int) -> str:
    if time_base == TimeBase.TB_WORKSTATION_TIME:
        stamp = dt.datetime.fromtimestamp(seconds, dt.timezone.utc).replace(microsecond=useconds)
        return stamp.strftime("%Y-%m-%dT%H:%M:%S.%fZ")
    return f"{seconds}.{useconds:06d}"


def _stamps():
    rng = random.Random(32)
    edges = [0, 59, 60, 3_599, 3_600, 86_399, 86_400, 951_782_399, 951_868_800, 1_748_736_000, 2**31 - 1, 2**32 - 1]
    for seconds in edges + [rng.randrange(2**32) for _ in range(3000)]:
        for useconds in (0, 999_999, rng.randrange(1_000_000)):
            yield rng.choice([0, 1, 2, 0xFFFF, 7]), seconds, useconds
            yield 2, seconds, useconds


def test_time_text_is_strftime():
    """TIMETEXT-001."""
    for time_base, seconds, useconds in _stamps():
        assert time_text(time_base, seconds, useconds) == _reference(time_base, seconds, useconds)


@pytest.mark.parametrize("base", list(TimeBase))
def test_format_time_of_a_time(base):
    """TIMETEXT-002."""
    t = Time(base, 3, 1_748_736_013, 250_000)
    assert format_time(t) == _reference(int(base), 1_748_736_013, 250_000)
