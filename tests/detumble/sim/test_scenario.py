"""Scenario files: packaged scenarios load; every rejected value is named with its message (and line)."""

import math
import re
import textwrap

import pytest

from detumble.sim.scenario import ScenarioError, load_scenario, packaged_scenarios, parse_scenario
from detumble.sim.vec import mrp_to_quat


def test_packaged_scenarios_load():
    assert {"case_a", "default"} <= set(packaged_scenarios())
    for name in packaged_scenarios():
        assert load_scenario(name).name == name


def test_case_a_is_the_basilisk_case_exactly():
    sc = load_scenario("case_a")
    assert sc.spacecraft.mass_kg == 1.0
    assert sc.spacecraft.inertia_kg_m2 == ((1.67e-3, 0, 0), (0, 1.67e-3, 0), (0, 0, 1.67e-3))
    assert sc.orbit.mu_m3_s2 == 3.986004415e14 and sc.orbit.earth_radius_m == 6378136.6
    assert (sc.orbit.altitude_km, sc.orbit.inclination_deg, sc.orbit.raan_deg, sc.orbit.arg_latitude_deg) == (
        420.0, 51.6, 30.0, 0.0)
    assert not sc.orbit.j2
    f = sc.field
    assert (f.model, f.g10_nt, f.g11_nt, f.h11_nt) == ("dipole", -30926.0, -2318.0, 5817.0)
    assert f.earth_rotation_angle_deg == 0.0 and f.earth_rotation_rate_rad_s == 7.2921159e-5
    assert sc.q_BN0 == pytest.approx(mrp_to_quat((0.1, 0.2, -0.3)), abs=1e-15)
    axis = (0.36353657, 0.86429949, 0.34760259)
    assert sc.omega_BN_B0 == pytest.approx(tuple(math.radians(30.0) * a for a in axis), rel=1e-7)
    assert sc.magnetometer.ideal and sc.spacecraft.actuator_type == "rods"
    assert sc.spacecraft.rods_max_dipole_am2 == (0.2, 0.2, 0.2)
    assert sc.dynamics_step_s == 0.05 and sc.control.period_s == 0.05 and sc.control.law == "kopt"


def test_default_is_the_flight_layout():
    sc = load_scenario("default")
    coils = sc.spacecraft.coils
    assert sorted(coils) == [0, 1, 2, 3, 5]
    assert coils[0].max_dipole_am2 == pytest.approx(0.0581206, rel=1e-6)
    assert coils[5].max_dipole_am2 == pytest.approx(0.0087151, rel=1e-5)
    assert (sc.orbit.altitude_km, sc.orbit.inclination_deg) == (420.0, 51.6)
    assert math.degrees(math.sqrt(sum(w * w for w in sc.omega_BN_B0))) == pytest.approx(30.0)
    assert (sc.field.g10_nt, sc.field.g11_nt, sc.field.h11_nt) == (-29350.0, -1410.3, 4545.5)
    assert not sc.magnetometer.ideal and sc.magnetometer.coupling_t_per_am2 == (1.6e-3, 1.6e-3, 1.6e-3)


def test_scenario_path_or_name(tmp_path):
    path = tmp_path / "mine.yaml"
    path.write_text("name: mine\norbit:\n  altitude_km: 500\n")
    assert load_scenario(str(path)).orbit.altitude_km == 500.0
    assert load_scenario("case_a.yaml").name == "case_a"
    with pytest.raises(ScenarioError,
                       match=r"nope: no such scenario file, and not a packaged scenario \(packaged: .*case_a"):
        load_scenario("nope")


def _bad(text: str):
    with pytest.raises(ScenarioError) as info:
        parse_scenario(textwrap.dedent(text), source="s.yaml")
    return str(info.value)


