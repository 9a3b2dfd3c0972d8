"""SUNSAFE-010…014: the magnetorquer Sun-safe law and the Sun-vector gyro-bias observer (control.sun_safe), open
loop against closed forms."""

from __future__ import annotations

import math

import pytest

from detumble.control.sun_safe import SPIN_DOWN_FIELD_ANGLE_DEG, SunHold, SunRateBias, spin_down_tip, sun_spin_torque
from detumble.control.sun_vector import propagate_body_vector

DEG = math.pi / 180.0
I_DIAG = ((2.2e-3, 0.0, 0.0), (0.0, 2.15e-3, 0.0), (0.0, 0.0, 2.05e-3))
Z = (0.0, 0.0, 1.0)


def test_bias_observer_recovers_the_bias_across_the_sun_line():
    """SUNSAFE-010: a body at rest, the Sun fixed in B, exact readings at 1 Hz; the gyro reads the bias
    b = (0.3, −0.2, 0.1) °/s. Carrying each reading on ``gyro − b̂`` and folding in the next, b̂ converges to the
    part of b across ŝ (time constant 100 s: after 1500 s within 1e-4 °/s) and leaves the part along ŝ at zero."""
    b = (0.3 * DEG, -0.2 * DEG, 0.1 * DEG)
    s = (0.6, 0.0, 0.8)
    obs = SunRateBias(time_s=100.0)
    for _ in range(1500):
        est = obs.bias
        w = (b[0] - est[0], b[1] - est[1], b[2] - est[2])  # the gyro (true rate 0 + b) less the estimate
        obs.update(s, propagate_body_vector(s, w, 1.0), 1.0)
    along = sum(b[i] * s[i] for i in range(3))
    want = [b[i] - along * s[i] for i in range(3)]
    assert [c / DEG for c in obs.bias] == pytest.approx([c / DEG for c in want], abs=1e-4)
    assert sum(obs.bias[i] * s[i] for i in range(3)) == pytest.approx(0.0, abs=1e-9)
    assert obs.updates == 1500


def test_bias_observer_skips_gaps_and_jumps():
    """SUNSAFE-011: a reading more than max_gap_s after the last, or one that moved more than max_turn_rad from its
    prediction (a gross error, not a bias), changes nothing; a non-positive time constant is refused by name."""
    obs = SunRateBias(max_gap_s=3.0, max_turn_rad=0.1)
    obs.update((0.0, 0.0, 1.0), (0.01, 0.0, 1.0), 5.0)
    obs.update((0.0, 0.0, 1.0), (0.5, 0.0, 0.866), 1.0)
    assert obs.bias == (0.0, 0.0, 0.0) and obs.updates == 0
    with pytest.raises(ValueError, match="time constant"):
        SunRateBias(time_s=0.0)


def test_spin_law_closed_forms():
    """SUNSAFE-012: spinning at ω_s about â = +Z with the Sun on it (principal axes): no torque. The Sun along +X,
    the body spinning: the tip torque ``h_s Ω ŝ⊥`` with ``h_s = I_zz ω_s``, Ω capped; a transverse rate is damped,
    ``−k_t ω⊥``, plus the gyroscopic ``ω × I ω``; a spin error ``k_s (ω_s − ω_z)`` along â; no Sun (eclipse): the same
    without the tip term and θ NaN."""
    ws, kt, ks, kp, cap = 3.0 * DEG, 4e-4, 2e-4, 0.01, 8.0 * DEG
    tau, theta = sun_spin_torque((0.0, 0.0, ws), Z, Z, I_DIAG, ws, kt, ks, kp, cap)
    assert tau == pytest.approx((0.0, 0.0, 0.0), abs=1e-18) and theta == pytest.approx(0.0)
    tau, theta = sun_spin_torque((0.0, 0.0, ws), (1.0, 0.0, 0.0), Z, I_DIAG, ws, kt, ks, kp, cap)
    assert theta == pytest.approx(90.0)
    assert tau == pytest.approx((2.05e-3 * ws * kp * math.pi / 2, 0.0, 0.0), rel=1e-12, abs=1e-18)
    tau, _ = sun_spin_torque((0.0, 0.0, ws), (1.0, 0.0, 0.0), Z, I_DIAG, ws, kt, ks, 1.0, cap)
    assert tau[0] == pytest.approx(2.05e-3 * ws * cap, rel=1e-12)
    w = (0.01, -0.02, 0.8 * ws)
    tau, theta = sun_spin_torque(w, None, Z, I_DIAG, ws, kt, ks, kp, cap)
    iw = (2.2e-3 * w[0], 2.15e-3 * w[1], 2.05e-3 * w[2])
    gyro = (w[1] * iw[2] - w[2] * iw[1], w[2] * iw[0] - w[0] * iw[2], w[0] * iw[1] - w[1] * iw[0])
    want = (-kt * w[0] + gyro[0], -kt * w[1] + gyro[1], ks * 0.2 * ws + gyro[2])
    assert tau == pytest.approx(want, rel=1e-12) and math.isnan(theta)


