"""Electrical power system: energy balance over an orbit, eclipse fraction against the closed form,
solar input against an independent orbit average, battery voltage against state of charge and load."""

import dataclasses
import math

import pytest

from detumble.sim.epoch import julian_date
from detumble.sim.orbit import R_EARTH_EQ
from detumble.sim.plant import build_orbit
from detumble.sim.power import (Battery, BatteryConfig, ElectricalSystem, LoadConfig, PowerConfig, cell_ocv,
                                coil_supply_power_w)
from detumble.sim.scenario import load_scenario
from detumble.sim.sun import SOLAR_CONSTANT_W_M2, eclipse_fraction_circular, in_umbra, sun_direction_N
from detumble.sim.vec import cross, dot, unit

SCENARIO = load_scenario("default")
ORBIT = build_orbit(SCENARIO)
JD0 = julian_date(SCENARIO.epoch)
PERIOD_S = 2 * math.pi / ORBIT.arg_latitude_rate


def _fly(cfg, duration_s, dt=1.0, q=(1.0, 0.0, 0.0, 0.0), coil_w=0.0):
    eps = ElectricalSystem(cfg, JD0, R_EARTH_EQ)
    e0 = eps.battery.energy_j
    t = 0.0
    eclipsed = 0
    steps = int(round(duration_s / dt))
    for _ in range(steps):
        eps.step(dt, t, q, ORBIT.position_N(t), coil_w)
        eclipsed += eps.eclipse
        t += dt
    return eps, e0, eclipsed / steps


def test_eclipse_fraction_matches_the_closed_form():
    """EPS-ECL-001: over one orbit of the reference orbit (420 km, 51.6 deg, epoch 2025-06-01) the
    sampled cylindrical-shadow fraction equals acos(sqrt(r²−R²)/(r cos β))/π within 0.2 % of an
    orbit (1 s sampling; β from the Sun and the orbit normal at mid-orbit)."""
    dt = 1.0
    n = int(PERIOD_S / dt)
    s_N, _ = sun_direction_N(JD0 + PERIOD_S / 2 / 86400)
    shadow = sum(in_umbra(ORBIT.position_N(k * dt), s_N, R_EARTH_EQ) for k in range(n)) / n
    r0, r1 = ORBIT.position_N(PERIOD_S / 2), ORBIT.position_N(PERIOD_S / 2 + 1.0)
    h_hat = unit(cross(r0, r1))
    beta = math.asin(dot(h_hat, s_N))
    expected = eclipse_fraction_circular(ORBIT.radius_m, beta, R_EARTH_EQ)
    assert 0.25 < expected < 0.45                   # a real eclipse on this orbit and date
    assert shadow == pytest.approx(expected, abs=0.002)


def test_no_eclipse_beyond_the_critical_beta():
    """EPS-ECL-002: the closed form gives 0 once |β| ≥ asin(R/r), and full half-orbit shadow at r → R."""
    r = R_EARTH_EQ + 420e3
    beta_star = math.asin(R_EARTH_EQ / r)
    assert eclipse_fraction_circular(r, beta_star + 1e-6, R_EARTH_EQ) == 0.0
    assert eclipse_fraction_circular(r, beta_star - 0.01, R_EARTH_EQ) > 0.0
    assert eclipse_fraction_circular(R_EARTH_EQ * 1.000001, 0.0, R_EARTH_EQ) == pytest.approx(0.5, abs=1e-3)


def test_sun_direction_against_the_june_solstice():
    """EPS-SUN-001: at the 2025 June solstice (21 Jun 02:42 UTC) the Sun's declination is the
    obliquity, 23.44 deg, within 0.02 deg; at the March equinox (20 Mar 09:01 UTC) it is 0 ± 0.02 deg."""
    import datetime as dt
    s, d = sun_direction_N(julian_date(dt.datetime(2025, 6, 21, 2, 42, tzinfo=dt.timezone.utc)))
    assert math.degrees(math.asin(s[2])) == pytest.approx(23.44, abs=0.02)
    assert d == pytest.approx(1.016, abs=0.001)      # near aphelion
    s, _ = sun_direction_N(julian_date(dt.datetime(2025, 3, 20, 9, 1, tzinfo=dt.timezone.utc)))
    assert math.degrees(math.asin(s[2])) == pytest.approx(0.0, abs=0.02)


