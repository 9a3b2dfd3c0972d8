"""The detumble report's time in each manager state (truth.csv's frac_* columns, the progress line):
crediting a span only when the state changes or the shares are read gives, to the microsecond, what
crediting every event does (issue 32)."""

import random
from types import SimpleNamespace

from detumble.components.types import DetumbleState
from detumble.reports.detumble_report import DetumbleRunReport


def _report(start_us: int):
    """A report past ``begin()`` as far as the state bookkeeping goes (no spacecraft needed)."""
    report = DetumbleRunReport.__new__(DetumbleRunReport)
    report.manager = SimpleNamespace(state=DetumbleState.COOLDOWN)
    report._state_us = dict.fromkeys(DetumbleState, 0)
    report._progress_us = dict.fromkeys(DetumbleState, 0)
    report._state_since = report._last_us = start_us
    report._state = None
    return report


def test_state_time_matches_crediting_every_event():
    rng = random.Random(7)
    states = list(DetumbleState)
    report = _report(1_000)
    expected = dict.fromkeys(DetumbleState, 0)  # the reference: each event credits its span to the state now
    progress = dict.fromkeys(DetumbleState, 0)
    previous = 1_000
    t = 1_000
    for step in range(5_000):
        t += rng.choice((0, 1_000, 20_000, 20_000, 20_000, 333))
        if rng.random() < 0.05:
            report.manager.state = rng.choice(states)
        report._on_time(t)
        expected[report.manager.state] += t - previous
        progress[report.manager.state] += t - previous
        previous = t
        if step % 700 == 699:  # a truth sample reads and resets its count
            assert report.take_state_us() == expected
            expected = dict.fromkeys(DetumbleState, 0)
        if step % 1_100 == 1_099:  # a progress read
            total = sum(progress.values())
            assert report.state_shares() == {st.name: us / total for st, us in progress.items()}
            progress = dict.fromkeys(DetumbleState, 0)
    assert report.take_state_us() == expected