def test_spin_law_tips_away_from_the_anti_sun():
    """SUNSAFE-013: the Sun exactly opposite â (θ = 180°, no defined ŝ⊥): the law still tips the axis (a torque
    across â of the capped size), it does not stall."""
    ws = 3.0 * DEG
    tau, theta = sun_spin_torque((0.0, 0.0, ws), (0.0, 0.0, -1.0), Z, I_DIAG, ws, 4e-4, 2e-4, 0.01, 8.0 * DEG)
    assert theta == pytest.approx(180.0)
    assert math.hypot(tau[0], tau[1]) == pytest.approx(2.05e-3 * ws * 0.01 * math.pi, rel=1e-12)


def test_spin_down_waits_for_the_sun_held_then_ramps_while_the_field_is_across():
    """SUNSAFE-014: SunHold at 8 Hz (angle 10°, dwell 300 s, 3 → 1.5 °/s at 0.005 °/s²): the acquisition spin until
    θ has stayed ≤ 10° for 300 s, the count restarted by one reading above it or one with no Sun vector (NaN); then
    the command ramps by 0.000625 °/s a cycle only while the field is ≥ SPIN_DOWN_FIELD_ANGLE_DEG from the axis, to
    1.5 °/s and no lower; SUN_HOLD_ANGLE 0 never lowers; reset() starts again."""
    dt, across, along = 0.125, 0.0, math.cos(math.radians(SPIN_DOWN_FIELD_ANGLE_DEG - 1.0))
    h = SunHold()

    def run(seconds, theta, cos_b=across, angle=10.0):
        out = 3.0
        for _ in range(int(round(seconds / dt))):
            out = h.spin(theta, dt, 3.0, 1.5, angle, 300.0, 0.005, cos_b)
        return out

    assert run(299.0, 9.9) == 3.0 and not h.lowered
    assert run(1.0, 10.5) == 3.0 and h.held_s == 0.0  # broken: the count restarts
    assert run(200.0, 5.0) == 3.0 and run(0.1, math.nan) == 3.0 and h.held_s == 0.0  # eclipse breaks it too
    assert run(299.875, 5.0) == 3.0 and not h.lowered
    step = 0.005 * dt
    assert run(dt, 5.0) == pytest.approx(3.0 - step) and h.lowered  # the 300th second: lowering begins
    assert run(10.0, 5.0, cos_b=along) == pytest.approx(3.0 - step)  # field near the axis: the ramp waits
    assert run(10.0, 5.0, cos_b=None) == pytest.approx(3.0 - step)  # no field reading: it waits
    assert run(10.0, 40.0, cos_b=-across) == pytest.approx(3.0 - step - 0.05)  # latched: θ no longer matters
    assert run(1000.0, 5.0) == 1.5 and h.command_deg_s == 1.5
    h.reset()
    assert not h.lowered and h.command_deg_s is None and h.held_s == 0.0
    assert run(1000.0, 0.0, angle=0.0) == 3.0 and not h.lowered


