"""PD pointing (seed 003): τ = −K_p q_err.v − K_d ω with the shortest-path error.

Angles rad (deg where named), torque N·m, inertia kg·m², time s.
"""

import math

import pytest

from detumble.control.pointing import ErrorIntegrator, pd_gains, pd_torque
from detumble.control.quaternion import quat_angle, quat_error, quat_from_axis_angle, quat_mul
from detumble.sim.attitude import RigidBody


def test_torque_restores_and_follows_the_seed_formula():
    """ADCS-008: B turned +φ about x from the target gets τ_x = −K_p sin(φ/2) − K_d ω_x (the seed's law)."""
    q_t = quat_from_axis_angle((0.0, 0.0, 1.0), 0.5)
    phi = 0.2
    q = quat_mul(q_t, quat_from_axis_angle((1.0, 0.0, 0.0), phi))
    tau, qe = pd_torque(q_t, q, (0.01, 0.0, 0.0), 1e-3, 2e-3)
    assert abs(tau[0] - (-1e-3 * math.sin(phi / 2) - 2e-3 * 0.01)) < 1e-15
    assert abs(tau[1]) < 1e-15 and abs(tau[2]) < 1e-15


def test_shortest_path_turns_the_short_way():
    """ADCS-002: an attitude 300° about x from the target (= −60°) is driven through −60°: the torque is +x;
    without the flip the seed's raw q_err would push −x, the 300° way round."""
    q = quat_from_axis_angle((1.0, 0.0, 0.0), math.radians(300))
    tau, qe = pd_torque((1.0, 0.0, 0.0, 0.0), q, (0.0, 0.0, 0.0), 1e-3, 0.0)
    assert tau[0] > 0.0
    raw = quat_mul((1.0, 0.0, 0.0, 0.0), q)  # q_target⁻¹ ⊗ q without the flip
    assert -1e-3 * raw[1] < 0.0


def test_closed_loop_slew_matches_the_second_order_design():
    """ADCS-008: about a principal axis (I = 2.2e-3), pd_gains(ω_n = 0.35, ζ = 0.9) gives a 90° slew that is
    within 0.1° after 30 s; the peak overshoot is within 1° of the linear ζ = 0.9 value (0.15 % of 90°)."""
    i = 2.2e-3
    kp, kd = pd_gains(i, 0.35, 0.9)
    body = RigidBody(((i, 0, 0), (0, i, 0), (0, 0, i)))
    q_t = quat_from_axis_angle((0.0, 1.0, 0.0), math.pi / 2)
    state = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    worst_after = 0.0
    overshoot = 0.0
    for k in range(600):
        tau, qe = pd_torque(q_t, state[:4], state[4:], kp, kd)
        state = body.step(state, 0.1, tau)
        err = math.degrees(quat_angle(quat_error(q_t, state[:4])))
        if k * 0.1 >= 30.0:
            worst_after = max(worst_after, err)
        if qe[2] > 0.0:  # past the target
            overshoot = max(overshoot, err)
    assert worst_after < 0.1
    linear = 90.0 * math.exp(-0.9 * math.pi / math.sqrt(1 - 0.81))
    assert abs(overshoot - linear) < 1.0


def test_gains_formula():
    """ADCS-008: K_p = 2 I ω_n², K_d = 2 ζ I ω_n (the spring of −K_p q_err.v is K_p/2 per radian)."""
    assert pd_gains(2.0, 0.5, 0.7) == (2 * 2.0 * 0.25, 2 * 0.7 * 2.0 * 0.5)


def test_rate_limit_caps_the_slew_rate_and_leaves_the_seed_law_below_it():
    """ADCS-008: with rate_limit the commanded rate of a 120° slew is capped: the closed-loop rate never exceeds
    the limit by more than 5 %; for a 2° error (below the cap) the torque equals the seed's law to 1e-18 N·m."""
    i = 2.2e-3
    kp, kd = pd_gains(i, 0.35, 0.9)
    body = RigidBody(((i, 0, 0), (0, i, 0), (0, 0, i)))
    q_t = quat_from_axis_angle((0.0, 0.0, 1.0), math.radians(120))
    state = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    limit = math.radians(3.0)
    peak = 0.0
    for _ in range(1200):
        tau, _ = pd_torque(q_t, state[:4], state[4:], kp, kd, rate_limit=limit)
        state = body.step(state, 0.1, tau)
        peak = max(peak, math.sqrt(sum(w * w for w in state[4:])))
    assert peak <= 1.05 * limit
    assert math.degrees(quat_angle(quat_error(q_t, state[:4]))) < 0.1
    q = quat_from_axis_angle((0.0, 1.0, 0.0), math.radians(2))
    w = (0.001, -0.002, 0.0005)
    tau, qe = pd_torque((1.0, 0.0, 0.0, 0.0), q, w, kp, kd, rate_limit=limit)
    assert all(abs(tau[k] - (-kp * qe[k + 1] - kd * w[k])) < 1e-18 for k in range(3))


