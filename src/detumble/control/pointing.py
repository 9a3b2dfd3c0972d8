"""Seed 003's PD pointing law (plain floats; no framework import).

``τ = −K_p q_err.v − K_d (ω − ω_ref)`` with ``q_err = q_target⁻¹ ⊗ q`` forced onto the short way
(:func:`detumble.control.quaternion.quat_error`). Units: K_p in N·m, K_d in N·m·s, ω rad/s in B,
τ N·m in B. For a small error angle φ the spring is ``K_p/2`` per radian, so about a principal axis
of inertia I the loop has ``ω_n = sqrt(K_p / (2 I))`` and ``ζ = K_d / (2 I ω_n)``.
"""

from __future__ import annotations

import math

from detumble.control.quaternion import Quat, Vec3, quat_error

__all__ = ["pd_torque", "pd_gains", "ErrorIntegrator", "gyroscopic_torque", "gravity_gradient_torque"]


def pd_torque(q_target: Quat, q_BN: Quat, omega_B: Vec3, kp: float, kd: float,
              rate_limit: float = math.inf) -> tuple[Vec3, Quat]:
    """``(τ_req, q_err)`` for the target ``q_target`` (= q_TN) and the attitude ``q_BN``.

    Written as ``τ = −K_d (ω − ω_c)`` with the commanded rate ``ω_c = −(K_p/K_d) q_err.v``, which is
    the seed's law exactly; when ``|ω_c|`` would exceed ``rate_limit`` (rad/s) it is scaled down to it,
    so a large slew turns at no more than ``rate_limit`` (the seed's law is unchanged below it).
    """
    qe = quat_error(q_target, q_BN)
    if kd > 0.0:
        g = -kp / kd
        wc = (g * qe[1], g * qe[2], g * qe[3])
        n = math.sqrt(wc[0] * wc[0] + wc[1] * wc[1] + wc[2] * wc[2])
        if n > rate_limit:
            wc = (wc[0] * rate_limit / n, wc[1] * rate_limit / n, wc[2] * rate_limit / n)
        return ((-kd * (omega_B[0] - wc[0]), -kd * (omega_B[1] - wc[1]), -kd * (omega_B[2] - wc[2])), qe)
    return ((-kp * qe[1], -kp * qe[2], -kp * qe[3]), qe)


def pd_gains(inertia: float, natural_frequency_rad_s: float, damping_ratio: float) -> tuple[float, float]:
    """``(K_p, K_d)`` giving ``ω_n`` and ``ζ`` about an axis of inertia ``inertia`` (kg·m²)."""
    wn = natural_frequency_rad_s
    return 2.0 * inertia * wn * wn, 2.0 * damping_ratio * inertia * wn


def gyroscopic_torque(inertia, omega_B: Vec3, h_w_B: Vec3) -> Vec3:
    """``ω × (I ω + h_w)`` (N·m, B): the torque the wheels must add so that Euler's equation
    ``I ω̇ = τ − ω × (I ω + h_w)`` sees the PD's ``τ`` alone. ``inertia`` 3×3 kg·m², ``ω`` rad/s, ``h_w`` N·m·s."""
    w0, w1, w2 = omega_B
    h = (inertia[0][0] * w0 + inertia[0][1] * w1 + inertia[0][2] * w2 + h_w_B[0],
         inertia[1][0] * w0 + inertia[1][1] * w1 + inertia[1][2] * w2 + h_w_B[1],
         inertia[2][0] * w0 + inertia[2][1] * w1 + inertia[2][2] * w2 + h_w_B[2])
    return (w1 * h[2] - w2 * h[1], w2 * h[0] - w0 * h[2], w0 * h[1] - w1 * h[0])


def gravity_gradient_torque(inertia, r_B: Vec3, mu: float) -> Vec3:
    """The gravity-gradient torque ``3 μ/|r|³ r̂ × (I r̂)`` (N·m, B) at the position ``r_B`` (m, from the Earth's
    centre, in B) for the inertia model ``inertia`` (kg·m²) and ``μ`` (m³/s²). On a circular orbit
    ``3 μ/|r|³ = 3 n²``; with +Z to nadir and a diagonal inertia it vanishes, and a products-of-inertia term
    ``I_yz`` gives ``3 n² (−I_yz, I_xz, 0)`` (the closed form the tests check)."""
    x, y, z = r_B
    r2 = x * x + y * y + z * z
    r = math.sqrt(r2)
    k = 3.0 * mu / (r2 * r)
    x, y, z = x / r, y / r, z / r
    s = (inertia[0][0] * x + inertia[0][1] * y + inertia[0][2] * z,
         inertia[1][0] * x + inertia[1][1] * y + inertia[1][2] * z,
         inertia[2][0] * x + inertia[2][1] * y + inertia[2][2] * z)
    return (k * (y * s[2] - z * s[1]), k * (z * s[0] - x * s[2]), k * (x * s[1] - y * s[0]))


class ErrorIntegrator:
    """The integral term added to the seed's PD: ``τ_i = −K_i ∫ q_err.v dt`` (N·m; K_i in N·m/s).

    A PD law holds a constant torque error ``d`` (an unmodelled disturbance, a residual gyro bias in its
    ``K_d ω`` term) as an attitude offset of ``d / (K_p/2)`` rad; the integral removes it. Anti-windup:
    it integrates only while the error angle is below ``window_rad`` and its torque is clipped to
    ``max_torque`` per axis; :meth:`reset` on every new target.

    Rate gate (``rate_gate_rad_s`` > 0): it integrates only while, besides, the body's rate relative to the
    reference (rad/s, B, given to :meth:`update`; the wheel law gives the gyro's, which an unmodelled torque does not
    bias as it biases the rate observer's) is below the gate. A slew's final approach moves at more than
    ``K_d/(2 I)`` times its error and is not integrated until it has nearly ended; an offset held by a constant
    torque does not move, so it is integrated anywhere inside the window (docs/studies/robust_rates.md, "The rate
    gate").
    0 (the default) turns the gate off.
    """

    def __init__(self, window_rad: float, max_torque: float, rate_gate_rad_s: float = 0.0) -> None:
        self.window_rad = float(window_rad)
        self.max_torque = float(max_torque)
        self.rate_gate_rad_s = float(rate_gate_rad_s)
        self.state: Vec3 = (0.0, 0.0, 0.0)  # ∫ q_err.v dt, s

    def reset(self) -> None:
        self.state = (0.0, 0.0, 0.0)

    def update(self, q_err: Quat, dt: float, k_i: float, rate: Vec3 | None = None) -> Vec3:
        """Integrate ``q_err.v`` over ``dt`` s (inside the window and, with a gate, while ``|rate|`` rad/s is below
        it; no rate given: the gate is not applied) and return ``τ_i``."""
        v = math.sqrt(q_err[1] ** 2 + q_err[2] ** 2 + q_err[3] ** 2)
        angle = 2.0 * math.atan2(v, abs(q_err[0]))
        st = self.state
        gate = self.rate_gate_rad_s
        gated = (gate > 0.0 and rate is not None
                 and not rate[0] * rate[0] + rate[1] * rate[1] + rate[2] * rate[2] < gate * gate)
        if angle < self.window_rad and not gated:
            st = (st[0] + q_err[1] * dt, st[1] + q_err[2] * dt, st[2] + q_err[3] * dt)
            if k_i > 0.0:
                cap = self.max_torque / k_i
                st = (max(-cap, min(cap, st[0])), max(-cap, min(cap, st[1])), max(-cap, min(cap, st[2])))
            self.state = st
        return (-k_i * st[0], -k_i * st[1], -k_i * st[2])
