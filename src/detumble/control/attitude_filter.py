"""A small attitude filter: gyro propagation corrected by star-tracker quaternions, with a gyro-bias
estimate (a complementary filter on SO(3); plain floats, no framework import).

Why: the default gyro has a bias of up to 0.3 °/s; in the PD law's ``K_d ω`` term that alone holds
the attitude about ``K_d b / (K_p/2)`` away from the target (over a degree with the default gains).
The filter estimates the bias from the star tracker and hands the controller ``q̂`` and
``ω̂ = ω_gyro − b̂``.

    e   = 2 vec(q̂⁻¹ ⊗ q_st)          (small rotation from the estimate to the measurement, rad, B)
    q̂  ← q̂ ⊗ exp(½ (ω_gyro − b̂) Δt)           (propagate to the measurement's time)
    q̂  ← q̂ ⊗ exp(½ k_p e Δt),  b̂ ← b̂ − k_i e Δt   (correct)

Gains: ``k_p`` 1/s, ``k_i`` 1/s². Without a star-tracker sample the estimate is propagated on the
gyro alone; the estimate is "valid" only while the last measurement is recent.
"""

from __future__ import annotations

import math

from detumble.control.quaternion import Quat, Vec3, quat_conj, quat_mul, quat_normalize, quat_shortest

__all__ = ["AttitudeFilter"]


class AttitudeFilter:
    def __init__(self, k_p: float = 0.5, k_i: float = 0.02) -> None:
        self.k_p = float(k_p)
        self.k_i = float(k_i)
        self.q: Quat | None = None
        self.bias: Vec3 = (0.0, 0.0, 0.0)
        self.omega: Vec3 = (0.0, 0.0, 0.0)
        self.since_measurement_s = math.inf

    def reset(self) -> None:
        self.q = None
        self.bias = (0.0, 0.0, 0.0)
        self.since_measurement_s = math.inf

    def update(self, omega_gyro_B: Vec3, dt: float, q_measured: Quat | None = None, age_s: float = 0.0) -> None:
        """Advance by ``dt`` s with the gyro rate (rad/s, B) held over the interval that ends now, then
        correct with ``q_measured`` (``q_BN`` taken ``age_s`` s ago: a held star-tracker solution is
        carried to now on the bias-corrected gyro before it is compared), when given."""
        b = self.bias
        if q_measured is not None and age_s > 0.0:
            q_measured = _propagate(q_measured, (omega_gyro_B[0] - b[0], omega_gyro_B[1] - b[1],
                                                 omega_gyro_B[2] - b[2]), age_s)
        self.since_measurement_s += dt
        if self.q is None:
            if q_measured is not None:
                self.q = quat_shortest(q_measured)
                self.since_measurement_s = 0.0
            self.omega = (omega_gyro_B[0] - b[0], omega_gyro_B[1] - b[1], omega_gyro_B[2] - b[2])
            return
        q = _propagate(self.q, (omega_gyro_B[0] - b[0], omega_gyro_B[1] - b[1], omega_gyro_B[2] - b[2]), dt)
        if q_measured is not None:
            qe = quat_shortest(quat_mul(quat_conj(q), q_measured))
            e = (2.0 * qe[1], 2.0 * qe[2], 2.0 * qe[3])
            kp, ki = self.k_p, self.k_i
            q = _propagate(q, (kp * e[0], kp * e[1], kp * e[2]), dt)
            self.bias = b = (b[0] - ki * e[0] * dt, b[1] - ki * e[1] * dt, b[2] - ki * e[2] * dt)
            self.since_measurement_s = 0.0
        self.q = q
        self.omega = (omega_gyro_B[0] - b[0], omega_gyro_B[1] - b[1], omega_gyro_B[2] - b[2])


def _propagate(q: Quat, w: Vec3, dt: float) -> Quat:
    """``q ⊗ exp(½ w dt)``: turn the estimate by the body-frame rotation vector ``w dt``."""
    n = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    if n == 0.0:
        return q
    half = 0.5 * n * dt
    s = math.sin(half) / n
    return quat_normalize(quat_mul(q, (math.cos(half), w[0] * s, w[1] * s, w[2] * s)))