@pytest.mark.parametrize(
    "text, message",
    [
        ("colour: red\n", r"^s\.yaml:1: colour: unknown key 'colour'; allowed here: .*duration_s"),
        ("orbit:\n  altitude_km: 420\n  eccentricity: 0.1\n",
         r"^s\.yaml:3: orbit\.eccentricity: unknown key 'eccentricity'; allowed here: .*altitude_km"),
        ("spacecraft:\n  inertia_kg_m2: [1.0e-3, -2.0e-3, 1.0e-3]\n",
         r"^s\.yaml:2: spacecraft\.inertia_kg_m2: diagonal element J\[1\]\[1\] = -0\.002 must be positive"),
        ("spacecraft:\n  inertia_kg_m2:\n    - [1.0e-3, 2.0e-3, 0.0]\n    - [2.0e-3, 1.0e-3, 0.0]\n"
         "    - [0.0, 0.0, 1.0e-3]\n",
         r"^s\.yaml:2: spacecraft\.inertia_kg_m2: must be positive definite; eigenvalues are -0\.001, 0\.001, 0\.003"),
        ("spacecraft:\n  inertia_kg_m2:\n    - [1.0e-3, 2.0e-4, 0.0]\n    - [1.0e-4, 1.0e-3, 0.0]\n"
         "    - [0.0, 0.0, 1.0e-3]\n",
         r"spacecraft\.inertia_kg_m2: must be symmetric: J\[0\]\[1\] = 0\.0002 but J\[1\]\[0\] = 0\.0001"),
        ("spacecraft:\n  inertia_kg_m2: [1.0e-3, 1.0e-3, 3.0e-3]\n",
         r"violate the triangle inequality \(J1 \+ J2 >= J3\): no rigid body has them"),
        ("orbit:\n  altitude_km: -50\n",
         r"^s\.yaml:2: orbit\.altitude_km: -50\.0 km is inside the Earth; give the height above the surface"),
        ("orbit:\n  altitude_km: 0\n", r"orbit\.altitude_km: 0\.0 km is inside the Earth"),
        ("orbit:\n  inclination_deg: .nan\n", r"^s\.yaml:2: orbit\.inclination_deg: must be a finite number, got nan"),
        ("dynamics_step_s: .inf\n", r"dynamics_step_s: must be a finite number, got inf"),
        ("dynamics_step_s: -0.05\n", r"dynamics_step_s: must be positive, got -0\.05"),
        ("spacecraft:\n  mass_kg: 0\n", r"spacecraft\.mass_kg: must be positive, got 0\.0"),
        ("orbit:\n  mu_m3_s2: 3.986e14\n",
         r"orbit\.mu_m3_s2: expected a number, got the string '3\.986e14'; YAML reads exponents only with a sign"),
        ("sensors:\n  magnetometer:\n    bias_gauss: [0.0, 0.1]\n",
         r"^s\.yaml:3: sensors\.magnetometer\.bias_gauss: expected a list of 3 numbers"),
        ("sensors:\n  gyro:\n    noise_density_dps_rthz: -1.0\n",
         r"sensors\.gyro\.noise_density_dps_rthz: must not be negative, got -1\.0"),
        ("sensors:\n  gyro:\n    odr: 104\n", r"sensors\.gyro\.odr: unknown key 'odr'; allowed here: .*odr_hz"),
        ("field:\n  model: igrf13\n",
         r"field\.model: unknown value 'igrf13'; expected one of: dipole, igrf14, wmm2025, none"),
        ("field:\n  model: wmm2025\n  table_step_s: 10\n",
         r"field\.table_step_s: 10\.0 s: evaluate the WMM at <= 1 Hz"),
        ("control:\n  law: pid\n", r"control\.law: unknown value 'pid'; expected one of: none, kopt, bdot"),
        ("control:\n  period_s: 0.07\n", r"control\.period_s: 0\.07 s must be a whole number of dynamics steps"),
        ("initial:\n  attitude:\n    quaternion: [1.0, 0.1, 0.0, 0.0]\n",
         r"^s\.yaml:3: initial\.attitude\.quaternion: must be a unit quaternion \(scalar first\); "
         r"its norm is 1\.00498"),
        ("initial:\n  attitude:\n    quaternion: [1, 0, 0, 0]\n    mrp: [0, 0, 0]\n",
         r"initial\.attitude\.mrp: give either quaternion or mrp, not both"),
        ("initial:\n  rate:\n    magnitude_deg_s: 30\n    axis: [0, 0, 0]\n",
         r"initial\.rate\.axis: the rotation axis must not be the zero vector"),
        ("spacecraft:\n  actuators:\n    type: rods\n    max_dipole_am2: [0.2, -0.2, 0.2]\n",
         r"spacecraft\.actuators\.max_dipole_am2\[1\]: must not be negative, got -0\.2"),
        ("spacecraft:\n  actuators:\n    z_minus: {shape: hexagonal}\n",
         r"spacecraft\.actuators\.z_minus\.shape: unknown value 'hexagonal'; expected one of: rectangular, circular"),
        ("spacecraft:\n  actuators:\n    z_plus: {turns: 10}\n",
         r"spacecraft\.actuators\.z_plus: unknown key 'z_plus'; allowed here: .*x_minus"),
        ("epoch: yesterday\n", r"^s\.yaml:1: epoch: Invalid isoformat string: 'yesterday'"),
        ("orbit: [1, 2]\n", r"^s\.yaml:1: orbit: expected a mapping of keys, got list"),
        ("orbit:\n  altitude_km: [420\n", r"^s\.yaml:3: not valid YAML"),
    ],
)
def test_rejected_values_name_key_line_and_reason(text, message):
    import re

    got = _bad(text)
    assert re.search(message, got), got


