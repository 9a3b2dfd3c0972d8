"""Periodic LQR of the magnetorquer hold (detumble.analysis.magnetic_periodic_lqr): the periodic Riccati recursion
against the algebraic Riccati equation's closed form in a constant field, the α-shift, and the along-field pair that
a constant field cannot reach."""

import math

import numpy as np
import pytest

from detumble.analysis.magnetic_periodic_lqr import (
    closed_loop_rate,
    peak_dipole_ratio,
    periodic_riccati_gains,
    sampled_double_integrator,
)


def _double_integrator(g: float, h: float, n: int):
    """``n`` samples (step ``h`` s) of ``ẍ = g u`` with ``u`` held: the constant field's periodic sequence."""
    a = np.array([[1.0, h], [0.0, 1.0]])
    b = np.array([[0.5 * h * h * g], [h * g]])
    return [a] * n, [b] * n


def _care_double_integrator(g: float, q1: float, q2: float, r: float):
    """Closed form of ``AᵀP + PA − P B R⁻¹ Bᵀ P + Q = 0`` for ``A = [[0, 1], [0, 0]]``, ``B = [0; g]``,
    ``Q = diag(q1, q2)``, ``R = r``: ``p12 = √(q1 r)/g``, ``p22 = √(r (2 p12 + q2))/g``, ``p11 = g² p12 p22 / r``."""
    p12 = math.sqrt(q1 * r) / g
    p22 = math.sqrt(r * (2.0 * p12 + q2)) / g
    return np.array([[g * g * p12 * p22 / r, p12], [p12, p22]])


def test_constant_field_gives_the_algebraic_riccati_solution_and_its_eigenvalues():
    """MAGPT-100: a constant input matrix (a field that does not turn): the periodic recursion's P and gain are the
    continuous algebraic Riccati equation's closed form within 0.5 % (step 1 ms), and the closed loop's Floquet rate
    is the real part of the continuous closed loop's eigenvalues (s² + g k₂ s + g k₁) within 0.5 %."""
    g, q1, q2, r, h = 2.0, 3.0, 0.5, 0.7, 1.0e-3
    a_seq, b_seq = _double_integrator(g, h, 1000)
    gains, p, _ = periodic_riccati_gains(a_seq, b_seq, np.diag([q1, q2]), np.array([[r]]), h, max_periods=200)
    exact = _care_double_integrator(g, q1, q2, r)
    assert p == pytest.approx(exact, rel=5e-3)
    k_exact = g / r * exact[1]
    assert gains[0][0] == pytest.approx(k_exact, rel=5e-3)
    eig = np.roots([1.0, g * k_exact[1], g * k_exact[0]])
    rate = closed_loop_rate(a_seq, b_seq, gains, 1000 * h)
    assert rate == pytest.approx(max(eig.real), rel=5e-3)


def test_the_alpha_shift_makes_the_loop_decay_at_least_at_alpha():
    """MAGPT-101: the same loop with the α-shift (2 /s, well beyond the unshifted −1.3 /s) decays faster than α; the
    unshifted one does not."""
    g, h = 2.0, 1.0e-3
    a_seq, b_seq = _double_integrator(g, h, 1000)
    q, r = np.diag([3.0, 0.5]), np.array([[0.7]])
    plain, _, _ = periodic_riccati_gains(a_seq, b_seq, q, r, h, max_periods=200)
    shifted, _, _ = periodic_riccati_gains(a_seq, b_seq, q, r, h, alpha=2.0, max_periods=200)
    assert closed_loop_rate(a_seq, b_seq, plain, 1.0) > -2.0
    assert closed_loop_rate(a_seq, b_seq, shifted, 1.0) < -2.0


def test_a_field_that_does_not_turn_leaves_the_along_field_pair_uncontrollable():
    """MAGPT-102: with the dipole as input and a constant field along z, no gain holds the error about z (the
    recursion does not converge); the x and y pairs, reached through ``m × B``, have the double integrator's closed
    form with ``g = |B| / J`` once the z pair is let go (α = −0.05 /s shifts it stable); the peak dipole from an
    error about x is the gain's first step, and it is ⟂ B."""
    field, inertia, h, n = np.array([0.0, 0.0, 3.0e-5]), np.diag([2e-3, 2e-3, 2e-3]), 0.5, 200
    step = sampled_double_integrator(field, inertia, h)
    a_seq, b_seq = [step[0]] * n, [step[1]] * n
    q, r = np.diag([1.0] * 3 + [100.0] * 3), np.eye(3) * 1e6
    with pytest.raises(ArithmeticError):
        periodic_riccati_gains(a_seq, b_seq, q, r, h, max_periods=40)
    gains, _, _ = periodic_riccati_gains(a_seq, b_seq, q, r, h, alpha=-0.05, max_periods=400)
    shifted = _double_integrator(1.5e-2, h, n)  # the x pair alone, shifted by the same α
    pair, _, _ = periodic_riccati_gains(shifted[0], shifted[1], np.diag([1.0, 100.0]), np.array([[1e6]]), h,
                                        alpha=-0.05, max_periods=400)
    # θx is driven by m_y alone (τx = (m × B)x = m_y B_z, g = B_z / J): K's (y, [θx, ωx]) entries are the pair's gain
    assert gains[0][1, [0, 3]] == pytest.approx(pair[0][0], rel=1e-6)
    m = -gains[0] @ np.array([0.1, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert abs(m @ field) < 1e-12 * np.linalg.norm(m) * np.linalg.norm(field)
    ratio, peak = peak_dipole_ratio(a_seq, b_seq, gains, [0.1, 0, 0, 0, 0, 0], [1.0, 1.0, 1.0])
    assert peak == pytest.approx(np.linalg.norm(m), rel=1e-12)
    assert ratio == pytest.approx(np.max(np.abs(m)), rel=1e-12)
