"""Spin-stabilisation laws: seed 003's damper as written, the classical 3-axis damper, the rate regulator.

Rates rad/s, torques N·m, inertia kg·m², time s.
"""

import math

import pytest

from detumble.control.spin import SeedKaneDamper, SpinRateRegulator, VirtualDamper, rk4_scalar
from detumble.sim.attitude import RigidBody

#: the default scenario's inertia (ẑ is the minor axis) and a variant whose ẑ is the major axis
MINOR_Z = ((2.20e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.05e-3))
MAJOR_Z = ((2.05e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.40e-3))


def test_seed_damper_matches_its_closed_form():
    """ADCS-005: the seed's ẇ_d = I_d⁻¹(τ·ẑ − c w_d) integrated by RK4 at 0.1 s follows
    w_d(t) = τ/c + (w0 − τ/c) e^(−ct/I_d) to 1e-9 relative over 20 s."""
    d = SeedKaneDamper(c_damp=1e-4, i_d=2e-4)
    d.w_d = 0.05
    tau = (0.0, 0.0, 3e-7)
    for _ in range(200):
        d.update(tau, 0.1)
    exact = 3e-7 / 1e-4 + (0.05 - 3e-7 / 1e-4) * math.exp(-1e-4 * 20.0 / 2e-4)
    assert abs(d.w_d - exact) <= 1e-9 * abs(exact)
    assert d.torque_request() == (0.0, 0.0, -1e-4 * d.w_d)


def test_seed_damper_as_written_never_leaves_rest():
    """ADCS-005: the seed's damper is driven only by the magnetic torque about ẑ, which is zero until it
    asks for one: from rest it requests exactly zero torque for ever, whatever the body does."""
    d = SeedKaneDamper(1e-4, 2e-4)
    for _ in range(1000):
        d.update((0.0, 0.0, d.torque_request()[2]), 0.1)  # it can only feed back its own request
    assert d.torque_request() == (0.0, 0.0, 0.0)


def test_seed_damper_refuses_non_positive_inertia():
    """ADCS-005: I_d ≤ 0 is refused with a message naming I_d."""
    with pytest.raises(ValueError, match="I_d"):
        SeedKaneDamper(1e-4, 0.0)


def test_virtual_damper_matches_its_closed_form():
    """ADCS-006: I_d ω̇_d = c(ω − ω_d) with ω held: ω_d(t) = ω + (ω_d0 − ω) e^(−ct/I_d) per axis, to 1e-7
    relative (RK4 at 0.1 s)."""
    vd = VirtualDamper(1e-4, 2e-4)
    vd.update((0.0, 0.0, 0.0), 0.1)  # first call: ω_d starts at the body rate
    w = (0.1, -0.2, 0.05)
    for _ in range(50):
        vd.update(w, 0.1)
    f = math.exp(-1e-4 * 5.0 / 2e-4)
    for k in range(3):
        assert abs(vd.omega_d[k] - (w[k] + (0.0 - w[k]) * f)) < 1e-7 * abs(w[k])
    tau = vd.torque_request(w)
    assert all(abs(tau[k] + 1e-4 * (w[k] - vd.omega_d[k])) < 1e-18 for k in range(3))


def test_rk4_is_fourth_order():
    """ADCS-005: halving the step divides the RK4 error of ẋ = −x over 1 s by ≈ 16 (between 12 and 20)."""
    def err(n):
        x = 1.0
        for _ in range(n):
            x = rk4_scalar(lambda v: -v, x, 1.0 / n)
        return abs(x - math.exp(-1.0))
    assert 12.0 < err(10) / err(20) < 20.0


@pytest.mark.parametrize("inertia", [MINOR_Z, MAJOR_Z], ids=["z_minor", "z_major"])
def test_rate_regulator_holds_a_spin_about_a_minor_or_major_axis(inertia):
    """ADCS-007: with the full 3-axis torque the regulator takes a 10 °/s tumble to ω = 1.5 °/s ŝ (rate within
    1e-4 relative; momentum within 0.05° of its floor, the tilt atan(|(I_xz, I_yz)|/I_zz) that the products of
    inertia give a spin about body ẑ — the rest is the transverse rate k_t needs to balance ω × Iω) in 600 s,
    for ẑ the
    minor and ẑ the major axis."""
    body = RigidBody(inertia)
    target = math.radians(1.5)
    reg = SpinRateRegulator(2e-4, 2e-4, target)
    w0 = tuple(math.radians(10.0) * c for c in (0.36353657, 0.86429949, 0.34760259))
    state = (1.0, 0.0, 0.0, 0.0) + w0
    for _ in range(6000):
        state = body.step(state, 0.1, reg.torque_request(state[4:]))
    w = state[4:]
    assert abs(w[2] - target) < 1e-4 * target
    h = body.angular_momentum_B(state)
    floor = math.degrees(math.atan2(math.hypot(inertia[0][2], inertia[1][2]), inertia[2][2]))
    assert abs(math.degrees(math.atan2(math.hypot(h[0], h[1]), h[2])) - floor) < 0.05


def test_rate_regulator_torque_is_zero_at_the_target_and_opposes_errors():
    """ADCS-007: τ = 0 at ω = ω_s ŝ; a transverse error gets −k_t ω_⊥, a spin error −k_s (ω_s' − ω_s) ŝ."""
    reg = SpinRateRegulator(2e-4, 3e-4, 0.1, axis=(0.0, 0.0, 2.0))
    assert reg.torque_request((0.0, 0.0, 0.1)) == (0.0, 0.0, 0.0)
    tau = reg.torque_request((0.01, 0.0, 0.12))
    assert abs(tau[0] + 2e-6) < 1e-18 and abs(tau[2] + 3e-4 * 0.02) < 1e-15
