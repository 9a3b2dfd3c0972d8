"""The attitude run report's statistics (summary.json figures; angles deg, times s)."""

from types import SimpleNamespace

import pytest

from detumble.components.attitude_types import ControlMode
from detumble.reports.attitude_report import AttitudeRunReport, error_statistics, settle_time


def test_error_statistics_drop_the_first_tenth():
    """ADCS-042: median/p95/max over the samples after the first 10 % (linear-interpolated percentiles)."""
    values = [100.0] * 10 + [float(v) for v in range(1, 91)]  # the first 10 of 100 are dropped
    s = error_statistics(values)
    assert s["samples"] == 90 and s["max"] == 90.0
    assert s["median"] == pytest.approx(45.5) and s["p95"] == pytest.approx(85.55)
    assert error_statistics([]) is None


def test_settle_time_is_after_the_last_excursion():
    """ADCS-042: the time from start to the first sample after the last bad one; None when it ends bad."""
    t = [0.0, 1.0, 2.0, 3.0, 4.0]
    assert settle_time(t, [False, True, False, True, True], 0.0) == 3.0
    assert settle_time(t, [True] * 5, 1.0) == 0.0
    assert settle_time(t, [True, True, True, True, False], 0.0) is None


def test_spin_settled_counts_from_the_first_spin_stable_sample():
    """ADCS-042: spin_settled_s starts at the first SPIN_STABLE sample (an IDLE sample at the same time does not
    end the interval) and needs momentum within 5° and the rate within 5 % of SPIN_RATE_TARGET."""
    rep = AttitudeRunReport(SimpleNamespace(), controller="c")
    rep.controller = SimpleNamespace(SPIN_RATE_TARGET=SimpleNamespace(value=1.5))
    pad = (0.0,) * 10
    rep.rows = [(0.0, int(ControlMode.IDLE), 0.0, 90.0, 0.0, 0.0, *pad),
                (0.0, int(ControlMode.SPIN_STABLE), 0.0, 40.0, 0.5, 0.0, *pad),
                (10.0, int(ControlMode.SPIN_STABLE), 0.0, 4.0, 1.40, 0.0, *pad),  # rate 6.7 % off
                (20.0, int(ControlMode.SPIN_STABLE), 0.0, 4.0, 1.46, 0.0, *pad),
                (30.0, int(ControlMode.SPIN_STABLE), 0.0, 1.0, 1.50, 0.0, *pad),
                (40.0, int(ControlMode.POINTING), 0.0, 50.0, 0.0, 0.0, *pad)]
    assert rep.spin_settled_s() == 20.0
    assert rep._spin_settling() == (20.0, 10.0)  # settled at 20 s, in the band until the last SPIN_STABLE sample
