"""B-dot dipole from a window of five magnetometer samples (detumble.md §6).

Plain Python (no framework import); runs on the 50 Hz path. Units: magnetic field in **gauss**
(body frame), timestamps and periods in integer **microseconds**, gain in A·m²·s/G, dipole moment in
**A·m²** (body frame).

Ḃ is estimated with the 5-point central difference at the window's middle sample::

    Ḃ_k = (B0_k − 8·B1_k + 8·B3_k − B4_k) / (12·Δt)      (B0 oldest, B2 unused; G/s)
    m_k = −GAIN · Ḃ_k                                     (A·m²; no division by |B|)

Δt is the mean spacing of the window's timestamps, ``(t4 − t0) / 4`` (DEVIATION: the flight code
uses the magnetometer output period, half the real spacing at 50 Hz reads of a 100 Hz sensor). If
the timestamps are not strictly increasing, the configured magnetometer period is used instead; if
that is not positive either, the dipole is zero.
"""

from __future__ import annotations

import math
from typing import Sequence

__all__ = ["BDot", "WINDOW_SIZE"]

#: Number of samples in the estimation window.
WINDOW_SIZE = 5

_ZERO = (0.0, 0.0, 0.0)


class BDot:
    """Collects a window of B samples and turns it into a damping dipole moment."""

    def __init__(self) -> None:
        self.gain = 0.0  # A·m²·s/G
        self.magnetometer_sampling_period_us = 0  # µs
        self._fields: list[tuple[float, float, float]] = []
        self._times_us: list[int] = []

    def configure(self, gain: float, magnetometer_sampling_period_us: int) -> None:
        """Set the gain (A·m²·s/G) and the magnetometer output period (µs, the Δt fallback)."""
        self.gain = float(gain)
        self.magnetometer_sampling_period_us = magnetometer_sampling_period_us

    @property
    def sample_count(self) -> int:
        return len(self._fields)

    def add_sample(self, magnetic_field_gauss: Sequence[float], timestamp_us: int) -> bool:
        """Append one reading (gauss, body frame) taken at ``timestamp_us`` µs.

        Returns False, storing nothing, when the window is already full or when a component is
        not a finite number (a NaN or infinite reading must never reach the dipole).
        """
        if len(self._fields) >= WINDOW_SIZE:
            return False
        bx, by, bz = magnetic_field_gauss  # unpacked, then converted: no generator (a read every sensing tick)
        bx, by, bz = float(bx), float(by), float(bz)
        if not (math.isfinite(bx) and math.isfinite(by) and math.isfinite(bz)):
            return False
        self._fields.append((bx, by, bz))
        self._times_us.append(int(timestamp_us))
        return True

    def sampling_complete(self) -> bool:
        """True when the window holds all five samples."""
        return len(self._fields) >= WINDOW_SIZE

    def get_time_between_samples(self) -> int:
        """Time from the first to the last sample of the window, µs (0 with fewer than 2 samples)."""
        if len(self._times_us) < 2:
            return 0
        return self._times_us[-1] - self._times_us[0]

    def empty_sample_set(self) -> None:
        """Forget every sample."""
        self._fields.clear()
        self._times_us.clear()

    def sample_spacing_s(self) -> float:
        """The Δt used by the estimator, s: the mean timestamp spacing, else the configured
        magnetometer period, else 0.0 (no usable Δt)."""
        t = self._times_us
        if len(t) == WINDOW_SIZE and all(t[i] < t[i + 1] for i in range(WINDOW_SIZE - 1)):
            return (t[4] - t[0]) / 4 / 1e6
        period = self.magnetometer_sampling_period_us
        if isinstance(period, (int, float)) and math.isfinite(period) and period > 0:
            return period / 1e6
        return 0.0

    def compute_bdot(self) -> tuple[float, float, float]:
        """Ḃ at the window's middle sample, G/s (zeros when the window is not full or Δt is unusable)."""
        if not self.sampling_complete():
            return _ZERO
        dt = self.sample_spacing_s()
        if not dt > 0.0:
            return _ZERO
        b0, b1, _, b3, b4 = self._fields
        d = 12.0 * dt
        return ((b0[0] - 8.0 * b1[0] + 8.0 * b3[0] - b4[0]) / d,
                (b0[1] - 8.0 * b1[1] + 8.0 * b3[1] - b4[1]) / d,
                (b0[2] - 8.0 * b1[2] + 8.0 * b3[2] - b4[2]) / d)

    def get_magnetic_moment(self) -> tuple[float, float, float]:
        """Dipole ``m = −GAIN · Ḃ``, A·m² (body frame). Zero when the window is not full, Δt is
        unusable or the result is not finite."""
        bdot = self.compute_bdot()
        gain = self.gain
        moment = (-gain * bdot[0], -gain * bdot[1], -gain * bdot[2])
        if not all(math.isfinite(c) for c in moment):
            return _ZERO
        return moment
