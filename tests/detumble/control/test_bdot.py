"""BDot helper: 5-sample window, 5-point central difference, m = −GAIN·Ḃ (detumble.md §6).

Units: B in gauss, timestamps in µs, Ḃ in G/s, dipole in A·m².
"""

import math

import pytest

from detumble.control.bdot import BDot

US = 1


def filled(samples, times_us, gain=3.0, period_us=10_000):
    b = BDot()
    b.configure(gain, period_us)
    for s, t in zip(samples, times_us, strict=True):
        b.add_sample(s, t)
    return b


def test_linear_field_gives_its_slope_and_a_damping_dipole():
    """B-Dot Strategy: for B(t) = B0 + k·t the 5-point stencil returns exactly k, and m = −GAIN·k."""
    k = (0.02, -0.05, 0.1)  # G/s
    times = [1_000_000 + 20_000 * i for i in range(5)]
    samples = [tuple(0.3 + k[a] * (t - times[0]) / 1e6 for a in range(3)) for t in times]
    b = filled(samples, times, gain=3.0)
    assert b.compute_bdot() == pytest.approx(k, rel=1e-9)
    assert b.get_magnetic_moment() == pytest.approx(tuple(-3.0 * v for v in k), rel=1e-9)


def test_stencil_weights_by_hand_and_middle_sample_unused():
    """B-Dot Strategy: Ḃ = (B0 − 8B1 + 8B3 − B4)/(12Δt): with B = (0, 0, X, 1, 0) on x and
    Δt = 0.02 s, Ḃx = 8/(12·0.02) = 33.33 G/s whatever the middle sample X."""
    times = [0, 20_000, 40_000, 60_000, 80_000]
    for middle in (0.0, 123.0):
        samples = [(0.0, 0, 0), (0.0, 0, 0), (middle, 0, 0), (1.0, 0, 0), (0.0, 0, 0)]
        b = filled(samples, times, gain=1.0)
        assert b.compute_bdot()[0] == pytest.approx(8 / (12 * 0.02))
        assert b.get_magnetic_moment()[0] == pytest.approx(-8 / (12 * 0.02))


def test_dt_is_mean_timestamp_spacing_not_the_magnetometer_period():
    """DEVIATION (§6): Δt = (t4 − t0)/4 from the timestamps (20 ms at 50 Hz), not the 10 ms
    magnetometer period the flight code uses (which would double Ḃ)."""
    times = [0, 20_000, 40_000, 60_000, 80_000]
    samples = [(0.01 * i, 0.0, 0.0) for i in range(5)]  # 0.01 G per 20 ms = 0.5 G/s
    b = filled(samples, times, gain=1.0, period_us=10_000)
    assert b.sample_spacing_s() == pytest.approx(0.02)
    assert b.compute_bdot()[0] == pytest.approx(0.5)


def test_uneven_spacing_uses_the_mean():
    """B-Dot Strategy: Δt is the mean spacing (t4 − t0)/4 even when reads jitter."""
    b = filled([(0, 0, 0)] * 5, [0, 19_000, 41_000, 60_000, 100_000])
    assert b.sample_spacing_s() == pytest.approx(0.025)


def test_non_increasing_timestamps_fall_back_to_the_period_then_zero():
    """B-Dot Strategy: repeated timestamps → configured period; no positive period → zero dipole."""
    samples = [(0.01 * i, 0.0, 0.0) for i in range(5)]
    b = filled(samples, [5] * 5, gain=1.0, period_us=10_000)
    assert b.sample_spacing_s() == pytest.approx(0.01)
    assert b.compute_bdot()[0] == pytest.approx(0.01 * (-8 + 24 - 4) / (12 * 0.01))
    b0 = filled(samples, [5] * 5, gain=1.0, period_us=0)
    assert b0.get_magnetic_moment() == (0.0, 0.0, 0.0)
    backwards = filled(samples, [80_000, 60_000, 40_000, 20_000, 0], gain=1.0, period_us=0)
    assert backwards.get_magnetic_moment() == (0.0, 0.0, 0.0)


def test_window_holds_five_and_ignores_extra_samples():
    """B-Dot Strategy: the window takes five samples; a sixth is ignored; empty resets it."""
    b = BDot()
    for i in range(4):
        assert b.add_sample((1.0, 2.0, 3.0), i * 20_000)
        assert not b.sampling_complete()
    assert b.add_sample((1.0, 2.0, 3.0), 80_000)
    assert b.sampling_complete()
    assert not b.add_sample((9.0, 9.0, 9.0), 100_000)
    assert b.sample_count == 5
    assert b.get_time_between_samples() == 80_000 * US
    b.empty_sample_set()
    assert b.sample_count == 0 and not b.sampling_complete()
    assert b.get_time_between_samples() == 0


def test_time_between_samples_needs_two():
    """B-Dot Strategy: time between samples is 0 with fewer than two samples."""
    b = BDot()
    assert b.get_time_between_samples() == 0
    b.add_sample((0.0, 0.0, 0.0), 123)
    assert b.get_time_between_samples() == 0
    b.add_sample((0.0, 0.0, 0.0), 20_123)
    assert b.get_time_between_samples() == 20_000


def test_incomplete_window_gives_zero_dipole():
    """B-Dot Strategy: no dipole until the window is full."""
    b = filled([(1.0, 1.0, 1.0)] * 4, [0, 1, 2, 3])
    assert b.get_magnetic_moment() == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_samples_are_rejected(bad):
    """Error Reporting (helper level): NaN/inf samples are not stored and never raise."""
    b = BDot()
    assert not b.add_sample((0.1, bad, 0.2), 0)
    assert b.sample_count == 0


def test_gain_scales_the_dipole():
    """B-Dot Strategy: doubling GAIN doubles the dipole."""
    times = [0, 20_000, 40_000, 60_000, 80_000]
    samples = [(0.001 * i, -0.002 * i, 0.0005 * i) for i in range(5)]
    m1 = filled(samples, times, gain=1.5).get_magnetic_moment()
    m2 = filled(samples, times, gain=3.0).get_magnetic_moment()
    assert m2 == pytest.approx(tuple(2 * v for v in m1))
    assert m1[0] < 0 < m1[1]  # opposes Ḃ
