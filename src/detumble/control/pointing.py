"""Seed 003's PD pointing law (plain floats; no framework import).

``τ = −K_p q_err.v − K_d (ω − ω_ref)`` with ``q_err = q_target⁻¹ ⊗ q`` forced onto the short way
(:func:`detumble.control.quaternion.quat_error`). Units: K_p in N·m, K_d in N·m·s, ω rad/s in B,
τ N·m in B. For a small error angle φ the spring is ``K_p/2`` per radian, so about a principal axis
of inertia I the loop has ``ω_n = sqrt(K_p / (2 I))`` and ``ζ = K_d / (2 I ω_n)``.
"""

from __future__ import annotations

import math

from detumble.control.quaternion import Quat, Vec3, quat_error

__all__ = ["pd_torque", "pd_gains", "ErrorIntegrator"]


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


class ErrorIntegrator:
    """The integral term added to the seed's PD: ``τ_i = −K_i ∫ q_err.v dt`` (N·m; K_i in N·m/s).

    A PD law holds a constant torque error ``d`` (an unmodelled disturbance, a residual gyro bias in its
    ``K_d ω`` term) as an attitude offset of ``d / (K_p/2)`` rad; the integral removes it. Anti-windup:
    it integrates only while the error angle is below ``window_rad`` and its torque is clipped to
    ``max_torque`` per axis; :meth:`reset` on every new target.
    """

    def __init__(self, window_rad: float, max_torque: float) -> None:
        self.window_rad = float(window_rad)
        self.max_torque = float(max_torque)
        self.state: Vec3 = (0.0, 0.0, 0.0)  # ∫ q_err.v dt, s

    def reset(self) -> None:
        self.state = (0.0, 0.0, 0.0)

    def update(self, q_err: Quat, dt: float, k_i: float) -> Vec3:
        """Integrate ``q_err.v`` over ``dt`` s (inside the window) and return ``τ_i``."""
        v = math.sqrt(q_err[1] ** 2 + q_err[2] ** 2 + q_err[3] ** 2)
        angle = 2.0 * math.atan2(v, abs(q_err[0]))
        st = self.state
        if angle < self.window_rad:
            st = (st[0] + q_err[1] * dt, st[1] + q_err[2] * dt, st[2] + q_err[3] * dt)
            if k_i > 0.0:
                cap = self.max_torque / k_i
                st = (max(-cap, min(cap, st[0])), max(-cap, min(cap, st[1])), max(-cap, min(cap, st[2])))
            self.state = st
        return (-k_i * st[0], -k_i * st[1], -k_i * st[2])
