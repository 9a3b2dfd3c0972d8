"""Geomagnetic field models, evaluated in the inertial frame N, tesla.

* :class:`DipoleField` - centred tilted dipole from the degree-1 Gauss coefficients (default
  IGRF-14, epoch 2025: g10 = -29350.0, g11 = -1410.3, h11 = 4545.5 nT, reference radius
  6371.2 km), fixed in the Earth and rotating with it at 7.2921159e-5 rad/s. In Earth-fixed
  coordinates the degree-1 potential is ``V = a^3 (d . r) / r^3`` with ``d = (g11, h11, g10)``, so
  ``B = -grad V = (a/r)^3 [3 (d . r_hat) r_hat - d]``. Evaluated analytically in plain floats at
  every step (~1 us). Limits: a centred dipole misses the higher-degree field - it is off by up to
  ~16 uT near the South Atlantic Anomaly at LEO and by ~10 % in magnitude elsewhere; the
  coefficients drift ~20 nT/yr.
* :class:`WmmField` - the World Magnetic Model 2025 (degree 12) through the optional
  ``pygeomag`` package (~130 us a call); wrap it in :class:`TabulatedField` to evaluate along the
  orbit at <= 1 Hz and interpolate linearly between nodes.

The Earth rotation angle is ``theta(t) = theta0 + omega_E t``; Earth-fixed E and inertial N share
their third axis, ``r_E = R3(theta) r_N``.
"""

from __future__ import annotations

import math

from detumble.sim.frames import orbit_axes_N

EARTH_ROTATION_RATE = 7.2921159e-5  #: rad/s
IGRF_REFERENCE_RADIUS_M = 6371200.0
IGRF2025_G10_NT = -29350.0
IGRF2025_G11_NT = -1410.3
IGRF2025_H11_NT = 4545.5

# WGS84 ellipsoid (geodetic conversion for the WMM)
_WGS84_A = 6378137.0
_WGS84_F = 1.0 / 298.257223563
_WGS84_E2 = _WGS84_F * (2.0 - _WGS84_F)


class DipoleField:
    """Centred tilted dipole rotating with the Earth.

    Coefficients in nT, ``reference_radius_m`` in m, ``earth_rotation_rate`` in rad/s,
    ``theta0_rad`` the Earth rotation angle at t = 0.
    """

    def __init__(
        self,
        g10_nT: float = IGRF2025_G10_NT,
        g11_nT: float = IGRF2025_G11_NT,
        h11_nT: float = IGRF2025_H11_NT,
        reference_radius_m: float = IGRF_REFERENCE_RADIUS_M,
        earth_rotation_rate: float = EARTH_ROTATION_RATE,
        theta0_rad: float = 0.0,
    ) -> None:
        self.g10_nT, self.g11_nT, self.h11_nT = float(g10_nT), float(g11_nT), float(h11_nT)
        self.reference_radius_m = float(reference_radius_m)
        self.earth_rotation_rate = float(earth_rotation_rate)
        self.theta0_rad = float(theta0_rad)
        a3 = self.reference_radius_m**3 * 1e-9  # nT -> T folded in
        self._dx, self._dy, self._dz = a3 * self.g11_nT, a3 * self.h11_nT, a3 * self.g10_nT

    def earth_angle(self, t: float) -> float:
        return self.theta0_rad + self.earth_rotation_rate * t

    def dipole_axis_N(self, t: float) -> tuple[float, float, float]:
        """Unit vector towards the geomagnetic *north* pole (i.e. ``-d``) in N at time ``t``."""
        c, s = math.cos(self.earth_angle(t)), math.sin(self.earth_angle(t))
        dx, dy, dz = c * self._dx - s * self._dy, s * self._dx + c * self._dy, self._dz
        n = math.sqrt(dx * dx + dy * dy + dz * dz)
        return (-dx / n, -dy / n, -dz / n)

    def b_N(self, t: float, r_N: tuple[float, float, float]) -> tuple[float, float, float]:
        """Field (T) in N at position ``r_N`` (m) and time ``t`` (s after epoch)."""
        th = self.theta0_rad + self.earth_rotation_rate * t
        c, s = math.cos(th), math.sin(th)
        # Earth-fixed dipole vector expressed in N: R3(theta)^T d
        dx = c * self._dx - s * self._dy
        dy = s * self._dx + c * self._dy
        dz = self._dz
        x, y, z = r_N
        r2 = x * x + y * y + z * z
        r = math.sqrt(r2)
        inv_r3 = 1.0 / (r2 * r)
        k = 3.0 * (dx * x + dy * y + dz * z) / r2
        return ((k * x - dx) * inv_r3, (k * y - dy) * inv_r3, (k * z - dz) * inv_r3)


