"""Sensor models: LIS2MDL magnetometer and LSM6DSO gyro, sample-and-hold at their output data rate.

Both sensors latch a new sample at every ODR instant ``k / odr`` (integer-nanosecond grid from
t = 0) and hold it until the next; a read returns the held sample plus the read time. The true
value at an ODR instant inside a plant step is linearly interpolated between the step's ends.
Noise is Gaussian, drawn from the sensor's own seeded ``random.Random`` (one draw per axis per
latched sample), so runs are reproducible and one sensor's noise does not shift another's.

Magnetometer (LIS2MDL): reports **gauss** (1 G = 1e-4 T). ``measured = quantise(b_B + K m_coils_B
+ bias + noise)``, quantisation 1.5 mG/LSB (round to nearest), saturation at +-full scale (50 G).
``K`` (T per A m^2, one gain per body axis, default 1.6e-3) is the coils' own field at the sensor:
sampling while a coil is on reads e.g. 1.6e-3 * 0.116 = 186 uT extra on X - several times the
Earth's field. ``ideal: true`` returns the true field at the read time: no hold, noise, bias,
quantisation or coupling.

Gyro (LSM6DSO): reports **rad/s** ``omega_BN_B``. Per-sample noise std = noise density *
sqrt(odr / 2) (the density over the output bandwidth), constant bias, quantisation at the
full-scale's sensitivity (4.375 mdps/LSB at 125 dps ... 70 mdps/LSB at 2000 dps) and saturation
at +-full scale.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

GAUSS_PER_TESLA = 1e4
LSM6DSO_SENSITIVITY_MDPS = {125.0: 4.375, 250.0: 8.75, 500.0: 17.5, 1000.0: 35.0, 2000.0: 70.0}


@dataclass(frozen=True)
class MagnetometerSpec:
    ideal: bool = False
    odr_hz: float = 100.0
    noise_std_gauss: float = 0.003
    bias_gauss: tuple[float, float, float] = (0.0, 0.0, 0.0)
    resolution_gauss: float = 0.0015
    full_scale_gauss: float = 50.0
    coupling_t_per_am2: tuple[float, float, float] = (1.6e-3, 1.6e-3, 1.6e-3)


@dataclass(frozen=True)
class GyroSpec:
    ideal: bool = False
    odr_hz: float = 104.0
    noise_density_dps_rthz: float = 0.0038
    bias_dps: tuple[float, float, float] = (0.0, 0.0, 0.0)
    full_scale_dps: float = 2000.0
    resolution_dps: float | None = None  # None: the LSM6DSO sensitivity for full_scale_dps (0 = off)

    @property
    def noise_std_dps(self) -> float:
        return self.noise_density_dps_rthz * math.sqrt(self.odr_hz / 2.0)

    @property
    def lsb_dps(self) -> float:
        if self.resolution_dps is not None:
            return self.resolution_dps
        return LSM6DSO_SENSITIVITY_MDPS.get(self.full_scale_dps, self.full_scale_dps / 32768.0 * 1e3) / 1e3


def _quantise(x: float, lsb: float, limit: float) -> float:
    if lsb > 0.0:
        x = math.floor(x / lsb + 0.5) * lsb
    if x > limit:
        return limit
    if x < -limit:
        return -limit
    return x


class _SampleHold:
    """Shared ODR bookkeeping on the integer-nanosecond grid."""

    def __init__(self, odr_hz: float) -> None:
        if not odr_hz > 0:
            raise ValueError(f"odr_hz must be positive, got {odr_hz}")
        self.period_ns = int(round(1e9 / odr_hz))
        self.sample_time_ns = -1

    def latest_instant(self, t0_ns: int, t1_ns: int) -> int | None:
        """Latest ODR instant in (t0, t1], or None."""
        k = t1_ns // self.period_ns
        tk = k * self.period_ns
        return tk if tk > t0_ns else None


class Magnetometer(_SampleHold):
    """LIS2MDL model. :meth:`read` returns ``(bx, by, bz, t_read)``: gauss and seconds."""

    def __init__(self, spec: MagnetometerSpec, seed: int | None = None) -> None:
        super().__init__(spec.odr_hz)
        self.spec = spec
        self.rng = random.Random(seed)
        self.sample_gauss = (0.0, 0.0, 0.0)
        g = GAUSS_PER_TESLA
        self._k = tuple(g * k for k in spec.coupling_t_per_am2)  # gauss per A m^2

    def measure(self, b_B: tuple[float, float, float],
                m_coils_B: tuple[float, float, float]) -> tuple[float, float, float]:
        """One noisy, quantised measurement (gauss) of true field ``b_B`` (T) with coils at ``m_coils_B``."""
        s = self.spec
        g = GAUSS_PER_TESLA
        k = self._k
        bias = s.bias_gauss
        x = g * b_B[0] + k[0] * m_coils_B[0] + bias[0]
        y = g * b_B[1] + k[1] * m_coils_B[1] + bias[1]
        z = g * b_B[2] + k[2] * m_coils_B[2] + bias[2]
        sd = s.noise_std_gauss
        if sd > 0.0:
            gauss = self.rng.gauss
            x += gauss(0.0, sd)
            y += gauss(0.0, sd)
            z += gauss(0.0, sd)
        lsb, fs = s.resolution_gauss, s.full_scale_gauss
        return (_quantise(x, lsb, fs), _quantise(y, lsb, fs), _quantise(z, lsb, fs))

    def latch(self, t0_ns: int, t1_ns: int, b0_B, b1_B, m_coils_B) -> None:
        """Take the sample due in (t0, t1] if any; ``b0_B``/``b1_B`` true field (T) at the ends."""
        tk = self.latest_instant(t0_ns, t1_ns)
        if tk is None:
            return
        s = (tk - t0_ns) / (t1_ns - t0_ns) if t1_ns > t0_ns else 1.0
        b = (b0_B[0] + s * (b1_B[0] - b0_B[0]), b0_B[1] + s * (b1_B[1] - b0_B[1]), b0_B[2] + s * (b1_B[2] - b0_B[2]))
        self.sample_gauss = self.measure(b, m_coils_B)
        self.sample_time_ns = tk


class Gyro(_SampleHold):
    """LSM6DSO model. :meth:`measure` returns rad/s."""

    def __init__(self, spec: GyroSpec, seed: int | None = None) -> None:
        super().__init__(spec.odr_hz)
        self.spec = spec
        self.rng = random.Random(seed)
        self.sample_rad_s = (0.0, 0.0, 0.0)
        self._sd = math.radians(spec.noise_std_dps)
        self._lsb = math.radians(spec.lsb_dps)
        self._fs = math.radians(spec.full_scale_dps)
        self._bias = tuple(math.radians(b) for b in spec.bias_dps)

    def measure(self, omega_B: tuple[float, float, float]) -> tuple[float, float, float]:
        bias = self._bias
        x, y, z = omega_B[0] + bias[0], omega_B[1] + bias[1], omega_B[2] + bias[2]
        sd = self._sd
        if sd > 0.0:
            gauss = self.rng.gauss
            x += gauss(0.0, sd)
            y += gauss(0.0, sd)
            z += gauss(0.0, sd)
        lsb, fs = self._lsb, self._fs
        return (_quantise(x, lsb, fs), _quantise(y, lsb, fs), _quantise(z, lsb, fs))

    def latch(self, t0_ns: int, t1_ns: int, w0_B, w1_B) -> None:
        tk = self.latest_instant(t0_ns, t1_ns)
        if tk is None:
            return
        s = (tk - t0_ns) / (t1_ns - t0_ns) if t1_ns > t0_ns else 1.0
        w = (w0_B[0] + s * (w1_B[0] - w0_B[0]), w0_B[1] + s * (w1_B[1] - w0_B[1]), w0_B[2] + s * (w1_B[2] - w0_B[2]))
        self.sample_rad_s = self.measure(w)
        self.sample_time_ns = tk
