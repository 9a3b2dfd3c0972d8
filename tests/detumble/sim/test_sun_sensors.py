"""SUN-001…004: the six face light sensors (detumble.sim.sun_sensors): cosine law, eclipse, noise as stated."""

from __future__ import annotations

import math
import statistics

import pytest

from detumble.sim.orbit import R_EARTH_EQ
from detumble.sim.sun import sun_direction_N
from detumble.sim.sun_sensors import FULL_SUN_LUX, SunSensorModel, SunSensorSpec, ideal_illuminance

JD = 2460827.5  # 2025-06-01


def _ideal_model() -> SunSensorModel:
    return SunSensorModel(JD, R_EARTH_EQ, SunSensorSpec(gain_sigma=0.0, noise_sigma=0.0))


def test_cosine_law_on_each_face():
    """SUN-001: a face reads E cos θ to the Sun (E = 133 klx / d²), 0 turned away; opposite faces never both lit."""
    for angle_deg in (0.0, 30.0, 60.0, 89.0, 91.0, 150.0):
        a = math.radians(angle_deg)
        s = (math.cos(a), math.sin(a), 0.0)
        r = ideal_illuminance(s, 1.0, False)
        assert r[0] == pytest.approx(FULL_SUN_LUX * max(0.0, math.cos(a)), abs=1e-9)
        assert r[1] == pytest.approx(FULL_SUN_LUX * max(0.0, -math.cos(a)), abs=1e-9)
        assert r[2] == pytest.approx(FULL_SUN_LUX * math.sin(a), abs=1e-9)
        assert r[3] == 0.0 and r[4] == r[5] == 0.0
    assert ideal_illuminance((0.0, 0.0, 1.0), 1.0167, False)[4] == pytest.approx(FULL_SUN_LUX / 1.0167 ** 2)


def test_eclipse_behind_the_earth_and_lit_on_the_sun_side():
    """SUN-002: Behind the Earth on the Earth–Sun line every sensor reads 0; on the Sun side the face toward the Sun
    reads the full Sun (the attitude is the identity, so B = N)."""
    m = _ideal_model()
    s_N, d = sun_direction_N(JD)
    r = 7.0e6
    behind = tuple(-r * c for c in s_N)
    assert m.read(0.0, (1.0, 0.0, 0.0, 0.0), behind) == (0.0,) * 6 and m.eclipse
    front = tuple(r * c for c in s_N)
    lit = m.read(1.0, (1.0, 0.0, 0.0, 0.0), front)
    assert not m.eclipse
    s_N1, d1 = sun_direction_N(JD + 1.0 / 86400.0)
    expected = ideal_illuminance(s_N1, d1, False)
    assert lit == pytest.approx(expected, abs=1e-6)
    # beside the shadow cylinder (just over one Earth radius off the line, behind the Earth): lit again
    perp = (s_N[1], -s_N[0], 0.0)
    k = math.hypot(*perp)
    side = tuple(-r * c + 1.01 * R_EARTH_EQ * p / k for c, p in zip(s_N, perp, strict=True))
    m.read(2.0, (1.0, 0.0, 0.0, 0.0), side)
    assert not m.eclipse


def test_noise_and_gain_errors_have_the_stated_spread():
    """SUN-003: Over many readings the noise is N(0, 0.5 % of full Sun) and the gains spread as N(1, 2 %); the same
    instant read twice gives the same exposure; the same seed repeats."""
    spec = SunSensorSpec()
    gains = [g for seed in range(200) for g in SunSensorModel(JD, R_EARTH_EQ, spec, seed).gains]
    assert statistics.fmean(gains) == pytest.approx(1.0, abs=0.004)
    assert statistics.stdev(gains) == pytest.approx(0.02, rel=0.1)
    m = SunSensorModel(JD, R_EARTH_EQ, spec, seed=3)
    q = (1.0, 0.0, 0.0, 0.0)
    r_N = tuple(7.0e6 * c for c in sun_direction_N(JD)[0])
    readings = [m.read(0.1 * k, q, r_N) for k in range(2000)]
    assert m.read(0.1 * 1999, q, r_N) is readings[-1]
    s_B = m.true_sun_B(0.0, q)
    lit = max(range(6), key=lambda i: readings[0][i])
    values = [r[lit] for r in readings]
    # the lit face: mean E cos θ times its gain (the Sun moves 0.0023 deg over 200 s), spread 0.5 % of E
    e = ideal_illuminance(s_B, sun_direction_N(JD)[1], False)[lit] * m.gains[lit]
    assert statistics.fmean(values) == pytest.approx(e, rel=2e-3)
    assert statistics.stdev(values) == pytest.approx(0.005 * FULL_SUN_LUX, rel=0.08)
    again = SunSensorModel(JD, R_EARTH_EQ, spec, seed=3)
    assert again.read(0.0, q, r_N) == readings[0]


def test_bad_noise_figures_are_refused():
    """SUN-004: a noise figure that is not a fraction is refused, naming it."""
    with pytest.raises(ValueError, match="noise_sigma"):
        SunSensorSpec(noise_sigma=-0.1)
    with pytest.raises(ValueError, match="gain_sigma"):
        SunSensorSpec(gain_sigma=float("nan"))


def test_the_scenario_sets_the_light_sensors():
    """SUN-005: ``sensors.sun_sensors`` reaches the deployment's sensors (albedo, penumbra, noise figures); absent,
    the defaults (no albedo: the deployments' outputs unchanged); a bad figure refused by name with the range."""
    import pytest

    from detumble.sim.scenario import ScenarioError, load_scenario
    from detumble.sim.sun_sensors import SunSensorSpec

    assert load_scenario("adcs").sun_sensors == SunSensorSpec()
    sc = load_scenario("adcs", settings=["sensors.sun_sensors.albedo=0.3", "sensors.sun_sensors.penumbra=true",
                                         "sensors.sun_sensors.noise_sigma=0.01"])
    assert sc.sun_sensors == SunSensorSpec(albedo=0.3, penumbra=True, noise_sigma=0.01)
    from detumble.drivers.spacecraft import SimulatedSpacecraft

    assert SimulatedSpacecraft(sc).sun_sensors.spec.albedo == 0.3
    with pytest.raises(ScenarioError, match=r"sensors\.sun_sensors\.albedo: .*\[0, 1\)"):
        load_scenario("adcs", settings=["sensors.sun_sensors.albedo=1.3"])
