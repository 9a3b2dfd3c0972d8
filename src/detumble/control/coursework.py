"""Seed 004's three detumbling controllers (a University of Surrey coursework report), as plain laws.

Written in the report's own convention, converted at the edge by :func:`from_plant_quaternion`:

* quaternions are scalar **last**, ``q = [q1, q2, q3, q4]`` with ``q4`` the real part, and give the
  attitude of the body B relative to the **orbit frame** O (z to nadir, y along the negative orbit
  normal, x completing the triad);
* ``A_OB`` (:func:`dcm_ob`) is its eq. 11, the DCM that takes orbit-frame components to body-frame
  components (``B_B = A_OB B_O``, eq. 12);
* ``ω`` is the body rate relative to inertial space, in B (rad/s); the rate relative to O is
  eq. 14, ``ω_O = ω − A_OB [0, −n, 0]ᵀ`` (:func:`rate_relative_to_orbit`);
* fields in tesla, dipoles in A·m², torques in N·m, wheel momenta in N·m·s.

The laws (eqs. 19–26) and the report's actuator limits:

* :func:`cross_product_dipole` — ``magnetorquer1``: ``M = k (ω × B_B)`` (eq. 19);
* :class:`BetaPd` — ``magnetorquer2``: the angle β between body y and B (eq. 20), its rate by a
  backward difference between successive calls (eq. 21; the first call has no previous β and
  commands nothing, as the MATLAB's empty globals do), ``M_y = K_d β̇`` (eq. 22) and the spin
  regulation of ω_y toward ``ω_ref = −n`` on x or z (eqs. 23–24);
* :func:`wheel_torque` — ``wheels``: the error quaternion of eq. 25 and the PD torque of eq. 26;
* :func:`clip_dipole`, :func:`limit_wheel_torque` — each dipole axis to ±1 A·m², each wheel torque
  to ±1 mN·m and cut to zero when its momentum is past ±0.1 N·m·s and the torque would push it
  further, exactly as the report's ``attitude_model`` does.

No framework import: the plant-only runner and the flight components both call these.
"""
from __future__ import annotations

import math
from typing import Sequence

from detumble.control.mat3 import cross as _cross

__all__ = ["REPORT_MEAN_MOTION", "Vec3", "Quat", "from_plant_quaternion", "to_plant_quaternion", "dcm_ob",
           "rate_relative_to_orbit", "cross_product_dipole", "BetaPd", "WheelsPd", "error_quaternion", "wheel_torque",
           "dumping_dipole",
           "clip_dipole", "limit_wheel_torque", "REPORT_DIPOLE_LIMIT", "REPORT_WHEEL_TORQUE_LIMIT",
           "REPORT_WHEEL_MOMENTUM_LIMIT"]

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]

#: The report's orbit rate, rad/s: ``sqrt(3.98e5 / 7000³)`` (its own μ in km³/s² and a 7000 km radius).
REPORT_MEAN_MOTION = math.sqrt(3.98e5 / 7000.0 ** 3)
#: Each magnetorquer axis, A·m².
REPORT_DIPOLE_LIMIT = 1.0
#: Each wheel's torque, N·m.
REPORT_WHEEL_TORQUE_LIMIT = 1e-3
#: Each wheel's momentum, N·m·s.
REPORT_WHEEL_MOMENTUM_LIMIT = 0.1


def from_plant_quaternion(q_scalar_first: Sequence[float]) -> Quat:
    """``[q0, q1, q2, q3]`` (the plant's scalar-first order) → the report's ``[q1, q2, q3, q4]``."""
    return (float(q_scalar_first[1]), float(q_scalar_first[2]), float(q_scalar_first[3]), float(q_scalar_first[0]))


def to_plant_quaternion(q: Sequence[float]) -> tuple[float, float, float, float]:
    """The report's ``[q1, q2, q3, q4]`` → the plant's scalar-first ``[q4, q1, q2, q3]``."""
    return (float(q[3]), float(q[0]), float(q[1]), float(q[2]))


def dcm_ob(q: Sequence[float]) -> tuple[Vec3, Vec3, Vec3]:
    """Eq. 11: ``A_OB`` of the scalar-last quaternion ``q`` (rows; orbit-frame → body-frame)."""
    q1, q2, q3, q4 = q
    return (
        (q1 * q1 - q2 * q2 - q3 * q3 + q4 * q4, 2.0 * (q1 * q2 + q3 * q4), 2.0 * (q1 * q3 - q2 * q4)),
        (2.0 * (q1 * q2 - q3 * q4), -q1 * q1 + q2 * q2 - q3 * q3 + q4 * q4, 2.0 * (q2 * q3 + q1 * q4)),
        (2.0 * (q1 * q3 + q2 * q4), 2.0 * (q2 * q3 - q1 * q4), -q1 * q1 - q2 * q2 + q3 * q3 + q4 * q4),
    )


