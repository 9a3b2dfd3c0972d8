"""Seed 004's laws in the report's own convention (scalar-last quaternions, eq. 11's DCM,
eqs. 19–26): closed forms and the report's equations written out."""
import math
import random

import pytest

from detumble.control import coursework as cw
from detumble.sim.vec import quat_from_axis_angle, rotate_n_to_b

N = cw.REPORT_MEAN_MOTION


def _random_unit_quaternion(rng):
    q = [rng.gauss(0, 1) for _ in range(4)]
    s = math.sqrt(sum(c * c for c in q))
    return tuple(c / s for c in q)


def test_report_mean_motion_is_its_own_constant():
    """CW-001: n = sqrt(3.98e5 / 7000³) rad/s (the report's μ and radius), ≈ 1.0771954e-3 rad/s."""
    assert N == pytest.approx(1.0771954e-3, rel=1e-6)


def test_eq11_dcm_is_a_rotation_and_about_z_is_the_passive_rotation():
    """CW-002: A_OB of eq. 11 is orthonormal with det +1; for q = [0, 0, sin θ/2, cos θ/2] it is the
    frame rotation [[c, s, 0], [−s, c, 0], [0, 0, 1]]; q = [0, 0, 0, 1] is the identity."""
    rng = random.Random(1)
    for _ in range(50):
        a = cw.dcm_ob(_random_unit_quaternion(rng))
        for i in range(3):
            for j in range(3):
                dot = sum(a[i][k] * a[j][k] for k in range(3))
                assert dot == pytest.approx(1.0 if i == j else 0.0, abs=1e-12)
        det = (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
               + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
        assert det == pytest.approx(1.0, abs=1e-12)
    theta = 0.7
    a = cw.dcm_ob((0.0, 0.0, math.sin(theta / 2), math.cos(theta / 2)))
    c, s = math.cos(theta), math.sin(theta)
    expected = ((c, s, 0.0), (-s, c, 0.0), (0.0, 0.0, 1.0))
    assert all(a[i][j] == pytest.approx(expected[i][j], abs=1e-15) for i in range(3) for j in range(3))
    assert cw.dcm_ob((0, 0, 0, 1)) == ((1, 0, 0), (0, 1, 0), (0, 0, 1))


def test_the_conversion_at_the_edge_gives_the_plants_rotation():
    """CW-003: the plant's scalar-first q reordered to [q1 q2 q3 q4] gives, through eq. 11, the same
    body-frame vector as the plant's own rotation (|Δ| ≤ 1e-15 per component)."""
    rng = random.Random(2)
    for _ in range(50):
        axis = (rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))
        norm = math.sqrt(sum(c * c for c in axis))
        q_plant = quat_from_axis_angle(tuple(c / norm for c in axis), rng.uniform(-3, 3))
        v = (rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))
        a = cw.dcm_ob(cw.from_plant_quaternion(q_plant))
        mine = tuple(sum(a[i][j] * v[j] for j in range(3)) for i in range(3))
        assert mine == pytest.approx(rotate_n_to_b(q_plant, v), abs=1e-14)
        assert cw.to_plant_quaternion(cw.from_plant_quaternion(q_plant)) == pytest.approx(q_plant, abs=0)


def test_eq14_rate_relative_to_orbit():
    """CW-004: aligned with O (q = [0,0,0,1]) a body turning at ω = [0, −n, 0] (synchronous
    rotation) has no rate relative to the orbit frame."""
    assert cw.rate_relative_to_orbit((0, 0, 0, 1), (0.0, -N, 0.0)) == pytest.approx((0, 0, 0), abs=1e-18)
    assert cw.rate_relative_to_orbit((0, 0, 0, 1), (1.0, 2.0, 3.0)) == pytest.approx((1.0, 2.0 + N, 3.0), rel=1e-15)


