"""Floquet analysis of magnetorquer-only pointing, linearised about an inertial target (numpy; analysis
only, not per-tick).

Small errors ``θ`` (rad, ``q_err.v ≈ θ/2``) and rates ``ω`` about an inertially fixed target obey
``θ̇ = ω``, ``J ω̇ = P(t) τ(θ, ω, t)`` with ``P = I − b̂ b̂ᵀ`` (the dipole's torque is the request's part
⟂ B), where ``b̂(t)`` is the field direction in the target frame along the orbit. Both laws are linear
in the state, so one orbit's transition matrix (monodromy) ``Φ(T)`` decides stability; the
per-second rate ``log(max |eig Φ|)/T`` is what the study quotes (positive: diverges). The field is
taken as periodic with the orbit (the Earth turns 24° per orbit, which this neglects).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["field_line_along_orbit", "closed_loop_matrix", "floquet_rate", "averaged_projection",
           "along_field_offset_from_gravity_gradient"]


def field_line_along_orbit(plant, q_target, samples: int = 1000, bias_t=(0.0, 0.0, 0.0)):
    """``(period s, b̂ (samples+1)×3, ḃ (samples+1)×3)``: the field direction in the target frame over one
    orbit of ``plant`` (a :class:`detumble.sim.plant.Plant`) and its time derivative (1/s, ⟂ b̂).

    ``bias_t``: a constant field (T) added in the target frame before normalising — what a law holding the
    target sees through a magnetometer with that bias (pass the result as ``b_law``/``bdot_law`` of
    :func:`floquet_rate`)."""
    period = 2.0 * math.pi / plant.orbit.mean_motion
    r_tn = _dcm(q_target)
    ts = np.linspace(0.0, period, samples + 1)
    b = np.array([r_tn @ np.array(plant.field.b_N(t, plant.orbit.position_N(t))) for t in ts])
    b += np.asarray(bias_t, dtype=float)[None, :]
    b /= np.linalg.norm(b, axis=1)[:, None]
    bd = np.gradient(b, ts[1] - ts[0], axis=0)
    bd -= np.sum(bd * b, axis=1)[:, None] * b
    return period, b, bd


def _dcm(q) -> np.ndarray:
    """``[TN]`` (maps N components to T components) of ``q_TN``, scalar first (detumble.control.quaternion's
    convention; analysis may not import control)."""
    q0, q1, q2, q3 = (float(c) for c in q)
    return np.array([[q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 + q0 * q3), 2 * (q1 * q3 - q0 * q2)],
                     [2 * (q1 * q2 - q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 + q0 * q1)],
                     [2 * (q1 * q3 + q0 * q2), 2 * (q2 * q3 - q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3]])


def averaged_projection(b_hat) -> np.ndarray:
    """Orbit average ``Γ̄ = ⟨I − b̂ b̂ᵀ⟩`` of the projection (the averaged model's input matrix)."""
    b = np.asarray(b_hat, dtype=float)
    return np.eye(3) - np.einsum("ki,kj->ij", b, b) / len(b)


def closed_loop_matrix(law: str, b, bd, inertia, k_p: float, k_d: float, rho: float = 2.0, zeta: float = 0.7,
                       r_min: float = 5.0e-4, b_law=None, bd_law=None) -> np.ndarray:
    """6×6 ``A`` of ``d[θ, ω]/dt = A [θ, ω]`` at one instant (field direction ``b``, its rate ``bd``).

    ``law``: ``"seed_pd"`` (``τ = −K_p θ/2 − K_d ω``) or ``"field_steering"`` (the linearisation of
    :func:`detumble.control.magnetic_pointing.field_steering_torque`, whose ``θ`` is ``2 q_err.v``).
    ``b_law``, ``bd_law``: the field direction and rate the law believes (a biased magnetometer), when they
    differ from the true ones (which set the projection).
    """
    p = np.eye(3) - np.outer(np.asarray(b, dtype=float), np.asarray(b, dtype=float))
    b = np.asarray(b if b_law is None else b_law, dtype=float)
    bd = np.asarray(bd if bd_law is None else bd_law, dtype=float)
    if law == "seed_pd":
        k_th, k_w = 0.5 * k_p * np.eye(3), k_d * np.eye(3)
    elif law == "field_steering":
        rn = float(np.linalg.norm(bd))
        r = max(rn, r_min)
        g = bd / rn if rn > 0.0 else np.zeros(3)
        c = 1.0 + rho * rho
        # s = s_th·θ + s_w·ω  with  s = −(2ζρr α + c β)/(2r),  α = b·θ,  β = b·ω − r g·θ
        s_th = -(2.0 * zeta * rho * r * b - c * r * g) / (2.0 * r) if rho > 0.0 else np.zeros(3)
        s_w = -(c * b) / (2.0 * r) if rho > 0.0 else np.zeros(3)
        k_th = k_p * np.eye(3) - k_p * np.outer(g, s_th) - k_d * np.outer(bd, b)
        k_w = k_d * np.eye(3) - k_p * np.outer(g, s_w)
    else:
        raise ValueError(f"law must be 'seed_pd' or 'field_steering', got {law!r}")
    j_inv = np.linalg.inv(np.asarray(inertia, dtype=float))
    a = np.zeros((6, 6))
    a[:3, 3:] = np.eye(3)
    a[3:, :3] = -j_inv @ p @ k_th
    a[3:, 3:] = -j_inv @ p @ k_w
    return a


def floquet_rate(law: str, period: float, b_hat, bdot, inertia, k_p: float, k_d: float, substeps: int = 8,
                 b_law=None, bdot_law=None, **kw) -> float:
    """``log(max |eig Φ(T)|)/T`` (1/s) over the samples of one period (RK4, ``A`` held over each sample).

    ``b_law``, ``bdot_law``: sampled like ``b_hat``: what the law sees, if not the truth (see
    :func:`closed_loop_matrix`)."""
    n = len(b_hat) - 1
    h = period / n / substeps
    phi = np.eye(6)
    for k in range(n):
        a = closed_loop_matrix(law, b_hat[k], bdot[k], inertia, k_p, k_d,
                               b_law=None if b_law is None else b_law[k],
                               bd_law=None if bdot_law is None else bdot_law[k], **kw)
        for _ in range(substeps):
            k1 = a @ phi
            k2 = a @ (phi + 0.5 * h * k1)
            k3 = a @ (phi + 0.5 * h * k2)
            k4 = a @ (phi + h * k3)
            phi = phi + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return math.log(max(abs(np.linalg.eigvals(phi)))) / period


def along_field_offset_from_gravity_gradient(plant, q_target, samples: int = 400):
    """``(t s, α rad)`` over one orbit: the quasi-static error about the field line that the gravity-gradient
    torque forces on a body held at ``q_target``.

    No dipole torque acts along b̂, and for the along-field pair ``β̇ = r² α + τ∥ / J`` whatever the law (its
    control enters ``α̇`` only), so a slowly varying torque along the field, ``τ∥ = τ_gg · b̂``, is met at
    ``α = −τ∥ / (J r²)``: the along-field stiffness is ``J r²`` (≈ 8e-9 N·m/rad here), set by how fast the field
    line turns, not by the gains. ``J`` is the mean principal moment (kg·m²), ``τ_gg = 3 μ/R³ r̂ × (J r̂)`` in the
    target frame, with the 3 μ/R³ the plant's orbit flies (``gravity_gradient_coeff``)."""
    period, b, bd = field_line_along_orbit(plant, q_target, samples)
    inertia = np.asarray(plant.scenario.spacecraft.inertia_kg_m2, dtype=float)
    j_mean = float(np.trace(inertia)) / 3.0
    r_tn = _dcm(q_target)
    ts = np.linspace(0.0, period, samples + 1)
    alpha = np.empty(len(ts))
    for k, t in enumerate(ts):
        r = plant.orbit.position_N(t)
        r_n = np.array(r, dtype=float)
        rh = r_tn @ (r_n / float(np.linalg.norm(r_n)))
        tau = plant.orbit.gravity_gradient_coeff(r) * np.cross(rh, inertia @ rh)
        rate = float(np.linalg.norm(bd[k]))
        alpha[k] = -float(tau @ b[k]) / (j_mean * rate * rate)
    return ts, alpha
