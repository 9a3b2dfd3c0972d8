"""Where the Sun is, and whether the Earth hides it: the inputs of the solar-array model.

* :func:`sun_direction_N` — the unit vector from the Earth's centre to the Sun in the inertial frame
  N (J2000-like equatorial; precession ignored) from the low-precision solar coordinates of the
  Astronomical Almanac (about 0.01 deg over 1950–2050), and the Earth–Sun distance in AU.
* :func:`in_umbra` — the cylindrical shadow model: the spacecraft is in eclipse when it is behind the
  Earth (``r·s < 0``) and within one Earth radius of the Earth–Sun line. Penumbra is ignored (it
  lasts ~8 s per pass in LEO).
* :func:`sunlit_fraction` — the conical (umbra/penumbra) shadow model of Montenbruck & Gill (*Satellite
  Orbits*, 3.4.2): the fraction of the Sun's disc not hidden by the Earth's, both as discs of their
  apparent radii, overlapping as plane circles. Used where a penumbra is asked for; ``in_umbra`` stays
  the power model's.
* :func:`eclipse_fraction_circular` — the closed form of the eclipse fraction of a circular orbit
  under that shadow model, for tests and mission planning.

Units: metres, radians, AU. Time is a Julian date (UTC used as TT; 69 s make 0.0008 deg of solar
longitude).
"""

from __future__ import annotations

import math

__all__ = ["sun_direction_N", "in_umbra", "sunlit_fraction", "eclipse_fraction_circular", "SOLAR_CONSTANT_W_M2",
           "SUN_RADIUS_M", "AU_M"]

#: Total solar irradiance at 1 AU, W/m² (TSIS-1 mean).
SOLAR_CONSTANT_W_M2 = 1361.0

_J2000_JD = 2451545.0
#: The Sun's radius, m (IAU 2015 nominal), and the astronomical unit, m.
SUN_RADIUS_M = 6.957e8
AU_M = 1.495978707e11


def sun_direction_N(jd: float) -> tuple[tuple[float, float, float], float]:
    """``(s_hat_N, distance_au)``: the Sun's direction from the Earth (unit vector in N) at ``jd``."""
    n = jd - _J2000_JD
    mean_longitude = math.radians((280.460 + 0.9856474 * n) % 360.0)
    g = math.radians((357.528 + 0.9856003 * n) % 360.0)
    ecliptic_longitude = mean_longitude + math.radians(1.915) * math.sin(g) + math.radians(0.020) * math.sin(2 * g)
    obliquity = math.radians(23.439 - 4.0e-7 * n)
    cl, sl = math.cos(ecliptic_longitude), math.sin(ecliptic_longitude)
    distance = 1.00014 - 0.01671 * math.cos(g) - 0.00014 * math.cos(2 * g)
    return (cl, math.cos(obliquity) * sl, math.sin(obliquity) * sl), distance


def in_umbra(r_N: tuple[float, float, float], s_hat_N: tuple[float, float, float], earth_radius_m: float) -> bool:
    """True when position ``r_N`` (m) is in the Earth's cylindrical shadow for Sun direction ``s_hat_N``."""
    along = r_N[0] * s_hat_N[0] + r_N[1] * s_hat_N[1] + r_N[2] * s_hat_N[2]
    if along >= 0.0:
        return False
    px = r_N[0] - along * s_hat_N[0]
    py = r_N[1] - along * s_hat_N[1]
    pz = r_N[2] - along * s_hat_N[2]
    return px * px + py * py + pz * pz < earth_radius_m * earth_radius_m


def sunlit_fraction(r_N: tuple[float, float, float], s_hat_N: tuple[float, float, float], distance_au: float,
                    earth_radius_m: float) -> float:
    """The fraction (0…1) of the Sun's disc seen from position ``r_N`` (m, from the Earth's centre) with the Sun
    along ``s_hat_N`` at ``distance_au``: apparent radii ``a = asin(R_sun / |R_s − r|)``, ``b = asin(R_E / |r|)``,
    separation ``c`` between the Earth's centre and the Sun as seen from ``r``; 1 for ``c ≥ a + b``, 0 for
    ``c ≤ b − a`` (umbra), else ``1 − A / (π a²)`` with ``A`` the overlap of two plane circles (M&G eq. 3.85–3.87)."""
    d = distance_au * AU_M
    sx, sy, sz = s_hat_N[0] * d - r_N[0], s_hat_N[1] * d - r_N[1], s_hat_N[2] * d - r_N[2]  # spacecraft → Sun
    ds = math.sqrt(sx * sx + sy * sy + sz * sz)
    rn = math.sqrt(r_N[0] * r_N[0] + r_N[1] * r_N[1] + r_N[2] * r_N[2])
    if rn <= earth_radius_m:
        raise ValueError(f"position {rn} m from the Earth's centre is inside the Earth ({earth_radius_m} m)")
    a = math.asin(min(1.0, SUN_RADIUS_M / ds))
    b = math.asin(earth_radius_m / rn)
    cos_c = -(r_N[0] * sx + r_N[1] * sy + r_N[2] * sz) / (rn * ds)
    c = math.acos(max(-1.0, min(1.0, cos_c)))
    if c >= a + b:
        return 1.0
    if c <= b - a:
        return 0.0
    if c <= a - b:  # the Earth inside the Sun's disc (not reached in Earth orbit)
        return 1.0 - (b * b) / (a * a)
    x = (c * c + a * a - b * b) / (2.0 * c)
    y = math.sqrt(max(0.0, a * a - x * x))
    area = a * a * math.acos(max(-1.0, min(1.0, x / a))) + b * b * math.acos(max(-1.0, min(1.0, (c - x) / b))) - c * y
    return max(0.0, min(1.0, 1.0 - area / (math.pi * a * a)))


def eclipse_fraction_circular(radius_m: float, beta_rad: float, earth_radius_m: float) -> float:
    """Fraction of a circular orbit of ``radius_m`` spent in the cylindrical shadow, for a Sun
    elevation ``beta_rad`` above the orbit plane: ``acos(sqrt(r² − R²) / (r cos β)) / π``, 0 when
    the orbit never enters the shadow (``|sin β| ≥ R/r`` … i.e. the argument reaches 1)."""
    if radius_m <= earth_radius_m:
        raise ValueError(f"orbit radius {radius_m} m is inside the Earth ({earth_radius_m} m)")
    c = math.cos(beta_rad)
    if c <= 0.0:
        return 0.0
    x = math.sqrt(radius_m * radius_m - earth_radius_m * earth_radius_m) / (radius_m * c)
    return 0.0 if x >= 1.0 else math.acos(x) / math.pi
