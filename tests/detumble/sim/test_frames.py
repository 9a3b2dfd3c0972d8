"""Orbit frame, q_BO, and seed 004's scalar-last convention written out in its own equations."""

import math
import random

import pytest

from detumble.control.coursework import dcm_ob, from_plant_quaternion, to_plant_quaternion
from detumble.sim import frames
from detumble.sim.orbit import CircularOrbit
from detumble.sim.vec import dot, norm, quat_normalize, quat_to_dcm, rotate_n_to_b


def seed_eq11(q):
    """Seed 004 eq. 11, A_O->B of a scalar-last quaternion (q1, q2, q3, q4), as printed."""
    q1, q2, q3, q4 = q
    return (
        (q1 * q1 - q2 * q2 - q3 * q3 + q4 * q4, 2 * (q1 * q2 + q3 * q4), 2 * (q1 * q3 - q2 * q4)),
        (2 * (q1 * q2 - q3 * q4), -q1 * q1 + q2 * q2 - q3 * q3 + q4 * q4, 2 * (q2 * q3 + q1 * q4)),
        (2 * (q1 * q3 + q2 * q4), 2 * (q2 * q3 - q1 * q4), -q1 * q1 - q2 * q2 + q3 * q3 + q4 * q4),
    )


def seed_eq6(w, q):
    """Seed 004 eq. 6/16: q_dot = 1/2 Omega(w_O) q, scalar last."""
    wx, wy, wz = w
    om = ((0, wz, -wy, wx), (-wz, 0, wx, wy), (wy, -wx, 0, wz), (-wx, -wy, -wz, 0))
    return tuple(0.5 * sum(om[r][c] * q[c] for c in range(4)) for r in range(4))


def test_scalar_last_conversion_reproduces_eq11_and_eq6():
    """FR-001: for random quaternions, seed 004's eq. 11 on (q1..q4) (written out here, and the
    control module's dcm_ob) equals our [BN] of the scalar-first (q4, q1, q2, q3) to 1e-15, and its
    kinematics eq. 6 equal ours (1/2 q (x) (0, w)) after the same conversion."""
    rng = random.Random(5)
    for _ in range(50):
        q_sl = quat_normalize(tuple(rng.gauss(0, 1) for _ in range(4)))
        a = seed_eq11(q_sl)
        b = quat_to_dcm(to_plant_quaternion(q_sl))
        assert max(abs(a[i][j] - b[i][j]) for i in range(3) for j in range(3)) < 1e-15
        assert dcm_ob(q_sl) == a
        assert from_plant_quaternion(to_plant_quaternion(q_sl)) == q_sl
        w = tuple(rng.gauss(0, 1) for _ in range(3))
        q = to_plant_quaternion(q_sl)
        ours = (0.5 * (-q[1] * w[0] - q[2] * w[1] - q[3] * w[2]),
                0.5 * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]),
                0.5 * (q[0] * w[1] - q[1] * w[2] + q[3] * w[0]),
                0.5 * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0]))
        assert to_plant_quaternion(seed_eq6(w, q_sl)) == pytest.approx(ours, abs=1e-15)


def test_orbit_frame_axes_and_rate():
    """FR-002: O is right-handed, z_O points at the Earth's centre, y_O along -(r x v), and O turns
    at (0, -n, 0) in O: the axes a small time later match a rotation by -n dt about y_O (1e-9)."""
    orbit = CircularOrbit(622e3, math.radians(40.0), 0.3, 0.7, 3.98e14, 6378e3)
    r, v = orbit.position_N(100.0), orbit.velocity_N(100.0)
    x, y, z = frames.orbit_axes_N(r, v)
    assert dot(x, y) == pytest.approx(0, abs=1e-15) and norm(z) == pytest.approx(1, abs=1e-15)
    assert dot(z, r) == pytest.approx(-norm(r))
    n = frames.orbit_rate(r, v)
    assert n == pytest.approx(math.sqrt(3.98e5 / 7000.0 ** 3), rel=1e-12)
    dt = 1.0
    x2, _, z2 = frames.orbit_axes_N(orbit.position_N(100.0 + dt), orbit.velocity_N(100.0 + dt))
    # rotating by n dt about the orbit normal (-y_O) turns x_O toward z_O
    c, s = math.cos(n * dt), math.sin(n * dt)
    expect_x2 = tuple(c * x[i] + s * z[i] for i in range(3))
    assert max(abs(a - b) for a, b in zip(x2, expect_x2, strict=True)) < 1e-9
    q_on = frames.q_ON(orbit, 100.0)
    assert rotate_n_to_b(q_on, r) == pytest.approx((0.0, 0.0, -norm(r)), abs=1e-6)


def test_dcm_to_quat_round_trip():
    """FR-003: dcm_to_quat inverts quat_to_dcm (up to sign) in every branch of Shepperd's method."""
    rng = random.Random(2)
    cases = [(1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)]
    cases += [quat_normalize(tuple(rng.gauss(0, 1) for _ in range(4))) for _ in range(40)]
    for q in cases:
        back = frames.dcm_to_quat(quat_to_dcm(q))
        sign = 1 if dot(back[1:], q[1:]) + back[0] * q[0] >= 0 else -1
        assert tuple(sign * x for x in back) == pytest.approx(q, abs=1e-14)
