"""A model-aided body-rate observer for the PD law's derivative term (plain floats, no framework import).

Why: the gyro's white noise, through ``K_d ω``, is what limits the pointing error on the wheels
(docs/studies/attitude_knowledge.md). A plain low-pass chosen above the closed-loop bandwidth removes
noise the plant's inertia would have filtered anyway and adds lag; the noise that moves the body lies
near the loop's natural frequency. This observer integrates Euler's equation with the torque the
controller itself commands (known to the flight software) and only pulls toward the bias-corrected gyro
with gain ``L``, so near and above ``L`` the rate comes from the model (no lag on commanded motion, no
gyro noise) and below ``L`` from the gyro (which corrects the model's errors: unknown disturbance torques,
inertia error)::

    a      = I⁻¹ (τ − ω̂ × (I ω̂ + h_w))                 (rad/s², B; τ the body torque over the last cycle)
    r      = ω_meas − (ω̂ + a Δt/2)                     (the gyro mean describes the interval's middle)
    ω̂     ← ω̂ + a Δt + (1 − e^(−L Δt)) r

Units: rad/s, N·m, N·m·s, kg·m², s. The inertia is diagonal (principal moments in B); products of
inertia below 1 % of the moments are neglected.
"""

from __future__ import annotations

import math

from detumble.control.quaternion import Vec3

__all__ = ["RateObserver"]


class RateObserver:
    """Args: ``inertia_kg_m2`` the three principal moments (B axes), ``gain_per_s`` the pull ``L`` toward the gyro."""

    def __init__(self, inertia_kg_m2: Vec3, gain_per_s: float) -> None:
        self.set_model(inertia_kg_m2, gain_per_s)
        self.omega: Vec3 | None = None

    def set_model(self, inertia_kg_m2: Vec3, gain_per_s: float) -> None:
        if not all(math.isfinite(i) and i > 0.0 for i in inertia_kg_m2):
            raise ValueError(f"inertia_kg_m2 must be three positive moments, got {inertia_kg_m2}")
        if not (math.isfinite(gain_per_s) and gain_per_s > 0.0):
            raise ValueError(f"gain_per_s must be positive, got {gain_per_s}")
        self.inertia = (float(inertia_kg_m2[0]), float(inertia_kg_m2[1]), float(inertia_kg_m2[2]))
        self.gain = float(gain_per_s)

    def reset(self, omega: Vec3 | None = None) -> None:
        self.omega = None if omega is None else (float(omega[0]), float(omega[1]), float(omega[2]))

    def update(self, omega_meas: Vec3, torque_B: Vec3, wheel_momentum_B: Vec3, dt: float) -> Vec3:
        """Advance by ``dt`` under ``torque_B`` (the body torque applied over the interval) and correct with
        ``omega_meas`` (bias-corrected gyro mean over it); returns the estimate now."""
        w = self.omega
        if w is None:
            self.omega = w = (float(omega_meas[0]), float(omega_meas[1]), float(omega_meas[2]))
            return w
        ix, iy, iz = self.inertia
        h = wheel_momentum_B
        hx, hy, hz = ix * w[0] + h[0], iy * w[1] + h[1], iz * w[2] + h[2]
        gx = w[1] * hz - w[2] * hy
        gy = w[2] * hx - w[0] * hz
        gz = w[0] * hy - w[1] * hx
        a = ((torque_B[0] - gx) / ix, (torque_B[1] - gy) / iy, (torque_B[2] - gz) / iz)
        k = 1.0 - math.exp(-self.gain * dt)
        half = 0.5 * dt
        out = tuple(w[i] + a[i] * dt + k * (omega_meas[i] - (w[i] + a[i] * half)) for i in range(3))
        self.omega = (out[0], out[1], out[2])
        return self.omega
