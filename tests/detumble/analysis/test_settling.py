"""Settling metrics against closed forms and MATLAB lsiminfo's definitions."""
import math

import numpy as np
import pytest

from detumble.analysis.settling import settling_time, settling_times_per_axis, time_below, transient_time


def test_exponential_decay_settles_at_the_closed_form():
    """SET-001: y = e^(−t/τ) from 1 to 0 enters the 2 % band of |y_final − y_init| = 1 at τ ln 50
    (within one sample of 1 ms)."""
    t = np.arange(0.0, 20.0, 1e-3)
    y = np.exp(-t / 2.0)
    assert settling_time(t, y, y_final=0.0, y_init=1.0) == pytest.approx(2.0 * math.log(50.0), abs=1e-3)


def test_band_is_relative_to_the_step_not_to_the_final_value():
    """SET-002: for ω_y going 2 → −n (the report's y channel), the band is 2 % of |−n − 2|."""
    n = 1.077e-3
    t = np.linspace(0.0, 100.0, 100001)
    y = -n + (2.0 + n) * np.exp(-t / 10.0)
    expected = 10.0 * math.log(1.0 / 0.02)
    assert settling_time(t, y, y_final=-n, y_init=2.0) == pytest.approx(expected, abs=1e-3)


def test_an_oscillation_counts_its_last_excursion_and_a_never_settling_series_is_none():
    """SET-003: a decaying oscillation settles after its last excursion outside the band, not its
    first entry; a series still outside the band at its end gives None."""
    t = np.linspace(0.0, 50.0, 50001)
    y = np.exp(-t / 5.0) * np.cos(2.0 * t)
    st = settling_time(t, y, y_final=0.0, y_init=1.0)
    outside = np.abs(y) > 0.02
    assert st == pytest.approx(t[np.flatnonzero(outside)[-1] + 1])
    assert st > 5.0 * math.log(50.0) - 2.0  # close to, never before, the envelope's crossing
    assert settling_time(t, np.ones_like(t), y_final=0.0, y_init=1.0) is None


def test_default_final_value_is_the_last_sample_and_moves_with_the_horizon():
    """SET-004: with y_final omitted the last sample is used (lsiminfo's default), so a slowly
    drifting signal has a horizon-dependent settling time."""
    t = np.linspace(0.0, 100.0, 10001)
    y = 1.0 - t / 100.0 * 0.5
    short, long_ = settling_time(t[:5001], y[:5001], y_init=0.0), settling_time(t, y, y_init=0.0)
    assert short != long_


def test_transient_time_uses_the_peak_error():
    """SET-005: TransientTime's band is 2 % of max|y − y_final|: for e^(−t/τ) scaled by 3 it is
    still τ ln 50."""
    t = np.arange(0.0, 20.0, 1e-3)
    assert transient_time(t, 3.0 * np.exp(-t / 2.0), y_final=0.0) == pytest.approx(2.0 * math.log(50.0), abs=1e-3)


def test_overall_is_the_largest_axis_and_time_below_is_horizon_free():
    """SET-006: the overall settling time is the largest per-axis one (None if any axis never
    settles); time_below gives the first time after which |ω| stays below a threshold."""
    t = np.linspace(0.0, 10.0, 10001)
    each, overall = settling_times_per_axis(t, [np.exp(-t), np.exp(-t / 2)], [0.0, 0.0], [1.0, 1.0])
    assert overall == max(each) == pytest.approx(2.0 * math.log(50.0), abs=1e-3)
    _, never = settling_times_per_axis(t, [np.exp(-t), np.ones_like(t)], [0.0, 0.0], [1.0, 1.0])
    assert never is None
    mag = np.where(t < 3.0, 2.0, 0.5)
    mag[5000] = 1.5
    assert time_below(t, mag, 1.0) == pytest.approx(t[5001])
    assert time_below(t, np.full_like(t, 2.0), 1.0) is None


def test_on_line_trackers_agree_with_the_batch_functions_sample_for_sample():
    """SET-007: SettlingTracker and BelowTracker give, after every sample, exactly what the batch
    functions give for the series so far (random walks in and out of the band)."""
    from detumble.analysis.settling import BelowTracker, SettlingTracker

    rng = np.random.default_rng(7)
    t = np.arange(0.0, 300.0, 1.0)
    y = np.cumsum(rng.normal(0.0, 0.01, t.size)) + 0.05
    tracker, below = SettlingTracker(0.0, 1.0), BelowTracker(0.03)
    for k in range(t.size):
        tracker.update(t[k], y[k])
        below.update(t[k], abs(y[k]))
        assert tracker.time == settling_time(t[: k + 1], y[: k + 1], y_final=0.0, y_init=1.0)
        assert below.time == time_below(t[: k + 1], np.abs(y[: k + 1]), 0.03)