def test_random_initial_rate_is_seeded():
    text = "initial:\n  rate:\n    magnitude_deg_s: 30\n    random_axis: true\n"
    a = parse_scenario(text, seed=3).omega_BN_B0
    b = parse_scenario(text, seed=3).omega_BN_B0
    c = parse_scenario(text, seed=4).omega_BN_B0
    assert a == b and a != c
    assert math.degrees(math.sqrt(sum(w * w for w in a))) == pytest.approx(30.0, rel=1e-12)
    fixed = parse_scenario(text + "    seed: 11\n", seed=99).omega_BN_B0
    assert fixed == parse_scenario(text + "    seed: 11\n", seed=5).omega_BN_B0


def test_coil_override_merges_with_defaults_and_safe_load_only():
    sc = parse_scenario("spacecraft:\n  actuators:\n    x_plus: {turns: 50}\n")
    assert sc.spacecraft.coils[0].turns == 50.0 and sc.spacecraft.coils[0].resistance_ohm == 13.0
    with pytest.raises(ScenarioError, match="not valid YAML"):
        parse_scenario("name: !!python/object/apply:os.system ['true']\n")


def test_settings_override_single_values_with_yaml_types():
    sc = load_scenario("default", settings=["sensors.magnetometer.noise_std_gauss=0",
                                            "sensors.magnetometer.bias_gauss=[0, 0, 0.001]",
                                            "initial.rate.magnitude_deg_s=12.5"])
    default = load_scenario("default")
    assert sc.magnetometer.noise_std_gauss == 0.0 != default.magnetometer.noise_std_gauss
    assert tuple(sc.magnetometer.bias_gauss) == (0.0, 0.0, 0.001)
    assert math.degrees(math.sqrt(sum(w * w for w in sc.omega_BN_B0))) == pytest.approx(12.5)
    # A list element by index.
    one = load_scenario("default", settings=["sensors.magnetometer.bias_gauss.1=0.5"])
    assert one.magnetometer.bias_gauss == (0.012, 0.5, 0.005)


@pytest.mark.parametrize("setting, message", [
    ("sensors.magnetometr.noise_std_gauss=0",
     "has no key 'magnetometr' at sensors (keys there: magnetometer, gyro, accelerometer)"),
    ("noise=0", "has no key 'noise' at the top level"),
    ("sensors.magnetometer.noise_std_gauss", "expected KEY.PATH=VALUE"),
    ("sensors.magnetometer.bias_gauss.7=0", "is a list of 3; address an element by its index 0..2"),
    ("sensors.magnetometer.odr_hz.x=1", "sensors.magnetometer.odr_hz is a value, not a section"),
    ("sensors.magnetometer.odr_hz=[1", "the value is not valid YAML"),
])
def test_bad_settings_say_what_is_wrong(setting, message):
    with pytest.raises(ScenarioError, match=re.escape(message)):
        load_scenario("default", settings=[setting])


def test_a_setting_is_still_validated_like_the_file():
    with pytest.raises(ScenarioError, match="noise_std_gauss"):
        load_scenario("default", settings=["sensors.magnetometer.noise_std_gauss=-1"])
