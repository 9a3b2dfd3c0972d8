"""POINTING targets as data (detumble.control.targets): each target's reference attitude, rate and acceleration
against closed forms and against central differences of the reference itself; refusals (issue 27)."""

import math

import pytest

from detumble.analysis.pointing_windows import acquisition_time, pointing_windows
from detumble.control.quaternion import quat_angle, quat_conj, quat_mul, rotate_n_to_b
from detumble.control.targets import (EARTH_RATE_RAD_S, MU_EARTH_M3_S2, Ephemeris, InertialTarget, NadirTarget,
                                      StationTarget, SunTarget, axes_error, station_ecef, station_elevation_deg,
                                      station_error, target_entry_error)

A = 6378136.6 + 420e3  # m
N = math.sqrt(MU_EARTH_M3_S2 / A ** 3)  # rad/s
INC = math.radians(51.6)
SUN = (0.6, 0.64, 0.48)  # unit


def eph(t, theta0=0.3):
    """A circular two-body orbit (RAAN 0, argument of latitude n t) and a rotating Earth."""
    u = N * t
    r = (A * math.cos(u), A * math.sin(u) * math.cos(INC), A * math.sin(u) * math.sin(INC))
    v = (-A * N * math.sin(u), A * N * math.cos(u) * math.cos(INC), A * N * math.cos(u) * math.sin(INC))
    return Ephemeris(r, v, theta0 + EARTH_RATE_RAD_S * t, SUN)


def _unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def _fd_rate(target, t, h=0.05):
    """ω_R by a central difference of the reference attitude: q(t−h)⁻¹ ⊗ q(t+h) ≈ (1, ω h)."""
    q1, q2 = target.reference(eph(t - h)).q_RN, target.reference(eph(t + h)).q_RN
    dq = quat_mul(quat_conj(q1), q2)
    if dq[0] < 0:
        dq = tuple(-c for c in dq)
    return tuple(c / h for c in dq[1:])


def test_lvlh_rate_is_the_orbit_rate_about_the_orbit_normal():
    """TGT-001: +Z to nadir, +X along the velocity: in the reference frame ω_R = (0, −n, 0) (the orbit normal is −Y)
    to 1e-12 rad/s, α_R = 0 (circular orbit) to 1e-15 rad/s², and the attitude puts +Z on −r̂ and +X on v̂ (1e-12)."""
    for t in (0.0, 700.0, 3000.0):
        e = eph(t)
        ref = NadirTarget().reference(e)
        assert ref.omega_R == pytest.approx((0.0, -N, 0.0), abs=1e-12)
        assert max(abs(a) for a in ref.alpha_R) < 1e-15
        assert rotate_n_to_b(ref.q_RN, _unit(e.r_N)) == pytest.approx((0.0, 0.0, -1.0), abs=1e-12)
        assert rotate_n_to_b(ref.q_RN, _unit(e.v_N)) == pytest.approx((1.0, 0.0, 0.0), abs=1e-12)


@pytest.mark.parametrize("primary, secondary", [(4, 0), (1, 2), (3, 5), (0, 4)])
def test_nadir_any_axis_pair_and_its_rate_match_central_differences(primary, secondary):
    """TGT-002: any perpendicular body-axis pair: the primary axis on nadir, |ω| = n, and ω_R equals the central
    difference of the reference attitude (1e-9 rad/s)."""
    from detumble.control.targets import BODY_AXES
    target = NadirTarget(primary, secondary)
    e = eph(1234.0)
    ref = target.reference(e)
    assert rotate_n_to_b(ref.q_RN, _unit(tuple(-c for c in e.r_N))) == pytest.approx(BODY_AXES[primary][1], abs=1e-12)
    assert math.sqrt(sum(c * c for c in ref.omega_R)) == pytest.approx(N, rel=1e-12)
    assert ref.omega_R == pytest.approx(_fd_rate(target, 1234.0), abs=1e-9)


def _overhead_station(t):
    """A station on the ground track at ``t`` (geocentric latitude taken as geodetic: a few km off, still in view)."""
    e = eph(t)
    th = e.earth_angle_rad
    x, y, z = e.r_N
    xe, ye = math.cos(th) * x + math.sin(th) * y, -math.sin(th) * x + math.cos(th) * y
    return math.degrees(math.atan2(z, math.hypot(xe, ye))), math.degrees(math.atan2(ye, xe))