def test_energy_balance_over_an_orbit():
    """EPS-BAL-001: over one orbit with the coils drawing 2 W, solar in − shunted = loads −
    unserved + I²R loss + ΔE_battery to 1e-6 of the energies involved (J)."""
    eps, e0, _ = _fly(SCENARIO.power, PERIOD_S, coil_w=2.0)
    lhs = eps.solar_j - eps.shunted_j
    rhs = eps.load_j - eps.unserved_j + eps.loss_j + (eps.battery.energy_j - e0)
    assert eps.loss_j > 0.0 and eps.solar_j > 0.0
    assert lhs == pytest.approx(rhs, rel=1e-6, abs=1e-6 * eps.load_j)
    assert eps.coil_j == pytest.approx(2.0 * round(PERIOD_S), rel=1e-9)  # 1 s steps


def test_energy_balance_with_a_full_battery_shunting():
    """EPS-BAL-002: a full battery and a light load: the surplus is shunted, the balance still holds
    and the state of charge never exceeds 1."""
    cfg = dataclasses.replace(SCENARIO.power, battery=BatteryConfig(initial_soc=1.0),
                              loads=LoadConfig(avionics_w=0.1, face_board_w=0.0))
    eps, e0, _ = _fly(cfg, PERIOD_S)
    assert eps.shunted_j > 0.0 and eps.battery.soc <= 1.0
    rhs = eps.load_j - eps.unserved_j + eps.loss_j + (eps.battery.energy_j - e0)
    assert eps.solar_j - eps.shunted_j == pytest.approx(rhs, rel=1e-6)


def test_energy_balance_when_the_battery_runs_empty():
    """EPS-BAL-003: an almost empty battery under a heavy load in eclipse runs out: what it could not
    deliver is counted as unserved, the bus voltage drops to 0, and the balance holds."""
    cfg = dataclasses.replace(SCENARIO.power, battery=BatteryConfig(capacity_wh=0.01, initial_soc=0.5),
                              solar=dataclasses.replace(SCENARIO.power.solar, efficiency=0.0))
    eps, e0, _ = _fly(cfg, 600.0, coil_w=5.0)
    assert eps.unserved_j > 0.0 and eps.battery.soc == 0.0 and eps.bus_v == 0.0
    rhs = eps.load_j - eps.unserved_j + eps.loss_j + (eps.battery.energy_j - e0)
    assert eps.solar_j - eps.shunted_j == pytest.approx(rhs, rel=1e-6, abs=1e-9)


def test_solar_input_against_the_orbit_average():
    """EPS-SOL-001: in an inertially fixed attitude with equal panels on all faces, the array power in
    sunlight is S/d²·η·A·(|sx|+|sy|+|sz|); the energy over one orbit equals that times the sunlit
    time from the closed-form eclipse fraction, within 0.5 % (the Sun moves 0.07 deg per orbit)."""
    eps, _, shadow = _fly(SCENARIO.power, PERIOD_S)
    s, d = sun_direction_N(JD0 + PERIOD_S / 2 / 86400)
    a = SCENARIO.power.solar.panel_area_m2[0]
    p_sun = SOLAR_CONSTANT_W_M2 / d**2 * SCENARIO.power.solar.efficiency * a * (abs(s[0]) + abs(s[1]) + abs(s[2]))
    r0, r1 = ORBIT.position_N(PERIOD_S / 2), ORBIT.position_N(PERIOD_S / 2 + 1.0)
    beta = math.asin(dot(unit(cross(r0, r1)), s))
    f = eclipse_fraction_circular(ORBIT.radius_m, beta, R_EARTH_EQ)
    assert eps.solar_j == pytest.approx(p_sun * PERIOD_S * (1.0 - f), rel=0.005)
    assert shadow == pytest.approx(f, abs=0.002)


