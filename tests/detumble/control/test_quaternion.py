"""Quaternion math of the attitude controller (scalar first, q_BN; detumble.control.quaternion).

Angles in radians, tolerances in radians or as dimensionless norms.
"""

import math
import random

import pytest

from detumble.control.quaternion import (dcm_to_quat, is_unit_quaternion, quat_angle, quat_conj, quat_error,
                                         quat_from_axis_angle, quat_inv, quat_mul, quat_normalize, quat_to_axis_angle,
                                         quat_to_dcm, rotate_b_to_n, rotate_n_to_b, target_pointing_axis)
from detumble.sim import vec


def rand_q(rng):
    return quat_normalize(tuple(rng.gauss(0, 1) for _ in range(4)))


def close(a, b, tol=1e-12):
    return all(abs(x - y) <= tol for x, y in zip(a, b, strict=True))


def test_product_matches_the_plant_and_composes_dcms():
    """ADCS-001: the Hamilton product composes frames as [CN] = [CB][BN] (q_CN = q_BN ⊗ q_CB), the
    plant's rule, to 1e-12."""
    rng = random.Random(1)
    for _ in range(50):
        q_bn, q_cb = rand_q(rng), rand_q(rng)
        q_cn = quat_mul(q_bn, q_cb)
        assert close(q_cn, vec.quat_mul(q_bn, q_cb))
        c_cb, c_bn = quat_to_dcm(q_cb), quat_to_dcm(q_bn)
        product = tuple(tuple(sum(c_cb[i][k] * c_bn[k][j] for k in range(3)) for j in range(3)) for i in range(3))
        assert all(close(r1, r2) for r1, r2 in zip(quat_to_dcm(q_cn), product, strict=True))


def test_inverse_and_conjugate():
    """ADCS-001: q ⊗ q⁻¹ = identity (also for a non-unit q); the conjugate is the inverse of a unit q."""
    rng = random.Random(2)
    q = tuple(rng.gauss(0, 1) for _ in range(4))
    assert close(quat_mul(q, quat_inv(q)), (1.0, 0.0, 0.0, 0.0))
    u = quat_normalize(q)
    assert close(quat_conj(u), quat_inv(u))
    with pytest.raises(ValueError, match="zero quaternion"):
        quat_inv((0.0, 0.0, 0.0, 0.0))


def test_dcm_round_trip_at_every_angle():
    """ADCS-001: dcm_to_quat(quat_to_dcm(q)) = ±q to 1e-12, including 180° turns (Shepperd's branches)."""
    rng = random.Random(3)
    cases = [rand_q(rng) for _ in range(100)]
    cases += [quat_from_axis_angle(a, math.pi) for a in ((1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0))]
    for q in cases:
        back = dcm_to_quat(quat_to_dcm(q))
        assert back[0] >= 0.0
        assert close(back, q, 1e-12) or close(back, tuple(-c for c in q), 1e-12)


def test_axis_angle_and_the_documented_example():
    """ADCS-001: q = (cos t/2, 0, 0, sin t/2) is B turned by +t about N3, so N1 in B is (cos t, −sin t, 0);
    axis-angle round trip to 1e-12."""
    t = 0.7
    q = quat_from_axis_angle((0.0, 0.0, 2.0), t)
    assert close(rotate_n_to_b(q, (1.0, 0.0, 0.0)), (math.cos(t), -math.sin(t), 0.0))
    assert close(rotate_b_to_n(q, rotate_n_to_b(q, (0.3, -0.2, 0.9))), (0.3, -0.2, 0.9))
    axis, angle = quat_to_axis_angle(q)
    assert close(axis, (0.0, 0.0, 1.0)) and abs(angle - t) < 1e-12
    assert quat_to_axis_angle((1.0, 0.0, 0.0, 0.0)) == ((1.0, 0.0, 0.0), 0.0)


