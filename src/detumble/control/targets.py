"""POINTING targets as data: inertial, nadir (LVLH), ground station and Sun (plain floats; no framework import).

A target is a small frozen record; :meth:`reference` turns it, with an :class:`Ephemeris` (what the spacecraft
knows of its orbit, the Earth's rotation and the Sun), into a :class:`Reference`: the attitude to hold now
``q_RN`` (the target frame R as a body attitude, scalar first), its angular rate ``omega_R`` and acceleration
``alpha_R`` (rad/s, rad/s², both in R: the rate of R relative to N) and a label saying which reference is active
(:data:`LABELS`). The wheel law feeds the rate and acceleration forward (``three_mode``).

Every non-inertial target is a **two-axis** target: body axis ``primary`` (a unit vector of :data:`BODY_AXES`)
along a reference direction P(t), and body axis ``secondary`` as near as it can be to a second direction S(t)
(exactly onto S's part ⟂ P). The frame rate comes in closed form from the directions' first and second time
derivatives, carried through the normalisations and cross products (:class:`_Jet`): for the orthonormal triad
``e_i(t)`` (columns in N) of the reference frame, ``ω_N = ½ Σ e_i × ė_i`` and ``α_N = ½ Σ e_i × ë_i``.

* :class:`InertialTarget`: ``q_TN`` fixed (SET_TARGET_QUATERNION, SET_TARGET_DIRECTION); zero rate.
* :class:`NadirTarget`: P = −r̂ (nadir), S = v (along-track): LVLH with +Z nadir, +X along velocity by default.
  On a circular orbit ``ω = n ĥ`` (orbit rate about the orbit normal), ``α = 0``.
* :class:`StationTarget`: P = the line of sight to a ground station (WGS-84 geodetic latitude, longitude,
  altitude), S = v; in view while the station sees the spacecraft at or above ``min_elevation_deg``. Out of
  view the fallback is the :class:`NadirTarget` with the same axes (label ``STATION_FALLBACK``).
* :class:`SunTarget`: P = the Sun direction, S = the orbit normal ``r × v``. The Sun moves 1.1e-5 °/s in N and
  the two-body orbit normal not at all: its reference rate is taken as zero (stated, not computed).

Orbit derivatives use two-body gravity (``r̈ = −μ r/|r|³``); the station turns with the Earth at
:data:`EARTH_RATE_RAD_S` about N's z axis. Units: m, m/s, rad, s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, NamedTuple, Sequence, Union

from detumble.control.quaternion import Quat, Vec3, dcm_to_quat, is_unit_quaternion

__all__ = ["Ephemeris", "Reference", "InertialTarget", "NadirTarget", "StationTarget", "SunTarget", "Target",
           "BODY_AXES", "LABELS", "TARGET_KINDS", "MU_EARTH_M3_S2", "EARTH_RATE_RAD_S", "station_ecef",
           "station_elevation_deg", "axes_error", "station_error", "true_reference_q", "target_command",
           "target_entry_error"]

#: m³/s²: the Earth's gravitational parameter (two-body reference accelerations).
MU_EARTH_M3_S2 = 3.986004415e14
#: rad/s: the Earth's rotation rate (the scenarios' field and frame rate).
EARTH_RATE_RAD_S = 7.2921159e-5
_WGS84_A = 6378137.0
_WGS84_F = 1.0 / 298.257223563
_E2 = _WGS84_F * (2.0 - _WGS84_F)

#: The body axes a target may name, by the flight enum's order (BodyAxis).
BODY_AXES: tuple[tuple[str, Vec3], ...] = (
    ("PLUS_X", (1.0, 0.0, 0.0)), ("MINUS_X", (-1.0, 0.0, 0.0)), ("PLUS_Y", (0.0, 1.0, 0.0)),
    ("MINUS_Y", (0.0, -1.0, 0.0)), ("PLUS_Z", (0.0, 0.0, 1.0)), ("MINUS_Z", (0.0, 0.0, -1.0)))
#: The kinds of target (TargetKind), by value.
TARGET_KINDS = ("INERTIAL", "NADIR", "GROUND_STATION", "SUN")
#: Which reference is active (PointingReference), by value: a station target out of view flies its fallback.
LABELS = ("INERTIAL", "NADIR", "GROUND_STATION", "STATION_FALLBACK", "SUN")
INERTIAL, NADIR, GROUND_STATION, STATION_FALLBACK, SUN = range(5)
_ZERO = (0.0, 0.0, 0.0)


class Ephemeris(NamedTuple):
    """What the spacecraft knows of where it is: position ``r_N`` (m) and velocity ``v_N`` (m/s) in N, the Earth
    rotation angle (rad: Earth-fixed x from N's x about z) and the Sun's unit direction ``sun_N``."""

    r_N: Vec3
    v_N: Vec3
    earth_angle_rad: float
    sun_N: Vec3


class Reference(NamedTuple):
    """The attitude to hold ``q_RN``, the reference rate ``omega_R`` (rad/s) and acceleration ``alpha_R``
    (rad/s²), both of R relative to N in R, and the active label (index in :data:`LABELS`)."""

    q_RN: Quat  # noqa: N815 - frame suffixes (Basilisk convention)
    omega_R: Vec3  # noqa: N815
    alpha_R: Vec3  # noqa: N815
    label: int


# --- vectors with their first two time derivatives ---------------------------------------------------

def _add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _scale(k, a):
    return (k * a[0], k * a[1], k * a[2])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


class _Jet(NamedTuple):
    """A vector ``x`` with its first and second time derivatives ``d``, ``dd``."""

    x: Vec3
    d: Vec3
    dd: Vec3

    def unit(self) -> "_Jet":
        # p = n u: ṗ = ṅ u + n u̇, p̈ = n̈ u + 2 ṅ u̇ + n ü
        n = math.sqrt(_dot(self.x, self.x))
        if not n > 0.0:
            raise ValueError("a reference direction is the zero vector")
        u = _scale(1.0 / n, self.x)
        nd = _dot(u, self.d)
        ud = _scale(1.0 / n, _sub(self.d, _scale(nd, u)))
        ndd = _dot(ud, self.d) + _dot(u, self.dd)
        udd = _scale(1.0 / n, _sub(_sub(self.dd, _scale(ndd, u)), _scale(2.0 * nd, ud)))
        return _Jet(u, ud, udd)

    def cross(self, other: "_Jet") -> "_Jet":
        a, b = self, other
        return _Jet(_cross(a.x, b.x), _add(_cross(a.d, b.x), _cross(a.x, b.d)),
                    _add(_add(_cross(a.dd, b.x), _scale(2.0, _cross(a.d, b.d))), _cross(a.x, b.dd)))


def _orbit_jets(eph: Ephemeris) -> tuple[_Jet, _Jet]:
    """Position and velocity with their derivatives under two-body gravity."""
    r, v = eph.r_N, eph.v_N
    r2 = _dot(r, r)
    rn = math.sqrt(r2)
    k = -MU_EARTH_M3_S2 / (r2 * rn)
    a = _scale(k, r)
    # d/dt (−μ r/|r|³) = −μ (v/|r|³ − 3 r (r·v)/|r|⁵)
    jerk = _add(_scale(k, v), _scale(-3.0 * k * _dot(r, v) / r2, r))
    # d²/dt² of the acceleration (for the velocity's second derivative we need only jerk)
    return _Jet(r, v, a), _Jet(v, a, jerk)


def _two_axis(primary_B: Vec3, secondary_B: Vec3, p: _Jet, s: _Jet, label: int) -> Reference:
    """Body ``primary_B`` along P, ``secondary_B`` onto S's part ⟂ P; the frame's rate and acceleration."""
    e1 = p.unit()
    e2 = e1.cross(s).unit()
    e3 = e1.cross(e2)
    f1 = primary_B
    f2 = _cross(f1, secondary_B)
    f3 = _cross(f1, f2)
    # [RN] = Σ f_i e_iᵀ maps N components to R components
    c = tuple(tuple(f1[j] * e1.x[k] + f2[j] * e2.x[k] + f3[j] * e3.x[k] for k in range(3)) for j in range(3))
    w_n = _scale(0.5, _add(_add(_cross(e1.x, e1.d), _cross(e2.x, e2.d)), _cross(e3.x, e3.d)))
    a_n = _scale(0.5, _add(_add(_cross(e1.x, e1.dd), _cross(e2.x, e2.dd)), _cross(e3.x, e3.dd)))

    def to_r(v):
        return (_dot(c[0], v), _dot(c[1], v), _dot(c[2], v))

    return Reference(dcm_to_quat(c), to_r(w_n), to_r(a_n), label)  # type: ignore[arg-type]


def _axis(index: int) -> Vec3:
    return BODY_AXES[index][1]


def axes_error(primary: int, secondary: int) -> str | None:
    """Why the body-axis pair cannot define a target (None when it can): unknown, or not perpendicular."""
    n = len(BODY_AXES)
    if not (isinstance(primary, int) and isinstance(secondary, int) and 0 <= primary < n and 0 <= secondary < n):
        return f"axes must be among {', '.join(a for a, _ in BODY_AXES)}"
    if abs(_dot(_axis(primary), _axis(secondary))) > 0.5:
        return (f"the secondary axis {BODY_AXES[secondary][0]} is parallel to the primary axis "
                f"{BODY_AXES[primary][0]}; give a perpendicular pair")
    return None


def station_error(latitude_deg: float, longitude_deg: float, altitude_m: float) -> str | None:
    """Why a ground station is refused (None when it is usable)."""
    vals = (latitude_deg, longitude_deg, altitude_m)
    if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in vals):
        return "latitude, longitude and altitude must be finite numbers"
    if not -90.0 <= latitude_deg <= 90.0:
        return f"latitude {latitude_deg} deg is outside [-90, 90]"
    if not -180.0 <= longitude_deg <= 360.0:
        return f"longitude {longitude_deg} deg is outside [-180, 360]"
    if not -500.0 <= altitude_m <= 10000.0:
        return f"altitude {altitude_m} m is outside [-500, 10000] (a ground station)"
    return None


def station_ecef(latitude_deg: float, longitude_deg: float, altitude_m: float) -> tuple[Vec3, Vec3]:
    """``(position m, unit local vertical)`` of a WGS-84 geodetic point in Earth-fixed axes."""
    lat, lon = math.radians(latitude_deg), math.radians(longitude_deg)
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    n = _WGS84_A / math.sqrt(1.0 - _E2 * sl * sl)
    pos = ((n + altitude_m) * cl * co, (n + altitude_m) * cl * so, (n * (1.0 - _E2) + altitude_m) * sl)
    return pos, (cl * co, cl * so, sl)


def _earth_to_n(v: Vec3, theta: float) -> Vec3:
    c, s = math.cos(theta), math.sin(theta)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1], v[2])


def station_elevation_deg(station: tuple[Vec3, Vec3], eph: Ephemeris) -> float:
    """Elevation of the spacecraft above the station's local horizon, deg (geodetic vertical)."""
    pos, up = station
    s_n, up_n = _earth_to_n(pos, eph.earth_angle_rad), _earth_to_n(up, eph.earth_angle_rad)
    los = _sub(eph.r_N, s_n)
    return math.degrees(math.asin(max(-1.0, min(1.0, _dot(los, up_n) / math.sqrt(_dot(los, los))))))


@dataclass(frozen=True)
class InertialTarget:
    """A fixed ``q_TN`` (scalar first, unit)."""

    q: Quat
    kind = 0
    needs_ephemeris = False

    def reference(self, eph: Ephemeris | None = None) -> Reference:
        return Reference(self.q, _ZERO, _ZERO, INERTIAL)


@dataclass(frozen=True)
class NadirTarget:
    """Body ``primary`` (BODY_AXES index) to nadir, ``secondary`` along the velocity (LVLH)."""

    primary: int = 4  # PLUS_Z
    secondary: int = 0  # PLUS_X
    kind = 1
    needs_ephemeris = True

    def reference(self, eph: Ephemeris, label: int = NADIR) -> Reference:
        r, v = _orbit_jets(eph)
        nadir = _Jet(_scale(-1.0, r.x), _scale(-1.0, r.d), _scale(-1.0, r.dd))
        return _two_axis(_axis(self.primary), _axis(self.secondary), nadir, v, label)


@dataclass(frozen=True)
class StationTarget:
    """Body ``primary`` at a ground station while it sees the spacecraft at ``min_elevation_deg`` or more,
    ``secondary`` along the velocity; otherwise the nadir target with the same axes."""

    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    primary: int = 4
    secondary: int = 0
    min_elevation_deg: float = 10.0
    kind = 2
    needs_ephemeris = True

    def in_view(self, eph: Ephemeris) -> bool:
        station = station_ecef(self.latitude_deg, self.longitude_deg, self.altitude_m)
        return station_elevation_deg(station, eph) >= self.min_elevation_deg

    def reference(self, eph: Ephemeris) -> Reference:
        if not self.in_view(eph):
            return NadirTarget(self.primary, self.secondary).reference(eph, STATION_FALLBACK)
        pos, _ = station_ecef(self.latitude_deg, self.longitude_deg, self.altitude_m)
        th = eph.earth_angle_rad
        w = (0.0, 0.0, EARTH_RATE_RAD_S)
        s = _earth_to_n(pos, th)
        sd = _cross(w, s)
        sdd = _cross(w, sd)
        r, _ = _orbit_jets(eph)
        los = _Jet(_sub(s, r.x), _sub(sd, r.d), _sub(sdd, r.dd))
        return _two_axis(_axis(self.primary), _axis(self.secondary), los, _orbit_jets(eph)[1], GROUND_STATION)


@dataclass(frozen=True)
class SunTarget:
    """Body ``primary`` at the Sun, ``secondary`` toward the orbit normal (its part ⟂ the Sun line)."""

    primary: int = 4
    secondary: int = 0
    kind = 3
    needs_ephemeris = True

    def reference(self, eph: Ephemeris) -> Reference:
        h = _cross(eph.r_N, eph.v_N)
        ref = _two_axis(_axis(self.primary), _axis(self.secondary), _Jet(eph.sun_N, _ZERO, _ZERO),
                        _Jet(h, _ZERO, _ZERO), SUN)
        return ref


Target = Union[InertialTarget, NadirTarget, StationTarget, SunTarget]


def true_reference_q(spec: Target | None, ephemeris: Callable[[], Ephemeris], held: Quat | None) -> Quat | None:
    """The attitude ``spec`` asks for now by the true ephemeris (``ephemeris()`` is called only for a moving
    target); ``held`` (the controller's own reference) where there is no target or its reference is undefined.
    What the truth measurements (attitude.csv, the plant-only summary) compare the attitude with."""
    if spec is None or not spec.needs_ephemeris:
        return held
    try:
        return spec.reference(ephemeris()).q_RN
    except ValueError:
        return held


def target_command(law, entry: Sequence) -> str:
    """Send the target command ``entry`` to a ThreeModeLaw-like ``law``: four numbers (SET_TARGET_QUATERNION),
    ``("NADIR", primary, secondary)``, ``("SUN", primary, secondary)`` or ``("GROUND_STATION", latitude_deg,
    longitude_deg, altitude_m, primary, secondary)`` (axes by BodyAxis name or index); the law's answer."""
    if entry and isinstance(entry[0], str):
        kind, *args = entry
        names = [a for a, _ in BODY_AXES]
        axes = [names.index(a) if isinstance(a, str) and a in names else a for a in args[-2:]]
        if kind == "NADIR" and len(args) == 2:
            return law.set_target_nadir(*axes)
        if kind == "SUN" and len(args) == 2:
            return law.set_target_sun(*axes)
        if kind == "GROUND_STATION" and len(args) == 5:
            return law.set_target_ground_station(float(args[0]), float(args[1]), float(args[2]), *axes)
        raise ValueError(f"target {tuple(entry)!r}: give NADIR p s, SUN p s or GROUND_STATION lat lon alt p s")
    return law.set_target_quaternion(tuple(float(c) for c in entry))


def target_entry_error(q) -> str | None:
    """Why a target change cannot be sent (None when it can): not a unit quaternion, a bad axis pair or station."""
    if q and isinstance(q[0], str):
        kind, *args = q
        names = [a for a, _ in BODY_AXES]
        shape = {"NADIR": 2, "SUN": 2, "GROUND_STATION": 5}
        if kind not in shape or len(args) != shape[kind]:
            return f"{tuple(q)!r}: give NADIR p s, SUN p s or GROUND_STATION lat lon alt p s (axes {', '.join(names)})"
        if any(a not in names for a in args[-2:]):
            return f"{tuple(q)!r}: the axes must be among {', '.join(names)}"
        why = axes_error(names.index(args[-2]), names.index(args[-1]))
        if why is None and kind == "GROUND_STATION":
            if not all(isinstance(a, (int, float)) and not isinstance(a, bool) for a in args[:3]):
                return f"{tuple(q)!r}: latitude, longitude and altitude must be numbers"
            why = station_error(*(float(a) for a in args[:3]))
        return None if why is None else f"{tuple(q)!r}: {why}"
    if len(q) != 4 or not is_unit_quaternion(q):
        return f"{q!r} is not a unit quaternion (within 1e-3), as SET_TARGET_QUATERNION requires"
    return None