def ecef_to_geodetic(x: float, y: float, z: float) -> tuple[float, float, float]:
    """WGS84 geodetic latitude (rad), longitude (rad), height (m) from ECEF metres."""
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1.0 - _WGS84_E2))
    h = 0.0
    for _ in range(6):
        s = math.sin(lat)
        n = _WGS84_A / math.sqrt(1.0 - _WGS84_E2 * s * s)
        h = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1.0 - _WGS84_E2 * n / (n + h)))
    return lat, lon, h


class WmmField:
    """WMM2025 via ``pygeomag`` (optional dependency), in N, tesla.

    ``epoch`` is an aware UTC datetime (sets the decimal year); the Earth angle as for the dipole.
    """

    def __init__(self, epoch, earth_rotation_rate: float = EARTH_ROTATION_RATE, theta0_rad: float = 0.0) -> None:
        try:
            from pygeomag import GeoMag
        except ImportError as exc:
            raise ImportError(
                "field.model 'wmm2025' needs the optional 'pygeomag' package: pip install pygeomag "
                "(or use field.model 'dipole')"
            ) from exc
        from detumble.sim.epoch import decimal_year

        self._geomag = GeoMag(coefficients_file="wmm/WMM_2025.COF")
        self._epoch = epoch
        self._year0 = decimal_year(epoch)
        self.earth_rotation_rate = earth_rotation_rate
        self.theta0_rad = theta0_rad

    def b_N(self, t: float, r_N: tuple[float, float, float]) -> tuple[float, float, float]:
        th = self.theta0_rad + self.earth_rotation_rate * t
        c, s = math.cos(th), math.sin(th)
        x, y, z = r_N
        xe, ye = c * x + s * y, -s * x + c * y
        lat, lon, h = ecef_to_geodetic(xe, ye, z)
        res = self._geomag.calculate(
            glat=math.degrees(lat), glon=math.degrees(lon), alt=h / 1000.0,
            time=self._year0 + t / (365.25 * 86400.0), allow_date_outside_lifespan=True,
        )
        bn, be, bd = res.x * 1e-9, res.y * 1e-9, res.z * 1e-9
        sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
        bxe = -sl * co * bn - so * be - cl * co * bd
        bye = -sl * so * bn + co * be - cl * so * bd
        bze = cl * bn - sl * bd
        return (c * bxe - s * bye, s * bxe + c * bye, bze)


class FieldAlongOrbit:
    """The field seen by the spacecraft as a function of time only: ``b_N(t)``.

    With ``table_step_s`` None the model is evaluated at every call (right for the dipole). With a
    step, nodes ``k * table_step_s`` are evaluated lazily at the orbit position of that time and
    linearly interpolated (right for the WMM: <= 1 Hz evaluation).
    """

    def __init__(self, model, orbit, table_step_s: float | None = None) -> None:
        self.model = model
        self.orbit = orbit
        self.table_step_s = table_step_s
        self._nodes: dict[int, tuple[float, float, float]] = {}

    def _node(self, k: int):
        v = self._nodes.get(k)
        if v is None:
            step = self.table_step_s
            assert step is not None  # nodes are tabulated only with a table step
            t = k * step
            v = self.model.b_N(t, self.orbit.position_N(t))
            if len(self._nodes) > 4096:
                self._nodes.clear()
            self._nodes[k] = v
        return v

    def b_N(self, t: float, r_N: tuple[float, float, float] | None = None) -> tuple[float, float, float]:
        h = self.table_step_s
        if h is None:
            return self.model.b_N(t, r_N if r_N is not None else self.orbit.position_N(t))
        k = math.floor(t / h)
        s = t / h - k
        a, b = self._node(k), self._node(k + 1)
        return (a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2]))


class OrbitConstantField:
    """A field constant in the orbit frame O (seed 004's environment): ``b_N = [ON]^T b_O``.

    ``b_O`` in tesla, O as defined in :mod:`detumble.sim.frames` (z nadir, y negative orbit
    normal). Not a geomagnetic model: it reproduces the coursework's simplification, in which the
    field seen by a body at rest in O never changes. ``orbit`` must give ``position_N`` and
    ``velocity_N``.
    """

    def __init__(self, b_O: tuple[float, float, float], orbit) -> None:
        self.b_O = tuple(float(x) for x in b_O)
        self.orbit = orbit

    def b_N(self, t: float, r_N: tuple[float, float, float] | None = None) -> tuple[float, float, float]:
        r = r_N if r_N is not None else self.orbit.position_N(t)
        x, y, z = orbit_axes_N(r, self.orbit.velocity_N(t))
        a, b, c = self.b_O
        return (a * x[0] + b * y[0] + c * z[0], a * x[1] + b * y[1] + c * z[1], a * x[2] + b * y[2] + c * z[2])
