"""The ADCS truth columns: pointing error to a target, torques, wheels (detumble.sim.truth)."""

import math

import pytest

from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario
from detumble.sim.truth import adcs_header, adcs_row
from detumble.sim.vec import cross, quat_from_axis_angle, quat_mul

N_SEED = math.sqrt(3.98e5 / 7000.0 ** 3)


def test_pointing_error_to_an_inertial_and_an_orbit_target():
    """TR-001: a target 10 deg off the attitude reads 10 deg; a body at rest in O pointing at
    q_BO = identity reads 0 after 300 s (orbit target followed through the orbit's turn of 18 deg);
    without a target the column is empty."""
    p = Plant(load_scenario("surrey", settings=[f"initial.rate.omega_rad_s=[0, {-N_SEED!r}, 0]",
                                              "dynamics_step_s=0.1", "control.period_s=0.1"]))
    row = dict(zip(adcs_header(p), adcs_row(p), strict=True))
    assert row["pointing_error_deg"] == ""
    p.set_pointing_target(quat_mul(p.q_BN, quat_from_axis_angle((0.3, -1.0, 0.2), math.radians(10.0))))
    assert math.degrees(p.pointing_error_rad()) == pytest.approx(10.0, abs=1e-9)
    p.set_pointing_target((1.0, 0.0, 0.0, 0.0), frame="orbit")
    p.advance_to(300.0)
    row = dict(zip(adcs_header(p), adcs_row(p), strict=True))
    assert row["pointing_error_deg"] < 1e-6
    p.set_pointing_target(p.q_BN)  # inertial target now: the orbit turns away from it
    p.advance_to(400.0)
    assert math.degrees(p.pointing_error_rad()) == pytest.approx(math.degrees(N_SEED * 100.0), rel=1e-6)
    with pytest.raises(ValueError, match="'inertial' or 'orbit'"):
        p.set_pointing_target((1.0, 0.0, 0.0, 0.0), frame="body")


def test_torque_and_wheel_columns():
    """TR-002: tmag = (m + m_res) x b_B from the logged columns; trw = -sum u_i g_i; one
    momentum/speed/torque triple per wheel."""
    p = Plant(load_scenario("surrey"))
    p.apply_dipole_B((0.5, -2.0, 0.25))
    p.set_wheel_torques([1e-4, -2e-3, 0.0])
    p.step()
    row = dict(zip(adcs_header(p), adcs_row(p), strict=True))
    m = tuple(row[f"m_{a}_Am2"] for a in "xyz")
    assert m == (0.5, -1.0, 0.25)  # clipped per axis
    assert tuple(row[f"mcmd_{a}_Am2"] for a in "xyz") == (0.5, -2.0, 0.25)
    b = tuple(row[f"b_{a}_uT"] * 1e-6 for a in "xyz")
    assert tuple(row[f"tmag_{a}_Nm"] for a in "xyz") == pytest.approx(cross(m, b), rel=1e-9)
    assert tuple(row[f"trw_{a}_Nm"] for a in "xyz") == (-1e-4, 1e-3, 0.0)
    assert [row[f"u{i}_Nm"] for i in range(3)] == [1e-4, -1e-3, 0.0]
    assert row["h1_Nms"] == pytest.approx(-1e-3 * 0.01, rel=1e-12)
    assert "h3_Nms" not in row
    assert not any(k.startswith("h0") for k in adcs_header(Plant(load_scenario("default"))))


def test_a_fresh_truth_sample_gives_the_same_row_and_a_stale_one_is_ignored():
    """TR-004: adcs_row takes the orbit-frame attitude, rate and pointing error from a TruthSample of
    the plant's present state (the reports' 1 Hz rows: computed once, not twice) — the same row to
    the bit as computed afresh; a sample of an earlier instant is not used."""
    from detumble.drivers.spacecraft import SimulatedSpacecraft

    craft = SimulatedSpacecraft(load_scenario("surrey"))
    plant = craft.plant
    plant.set_pointing_target((1.0, 0.0, 0.0, 0.0), frame="orbit")
    craft.clock.set_us(craft.clock.current_us + 30_000_000)
    craft.sync()
    sample = craft.truth()
    assert sample.pointing_error_rad is not None
    assert repr(adcs_row(plant, sample=sample)) == repr(adcs_row(plant))
    craft.clock.set_us(craft.clock.current_us + 1_000_000)
    craft.sync()
    assert repr(adcs_row(plant, sample=sample)) == repr(adcs_row(plant))
    assert adcs_row(plant, sample=sample)[4:8] != list(sample.q_BO)


@pytest.mark.parametrize("scenario", ["default", "adcs", "surrey"])
def test_orbit_relative_is_the_two_properties_to_the_bit(scenario):
    """TR-005: Plant.orbit_relative() (what a TruthSample takes: the orbit's position and O's axes
    computed once) gives q_BO and omega_BO_B as the two properties do, bit for bit, along a flight;
    and a TruthSample carries those values."""
    from detumble.drivers.spacecraft import SimulatedSpacecraft

    craft = SimulatedSpacecraft(load_scenario(scenario))
    plant = craft.plant
    for _ in range(12):
        craft.clock.set_us(craft.clock.current_us + 7_130_000)
        craft.sync()
        q_bo, w_bo = plant.orbit_relative()
        assert repr(q_bo) == repr(plant.q_BO)
        assert repr(w_bo) == repr(plant.omega_BO_B)
        sample = craft.truth()
        assert repr((sample.q_BO, sample.omega_BO_B)) == repr((plant.q_BO, plant.omega_BO_B))
