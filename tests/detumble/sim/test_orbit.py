"""Orbit models: circular Keplerian geometry, J2 secular rates, optional SGP4."""

import math

import pytest

from detumble.sim.orbit import CircularOrbit
from detumble.sim.vec import cross, dot, norm

M = 1.0  # metre
MU = 3.986004415e14
RE = 6378136.6


def test_circular_orbit_geometry():
    o = CircularOrbit(420e3, math.radians(51.6), math.radians(30.0), 0.0, MU, RE)
    a = RE + 420e3
    assert abs(o.mean_motion - math.sqrt(MU / a**3)) < 1e-18
    # period of the Basilisk case: 5578 s
    assert abs(2 * math.pi / o.mean_motion - 5578.2) < 0.1
    r0 = o.position_N(0.0)
    # argument of latitude 0: on the ascending node line, at RAAN 30 deg
    assert abs(r0[0] - a * math.cos(math.radians(30))) < 1e-6 * M
    assert abs(r0[1] - a * math.sin(math.radians(30))) < 1e-6 * M
    assert abs(r0[2]) < 1e-6 * M
    r1 = o.position_N(100.0)
    h = cross(r0, r1)
    assert abs(math.degrees(math.acos(h[2] / norm(h))) - 51.6) < 1e-9
    # quarter period later: highest point, z = a sin i
    rq = o.position_N(0.25 * 2 * math.pi / o.mean_motion)
    assert abs(rq[2] - a * math.sin(math.radians(51.6))) < 1e-6 * M
    for t in (0.0, 1000.0, 3333.3):
        assert abs(norm(o.position_N(t)) - a) < 1e-6 * M
    # speed = sqrt(mu/a): finite difference
    p, q = o.position_N(10.0), o.position_N(10.001)
    v = norm(tuple((y - x) / 0.001 for x, y in zip(p, q, strict=True)))
    assert abs(v - math.sqrt(MU / a)) < 1e-3  # m/s


def test_j2_nodal_regression_at_420km_51_6deg():
    """Secular RAAN drift -1.5 n J2 (R/a)^2 cos i: about -5.0 deg/day for the ISS-like orbit."""
    o = CircularOrbit(420e3, math.radians(51.6), 0.0, 0.0, MU, RE, j2=1.0826267e-3)
    deg_per_day = math.degrees(o.raan_rate) * 86400
    assert -5.2 < deg_per_day < -4.8
    r0 = o.position_N(0.0)
    r1 = o.position_N(86400.0)
    assert abs(norm(r1) - norm(r0)) < 1e-6 * M
    # without J2 the plane is fixed
    assert CircularOrbit(420e3, 0.9, 0.0, 0.0).raan_rate == 0.0


def test_tle_orbit_with_sgp4():
    """SGP4 via the optional sgp4 package; Hermite table within 5 m of direct SGP4."""
    sgp4_api = pytest.importorskip("sgp4.api")
    from detumble.sim.epoch import julian_date, parse_epoch
    from detumble.sim.orbit import TleOrbit

    l1 = "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991"
    l2 = "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482"
    epoch = parse_epoch("2019-12-09T16:00:00Z")
    o = TleOrbit(l1, l2, julian_date(epoch), step_s=10.0)
    sat = sgp4_api.Satrec.twoline2rv(l1, l2)
    for t in (0.0, 4.0, 1234.5, 5000.0):
        r = o.position_N(t)
        assert 6.65e6 < norm(r) < 6.85e6
        jd = julian_date(epoch) + t / 86400.0
        _, r_km, _ = sat.sgp4(math.floor(jd), jd - math.floor(jd))
        assert norm(tuple(a - 1e3 * b for a, b in zip(r, r_km, strict=True))) < 5 * M
    assert abs(math.degrees(o.inclination_rad) - 51.6439) < 1e-9
    assert dot(r, r) > 0
