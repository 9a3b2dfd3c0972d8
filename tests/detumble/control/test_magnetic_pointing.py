"""Magnetorquer-only pointing (detumble.control.magnetic_pointing) against closed forms.

The test field is the simplest one that turns: its inertial direction rotates in the x–y plane at a
constant rate ``r`` (rad/s), ``b̂_N(t) = (cos rt, sin rt, 0)``. The body is isotropic (2.2e-3 kg·m²),
the target the identity, the torque exactly the requested one's part ⟂ B (an ideal projection), RK4
at 1 s. Decay and growth rates in 1/s are fitted on the error's envelope (its largest value in
±200 s windows) between two times.
"""

import math

import pytest

from detumble.control.magnetic_pointing import (FieldDirectionRate, field_steering_torque, scheduled_rho,
                                               slow_pole_rate)
from detumble.control.pointing import pd_torque
from detumble.control.quaternion import quat_angle, quat_from_axis_angle, quat_mul, rotate_n_to_b
from detumble.sim.attitude import RigidBody

J = 2.2e-3  # kg·m²
R = 2.0e-3  # rad/s, about 2 n in LEO
TARGET = (1.0, 0.0, 0.0, 0.0)


def fly(law, duration_s, theta0_deg=1.0, axis=(1.0, 0.0, 0.0), **gains):
    """[(t s, error rad)] for ``law`` "steer" (field_steering_torque) or "pd" (seed 003's PD)."""
    body = RigidBody(((J, 0.0, 0.0), (0.0, J, 0.0), (0.0, 0.0, J)))
    q = quat_from_axis_angle(axis, math.radians(theta0_deg))
    s = (*q, 0.0, 0.0, 0.0)
    out = []
    for k in range(int(duration_s)):
        t = float(k)
        b_n = (math.cos(R * t), math.sin(R * t), 0.0)
        bd_n = (-R * math.sin(R * t), R * math.cos(R * t), 0.0)
        q, w = s[:4], s[4:]
        b, bd = rotate_n_to_b(q, b_n), rotate_n_to_b(q, bd_n)
        if law == "steer":
            tau, _ = field_steering_torque(TARGET, q, w, b, bd, **gains)
        else:
            tau, _ = pd_torque(TARGET, q, w, gains["k_p"], gains["k_d"])
        a = sum(tau[i] * b[i] for i in range(3))
        s = body.step(s, 1.0, tuple(tau[i] - a * b[i] for i in range(3)))
        out.append((t + 1.0, quat_angle(s[:4])))
    return out


def rate(trace, t1, t2):
    """Growth rate (1/s; negative = decay) of the envelope between t1 and t2."""
    def env(tc):
        return max(e for t, e in trace if tc - 200 <= t < tc + 200)
    return math.log(env(t2) / env(t1)) / (t2 - t1)


def test_the_along_field_pair_decays_at_zeta_rho_r():
    """MAGPT-001: with ρ = 1, ζ = 0.7 the error decays at the closed-form rate ζ ρ r of the along-field pair
    (1.40e-3 /s) within 15 % for two ⟂-loop gain sets (measured 1.36e-3 and 1.25e-3 /s: the closed form takes
    the ⟂ loop as infinitely fast, and K_D = 1e-4 N·m·s makes it overdamped)."""
    for kd in (4.0e-5, 1.0e-4):
        trace = fly("steer", 3000, k_p=1.0e-6, k_d=kd, rho=1.0, zeta=0.7)
        assert -rate(trace, 1000, 2500) == pytest.approx(slow_pole_rate(R, 1.0, 0.7), rel=0.15)


def test_without_steering_the_error_runs_away_at_the_field_line_rate():
    """MAGPT-002: the stiff PD ⟂ B pins the error onto the turning field line, where it grows like a bead on
    a rotating rod, at ≈ r: with ρ = 0 (no steering) the measured growth is within 10 % of r, and seed 003's
    projected PD (same stiffness) grows at 0.7–1.1 r (measured 0.84 r: its D term acts on the rod's own motion)."""
    g0 = rate(fly("steer", 3000, k_p=1.0e-6, k_d=4.0e-5, rho=0.0), 1000, 2500)
    assert g0 == pytest.approx(R, rel=0.10)
    g_seed = rate(fly("pd", 3000, k_p=1.0e-6, k_d=4.0e-5), 1000, 2500)
    assert 0.7 * R < g_seed < 1.1 * R


