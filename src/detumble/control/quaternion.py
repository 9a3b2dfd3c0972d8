"""Quaternion arithmetic on plain-float tuples (no framework import; per-tick safe).

Convention (the plant's, ``docs/scenarios.md``): **scalar first**, ``q_BN = (q0, q1, q2, q3)``
with ``q0 = cos(phi/2)`` and ``(q1, q2, q3) = e sin(phi/2)``: the rotation that takes frame N onto
frame B about the unit axis ``e`` by the angle ``phi``. The DCM ``[BN]`` built from it maps N
components to B components (``v_B = [BN] v_N``). With the Hamilton product :func:`quat_mul`,
frames compose as ``q_CN = q_BN ⊗ q_CB`` (``[CN] = [CB][BN]``), so the attitude of B relative to a
target frame T is ``q_BT = q_TN⁻¹ ⊗ q_BN`` — seed 003's ``q_err = q_target⁻¹ * q_current``.
"""

from __future__ import annotations

import math

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Mat3 = tuple[Vec3, Vec3, Vec3]

__all__ = ["quat_mul", "quat_conj", "quat_inv", "quat_norm", "quat_normalize", "quat_error",
           "quat_shortest", "quat_to_dcm", "dcm_to_quat", "quat_from_axis_angle", "quat_to_axis_angle",
           "rotate_n_to_b", "rotate_b_to_n", "quat_angle", "target_pointing_axis", "is_unit_quaternion"]


def quat_mul(p: Quat, q: Quat) -> Quat:
    """Hamilton product ``p ⊗ q`` (scalar first)."""
    p0, p1, p2, p3 = p
    q0, q1, q2, q3 = q
    return (
        p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
        p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
        p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
        p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0,
    )


def quat_conj(q: Quat) -> Quat:
    """Conjugate ``(q0, −q1, −q2, −q3)``: the inverse of a unit quaternion."""
    return (q[0], -q[1], -q[2], -q[3])


def quat_norm(q: Quat) -> float:
    return math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])


def quat_inv(q: Quat) -> Quat:
    """Inverse ``q* / |q|²`` (any non-zero quaternion); raises ``ValueError`` for zero."""
    n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]
    if n2 == 0.0:
        raise ValueError("the zero quaternion has no inverse")
    return (q[0] / n2, -q[1] / n2, -q[2] / n2, -q[3] / n2)


def quat_normalize(q: Quat) -> Quat:
    n = quat_norm(q)
    if n == 0.0:
        raise ValueError("cannot normalise a zero quaternion")
    return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


def is_unit_quaternion(q, tol: float = 1e-3) -> bool:
    """True when ``q`` is four finite numbers with ``| |q| − 1 | ≤ tol``.

    (Each component converted and checked in turn, the first non-finite one deciding, and the norm
    summed as :func:`quat_norm` sums it; the controller asks this of every star-tracker solution.)
    """
    isfinite = math.isfinite
    n2 = 0.0
    try:
        if len(q) != 4:
            return False
        for c in q:
            x = float(c)
            if not isfinite(x):
                return False
            n2 += x * x  # 0.0 + q0² is q0²: then the same sum in the same order as quat_norm's
    except (TypeError, ValueError):
        return False
    return abs(math.sqrt(n2) - 1.0) <= tol


def quat_shortest(q: Quat) -> Quat:
    """``q`` or ``−q`` (the same attitude), whichever has a non-negative scalar part."""
    return (-q[0], -q[1], -q[2], -q[3]) if q[0] < 0.0 else q


def quat_error(q_target: Quat, q_current: Quat) -> Quat:
    """Seed 003's ``q_err = q_target⁻¹ ⊗ q_current`` (= ``q_BT``), forced onto the short way round.

    DEVIATION from the seed: the sign is chosen so that ``q_err[0] ≥ 0`` (rotation angle ≤ 180°);
    without it a PD law on ``q_err.v`` may turn the long way (unwinding).
    """
    return quat_shortest(quat_mul(quat_conj(q_target), q_current))


def quat_angle(q: Quat) -> float:
    """Rotation angle of ``q`` in [0, π] rad (short way), accurate near 0."""
    v = math.sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    return 2.0 * math.atan2(v, abs(q[0]))


def quat_from_axis_angle(axis: Vec3, angle_rad: float) -> Quat:
    """The quaternion of a rotation by ``angle_rad`` about ``axis`` (normalised here)."""
    n = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    if n == 0.0:
        raise ValueError("the rotation axis must not be the zero vector")
    s = math.sin(0.5 * angle_rad) / n
    return (math.cos(0.5 * angle_rad), axis[0] * s, axis[1] * s, axis[2] * s)


def quat_to_axis_angle(q: Quat) -> tuple[Vec3, float]:
    """``(unit axis, angle rad in [0, π])`` of the short rotation; axis (1, 0, 0) for the identity."""
    q = quat_shortest(q)
    v = math.sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    if v == 0.0:
        return (1.0, 0.0, 0.0), 0.0
    return (q[1] / v, q[2] / v, q[3] / v), 2.0 * math.atan2(v, q[0])


