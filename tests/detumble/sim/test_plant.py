"""Plant: seeded reproducibility, clock handling, driver-facing getters."""

import math

import pytest

from detumble.sim.coils import X_MINUS, X_PLUS, Y_PLUS, Z_MINUS
from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario, scenario_from_dict


def _fly(seed: int, steps: int = 400):
    """Default scenario, a fixed coil pattern, every getter polled: the full trajectory."""
    p = Plant(load_scenario("default"), seed=seed)
    out = []
    for k in range(steps):
        if k % 50 == 0:
            level = (k // 50) * 17 % 255 - 127
            p.set_coil_level(X_PLUS, level)
            p.set_coil_level(X_MINUS, -level)
            p.set_coil_level(Z_MINUS, level // 2)
        p.step()
        out.append((p.state, p.magnetometer_reading(), p.gyro_reading()))
    return out


def test_same_seed_same_trajectory_and_readings():
    a = _fly(5)
    b = _fly(5)
    assert a == b  # bit-identical: states, magnetometer and gyro readings
    c = _fly(6)
    assert [x[1] for x in a] != [x[1] for x in c]  # different sensor noise
    # the true dynamics do not depend on the sensor-noise seed
    assert a[-1][0] == c[-1][0]


def test_clock_is_integer_nanoseconds_and_advance_to_partial_steps():
    p = Plant(load_scenario("case_a"))
    for _ in range(3):
        p.advance_to(p.t + 0.02)  # a 50 Hz scheduler driving a 20 Hz dynamics step
    assert p.t_ns == 60_000_000
    p.advance_to(1.0)
    assert p.t_ns == 1_000_000_000
    with pytest.raises(ValueError,
                       match=r"cannot go back in time: plant is at 1\.000000000 s, asked for 0\.500000000 s"):
        p.advance_to(0.5)
    # the same 1 s of physics in whole steps agrees to integration error
    q = Plant(load_scenario("case_a"))
    for _ in range(20):
        q.step()
    assert max(abs(a - b) for a, b in zip(p.state, q.state, strict=True)) < 1e-9


def test_getters_are_plain_floats_in_stated_units():
    p = Plant(load_scenario("default"))
    p.advance_to(0.5)
    w = p.omega_BN_B
    assert all(type(x) is float for x in w)
    assert math.degrees(math.sqrt(sum(x * x for x in w))) == pytest.approx(30.0, rel=0.01)
    b = p.b_B
    assert all(type(x) is float for x in b) and 19e-6 < math.sqrt(sum(x * x for x in b)) < 53e-6  # T
    bx, by, bz, t = p.magnetometer_reading()
    assert all(type(x) is float for x in (bx, by, bz, t)) and t == 0.5
    assert math.sqrt(bx * bx + by * by + bz * bz) == pytest.approx(math.sqrt(sum(x * x for x in b)) * 1e4, abs=0.03)
    assert p.magnetometer_period_s == 0.01
    gx, gy, gz, tg = p.gyro_reading()
    assert (gx, gy, gz) == pytest.approx(w, abs=math.radians(0.5))  # bias 0.3 deg/s + noise
    p.set_coil_level(Y_PLUS, 10, t=0.6)
    assert p.t == pytest.approx(0.6) and p.coil_levels()[Y_PLUS] == 10


def test_rods_spacecraft_has_no_face_coils():
    p = Plant(load_scenario("case_a"))
    with pytest.raises(TypeError, match="this spacecraft has ideal torque rods, not face coils; use apply_dipole_B"):
        p.set_coil_level(X_PLUS, 10)


def test_magnetic_torque_changes_momentum_as_m_cross_b():
    """Over a short interval dH/dt = m x B (isotropic body, no other torque)."""
    sc = scenario_from_dict({
        "spacecraft": {"inertia_kg_m2": [2e-3, 2e-3, 2e-3], "gravity_gradient": False,
                       "actuators": {"type": "rods", "max_dipole_am2": [0.2, 0.2, 0.2]}},
        "sensors": {"magnetometer": {"ideal": True}, "gyro": {"ideal": True}},
        "dynamics_step_s": 0.01,
    })
    p = Plant(sc)
    p.apply_dipole_B((0.2, -0.1, 0.05))
    h0 = p.angular_momentum_B()
    b = p.b_B
    m = p.m_coils_B
    tau = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
    p.step(0.01)
    h1 = p.angular_momentum_B()
    # body frame is non-rotating here (omega0 = 0), so dH_B = tau dt to second order
    assert all(abs((h1[i] - h0[i]) - tau[i] * 0.01) < 1e-3 * max(abs(t) for t in tau) * 0.01 for i in range(3))


def test_optional_wmm_and_tle_scenarios_fly():
    """WMM2025 field (pygeomag) and a TLE orbit (sgp4) through the scenario loader and the plant."""
    pytest.importorskip("pygeomag")
    pytest.importorskip("sgp4")
    from detumble.sim.scenario import parse_scenario

    text = (
        'epoch: "2019-12-09T16:00:00Z"\n'
        "orbit:\n  type: tle\n  tle:\n"
        '    - "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991"\n'
        '    - "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482"\n'
        "field:\n  model: wmm2025\n"
    )
    p = Plant(parse_scenario(text))
    p.advance_to(3.0)
    b = math.sqrt(sum(x * x for x in p.b_B))
    assert 15e-6 < b < 60e-6  # T
    assert 6.65e6 < math.sqrt(sum(x * x for x in p.r_N)) < 6.85e6  # m


def test_recommanding_an_unchanged_coil_level_keeps_the_commanded_dipole_exactly():
    """SIM-PLANT-020: set_coil_level with an unchanged level skips the recomputation, yet
    m_commanded_B always equals (==) the dipole the levels command - also after apply_dipole_B
    replaced it with a requested dipole."""
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    p = Plant(load_scenario("default"))
    p.set_coil_level(0, 60)
    p.set_coil_level(5, -30)
    expected = p.actuators.commanded_dipole_B()
    p.set_coil_level(0, 60)
    assert p.m_commanded_B == expected
    p.apply_dipole_B((0.01, 0.0, 0.0))  # a requested dipole, not the levels' own
    p.set_coil_level(5, p.coil_levels()[5])  # unchanged level: m_commanded_B must follow the levels again
    assert p.m_commanded_B == p.actuators.commanded_dipole_B()


def test_commanded_dipole_follows_each_level_change_when_read_later():
    """m_commanded_B is computed from the levels when read: after any run of set_coil_level calls
    (changed, unchanged, several between reads) it equals (==) the dipole the present levels command,
    and apply_dipole_B's requested dipole stands until the next set_coil_level."""
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    p = Plant(load_scenario("default"))
    assert p.m_commanded_B == (0.0, 0.0, 0.0)
    for face, level in ((0, 60), (1, -60), (2, 17), (3, -17), (5, 127)):
        p.set_coil_level(face, level)
    assert p.m_commanded_B == p.actuators.commanded_dipole_B() != (0.0, 0.0, 0.0)
    p.set_coil_level(2, -40)
    assert p.m_commanded_B == p.actuators.commanded_dipole_B()
    p.set_coil_level(5, 0)
    p.set_coil_level(0, 0)
    p.step()
    assert p.m_commanded_B == p.actuators.commanded_dipole_B()
    p.apply_dipole_B((0.0, 0.01, 0.0))
    assert p.m_commanded_B == (0.0, 0.01, 0.0)
    p.step()
    assert p.m_commanded_B == (0.0, 0.01, 0.0)  # not overwritten by the levels apply_dipole_B chose
