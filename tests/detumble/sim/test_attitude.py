"""Rigid-body dynamics against conservation laws and the axisymmetric closed form."""

import math

from detumble.sim.attitude import RigidBody
from detumble.sim.torques import gravity_gradient_torque, magnetic_torque
from detumble.sim.vec import (add, angle_between, cross, dot, norm, quat_from_axis_angle, rotate_b_to_n,
                              rotate_n_to_b, scale)

REL_TOL_CONSERVATION = 1e-9  # relative, dimensionless


def test_torque_free_conserves_momentum_and_energy_over_1e5_steps():
    """|H| and rotational energy conserved to <= 1e-9 relative over 1e5 RK4 steps (full tensor)."""
    inertia = ((2.0e-3, 1.0e-4, -5.0e-5), (1.0e-4, 3.0e-3, 8.0e-5), (-5.0e-5, 8.0e-5, 4.0e-3))
    body = RigidBody(inertia)
    s = quat_from_axis_angle((1.0, 1.0, 0.0), 0.4) + (0.15, -0.2, 0.25)  # rad/s, ~20 deg/s
    h0 = body.angular_momentum_B(s)
    h0_N = rotate_b_to_n(s[:4], h0)
    e0 = body.kinetic_energy(s)
    for _ in range(100_000):
        s = body.step(s, 0.01)
    h1 = body.angular_momentum_B(s)
    assert abs(norm(h1) - norm(h0)) / norm(h0) <= REL_TOL_CONSERVATION
    assert abs(body.kinetic_energy(s) - e0) / e0 <= REL_TOL_CONSERVATION
    # inertial H vector (checks the kinematics too): direction fixed to < 1e-8 rad
    assert angle_between(rotate_b_to_n(s[:4], h1), h0_N) < 1e-8


def test_axisymmetric_free_precession_matches_closed_form():
    """J = diag(It, It, Ia): body rates rotate at lambda = (Ia-It)/It w3; the symmetry axis cones about H at |H|/It."""
    it, ia = 2.0e-3, 3.5e-3  # kg m^2
    body = RigidBody(((it, 0, 0), (0, it, 0), (0, 0, ia)))
    w0 = (0.2, 0.05, 0.4)  # rad/s
    q0 = quat_from_axis_angle((0.3, -0.2, 1.0), 0.8)
    s = q0 + w0
    lam = (ia - it) / it * w0[2]
    h_N = rotate_b_to_n(q0, body.angular_momentum_B(s))
    h_hat = scale(1.0 / norm(h_N), h_N)
    precession_rate = norm(h_N) / it
    z0_N = rotate_b_to_n(q0, (0.0, 0.0, 1.0))
    dt, n = 0.01, 20_000  # 200 s
    max_rate_err = 0.0
    max_axis_err = 0.0
    for k in range(1, n + 1):
        s = body.step(s, dt)
        if k % 1000 == 0:
            t = k * dt
            c, sn = math.cos(lam * t), math.sin(lam * t)
            expect_w = (w0[0] * c - w0[1] * sn, w0[0] * sn + w0[1] * c, w0[2])
            max_rate_err = max(max_rate_err, max(abs(a - b) for a, b in zip(s[4:7], expect_w, strict=True)))
            # Rodrigues rotation of z0_N about H_hat by precession_rate * t
            a = precession_rate * t
            ca, sa = math.cos(a), math.sin(a)
            expect_z = add(add(scale(ca, z0_N), scale(sa, cross(h_hat, z0_N))),
                           scale(dot(h_hat, z0_N) * (1 - ca), h_hat))
            max_axis_err = max(max_axis_err, angle_between(rotate_b_to_n(s[:4], (0.0, 0.0, 1.0)), expect_z))
    assert max_rate_err < 1e-9  # rad/s
    assert max_axis_err < 1e-8  # rad


def test_step_env_torques_match_reference_formulas():
    """The inline per-stage torques equal torques.py evaluated at every RK4 stage (1e-12 relative)."""
    inertia = ((2.0e-3, 1.0e-4, 0.0), (1.0e-4, 3.0e-3, 2.0e-5), (0.0, 2.0e-5, 2.5e-3))
    body = RigidBody(inertia)
    m_B = (0.05, -0.1, 0.02)  # A m^2
    b_N = (2.0e-5, -1.0e-5, 3.0e-5)  # T
    mu = 3.986004415e14
    r_N = (3.0e6, -4.0e6, 4.5e6)  # m
    rn = norm(r_N)
    r_hat = scale(1.0 / rn, r_N)
    gg = 3.0 * mu / rn**3
    s = quat_from_axis_angle((1.0, -2.0, 0.5), 1.1) + (0.3, -0.4, 0.5)
    dt = 0.05

    def torque(state):
        q = state[:4]
        return add(magnetic_torque(m_B, rotate_n_to_b(q, b_N)),
                   gravity_gradient_torque(mu, rotate_n_to_b(q, r_N), inertia))

    def rk4_ref(state):
        # torques are evaluated on the stage quaternion renormalised (the reference formulas want a rotation)
        def f(x):
            qn = math.sqrt(sum(c * c for c in x[:4]))
            return body.derivative(x, torque(tuple(c / qn for c in x[:4]) + x[4:]))
        k1 = f(state)
        k2 = f(tuple(a + dt / 2 * b for a, b in zip(state, k1, strict=True)))
        k3 = f(tuple(a + dt / 2 * b for a, b in zip(state, k2, strict=True)))
        k4 = f(tuple(a + dt * b for a, b in zip(state, k3, strict=True)))
        out = tuple(a + dt / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(state, k1, k2, k3, k4, strict=True))
        qn = math.sqrt(sum(c * c for c in out[:4]))
        return tuple(c / qn for c in out[:4]) + out[4:]

    ref = rk4_ref(s)
    got = body.step_env(s, dt, m_B, b_N, gg, r_hat)
    dw = max(abs(a - b) for a, b in zip(got[4:], ref[4:], strict=True))
    assert dw < 1e-9 * norm(s[4:])  # rad/s; the schemes agree to RK4 order, not bit for bit
    assert max(abs(a - b) for a, b in zip(got[:4], ref[:4], strict=True)) < 1e-9
    # and the torque actually did something measurable in one step
    assert max(abs(a - b) for a, b in zip(got[4:], body.step(s, dt)[4:], strict=True)) > 1e-5


def test_gravity_gradient_zero_for_isotropic_and_restoring_for_slender():
    r_B = (7.0e6, 0.0, 0.0)
    iso = ((2e-3, 0, 0), (0, 2e-3, 0), (0, 0, 2e-3))
    assert norm(gravity_gradient_torque(3.986e14, r_B, iso)) == 0.0
    # long (minimum-inertia) axis z; position 10 deg from x towards z, i.e. 80 deg from the long axis
    slender = ((5e-3, 0, 0), (0, 5e-3, 0), (0, 0, 1e-3))
    a = math.radians(10.0)
    r_tilted = (7.0e6 * math.cos(a), 0.0, 7.0e6 * math.sin(a))
    t = gravity_gradient_torque(3.986e14, r_tilted, slender)
    n2 = 3.986e14 / 7.0e6**3
    # closed form 3 n^2 (Jx - Jz) sin a cos a about +y, which turns body z towards +x, i.e. towards r
    expected = 3 * n2 * (5e-3 - 1e-3) * math.sin(a) * math.cos(a)  # N m
    assert t[1] > 0.0
    assert abs(t[1] - expected) < 1e-12 * expected
    assert t[0] == 0.0 and t[2] == 0.0
