"""Seed 003's PD pointing law (plain floats; no framework import).

``τ = −K_p q_err.v − K_d (ω − ω_ref)`` with ``q_err = q_target⁻¹ ⊗ q`` forced onto the short way
(:func:`detumble.control.quaternion.quat_error`). Units: K_p in N·m, K_d in N·m·s, ω rad/s in B,
τ N·m in B. For a small error angle φ the spring is ``K_p/2`` per radian, so about a principal axis
of inertia I the loop has ``ω_n = sqrt(K_p / (2 I))`` and ``ζ = K_d / (2 I ω_n)``.
"""

from __future__ import annotations

from detumble.control.quaternion import Quat, Vec3, quat_error

__all__ = ["pd_torque", "pd_gains"]


def pd_torque(q_target: Quat, q_BN: Quat, omega_B: Vec3, kp: float, kd: float,
              omega_ref_B: Vec3 = (0.0, 0.0, 0.0)) -> tuple[Vec3, Quat]:
    """``(τ_req, q_err)`` for the target ``q_target`` (= q_TN) and the attitude ``q_BN``."""
    qe = quat_error(q_target, q_BN)
    return ((-kp * qe[1] - kd * (omega_B[0] - omega_ref_B[0]),
             -kp * qe[2] - kd * (omega_B[1] - omega_ref_B[1]),
             -kp * qe[3] - kd * (omega_B[2] - omega_ref_B[2])), qe)


def pd_gains(inertia: float, natural_frequency_rad_s: float, damping_ratio: float) -> tuple[float, float]:
    """``(K_p, K_d)`` giving ``ω_n`` and ``ζ`` about an axis of inertia ``inertia`` (kg·m²)."""
    wn = natural_frequency_rad_s
    return 2.0 * inertia * wn * wn, 2.0 * damping_ratio * inertia * wn
