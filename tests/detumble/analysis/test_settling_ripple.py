"""The settling time of a rippled decay: lsiminfo's figure jumps by a ripple period, the envelope's does not.

docs/studies/coursework_reproduction.md explains the listing β-PD's non-monotone convergence sequence this way:
the slow axis decays with a ripple (once per turn of the body through the field, the bang-bang spin terms
switching), the 2 % settling time is the falling edge of the last ripple peak above the band, and a change of a
peak's height by a hair moves it by one ripple period; the envelope through the peaks moves continuously.
"""
import math

import numpy as np
import pytest

from detumble.analysis.settling import envelope_settling_time, ripple_peaks, settling_time


def _rippled(t, phase, tau=1000.0, period=50.0, depth=0.05):
    return np.exp(-t / tau) * (1.0 + depth * np.cos(2.0 * math.pi * t / period + phase))


def test_ripple_peaks_are_the_maxima_refined_between_samples():
    """STUDY-050: on a cosine sampled every 0.5 s the peaks come out at its maxima, in time to well under a
    sample (the parabola through three samples) and in height to 1e-5 of the amplitude."""
    t = np.arange(0.0, 200.0, 0.5)
    y = 2.0 * np.cos(2.0 * math.pi * (t - 0.2) / 40.0)  # maxima of |y| every 20 s, at 0.2 + 20 k s
    peaks = ripple_peaks(t, y, 0.0)
    assert len(peaks) == 9  # t = 20.2 … 180.2 (0.2 s is next to the first sample: not a peak)
    for k, (tp, h) in enumerate(peaks, start=1):
        assert tp == pytest.approx(0.2 + 20.0 * k, abs=0.01)
        assert h == pytest.approx(2.0, abs=2e-5)


def test_lsiminfo_jumps_by_a_ripple_period_where_the_envelope_moves_continuously():
    """STUDY-051: e^(−t/τ)(1 + 0.05 cos(2πt/T + φ)), band 0.02: over a turn of the phase φ the 2 % settling time
    spans most of a ripple period T, the envelope's crossing stays within 1 s of the closed form
    τ ln(1.05 / 0.02)."""
    t = np.arange(0.0, 6000.0, 0.5)
    plain, envelope = [], []
    for phase in np.linspace(0.0, 2.0 * math.pi, 24, endpoint=False):
        y = _rippled(t, phase)
        plain.append(settling_time(t, y, 0.0, 1.0))
        envelope.append(envelope_settling_time(t, y, 0.0, 1.0))
    expected = 1000.0 * math.log(1.05 / 0.02)
    assert max(plain) - min(plain) > 0.6 * 50.0
    assert max(abs(e - expected) for e in envelope) < 1.0


def test_a_plain_decay_settles_as_lsiminfo_says():
    """STUDY-052: without a peak above the band the envelope figure is the plain settling time."""
    t = np.arange(0.0, 20.0, 1e-3)
    y = np.exp(-t / 2.0)
    assert envelope_settling_time(t, y, 0.0, 1.0) == settling_time(t, y, 0.0, 1.0)


@pytest.fixture(scope="module")
def listing_late_phase():
    """The listing β-PD (both spin terms) from a rate like the 9000 s run's at about 6000 s, 1500 s at 0.01 s."""
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    scenario = load_scenario("surrey", settings=["initial.rate.omega_rad_s=[0.024,-0.0010771953649303385,0.06]",
                                                 "control.beta_pd.switched=false", "record_interval_s=0.5"])
    rows = np.asarray(run(scenario, law="beta_pd", duration_s=1500.0).rows, dtype=float)
    return rows[:, 0], np.radians(rows[:, 1:4])


def test_the_plant_ripples_once_a_turn_and_its_settling_time_jumps_a_period(listing_late_phase):
    """STUDY-053: the listing β-PD's ω_x, late in the detumble, ripples at the body's turn through the field:
    peak spacing within 10 % of 2π/|ω − ω_final|. With the band set a hair (1e-4 of it) above, then below, a
    ripple peak's height, the 2 % settling time moves from just after that peak back to the previous peak's
    falling edge: by more than half the spacing of the two peaks (and at most all of it); the envelope's by < 1 s."""
    t, w = listing_late_phase
    n = 0.0010771953649303385
    rel = np.linalg.norm(w - np.array([0.0, -n, 0.0]), axis=1)
    peaks = ripple_peaks(t, w[:, 0], 0.0)
    assert len(peaks) >= 8
    for (t0, _), (t1, _) in zip(peaks[1:-1], peaks[2:], strict=False):
        turn = 2.0 * math.pi / rel[int(np.searchsorted(t, 0.5 * (t0 + t1)))]
        assert t1 - t0 == pytest.approx(turn, rel=0.10)
    k = len(peaks) - 4
    (tp, _), (tk, hk) = peaks[k - 1], peaks[k]
    plain, envelope = [], []
    for width in (hk * (1.0 - 1e-4), hk * (1.0 + 1e-4)):
        y_init = width / 0.02  # the band is 2 % of |y_final − y_init|, y_final = 0
        plain.append(settling_time(t, w[:, 0], 0.0, y_init))
        envelope.append(envelope_settling_time(t, w[:, 0], 0.0, y_init))
    assert tk < plain[0] < tk + 5.0  # a hair above the band: settled just after that peak
    assert 0.5 * (tk - tp) < plain[0] - plain[1] <= tk - tp
    assert abs(envelope[0] - envelope[1]) < 1.0