def test_eq19_cross_product_law_dissipates_rotational_energy():
    """CW-005: M = k (ω × B) gives a magnetic torque M × B with τ·ω = −k |ω⊥B|² |B|² ≤ 0."""
    rng = random.Random(3)
    for _ in range(100):
        w = (rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))
        b = tuple(rng.gauss(0, 3e-5) for _ in range(3))
        m = cw.cross_product_dipole(146.0, w, b)
        tau = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
        b2 = sum(c * c for c in b)
        w_dot_b = sum(wi * bi for wi, bi in zip(w, b, strict=True))
        expected = -146.0 * (sum(c * c for c in w) * b2 - w_dot_b ** 2)
        assert sum(ti * wi for ti, wi in zip(tau, w, strict=True)) == pytest.approx(expected, rel=1e-9, abs=1e-30)
        assert expected <= 0.0


def test_eqs20_to_24_beta_pd_as_the_listing_and_as_the_equations():
    """CW-006: the first call commands nothing (no previous β); the second gives M_y = K_d Δβ/Δt and
    the spin terms K_s (ω_y + n) sign(B_z) on x and −K_s (ω_y + n) sign(B_x) on z; the switched form
    keeps only the axis of eq. 23 or 24 chosen by |B_z| vs |B_x|."""
    law = cw.BetaPd(k_s=990.0, k_d=0.06, switched=False)
    b1 = (1e-5, 2e-5, 3e-5)
    b2 = (-1.2e-5, 2.1e-5, 2.9e-5)
    w = (0.1, 0.2, 0.3)
    assert law.dipole(0.0, w, b1) == (0.0, 0.0, 0.0)
    beta1 = math.acos(b1[1] / math.sqrt(sum(c * c for c in b1)))
    beta2 = math.acos(b2[1] / math.sqrt(sum(c * c for c in b2)))
    m = law.dipole(0.5, w, b2)
    assert m[1] == pytest.approx(0.06 * (beta2 - beta1) / 0.5, rel=1e-12)
    assert m[0] == pytest.approx(990.0 * (0.2 + N) * 1.0)
    assert m[2] == pytest.approx(-990.0 * (0.2 + N) * -1.0)
    switched = cw.BetaPd(k_s=990.0, k_d=0.06, switched=True)
    switched.dipole(0.0, w, b1)
    ms = switched.dipole(0.5, w, b2)  # |B_z| > |B_x|: eq. 23 only
    assert ms[0] == pytest.approx(m[0]) and ms[2] == 0.0 and ms[1] == pytest.approx(m[1])
    assert law.dipole(0.5, w, b2) == (0.0, 0.0, 0.0)  # no time since the last call: dT > 0 fails


def test_eq25_error_quaternion_is_zero_at_the_target_and_the_inverse_from_identity():
    """CW-007: q_e = A(q_t) q⁻¹ is [0, 0, 0, ±1] when q = q_t, and q⁻¹ when q_t = [0, 0, 0, 1];
    q_t is normalised first (the listing scales it)."""
    rng = random.Random(5)
    for _ in range(20):
        q = _random_unit_quaternion(rng)
        e = cw.error_quaternion(tuple(3.0 * c for c in q), q)
        assert e[:3] == pytest.approx((0, 0, 0), abs=1e-15) and abs(e[3]) == pytest.approx(1.0, abs=1e-15)
        assert cw.error_quaternion((0, 0, 0, 1), q) == pytest.approx((-q[0], -q[1], -q[2], q[3]), abs=1e-15)


