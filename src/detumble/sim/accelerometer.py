"""The LSM6DSO accelerometer: specific force at the IMU with bias, noise and quantisation.

In orbit the spacecraft is in free fall, so the true specific force at the centre of mass is zero
(no drag is modelled). The IMU sits at ``lever_arm_m`` from the centre of mass, so a tumbling body
adds the centripetal term ``ω × (ω × r)`` (the angular-acceleration term is negligible: detumble
torques give |ω̇| < 1e-3 rad/s²). The sensor adds a constant zero-g offset ``bias_mps2`` and white
noise of ``noise_std_mps2`` per sample, then quantises to ``lsb_mps2`` and clips at the full scale —
so a real reading is never exactly zero.

Units m/s², body axes B (sensor frame = body frame). Defaults: the LSM6DSO at ±2 g, 104 Hz,
high-performance mode (70 µg/√Hz → 0.005 m/s² per sample, 0.061 mg/LSB, zero-g offset up to
±20 mg; the default offset is a plausible 5–12 mg).
"""

from __future__ import annotations

import random
from dataclasses import dataclass

__all__ = ["AccelerometerSpec", "Accelerometer", "STANDARD_GRAVITY"]

STANDARD_GRAVITY = 9.80665  #: m/s² per g


@dataclass(frozen=True)
class AccelerometerSpec:
    bias_mps2: tuple = (0.049, -0.078, 0.118)     #: zero-g offset, m/s² (5, −8, 12 mg)
    noise_std_mps2: float = 0.005                  #: white noise per sample, m/s²
    lsb_mps2: float = 0.061e-3 * STANDARD_GRAVITY  #: resolution at ±2 g
    full_scale_mps2: float = 2.0 * STANDARD_GRAVITY
    lever_arm_m: tuple = (0.02, 0.01, -0.03)       #: IMU position from the centre of mass, B
    ideal: bool = False                            #: True: the exact specific force, no errors


class Accelerometer:
    """Draws one reading per call (the LSM6DSO's output register, read on demand)."""

    def __init__(self, spec: AccelerometerSpec, seed: int | None = None) -> None:
        self.spec = spec
        self._rng = random.Random(seed)

    def true_specific_force(self, omega_B) -> tuple[float, float, float]:
        """``ω × (ω × r)``, m/s² (centripetal acceleration at the IMU)."""
        wx, wy, wz = omega_B
        rx, ry, rz = self.spec.lever_arm_m
        cx, cy, cz = wy * rz - wz * ry, wz * rx - wx * rz, wx * ry - wy * rx
        return (wy * cz - wz * cy, wz * cx - wx * cz, wx * cy - wy * cx)

    def measure(self, omega_B) -> tuple[float, float, float]:
        a = self.true_specific_force(omega_B)
        s = self.spec
        if s.ideal:
            return a
        gauss = self._rng.gauss
        out = []
        for k in range(3):
            v = a[k] + s.bias_mps2[k] + gauss(0.0, s.noise_std_mps2)
            if s.lsb_mps2 > 0.0:
                v = round(v / s.lsb_mps2) * s.lsb_mps2
            out.append(max(-s.full_scale_mps2, min(s.full_scale_mps2, v)))
        return (out[0], out[1], out[2])
