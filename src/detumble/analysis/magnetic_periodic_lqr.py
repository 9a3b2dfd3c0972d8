"""Periodic LQR of magnetorquer-only pointing over the orbit's field: how fast ANY linear coil law with perfect
knowledge of ``B(t)`` can make the linearised hold decay, and at what peak dipole (numpy; analysis only).

The plant is magnetic_floquet's linearisation about an inertially fixed target — small errors ``θ`` (rad) and
rates ``ω`` (rad/s) in the target frame, ``θ̇ = ω``, ``J ω̇ = m × B(t)`` — but with the dipole ``m`` (A·m², target
frame ≈ body frame in the hold) as the input and the field ``B(t)`` (T, target frame) with its magnitude, so that
the input matrix is ``[0; −J⁻¹ [B×]]`` and the dipole along ``B`` does nothing (the quadratic cost makes the optimal
``m`` ⟂ ``B``). The loop is sampled: the dipole is held over each of the orbit's ``N`` samples (step ``h`` s), the
field held at the sample's value, which makes the step exact (``A_d = [[I, hI], [0, I]]``,
``B_d = [h²/2 G; h G]``, ``G = −J⁻¹ [B×]``). The discrete periodic Riccati recursion

    ``P_k = Q h + Â_kᵀ P_{k+1} Â_k − Â_kᵀ P_{k+1} B̂_k (R h + B̂_kᵀ P_{k+1} B̂_k)⁻¹ B̂_kᵀ P_{k+1} Â_k``

is run backward over the orbit, orbit after orbit, until ``P_0`` repeats; ``Â = e^{αh} A_d``, ``B̂ = e^{αh} B_d``
(the α-shift: the gains stabilise the shifted loop, so the true loop decays at least at ``α`` /s). The gains
``K_k = (R h + B̂ᵀ P B̂)⁻¹ B̂ᵀ P Â`` (``m = −K_k x``) give the closed loop's monodromy, whose slowest Floquet rate
(``log max |eig| / T``, 1/s) and peak dipole from a given initial error are the figures. With ``Q h``, ``R h`` the
recursion tends to the continuous Riccati equation as ``h → 0`` (in a constant field, the algebraic one).
"""

from __future__ import annotations

import math

import numpy as np

from detumble.analysis.magnetic_floquet import _dcm

__all__ = ["field_vector_along_orbit", "sampled_double_integrator", "periodic_riccati_gains", "closed_loop_rate",
           "peak_dipole_ratio"]


def field_vector_along_orbit(plant, q_target, samples: int = 1000, bias_t=(0.0, 0.0, 0.0)):
    """``(period s, B samples×3 T)``: the field in the target frame at the start of each of ``samples`` equal steps
    of one orbit of ``plant`` (a :class:`detumble.sim.plant.Plant`); ``bias_t`` (T, target frame) added: what a law
    holding the target sees through a magnetometer with that bias."""
    period = 2.0 * math.pi / plant.orbit.mean_motion
    r_tn = _dcm(q_target)
    ts = np.arange(samples) * (period / samples)
    b = np.array([r_tn @ np.array(plant.field.b_N(t, plant.orbit.position_N(t))) for t in ts])
    return period, b + np.asarray(bias_t, dtype=float)[None, :]


def _skew(v) -> np.ndarray:
    x, y, z = (float(c) for c in v)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def sampled_double_integrator(b_t, inertia, h: float):
    """``(A_d 6×6, B_d 6×3)`` of one step ``h`` (s) of ``[θ, ω]`` with the dipole (A·m²) held in the field ``b_t``
    (T): exact for the held field."""
    g = -np.linalg.solve(np.asarray(inertia, dtype=float), _skew(b_t))
    a = np.eye(6)
    a[:3, 3:] = h * np.eye(3)
    b = np.vstack([0.5 * h * h * g, h * g])
    return a, b


def periodic_riccati_gains(a_seq, b_seq, q, r, h: float, alpha: float = 0.0, tol: float = 1e-9,
                           max_periods: int = 400):
    """``(K list of m×n, P_0 n×n, periods run)``: the periodic LQR gains of the sampled loop ``x_{k+1} = A_k x_k +
    B_k u_k`` (``u_k = −K_k x_k``, period ``len(a_seq)`` samples of ``h`` s), weights ``Q h``, ``R h``, shifted by
    ``α`` (1/s). Backward recursion over whole periods until ``P_0`` changes by less than ``tol`` relative to its
    norm; raises :class:`ArithmeticError` if it has not converged after ``max_periods`` periods (the shifted loop is
    not stabilisable: no such gain exists) or overflows."""
    q_h = np.asarray(q, dtype=float) * h
    r_h = np.asarray(r, dtype=float) * h
    s = math.exp(alpha * h)
    a_hat = [s * np.asarray(a, dtype=float) for a in a_seq]
    b_hat = [s * np.asarray(b, dtype=float) for b in b_seq]
    n = len(a_hat)
    p = q_h.copy()
    gains: list[np.ndarray] = [np.zeros((r_h.shape[0], q_h.shape[0]))] * n
    last = None
    for period in range(1, max_periods + 1):
        for k in range(n - 1, -1, -1):
            a, b = a_hat[k], b_hat[k]
            pa, pb = p @ a, p @ b
            gain = np.linalg.solve(r_h + b.T @ pb, pb.T @ a)
            p = q_h + a.T @ pa - pa.T @ b @ gain
            p = 0.5 * (p + p.T)
            gains[k] = gain
        if not np.all(np.isfinite(p)):
            raise ArithmeticError("the periodic Riccati recursion overflowed: no stabilising gain at this α")
        if last is not None and np.linalg.norm(p - last) <= tol * np.linalg.norm(p):
            return gains, p, period
        last = p.copy()
    raise ArithmeticError(f"the periodic Riccati recursion did not converge in {max_periods} periods")


def closed_loop_rate(a_seq, b_seq, gains, period_s: float) -> float:
    """Slowest Floquet rate (1/s; negative decays) of ``x_{k+1} = (A_k − B_k K_k) x_k`` over one period: ``b_seq``
    is the true input (the plant's field), ``gains`` may come from another field (the law's). ``inf`` if the
    monodromy grows past the floats within the period."""
    phi = np.eye(len(a_seq[0]))
    with np.errstate(all="ignore"):
        for a, b, k in zip(a_seq, b_seq, gains, strict=True):
            phi = (a - b @ k) @ phi
    if not np.all(np.isfinite(phi)):
        return math.inf
    return math.log(max(abs(np.linalg.eigvals(phi)))) / period_s


def peak_dipole_ratio(a_seq, b_seq, gains, x0, m_max, start: int = 0, periods: int = 2):
    """``(max_k max_i |m_i| / m_max_i, max |m| A·m²)``: the closed loop flown from ``x0`` at sample ``start`` for
    ``periods`` periods; ``m_max`` the per-axis capacity (A·m²). Above 1: the linear law asks more than the coils."""
    n = len(a_seq)
    cap = np.asarray(m_max, dtype=float)
    x = np.asarray(x0, dtype=float)
    ratio, peak = 0.0, 0.0
    for j in range(periods * n):
        k = (start + j) % n
        m = -gains[k] @ x
        ratio = max(ratio, float(np.max(np.abs(m) / cap)))
        peak = max(peak, float(np.linalg.norm(m)))
        x = a_seq[k] @ x + b_seq[k] @ m
    return ratio, peak