def test_station_rate_and_acceleration_match_central_differences_through_a_pass():
    """TGT-003: during a near-overhead pass the station target's ω_R matches the central difference of its attitude
    (1e-8 rad/s) and α_R that of ω_R (1e-8 rad/s²), at rates up to ~1 °/s; the primary axis is on the line of
    sight (1e-12)."""
    lat, lon = _overhead_station(1500.0)
    target = StationTarget(lat, lon + 1.0, 0.0, min_elevation_deg=10.0)
    peak = 0.0
    for t in (1400.0, 1480.0, 1500.0, 1520.0, 1600.0):
        e = eph(t)
        assert target.in_view(e)
        ref = target.reference(e)
        assert ref.label == 2
        assert ref.omega_R == pytest.approx(_fd_rate(target, t, 0.02), abs=1e-8)
        h = 0.02
        w1, w2 = target.reference(eph(t - h)).omega_R, target.reference(eph(t + h)).omega_R
        # ω_R is in the moving frame; the difference of its components is α_R to first order (α_R × ω term is 0)
        assert ref.alpha_R == pytest.approx(tuple((b - a) / (2 * h) for a, b in zip(w1, w2, strict=False)), abs=1e-8)
        pos, _ = station_ecef(lat, lon + 1.0, 0.0)
        th = e.earth_angle_rad
        s_n = (math.cos(th) * pos[0] - math.sin(th) * pos[1], math.sin(th) * pos[0] + math.cos(th) * pos[1], pos[2])
        los = _unit(tuple(a - b for a, b in zip(s_n, e.r_N, strict=False)))
        assert rotate_n_to_b(ref.q_RN, los) == pytest.approx((0.0, 0.0, 1.0), abs=1e-12)
        peak = max(peak, math.degrees(math.sqrt(sum(c * c for c in ref.omega_R))))
    assert 0.5 < peak < 1.2


def test_station_line_of_sight_rate_at_closest_approach_is_the_closed_form():
    """TGT-004: at the pass's closest approach the line of sight turns at |v_rel ⊥ los| / range (v_rel = v − ω_E × s):
    the component of ω_R across the primary axis equals it to 1e-9 rad/s."""
    lat, lon = _overhead_station(1500.0)
    target = StationTarget(lat, lon, 0.0)
    # the closest approach: the range is smallest
    def rng(t):
        e = eph(t)
        pos, _ = station_ecef(lat, lon, 0.0)
        th = e.earth_angle_rad
        s_n = (math.cos(th) * pos[0] - math.sin(th) * pos[1], math.sin(th) * pos[0] + math.cos(th) * pos[1], pos[2])
        return math.dist(s_n, e.r_N), s_n, e
    t = min((1500.0 + k * 0.05 for k in range(-400, 400)), key=lambda x: rng(x)[0])
    d, s_n, e = rng(t)
    w_e = (0.0, 0.0, EARTH_RATE_RAD_S)
    ws = (w_e[1] * s_n[2] - w_e[2] * s_n[1], w_e[2] * s_n[0] - w_e[0] * s_n[2], w_e[0] * s_n[1] - w_e[1] * s_n[0])
    v_rel = tuple(a - b for a, b in zip(e.v_N, ws, strict=False))
    los = _unit(tuple(a - b for a, b in zip(s_n, e.r_N, strict=False)))
    along = sum(a * b for a, b in zip(v_rel, los, strict=False))
    closed = math.sqrt(sum((a - along * b) ** 2 for a, b in zip(v_rel, los, strict=False))) / d
    w = target.reference(e).omega_R
    assert math.hypot(w[0], w[1]) == pytest.approx(closed, abs=1e-9)


def test_station_out_of_view_flies_the_nadir_fallback():
    """TGT-005: below the elevation mask the station target is the nadir target with the same axes
    (STATION_FALLBACK), and the elevation agrees with the geometry (the antipode is at −90°)."""
    lat, lon = _overhead_station(1500.0)
    e = eph(1500.0 + 2500.0)
    target = StationTarget(lat, lon, 0.0, 1, 2)
    assert not target.in_view(e)
    ref = target.reference(e)
    assert ref.label == 3 and ref.q_RN == NadirTarget(1, 2).reference(e).q_RN
    assert station_elevation_deg(station_ecef(0.0, 0.0, 0.0), Ephemeris((-A, 0.0, 0.0), (0.0, 7.6e3, 0.0), 0.0, SUN)) \
        == pytest.approx(-90.0)
    assert station_elevation_deg(station_ecef(0.0, 0.0, 0.0), Ephemeris((A, 0.0, 0.0), (0.0, 7.6e3, 0.0), 0.0, SUN)) \
        == pytest.approx(90.0)


