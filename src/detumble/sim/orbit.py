"""Orbit models giving the spacecraft position ``r_N`` (m) in the inertial frame N.

N is Earth-centred inertial with its third axis along the Earth's rotation axis (treated as
J2000/GCRF; precession and nutation are ignored). Time ``t`` is seconds since the scenario epoch.

* :class:`CircularOrbit` - analytic circular Keplerian orbit (altitude, inclination, RAAN,
  argument of latitude at epoch), optionally with the secular J2 drift of RAAN and argument of
  latitude. Exact and cheap (two trig calls), so it is evaluated directly at each step.
* :class:`TleOrbit` - SGP4 from a two-line element set through the optional ``sgp4`` package,
  evaluated on a coarse grid (default 10 s) and interpolated with cubic Hermite polynomials. SGP4
  positions are in TEME, used here as N (TEME differs from J2000 by precession/nutation, < 0.5
  deg, irrelevant for detumbling).
"""

from __future__ import annotations

import math

MU_EARTH = 3.986004415e14  #: m^3/s^2
R_EARTH_EQ = 6378136.6  #: m, equatorial radius
J2_EARTH = 1.0826267e-3

_cos, _sin = math.cos, math.sin


class CircularOrbit:
    """Circular orbit; angles in radians, lengths in metres."""

    def __init__(
        self,
        altitude_m: float,
        inclination_rad: float,
        raan_rad: float,
        arg_latitude_rad: float,
        mu: float = MU_EARTH,
        earth_radius_m: float = R_EARTH_EQ,
        j2: float = 0.0,
    ) -> None:
        if not altitude_m > 0.0:
            raise ValueError(f"altitude must be above the Earth's surface, got {altitude_m} m")
        self.radius_m = earth_radius_m + altitude_m
        self.mu = mu
        self.inclination_rad = inclination_rad
        self.raan0_rad = raan_rad
        self.arg_latitude0_rad = arg_latitude_rad
        a = self.radius_m
        #: Keplerian mean motion sqrt(mu/a^3), rad/s
        self.mean_motion = math.sqrt(mu / a**3)
        ci = math.cos(inclination_rad)
        k = 1.5 * j2 * (earth_radius_m / a) ** 2 * self.mean_motion  # circular: p = a
        self.raan_rate = -k * ci
        # du/dt = n + dw/dt + dM/dt - n, secular J2 terms for e = 0
        self.arg_latitude_rate = self.mean_motion + 0.5 * k * (5.0 * ci * ci - 1.0) + 0.5 * k * (3.0 * ci * ci - 1.0)
        self._si = math.sin(inclination_rad)
        self._ci = ci
        #: 3 mu / r^3 (1/s^2), the gravity-gradient coefficient, constant on a circular orbit
        self.gg_coeff = 3.0 * mu / a**3

    def position_N(self, t: float) -> tuple[float, float, float]:
        """Inertial position at ``t`` s after epoch, metres."""
        u = self.arg_latitude0_rad + self.arg_latitude_rate * t
        raan = self.raan0_rad + self.raan_rate * t
        cu, su = math.cos(u), math.sin(u)
        co, so = math.cos(raan), math.sin(raan)
        a = self.radius_m
        return (
            a * (co * cu - so * su * self._ci),
            a * (so * cu + co * su * self._ci),
            a * (su * self._si),
        )

    def velocity_N(self, t: float) -> tuple[float, float, float]:
        """Inertial velocity at ``t`` s after epoch, m/s (the derivative of :meth:`position_N`)."""
        u = self.arg_latitude0_rad + self.arg_latitude_rate * t
        raan = self.raan0_rad + self.raan_rate * t
        cu, su = math.cos(u), math.sin(u)
        co, so = math.cos(raan), math.sin(raan)
        a, du, dr, ci = self.radius_m, self.arg_latitude_rate, self.raan_rate, self._ci
        return (
            a * (du * (-co * su - so * cu * ci) + dr * (-so * cu - co * su * ci)),
            a * (du * (-so * su + co * cu * ci) + dr * (co * cu - so * su * ci)),
            a * du * cu * self._si,
        )

    def position_velocity_N(self, t: float) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """``(position_N(t), velocity_N(t))`` (m, m/s) with the angles' sines and cosines computed
        once: the same floats as the two calls."""
        u = self.arg_latitude0_rad + self.arg_latitude_rate * t
        raan = self.raan0_rad + self.raan_rate * t
        cu, su = _cos(u), _sin(u)
        co, so = _cos(raan), _sin(raan)
        a, du, dr, ci, si = self.radius_m, self.arg_latitude_rate, self.raan_rate, self._ci, self._si
        return (
            (a * (co * cu - so * su * ci), a * (so * cu + co * su * ci), a * (su * si)),
            (a * (du * (-co * su - so * cu * ci) + dr * (-so * cu - co * su * ci)),
             a * (du * (-so * su + co * cu * ci) + dr * (co * cu - so * su * ci)),
             a * du * cu * si),
        )

    def gravity_gradient_coeff(self, r_N: tuple[float, float, float]) -> float:
        return self.gg_coeff


