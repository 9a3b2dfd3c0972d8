"""The orbit frame O, attitude relative to it, and the quaternion conventions at the seeds' edge.

Orbit frame O (seed 004's, the usual LVLH of attitude texts): ``z_O`` toward nadir (``-r_hat``),
``y_O`` along the *negative* orbit normal (``-(r x v)/|r x v|``), ``x_O = y_O x z_O`` (along the
velocity on a circular orbit). ``[ON]`` has the rows ``x_O, y_O, z_O`` written in N, so
``v_O = [ON] v_N``; ``q_ON`` is its quaternion (scalar first, as everywhere in ``detumble.sim``)
and the body attitude relative to O is ``q_BO = q_ON* (x) q_BN`` (``[BO] = [BN][ON]^T``).

O turns relative to N at ``omega_ON = (r x v)/r^2``: in O that is ``(0, -n, 0)`` on a circular
orbit of rate ``n`` (seed 004's ``[0, -n, 0]``), so the body rate relative to O is
``omega_BO_B = omega_BN_B - [BO] (0, -n, 0)`` - seed 004's eq. 14 ("synchronous rotation": a
body at rest in O has ``omega_BN_B = (0, -n, 0)``). The secular J2 drift of the orbit plane is
left out of ``omega_ON`` (it is < 1e-6 rad/s).

Seed 004 writes quaternions **scalar last** ``(q1, q2, q3, q4)``, ``q4`` the real part; its DCM
(eq. 11) is then exactly :func:`detumble.sim.vec.quat_to_dcm` of the scalar-first quaternion
``(q4, q1, q2, q3)``. The conversion at the edge is
:func:`detumble.control.coursework.to_plant_quaternion` / ``from_plant_quaternion``.
"""

from __future__ import annotations

import math

from detumble.sim.vec import Mat3, Quat, Vec3, quat_conj, quat_mul

_sqrt = math.sqrt


def dcm_to_quat(m: Mat3) -> Quat:
    """Quaternion (scalar first, q0 >= 0) of a rotation matrix ``[BN]`` (Shepperd's method)."""
    m0, m1, m2 = m
    m00, m11, m22 = m0[0], m1[1], m2[2]
    t = m00 + m11 + m22
    # The branch of the largest of (t, m00, m11, m22), the first one on a tie (as max() picks it;
    # a NaN never replaces the one held): the same k as max(range(4), key=...), without the calls.
    k, best = 0, t
    if m00 > best:
        k, best = 1, m00
    if m11 > best:
        k, best = 2, m11
    if m22 > best:
        k = 3
    if k == 0:
        q0 = 0.5 * _sqrt(1.0 + t)
        f = 0.25 / q0
        q = (q0, f * (m1[2] - m2[1]), f * (m2[0] - m0[2]), f * (m0[1] - m1[0]))
    elif k == 1:
        q1 = 0.5 * _sqrt(1.0 + 2.0 * m00 - t)
        f = 0.25 / q1
        q = (f * (m1[2] - m2[1]), q1, f * (m0[1] + m1[0]), f * (m2[0] + m0[2]))
    elif k == 2:
        q2 = 0.5 * _sqrt(1.0 + 2.0 * m11 - t)
        f = 0.25 / q2
        q = (f * (m2[0] - m0[2]), f * (m0[1] + m1[0]), q2, f * (m1[2] + m2[1]))
    else:
        q3 = 0.5 * _sqrt(1.0 + 2.0 * m22 - t)
        f = 0.25 / q3
        q = (f * (m0[1] - m1[0]), f * (m2[0] + m0[2]), f * (m1[2] + m2[1]), q3)
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    return q


def orbit_axes_N(r_N: Vec3, v_N: Vec3) -> Mat3:
    """``[ON]``: the rows are O's axes ``x_O, y_O, z_O`` in N (see the module docstring)."""
    r0, r1, r2 = r_N
    v0, v1, v2 = v_N
    rn = _sqrt(r0 ** 2 + r1 ** 2 + r2 ** 2)  # ** as written (libm pow: not always x * x)
    z0, z1, z2 = -r0 / rn, -r1 / rn, -r2 / rn
    hx = r1 * v2 - r2 * v1
    hy = r2 * v0 - r0 * v2
    hz = r0 * v1 - r1 * v0
    hn = _sqrt(hx * hx + hy * hy + hz * hz)
    y0, y1, y2 = -hx / hn, -hy / hn, -hz / hn
    return ((y1 * z2 - y2 * z1, y2 * z0 - y0 * z2, y0 * z1 - y1 * z0), (y0, y1, y2), (z0, z1, z2))


def orbit_rate(r_N: Vec3, v_N: Vec3) -> float:
    """``|r x v| / r^2``, rad/s: O's rate about ``-y_O``."""
    hx = r_N[1] * v_N[2] - r_N[2] * v_N[1]
    hy = r_N[2] * v_N[0] - r_N[0] * v_N[2]
    hz = r_N[0] * v_N[1] - r_N[1] * v_N[0]
    return math.sqrt(hx * hx + hy * hy + hz * hz) / (r_N[0] ** 2 + r_N[1] ** 2 + r_N[2] ** 2)


def q_ON(orbit, t: float) -> Quat:
    """Quaternion of the orbit frame relative to N at ``t`` s (``orbit`` has ``position_velocity_N``,
    as :mod:`detumble.sim.orbit`'s orbits do: position in m and velocity in m/s, both in N)."""
    r_N, v_N = orbit.position_velocity_N(t)
    return dcm_to_quat(orbit_axes_N(r_N, v_N))


def q_BO(q_BN: Quat, q_on: Quat) -> Quat:
    """Body attitude relative to O from ``q_BN`` and ``q_ON`` (scalar first, q0 >= 0)."""
    q = quat_mul(quat_conj(q_on), q_BN)
    return q if q[0] >= 0.0 else (-q[0], -q[1], -q[2], -q[3])


def q_BN_from_orbit(q_bo: Quat, q_on: Quat) -> Quat:
    """``q_BN = q_ON (x) q_BO``."""
    return quat_mul(q_on, q_bo)


def attitude_error_rad(q_BN: Quat, q_target_N: Quat) -> float:
    """Rotation angle (rad, 0..pi) between an attitude and a target attitude, both relative to N."""
    e = quat_mul(quat_conj(q_target_N), q_BN)
    v = math.sqrt(e[1] * e[1] + e[2] * e[2] + e[3] * e[3])
    return 2.0 * math.atan2(v, abs(e[0]))
