"""Geomagnetic field: the IGRF-2025 dipole against its closed form and along a 420 km orbit."""

import math

import pytest

from detumble.sim.field import DipoleField, FieldAlongOrbit, ecef_to_geodetic
from detumble.sim.orbit import CircularOrbit
from detumble.sim.vec import dot, norm

NT = 1e-9  # tesla per nanotesla
UT = 1e-6  # tesla per microtesla
R_420 = 6371.2e3 + 420e3  # m, 420 km above the IGRF reference sphere


def test_defaults_are_igrf_2025():
    f = DipoleField()
    assert (f.g10_nT, f.g11_nT, f.h11_nT) == (-29350.0, -1410.3, 4545.5)
    assert f.reference_radius_m == 6371200.0
    assert f.earth_rotation_rate == 7.2921159e-5


def test_dipole_closed_form_at_magnetic_equator_and_pole():
    """|B| = B0 (a/r)^3 sqrt(1 + 3 sin^2 lambda_m), B0 = sqrt(g10^2 + g11^2 + h11^2)."""
    f = DipoleField()
    b0 = math.sqrt(29350.0**2 + 1410.3**2 + 4545.5**2) * NT * (6371.2e3 / R_420) ** 3
    pole = f.dipole_axis_N(0.0)
    at_pole = tuple(R_420 * x for x in pole)
    assert abs(norm(f.b_N(0.0, at_pole)) - 2.0 * b0) < 1e-3 * NT
    # field at the geomagnetic north pole points down (towards the Earth's centre)
    assert dot(f.b_N(0.0, at_pole), pole) < 0.0
    # a point on the magnetic equator: any unit vector orthogonal to the axis
    e = (pole[1], -pole[0], 0.0)
    e = tuple(x / norm(e) for x in e)
    b_eq = f.b_N(0.0, tuple(R_420 * x for x in e))
    assert abs(norm(b_eq) - b0) < 1e-3 * NT
    # there the field is horizontal and points to magnetic north
    assert abs(dot(b_eq, e)) < 1e-3 * NT
    assert dot(b_eq, pole) > 0.0
    # values in uT for the record: 24.5 at the equator, 49.1 at the pole
    assert 24.0 * UT < b0 < 25.0 * UT


def test_field_rotates_with_the_earth():
    """Rotating position and time together by one sidereal step leaves the body-fixed field unchanged."""
    f = DipoleField(theta0_rad=0.3)
    w = f.earth_rotation_rate
    t = 1234.0
    r0 = (5.0e6, 3.0e6, 3.5e6)
    c, s = math.cos(w * t), math.sin(w * t)
    r_t = (c * r0[0] - s * r0[1], s * r0[0] + c * r0[1], r0[2])
    b0 = f.b_N(0.0, r0)
    b_t = f.b_N(t, r_t)
    expect = (c * b0[0] - s * b0[1], s * b0[0] + c * b0[1], b0[2])
    assert max(abs(a - b) for a, b in zip(b_t, expect, strict=True)) < 1e-6 * NT


def test_field_along_420km_orbit_between_19_and_53_uT_min_at_equator_max_near_poles():
    """Over a day of a 51.6 deg orbit: 19 uT < |B| < 53 uT; min at |lambda_m| < 5 deg, max at the highest |lambda_m|."""
    orbit = CircularOrbit(420e3, math.radians(51.6), 0.0, 0.0, earth_radius_m=6371.2e3)
    f = DipoleField()
    samples = []
    for k in range(0, 86400, 20):
        t = float(k)
        r = orbit.position_N(t)
        lam = math.asin(dot(r, f.dipole_axis_N(t)) / norm(r))
        samples.append((norm(f.b_N(t, r)), abs(lam)))
    b_min, lam_at_min = min(samples)
    b_max, lam_at_max = max(samples)
    assert 19 * UT < b_min and b_max < 53 * UT
    assert lam_at_min < math.radians(5.0)
    assert lam_at_max > max(lam for _, lam in samples) - math.radians(3.0)
    assert lam_at_max > math.radians(55.0)  # 51.6 deg orbit + ~9.7 deg dipole tilt
    # the spread is the dipole's factor of ~sqrt(1 + 3 sin^2 lambda): ~1.8 at these latitudes
    assert 1.6 < b_max / b_min < 2.0


def test_ecef_to_geodetic_round_trip():
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    lat, lon, h = math.radians(-33.0), math.radians(151.0), 420e3
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    x = (n + h) * math.cos(lat) * math.cos(lon)
    y = (n + h) * math.cos(lat) * math.sin(lon)
    z = (n * (1 - e2) + h) * math.sin(lat)
    lat2, lon2, h2 = ecef_to_geodetic(x, y, z)
    assert abs(lat2 - lat) < 1e-11 and abs(lon2 - lon) < 1e-12 and abs(h2 - h) < 1e-4  # rad, rad, m


def test_wmm2025_close_to_dipole_except_anomalies_and_table_interpolates():
    """WMM2025 (pygeomag) along the orbit: within ~17 uT of the IGRF dipole; 1 s table within 20 nT of direct."""
    pytest.importorskip("pygeomag")
    from detumble.sim.epoch import parse_epoch
    from detumble.sim.field import WmmField

    epoch = parse_epoch("2025-06-01T00:00:00Z")
    orbit = CircularOrbit(420e3, math.radians(51.6), 0.0, 0.0)
    wmm = WmmField(epoch, theta0_rad=0.0)
    dip = DipoleField(theta0_rad=0.0)
    worst = 0.0
    for k in range(0, 5600, 100):
        r = orbit.position_N(float(k))
        bw, bd = wmm.b_N(float(k), r), dip.b_N(float(k), r)
        assert 15 * UT < norm(bw) < 60 * UT
        worst = max(worst, norm(tuple(a - b for a, b in zip(bw, bd, strict=True))))
    assert 3 * UT < worst < 18 * UT
    table = FieldAlongOrbit(wmm, orbit, table_step_s=1.0)
    for t in (10.25, 10.5, 333.7):
        direct = wmm.b_N(t, orbit.position_N(t))
        assert norm(tuple(a - b for a, b in zip(table.b_N(t), direct, strict=True))) < 20 * NT