def test_eq26_wheel_torque_makes_the_closed_loop_a_pd():
    """CW-008: substituted in the report's dynamics I ω̇ = −T − ω × (I ω + h), eq. 26 gives
    ω̇ = −K_p q_e,v − K_d ω_O exactly (the gyroscopic term cancels)."""
    inertia = ((2e-3, 1e-5, 0.0), (1e-5, 3e-3, 2e-5), (0.0, 2e-5, 4e-3))
    q_e, w_o, w, h = (0.1, -0.2, 0.05, 0.97), (0.3, -0.1, 0.2), (0.31, -0.09, 0.2), (0.01, 0.02, -0.03)
    t = cw.wheel_torque(5.0, 9.0, inertia, q_e, w_o, w, h)
    iw = [sum(inertia[i][j] * w[j] for j in range(3)) for i in range(3)]
    hh = [iw[i] + h[i] for i in range(3)]
    gyro = (w[1] * hh[2] - w[2] * hh[1], w[2] * hh[0] - w[0] * hh[2], w[0] * hh[1] - w[1] * hh[0])
    i_wdot = [-t[i] - gyro[i] for i in range(3)]
    expected = [-5.0 * q_e[i] - 9.0 * w_o[i] for i in range(3)]
    i_expected = [sum(inertia[i][j] * expected[j] for j in range(3)) for i in range(3)]
    assert i_wdot == pytest.approx(i_expected, rel=1e-12)


def test_the_reports_limits_are_applied_as_its_loops_do():
    """CW-009: dipole clipped per axis to ±1 A·m²; wheel torque to ±1 mN·m, and cut to 0 only when the
    momentum is past ±0.1 N·m·s and the torque pushes it further."""
    assert cw.clip_dipole((2.0, -3.0, 0.5)) == (1.0, -1.0, 0.5)
    assert cw.limit_wheel_torque((5e-3, -5e-3, 2e-4), (0.0, 0.0, 0.0)) == (1e-3, -1e-3, 2e-4)
    assert cw.limit_wheel_torque((5e-4, -5e-4, 5e-4), (0.11, 0.11, -0.11)) == (0.0, -5e-4, 5e-4)
    assert cw.limit_wheel_torque((-5e-4, 5e-4, 0.0), (-0.11, -0.11, 0.1)) == (0.0, 5e-4, 0.0)


