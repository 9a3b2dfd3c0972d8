"""SUNENV-001…004: the conical shadow (``sim.sun.sunlit_fraction``) and the Earth albedo on the light sensors
(``sim.sun_sensors``, the stated point-source model), against closed forms."""

from __future__ import annotations

import math

import pytest

from detumble.sim.sun import AU_M, SUN_RADIUS_M, in_umbra, sunlit_fraction
from detumble.sim.sun_sensors import FULL_SUN_LUX, SunSensorModel, SunSensorSpec

R_E = 6378137.0
R = R_E + 500e3
SUN = (1.0, 0.0, 0.0)


def _at(angle_deg: float):
    """A position on the orbit circle in the x–y plane, ``angle_deg`` past the anti-Sun line (0: midnight)."""
    t = math.radians(angle_deg)
    return (-R * math.cos(t), R * math.sin(t), 0.0)


def test_shadow_fraction_closed_forms():
    """SUNENV-001: lit side 1; midnight 0; on the Earth's limb line through the Sun's centre (c = b) half the disc
    (the limb nearly straight across the 0.27° Sun: 0.5 to 1 %); monotonic across the penumbra."""
    assert sunlit_fraction((R, 0.0, 0.0), SUN, 1.0, R_E) == 1.0
    assert sunlit_fraction(_at(0.0), SUN, 1.0, R_E) == 0.0
    b = math.asin(R_E / R)
    # at angle t past midnight the Earth's centre is seen t away from the Sun's direction: c = t
    mid = sunlit_fraction(_at(math.degrees(b)), SUN, 1.0, R_E)
    assert mid == pytest.approx(0.5, abs=0.01)
    fractions = [sunlit_fraction(_at(math.degrees(b) + d), SUN, 1.0, R_E) for d in (-0.4, -0.2, 0.0, 0.2, 0.4)]
    assert fractions == sorted(fractions) and fractions[0] == 0.0 and fractions[-1] == 1.0


def test_penumbra_lasts_seconds_and_brackets_the_cylinder():
    """SUNENV-002: a 500 km circular orbit with the Sun in its plane: the penumbra spans 2a / (cos-projected) of
    the orbit angle (the Sun's apparent diameter 0.53° over the limb's rate), i.e. 8–12 s at n = 0.063 °/s; the
    cylinder's shadow edge lies inside the conical penumbra's span."""
    steps = [60.0 + i * 0.001 for i in range(0, 16000)]  # deg past midnight, 60…76° (the limb at 68°)
    lit = [sunlit_fraction(_at(a), SUN, 1.0, R_E) for a in steps]
    partial = [a for a, f in zip(steps, lit, strict=True) if 0.0 < f < 1.0]
    n_deg_s = math.degrees(math.sqrt(3.986004418e14 / R ** 3))
    duration = (partial[-1] - partial[0]) / n_deg_s
    assert 8.0 <= duration <= 12.0
    edge = next(a for a in steps if not in_umbra(_at(a), SUN, R_E))
    assert partial[0] <= edge <= partial[-1]
    assert math.degrees(2 * math.asin(SUN_RADIUS_M / AU_M)) == pytest.approx(0.533, abs=0.002)


def test_albedo_lights_the_nadir_face_by_the_stated_model():
    """SUNENV-003: body = N, the spacecraft on +X (the Sun overhead, elevation 1): with albedo 0.3 the −X face
    (toward nadir) reads 0.3 (R_E/r)² E_1AU/d² (26 % of full Sun at 500 km) more than without; the +X face (the
    Sun's) is unchanged; at the terminator (elevation 0) it adds nothing."""
    jd = 2460827.5
    readings = {}
    for a in (0.0, 0.3):
        m = SunSensorModel(jd, R_E, SunSensorSpec(gain_sigma=0.0, noise_sigma=0.0, albedo=a), seed=1)
        s_N, d_au = m.sun(0.0)
        readings[a] = m.read(0.0, (1.0, 0.0, 0.0, 0.0), (R * s_N[0], R * s_N[1], R * s_N[2]))
    s_x = s_N[0]
    expected = 0.3 * (R_E / R) ** 2 * FULL_SUN_LUX / d_au ** 2
    nadir_B = (-s_N[0], -s_N[1], -s_N[2])
    for i, n in enumerate(((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1))):
        cos_nadir = max(0.0, sum(n[k] * nadir_B[k] for k in range(3)))
        assert readings[0.3][i] - readings[0.0][i] == pytest.approx(expected * cos_nadir, rel=1e-12, abs=1e-9)
    assert expected / FULL_SUN_LUX * d_au ** 2 == pytest.approx(0.258, abs=0.002)
    assert s_x != 0.0
    m = SunSensorModel(jd, R_E, SunSensorSpec(gain_sigma=0.0, noise_sigma=0.0, albedo=0.3), seed=1)
    s_N, _ = m.sun(0.0)
    side = (s_N[1] * R / math.hypot(s_N[0], s_N[1]), -s_N[0] * R / math.hypot(s_N[0], s_N[1]), 0.0)  # r ⟂ ŝ
    m0 = SunSensorModel(jd, R_E, SunSensorSpec(gain_sigma=0.0, noise_sigma=0.0), seed=1)
    assert m.read(0.0, (1.0, 0.0, 0.0, 0.0), side) == pytest.approx(m0.read(0.0, (1.0, 0.0, 0.0, 0.0), side))


def test_bad_environment_figures_are_refused():
    """SUNENV-004: an albedo outside [0, 1) or a penumbra flag that is not a bool is refused by name."""
    with pytest.raises(ValueError, match="albedo"):
        SunSensorSpec(albedo=1.2)
    with pytest.raises(ValueError, match="penumbra"):
        SunSensorSpec(penumbra="yes")  # type: ignore[arg-type]
