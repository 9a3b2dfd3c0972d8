"""An on-board geomagnetic field model small enough for a flight computer: the centred tilted dipole (plain floats;
no framework import).

What it is for: a reference direction of the field in the inertial frame N, against which a magnetometer
reading in the body frame B fixes the attitude about another measured direction (TRIAD: the albedo correction of
the light-sensor Sun vector, ``control.albedo``). Only the direction is used there.

The model: the degree-1 Gauss coefficients of IGRF-14 at epoch 2025 (g10, g11, h11 in nT; reference radius
6371.2 km). In Earth-fixed coordinates E the dipole's potential is ``V = a³ (d·r) / r³`` with ``d = (g11, h11,
g10)``, so ``B_E = (a/r)³ [3 (d·r̂) r̂ − d]``; E is N turned by the Earth rotation angle θ about their common third
axis (``r_E = R3(θ) r_N``), θ as the on-board ephemeris gives it (``control.targets.Ephemeris.earth_angle``).

Accuracy against the full field (IGRF-14 to degree 13, the plant's) at 420 km within ±51.6° latitude, 5000
uniform points: the direction off by 6.8° at the median, 27.8° at p95, 35.7° at worst
(``python campaigns/adcs/dipole_vs_igrf.py``) — the weak-field regions (the South Atlantic Anomaly) are the worst.
For the albedo correction that error enters the nadir direction ê about the Sun line and is scaled down by the
albedo share (≤ 0.26), ``control.albedo``'s error budget.

Units: position m, angle rad, field tesla; N inertial.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

__all__ = ["dipole_field_N", "OnboardField", "IGRF2025_G10_NT", "IGRF2025_G11_NT", "IGRF2025_H11_NT",
           "IGRF_REFERENCE_RADIUS_M"]

#: nT: IGRF-14 degree-1 Gauss coefficients at epoch 2025.0.
IGRF2025_G10_NT = -29350.0
IGRF2025_G11_NT = -1410.3
IGRF2025_H11_NT = 4545.5
#: m: the IGRF reference radius.
IGRF_REFERENCE_RADIUS_M = 6371200.0


def dipole_field_N(r_N: Sequence[float], earth_angle_rad: float, *, g10_nT: float = IGRF2025_G10_NT,
                   g11_nT: float = IGRF2025_G11_NT, h11_nT: float = IGRF2025_H11_NT,
                   reference_radius_m: float = IGRF_REFERENCE_RADIUS_M) -> tuple[float, float, float]:
    """The centred tilted dipole's field (T, in N) at the position ``r_N`` (m, N) when the Earth rotation angle is
    ``earth_angle_rad``. Raises ValueError at the Earth's centre."""
    x, y, z = float(r_N[0]), float(r_N[1]), float(r_N[2])
    r2 = x * x + y * y + z * z
    if not r2 > 0.0:
        raise ValueError("the field model needs a position away from the Earth's centre")
    scale = reference_radius_m ** 3 * 1e-9  # a³, with nT → T
    ex, ey, ez = scale * g11_nT, scale * h11_nT, scale * g10_nT  # d in E
    c, s = math.cos(earth_angle_rad), math.sin(earth_angle_rad)
    dx, dy, dz = c * ex - s * ey, s * ex + c * ey, ez  # d in N: R3(θ)ᵀ d_E
    r = math.sqrt(r2)
    k = 3.0 * (dx * x + dy * y + dz * z) / r2
    inv_r3 = 1.0 / (r2 * r)
    return ((k * x - dx) * inv_r3, (k * y - dy) * inv_r3, (k * z - dz) * inv_r3)


class OnboardField:
    """The on-board field model as a function of position and Earth angle: the tilted dipole
    (:func:`dipole_field_N`, ``degree`` 1) or IGRF-14 truncated to ``degree`` (2…13, ``control.igrf``, its 2025.0
    coefficients without secular variation). Call with ``(r_N m, earth_angle_rad)``; returns T in N."""

    def __init__(self, degree: int = 1) -> None:
        from detumble.control.igrf import IgrfField

        self.degree = int(degree)
        if not 1 <= self.degree <= 13:
            raise ValueError(f"the on-board field model's degree must be 1…13, got {degree}")
        self._igrf = IgrfField(2025.0, self.degree) if self.degree > 1 else None

    def __call__(self, r_N: Sequence[float], earth_angle_rad: float) -> tuple[float, float, float]:  # noqa: N803
        if self._igrf is None:
            return dipole_field_N(r_N, earth_angle_rad)
        return self._igrf.b_N_at_angle((float(r_N[0]), float(r_N[1]), float(r_N[2])), earth_angle_rad)
