"""Magnetic laws: dipole projection (seed 003's sign fixed), B-dot on measured spacing, momentum dumping.

Field in tesla, torque N·m, dipole A·m², time s.
"""

import random

from detumble.control.magnetic import (bdot_dipole, dump_torque, project_dipole, project_dipole_weighted,
                                       scale_to_limits, seed_project_dipole)
from detumble.sim.vec import cross, dot, norm, sub


def test_a_torque_perpendicular_to_b_is_reproduced_with_its_own_sign():
    """ADCS-003: for τ ⟂ B, m = (B × τ)/|B|² gives m × B = τ exactly (1e-18 N·m); the seed's (τ × B)/|B|²
    gives −τ. This is the sign fix."""
    b = (2.0e-5, -1.0e-5, 3.0e-5)
    tau = cross(b, (1.0, 2.0, -0.5))
    tau = tuple(1e-6 * c / norm(tau) for c in tau)  # 1 µN·m, ⟂ B
    m, lost = project_dipole(tau, b)
    assert norm(sub(cross(m, b), tau)) < 1e-18
    assert norm(lost) < 1e-18
    seed = seed_project_dipole(tau, b)
    assert norm(sub(cross(seed, b), tuple(-c for c in tau))) < 1e-18


def test_the_component_along_b_is_reported_as_not_achievable():
    """ADCS-003: a general τ: m × B is τ's part ⟂ B and the reported loss is its part along B (1e-18 N·m)."""
    rng = random.Random(5)
    for _ in range(50):
        b = tuple(rng.gauss(0, 3e-5) for _ in range(3))
        tau = tuple(rng.gauss(0, 1e-6) for _ in range(3))
        m, lost = project_dipole(tau, b)
        along = dot(tau, b) / dot(b, b)
        assert norm(sub(lost, tuple(along * c for c in b))) < 1e-18
        assert norm(sub(cross(m, b), sub(tau, lost))) < 1e-18
        assert abs(dot(m, b)) < 1e-18  # no useless dipole along B


def test_zero_field_gives_no_dipole():
    """ADCS-003: with B = 0 (or NaN) no dipole is commanded and the whole request is lost."""
    assert project_dipole((1e-6, 0.0, 0.0), (0.0, 0.0, 0.0)) == ((0.0, 0.0, 0.0), (1e-6, 0.0, 0.0))
    assert project_dipole((1e-6, 0.0, 0.0), (float("nan"), 0.0, 0.0))[0] == (0.0, 0.0, 0.0)


def test_bdot_uses_the_measured_spacing():
    """ADCS-004: M = −k (B_n − B_{n−1})/Δt with Δt the readings' own spacing: the same ΔB over twice the
    time gives half the dipole; Δt ≤ 0 gives no dipole."""
    b0, b1 = (0.30, 0.00, 0.40), (0.31, -0.02, 0.40)
    m1 = bdot_dipole(b0, b1, 0.1, 3.0)
    assert all(abs(x - y) < 1e-12 for x, y in zip(m1, (-0.3, 0.6, 0.0), strict=True))
    m2 = bdot_dipole(b0, b1, 0.2, 3.0)
    assert all(abs(2 * x - y) < 1e-12 for x, y in zip(m2, m1, strict=True))
    assert bdot_dipole(b0, b1, 0.0, 3.0) is None
    assert bdot_dipole(b0, b1, -0.1, 3.0) is None


def test_bdot_opposes_the_field_rotation_and_removes_energy():
    """ADCS-004: for a body spinning at ω in a fixed inertial field, Ḃ_B = −ω × B, and the B-dot dipole's
    torque does negative work (τ·ω < 0)."""
    w = (0.2, -0.1, 0.4)
    b = (2e-5, 1e-5, -3e-5)
    dt = 1e-3
    b_next = sub(b, tuple(dt * c for c in cross(w, b)))
    m = bdot_dipole(b, b_next, dt, 1e4)
    assert dot(cross(m, b), w) < 0.0


def test_dumping_torque_lowers_wheel_momentum():
    """ADCS-010: τ = −k (h − h_target): along the excess, with the rate k (1/s); its projection onto the
    plane ⟂ B is what the coils give, and that part still reduces |h| (τ_⊥·h ≤ 0)."""
    h = (1e-3, -2e-3, 5e-4)
    tau = dump_torque(h, 0.01)
    assert tau == (-1e-5, 2e-5, -5e-6)
    b = (2e-5, 1e-5, -3e-5)
    m, lost = project_dipole(tau, b)
    assert dot(cross(m, b), h) < 0.0
    assert dump_torque(h, 0.01, h) == (0.0, 0.0, 0.0)


def test_scale_to_limits_keeps_direction():
    """ADCS-003: a dipole beyond one axis's limit is scaled as a whole (direction kept, that axis at its limit)."""
    m = scale_to_limits((0.2, 0.05, 0.01), (0.1, 0.1, 0.1))
    assert abs(m[0] - 0.1) < 1e-15 and abs(m[1] / m[0] - 0.25) < 1e-12
    assert scale_to_limits((0.01, 0.0, 0.0), (0.1, 0.1, 0.1)) == (0.01, 0.0, 0.0)


def test_weighted_projection_gives_the_same_torque_with_less_of_the_weak_coil():
    """ADCS-003: m_w = m0 + λB gives the same torque as m0 (1e-18 N·m) and minimises Σ(m_i/m_max_i)²: never
    more than m0's, and with Z− at 1/13 of X and Y, a field mostly along z gets ≤ m0's |m_z|."""
    rng = random.Random(6)
    m_max = (0.116, 0.116, 0.0087)
    for _ in range(100):
        b = tuple(rng.gauss(0, 3e-5) for _ in range(3))
        tau = tuple(rng.gauss(0, 1e-6) for _ in range(3))
        m0, lost0 = project_dipole(tau, b)
        mw, lost = project_dipole_weighted(tau, b, m_max)
        assert norm(sub(cross(mw, b), cross(m0, b))) < 1e-18 and lost == lost0
        cost = lambda m: sum((m[k] / m_max[k]) ** 2 for k in range(3))  # noqa: E731
        assert cost(mw) <= cost(m0) * (1 + 1e-12)
    b = (2e-6, -1e-6, 3e-5)
    m0, _ = project_dipole((1e-6, 0.5e-6, 0.0), b)
    mw, _ = project_dipole_weighted((1e-6, 0.5e-6, 0.0), b, m_max)
    assert abs(mw[2]) < abs(m0[2])