def _mat_vec(a, v) -> Vec3:
    return (a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2],
            a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
            a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2])



def rate_relative_to_orbit(q: Sequence[float], w_B: Sequence[float], n: float = REPORT_MEAN_MOTION) -> Vec3:
    """Eq. 14: ``ω_O = ω − A_OB [0, −n, 0]ᵀ`` (rad/s, body frame)."""
    a = dcm_ob(q)
    return (w_B[0] + a[0][1] * n, w_B[1] + a[1][1] * n, w_B[2] + a[2][1] * n)


def cross_product_dipole(k: float, w_B: Sequence[float], b_B: Sequence[float]) -> Vec3:
    """Eq. 19 (``magnetorquer1``): ``M = k (ω × B_B)``; ``k`` in A·m² per (rad/s · T), unclipped."""
    c = _cross(w_B, b_B)
    return (k * c[0], k * c[1], k * c[2])


class BetaPd:
    """Eqs. 20–24 (``magnetorquer2``): PD on the angle between body y and the field.

    Args:
        k_s: spin gain K_s, A·m² per rad/s.
        k_d: derivative gain K_d, A·m² per rad/s of β̇.
        n: orbit rate, rad/s (``ω_ref = −n``).
        switched: ``True`` (default) applies eq. 23 *or* eq. 24 by the larger of |B_z| and |B_x|, as
            the report's equations say — and its figures: only this form gives Table 1's per-axis
            pattern (ω_x before ω_z, ω_y in about 83 s; docs/studies/coursework_reproduction.md);
            ``False`` applies both at once, as its MATLAB listing does (the two ``if`` lines are
            commented out there).
    """

    def __init__(self, k_s: float, k_d: float, n: float = REPORT_MEAN_MOTION, switched: bool = True):
        self.k_s = float(k_s)
        self.k_d = float(k_d)
        self.n = float(n)
        self.switched = switched
        self.previous: tuple[float, float] | None = None  # (t s, β rad) of the last call

    def dipole(self, t: float, w_B: Sequence[float], b_B: Sequence[float]) -> Vec3:
        """Dipole (A·m², unclipped) at time ``t`` s from ω (rad/s, B) and the field (T, B)."""
        bx, by, bz = b_B
        b = math.sqrt(bx * bx + by * by + bz * bz)
        beta = math.acos(max(-1.0, min(1.0, by / b))) if b > 0.0 else 0.0
        previous, self.previous = self.previous, (float(t), beta)
        if previous is None or not t > previous[0]:
            return (0.0, 0.0, 0.0)  # no earlier call (or no time between): the MATLAB's dT > 0 fails
        beta_rate = (beta - previous[1]) / (t - previous[0])
        spin_error = w_B[1] - (-self.n)
        m_y = self.k_d * beta_rate
        m_x = self.k_s * spin_error * _sign(bz)
        m_z = -self.k_s * spin_error * _sign(bx)
        if self.switched:
            if abs(bz) > abs(bx):
                m_z = 0.0
            else:
                m_x = 0.0
        return (m_x, m_y, m_z)


def _sign(x: float) -> float:
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


def error_quaternion(q_target: Sequence[float], q: Sequence[float]) -> Quat:
    """Eq. 25: ``q_e = A(q_t) q⁻¹`` in the report's scalar-last convention (q_t normalised first)."""
    s = math.sqrt(sum(c * c for c in q_target))
    t1, t2, t3, t4 = (c / s for c in q_target)
    i1, i2, i3, i4 = -q[0], -q[1], -q[2], q[3]
    return (t4 * i1 + t3 * i2 - t2 * i3 + t1 * i4,
            -t3 * i1 + t4 * i2 + t1 * i3 + t2 * i4,
            t2 * i1 - t1 * i2 + t4 * i3 + t3 * i4,
            -t1 * i1 - t2 * i2 - t3 * i3 + t4 * i4)


def wheel_torque(k_p: float, k_d: float, inertia: Sequence[Sequence[float]], q_e: Sequence[float],
                 w_O: Sequence[float], w_B: Sequence[float], h_B: Sequence[float]) -> Vec3:
    """Eq. 26: ``T = K_p I q_e,v + K_d I ω_O − ω × (I ω + h)`` (N·m, unlimited).

    ``T`` is the torque the wheels take from the body: the report's dynamics are
    ``I ω̇ = M × B − T − ω × (I ω + h)`` and ``ḣ = T``.
    """
    pd = tuple(k_p * q_e[i] for i in range(3))
    ipd = _mat_vec(inertia, pd)
    iwo = _mat_vec(inertia, w_O)
    iw = _mat_vec(inertia, w_B)
    gyro = _cross(w_B, (iw[0] + h_B[0], iw[1] + h_B[1], iw[2] + h_B[2]))
    return (ipd[0] + k_d * iwo[0] - gyro[0], ipd[1] + k_d * iwo[1] - gyro[1], ipd[2] + k_d * iwo[2] - gyro[2])


