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


# --- the written-out orbit frame (issue #19): bit for bit the formulas it replaced ----------------

def _old_dcm_to_quat(m):
    """dcm_to_quat before issue #19's tick work: the branch by max(range(4), key=...)."""
    t = m[0][0] + m[1][1] + m[2][2]
    cands = (t, m[0][0], m[1][1], m[2][2])
    k = max(range(4), key=lambda i: cands[i])
    if k == 0:
        q0 = 0.5 * math.sqrt(1.0 + t)
        f = 0.25 / q0
        q = (q0, f * (m[1][2] - m[2][1]), f * (m[2][0] - m[0][2]), f * (m[0][1] - m[1][0]))
    elif k == 1:
        q1 = 0.5 * math.sqrt(1.0 + 2.0 * m[0][0] - t)
        f = 0.25 / q1
        q = (f * (m[1][2] - m[2][1]), q1, f * (m[0][1] + m[1][0]), f * (m[2][0] + m[0][2]))
    elif k == 2:
        q2 = 0.5 * math.sqrt(1.0 + 2.0 * m[1][1] - t)
        f = 0.25 / q2
        q = (f * (m[2][0] - m[0][2]), f * (m[0][1] + m[1][0]), q2, f * (m[1][2] + m[2][1]))
    else:
        q3 = 0.5 * math.sqrt(1.0 + 2.0 * m[2][2] - t)
        f = 0.25 / q3
        q = (f * (m[0][1] - m[1][0]), f * (m[2][0] + m[0][2]), f * (m[1][2] + m[2][1]), q3)
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    return q


def _old_orbit_axes_N(r_N, v_N):
    rn = math.sqrt(r_N[0] ** 2 + r_N[1] ** 2 + r_N[2] ** 2)
    z = (-r_N[0] / rn, -r_N[1] / rn, -r_N[2] / rn)
    hx = r_N[1] * v_N[2] - r_N[2] * v_N[1]
    hy = r_N[2] * v_N[0] - r_N[0] * v_N[2]
    hz = r_N[0] * v_N[1] - r_N[1] * v_N[0]
    hn = math.sqrt(hx * hx + hy * hy + hz * hz)
    y = (-hx / hn, -hy / hn, -hz / hn)
    x = (y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0])
    return (x, y, z)


def _same(a, b):
    """Bit for bit (NaN equal to NaN), element by element of nested tuples."""
    if isinstance(a, tuple):
        return isinstance(b, tuple) and len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return (math.isnan(a) and math.isnan(b)) or (a == b and math.copysign(1.0, a) == math.copysign(1.0, b))


def test_dcm_to_quat_picks_the_branch_and_floats_of_the_max_formula():
    """FR-004: the written-out dcm_to_quat gives bit for bit the old max(range(4), key=...) form's
    quaternion: rotations of random quaternions, the exact ties (first branch wins), NaN entries
    and arbitrary matrices (every branch taken)."""
    rng = random.Random(41)
    mats = [quat_to_dcm(quat_normalize(tuple(rng.gauss(0, 1) for _ in range(4)))) for _ in range(3000)]
    mats += [((0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, -1.0)),   # m00 = m11 the largest: k = 1
             ((-1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),   # m11 = m22: k = 2
             ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),    # t the largest
             ((1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, -1.0)),  # t = -1 = m11 = m22 < m00
             ((math.nan, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
             ((0.2, 0.0, 0.0), (0.0, math.nan, 0.0), (0.0, 0.0, 0.9))]
    mats += [tuple(tuple(rng.uniform(-1.0, 1.0) for _ in range(3)) for _ in range(3)) for _ in range(3000)]
    for diagonal in ((0.5, 0.25, -0.25), (0.3, 0.3, -0.8), (-0.8, 0.3, 0.3), (0.25, -0.25, 0.5), (0.3, -0.8, 0.3)):
        for _ in range(50):  # exact ties of the two largest candidates, off-diagonals that tell the branches apart
            off = [rng.uniform(-1.0, 1.0) for _ in range(6)]
            mats.append(((diagonal[0], off[0], off[1]), (off[2], diagonal[1], off[3]), (off[4], off[5], diagonal[2])))
    branches = set()
    for m in mats:
        with_nan = any(math.isnan(c) for row in m for c in row)
        try:
            old = _old_dcm_to_quat(m)
        except ValueError:  # sqrt of a negative: the new one must raise too
            with pytest.raises(ValueError):
                frames.dcm_to_quat(m)
            continue
        assert _same(frames.dcm_to_quat(m), old), m
        if not with_nan:
            t = m[0][0] + m[1][1] + m[2][2]
            branches.add(max(range(4), key=lambda i: (t, m[0][0], m[1][1], m[2][2])[i]))
    assert branches == {0, 1, 2, 3}


def test_orbit_axes_and_q_on_give_the_floats_of_the_old_formulas():
    """FR-005: orbit_axes_N and q_ON (now one position_velocity_N call, the sines and cosines
    shared) are bit for bit the old formulas over random circular orbits (with and without J2)
    and times; position_velocity_N is exactly (position_N, velocity_N)."""
    rng = random.Random(43)
    for _ in range(300):
        orbit = CircularOrbit(rng.uniform(3e5, 3e7), rng.uniform(0.0, math.pi), rng.uniform(-4.0, 4.0),
                              rng.uniform(-4.0, 4.0), rng.choice((3.986004415e14, 3.98e14)), 6378136.6,
                              rng.choice((0.0, 1.0826267e-3)))
        for t in (0.0, rng.uniform(0.0, 1e4), rng.uniform(0.0, 1e7), 0.01 * rng.randrange(10 ** 8)):
            r, v = orbit.position_N(t), orbit.velocity_N(t)
            assert orbit.position_velocity_N(t) == (r, v)
            assert _same(frames.orbit_axes_N(r, v), _old_orbit_axes_N(r, v))
            assert _same(frames.q_ON(orbit, t), _old_dcm_to_quat(_old_orbit_axes_N(r, v)))
    for _ in range(2000):
        r = tuple(rng.uniform(-1e7, 1e7) for _ in range(3))
        v = tuple(rng.uniform(-1e4, 1e4) for _ in range(3))
        assert _same(frames.orbit_axes_N(r, v), _old_orbit_axes_N(r, v))