def test_integral_removes_the_pd_offset_under_a_constant_disturbance():
    """ADCS-008: a constant 5e-8 N·m disturbance holds the PD alone d/(K_p/2) ≈ 0.011° off (to 2 %); with the
    integrator (K_i = 0.05 K_p) the offset after 400 s is below 1 % of that."""
    i = 2.2e-3
    kp, kd = pd_gains(i, 0.35, 0.9)
    body = RigidBody(((i, 0, 0), (0, i, 0), (0, 0, i)))
    d = (5e-8, 0.0, 0.0)

    def fly(k_i):
        integ = ErrorIntegrator(math.radians(1.0), 1e-5)
        state = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        for _ in range(4000):
            tau, qe = pd_torque((1.0, 0.0, 0.0, 0.0), state[:4], state[4:], kp, kd)
            ti = integ.update(qe, 0.1, k_i)
            state = body.step(state, 0.1, tuple(tau[k] + ti[k] + d[k] for k in range(3)))
        return quat_angle(state[:4])

    offset = fly(0.0)
    assert offset == pytest.approx(d[0] / (kp / 2), rel=0.02)
    assert fly(0.05 * kp) < 0.01 * offset


def _slow_root(i, kp, kd, ki):
    """The real root of ``I s³ + K_D s² + (K_P/2) s + K_I/2`` (1/s): Newton from 0 (the one nearest it)."""
    s = 0.0
    for _ in range(60):
        f = ((i * s + kd) * s + kp / 2) * s + ki / 2
        s -= f / ((3 * i * s + 2 * kd) * s + kp / 2)
    return s


def test_integral_tail_after_an_approach_is_the_slow_root_and_the_window_bounds_it():
    """ADCS-130: the defaults' PID (K_P 1.1e-3, K_D 2e-3, K_I 5.5e-5, I = 2.2e-3) from 0.9° at rest, control at
    10 Hz. Whatever the integral state ``z = ∫ q_err.v dt`` holds once the PD's fast modes are gone leaves an error
    ``θ = −K_I z / (K_P/2 + K_D s₁ + I s₁²)`` decaying at the slow root s₁ of ``I s³ + K_D s² + (K_P/2) s + K_I/2``
    (−0.064/s: a 16 s time constant; docs/studies/robust_rates.md): checked from 25 s to 40 s to 3 %. The approach
    itself fills z when the window is 1° (the tail at 25 s is over 0.05°); with a 0.1° window it is under a tenth
    of that."""
    i = 2.2e-3
    kp, kd, ki = 1.1e-3, 2.0e-3, 5.5e-5
    s1 = _slow_root(i, kp, kd, ki)
    assert -0.07 < s1 < -0.06
    body = RigidBody(((i, 0, 0), (0, i, 0), (0, 0, i)))

    def fly(window_deg):
        integ = ErrorIntegrator(math.radians(window_deg), 1e-5)
        state = (math.cos(math.radians(0.45)), math.sin(math.radians(0.45)), 0.0, 0.0, 0.0, 0.0, 0.0)
        out = {}
        for k in range(400):
            tau, qe = pd_torque((1.0, 0.0, 0.0, 0.0), state[:4], state[4:], kp, kd)
            ti = integ.update(qe, 0.1, ki)
            state = body.step(state, 0.1, (tau[0] + ti[0], tau[1] + ti[1], tau[2] + ti[2]))
            out[k + 1] = (2.0 * math.atan2(state[1], state[0]), integ.state[0])  # signed angle about x, z
        return out

    wide = fly(1.0)
    for k in (250, 300, 350, 400):
        theta, z = wide[k]
        assert theta == pytest.approx(-ki * z / (kp / 2 + kd * s1 + i * s1 * s1), rel=0.03)
    assert wide[400][0] / wide[250][0] == pytest.approx(math.exp(s1 * 15.0), rel=0.03)
    assert abs(math.degrees(wide[250][0])) > 0.05
    narrow = fly(0.1)
    assert abs(narrow[250][0]) < 0.1 * abs(wide[250][0])


