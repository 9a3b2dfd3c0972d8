"""Quaternion convention (scalar first, q_BN maps N onto B, v_B = [BN] v_N) and vector helpers."""

import math

from detumble.sim.attitude import RigidBody
from detumble.sim.vec import (angle_between, cross, mat_inv, mat_vec, mrp_to_quat, quat_from_axis_angle,
                              quat_mul, quat_to_dcm, quat_to_mrp, rotate_b_to_n, rotate_n_to_b)

TOL = 1e-12  # dimensionless (unit vectors, quaternion components)


def test_quaternion_convention_scalar_first_passive_rotation():
    """q_BN = (cos t/2, 0, 0, sin t/2): B is N turned +t about N3; N1 seen in B is (cos t, -sin t, 0)."""
    t = math.radians(30.0)
    q = (math.cos(t / 2), 0.0, 0.0, math.sin(t / 2))
    n1_B = rotate_n_to_b(q, (1.0, 0.0, 0.0))
    assert all(abs(a - b) < TOL for a, b in zip(n1_B, (math.cos(t), -math.sin(t), 0.0), strict=True))
    # B's first axis expressed in N is N1 turned by +t
    b1_N = rotate_b_to_n(q, (1.0, 0.0, 0.0))
    assert all(abs(a - b) < TOL for a, b in zip(b1_N, (math.cos(t), math.sin(t), 0.0), strict=True))
    assert q == quat_from_axis_angle((0.0, 0.0, 1.0), t)


def test_kinematics_match_convention():
    """Spinning at omega_BN_B = (0, 0, w) for time T from identity gives q = (cos wT/2, 0, 0, sin wT/2)."""
    body = RigidBody(((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0)))
    w, dt, n = 0.3, 0.01, 1000
    s = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, w)
    for _ in range(n):
        s = body.step(s, dt)
    angle = w * dt * n
    assert abs(s[0] - math.cos(angle / 2)) < 1e-10
    assert abs(s[3] - math.sin(angle / 2)) < 1e-10


def test_composition_matches_dcm_product():
    """q_CN = q_BN (x) q_CB  <=>  [CN] = [CB][BN] (passive convention, body-frame kinematics)."""
    q_bn = quat_from_axis_angle((1.0, 2.0, 3.0), 0.7)
    q_cb = quat_from_axis_angle((-1.0, 0.5, 0.2), 1.9)
    q_cn = quat_mul(q_bn, q_cb)
    v = (0.3, -1.2, 2.0)
    direct = rotate_n_to_b(q_cn, v)
    chained = rotate_n_to_b(q_cb, rotate_n_to_b(q_bn, v))
    assert all(abs(a - b) < TOL for a, b in zip(direct, chained, strict=True))


def test_mrp_round_trip_and_value():
    sigma = (0.1, 0.2, -0.3)
    q = mrp_to_quat(sigma)
    # |sigma|^2 = 0.14: q0 = 0.86/1.14
    assert abs(q[0] - 0.86 / 1.14) < TOL
    assert abs(sum(x * x for x in q) - 1.0) < TOL
    assert all(abs(a - b) < TOL for a, b in zip(quat_to_mrp(q), sigma, strict=True))
    # MRP = e tan(phi/4)
    phi = 1.2
    e = (0.0, 1.0, 0.0)
    q2 = mrp_to_quat(tuple(math.tan(phi / 4) * x for x in e))
    assert all(abs(a - b) < TOL for a, b in zip(q2, quat_from_axis_angle(e, phi), strict=True))


def test_dcm_orthonormal_and_helpers():
    q = quat_from_axis_angle((0.2, -0.4, 0.9), 2.3)
    c = quat_to_dcm(q)
    ci = mat_inv(c)
    for i in range(3):
        for k in range(3):
            assert abs(ci[i][k] - c[k][i]) < TOL
    assert abs(angle_between((1.0, 0.0, 0.0), (0.0, 2.0, 0.0)) - math.pi / 2) < TOL
    assert cross((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)) == (0.0, 0.0, 1.0)
    assert mat_vec(((1, 2, 3), (4, 5, 6), (7, 8, 10)), (1, 1, 1)) == (6, 15, 25)
