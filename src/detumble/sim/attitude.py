"""Rigid-body attitude dynamics: quaternion kinematics + Euler's equations, fixed-step RK4.

State is a plain 7-tuple ``(q0, q1, q2, q3, wx, wy, wz)``: the attitude ``q_BN`` (scalar first,
see :mod:`detumble.sim.vec` for the full convention) and ``omega_BN_B`` in rad/s. The inertia
tensor ``J`` (kg m^2, body frame, about the centre of mass) may be full; an optional constant
wheel momentum ``h_w_B`` (N m s) enters the gyroscopic term::

    dq_BN/dt      = 1/2 q_BN (x) (0, omega_BN_B)
    J domega/dt   = tau_B - omega x (J omega + h_w_B)

The quaternion is renormalised after every step. Torques (N m, body frame) are either held
constant over the step (:meth:`RigidBody.step`, the bare-physics floor) or, in
:meth:`RigidBody.step_env`, re-evaluated at every RK4 stage from the current attitude: the
magnetic torque ``m_B x ([BN] b_N)`` and the gravity-gradient torque
``3 n^2 r_B x (J r_B)`` with ``r_B = [BN] r_hat_N`` (the same formulas as :mod:`.torques`,
written out inline here because this is the per-tick path). The field and position direction are
held fixed in N over one step (they change by <0.3 % in 0.05 s of orbit).
"""

from __future__ import annotations

import math

from detumble.sim.vec import Mat3, Vec3, mat_inv

State = tuple[float, float, float, float, float, float, float]


