"""GEO-001…002: the on-board tilted-dipole field model (control.geomagnetic)."""

from __future__ import annotations

import math
import random

import pytest

from detumble.control.geomagnetic import (IGRF2025_G10_NT, IGRF2025_G11_NT, IGRF2025_H11_NT, IGRF_REFERENCE_RADIUS_M,
                                          dipole_field_N)
from detumble.sim.field import DipoleField


def test_the_model_is_the_plant_s_dipole():
    """GEO-001: at random positions (LEO shell) and times the model, given the Earth angle the ephemeris gives
    (θ0 + ω t), is the plant's DipoleField to 1e-12 of its magnitude: the same frames and coefficients."""
    rng = random.Random(5)
    plant = DipoleField(theta0_rad=1.1)
    for _ in range(50):
        v = [rng.gauss(0.0, 1.0) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        r = tuple((6.8e6 + rng.uniform(0.0, 5e5)) * x / n for x in v)
        t = rng.uniform(0.0, 86400.0)
        want = plant.b_N(t, r)
        got = dipole_field_N(r, plant.earth_angle(t))
        size = math.sqrt(sum(x * x for x in want))
        assert max(abs(a - b) for a, b in zip(got, want, strict=True)) < 1e-12 * size


def test_on_the_dipole_axis_the_field_is_twice_the_equator_s_along_the_axis():
    """GEO-002: on the dipole's axis (Earth-fixed direction d = (g11, h11, g10)) at r the field is along the axis
    with magnitude 2 (a/r)³ |d|; at the Earth's centre the model refuses (ValueError)."""
    d = (IGRF2025_G11_NT, IGRF2025_H11_NT, IGRF2025_G10_NT)
    size = math.sqrt(sum(x * x for x in d))
    angle = 0.3
    c, s = math.cos(angle), math.sin(angle)
    axis_N = ((c * d[0] - s * d[1]) / size, (s * d[0] + c * d[1]) / size, d[2] / size)
    r = 7.0e6
    b = dipole_field_N(tuple(r * a for a in axis_N), angle)
    expected = 2.0 * (IGRF_REFERENCE_RADIUS_M / r) ** 3 * size * 1e-9
    assert math.sqrt(sum(x * x for x in b)) == pytest.approx(expected, rel=1e-12)
    assert sum(x * a for x, a in zip(b, axis_N, strict=True)) == pytest.approx(expected, rel=1e-12)
    with pytest.raises(ValueError):
        dipole_field_N((0.0, 0.0, 0.0), angle)
