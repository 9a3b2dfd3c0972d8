"""Rigid-body dynamics against conservation laws and the axisymmetric closed form."""

import math

from detumble.sim.attitude import RigidBody, _combine
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


def _stagewise_step_env(self, state, dt, m_B, b_N, gg_coeff, r_hat_N, torque_B=(0.0, 0.0, 0.0)):
    """The step_env of ea48e23: the stage derivative as a nested function called four times."""
    j11, j12, j13, j21, j22, j23, j31, j32, j33 = self._j
    i11, i12, i13, i21, i22, i23, i31, i32, i33 = self._jinv
    hx, hy, hz = self.wheel_momentum_B
    mx, my, mz = m_B
    tx, ty, tz = torque_B
    g = gg_coeff
    q0, q1, q2, q3, w1, w2, w3 = state
    c11 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
    c12 = 2.0 * (q1 * q2 + q0 * q3)
    c13 = 2.0 * (q1 * q3 - q0 * q2)
    c21 = 2.0 * (q1 * q2 - q0 * q3)
    c22 = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3
    c23 = 2.0 * (q2 * q3 + q0 * q1)
    c31 = 2.0 * (q1 * q3 + q0 * q2)
    c32 = 2.0 * (q2 * q3 - q0 * q1)
    c33 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
    bx, by, bz = b_N
    b1 = c11 * bx + c12 * by + c13 * bz
    b2 = c21 * bx + c22 * by + c23 * bz
    b3 = c31 * bx + c32 * by + c33 * bz
    rx, ry, rz = r_hat_N
    r1 = c11 * rx + c12 * ry + c13 * rz
    r2 = c21 * rx + c22 * ry + c23 * rz
    r3 = c31 * rx + c32 * ry + c33 * rz

    def f(q0, q1, q2, q3, w1, w2, w3, b1, b2, b3, r1, r2, r3):
        s1 = j11 * r1 + j12 * r2 + j13 * r3
        s2 = j21 * r1 + j22 * r2 + j23 * r3
        s3 = j31 * r1 + j32 * r2 + j33 * r3
        h1 = j11 * w1 + j12 * w2 + j13 * w3 + hx
        h2 = j21 * w1 + j22 * w2 + j23 * w3 + hy
        h3 = j31 * w1 + j32 * w2 + j33 * w3 + hz
        # tau = m x b + 3n^2 r x (J r) + tau_ext - omega x H
        g1 = tx + my * b3 - mz * b2 + g * (r2 * s3 - r3 * s2) - (w2 * h3 - w3 * h2)
        g2 = ty + mz * b1 - mx * b3 + g * (r3 * s1 - r1 * s3) - (w3 * h1 - w1 * h3)
        g3 = tz + mx * b2 - my * b1 + g * (r1 * s2 - r2 * s1) - (w1 * h2 - w2 * h1)
        return (
            0.5 * (-q1 * w1 - q2 * w2 - q3 * w3),
            0.5 * (q0 * w1 + q2 * w3 - q3 * w2),
            0.5 * (q0 * w2 - q1 * w3 + q3 * w1),
            0.5 * (q0 * w3 + q1 * w2 - q2 * w1),
            i11 * g1 + i12 * g2 + i13 * g3,
            i21 * g1 + i22 * g2 + i23 * g3,
            i31 * g1 + i32 * g2 + i33 * g3,
            b2 * w3 - b3 * w2, b3 * w1 - b1 * w3, b1 * w2 - b2 * w1,
            r2 * w3 - r3 * w2, r3 * w1 - r1 * w3, r1 * w2 - r2 * w1,
        )

    a = 0.5 * dt
    k1 = f(q0, q1, q2, q3, w1, w2, w3, b1, b2, b3, r1, r2, r3)
    k2 = f(q0 + a * k1[0], q1 + a * k1[1], q2 + a * k1[2], q3 + a * k1[3],
           w1 + a * k1[4], w2 + a * k1[5], w3 + a * k1[6],
           b1 + a * k1[7], b2 + a * k1[8], b3 + a * k1[9],
           r1 + a * k1[10], r2 + a * k1[11], r3 + a * k1[12])
    k3 = f(q0 + a * k2[0], q1 + a * k2[1], q2 + a * k2[2], q3 + a * k2[3],
           w1 + a * k2[4], w2 + a * k2[5], w3 + a * k2[6],
           b1 + a * k2[7], b2 + a * k2[8], b3 + a * k2[9],
           r1 + a * k2[10], r2 + a * k2[11], r3 + a * k2[12])
    k4 = f(q0 + dt * k3[0], q1 + dt * k3[1], q2 + dt * k3[2], q3 + dt * k3[3],
           w1 + dt * k3[4], w2 + dt * k3[5], w3 + dt * k3[6],
           b1 + dt * k3[7], b2 + dt * k3[8], b3 + dt * k3[9],
           r1 + dt * k3[10], r2 + dt * k3[11], r3 + dt * k3[12])
    return _combine(state, dt, k1, k2, k3, k4)



def test_step_env_written_out_equals_the_stagewise_version_bit_for_bit():
    """SIM-ATT-010: the written-out RK4 of step_env gives exactly (==, not approx) the floats of the
    stage-function version it replaced, over random full inertias, wheel momenta, dipoles, fields,
    gravity gradient and extra torques, chained over 200 steps."""
    import random

    rng = random.Random(19)
    for case in range(20):
        d = [rng.uniform(1e-3, 3e-3) for _ in range(3)]
        off = [rng.uniform(-2e-4, 2e-4) for _ in range(3)]
        inertia = ((d[0], off[0], off[1]), (off[0], d[1], off[2]), (off[1], off[2], d[2]))
        body = RigidBody(inertia, tuple(rng.uniform(-1e-3, 1e-3) for _ in range(3)) if case % 2 else (0.0, 0.0, 0.0))
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        s_new = s_old = tuple(x / n for x in q) + tuple(rng.uniform(-0.5, 0.5) for _ in range(3))
        for _ in range(200):
            args = (rng.choice((0.02, 0.05, 0.0013)), tuple(rng.uniform(-0.2, 0.2) for _ in range(3)),
                    tuple(rng.uniform(-5e-5, 5e-5) for _ in range(3)), rng.choice((0.0, 3.4e-6)),
                    (0.6, -0.48, 0.64), tuple(rng.uniform(-1e-7, 1e-7) for _ in range(3)))
            s_new = body.step_env(s_new, *args)
            s_old = _stagewise_step_env(body, s_old, *args)
            assert s_new == s_old
