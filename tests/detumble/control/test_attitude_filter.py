"""Attitude filter: gyro propagation corrected by the star tracker, with a gyro-bias estimate (rad, rad/s)."""

import math
import random

from detumble.control.attitude_filter import AttitudeFilter
from detumble.control.quaternion import quat_angle, quat_error, quat_from_axis_angle, quat_mul
from detumble.sim.attitude import RigidBody


def test_bias_and_attitude_converge_with_a_noisy_tracker():
    """ADCS-011: a body at a steady 1 °/s, gyro bias (0.3, −0.2, 0.1) °/s, tracker noise 10″ at 10 Hz: after
    300 s the bias estimate is within 0.005 °/s per axis and the attitude within 10″ (truth from RK4)."""
    rng = random.Random(7)
    arcsec = math.pi / 180 / 3600
    bias = tuple(math.radians(b) for b in (0.3, -0.2, 0.1))
    body = RigidBody(((2e-3, 0, 0), (0, 2e-3, 0), (0, 0, 2e-3)))
    state = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, math.radians(1.0))
    f = AttitudeFilter(k_p=0.5, k_i=0.02)
    for _ in range(3000):
        state = body.step(state, 0.1)
        noise = tuple(rng.gauss(0, 10 * arcsec) for _ in range(3))
        q_meas = quat_mul(state[:4], quat_from_axis_angle(noise, math.sqrt(sum(n * n for n in noise)))) \
            if any(noise) else state[:4]
        f.update(tuple(w + b for w, b in zip(state[4:], bias, strict=True)), 0.1, q_meas)
    assert all(abs(math.degrees(e - b)) < 0.005 for e, b in zip(f.bias, bias, strict=True))
    assert quat_angle(quat_error(state[:4], f.q)) < 10 * arcsec


def test_without_measurements_it_propagates_on_the_gyro():
    """ADCS-011: with no tracker the estimate follows the gyro (1e-9 rad over 10 s of a constant rate) and
    the time since the last fix grows."""
    f = AttitudeFilter()
    f.update((0.0, 0.0, 0.1), 0.1, (1.0, 0.0, 0.0, 0.0))
    for _ in range(100):
        f.update((0.0, 0.0, 0.1), 0.1)
    assert quat_angle(quat_error(quat_from_axis_angle((0, 0, 1), 1.0), f.q)) < 1e-9
    assert abs(f.since_measurement_s - 10.0) < 1e-9
