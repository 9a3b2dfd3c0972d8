"""The coursework's simulated torque-rod driver and orbit ephemeris, through the port harness."""
import math

import pytest

from fprime_lite import CmdResponse
from fprime_lite.model.time import SimulatedClock

from detumble.components.types import DipoleMoment, Success
from detumble.sim.vec import quat_mul, quat_conj
from detumble.drivers.orbit_ephemeris import OrbitEphemeris
from detumble.drivers.spacecraft import SimulatedSpacecraft
from detumble.drivers.torque_rod_driver import TorqueRodDriver


@pytest.fixture
def spacecraft():
    return SimulatedSpacecraft("surrey", clock=SimulatedClock())


def test_rods_apply_the_dipole_limit_it_and_report_it(fprime_harness, spacecraft):
    """ROD-001: dipoleSet applies the dipole to the plant (each axis limited to ±1 A·m²), the
    Dipole channel shows what the rods give, a limited request raises DipoleLimited."""
    h = fprime_harness(TorqueRodDriver("torqueRods", spacecraft, base_id=0x10072000))
    assert h.invoke("dipoleSet", DipoleMoment(0.2, -0.3, 0.4)) == Success.SUCCESS
    assert spacecraft.plant.m_coils_B == pytest.approx((0.2, -0.3, 0.4))
    assert h.invoke("dipoleSet", DipoleMoment(2.0, -0.3, -5.0)) == Success.SUCCESS
    assert spacecraft.plant.m_coils_B == pytest.approx((1.0, -0.3, -1.0))
    h.assert_event("DipoleLimited", 0, 2.0, -0.3, -5.0)
    last = h.tlm_values("Dipole")[-1]
    assert (last.x, last.y, last.z) == pytest.approx((1.0, -0.3, -1.0))


def test_rods_turn_off_for_a_non_finite_request_and_on_stop(fprime_harness, spacecraft):
    """ROD-002: a NaN request answers FAILURE, turns the rods off and raises InvalidDipole; STOP
    turns them off with RodsStopped."""
    h = fprime_harness(TorqueRodDriver("torqueRods", spacecraft, base_id=0x10072000))
    h.invoke("dipoleSet", DipoleMoment(0.5, 0.5, 0.5))
    assert h.invoke("dipoleSet", DipoleMoment(math.nan, 0.0, 0.0)) == Success.FAILURE
    assert spacecraft.plant.m_coils_B == (0.0, 0.0, 0.0)
    assert h.events_named("InvalidDipole")
    h.invoke("dipoleSet", DipoleMoment(0.5, 0.5, 0.5))
    h.send_command("STOP")
    h.assert_cmd_response(0, "STOP", CmdResponse.OK)
    assert spacecraft.plant.m_coils_B == (0.0, 0.0, 0.0)
    h.assert_event_count("RodsStopped", 1)


def test_rods_refuse_a_spacecraft_with_coils():
    """ROD-003: the driver names what to change when the scenario has coils, not rods."""
    with pytest.raises(ValueError, match="actuators.type: rods"):
        TorqueRodDriver("torqueRods", SimulatedSpacecraft("default", clock=SimulatedClock()))


def test_ephemeris_gives_the_orbit_frame_the_plant_uses(fprime_harness, spacecraft):
    """EPH-001: orbitFrameGet answers q_ON and n such that q_ON⁻¹ ⊗ q_BN is the plant's q_BO
    (to 1e-12) and n is the orbit's mean motion."""
    h = fprime_harness(OrbitEphemeris("orbitEphemeris", spacecraft, base_id=0x10071000))
    value, condition = h.invoke("orbitFrameGet")
    assert condition == Success.SUCCESS and value.n == spacecraft.plant.orbit.mean_motion
    q_bo = quat_mul(quat_conj((value.q0, value.q1, value.q2, value.q3)), spacecraft.plant.q_BN)
    sign = 1.0 if q_bo[0] >= 0 else -1.0
    assert tuple(sign * c for c in q_bo) == pytest.approx(spacecraft.plant.q_BO, abs=1e-12)


def test_the_read_ports_return_real_result_named_tuples(fprime_harness, spacecraft):
    """EPH-101: orbitFrameGet, the wheels' wheelStateGet, the star tracker's attitudeGet and the IMU
    manager's angularVelocityGet and magneticFieldGet build their answers with tuple.__new__ (no
    Python frame): each is a Result — its type, fields, equality and ``ok`` as Result(value,
    condition) gives them."""
    from detumble.components.types import Result
    from detumble.drivers.reaction_wheel_driver import ReactionWheelDriver
    from detumble.drivers.star_tracker import StarTracker
    from detumble.proves.imu_manager import ImuManager

    imu = fprime_harness(ImuManager("imuManager", spacecraft))
    answers = [fprime_harness(OrbitEphemeris("orbitEphemeris", spacecraft)).invoke("orbitFrameGet"),
               fprime_harness(ReactionWheelDriver("reactionWheel1", spacecraft, 1)).invoke("wheelStateGet"),
               fprime_harness(StarTracker("starTracker", spacecraft)).invoke("attitudeGet"),
               imu.invoke("angularVelocityGet"), imu.invoke("magneticFieldGet")]
    for answer in answers:
        assert type(answer) is Result and answer.ok and answer.condition == Success.SUCCESS
        assert answer == Result(answer.value, Success.SUCCESS) and answer._fields == ("value", "condition")
        value, condition = answer
        assert value is answer.value and condition is Success.SUCCESS
