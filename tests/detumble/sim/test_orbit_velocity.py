"""Orbit velocities (needed by the orbit frame): the derivative of the positions."""

import math

import pytest

from detumble.sim.orbit import J2_EARTH, CircularOrbit, TleOrbit


def _central_difference(orbit, t, h=1e-2):
    a, b = orbit.position_N(t - h), orbit.position_N(t + h)
    return tuple((y - x) / (2 * h) for x, y in zip(a, b, strict=True))


def test_circular_velocity_is_the_derivative_of_the_position_with_j2():
    """OV-001: analytic velocity = central difference (0.1 s) of the position to 1e-4 m/s (J2 drift
    on; leaving out the RAAN-drift term would be off by ~7 m/s)."""
    orbit = CircularOrbit(420e3, math.radians(51.6), 0.4, 1.1, j2=J2_EARTH)
    for t in (0.0, 1234.5, 86400.0):
        assert orbit.velocity_N(t) == pytest.approx(_central_difference(orbit, t, 0.1), abs=1e-4)


def test_tle_velocity_is_the_derivative_of_the_hermite_interpolant():
    """OV-002: the TLE orbit's velocity (derivative of its cubic Hermite table, filled here from a
    circular orbit instead of SGP4) equals the central difference of its positions to 1e-5 m/s,
    and the circular orbit's own velocity to 0.05 m/s between 10 s nodes."""
    ref = CircularOrbit(500e3, 0.9, 0.2, 0.3)
    tle = TleOrbit.__new__(TleOrbit)
    tle.step_s = 10.0
    tle._cache = {k: (ref.position_N(10.0 * k), ref.velocity_N(10.0 * k)) for k in range(-2, 40)}
    for t in (3.3, 57.1, 101.9):
        assert tle.velocity_N(t) == pytest.approx(_central_difference(tle, t), abs=1e-5)
        assert tle.velocity_N(t) == pytest.approx(ref.velocity_N(t), abs=0.05)