def test_a_slow_pd_follows_the_averaged_model():
    """MAGPT-003: seed 003's PD with gains 10× below the field line's rate (ε-scaled, ω_n = r/10) follows the
    orbit-averaged linear model ``J θ̈ = −Γ̄ (K_p/2 θ + K_d θ̇)``: for an error about x (⟂ B half the time,
    Γ̄_xx = ½), its slower root decays at −0.382 ω_n = 7.6e-5 /s; measured within 15 %. It is stable, and
    25 times slower than the steering law above."""
    wn = R / 10.0
    gamma = 0.5
    kp = 2.0 * J * wn * wn / gamma
    kd = 2.0 * 1.5 * J * wn / gamma  # ζ = 1.5 on the averaged axis
    predicted = wn * (1.5 - math.sqrt(1.5 ** 2 - 1.0))
    trace = fly("pd", 40000, k_p=kp, k_d=kd)
    assert -rate(trace, 15000, 35000) == pytest.approx(predicted, rel=0.15)


def test_field_direction_rate_is_independent_of_the_body_motion():
    """MAGPT-004: the estimator of db̂_N/dt, fed the field in B of a body turning at 0.5 °/s about an oblique
    axis, returns the inertial field line's rate in B: after 300 s its magnitude within 2 % of |ḃ| = r, its
    direction behind the truth by the tracking filter's lag 2 r / w (closed form for a critically damped
    α-β filter of bandwidth w ≫ r: 4.6° here) within 15 %."""
    est = FieldDirectionRate(0.05)
    axis = (0.3, -0.5, 0.8)
    n = math.sqrt(sum(c * c for c in axis))
    axis = tuple(c / n for c in axis)
    dt = 0.1
    q = (1.0, 0.0, 0.0, 0.0)
    turn = quat_from_axis_angle(axis, math.radians(0.5) * dt)
    bd = None
    for k in range(3000):
        t = k * dt
        b_n = (3e-5 * math.cos(R * t), 3e-5 * math.sin(R * t), 0.0)
        bd = est.update(q, rotate_n_to_b(q, b_n), dt)
        q = quat_mul(q, turn)
    q_last = quat_mul(q, (turn[0], -turn[1], -turn[2], -turn[3]))
    t = 2999 * dt
    truth = rotate_n_to_b(q_last, (-R * math.sin(R * t), R * math.cos(R * t), 0.0))
    assert bd is not None
    nb = math.sqrt(sum(c * c for c in bd))
    assert nb == pytest.approx(R, rel=0.02)
    cosang = sum(a * b for a, b in zip(bd, truth, strict=True)) / (nb * R)
    assert math.acos(min(1.0, cosang)) == pytest.approx(2.0 * R / 0.05, rel=0.15)


def test_field_direction_rate_needs_two_readings_and_a_field():
    """MAGPT-004: no estimate before two readings, none for a zero field or a non-positive step; reset forgets."""
    est = FieldDirectionRate()
    q = (1.0, 0.0, 0.0, 0.0)
    assert est.update(q, (1.0, 0.0, 0.0), 0.1) is None
    assert est.update(q, (0.0, 0.0, 0.0), 0.1) is None
    assert est.update(q, (1.0, 0.0, 0.0), 0.0) is None
    assert est.update(q, (1.0, 0.01, 0.0), 0.1) is not None
    est.reset()
    assert est.update(q, (1.0, 0.0, 0.0), 0.1) is None