def test_spin_down_field_gate_is_the_given_angle():
    """SUNSAFE-030: SunHold's ramp opens at ``field_angle_deg`` (SUN_HOLD_FIELD_ANGLE), not at a fixed 80°: once
    lowering has begun, a field 1° closer to the axis than the gate holds the command, 1° farther lets it ramp; the
    default argument is SPIN_DOWN_FIELD_ANGLE_DEG (80°)."""
    dt = 0.125
    for gate in (60.0, 80.0, 85.0):
        h = SunHold()
        across, near = (math.cos(math.radians(gate + d)) for d in (1.0, -1.0))  # 1° past the gate, 1° short
        for _ in range(int(round(1.0 / dt))):
            h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, 0.005, across, gate)
        assert h.lowered and h.command_deg_s == pytest.approx(3.0 - 0.005 * dt)
        assert h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, 0.005, near, gate) == pytest.approx(3.0 - 0.005 * dt)
        assert h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, 0.005, -across, gate) == pytest.approx(3.0 - 2 * 0.005 * dt)
    h = SunHold()
    h.spin(5.0, dt, 3.0, 1.5, 10.0, 0.0, 0.005, math.cos(math.radians(79.0)))
    assert h.lowered and h.command_deg_s == 3.0  # the default gate: 79° waits
    assert SPIN_DOWN_FIELD_ANGLE_DEG == 80.0


def test_the_spin_down_tip_is_the_projected_spin_torque_across_the_axis():
    """SUNSAFE-033: ``spin_down_tip`` against the closed form: the spin torque −â projected ⟂ B, ``−(â − cos β B̂)``,
    has its part across â along ``cos β B̂⊥â``; with B 30° from +Z in the x–z plane that is +x, so a Sun 5° toward
    +x is ahead (sin σ = sin 5°) and one toward −x behind; tan β = tan 30°; B along or across â gives None."""
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    b = (2e-5 * s, 0.0, 2e-5 * c)
    tau = [-(Z[i] - c * b[i] / 2e-5) for i in range(3)]  # −â projected ⟂ B̂
    assert tau[0] > 0.0 and tau[1] == 0.0  # across â: along +x
    sun_ahead = (math.sin(math.radians(5.0)), 0.0, math.cos(math.radians(5.0)))
    ahead, tan_b = spin_down_tip(Z, b, sun_ahead)
    assert ahead == pytest.approx(math.sin(math.radians(5.0)), rel=1e-12)
    assert tan_b == pytest.approx(math.tan(math.radians(30.0)), rel=1e-12)
    assert spin_down_tip(Z, b, (-sun_ahead[0], 0.0, sun_ahead[2]))[0] == pytest.approx(-math.sin(math.radians(5.0)))
    b_down = (-b[0], 0.0, -b[2])  # the field reversed: the same tip (it is quadratic in B̂)
    assert spin_down_tip(Z, b_down, sun_ahead)[0] == pytest.approx(ahead, rel=1e-12)
    assert spin_down_tip(Z, (0.0, 0.0, 3e-5), sun_ahead) is None
    assert spin_down_tip(Z, (3e-5, 0.0, 0.0), sun_ahead) is None


def test_the_spin_down_ramps_outside_the_gate_only_toward_the_sun():
    """SUNSAFE-034: with SUN_HOLD_TIP_ANGLE 1° and the field 30° from the axis (gate closed), once lowering has begun
    the command ramps at ``ramp × tan 30°`` while the Sun is ≥ 1° ahead along the tip, waits when it is 0.5° ahead
    or behind, and with SUN_HOLD_TIP_ANGLE 0 waits whatever the Sun does."""
    dt, ramp = 0.125, 0.005
    cos_b = math.cos(math.radians(30.0))
    tan_b = math.tan(math.radians(30.0))
    h = SunHold()
    for _ in range(8):
        h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, ramp, math.cos(math.radians(85.0)))
    start = h.command_deg_s
    assert h.lowered and start == pytest.approx(3.0 - ramp * dt)
    ahead = (math.sin(math.radians(2.0)), tan_b)
    assert h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, ramp, cos_b, 80.0, ahead, 1.0) == pytest.approx(
        start - ramp * dt * tan_b, rel=1e-12)
    now = h.command_deg_s
    for tip in ((math.sin(math.radians(0.5)), tan_b), (-math.sin(math.radians(2.0)), tan_b), None):
        assert h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, ramp, cos_b, 80.0, tip, 1.0) == now
    assert h.spin(5.0, dt, 3.0, 1.5, 10.0, 1.0, ramp, cos_b, 80.0, ahead, 0.0) == now