class WheelsPd:
    """Eqs. 25–26 as a law with memory: the report integrates its quaternion continuously, and with
    its signs eq. 26's stable equilibrium is ``q_e4 = −1`` — the target in its other representation,
    reached the long way round (up to a full turn). A sensor reports one representation (``q0 ≥ 0``),
    so this law keeps the quaternion it feeds eq. 25 continuous, flipping a reading whose dot product
    with the previous one is negative: what the report's integration amounts to.

    ``shortest_path=True`` (default) is the corrected law: the proportional term takes the sign of
    the error's real part, so both representations are stable and the body turns the short way.
    ``shortest_path=False`` is eq. 25 as the report writes it: from 1° off the target it turns the
    body 179° away before settling (a full turn; docs/studies/coursework_reproduction.md).
    ``torque(q, ω, h)`` takes the report's scalar-last ``q`` (B relative to O), ω in B (rad/s) and
    the wheel momenta along x, y, z (N·m·s) and returns eq. 26's unlimited torque (N·m).
    """

    def __init__(self, k_p: float, k_d: float, inertia: Sequence[Sequence[float]], target: Sequence[float],
                 n: float = REPORT_MEAN_MOTION, shortest_path: bool = True):
        self.k_p, self.k_d = float(k_p), float(k_d)
        self.inertia = inertia
        self.target = tuple(float(c) for c in target)
        self.n = float(n)
        self.shortest_path = shortest_path
        self.previous: Quat | None = None

    @property
    def inertia(self) -> Sequence[Sequence[float]]:
        """The inertia ``I`` of eq. 26 (kg·m², rows, in B)."""
        return self._inertia

    @inertia.setter
    def inertia(self, inertia: Sequence[Sequence[float]]) -> None:
        self._inertia = inertia
        self._j = tuple(inertia[r][c] for r in range(3) for c in range(3))  # row by row, as given

    @property
    def target(self) -> Quat:
        """The target ``q_t`` of eq. 25 (scalar last, B relative to O), as given."""
        return self._target

    @target.setter
    def target(self, target: Sequence[float]) -> None:
        t1, t2, t3, t4 = target
        self._target = (t1, t2, t3, t4)
        # error_quaternion's normalised target: its first two lines, once per target
        s = math.sqrt(sum(c * c for c in self._target))
        self._target_unit = (t1 / s, t2 / s, t3 / s, t4 / s)

    def torque(self, q: Sequence[float], w_B: Sequence[float], h_B: Sequence[float]) -> Vec3:
        # error_quaternion, rate_relative_to_orbit and wheel_torque written out in one body (the
        # wheel cycle runs at 100 Hz): the same operations in the same order, so the same floats
        # (tests/detumble/control/test_coursework.py checks it against the three functions). Kept
        # (issue 26): 6.2-9.9 µs less a call than the three calls, once a 100 Hz coursework tick
        # (≈ 71 µs of CPU): 9-14 % of it; `python benchmarks/bench_inlined.py wheels_pd_torque`
        # (3 sittings on the shared 2-core machine, 2026-12-03, each the best of 40).
        p = self.previous
        q1, q2, q3, q4 = float(q[0]), float(q[1]), float(q[2]), float(q[3])
        if p is not None and q1 * p[0] + q2 * p[1] + q3 * p[2] + q4 * p[3] < 0.0:
            q1, q2, q3, q4 = -q1, -q2, -q3, -q4
        self.previous = (q1, q2, q3, q4)
        # eq. 25: q_e = A(q_t) q⁻¹
        t1, t2, t3, t4 = self._target_unit
        i1, i2, i3, i4 = -q1, -q2, -q3, q4
        e1 = t4 * i1 + t3 * i2 - t2 * i3 + t1 * i4
        e2 = -t3 * i1 + t4 * i2 + t1 * i3 + t2 * i4
        e3 = t2 * i1 - t1 * i2 + t4 * i3 + t3 * i4
        if self.shortest_path and -t1 * i1 - t2 * i2 - t3 * i3 + t4 * i4 >= 0.0:
            e1, e2, e3 = -e1, -e2, -e3
        # eq. 14: ω_O = ω − A_OB [0, −n, 0]ᵀ (the middle column of dcm_ob)
        n = self.n
        w1, w2, w3 = w_B[0], w_B[1], w_B[2]
        wo1 = w1 + 2.0 * (q1 * q2 + q3 * q4) * n
        wo2 = w2 + (-q1 * q1 + q2 * q2 - q3 * q3 + q4 * q4) * n
        wo3 = w3 + 2.0 * (q2 * q3 - q1 * q4) * n
        # eq. 26: T = K_p I q_e,v + K_d I ω_O − ω × (I ω + h)
        k_p, k_d = self.k_p, self.k_d
        j11, j12, j13, j21, j22, j23, j31, j32, j33 = self._j
        p1, p2, p3 = k_p * e1, k_p * e2, k_p * e3
        ipd1 = j11 * p1 + j12 * p2 + j13 * p3
        ipd2 = j21 * p1 + j22 * p2 + j23 * p3
        ipd3 = j31 * p1 + j32 * p2 + j33 * p3
        iwo1 = j11 * wo1 + j12 * wo2 + j13 * wo3
        iwo2 = j21 * wo1 + j22 * wo2 + j23 * wo3
        iwo3 = j31 * wo1 + j32 * wo2 + j33 * wo3
        b1 = j11 * w1 + j12 * w2 + j13 * w3 + h_B[0]
        b2 = j21 * w1 + j22 * w2 + j23 * w3 + h_B[1]
        b3 = j31 * w1 + j32 * w2 + j33 * w3 + h_B[2]
        return (ipd1 + k_d * iwo1 - (w2 * b3 - w3 * b2),
                ipd2 + k_d * iwo2 - (w3 * b1 - w1 * b3),
                ipd3 + k_d * iwo3 - (w1 * b2 - w2 * b1))