def test_sun_target_points_the_axis_at_the_sun_with_the_secondary_toward_the_orbit_normal():
    """TGT-006: the primary axis on the Sun (1e-12), the secondary axis in the plane of the Sun line and the orbit
    normal on the normal's side, zero reference rate (the Sun's 1.1e-5 °/s is neglected: stated)."""
    e = eph(100.0)
    ref = SunTarget(0, 4).reference(e)
    assert rotate_n_to_b(ref.q_RN, SUN) == pytest.approx((1.0, 0.0, 0.0), abs=1e-12)
    h = _unit((e.r_N[1] * e.v_N[2] - e.r_N[2] * e.v_N[1], e.r_N[2] * e.v_N[0] - e.r_N[0] * e.v_N[2],
               e.r_N[0] * e.v_N[1] - e.r_N[1] * e.v_N[0]))
    hb = rotate_n_to_b(ref.q_RN, h)
    assert hb[1] == pytest.approx(0.0, abs=1e-12) and hb[2] > 0
    assert ref.omega_R == (0.0, 0.0, 0.0) and ref.alpha_R == (0.0, 0.0, 0.0)
    assert InertialTarget((1.0, 0.0, 0.0, 0.0)).reference().omega_R == (0.0, 0.0, 0.0)
    assert quat_angle(quat_mul(quat_conj(ref.q_RN), SunTarget(0, 4).reference(eph(100.0)).q_RN)) == 0.0


def test_bad_axes_and_stations_are_refused_with_a_reason():
    """TGT-007: a parallel or unknown axis pair, a station off the Earth or not finite, and malformed target entries
    are refused with the reason; good ones pass."""
    assert axes_error(4, 0) is None and axes_error(4, 5) is not None and "parallel" in axes_error(2, 2)
    assert axes_error(4, 6) is not None
    assert station_error(45.0, -120.0, 300.0) is None
    assert "latitude" in station_error(91.0, 0.0, 0.0) and "longitude" in station_error(0.0, 400.0, 0.0)
    assert "altitude" in station_error(0.0, 0.0, 5e5) and "finite" in station_error(float("nan"), 0.0, 0.0)
    assert target_entry_error(("NADIR", "PLUS_Z", "PLUS_X")) is None
    assert target_entry_error(("GROUND_STATION", 40.0, -105.0, 1600.0, "PLUS_Z", "PLUS_X")) is None
    assert "parallel" in target_entry_error(("SUN", "PLUS_Z", "MINUS_Z"))
    assert "latitude" in target_entry_error(("GROUND_STATION", 100.0, 0.0, 0.0, "PLUS_Z", "PLUS_X"))
    assert "among" in target_entry_error(("NADIR", "UP", "PLUS_X"))
    assert "give NADIR" in target_entry_error(("MOON", "PLUS_Z", "PLUS_X"))
    assert "unit quaternion" in target_entry_error((0.5, 0.0, 0.0, 0.0))


def test_acquisition_is_reported_apart_from_the_steady_statistics():
    """TGT-010: intervals start at entry, at a target change and after a gap; acquisition is the time until the error
    stays below the interval's threshold (0.1° on the wheels, 30° on the coils), None when it never does (the whole
    interval is then left out of the steady statistics), and the steady statistics hold only the samples after."""
    assert acquisition_time([0, 1, 2, 3], [5.0, 0.5, 2.0, 0.1], 1.0) == 3
    assert acquisition_time([0, 1, 2], [0.5, 0.2, 0.1], 1.0) == 0.0
    assert acquisition_time([0, 1, 2], [0.5, 0.2, 3.0], 1.0) is None
    s = [(t * 0.5, 50.0 if t < 4 else 0.01, "a", "NADIR", True) for t in range(20)]
    s += [(10.0 + t * 0.5, 40.0 if t < 2 else 20.0, "b", "INERTIAL", False) for t in range(10)]  # coils: below 30
    s += [(100.0 + t * 0.5, 2.0, "c", "SUN", True) for t in range(4)]  # a new interval after a gap: never acquired
    w = pointing_windows(s, 0.5)
    assert w["acquisition_s"] == 2.0 and w["acquisition_threshold_deg"] == 0.1
    assert [(i["target"], i["acquisition_s"], i["threshold_deg"]) for i in w["intervals"]] == [
        ("NADIR", 2.0, 0.1), ("INERTIAL", 1.0, 30.0), ("SUN", None, 0.1)]
    assert w["steady"]["samples"] == 16 + 8 and w["steady"]["max"] == 20.0
    assert w["by_target"]["NADIR"]["median"] == 0.01 and w["by_target"]["SUN"] is None
