"""Plain-float 3-vector, 3x3 matrix and quaternion helpers.

Everything here works on tuples of Python floats: on 3-vectors, plain floats are 30-40x faster
than numpy, and these helpers sit on the per-tick path of the plant.

Quaternion convention (used by the whole ``detumble.sim`` package): **scalar first**,
``q_BN = (q0, q1, q2, q3)`` with ``q0 = cos(phi/2)`` and ``(q1, q2, q3) = e * sin(phi/2)``, the
Euler parameters of the rotation that takes frame N onto frame B (principal axis ``e``, angle
``phi``). This is Basilisk's ``beta_BN``. The direction-cosine matrix ``[BN]`` built from it maps
N components to B components: ``v_B = [BN] v_N``. With the Hamilton product :func:`quat_mul`,
composition is ``q_CN = q_BN (x) q_CB`` (so ``[CN] = [CB][BN]``) and the kinematics are
``dq_BN/dt = 1/2 q_BN (x) (0, omega_BN_B)``.

Example: ``q_BN = (cos(t/2), 0, 0, sin(t/2))`` is B turned by +t about N's third axis, so N's first
axis seen in B is ``(cos t, -sin t, 0)``.
"""

from __future__ import annotations

import math

from detumble.control.mat3 import cross  # the one cross product of the application (control is below sim)

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Mat3 = tuple[Vec3, Vec3, Vec3]


def dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]




def norm(a: Vec3) -> float:
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def add(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(s: float, a: Vec3) -> Vec3:
    return (s * a[0], s * a[1], s * a[2])


def unit(a: Vec3) -> Vec3:
    """``a / |a|``; raises ``ValueError`` for the zero vector."""
    n = norm(a)
    if n == 0.0:
        raise ValueError("cannot normalise a zero vector")
    return (a[0] / n, a[1] / n, a[2] / n)


def angle_between(a: Vec3, b: Vec3) -> float:
    """Angle between two non-zero vectors, radians, in [0, pi] (atan2 form: accurate near 0)."""
    return math.atan2(norm(cross(a, b)), dot(a, b))


def mat_vec(m: Mat3, v: Vec3) -> Vec3:
    return (
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    )


def mat_transpose(m: Mat3) -> Mat3:
    return ((m[0][0], m[1][0], m[2][0]), (m[0][1], m[1][1], m[2][1]), (m[0][2], m[1][2], m[2][2]))


def mat_det(m: Mat3) -> float:
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def mat_inv(m: Mat3) -> Mat3:
    """Inverse of a 3x3 matrix by cofactors; raises ``ValueError`` if singular."""
    det = mat_det(m)
    if det == 0.0:
        raise ValueError("singular matrix")
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    s = 1.0 / det
    return (
        (s * (e * i - f * h), s * (c * h - b * i), s * (b * f - c * e)),
        (s * (f * g - d * i), s * (a * i - c * g), s * (c * d - a * f)),
        (s * (d * h - e * g), s * (b * g - a * h), s * (a * e - b * d)),
    )


def diag(a: float, b: float, c: float) -> Mat3:
    return ((a, 0.0, 0.0), (0.0, b, 0.0), (0.0, 0.0, c))


# --- quaternions (scalar first) -------------------------------------------------------------


# The quaternion helpers are the control layer's (one implementation for plant and flight code).
from detumble.control.quaternion import (quat_conj, quat_from_axis_angle, quat_mul, quat_normalize,  # noqa: E402,F401
                                         quat_to_dcm, rotate_b_to_n, rotate_n_to_b)


def mrp_to_quat(sigma: Vec3) -> Quat:
    """Modified Rodrigues parameters ``sigma_BN`` to ``q_BN`` (scalar first, q0 >= 0 when |sigma| <= 1)."""
    s2 = dot(sigma, sigma)
    d = 1.0 + s2
    return ((1.0 - s2) / d, 2.0 * sigma[0] / d, 2.0 * sigma[1] / d, 2.0 * sigma[2] / d)


def quat_to_mrp(q: Quat) -> Vec3:
    """``q_BN`` to the short-rotation MRP set ``sigma_BN`` (|sigma| <= 1)."""
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    d = 1.0 + q[0]
    return (q[1] / d, q[2] / d, q[3] / d)
