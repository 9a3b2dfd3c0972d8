"""Reaction wheels: spin-axis momentum states integrated with the body in one RK4 step.

N wheels, wheel ``i`` with unit spin axis ``g_i`` (body frame B), axial inertia ``J_s`` (kg m^2)
and absolute axial angular momentum ``h_i = J_s (Omega_i + g_i . omega_BN_B)`` (N m s), where
``Omega_i`` is the wheel's speed relative to the body (rad/s). With the motor torque ``u_i``
(N m, on the wheel, positive along ``g_i``) and the bearing friction torque ``f_i`` on the wheel::

    I omega_dot = tau_ext - omega x (I omega + sum h_i g_i + h_const) - sum (u_i + f_i) g_i
    h_i_dot     = u_i + f_i
    f_i         = -c_v Omega_i - c_c sat(Omega_i / Omega_s)          (sat clips to -1..1)

``I`` is the spacecraft inertia *without* the wheels' axial inertia
(``I = J_total - sum J_s g_i g_i^T``; the scenario gives ``J_total``, the inertia one measures
with the wheels locked). Internal torques cancel in ``I omega + sum h_i g_i``, so the total
angular momentum is conserved in N when no external torque acts (tested to 1e-9).

Limits, applied to the motor torque at the start of every step and held over it:

* ``|u_i| <= u_max`` (a larger command is clipped; the driver reports TorqueSaturated);
* momentum: a torque that would carry ``|h_i|`` past ``h_max`` during the step is cut to the
  torque that reaches ``h_max`` exactly at the step's end, and to zero once there (seed 004 cuts
  it to zero only after the limit has been crossed; here it is never crossed without friction,
  and friction only ever slows the wheel).

Speed mode: the wheel electronics run a speed loop, ``u = J_s (Omega_cmd - Omega) / tau`` with
``tau = max(speed_loop_time_constant_s, 2 dt)``, then the same limits.

Everything here is plain floats; nothing of this module runs when a scenario has no wheels.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import Any

from detumble.sim.vec import Vec3, rotate_n_to_b

TORQUE, SPEED = "torque", "speed"
_isfinite = math.isfinite


@dataclass(frozen=True)
class WheelModel:
    """Catalogue entry: one wheel class. SI units (N m, N m s, kg m^2, rad/s)."""

    name: str
    max_torque_nm: float
    max_momentum_nms: float
    inertia_kg_m2: float
    source: str


#: Wheel classes. ``surrey_coursework`` is seed 004's wheel (its limits; the seed gives no wheel
#: inertia, 1e-4 kg m^2 is ours and only sets the speed scale). The two 1U entries are
#: *representative of the class* of commercial 1U/CubeSat wheels (torque 2-4 mN m, momentum
#: 4-20 mN m s at about 6000-10000 rpm; spec control.md), not one product's datasheet.
CATALOGUE: dict[str, WheelModel] = {
    "surrey_coursework": WheelModel("surrey_coursework", 1.0e-3, 0.1, 1.0e-4,
                                    "seed 004: +-1 mN m, +-0.1 N m s (5-28x a real 1U wheel)"),
    "cubesat_1u_small": WheelModel("cubesat_1u_small", 2.0e-3, 4.0e-3, 6.4e-6,
                                   "1U wheel class, low end: 2 mN m, 4 mN m s (6000 rpm)"),
    "cubesat_1u": WheelModel("cubesat_1u", 4.0e-3, 1.5e-2, 1.43e-5,
                             "1U wheel class, high end: 4 mN m, 15 mN m s (10000 rpm)"),
}


@dataclass(frozen=True)
class WheelSpec:
    """One wheel of a scenario (validated). Axis is a unit vector in B."""

    axis_B: Vec3
    inertia_kg_m2: float
    max_torque_nm: float
    max_momentum_nms: float
    viscous_friction_nms: float = 0.0        # N m s/rad (c_v)
    coulomb_friction_nm: float = 0.0         # N m (c_c)
    coulomb_smoothing_rad_s: float = 0.1     # Omega_s
    momentum_noise_std_nms: float = 0.0      # 1 sigma on the reported momentum
    initial_momentum_nms: float = 0.0
    speed_loop_time_constant_s: float = 0.1


class WheelAssembly:
    """The wheels of one spacecraft: commands, limits and the coupled RK4 step.

    ``h`` is the tuple of absolute axial momenta (N m s). Commands are held until changed.
    """

    def __init__(self, specs: tuple[WheelSpec, ...], seed: int | None = None) -> None:
        if not specs:
            raise ValueError("a wheel assembly needs at least one wheel")
        self.specs = tuple(specs)
        self.n = len(specs)
        self.axes = tuple(s.axis_B for s in specs)
        self._g = tuple(c for s in specs for c in s.axis_B)  # flat g1x g1y g1z g2x ...
        self.js = tuple(s.inertia_kg_m2 for s in specs)
        self.u_max = tuple(s.max_torque_nm for s in specs)
        self.h_max = tuple(s.max_momentum_nms for s in specs)
        self.friction = any(s.viscous_friction_nms > 0.0 or s.coulomb_friction_nm > 0.0 for s in specs)
        self.h: tuple[float, ...] = tuple(s.initial_momentum_nms for s in specs)
        self.mode = [TORQUE] * self.n
        self.enabled = [True] * self.n
        self.command = [0.0] * self.n           # N m (torque mode) or rad/s (speed mode)
        self.torque_applied = [0.0] * self.n    # motor torque over the last step, N m
        self.torque_clipped = [False] * self.n  # last step: |command| > u_max
        self.momentum_limited = [False] * self.n  # last step: cut by the momentum limit
        self.rng = random.Random(seed)
        self._taus = tuple(s.speed_loop_time_constant_s for s in specs)
        #: the compiled kernel's :meth:`motor_torques` (``Kernel.motor_torques``: the same floats and flags), set by a
        #: plant flying the kernel with these wheels (:meth:`.plant.Plant.__init__`); None: the Python below
        self.compiled: Any = None

    # --- commands --------------------------------------------------------------------------

    def _index(self, i: int) -> int:
        if isinstance(i, bool) or not isinstance(i, int) or not 0 <= i < self.n:
            raise ValueError(f"no wheel {i!r}; this spacecraft has wheels 0..{self.n - 1}")
        return i

    def set_torque(self, i: int, torque_nm: float) -> None:
        """Motor torque on wheel ``i`` (N m, along its axis; the body feels the opposite)."""
        if type(i) is not int or not 0 <= i < self.n:
            i = self._index(i)  # raises for anything but a wheel's index
        if not _isfinite(torque_nm):
            raise ValueError(f"wheel {i}: torque must be finite, got {torque_nm!r}")
        self.mode[i] = TORQUE
        self.command[i] = float(torque_nm)

    def set_speed(self, i: int, speed_rad_s: float) -> None:
        """Speed set-point of wheel ``i`` relative to the body, rad/s (the wheel's own loop)."""
        i = self._index(i)
        if not math.isfinite(speed_rad_s):
            raise ValueError(f"wheel {i}: speed must be finite, got {speed_rad_s!r}")
        self.mode[i] = SPEED
        self.command[i] = float(speed_rad_s)

    def set_enabled(self, i: int, enabled: bool) -> None:
        """A disabled wheel's motor gives no torque (it coasts; friction still acts)."""
        self.enabled[self._index(i)] = bool(enabled)

    # --- state -----------------------------------------------------------------------------

    def momentum_B(self) -> Vec3:
        """``sum h_i g_i``, N m s in B."""
        g, h = self._g, self.h
        x = y = z = 0.0
        for i in range(self.n):
            x += h[i] * g[3 * i]
            y += h[i] * g[3 * i + 1]
            z += h[i] * g[3 * i + 2]
        return (x, y, z)

    def speed_rad_s(self, i: int, omega_B: Vec3) -> float:
        """Wheel speed relative to the body, rad/s."""
        g = self.axes[i]
        return self.h[i] / self.js[i] - (g[0] * omega_B[0] + g[1] * omega_B[1] + g[2] * omega_B[2])

    def measured_momentum(self, i: int) -> float:
        """``h_i`` plus the configured reading noise (one draw per call), N m s."""
        sd = self.specs[i].momentum_noise_std_nms
        return self.h[i] + (self.rng.gauss(0.0, sd) if sd > 0.0 else 0.0)

    # --- the step --------------------------------------------------------------------------

    def motor_torques(self, dt: float, omega_B: Vec3) -> tuple[float, ...]:
        """The limited motor torques to hold over the next step of ``dt`` s."""
        if self.compiled is not None:  # plant_kernel.c Kernel.motor_torques: the lines below, compiled
            torques = self.compiled(dt, omega_B, self.h, self.mode, SPEED, self.enabled, self.command, self.u_max,
                                    self.h_max, self._taus, self.torque_clipped, self.momentum_limited)
            self.torque_applied = list(torques)
            return torques
        out = []
        enabled, mode, command, u_max, h_max = self.enabled, self.mode, self.command, self.u_max, self.h_max
        h_all = self.h
        clipped_out, limited_out = self.torque_clipped, self.momentum_limited
        friction = self.friction
        for i in range(self.n):
            if not enabled[i]:
                out.append(0.0)
                clipped_out[i] = limited_out[i] = False
                continue
            m = mode[i]
            speed = self.speed_rad_s(i, omega_B) if m == SPEED or friction else 0.0  # both uses: the same value
            if m == SPEED:
                tau = max(self.specs[i].speed_loop_time_constant_s, 2.0 * dt)
                u = self.js[i] * (command[i] - speed) / tau
            else:
                u = command[i]
            um = u_max[i]
            clipped = u > um or u < -um
            if clipped:
                u = um if u > 0.0 else -um
            h, hm = h_all[i], h_max[i]
            limited = False
            if friction:
                f0 = _friction(self.specs[i], speed)
            else:
                f0 = 0.0
            h1 = h + (u + f0) * dt
            if h1 > hm and u > 0.0:
                u = max(0.0, (hm - h) / dt - f0)
                limited = True
            elif h1 < -hm and u < 0.0:
                u = min(0.0, (-hm - h) / dt - f0)
                limited = True
            clipped_out[i] = clipped and m == TORQUE
            limited_out[i] = limited
            out.append(u)
        self.torque_applied = out
        return tuple(out)


def _friction(spec: WheelSpec, omega_rel: float) -> float:
    smoothing = spec.coulomb_smoothing_rad_s
    s = omega_rel / smoothing if smoothing > 0.0 else math.copysign(1e9, omega_rel)
    sat = 1.0 if s > 1.0 else (-1.0 if s < -1.0 else s)
    return -spec.viscous_friction_nms * omega_rel - spec.coulomb_friction_nm * sat


def step_with_wheels(body, state, h, u, wheels: WheelAssembly, dt: float, m_B: Vec3, b_N: Vec3,
                     gg_coeff: float, r_hat_N: Vec3, torque_B: Vec3 | None = None):
    """One RK4 step of body + wheel momenta; returns ``(state, h)``.

    Same environment treatment as :meth:`RigidBody.step_env` (``b_N`` and ``r_hat_N`` held in N,
    carried in B as stage states); ``u`` the motor torques held over the step (N m); ``torque_B`` an
    external body torque held over the step (N m, B; drag and solar pressure), None for none.
    """
    j11, j12, j13, j21, j22, j23, j31, j32, j33 = body._j
    i11, i12, i13, i21, i22, i23, i31, i32, i33 = body._jinv
    hcx, hcy, hcz = body.wheel_momentum_B
    mx, my, mz = m_B
    g = gg_coeff
    ga = wheels._g
    n = wheels.n
    friction = wheels.friction
    specs = wheels.specs
    js = wheels.js
    rng_n = range(n)
    q = state[:4]
    b1, b2, b3 = rotate_n_to_b(q, b_N)
    r1, r2, r3 = rotate_n_to_b(q, r_hat_N)
    x0 = (*state, b1, b2, b3, r1, r2, r3)

    # The stage derivative repeats RigidBody.step_env's with the wheel terms added: a separate
    # function, so that the wheel-free path pays nothing for wheels (spec: per-tick budget).
    # (hwx, hwy, hwz): total wheel momentum in B; (tx, ty, tz): the wheels' torque on the body.
    def f(x, hwx, hwy, hwz, tx, ty, tz):
        q0, q1, q2, q3, w1, w2, w3, b1, b2, b3, r1, r2, r3 = x
        s1 = j11 * r1 + j12 * r2 + j13 * r3
        s2 = j21 * r1 + j22 * r2 + j23 * r3
        s3 = j31 * r1 + j32 * r2 + j33 * r3
        h1 = j11 * w1 + j12 * w2 + j13 * w3 + hwx
        h2 = j21 * w1 + j22 * w2 + j23 * w3 + hwy
        h3 = j31 * w1 + j32 * w2 + j33 * w3 + hwz
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
    c = dt / 6.0
    if not friction:
        # h_i_dot = u_i is constant over the step: the wheel momentum is linear in time, so its
        # stage values are exact and need no per-wheel work inside the stages.
        hx, hy, hz = hcx, hcy, hcz
        ux = uy = uz = 0.0
        for i in rng_n:
            gx, gy, gz = ga[3 * i], ga[3 * i + 1], ga[3 * i + 2]
            hx += h[i] * gx
            hy += h[i] * gy
            hz += h[i] * gz
            ux += u[i] * gx
            uy += u[i] * gy
            uz += u[i] * gz
        if torque_B is None:
            tx, ty, tz = -ux, -uy, -uz
        else:
            tx, ty, tz = torque_B[0] - ux, torque_B[1] - uy, torque_B[2] - uz
        k1 = f(x0, hx, hy, hz, tx, ty, tz)
        xa = [x + a * k for x, k in zip(x0, k1, strict=True)]
        k2 = f(xa, hx + a * ux, hy + a * uy, hz + a * uz, tx, ty, tz)
        xa = [x + a * k for x, k in zip(x0, k2, strict=True)]
        k3 = f(xa, hx + a * ux, hy + a * uy, hz + a * uz, tx, ty, tz)
        xa = [x + dt * k for x, k in zip(x0, k3, strict=True)]
        k4 = f(xa, hx + dt * ux, hy + dt * uy, hz + dt * uz, tx, ty, tz)
        new_h = tuple(h[i] + u[i] * dt for i in rng_n)
    else:
        def wheel_terms(x, hs):
            w1, w2, w3 = x[4], x[5], x[6]
            hx, hy, hz = hcx, hcy, hcz
            tx = ty = tz = 0.0
            hdot = []
            for i in rng_n:
                gx, gy, gz = ga[3 * i], ga[3 * i + 1], ga[3 * i + 2]
                hi = hs[i]
                hx += hi * gx
                hy += hi * gy
                hz += hi * gz
                d = u[i] + _friction(specs[i], hi / js[i] - (gx * w1 + gy * w2 + gz * w3))
                hdot.append(d)
                tx -= d * gx
                ty -= d * gy
                tz -= d * gz
            if torque_B is not None:
                tx, ty, tz = tx + torque_B[0], ty + torque_B[1], tz + torque_B[2]
            return (hx, hy, hz, tx, ty, tz), hdot

        e, l1 = wheel_terms(x0, h)
        k1 = f(x0, *e)
        xa = [x + a * k for x, k in zip(x0, k1, strict=True)]
        e, l2 = wheel_terms(xa, [hi + a * d for hi, d in zip(h, l1, strict=True)])
        k2 = f(xa, *e)
        xa = [x + a * k for x, k in zip(x0, k2, strict=True)]
        e, l3 = wheel_terms(xa, [hi + a * d for hi, d in zip(h, l2, strict=True)])
        k3 = f(xa, *e)
        xa = [x + dt * k for x, k in zip(x0, k3, strict=True)]
        e, l4 = wheel_terms(xa, [hi + dt * d for hi, d in zip(h, l3, strict=True)])
        k4 = f(xa, *e)
        new_h = tuple(h[i] + c * (l1[i] + 2.0 * (l2[i] + l3[i]) + l4[i]) for i in rng_n)
    q = [x0[j] + c * (k1[j] + 2.0 * (k2[j] + k3[j]) + k4[j]) for j in range(7)]
    nq = 1.0 / math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    return (q[0] * nq, q[1] * nq, q[2] * nq, q[3] * nq, q[4], q[5], q[6]), new_h


def equations_inertia(total_inertia, specs: tuple[WheelSpec, ...]):
    """``J_total - sum J_s g g^T``: the inertia that appears in the coupled equations."""
    j = [list(row) for row in total_inertia]
    for s in specs:
        g = s.axis_B
        for r in range(3):
            for c in range(3):
                j[r][c] -= s.inertia_kg_m2 * g[r] * g[c]
    return tuple(tuple(row) for row in j)