def test_dumping_dipole_removes_momentum_across_the_field_only():
    """CW-010: M = k (h × B)/|B|² gives M × B = −k h⊥ exactly (the part of h along B untouched)."""
    rng = random.Random(9)
    for _ in range(50):
        h = tuple(rng.gauss(0, 1e-3) for _ in range(3))
        b = tuple(rng.gauss(0, 3e-5) for _ in range(3))
        m = cw.dumping_dipole(0.01, h, b)
        tau = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
        b2 = sum(c * c for c in b)
        along = sum(hi * bi for hi, bi in zip(h, b, strict=True)) / b2
        h_perp = tuple(h[i] - along * b[i] for i in range(3))
        assert tau == pytest.approx(tuple(-0.01 * c for c in h_perp), rel=1e-9, abs=1e-18)
    assert cw.dumping_dipole(0.01, (1e-3, 0, 0), (0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)


# --- the written-out wheel law (issue #19): bit for bit the functions it replaced -------------------

def _bits(a, b):
    """Tuples equal bit for bit and in type (NaN equal to NaN, the sign of zero counted)."""
    return len(a) == len(b) and all(type(x) is type(y) and ((math.isnan(x) and math.isnan(y)) or
                                    (x == y and math.copysign(1.0, x) == math.copysign(1.0, y)))
                                    for x, y in zip(a, b, strict=True))


def _old_torque(law_state, q, w_B, h_B):
    """WheelsPd.torque before issue #19's tick work: error_quaternion, rate_relative_to_orbit and
    wheel_torque called in turn. ``law_state`` holds k_p, k_d, inertia, target, n, shortest_path and
    previous (updated as the law updates its own)."""
    p = law_state["previous"]
    qq = (float(q[0]), float(q[1]), float(q[2]), float(q[3]))
    if p is not None and qq[0] * p[0] + qq[1] * p[1] + qq[2] * p[2] + qq[3] * p[3] < 0.0:
        qq = (-qq[0], -qq[1], -qq[2], -qq[3])
    law_state["previous"] = qq
    q_e = cw.error_quaternion(law_state["target"], qq)
    if law_state["shortest_path"] and q_e[3] >= 0.0:
        q_e = (-q_e[0], -q_e[1], -q_e[2], q_e[3])
    w_o = cw.rate_relative_to_orbit(qq, w_B, law_state["n"])
    return cw.wheel_torque(law_state["k_p"], law_state["k_d"], law_state["inertia"], q_e, w_o, w_B, h_B)


def test_wheels_pd_torque_is_bit_for_bit_the_three_functions():
    """CW-101: WheelsPd.torque (eqs. 25, 14 and 26 written out in one body) gives the floats of
    error_quaternion, rate_relative_to_orbit and wheel_torque called in turn, cycle after cycle
    (the continuity flip included), for both error forms, full (non-diagonal) and diagonal
    inertias with zeros, non-unit targets, a changed target and orbit rate, and non-finite inputs."""
    rng = random.Random(1919)
    for case in range(60):
        if case % 3 == 0:
            inertia = ((1.67e-3, 0.0, 0.0), (0.0, 1.67e-3, 0.0), (0.0, 0.0, 1.67e-3))
        else:
            inertia = tuple(tuple(rng.uniform(-1e-3, 3e-3) for _ in range(3)) for _ in range(3))
        target = tuple(rng.uniform(-1.0, 1.0) for _ in range(4))
        state = {"k_p": rng.uniform(0.0, 10.0), "k_d": rng.uniform(0.0, 10.0), "inertia": inertia,
                 "target": target, "n": rng.uniform(0.0, 2e-3), "shortest_path": case % 2 == 1, "previous": None}
        law = cw.WheelsPd(state["k_p"], state["k_d"], inertia, target, n=state["n"],
                          shortest_path=state["shortest_path"])
        for step in range(60):
            if step == 30:  # a new target and orbit rate on the same law object
                law.target = state["target"] = tuple(rng.uniform(-1.0, 1.0) for _ in range(4))
                law.n = state["n"] = rng.uniform(0.0, 2e-3)
            q = tuple(rng.gauss(0.0, 1.0) for _ in range(4))
            w = tuple(rng.uniform(-4.0, 4.0) for _ in range(3))
            h = tuple(rng.uniform(-0.2, 0.2) for _ in range(3))
            if step == 45:
                w = (math.nan, 0.0, math.inf)
            assert _bits(law.torque(q, w, h), _old_torque(state, q, w, h)), (case, step)
            assert law.previous == state["previous"] or any(math.isnan(c) for c in state["previous"])


# the report's loop, the old code (kept for lengths other than three)
_old_limit = cw._limit_wheel_torque_loop


def test_limit_wheel_torque_is_bit_for_bit_the_loop():
    """CW-102: the written-out three-wheel limit equals the report's loop (the old code, still the
    path for other lengths) bit for bit: torques inside, at and beyond the limit, momenta inside
    and beyond it, signed zeros, NaN and ints; other lengths still go through the loop (and its
    errors)."""
    rng = random.Random(23)
    special = (0.0, -0.0, 1e-3, -1e-3, 0.1, -0.1, math.nan, math.inf, -math.inf, 0, 1)
    for _ in range(20000):
        u = tuple(rng.choice(special) if rng.random() < 0.2 else rng.uniform(-3e-3, 3e-3) for _ in range(3))
        h = tuple(rng.choice(special) if rng.random() < 0.2 else rng.uniform(-0.2, 0.2) for _ in range(3))
        limits = ((cw.REPORT_WHEEL_TORQUE_LIMIT, cw.REPORT_WHEEL_MOMENTUM_LIMIT) if rng.random() < 0.5
                  else (rng.uniform(1e-4, 2e-3), rng.uniform(0.01, 0.15)))
        assert _bits(cw.limit_wheel_torque(u, h, *limits), _old_limit(u, h, *limits))
    assert cw.limit_wheel_torque([2e-3, -2e-3, 0.0, 5.0], [0.0] * 4) == (1e-3, -1e-3, 0.0)
    with pytest.raises(ValueError):
        cw.limit_wheel_torque((0.0, 0.0, 0.0), (0.0, 0.0))
