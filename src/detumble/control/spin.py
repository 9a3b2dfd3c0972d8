"""Spin-stabilisation laws (plain floats; no framework import): seed 003's virtual Kane damper as
written, the classical 3-axis virtual damper, and the rate regulator the flight component uses.

Units: rates rad/s, torques N·m, inertias kg·m², damping coefficients N·m·s, all in the body
frame B. Every law returns the *requested* body torque; the caller turns it into a dipole (only the
part perpendicular to B is achievable) or wheel torques.

Why three (``/work/shared/spec/control.md`` item 4): a Kane damper is an energy sink and energy
dissipation drives a spin to the **major** axis, so no damper alone holds the default body's ẑ
(its minor axis). Seed 003's single-axis form does not even see the body rate: its state is
driven only by the magnetic torque the controller itself produced, so from rest it never leaves
zero (``tests/detumble/control/test_spin.py``). :class:`SpinRateRegulator` drives the rate
toward ``ω_s ŝ`` on all three axes and holds a minor-axis spin as well as a major-axis one.
"""

from __future__ import annotations

import math

Vec3 = tuple[float, float, float]

__all__ = ["SeedKaneDamper", "VirtualDamper", "SpinRateRegulator", "rk4_scalar", "spin_errors", "spin_axis_error_deg"]



def spin_errors(w: Vec3, target_rad_s: float) -> tuple[float, float]:
    """``(angle of ω from +Z deg, |ω_z − target| / |target|)`` for the rate ``w`` (rad/s, B) and the spin
    target (rad/s about +Z; a zero target gives ``|ω_z|``); a zero rate is 180° off the axis."""
    return spin_axis_error_deg(w), (abs(w[2] - target_rad_s) / abs(target_rad_s) if target_rad_s != 0.0 else abs(w[2]))


def spin_axis_error_deg(w: Vec3) -> float:
    """The angle between the rate ``w`` (B) and +Z, deg; 180 for a zero rate."""
    size = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    return math.degrees(math.atan2(math.hypot(w[0], w[1]), w[2])) if size > 0.0 else 180.0


def rk4_scalar(f, x: float, dt: float) -> float:
    """One classical RK4 step of ``dx/dt = f(x)``."""
    k1 = f(x)
    k2 = f(x + 0.5 * dt * k1)
    k3 = f(x + 0.5 * dt * k2)
    k4 = f(x + dt * k3)
    return x + dt * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0


class SeedKaneDamper:
    """Seed 003 exactly as written: ``ẇ_d = I_d⁻¹ (τ_mag·ẑ − c_damp w_d)``, ``τ_req = −c_damp w_d ẑ``.

    ``w_d`` is a scalar (rad/s; the seed's ``float w_d[1]``), integrated by RK4 each cycle with
    ``τ_mag`` (N·m, the magnetic torque actually applied over the cycle) held. Closed form for a
    held τ: ``w_d(t) = τ/c + (w_d0 − τ/c) e^(−c t / I_d)``.
    """

    def __init__(self, c_damp: float, i_d: float) -> None:
        if not i_d > 0.0:
            raise ValueError(f"I_d must be positive, got {i_d}")
        self.c_damp = float(c_damp)
        self.i_d = float(i_d)
        self.w_d = 0.0

    def reset(self) -> None:
        self.w_d = 0.0

    def update(self, tau_mag_B: Vec3, dt: float) -> None:
        tz, c, i_d = tau_mag_B[2], self.c_damp, self.i_d
        self.w_d = rk4_scalar(lambda w: (tz - c * w) / i_d, self.w_d, dt)

    def torque_request(self) -> Vec3:
        return (0.0, 0.0, -self.c_damp * self.w_d)


class VirtualDamper:
    """The classical 3-axis viscous damper: a virtual rotor of inertia ``I_d`` (rad/s state
    ``ω_d``) dragged by the body, ``I_d ω̇_d = c (ω − ω_d)``; the body feels ``τ = −c (ω − ω_d)``.

    Integrated by RK4 each cycle with the body rate held (the closed form per axis is
    ``ω_d(t) = ω + (ω_d0 − ω) e^(−c t / I_d)``). It dissipates energy and nothing else: it damps
    changes of the body rate but leaves a steady spin to drift to the major axis.
    """

    def __init__(self, c_damp: float, i_d: float) -> None:
        if not i_d > 0.0:
            raise ValueError(f"I_d must be positive, got {i_d}")
        self.c_damp = float(c_damp)
        self.i_d = float(i_d)
        self.omega_d: Vec3 | None = None

    def reset(self) -> None:
        self.omega_d = None

    def update(self, omega_B: Vec3, dt: float) -> None:
        if self.omega_d is None:
            self.omega_d = (omega_B[0], omega_B[1], omega_B[2])
            return
        c, i_d = self.c_damp, self.i_d
        od = self.omega_d

        def rate(w: float):
            return lambda x: c * (w - x) / i_d

        self.omega_d = (rk4_scalar(rate(omega_B[0]), od[0], dt), rk4_scalar(rate(omega_B[1]), od[1], dt),
                        rk4_scalar(rate(omega_B[2]), od[2], dt))

    def torque_request(self, omega_B: Vec3) -> Vec3:
        if self.omega_d is None:
            return (0.0, 0.0, 0.0)
        c, d = self.c_damp, self.omega_d
        return (-c * (omega_B[0] - d[0]), -c * (omega_B[1] - d[1]), -c * (omega_B[2] - d[2]))


class SpinRateRegulator:
    """Holds a spin of ``rate`` rad/s about the unit body axis ``axis``:

        τ = −k_t (ω − (ω·ŝ) ŝ) − k_s ((ω·ŝ) − ω_s) ŝ

    The transverse term removes nutation and coning (so the momentum comes onto ŝ), the spin term
    regulates the rate; with ``k_t, k_s > 0`` the only equilibrium is ``ω = ω_s ŝ``, whatever ŝ's
    place among the principal axes. Gains in N·m·s.
    """

    def __init__(self, k_transverse: float, k_spin: float, rate: float, axis: Vec3 = (0.0, 0.0, 1.0)) -> None:
        n = (axis[0] ** 2 + axis[1] ** 2 + axis[2] ** 2) ** 0.5
        if not n > 0.0:
            raise ValueError("the spin axis must not be the zero vector")
        self.k_transverse = float(k_transverse)
        self.k_spin = float(k_spin)
        self.rate = float(rate)
        self.axis: Vec3 = (axis[0] / n, axis[1] / n, axis[2] / n)

    def torque_request(self, omega_B: Vec3) -> Vec3:
        s = self.axis
        ws = omega_B[0] * s[0] + omega_B[1] * s[1] + omega_B[2] * s[2]
        kt, along = self.k_transverse, -self.k_spin * (ws - self.rate)
        return (-kt * (omega_B[0] - ws * s[0]) + along * s[0], -kt * (omega_B[1] - ws * s[1]) + along * s[1],
                -kt * (omega_B[2] - ws * s[2]) + along * s[2])