def test_battery_voltage_against_charge_and_load():
    """EPS-BAT-001: terminal voltage is OCV(SoC)·cells − I·R with (OCV − IR)·I = P; OCV rises
    monotonically from 3.0 V (empty) to 4.2 V (full) per cell; a load beyond OCV²/4R is capped at
    the maximum-power current OCV/2R."""
    assert cell_ocv(0.0) == 3.0 and cell_ocv(1.0) == 4.2 and cell_ocv(0.55) == pytest.approx(3.82)
    assert all(cell_ocv(k / 100) < cell_ocv((k + 1) / 100) for k in range(100))
    bat = Battery(BatteryConfig(initial_soc=0.5, internal_resistance_ohm=0.2))
    ocv = bat.ocv()
    assert ocv == pytest.approx(2 * 3.78)
    i = bat.current_for(5.0)
    assert (ocv - i * 0.2) * i == pytest.approx(5.0, rel=1e-12)
    assert bat.current_for(-3.0) < 0.0                     # charging
    assert bat.current_for(1e6) == pytest.approx(ocv / 0.4)


def test_load_switches_shed_their_loads():
    """EPS-LOAD-001: each closed face switch adds face_board_w, the payload switch payload_power_w;
    unknown switches are refused with their valid names."""
    cfg = PowerConfig(switches_on=())
    eps = ElectricalSystem(cfg, JD0, R_EARTH_EQ)
    base = eps.switched_load_w()
    assert base == pytest.approx(cfg.loads.avionics_w)
    eps.set_switch("face2", True)
    eps.set_switch("payloadPower", True)
    assert eps.switched_load_w() == pytest.approx(base + cfg.loads.face_board_w + cfg.loads.payload_power_w)
    assert eps.face_powered(2) and not eps.face_powered(0)
    with pytest.raises(ValueError, match="payloadPower"):
        eps.set_switch("face9", True)


def test_coil_supply_power_is_v_squared_over_r_at_steady_state():
    """EPS-COIL-001: a coil at level L draws (L/127·V)²/R at its steady current."""
    v, r = 3.3, 13.0
    for level in (127, -64, 10):
        i = level / 127 * v / r
        assert coil_supply_power_w(level, 127, v, i) == pytest.approx((level / 127 * v) ** 2 / r)


def test_power_keys_can_be_set_on_a_scenario_without_them():
    """EPS-KEY-001: --set adds power and accelerometer keys to a scenario that has none (case_a), and
    a misspelt power key is an error naming the keys there."""
    from detumble.sim.scenario import ScenarioError
    sc = load_scenario("case_a", settings=["power.battery.initial_soc=0.05", "sensors.accelerometer.ideal=true"])
    assert sc.power.battery.initial_soc == 0.05 and sc.accelerometer.ideal is True
    with pytest.raises(ScenarioError, match="capacity_wh"):
        load_scenario("default", settings=["power.battery.capacity_w=3"])


def test_switched_load_counts_every_face_switch_as_the_sum_over_the_faces():
    """EPS-LOAD-002: the switched load is exactly ``avionics + face_board · (closed face switches)``
    (+ the payload lines) for every one of the 256 switch settings: each face counts once."""
    import itertools

    from detumble.sim.power import FACE_SWITCHES, SWITCH_NAMES
    eps = ElectricalSystem(PowerConfig(loads=LoadConfig(payload_battery_w=0.7)), JD0, R_EARTH_EQ)
    loads = eps.cfg.loads
    for setting in itertools.product((False, True), repeat=len(SWITCH_NAMES)):
        for name, on in zip(SWITCH_NAMES, setting, strict=True):
            eps.set_switch(name, on)
        faces = sum(1 for f in FACE_SWITCHES if eps.switches[f])
        expected = loads.avionics_w + loads.face_board_w * faces
        expected += loads.payload_power_w if eps.switches["payloadPower"] else 0.0
        expected += loads.payload_battery_w if eps.switches["payloadBattery"] else 0.0
        assert eps.switched_load_w() == expected


def test_the_current_at_a_given_ocv_is_the_current_for_the_load():
    """EPS-BAT-002: ``current_for_ocv(P, ocv())`` is ``current_for(P)`` bit for bit, for loads,
    charging and a load beyond the pack's maximum power, at several states of charge."""
    for soc in (0.0, 0.05, 0.37, 0.9, 1.0):
        bat = Battery(BatteryConfig(initial_soc=soc, internal_resistance_ohm=0.2))
        for p in (-7.5, -0.3, 0.0, 0.01, 5.0, 1e6):
            assert bat.current_for_ocv(p, bat.ocv()) == bat.current_for(p)
    ideal = Battery(BatteryConfig(internal_resistance_ohm=0.0))
    assert ideal.current_for_ocv(3.0, ideal.ocv()) == 3.0 / ideal.ocv()
