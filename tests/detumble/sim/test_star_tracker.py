"""Star tracker model: error statistics match the configuration (seeded), dropouts, rate limit."""

import math

import pytest

from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario
from detumble.sim.star_tracker import ARCSEC, StarTracker, StarTrackerSpec
from detumble.sim.vec import dot, quat_conj, quat_from_axis_angle, quat_mul

N_SAMPLES = 20_000


def _error_vector(q_true, q_meas):
    """Rotation vector (rad, in B) of q_true^-1 (x) q_meas."""
    e = quat_mul(quat_conj(q_true), q_meas)
    if e[0] < 0:
        e = tuple(-x for x in e)
    return (2 * e[1], 2 * e[2], 2 * e[3])


def _std(xs):
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1)), m


def test_error_statistics_match_the_configuration():
    """ST-001: with an oblique boresight, the error about the boresight has the configured 1-sigma
    (70 arcsec) and each cross axis its own (10 arcsec), zero mean, and the components are
    uncorrelated: 20000 seeded samples, sigma within 3 % (the estimate's 1-sigma is 0.5 %), means
    within 4 standard errors."""
    bore = (1 / math.sqrt(2), 1 / math.sqrt(2), 0.0)
    spec = StarTrackerSpec(noise_cross_boresight_arcsec=10.0, noise_about_boresight_arcsec=70.0, boresight_B=bore,
                           max_rate_deg_s=0.0)
    st = StarTracker(spec, seed=11)
    q = quat_from_axis_angle((0.2, -0.5, 0.8), 2.1)
    along, c1, c2 = [], [], []
    for _ in range(N_SAMPLES):
        q_meas, valid = st.measure(q, (0.0, 0.0, 0.0))
        assert valid
        d = _error_vector(q, q_meas)
        along.append(dot(d, st.bore) / ARCSEC)
        c1.append(dot(d, st.e1) / ARCSEC)
        c2.append(dot(d, st.e2) / ARCSEC)
    for values, sigma in ((along, 70.0), (c1, 10.0), (c2, 10.0)):
        sd, mean = _std(values)
        assert sd == pytest.approx(sigma, rel=0.03)
        assert abs(mean) < 4 * sigma / math.sqrt(N_SAMPLES)
    corr = sum(a * b for a, b in zip(along, c1, strict=True)) / (N_SAMPLES * _std(along)[0] * _std(c1)[0])
    assert abs(corr) < 4 / math.sqrt(N_SAMPLES)


def test_bias_dropouts_and_the_rate_limit():
    """ST-002: a constant misalignment shifts the mean by exactly the bias; dropouts occur at the
    configured probability (binomial, 4 sigma); above max_rate_deg_s no sample is valid."""
    spec = StarTrackerSpec(noise_cross_boresight_arcsec=1.0, noise_about_boresight_arcsec=1.0,
                           bias_arcsec=(30.0, 0.0, -20.0), dropout_probability=0.1, max_rate_deg_s=2.0)
    st = StarTracker(spec, seed=3)
    q = (1.0, 0.0, 0.0, 0.0)
    errs, invalid = [], 0
    for _ in range(N_SAMPLES):
        q_meas, valid = st.measure(q, (0.0, 0.0, math.radians(1.0)))
        if valid:
            errs.append(_error_vector(q, q_meas))
        else:
            invalid += 1
    p = invalid / N_SAMPLES
    assert abs(p - 0.1) < 4 * math.sqrt(0.1 * 0.9 / N_SAMPLES)
    mean = [sum(e[i] for e in errs) / len(errs) / ARCSEC for i in range(3)]
    assert mean == pytest.approx([30.0, 0.0, -20.0], abs=0.1)
    assert not any(st.measure(q, (0.0, math.radians(2.5), 0.0))[1] for _ in range(100))


def test_plant_latches_at_the_update_rate_and_holds():
    """ST-003: in the plant the tracker samples at rate_hz on the ns grid and holds the sample in
    between; the ideal option returns the truth now."""
    sc = load_scenario("case_a", settings=["sensors.star_tracker.rate_hz=4",
                                            "sensors.star_tracker.max_rate_deg_s=0",
                                            "initial.rate.magnitude_deg_s=1"])
    plant = Plant(sc)
    plant.advance_to(0.3)
    *q, valid, t = plant.star_tracker_reading()
    assert valid and t == 0.25
    plant.advance_to(0.49)
    assert plant.star_tracker_reading()[5] == 0.25
    plant.advance_to(0.5)
    *q, valid, t = plant.star_tracker_reading()
    assert t == 0.5 and valid
    err = _error_vector(plant.q_BN, tuple(q))
    assert math.sqrt(dot(err, err)) < 10 * 70 * ARCSEC  # a real sample of the truth, not a stale one
    ideal = Plant(load_scenario("case_a", settings=["sensors.star_tracker.ideal=true"]))
    ideal.advance_to(0.37)
    assert ideal.star_tracker_reading() == (*ideal.q_BN, True, 0.37)