class TleOrbit:
    """SGP4 propagation of a TLE (needs the ``sgp4`` package), tabulated and interpolated.

    ``epoch_jd`` is the scenario epoch (UTC Julian date); ``step_s`` the table spacing.
    """

    def __init__(self, line1: str, line2: str, epoch_jd: float, step_s: float = 10.0, mu: float = MU_EARTH) -> None:
        try:
            from sgp4.api import Satrec
        except ImportError as exc:  # pragma: no cover - depends on the environment
            raise ImportError(
                "orbit.type 'tle' needs the optional 'sgp4' package: pip install sgp4 "
                "(or use orbit.type 'circular')"
            ) from exc
        self._sat = Satrec.twoline2rv(line1, line2)
        self._epoch_jd = epoch_jd
        self.step_s = float(step_s)
        self.mu = mu
        self._cache: dict[int, tuple[tuple[float, float, float], tuple[float, float, float]]] = {}
        r, _ = self._node(0)
        a = math.sqrt(r[0] ** 2 + r[1] ** 2 + r[2] ** 2)
        self.radius_m = a
        self.mean_motion = math.sqrt(mu / a**3)
        self.inclination_rad = self._sat.inclo

    def _node(self, k: int):
        node = self._cache.get(k)
        if node is None:
            t = k * self.step_s
            jd = self._epoch_jd + t / 86400.0
            jd_int = math.floor(jd)
            err, r_km, v_km_s = self._sat.sgp4(jd_int, jd - jd_int)
            if err != 0:
                raise RuntimeError(f"SGP4 error code {err} at t = {t} s after epoch")
            node = (tuple(1e3 * x for x in r_km), tuple(1e3 * x for x in v_km_s))
            if len(self._cache) > 4096:
                self._cache.clear()
            self._cache[k] = node
        return node

    def position_N(self, t: float) -> tuple[float, float, float]:
        h = self.step_s
        k = math.floor(t / h)
        s = t / h - k
        (r0, v0), (r1, v1) = self._node(k), self._node(k + 1)
        h00 = (1.0 + 2.0 * s) * (1.0 - s) ** 2
        h10 = s * (1.0 - s) ** 2 * h
        h01 = s * s * (3.0 - 2.0 * s)
        h11 = s * s * (s - 1.0) * h
        return tuple(h00 * r0[i] + h10 * v0[i] + h01 * r1[i] + h11 * v1[i] for i in range(3))

    def velocity_N(self, t: float) -> tuple[float, float, float]:
        """Inertial velocity, m/s: the derivative of the Hermite interpolant of :meth:`position_N`."""
        h = self.step_s
        k = math.floor(t / h)
        s = t / h - k
        (r0, v0), (r1, v1) = self._node(k), self._node(k + 1)
        d00 = 6.0 * s * s - 6.0 * s
        d10 = (3.0 * s * s - 4.0 * s + 1.0) * h
        d01 = -d00
        d11 = (3.0 * s * s - 2.0 * s) * h
        return tuple((d00 * r0[i] + d10 * v0[i] + d01 * r1[i] + d11 * v1[i]) / h for i in range(3))

    def position_velocity_N(self, t: float) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """``(position_N(t), velocity_N(t))``, m and m/s."""
        return self.position_N(t), self.velocity_N(t)

    def gravity_gradient_coeff(self, r_N: tuple[float, float, float]) -> float:
        r2 = r_N[0] ** 2 + r_N[1] ** 2 + r_N[2] ** 2
        return 3.0 * self.mu / (r2 * math.sqrt(r2))