class RigidBody:
    """Inertia properties plus the integrator. Immutable after construction.

    ``inertia`` is a 3x3 nested sequence in kg m^2; ``wheel_momentum_B`` in N m s.
    """

    def __init__(self, inertia: Mat3, wheel_momentum_B: Vec3 = (0.0, 0.0, 0.0)) -> None:
        r = [[float(x) for x in row] for row in inertia]
        if len(r) != 3 or any(len(row) != 3 for row in r):
            raise ValueError("inertia must be a 3x3 matrix")
        j = ((r[0][0], r[0][1], r[0][2]), (r[1][0], r[1][1], r[1][2]), (r[2][0], r[2][1], r[2][2]))
        self.inertia: Mat3 = j
        self.inertia_inv: Mat3 = mat_inv(self.inertia)
        h = [float(x) for x in wheel_momentum_B]
        if len(h) != 3:
            raise ValueError("wheel_momentum_B must have 3 components")
        self.wheel_momentum_B: Vec3 = (h[0], h[1], h[2])
        self._j = j[0] + j[1] + j[2]
        inv = self.inertia_inv
        self._jinv = inv[0] + inv[1] + inv[2]

    # --- diagnostics ------------------------------------------------------------------------

    def angular_momentum_B(self, state: State) -> Vec3:
        """Body angular momentum ``J omega + h_w`` in B, N m s."""
        j = self.inertia
        w = state[4:7]
        h = self.wheel_momentum_B
        return (j[0][0] * w[0] + j[0][1] * w[1] + j[0][2] * w[2] + h[0],
                j[1][0] * w[0] + j[1][1] * w[1] + j[1][2] * w[2] + h[1],
                j[2][0] * w[0] + j[2][1] * w[1] + j[2][2] * w[2] + h[2])

    def kinetic_energy(self, state: State) -> float:
        """Rotational kinetic energy ``1/2 omega . J omega`` in J."""
        j = self.inertia
        w = state[4:7]
        return 0.5 * sum(w[i] * (j[i][0] * w[0] + j[i][1] * w[1] + j[i][2] * w[2]) for i in range(3))

    def derivative(self, state: State, torque_B: Vec3 = (0.0, 0.0, 0.0)) -> State:
        """Time derivative of the state for a given body torque (N m)."""
        return _derivative(state, self._j, self._jinv, self.wheel_momentum_B, torque_B)

    # --- integrators ------------------------------------------------------------------------

    def step(self, state: State, dt: float, torque_B: Vec3 = (0.0, 0.0, 0.0)) -> State:
        """One RK4 step of ``dt`` seconds with a body torque held constant over the step."""
        j, ji, h = self._j, self._jinv, self.wheel_momentum_B
        q0, q1, q2, q3, w1, w2, w3 = state
        k1 = _derivative(state, j, ji, h, torque_B)
        a = 0.5 * dt
        k2 = _derivative(
            (q0 + a * k1[0], q1 + a * k1[1], q2 + a * k1[2], q3 + a * k1[3],
             w1 + a * k1[4], w2 + a * k1[5], w3 + a * k1[6]), j, ji, h, torque_B)
        k3 = _derivative(
            (q0 + a * k2[0], q1 + a * k2[1], q2 + a * k2[2], q3 + a * k2[3],
             w1 + a * k2[4], w2 + a * k2[5], w3 + a * k2[6]), j, ji, h, torque_B)
        k4 = _derivative(
            (q0 + dt * k3[0], q1 + dt * k3[1], q2 + dt * k3[2], q3 + dt * k3[3],
             w1 + dt * k3[4], w2 + dt * k3[5], w3 + dt * k3[6]), j, ji, h, torque_B)
        return _combine(state, dt, k1, k2, k3, k4)

    def step_env(
        self,
        state: State,
        dt: float,
        m_B: Vec3,
        b_N: Vec3,
        gg_coeff: float,
        r_hat_N: Vec3,
        torque_B: Vec3 = (0.0, 0.0, 0.0),
    ) -> State:
        """One RK4 step with attitude-dependent environment torques evaluated at every stage.

        ``m_B`` (A m^2) is the total body dipole, ``b_N`` (T) the inertial field, both held over the
        step; ``gg_coeff`` is ``3 mu / r^3`` (1/s^2, 0 disables gravity gradient) and ``r_hat_N``
        the unit position vector; ``torque_B`` an extra constant body torque (N m).

        Rather than rebuild ``[BN]`` at every stage, the body components of the (inertially
        fixed over the step) field and position direction are carried as extra RK4 states with
        ``d b_B/dt = -omega x b_B``: the same stage values to RK4 order, at half the cost.
        """
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

        # The stage derivative (attitude rates; Euler's equations with the torques
        # tau = m x b + 3n^2 r x (J r) + tau_ext - omega x H; d b_B/dt = -omega x b_B, the same for
        # r_B) is written out at each of the four stages: a nested function called four times
        # cost a third of the step. The arithmetic is the same, operation for operation, as
        # the stage function it replaced: tests/detumble/sim/test_attitude.py keeps that version
        # and checks the two agree bit for bit. Kept (issue 26): 1.9-2.3 µs less a step than the
        # stage function (15-18 % of the step, one a dynamics step of the pure-Python plant);
        # `python benchmarks/bench_inlined.py rk4_step_env --repeat 150` (3 sittings on the shared
        # 2-core machine, 2026-12-03).
        a = 0.5 * dt
        # stage 1
        s1_1 = j11 * r1 + j12 * r2 + j13 * r3
        s2_1 = j21 * r1 + j22 * r2 + j23 * r3
        s3_1 = j31 * r1 + j32 * r2 + j33 * r3
        h1_1 = j11 * w1 + j12 * w2 + j13 * w3 + hx
        h2_1 = j21 * w1 + j22 * w2 + j23 * w3 + hy
        h3_1 = j31 * w1 + j32 * w2 + j33 * w3 + hz
        g1_1 = tx + my * b3 - mz * b2 + g * (r2 * s3_1 - r3 * s2_1) - (w2 * h3_1 - w3 * h2_1)
        g2_1 = ty + mz * b1 - mx * b3 + g * (r3 * s1_1 - r1 * s3_1) - (w3 * h1_1 - w1 * h3_1)
        g3_1 = tz + mx * b2 - my * b1 + g * (r1 * s2_1 - r2 * s1_1) - (w1 * h2_1 - w2 * h1_1)
        k1_0 = 0.5 * (-q1 * w1 - q2 * w2 - q3 * w3)
        k1_1 = 0.5 * (q0 * w1 + q2 * w3 - q3 * w2)
        k1_2 = 0.5 * (q0 * w2 - q1 * w3 + q3 * w1)
        k1_3 = 0.5 * (q0 * w3 + q1 * w2 - q2 * w1)
        k1_4 = i11 * g1_1 + i12 * g2_1 + i13 * g3_1
        k1_5 = i21 * g1_1 + i22 * g2_1 + i23 * g3_1
        k1_6 = i31 * g1_1 + i32 * g2_1 + i33 * g3_1
        k1_7 = b2 * w3 - b3 * w2
        k1_8 = b3 * w1 - b1 * w3
        k1_9 = b1 * w2 - b2 * w1
        k1_10 = r2 * w3 - r3 * w2
        k1_11 = r3 * w1 - r1 * w3
        k1_12 = r1 * w2 - r2 * w1
        # stage 2
        q0_2 = q0 + a * k1_0
        q1_2 = q1 + a * k1_1
        q2_2 = q2 + a * k1_2
        q3_2 = q3 + a * k1_3
        w1_2 = w1 + a * k1_4
        w2_2 = w2 + a * k1_5
        w3_2 = w3 + a * k1_6
        b1_2 = b1 + a * k1_7
        b2_2 = b2 + a * k1_8
        b3_2 = b3 + a * k1_9
        r1_2 = r1 + a * k1_10
        r2_2 = r2 + a * k1_11
        r3_2 = r3 + a * k1_12
        s1_2 = j11 * r1_2 + j12 * r2_2 + j13 * r3_2
        s2_2 = j21 * r1_2 + j22 * r2_2 + j23 * r3_2
        s3_2 = j31 * r1_2 + j32 * r2_2 + j33 * r3_2
        h1_2 = j11 * w1_2 + j12 * w2_2 + j13 * w3_2 + hx
        h2_2 = j21 * w1_2 + j22 * w2_2 + j23 * w3_2 + hy
        h3_2 = j31 * w1_2 + j32 * w2_2 + j33 * w3_2 + hz
        g1_2 = tx + my * b3_2 - mz * b2_2 + g * (r2_2 * s3_2 - r3_2 * s2_2) - (w2_2 * h3_2 - w3_2 * h2_2)
        g2_2 = ty + mz * b1_2 - mx * b3_2 + g * (r3_2 * s1_2 - r1_2 * s3_2) - (w3_2 * h1_2 - w1_2 * h3_2)
        g3_2 = tz + mx * b2_2 - my * b1_2 + g * (r1_2 * s2_2 - r2_2 * s1_2) - (w1_2 * h2_2 - w2_2 * h1_2)
        k2_0 = 0.5 * (-q1_2 * w1_2 - q2_2 * w2_2 - q3_2 * w3_2)
        k2_1 = 0.5 * (q0_2 * w1_2 + q2_2 * w3_2 - q3_2 * w2_2)
        k2_2 = 0.5 * (q0_2 * w2_2 - q1_2 * w3_2 + q3_2 * w1_2)
        k2_3 = 0.5 * (q0_2 * w3_2 + q1_2 * w2_2 - q2_2 * w1_2)
        k2_4 = i11 * g1_2 + i12 * g2_2 + i13 * g3_2
        k2_5 = i21 * g1_2 + i22 * g2_2 + i23 * g3_2
        k2_6 = i31 * g1_2 + i32 * g2_2 + i33 * g3_2
        k2_7 = b2_2 * w3_2 - b3_2 * w2_2
        k2_8 = b3_2 * w1_2 - b1_2 * w3_2
        k2_9 = b1_2 * w2_2 - b2_2 * w1_2
        k2_10 = r2_2 * w3_2 - r3_2 * w2_2
        k2_11 = r3_2 * w1_2 - r1_2 * w3_2
        k2_12 = r1_2 * w2_2 - r2_2 * w1_2
        # stage 3
        q0_3 = q0 + a * k2_0
        q1_3 = q1 + a * k2_1
        q2_3 = q2 + a * k2_2
        q3_3 = q3 + a * k2_3
        w1_3 = w1 + a * k2_4
        w2_3 = w2 + a * k2_5
        w3_3 = w3 + a * k2_6
        b1_3 = b1 + a * k2_7
        b2_3 = b2 + a * k2_8
        b3_3 = b3 + a * k2_9
        r1_3 = r1 + a * k2_10
        r2_3 = r2 + a * k2_11
        r3_3 = r3 + a * k2_12
        s1_3 = j11 * r1_3 + j12 * r2_3 + j13 * r3_3
        s2_3 = j21 * r1_3 + j22 * r2_3 + j23 * r3_3
        s3_3 = j31 * r1_3 + j32 * r2_3 + j33 * r3_3
        h1_3 = j11 * w1_3 + j12 * w2_3 + j13 * w3_3 + hx
        h2_3 = j21 * w1_3 + j22 * w2_3 + j23 * w3_3 + hy
        h3_3 = j31 * w1_3 + j32 * w2_3 + j33 * w3_3 + hz
        g1_3 = tx + my * b3_3 - mz * b2_3 + g * (r2_3 * s3_3 - r3_3 * s2_3) - (w2_3 * h3_3 - w3_3 * h2_3)
        g2_3 = ty + mz * b1_3 - mx * b3_3 + g * (r3_3 * s1_3 - r1_3 * s3_3) - (w3_3 * h1_3 - w1_3 * h3_3)
        g3_3 = tz + mx * b2_3 - my * b1_3 + g * (r1_3 * s2_3 - r2_3 * s1_3) - (w1_3 * h2_3 - w2_3 * h1_3)
        k3_0 = 0.5 * (-q1_3 * w1_3 - q2_3 * w2_3 - q3_3 * w3_3)
        k3_1 = 0.5 * (q0_3 * w1_3 + q2_3 * w3_3 - q3_3 * w2_3)
        k3_2 = 0.5 * (q0_3 * w2_3 - q1_3 * w3_3 + q3_3 * w1_3)
        k3_3 = 0.5 * (q0_3 * w3_3 + q1_3 * w2_3 - q2_3 * w1_3)
        k3_4 = i11 * g1_3 + i12 * g2_3 + i13 * g3_3
        k3_5 = i21 * g1_3 + i22 * g2_3 + i23 * g3_3
        k3_6 = i31 * g1_3 + i32 * g2_3 + i33 * g3_3
        k3_7 = b2_3 * w3_3 - b3_3 * w2_3
        k3_8 = b3_3 * w1_3 - b1_3 * w3_3
        k3_9 = b1_3 * w2_3 - b2_3 * w1_3
        k3_10 = r2_3 * w3_3 - r3_3 * w2_3
        k3_11 = r3_3 * w1_3 - r1_3 * w3_3
        k3_12 = r1_3 * w2_3 - r2_3 * w1_3
        # stage 4
        q0_4 = q0 + dt * k3_0
        q1_4 = q1 + dt * k3_1
        q2_4 = q2 + dt * k3_2
        q3_4 = q3 + dt * k3_3
        w1_4 = w1 + dt * k3_4
        w2_4 = w2 + dt * k3_5
        w3_4 = w3 + dt * k3_6
        b1_4 = b1 + dt * k3_7
        b2_4 = b2 + dt * k3_8
        b3_4 = b3 + dt * k3_9
        r1_4 = r1 + dt * k3_10
        r2_4 = r2 + dt * k3_11
        r3_4 = r3 + dt * k3_12
        s1_4 = j11 * r1_4 + j12 * r2_4 + j13 * r3_4
        s2_4 = j21 * r1_4 + j22 * r2_4 + j23 * r3_4
        s3_4 = j31 * r1_4 + j32 * r2_4 + j33 * r3_4
        h1_4 = j11 * w1_4 + j12 * w2_4 + j13 * w3_4 + hx
        h2_4 = j21 * w1_4 + j22 * w2_4 + j23 * w3_4 + hy
        h3_4 = j31 * w1_4 + j32 * w2_4 + j33 * w3_4 + hz
        g1_4 = tx + my * b3_4 - mz * b2_4 + g * (r2_4 * s3_4 - r3_4 * s2_4) - (w2_4 * h3_4 - w3_4 * h2_4)
        g2_4 = ty + mz * b1_4 - mx * b3_4 + g * (r3_4 * s1_4 - r1_4 * s3_4) - (w3_4 * h1_4 - w1_4 * h3_4)
        g3_4 = tz + mx * b2_4 - my * b1_4 + g * (r1_4 * s2_4 - r2_4 * s1_4) - (w1_4 * h2_4 - w2_4 * h1_4)
        k4_0 = 0.5 * (-q1_4 * w1_4 - q2_4 * w2_4 - q3_4 * w3_4)
        k4_1 = 0.5 * (q0_4 * w1_4 + q2_4 * w3_4 - q3_4 * w2_4)
        k4_2 = 0.5 * (q0_4 * w2_4 - q1_4 * w3_4 + q3_4 * w1_4)
        k4_3 = 0.5 * (q0_4 * w3_4 + q1_4 * w2_4 - q2_4 * w1_4)
        k4_4 = i11 * g1_4 + i12 * g2_4 + i13 * g3_4
        k4_5 = i21 * g1_4 + i22 * g2_4 + i23 * g3_4
        k4_6 = i31 * g1_4 + i32 * g2_4 + i33 * g3_4
        # combine (as _combine) and renormalise the quaternion
        c = dt / 6.0
        p0 = q0 + c * (k1_0 + 2.0 * (k2_0 + k3_0) + k4_0)
        p1 = q1 + c * (k1_1 + 2.0 * (k2_1 + k3_1) + k4_1)
        p2 = q2 + c * (k1_2 + 2.0 * (k2_2 + k3_2) + k4_2)
        p3 = q3 + c * (k1_3 + 2.0 * (k2_3 + k3_3) + k4_3)
        n = 1.0 / math.sqrt(p0 * p0 + p1 * p1 + p2 * p2 + p3 * p3)
        return (
            p0 * n, p1 * n, p2 * n, p3 * n,
            w1 + c * (k1_4 + 2.0 * (k2_4 + k3_4) + k4_4),
            w2 + c * (k1_5 + 2.0 * (k2_5 + k3_5) + k4_5),
            w3 + c * (k1_6 + 2.0 * (k2_6 + k3_6) + k4_6),
        )


