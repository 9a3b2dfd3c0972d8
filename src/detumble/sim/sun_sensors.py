"""The six coarse Sun sensors of the PROVES faces: the VEML6031 light sensors as a Sun sensor sees them.

One sensor on each face (X+, X−, Y+, Y−, Z+, Z−: the plant's face order), its normal the face's outward
normal. What each reads, in lux:

* **cosine response**: ``E = E_1AU / d² · max(0, n̂·ŝ_B)`` with ``E_1AU`` = :data:`FULL_SUN_LUX` (the luminous
  efficacy of extraterrestrial sunlight times the solar constant: 133 klx) and ``d`` the Earth–Sun distance
  (AU). A face turned away reads 0 (the sensor cannot go negative).
* **eclipse**: 0 on every face in the Earth's cylindrical shadow (``sim.sun.in_umbra``: orbit position and the
  Sun ephemeris ``sim.sun.sun_direction_N`` at the reading's time); with ``penumbra`` the conical model instead
  (``sim.sun.sunlit_fraction``): the direct light scaled by the visible fraction of the Sun's disc (~8 s a pass).
* **Earth albedo** (``albedo`` > 0; the stated model): the Earth's reflected light as from a point source at its
  centre, of illuminance ``E_1AU / d² · a · (R_E / r)² · max(0, r̂·ŝ)`` (``a`` the Bond albedo, 0.30 for the
  Earth's mean; ``(R_E/r)²`` the Lambertian sphere's view factor to nadir; ``r̂·ŝ`` the Sun's elevation at the
  sub-satellite point standing in for the lit share of the visible disc), with the same cosine response toward
  nadir on each face. At 500 km with the Sun overhead it is 26 % of full Sun on the nadir face. It ignores the
  disc's extent (faces up to 20° beyond the horizon see none of it here), clouds, and the terminator's shape.
* **noise** (the stated model, albedo-free, as issue 27 asks): each sensor's gain is off by a fixed factor
  ``1 + g_i`` drawn once from N(0, ``gain_sigma``) (default 2 %: part-to-part spread and the window's
  transmission); each reading adds white noise N(0, ``noise_sigma`` × E_1AU) (default 0.5 % of full Sun: the
  VEML6031's count noise and ADC quantisation at the flight's gain, integration time and photodiode size,
  rounded up), then is clipped at 0. The sensor's non-cosine roll-off near grazing incidence and saturation are
  not modelled.

:class:`SunSensorModel` is framework-free; the simulated spacecraft (``drivers.spacecraft``) reads it for the
Veml6031Manager drivers, the plant-only Sun-safe check (``sim.sun_safe_check``) directly. Units: lux, AU, metres,
seconds; vectors in the body frame B unless named ``_N`` (inertial).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from detumble.sim.vec import rotate_n_to_b
from detumble.sim.sun import SOLAR_CONSTANT_W_M2, in_umbra, sun_direction_N, sunlit_fraction

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
    ``noise_sigma`` of each reading's white noise as a fraction of :data:`FULL_SUN_LUX`; the environment:
    ``albedo`` the Earth's Bond albedo (0: none, the default, as the deployments fly), ``penumbra`` the conical
    shadow instead of the cylinder."""

    gain_sigma: float = 0.02
    noise_sigma: float = 0.005
    albedo: float = 0.0
    penumbra: bool = False

    def __post_init__(self) -> None:
        for name in ("gain_sigma", "noise_sigma"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and 0.0 <= value < 0.5):
                raise ValueError(f"SunSensorSpec.{name} must be a fraction in [0, 0.5), got {value!r}")
        a = self.albedo
        if not (isinstance(a, (int, float)) and math.isfinite(a) and 0.0 <= a < 1.0):
            raise ValueError(f"SunSensorSpec.albedo must be a fraction in [0, 1) (Earth's mean: 0.30), got {a!r}")
        if not isinstance(self.penumbra, bool):
            raise ValueError(f"SunSensorSpec.penumbra must be true or false, got {self.penumbra!r}")


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
        spec = self.spec
        lit = 1.0
        if spec.penumbra:
            lit = sunlit_fraction(r_N, s_N, d_au, self.earth_radius_m)
            self.eclipse = lit <= 0.0
        else:
            self.eclipse = in_umbra(r_N, s_N, self.earth_radius_m)
        ideal = ideal_illuminance(rotate_n_to_b(q_BN, s_N), d_au, self.eclipse)
        if lit < 1.0:
            ideal = tuple(e * lit for e in ideal)
        if spec.albedo > 0.0:
            ideal = self._add_albedo(ideal, q_BN, r_N, s_N, d_au)
        sigma = self.spec.noise_sigma * FULL_SUN_LUX
        gauss = self._rng.gauss
        self._readings = tuple(max(0.0, e * g + gauss(0.0, sigma)) for e, g in zip(ideal, self.gains, strict=True))
        self._t_s = t_s
        return self._readings

    def _add_albedo(self, ideal, q_BN, r_N, s_N, d_au: float) -> tuple[float, ...]:
        """``ideal`` plus the Earth's reflected light (the stated point-source model, module docstring)."""
        rn = math.sqrt(r_N[0] * r_N[0] + r_N[1] * r_N[1] + r_N[2] * r_N[2])
        up = (r_N[0] / rn, r_N[1] / rn, r_N[2] / rn)
        elevation = up[0] * s_N[0] + up[1] * s_N[1] + up[2] * s_N[2]
        if elevation <= 0.0:
            return ideal
        ratio = self.earth_radius_m / rn
        e = FULL_SUN_LUX / (d_au * d_au) * self.spec.albedo * ratio * ratio * elevation
        x, y, z = rotate_n_to_b(q_BN, (-up[0], -up[1], -up[2]))
        cosines = (max(0.0, x), max(0.0, -x), max(0.0, y), max(0.0, -y), max(0.0, z), max(0.0, -z))
        return tuple(i + e * c for i, c in zip(ideal, cosines, strict=True))

    def true_sun_B(self, t_s: float, q_BN) -> tuple[float, float, float]:
        """The true Sun direction in B at ``t_s`` (for studies and tests)."""
        return rotate_n_to_b(q_BN, self.sun(t_s)[0])

