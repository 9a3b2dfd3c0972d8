"""Magnetic-actuation laws: the dipole for a requested torque, B-dot on measured spacing,
momentum dumping, and dipole limits (plain floats; no framework import).

Units: field ``b`` in any consistent unit (tesla for torques in N·m), dipole ``m`` in A·m²,
torques in N·m, angular momentum in N·m·s, all in the body frame B. The torque of a dipole is
``τ = m × B``.
"""

from __future__ import annotations

import math

from detumble.control.mat3 import cross as _cross

Vec3 = tuple[float, float, float]

__all__ = ["project_dipole", "project_dipole_weighted", "seed_project_dipole", "bdot_dipole", "normalised_bdot_dipole",
           "dump_torque", "scale_to_limits", "clip_to_limits"]

_ZERO = (0.0, 0.0, 0.0)



def project_dipole(tau_req: Vec3, b: Vec3) -> tuple[Vec3, Vec3]:
    """``(m, τ_lost)``: the dipole ``m = (B × τ_req)/|B|²`` and the part of ``τ_req`` along B it
    cannot give.

    ``m × B`` equals the component of ``τ_req`` perpendicular to B, with its own sign; ``τ_lost``
    (= the component along B) is what no dipole can produce. DEVIATION from seed 003, which writes
    ``(τ_req × B)/|B|²`` (:func:`seed_project_dipole`), the torque of which is ``−τ_req⊥``.
    A zero or non-finite field gives a zero dipole and loses the whole request.
    """
    b2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
    if not (b2 > 0.0 and math.isfinite(b2)):
        return _ZERO, (tau_req[0], tau_req[1], tau_req[2])
    c = _cross(b, tau_req)
    m = (c[0] / b2, c[1] / b2, c[2] / b2)
    along = (tau_req[0] * b[0] + tau_req[1] * b[1] + tau_req[2] * b[2]) / b2
    return m, (along * b[0], along * b[1], along * b[2])


def project_dipole_weighted(tau_req: Vec3, b: Vec3, m_max: Vec3) -> tuple[Vec3, Vec3]:
    """Like :func:`project_dipole`, but the free component along B is used to spare the weak coils.

    Every ``m0 + λ B`` gives the same torque as ``m0 = (B × τ)/|B|²``; this returns the one that
    minimises ``Σ (m_i / m_max_i)²``: ``λ = −Σ(m0_i B_i / w_i²) / Σ(B_i² / w_i²)`` with ``w = m_max``.
    With the default coils (Z− has 1/13 of the X and Y capacity) a request that needs m_z is then met
    with more m_x, m_y instead of being scaled down to fit Z. Returns ``(m, τ_lost)``.
    """
    m0, lost = project_dipole(tau_req, b)
    num = den = 0.0
    for k in range(3):
        w2 = m_max[k] * m_max[k]
        if not w2 > 0.0:
            return m0, lost
        num += m0[k] * b[k] / w2
        den += b[k] * b[k] / w2
    if not den > 0.0:
        return m0, lost
    lam = -num / den
    return (m0[0] + lam * b[0], m0[1] + lam * b[1], m0[2] + lam * b[2]), lost


def seed_project_dipole(tau_req: Vec3, b: Vec3) -> Vec3:
    """Seed 003's projection exactly as written, ``(τ_req × B)/|B|²`` (wrong sign; kept for the
    tests and the study that show why it is not used)."""
    b2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
    if not b2 > 0.0:
        return _ZERO
    c = _cross(tau_req, b)
    return (c[0] / b2, c[1] / b2, c[2] / b2)


def bdot_dipole(b_prev: Vec3, b_now: Vec3, dt_s: float, gain: float) -> Vec3 | None:
    """Seed 003's ``M = −k Ḃ`` with ``Ḃ ≈ (B_n − B_{n−1})/Δt`` over the readings' measured spacing.

    ``gain`` k in A·m² per (field unit / s); ``dt_s`` the time between the two readings' own
    timestamps, seconds. None when ``dt_s`` is not a positive finite number (no derivative).
    """
    if not (isinstance(dt_s, (int, float)) and math.isfinite(dt_s) and dt_s > 0.0):
        return None
    s = -gain / dt_s
    return (s * (b_now[0] - b_prev[0]), s * (b_now[1] - b_prev[1]), s * (b_now[2] - b_prev[2]))


def normalised_bdot_dipole(b_prev: Vec3, b_now: Vec3, dt_s: float, gain: float, b_size: float) -> Vec3:
    """BDotDetumble's ``m = −Gain·Ḃ/|B|`` with ``Ḃ = (B_now − B_prev)/Δt`` (B in gauss, ``b_size`` = |B_now|,
    ``dt_s`` > 0 in s, ``gain`` A·m²·s; m A·m²): the provider component and its plant-only stand-in."""
    scale = -gain / b_size
    return (scale * (b_now[0] - b_prev[0]) / dt_s, scale * (b_now[1] - b_prev[1]) / dt_s,
            scale * (b_now[2] - b_prev[2]) / dt_s)


def dump_torque(h_wheels_B: Vec3, gain: float, h_target_B: Vec3 = _ZERO) -> Vec3:
    """External torque that unloads the wheels: ``τ = −k (h_w − h_target)`` (N·m; k in 1/s).

    Produced magnetically (project it with :func:`project_dipole`) while the attitude loop holds
    the body, it lowers the total momentum, so the wheels' momentum decays toward ``h_target``.
    """
    return (-gain * (h_wheels_B[0] - h_target_B[0]), -gain * (h_wheels_B[1] - h_target_B[1]),
            -gain * (h_wheels_B[2] - h_target_B[2]))


def scale_to_limits(m: Vec3, m_max: Vec3) -> Vec3:
    """Scale the whole vector down (direction kept) so that ``|m_i| <= m_max_i`` on every axis."""
    s = 1.0
    for i in range(3):
        a = abs(m[i])
        if a > m_max[i]:
            s = min(s, m_max[i] / a if a > 0.0 else 1.0)
    if s == 1.0:
        return m
    return (m[0] * s, m[1] * s, m[2] * s)


def clip_to_limits(m: Vec3, m_max: Vec3) -> Vec3:
    """Clip each axis to ``±m_max_i`` independently (the direction may change; seed 004's way and the
    flight coils' own saturation)."""
    return (max(-m_max[0], min(m_max[0], m[0])), max(-m_max[1], min(m_max[1], m[1])),
            max(-m_max[2], min(m_max[2], m[2])))