def test_no_field_no_torque():
    """MAGPT-005: a zero or non-finite field gives no torque (nothing can be projected) but still the error."""
    q = quat_from_axis_angle((0.0, 1.0, 0.0), 0.3)
    for b in ((0.0, 0.0, 0.0), (math.nan, 0.0, 1.0)):
        tau, qe = field_steering_torque(TARGET, q, (0.0, 0.0, 0.0), b, (0.0, 1e-3, 0.0), 1e-6, 1e-4)
        assert tau == (0.0, 0.0, 0.0)
        assert quat_angle(qe) == pytest.approx(0.3, rel=1e-9)


def test_the_steering_offset_lies_along_the_field_line_motion():
    """MAGPT-005: the offset of the set point is along ĝ = ḃ/|ḃ| and opposes the along-field error: an error α
    about b̂ alone (no rate) asks for a torque whose part beyond the plain spring, −K_p·(−s ĝ), is along ĝ with
    s = −ζ ρ α (closed form, 1e-12 relative)."""
    b = (0.0, 0.0, 1.0)
    bd = (R, 0.0, 0.0)
    alpha = 0.02
    q = quat_from_axis_angle(b, alpha)
    kp, rho, zeta = 1e-6, 2.0, 0.7
    tau, _ = field_steering_torque(TARGET, q, (0.0, 0.0, 0.0), b, bd, kp, 0.0, rho, zeta)
    th = 2.0 * math.sin(alpha / 2.0)
    s = -(2.0 * zeta * rho * R * th) / (2.0 * R)
    assert tau[0] == pytest.approx(kp * s, rel=1e-12)
    assert tau[1] == 0.0
    assert tau[2] == pytest.approx(-kp * th, rel=1e-12)


# --- residual-dipole estimation -----------------------------------------------------------------------

M_RES = (1.0e-3, -5.0e-4, 8.0e-4)  # A·m², the adcs scenario's residual dipole
J_FULL = ((2.20e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.05e-3))


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def estimate_residual(duration_s, m_res=M_RES, gyro_sigma=2.0e-4, field_tilt=0.3, seed=5, dt=0.5):
    """Fly a body (the adcs inertia) at rest-ish under its residual dipole plus random known coil dipoles
    (±5e-3 A·m², changed every 10 s) in a 30 µT field turning at R in N (tilted out of the x–y plane by
    ``field_tilt``); feed the estimator the true rate plus white noise ``gyro_sigma`` rad/s and the known coil
    torque. Returns the estimator."""
    import random

    from detumble.control.magnetic_pointing import ResidualDipoleEstimator

    rng = random.Random(seed)
    body = RigidBody(J_FULL)
    s = (1.0, 0.0, 0.0, 0.0, 1e-4, -2e-4, 1e-4)
    est = ResidualDipoleEstimator(J_FULL, window_s=60.0)
    m_cmd = (0.0, 0.0, 0.0)
    for k in range(int(duration_s / dt)):
        t = k * dt
        if k % int(10.0 / dt) == 0:
            m_cmd = tuple(rng.uniform(-5e-3, 5e-3) for _ in range(3))
        b_n = (3e-5 * math.cos(R * t), 3e-5 * math.sin(R * t), 3e-5 * field_tilt)
        b = rotate_n_to_b(s[:4], b_n)
        tau_cmd = _cross(m_cmd, b)
        tau_res = _cross(m_res, b)
        s = body.step(s, dt, tuple(tau_cmd[i] + tau_res[i] for i in range(3)))
        w = tuple(s[4 + i] + rng.gauss(0.0, gyro_sigma) for i in range(3))
        est.update(w, tau_cmd, (0.0, 0.0, 0.0), b, dt)
    return est


def test_residual_dipole_estimate_converges_to_the_true_dipole():
    """MAGPT-030: the torque-balance estimator recovers a constant residual dipole of 1.37e-3 A·m² under known coil
    torques ±1.5e-7 N·m (4× the residual's) and gyro noise 2e-4 rad/s per reading: no estimate before 10 windows,
    then within 1.5e-4 A·m² per axis after one orbit (5580 s; closed-form noise ≈ √2 J σ/(|b| T) = 3.5e-4 A·m²
    per 60 s window, 92 windows: ≈ 5e-5 per axis, so 3σ; measured 1.9e-5 at worst); well conditioned (> 0.3;
    measured 0.999) for a field turning in B."""
    early = estimate_residual(500.0)
    assert early.estimate is None and early.windows < 10
    est = estimate_residual(5580.0)
    assert est.estimate is not None
    assert est.conditioning() > 0.3
    assert all(abs(e - m) <= 1.5e-4 for e, m in zip(est.estimate, M_RES, strict=True))


