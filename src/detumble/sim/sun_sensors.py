"""The six coarse Sun sensors of the PROVES faces: the VEML6031 light sensors as a Sun sensor sees them.

One sensor on each face (X+, X−, Y+, Y−, Z+, Z−: the plant's face order), its normal the face's outward
normal. What each reads, in lux:

* **cosine response**: ``E = E_1AU / d² · max(0, n̂·ŝ_B)`` with ``E_1AU`` = :data:`FULL_SUN_LUX` (the luminous
  efficacy of extraterrestrial sunlight times the solar constant: 133 klx) and ``d`` the Earth–Sun distance
  (AU). A face turned away reads 0 (the sensor cannot go negative).
* **eclipse**: 0 on every face in the Earth's cylindrical shadow (``sim.sun.in_umbra``: orbit position and the
  Sun ephemeris ``sim.sun.sun_direction_N`` at the reading's time). Penumbra (~8 s a pass) is ignored.
* **noise** (the stated model, albedo-free, as issue 27 asks): each sensor's gain is off by a fixed factor
  ``1 + g_i`` drawn once from N(0, ``gain_sigma``) (default 2 %: part-to-part spread and the window's
  transmission); each reading adds white noise N(0, ``noise_sigma`` × E_1AU) (default 0.5 % of full Sun: the
  VEML6031's count noise and ADC quantisation at the flight's gain, integration time and photodiode size,
  rounded up), then is clipped at 0. Earth albedo, the sensor's non-cosine roll-off near grazing incidence and
  saturation are not modelled.

:class:`SunSensorModel` is framework-free; the simulated spacecraft (``drivers.spacecraft``) reads it for the
Veml6031Manager drivers, the plant-only Sun-safe check (``sim.sun_safe_check``) directly. Units: lux, AU, metres,
seconds; vectors in the body frame B unless named ``_N`` (inertial).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from detumble.sim.vec import rotate_n_to_b
from detumble.sim.sun import SOLAR_CONSTANT_W_M2, in_umbra, sun_direction_N

__all__ = ["FACE_NORMALS_B", "FULL_SUN_LUX", "LUX_PER_W_M2", "SunSensorSpec", "SunSensorModel", "ideal_illuminance"]

#: The faces' outward normals in B, in the plant's face order (X+, X−, Y+, Y−, Z+, Z−).
FACE_NORMALS_B: tuple[tuple[float, float, float], ...] = (
    (1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, -1.0))
#: Illuminance of the Sun at 1 AU at normal incidence, lux (133 000 lux for 1361 W/m²: 97.7 lm/W).
FULL_SUN_LUX = 133_000.0
#: lm/W: the luminous efficacy that turns the solar constant into FULL_SUN_LUX.
LUX_PER_W_M2 = FULL_SUN_LUX / SOLAR_CONSTANT_W_M2


@dataclass(frozen=True)
class SunSensorSpec:
    """The noise model's figures (fractions, 1σ): ``gain_sigma`` of each sensor's fixed gain error,
    ``noise_sigma`` of each reading's white noise as a fraction of :data:`FULL_SUN_LUX`."""

    gain_sigma: float = 0.02
    noise_sigma: float = 0.005

    def __post_init__(self) -> None:
        for name in ("gain_sigma", "noise_sigma"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and 0.0 <= value < 0.5):
                raise ValueError(f"SunSensorSpec.{name} must be a fraction in [0, 0.5), got {value!r}")


def ideal_illuminance(s_B, distance_au: float, eclipse: bool) -> tuple[float, ...]:
    """The six noise-free readings (lux) for the Sun's unit direction ``s_B`` at ``distance_au``."""
    if eclipse:
        return (0.0,) * 6
    e = FULL_SUN_LUX / (distance_au * distance_au)
    x, y, z = s_B
    return (e * max(0.0, x), e * max(0.0, -x), e * max(0.0, y), e * max(0.0, -y), e * max(0.0, z),
            e * max(0.0, -z))


class SunSensorModel:
    """Six face light sensors with the noise model of :class:`SunSensorSpec`, seeded (``seed``) so a run repeats.

    Args:
        epoch_jd: Julian date of plant t = 0 (the Sun's position).
        earth_radius_m: radius of the shadow cylinder.
        spec: the noise figures.
        seed: draws the gain errors, then the readings' noise.
    """

    def __init__(self, epoch_jd: float, earth_radius_m: float, spec: SunSensorSpec = SunSensorSpec(),
                 seed: int = 0) -> None:
        self.epoch_jd = float(epoch_jd)
        self.earth_radius_m = float(earth_radius_m)
        self.spec = spec
        self._rng = random.Random(seed * 104729 + 27)
        #: each sensor's fixed gain factor 1 + g_i
        self.gains = tuple(1.0 + self._rng.gauss(0.0, spec.gain_sigma) for _ in range(6))
        self.eclipse = False  #: the last reading's shadow state
        self._t_s: float | None = None
        self._readings: tuple[float, ...] = (0.0,) * 6

    def sun(self, t_s: float) -> tuple[tuple[float, float, float], float]:
        """``(ŝ_N, distance AU)`` at plant time ``t_s``."""
        return sun_direction_N(self.epoch_jd + t_s / 86400.0)

    def read(self, t_s: float, q_BN, r_N) -> tuple[float, ...]:
        """The six readings (lux) at plant time ``t_s`` for attitude ``q_BN`` (scalar first) at position ``r_N``
        (m); the same numbers again for the same ``t_s`` (one exposure per instant)."""
        if t_s == self._t_s:
            return self._readings
        s_N, d_au = self.sun(t_s)
        self.eclipse = in_umbra(r_N, s_N, self.earth_radius_m)
        ideal = ideal_illuminance(rotate_n_to_b(q_BN, s_N), d_au, self.eclipse)
        sigma = self.spec.noise_sigma * FULL_SUN_LUX
        gauss = self._rng.gauss
        self._readings = tuple(max(0.0, e * g + gauss(0.0, sigma)) for e, g in zip(ideal, self.gains, strict=True))
        self._t_s = t_s
        return self._readings

    def true_sun_B(self, t_s: float, q_BN) -> tuple[float, float, float]:
        """The true Sun direction in B at ``t_s`` (for studies and tests)."""
        return rotate_n_to_b(q_BN, self.sun(t_s)[0])