def test_integrator_windup_guards():
    """ADCS-008: outside the window nothing accumulates; inside, the torque is clipped to max_torque."""
    integ = ErrorIntegrator(math.radians(1.0), 1e-6)
    big = quat_from_axis_angle((1.0, 0.0, 0.0), math.radians(5))
    assert integ.update(big, 10.0, 1e-3) == (0.0, 0.0, 0.0) and integ.state == (0.0, 0.0, 0.0)
    small = quat_from_axis_angle((1.0, 0.0, 0.0), math.radians(0.5))
    for _ in range(1000):
        tau = integ.update(small, 10.0, 1e-3)
    assert tau[0] == pytest.approx(-1e-6)
    integ.reset()
    assert integ.state == (0.0, 0.0, 0.0)


def test_gravity_gradient_feed_forward_closed_form():
    """ADCS-097: the controller's gravity-gradient model ``3 μ/r³ r̂ × (I r̂)``: zero for a principal axis to nadir;
    with +Z to nadir the products of inertia give ``3 n² (−I_yz, I_xz, 0)``; tilted by a small angle θ about x from
    nadir a diagonal body feels ``3 n² (I_zz − I_yy) θ`` about x (the librational restoring torque's sign and size)."""
    from detumble.control.pointing import gravity_gradient_torque, gyroscopic_torque

    mu, r = 3.986004415e14, 6.798e6
    n2 = mu / r ** 3
    diag = ((2.2e-3, 0.0, 0.0), (0.0, 2.15e-3, 0.0), (0.0, 0.0, 2.05e-3))
    assert gravity_gradient_torque(diag, (0.0, 0.0, -r), mu) == (0.0, 0.0, 0.0)
    full = ((2.2e-3, 2e-5, -1.5e-5), (2e-5, 2.15e-3, 1e-5), (-1.5e-5, 1e-5, 2.05e-3))
    t = gravity_gradient_torque(full, (0.0, 0.0, -r), mu)
    assert t == pytest.approx((3 * n2 * -1e-5, 3 * n2 * -1.5e-5, 0.0), rel=1e-12, abs=1e-20)
    th = 1e-4
    t = gravity_gradient_torque(diag, (0.0, r * math.sin(th), -r * math.cos(th)), mu)
    assert t[0] == pytest.approx(3 * n2 * (2.05e-3 - 2.15e-3) * th, rel=1e-6)
    assert gyroscopic_torque(diag, (0.0, 0.0, 0.0), (1e-3, 2e-3, 3e-3)) == (0.0, 0.0, 0.0)
    assert gyroscopic_torque(diag, (0.0, 0.0, 0.1), (1e-3, 0.0, 0.0)) == pytest.approx((0.0, 1e-4, 0.0), abs=1e-18)


def _rates(window_deg, gate_deg_s, seconds=60.0):
    """:func:`_fly_slew_end`'s flight: per cycle (t s, signed angle rad, rate about x rad/s)."""
    return _fly_slew_end(window_deg, gate_deg_s, seconds, rates=True)


def _fly_slew_end(window_deg, gate_deg_s, seconds=60.0, rates=False):
    """The defaults' PID (K_P 1.1e-3, K_D 2e-3, K_I 5.5e-5, I = 2.2e-3, the 8°/s slew limit) from 90° at rest about
    x, control at 10 Hz, the gate fed the body's rate: per cycle (t s, signed angle rad, integral state, whether the
    integral moved this cycle)."""
    i = 2.2e-3
    kp, kd, ki = 1.1e-3, 2.0e-3, 5.5e-5
    body = RigidBody(((i, 0, 0), (0, i, 0), (0, 0, i)))
    integ = ErrorIntegrator(math.radians(window_deg), 1e-5, math.radians(gate_deg_s))
    state = (math.cos(math.radians(45.0)), math.sin(math.radians(45.0)), 0.0, 0.0, 0.0, 0.0, 0.0)
    out = []
    for k in range(int(seconds * 10)):
        tau, qe = pd_torque((1.0, 0.0, 0.0, 0.0), state[:4], state[4:], kp, kd, math.radians(8.0))
        before = integ.state
        ti = integ.update(qe, 0.1, ki, state[4:])
        state = body.step(state, 0.1, (tau[0] + ti[0], tau[1] + ti[1], tau[2] + ti[2]))
        angle = 2.0 * math.atan2(state[1], state[0])
        out.append(((k + 1) * 0.1, angle, state[4]) if rates else
                   ((k + 1) * 0.1, angle, integ.state[0], integ.state != before))
    return out