def _derivative(state, j, ji, h, torque_B):
    q0, q1, q2, q3, w1, w2, w3 = state
    j11, j12, j13, j21, j22, j23, j31, j32, j33 = j
    h1 = j11 * w1 + j12 * w2 + j13 * w3 + h[0]
    h2 = j21 * w1 + j22 * w2 + j23 * w3 + h[1]
    h3 = j31 * w1 + j32 * w2 + j33 * w3 + h[2]
    g1 = torque_B[0] - (w2 * h3 - w3 * h2)
    g2 = torque_B[1] - (w3 * h1 - w1 * h3)
    g3 = torque_B[2] - (w1 * h2 - w2 * h1)
    return (
        0.5 * (-q1 * w1 - q2 * w2 - q3 * w3),
        0.5 * (q0 * w1 + q2 * w3 - q3 * w2),
        0.5 * (q0 * w2 - q1 * w3 + q3 * w1),
        0.5 * (q0 * w3 + q1 * w2 - q2 * w1),
        ji[0] * g1 + ji[1] * g2 + ji[2] * g3,
        ji[3] * g1 + ji[4] * g2 + ji[5] * g3,
        ji[6] * g1 + ji[7] * g2 + ji[8] * g3,
    )


def _combine(state, dt, k1, k2, k3, k4) -> State:
    c = dt / 6.0
    q0 = state[0] + c * (k1[0] + 2.0 * (k2[0] + k3[0]) + k4[0])
    q1 = state[1] + c * (k1[1] + 2.0 * (k2[1] + k3[1]) + k4[1])
    q2 = state[2] + c * (k1[2] + 2.0 * (k2[2] + k3[2]) + k4[2])
    q3 = state[3] + c * (k1[3] + 2.0 * (k2[3] + k3[3]) + k4[3])
    n = 1.0 / math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return (
        q0 * n, q1 * n, q2 * n, q3 * n,
        state[4] + c * (k1[4] + 2.0 * (k2[4] + k3[4]) + k4[4]),
        state[5] + c * (k1[5] + 2.0 * (k2[5] + k3[5]) + k4[5]),
        state[6] + c * (k1[6] + 2.0 * (k2[6] + k3[6]) + k4[6]),
    )