def quat_to_dcm(q: Quat) -> Mat3:
    """``[BN]`` from ``q_BN`` (maps N components to B components)."""
    q0, q1, q2, q3 = q
    return (
        (q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2.0 * (q1 * q2 + q0 * q3), 2.0 * (q1 * q3 - q0 * q2)),
        (2.0 * (q1 * q2 - q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2.0 * (q2 * q3 + q0 * q1)),
        (2.0 * (q1 * q3 + q0 * q2), 2.0 * (q2 * q3 - q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3),
    )


def dcm_to_quat(c: Mat3) -> Quat:
    """``q_BN`` (scalar ≥ 0) from a proper orthonormal ``[BN]`` (Shepperd: the largest of the four
    squared components is taken first, so the result is accurate at every angle)."""
    tr = c[0][0] + c[1][1] + c[2][2]
    squares = (1.0 + tr, 1.0 + 2.0 * c[0][0] - tr, 1.0 + 2.0 * c[1][1] - tr, 1.0 + 2.0 * c[2][2] - tr)
    k = max(range(4), key=squares.__getitem__)
    s = 2.0 * math.sqrt(max(squares[k], 0.0))  # = 4 |q_k|
    if k == 0:
        q = (s / 4.0, (c[1][2] - c[2][1]) / s, (c[2][0] - c[0][2]) / s, (c[0][1] - c[1][0]) / s)
    elif k == 1:
        q = ((c[1][2] - c[2][1]) / s, s / 4.0, (c[0][1] + c[1][0]) / s, (c[2][0] + c[0][2]) / s)
    elif k == 2:
        q = ((c[2][0] - c[0][2]) / s, (c[0][1] + c[1][0]) / s, s / 4.0, (c[1][2] + c[2][1]) / s)
    else:
        q = ((c[0][1] - c[1][0]) / s, (c[2][0] + c[0][2]) / s, (c[1][2] + c[2][1]) / s, s / 4.0)
    return quat_shortest(quat_normalize(q))


def rotate_n_to_b(q: Quat, v_N: Vec3) -> Vec3:
    """``v_B = [BN(q)] v_N``, from the quaternion's products directly (no [BN] matrix: fewer
    operations than ``quat_to_dcm(q)`` times ``v_N``, and rounded differently, so the two are not
    interchangeable where the last bit counts)."""
    q0, q1, q2, q3 = q
    x, y, z = v_N
    q00, q11, q22, q33 = q0 * q0, q1 * q1, q2 * q2, q3 * q3
    q01, q02, q03, q12, q13, q23 = q0 * q1, q0 * q2, q0 * q3, q1 * q2, q1 * q3, q2 * q3
    return (
        (q00 + q11 - q22 - q33) * x + 2.0 * ((q12 + q03) * y + (q13 - q02) * z),
        (q00 - q11 + q22 - q33) * y + 2.0 * ((q12 - q03) * x + (q23 + q01) * z),
        (q00 - q11 - q22 + q33) * z + 2.0 * ((q13 + q02) * x + (q23 - q01) * y),
    )


def rotate_b_to_n(q: Quat, v_B: Vec3) -> Vec3:
    """``v_N = [BN(q)]ᵀ v_B``."""
    return rotate_n_to_b(quat_conj(q), v_B)


def target_pointing_axis(q_current: Quat, axis_B: Vec3, direction_N: Vec3) -> Quat:
    """A target ``q_TN`` whose body ``axis_B`` points along ``direction_N`` and which is the smallest
    rotation from ``q_current`` that does so (the free rotation about the axis is left where it is).

    Raises ``ValueError`` for a zero axis or direction.
    """
    a_n = rotate_b_to_n(q_current, _unit(axis_B))
    d = _unit(direction_N)
    c = a_n[0] * d[0] + a_n[1] * d[1] + a_n[2] * d[2]
    w = (a_n[1] * d[2] - a_n[2] * d[1], a_n[2] * d[0] - a_n[0] * d[2], a_n[0] * d[1] - a_n[1] * d[0])
    s = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    if s < 1e-12:
        if c > 0.0:
            return quat_shortest(q_current)
        # opposite: turn 180° about any axis perpendicular to a_n
        p = (0.0, -a_n[2], a_n[1]) if abs(a_n[0]) < 0.9 else (-a_n[2], 0.0, a_n[0])
        return quat_shortest(quat_normalize(quat_mul(quat_from_axis_angle(p, math.pi), q_current)))
    # r turns a_n onto d about their common normal (an active rotation of the body seen in N);
    # with the frame-composition rule above the new attitude is r ⊗ q_current
    r = quat_from_axis_angle((w[0] / s, w[1] / s, w[2] / s), math.atan2(s, c))
    return quat_shortest(quat_normalize(quat_mul(r, q_current)))


def _unit(v: Vec3) -> Vec3:
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if not n > 0.0 or not math.isfinite(n):
        raise ValueError(f"expected a non-zero finite vector, got {tuple(v)}")
    return (v[0] / n, v[1] / n, v[2] / n)