def dumping_dipole(k: float, h_B: Sequence[float], b_B: Sequence[float]) -> Vec3:
    """Magnetic momentum dumping (not in the report): ``M = k (h × B)/|B|²`` (A·m²), whose torque
    ``M × B = −k h⊥`` removes the wheels' momentum across the field at the rate ``k`` (1/s); the
    wheel law then holds the body while the wheels unload. Zero in a zero field."""
    b2 = b_B[0] * b_B[0] + b_B[1] * b_B[1] + b_B[2] * b_B[2]
    if not b2 > 0.0:
        return (0.0, 0.0, 0.0)
    c = _cross(h_B, b_B)
    return (k * c[0] / b2, k * c[1] / b2, k * c[2] / b2)


def clip_dipole(m: Sequence[float], limit: float = REPORT_DIPOLE_LIMIT) -> Vec3:
    """Each axis clipped to ±``limit`` A·m² (the report's first loop)."""
    x, y, z = (limit if c > limit else (-limit if c < -limit else float(c)) for c in m)
    return (x, y, z)


def limit_wheel_torque(torque: Sequence[float], h: Sequence[float], torque_limit: float = REPORT_WHEEL_TORQUE_LIMIT,
                       momentum_limit: float = REPORT_WHEEL_MOMENTUM_LIMIT) -> Vec3:
    """The report's second loop: each torque to ±``torque_limit``; zero when the wheel's momentum is
    beyond ±``momentum_limit`` and the torque would push it further out."""
    if len(torque) != 3 or len(h) != 3:
        return _limit_wheel_torque_loop(torque, h, torque_limit, momentum_limit)
    # the loop below written out for three wheels (the wheel cycle runs at 100 Hz). Kept (issue 26):
    # 0.63-3.4 µs less a call than the loop (median of 7 sittings 1.4 µs), once a coursework tick
    # (≈ 71 µs of CPU): about 2 % of it; `python benchmarks/bench_inlined.py limit_wheel_torque`
    # (3 sittings on the shared 2-core machine, 2026-12-03, each the best of 40).
    lo = -torque_limit
    u0, u1, u2 = torque
    u0 = torque_limit if u0 > torque_limit else (lo if u0 < lo else float(u0))
    u1 = torque_limit if u1 > torque_limit else (lo if u1 < lo else float(u1))
    u2 = torque_limit if u2 > torque_limit else (lo if u2 < lo else float(u2))
    h0, h1, h2 = h
    if (h0 > momentum_limit and u0 > 0) or (h0 < -momentum_limit and u0 < 0):
        u0 = 0.0
    if (h1 > momentum_limit and u1 > 0) or (h1 < -momentum_limit and u1 < 0):
        u1 = 0.0
    if (h2 > momentum_limit and u2 > 0) or (h2 < -momentum_limit and u2 < 0):
        u2 = 0.0
    return (u0, u1, u2)


def _limit_wheel_torque_loop(torque: Sequence[float], h: Sequence[float], torque_limit: float,
                             momentum_limit: float) -> Vec3:
    out = []
    for u, hi in zip(torque, h, strict=True):
        u = torque_limit if u > torque_limit else (-torque_limit if u < -torque_limit else float(u))
        if (hi > momentum_limit and u > 0) or (hi < -momentum_limit and u < 0):
            u = 0.0
        out.append(u)
    return (out[0], out[1], out[2])