def test_rate_gate_keeps_the_slews_approach_out_of_the_integral():
    """ADCS-140: with the 1° window and INTEGRAL_RATE_GATE 0.05 °/s, a 90° slew's approach is not integrated until
    its error is below ``g 2I/K_D`` = 0.11° (the approach moves at more than ``K_D/(2I)`` = 0.45/s times its error in
    its last degree; docs/studies/robust_rates.md, "The rate gate"), where without the gate it is integrated from 1°;
    so the tail the integral returns at the slow root (ADCS-130) is gone: from 1 s after the error first fell below
    0.1°, the ungated error spends more than 5 s beyond 0.05° (past 0.07° on the other side), the gated none, and
    from 10 s on the gated error stays under 0.15 of the ungated one's largest."""
    i, kd = 2.2e-3, 2.0e-3
    gate = 0.05
    wide, gated = _fly_slew_end(1.0, 0.0), _fly_slew_end(1.0, gate)
    # the closed form's premise: from 1° down to 0.05° the approach moves at more than K_D/(2I) times its error
    approach = [(a, w) for (_, a, _, _), (_, _, w) in zip(wide[1:], _rates(1.0, 0.0)[1:], strict=True)
                if math.radians(0.05) < a < math.radians(1.0)]
    assert len(approach) > 10 and all(abs(w) > kd / (2 * i) * a for a, w in approach)

    def first_integrated_deg(run):  # the angle the integral saw (the previous cycle's) when it first moved
        return math.degrees(next(abs(run[k - 1][1]) for k in range(1, len(run)) if run[k][3]))

    assert 0.9 < first_integrated_deg(wide) <= 1.0
    assert first_integrated_deg(gated) <= math.degrees(math.radians(gate) * 2 * i / kd)  # 0.11°
    t_in = next(t for t, a, _, _ in wide if abs(a) < math.radians(0.1))

    def above(run):  # seconds beyond 0.05° from 1 s after the error first fell below 0.1° (past the descent)
        return 0.1 * sum(1 for t, a, _, _ in run if t > t_in + 1.0 and abs(a) > math.radians(0.05))

    assert above(wide) > 5.0 and min(a for t, a, _, _ in wide if t > t_in) < math.radians(-0.07)  # the tail, past 0
    assert above(gated) == 0.0
    # and no tail: from 10 s on (the PD's modes down to 1 %) under 0.15 of the ungated one's largest
    assert max(abs(a) for t, a, _, _ in gated if t > t_in + 10.0) < 0.15 * max(abs(a) for t, a, _, _ in wide
                                                                                 if t > t_in + 10.0)


def test_rate_gate_keeps_the_integrals_1_deg_reach_under_an_unmodelled_torque():
    """ADCS-141: the wheel law's loop about one axis with its rate observer (model = plant, L = 0.1/s, the blend off)
    in the D term and a constant torque d = 3e-7 N·m the observer does not know. Without the integral the observer's
    lag ``d/(I L)`` makes the spring hold ``(1 + K_D/(I L)) d/(K_P/2)`` = 0.316° (to 3 %), above a 0.1° window, which
    therefore never integrates it; with the 1° window and the 0.05 °/s gate fed the body's (gyro's) rate the integral
    removes it (below 2 % of it after 300 s). Fed the observer's rate instead, whose lag 0.078 °/s exceeds the gate,
    the gate would shut on the offset it is there to remove (why the wheel law gives it the gyro's)."""
    from detumble.control.rate_observer import RateObserver

    i = 2.2e-3
    kp, kd, ki, lg = 1.1e-3, 2.0e-3, 5.5e-5, 0.1
    d = 3.0e-7

    def fly(k_i, window_deg, gate_deg_s, gate_on_observer=False):
        body = RigidBody(((i, 0, 0), (0, i, 0), (0, 0, i)))
        obs = RateObserver((i, i, i), lg)
        integ = ErrorIntegrator(math.radians(window_deg), 1e-5, math.radians(gate_deg_s))
        state = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        torque = (0.0, 0.0, 0.0)
        for _ in range(3000):
            w_hat = obs.update(state[4:], torque, (0.0, 0.0, 0.0), 0.1)
            tau, qe = pd_torque((1.0, 0.0, 0.0, 0.0), state[:4], w_hat, kp, kd)
            ti = integ.update(qe, 0.1, k_i, w_hat if gate_on_observer else state[4:])
            torque = (tau[0] + ti[0], tau[1] + ti[1], tau[2] + ti[2])
            state = body.step(state, 0.1, (torque[0] + d, torque[1], torque[2]))
        return quat_angle(state[:4])

    offset = fly(0.0, 1.0, 0.0)
    assert offset == pytest.approx((1.0 + kd / (i * lg)) * d / (kp / 2), rel=0.03)
    assert math.degrees(offset) > 0.3
    assert fly(ki, 0.1, 0.0) > 0.9 * offset  # only what it integrated on the way up through 0.1°
    assert fly(ki, 1.0, 0.05) < 0.02 * offset
    assert fly(ki, 1.0, 0.05, gate_on_observer=True) > 0.5 * offset