def test_seed_error_formula_and_shortest_path_flip():
    """ADCS-002: q_err = q_target⁻¹ ⊗ q is the attitude of B relative to T; when the product's scalar part
    is negative (the same attitude written the long way) it is flipped, so the error angle is ≤ 180°."""
    q_t = quat_from_axis_angle((0.0, 1.0, 0.0), 0.4)
    rel = quat_from_axis_angle((1.0, 0.0, 0.0), 0.3)  # B = T turned by 0.3 rad about x
    q_b = quat_mul(q_t, rel)
    assert close(quat_error(q_t, q_b), rel)
    q_b_long = tuple(-c for c in q_b)  # the same attitude, scalar part negative
    raw = quat_mul(quat_conj(q_t), q_b_long)
    assert raw[0] < 0.0
    qe = quat_error(q_t, q_b_long)
    assert qe[0] > 0.0 and close(qe, rel)
    assert abs(quat_angle(qe) - 0.3) < 1e-12
    # a 350° turn about x is a −10° error
    qe = quat_error((1.0, 0.0, 0.0, 0.0), quat_from_axis_angle((1.0, 0.0, 0.0), math.radians(350)))
    assert qe[1] < 0.0 and abs(math.degrees(quat_angle(qe)) - 10.0) < 1e-9


def test_unit_check():
    """ADCS-001: is_unit_quaternion accepts |q| within 1e-3 of 1 and refuses short, long, NaN and 3-vectors."""
    assert is_unit_quaternion((0.7071, 0.0, 0.7071, 0.0))
    assert not is_unit_quaternion((0.5, 0.0, 0.0, 0.0))
    assert not is_unit_quaternion((1.01, 0.0, 0.0, 0.0))
    assert not is_unit_quaternion((float("nan"), 0.0, 0.0, 1.0))
    assert not is_unit_quaternion((1.0, 0.0, 0.0))


def test_target_direction_points_the_axis_by_the_smallest_turn():
    """ADCS-001: target_pointing_axis puts body axis a on direction d (≤ 1e-9 rad) and turns by exactly the
    angle between them (the smallest rotation), also for opposite vectors."""
    rng = random.Random(4)
    for _ in range(100):
        q = rand_q(rng)
        a = tuple(rng.gauss(0, 1) for _ in range(3))
        d = tuple(rng.gauss(0, 1) for _ in range(3))
        t = target_pointing_axis(q, a, d)
        assert vec.angle_between(rotate_b_to_n(t, a), d) < 1e-9
        turn = quat_angle(quat_error(t, q))
        assert abs(turn - vec.angle_between(rotate_b_to_n(q, a), d)) < 1e-9
    q = (1.0, 0.0, 0.0, 0.0)
    t = target_pointing_axis(q, (0.0, 0.0, 1.0), (0.0, 0.0, -1.0))
    assert vec.angle_between(rotate_b_to_n(t, (0.0, 0.0, 1.0)), (0.0, 0.0, -1.0)) < 1e-9
    with pytest.raises(ValueError, match="non-zero"):
        target_pointing_axis(q, (0.0, 0.0, 1.0), (0.0, 0.0, 0.0))


def _is_unit_quaternion_reference(q, tol=1e-3):
    """is_unit_quaternion as it was written before its components were checked one by one."""
    try:
        if len(q) != 4 or not all(math.isfinite(float(c)) for c in q):
            return False
    except (TypeError, ValueError):
        return False
    from detumble.control.quaternion import quat_norm

    return abs(quat_norm((float(q[0]), float(q[1]), float(q[2]), float(q[3]))) - 1.0) <= tol


def test_is_unit_quaternion_answers_as_the_all_over_components_form():
    """ADCS-001: the component-by-component check answers as ``all(isfinite(float(c)))`` plus the norm test did,
    for random near-unit quaternions around the tolerance, non-finite, non-numeric and overflowing components,
    other lengths."""
    import random

    rng = random.Random(12)
    odd = (math.nan, math.inf, -math.inf, "x", None, "0.5", 1, True, 10 ** 400)  # 10**400: float() overflows

    def outcome(check, q, tol):
        try:
            return check(q, tol=tol)
        except OverflowError:
            return OverflowError

    for _ in range(20000):
        n = rng.choice((4, 4, 4, 3, 5, 0))
        v = [rng.gauss(0.0, 1.0) for _ in range(n)]
        norm = math.sqrt(sum(c * c for c in v)) or 1.0
        scale = rng.choice((1.0, 1.0 + 1e-3, 1.0 - 1e-3, 1.0 + rng.uniform(-2e-3, 2e-3), 1.0 + 1e-2))
        q = [c / norm * scale for c in v]
        for _ in range(rng.choice((0, 0, 0, 1, 2))):
            if q:
                q[rng.randrange(len(q))] = rng.choice(odd)
        q = tuple(q) if rng.random() < 0.5 else q
        tol = rng.choice((1e-3, 1e-2))
        assert outcome(is_unit_quaternion, q, tol) == outcome(_is_unit_quaternion_reference, q, tol), (q, tol)
