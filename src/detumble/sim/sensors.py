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

Sampling is lazy: at each ODR instant the plant only records what the sample will be computed
from (:meth:`Magnetometer.defer`, :meth:`Gyro.defer`); the value is worked out when
``sample_gauss`` / ``sample_rad_s`` is read. A sample superseded before anyone read it still
consumes its three noise draws (:func:`skip_gauss`), so every sample that is read is bit for bit
the one eager sampling gives.
"""

from __future__ import annotations

import math
import random
from typing import Any
from dataclasses import dataclass

from detumble.control.units import GAUSS_PER_TESLA
from detumble.sim.vec import rotate_n_to_b

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


def _quantise3(x: float, y: float, z: float, lsb: float, limit: float) -> tuple[float, float, float]:
    """Each of the three components quantised to ``lsb`` and limited to ±``limit``: :func:`_quantise` of
    each, in one call (every sensor sample read passes here)."""
    if lsb > 0.0:
        floor = math.floor
        x = floor(x / lsb + 0.5) * lsb
        y = floor(y / lsb + 0.5) * lsb
        z = floor(z / lsb + 0.5) * lsb
    return (limit if x > limit else -limit if x < -limit else x,
            limit if y > limit else -limit if y < -limit else y,
            limit if z > limit else -limit if z < -limit else z)


def skip_gauss(rng: random.Random, n: int) -> None:
    """Advance ``rng`` exactly as ``n`` calls of ``rng.gauss`` would, without computing them.

    ``random.Random.gauss`` makes its draws in pairs from two ``random()`` values, keeping the
    second of a pair in ``gauss_next``: a whole pair is two ``random()`` calls; an odd draw left
    over is a real ``gauss`` call so that the cached half of its pair is the true one.
    """
    if n <= 0:
        return
    held: Any = rng  # CPython's Random keeps gauss's cached half in gauss_next, which typeshed omits
    if held.gauss_next is not None:  # the pending second half of a pair is the next draw
        held.gauss_next = None
        n -= 1
    if n >= 2:
        # a pair's two random() calls take two 32-bit outputs of the Mersenne Twister each; getrandbits
        # takes one output a 32 bits asked, so one call skips every whole pair
        rng.getrandbits(128 * (n // 2))
    if n % 2:
        rng.gauss()


class _SampleHold:
    """Shared ODR bookkeeping on the integer-nanosecond grid."""

    def __init__(self, odr_hz: float) -> None:
        if not odr_hz > 0:
            raise ValueError(f"odr_hz must be positive, got {odr_hz}")
        self.period_ns = int(round(1e9 / odr_hz))
        self.sample_time_ns = -1
        self.rng = random.Random()
        self._draws = 0  # noise draws per sample
        #: the inputs of the latest sample, not computed yet (see the subclasses' ``defer``)
        self._pending: tuple | None = None
        self._skipped = 0  # samples superseded unread since the last one computed
        self._sample: tuple[float, float, float] = (0.0, 0.0, 0.0)
        #: the compiled kernel's resolve of a held sample (the same floats and draws as the Python below), set by a
        #: plant flying the kernel (:meth:`.plant.Plant.__init__`); None: the Python
        self.compiled: Any = None

    def _held(self) -> tuple[float, float, float]:
        """The held sample, computed now if it was deferred."""
        if self._pending is not None:
            self._resolve()
        return self._sample

    def _hold(self, value: tuple[float, float, float]) -> None:
        """Replace the held sample (the deferred one's noise draws are consumed first)."""
        self._discard_unread()
        self._sample = value

    def _resolve(self) -> None:
        raise NotImplementedError

    def _discard_unread(self) -> None:
        """Drop the deferred sample, consuming the noise draws of every sample not computed."""
        if self._pending is not None:
            self._pending = None
            self._skipped += 1
        if self._skipped:
            skip_gauss(self.rng, self._draws * self._skipped)
            self._skipped = 0

    def _take_pending(self) -> tuple:
        """The deferred sample's inputs, the draws of the unread samples before it consumed."""
        pending = self._pending
        self._pending = None
        if self._skipped:
            skip_gauss(self.rng, self._draws * self._skipped)
            self._skipped = 0
        return pending  # type: ignore[return-value]

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
        self._draws = 3 if spec.noise_std_gauss > 0.0 else 0  # noise draws per sample
        g = GAUSS_PER_TESLA
        self._k = tuple(g * k for k in spec.coupling_t_per_am2)  # gauss per A m^2

    def _held_gauss(self) -> tuple[float, float, float]:
        """The held sample, gauss (body axes), computed now if it was deferred: the field at the
        step's ends rotated into B, interpolated to the sample's instant and measured."""
        if self._pending is None:
            return self._sample
        t0, t1, q0, q1, b0_N, b1_N, m = self._take_pending()
        if self.compiled is not None:  # plant_kernel.c magnetometer_sample: the lines below, compiled
            tk, s = self.sample_time_ns, self.spec
            sample = self._sample = self.compiled(q0, q1, b0_N, b1_N, (tk - t0) / (t1 - t0) if t1 > t0 else 1.0, m,
                                                  GAUSS_PER_TESLA, self._k, s.bias_gauss, s.noise_std_gauss,
                                                  s.resolution_gauss, s.full_scale_gauss, self.rng)
            return sample
        b0 = rotate_n_to_b((q0[0], q0[1], q0[2], q0[3]), b0_N)
        b1 = rotate_n_to_b((q1[0], q1[1], q1[2], q1[3]), b1_N)
        sample = self._sample = self._interpolated(t0, t1, self.sample_time_ns, b0, b1, m)
        return sample

    #: The held sample, gauss (body axes); computed when first read after a deferral.
    sample_gauss = property(_held_gauss, lambda self, value: self._hold(value))

    def measure(self, b_B: tuple[float, float, float],
                m_coils_B: tuple[float, float, float]) -> tuple[float, float, float]:
        """One noisy, quantised measurement (gauss) of true field ``b_B`` (T) with coils at ``m_coils_B``."""
        if self._pending is not None:  # the deferred sample draws its noise first, as eagerly
            self._resolve()
        return self._measured(b_B[0], b_B[1], b_B[2], m_coils_B)

    def _measured(self, bx: float, by: float, bz: float,
                  m_coils_B: tuple[float, float, float]) -> tuple[float, float, float]:
        """:meth:`measure` of the field ``(bx, by, bz)`` (T), no deferred sample pending."""
        s = self.spec
        g = GAUSS_PER_TESLA
        k = self._k
        bias = s.bias_gauss
        x = g * bx + k[0] * m_coils_B[0] + bias[0]
        y = g * by + k[1] * m_coils_B[1] + bias[1]
        z = g * bz + k[2] * m_coils_B[2] + bias[2]
        sd = s.noise_std_gauss
        if sd > 0.0:
            gauss = self.rng.gauss
            x += gauss(0.0, sd)
            y += gauss(0.0, sd)
            z += gauss(0.0, sd)
        return _quantise3(x, y, z, s.resolution_gauss, s.full_scale_gauss)

    def latch(self, t0_ns: int, t1_ns: int, b0_B, b1_B, m_coils_B) -> None:
        """Take the sample due in (t0, t1] if any; ``b0_B``/``b1_B`` true field (T) at the ends."""
        tk = self.latest_instant(t0_ns, t1_ns)
        if tk is None:
            return
        self._discard_unread()
        self._sample = self._interpolated(t0_ns, t1_ns, tk, b0_B, b1_B, m_coils_B)
        self.sample_time_ns = tk

    def defer(self, t0_ns: int, t1_ns: int, tk_ns: int, q0_BN, q1_BN, b0_N, b1_N, m_coils_B) -> None:
        """Record the sample at ODR instant ``tk_ns`` in (t0, t1] without computing it.

        ``q0_BN``/``q1_BN`` are the attitudes (scalar first; longer state tuples are fine) and
        ``b0_N``/``b1_N`` the inertial field (T) at the step's ends; ``m_coils_B`` the coils'
        dipole over the step (A m^2). The sample is computed when it is first read.
        """
        if self._pending is not None:
            self._skipped += 1
        self._pending = (t0_ns, t1_ns, q0_BN, q1_BN, b0_N, b1_N, m_coils_B)
        self.sample_time_ns = tk_ns

    def _resolve(self) -> None:
        self._held_gauss()

    def _interpolated(self, t0_ns: int, t1_ns: int, tk: int, b0_B, b1_B, m_coils_B) -> tuple[float, float, float]:
        s = (tk - t0_ns) / (t1_ns - t0_ns) if t1_ns > t0_ns else 1.0
        # no sample is pending here (taken or discarded by the callers): measure()'s check is not needed
        return self._measured(b0_B[0] + s * (b1_B[0] - b0_B[0]), b0_B[1] + s * (b1_B[1] - b0_B[1]),
                              b0_B[2] + s * (b1_B[2] - b0_B[2]), m_coils_B)


class Gyro(_SampleHold):
    """LSM6DSO model. :meth:`measure` returns rad/s."""

    def __init__(self, spec: GyroSpec, seed: int | None = None) -> None:
        super().__init__(spec.odr_hz)
        self.spec = spec
        self.rng = random.Random(seed)
        self._sd = math.radians(spec.noise_std_dps)
        self._draws = 3 if self._sd > 0.0 else 0
        self._lsb = math.radians(spec.lsb_dps)
        self._fs = math.radians(spec.full_scale_dps)
        self._bias = tuple(math.radians(b) for b in spec.bias_dps)

    def measure(self, omega_B: tuple[float, float, float]) -> tuple[float, float, float]:
        if self._pending is not None:  # the deferred sample draws its noise first, as eagerly
            self._resolve()
        return self._measured(omega_B[0], omega_B[1], omega_B[2])

    def _measured(self, wx: float, wy: float, wz: float) -> tuple[float, float, float]:
        """:meth:`measure` of the rate ``(wx, wy, wz)`` (rad/s), no deferred sample pending."""
        bias = self._bias
        x, y, z = wx + bias[0], wy + bias[1], wz + bias[2]
        sd = self._sd
        if sd > 0.0:
            gauss = self.rng.gauss
            x += gauss(0.0, sd)
            y += gauss(0.0, sd)
            z += gauss(0.0, sd)
        return _quantise3(x, y, z, self._lsb, self._fs)

    def _held_rad_s(self) -> tuple[float, float, float]:
        """The held sample, rad/s (body axes), computed now if it was deferred: the rate (the states'
        slots 4..6) interpolated to the sample's instant and measured."""
        if self._pending is None:
            return self._sample
        t0, t1, s0, s1 = self._take_pending()
        if self.compiled is not None:  # plant_kernel.c gyro_sample: the lines below, compiled
            tk = self.sample_time_ns
            sample = self._sample = self.compiled(s0, s1, (tk - t0) / (t1 - t0) if t1 > t0 else 1.0, self._bias,
                                                  self._sd, self._lsb, self._fs, self.rng)
            return sample
        sample = self._sample = self._interpolated(t0, t1, self.sample_time_ns, (s0[4], s0[5], s0[6]),
                                                   (s1[4], s1[5], s1[6]))
        return sample

    #: The held sample, rad/s (body axes); computed when first read after a deferral.
    sample_rad_s = property(_held_rad_s, lambda self, value: self._hold(value))

    def latch(self, t0_ns: int, t1_ns: int, w0_B, w1_B) -> None:
        tk = self.latest_instant(t0_ns, t1_ns)
        if tk is None:
            return
        self._discard_unread()
        self._sample = self._interpolated(t0_ns, t1_ns, tk, w0_B, w1_B)
        self.sample_time_ns = tk

    def defer(self, t0_ns: int, t1_ns: int, tk_ns: int, s0, s1) -> None:
        """Record the sample at ODR instant ``tk_ns`` in (t0, t1] without computing it; ``s0``/``s1``
        are the plant states (``omega_BN_B`` at indices 4..6) at the step's ends."""
        if self._pending is not None:
            self._skipped += 1
        self._pending = (t0_ns, t1_ns, s0, s1)
        self.sample_time_ns = tk_ns

    def _resolve(self) -> None:
        self._held_rad_s()

    def _interpolated(self, t0_ns: int, t1_ns: int, tk: int, w0_B, w1_B) -> tuple[float, float, float]:
        s = (tk - t0_ns) / (t1_ns - t0_ns) if t1_ns > t0_ns else 1.0
        # no sample is pending here (taken or discarded by the callers): measure()'s check is not needed
        return self._measured(w0_B[0] + s * (w1_B[0] - w0_B[0]), w0_B[1] + s * (w1_B[1] - w0_B[1]),
                              w0_B[2] + s * (w1_B[2] - w0_B[2]))