def test_residual_dipole_estimate_without_noise_is_exact_and_needs_a_turning_field():
    """MAGPT-031: without gyro noise the estimate equals the dipole within 1e-7 A·m² (measured 4.4e-8: the RK4 step
    and the field held over it); with a field that does not turn in B (R = 0 here: fixed b̂) nothing along b̂ is
    observable and the estimator gives none (conditioning below its threshold)."""
    est = estimate_residual(3000.0, gyro_sigma=0.0)
    assert est.estimate is not None
    assert all(abs(e - m) <= 1e-7 for e, m in zip(est.estimate, M_RES, strict=True))

    from detumble.control.magnetic_pointing import ResidualDipoleEstimator

    fixed = ResidualDipoleEstimator(J_FULL, window_s=60.0)
    b = (3e-5, 0.0, 1e-5)
    for _ in range(20000):
        fixed.update((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), b, 0.5)
    assert fixed.windows > 100
    assert fixed.conditioning() < 1e-9
    assert fixed.estimate is None


def test_scheduled_rho_ramps_between_the_two_angles():
    """MAGPT-070: ρ scheduled on the error (deg): MAG_STEER_RHO up to the lower angle (12°), the large ρ from the
    upper angle (20°) on, linear between (3 at 16° for 2 → 4); a large ρ of 0 is no schedule at every angle; an upper
    angle at or below the lower one is a step at the lower one."""
    assert scheduled_rho(2.0, 4.0, 5.0, 12.0, 20.0) == 2.0
    assert scheduled_rho(2.0, 4.0, 12.0, 12.0, 20.0) == 2.0
    assert scheduled_rho(2.0, 4.0, 16.0, 12.0, 20.0) == pytest.approx(3.0, abs=1e-12)
    assert scheduled_rho(2.0, 4.0, 20.0, 12.0, 20.0) == 4.0
    assert scheduled_rho(2.0, 4.0, 90.0, 12.0, 20.0) == 4.0
    assert scheduled_rho(2.0, 0.0, 90.0, 12.0, 20.0) == 2.0
    assert scheduled_rho(2.0, 4.0, 12.5, 12.0, 12.0) == 4.0
    assert scheduled_rho(2.0, 4.0, 11.5, 12.0, 12.0) == 2.0


def test_the_scheduled_law_is_the_plain_law_at_the_scheduled_rho():
    """MAGPT-071: field_steering_torque with a large ρ is the unscheduled law at scheduled_rho of its own error
    angle: below the lower angle the torque is the plain law's at MAG_STEER_RHO (bit for bit), above the upper
    angle the plain law's at the large ρ, which differs (the schedule acts)."""
    b, bd, w = (0.3, -0.2, 0.9), (1.5e-3, 1.0e-3, 0.0), (1e-3, -2e-3, 5e-4)
    for angle_deg, rho_used in ((8.0, 2.0), (25.0, 4.0), (16.0, 3.0)):
        q = quat_from_axis_angle((0.36, 0.48, 0.8), math.radians(angle_deg))
        tau, _ = field_steering_torque(TARGET, q, w, b, bd, 4e-6, 4e-4, 2.0, 1.0, 5e-4, 4.0, 12.0, 20.0)
        plain, _ = field_steering_torque(TARGET, q, w, b, bd, 4e-6, 4e-4, rho_used, 1.0, 5e-4)
        assert all(abs(a - e) <= 1e-15 for a, e in zip(tau, plain, strict=True))
        if rho_used != 2.0:
            unscheduled, _ = field_steering_torque(TARGET, q, w, b, bd, 4e-6, 4e-4, 2.0, 1.0, 5e-4)
            assert max(abs(a - e) for a, e in zip(tau, unscheduled, strict=True)) > 1e-9
