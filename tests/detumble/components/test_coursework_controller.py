"""CourseworkController (seed 004's controllers as an F´ component), through the port harness."""
import math

import pytest

from fprime_lite import CmdResponse, Time

from detumble.components.attitude_types import AngularVelocity
from detumble.components.coursework_controller import CourseworkController, CourseworkLaw, WheelError
from detumble.components.types import (AttitudeQuaternion, MagneticField, OrbitFrame, Result, Success, WheelMode,
                                       WheelState)
from detumble.control import coursework as cw

B_GAUSS = (0.3, -0.1, 0.2)
W = (0.1, -0.2, 0.3)
N = cw.REPORT_MEAN_MOTION


@pytest.fixture
def h(fprime_harness):
    harness = fprime_harness(CourseworkController("controller", base_id=0x10076000))
    harness.load_parameters()
    t = {"us": 1_000_000}

    def field():
        t["us"] += 10_000
        return Result(MagneticField(*B_GAUSS, Time(0, 0, t["us"] // 1_000_000, t["us"] % 1_000_000)), Success.SUCCESS)

    harness.set_port_handler("magneticFieldGet", field)
    harness.set_port_return("angularVelocityGet", Result(AngularVelocity(*W), Success.SUCCESS))
    harness.set_port_return("attitudeGet",
                            Result(AttitudeQuaternion(1.0, 0.0, 0.0, 0.0, True, Time()), Success.SUCCESS))
    harness.set_port_return("orbitFrameGet", Result(OrbitFrame(1.0, 0.0, 0.0, 0.0, N, Time()), Success.SUCCESS))
    harness.set_port_return("wheelStateGet",
                            Result(WheelState(0.0, 0.0, 0.0, WheelMode.TORQUE, Time()), Success.SUCCESS))
    harness.set_port_return("wheelTorqueSet", Success.SUCCESS)
    harness.set_port_return("dipoleSet", Success.SUCCESS)
    return harness


def _dipoles(h):
    return [tuple((c.args[0].x, c.args[0].y, c.args[0].z)) for c in h.from_port("dipoleSet")]


def test_off_by_default_commands_nothing(h):
    """CWC-001: LAW defaults to OFF: a cycle reads no sensor and commands no actuator."""
    h.invoke("run", 0)
    assert h.from_port("magneticFieldGet") == [] and h.from_port("dipoleSet") == []


def test_cross_product_commands_the_law_clipped_per_axis(h):
    """CWC-002: CROSS_PRODUCT commands clip(k (ω × B)) with B in tesla (gauss × 1e-4), each axis to
    ±DIPOLE_LIMIT, and reports it on DipoleCommand; SET_LAW answers OK with LawChanged."""
    h.send_command("SET_LAW", CourseworkLaw.CROSS_PRODUCT)
    h.assert_cmd_response(0, "SET_LAW", CmdResponse.OK)
    h.assert_event("LawChanged", 0, CourseworkLaw.CROSS_PRODUCT)
    h.clear_history()
    h.invoke("run", 0)
    b = tuple(c * 1e-4 for c in B_GAUSS)
    expected = cw.clip_dipole(cw.cross_product_dipole(146.0, W, b))
    assert _dipoles(h)[-1] == pytest.approx(expected, rel=1e-12)
    h.send_command("CROSS_PRODUCT_GAIN_PRM_SET", 1e9)
    h.invoke("run", 0)
    assert all(abs(c) <= 1.0 for c in _dipoles(h)[-1]) and max(abs(c) for c in _dipoles(h)[-1]) == 1.0


def test_beta_pd_first_cycle_primes_then_follows_eqs_20_to_24(h):
    """CWC-003: BETA_PD commands zero on its first cycle (no previous β), then the law's dipole: by
    default (BETA_SWITCHED = true) eq. 23 *or* 24, as the report's equations and figures — with
    |B_x| > |B_z| here, eq. 24 alone, so no spin term on x."""
    h.send_command("SET_LAW", CourseworkLaw.BETA_PD)
    h.invoke("run", 0)
    h.invoke("run", 0)
    first, second = _dipoles(h)[-2:]
    assert first == (0.0, 0.0, 0.0)
    law = cw.BetaPd(990.0, 0.06, switched=True)
    b = tuple(c * 1e-4 for c in B_GAUSS)
    law.dipole(1.01, W, b)
    assert second == pytest.approx(cw.clip_dipole(law.dipole(1.02, W, b)))
    assert second[0] == 0.0 and second[2] != 0.0


def test_beta_switched_false_flies_the_listing_with_both_spin_terms(h):
    """CWC-010: BETA_SWITCHED = false is the report's MATLAB listing (both spin terms at once)."""
    h.send_command("BETA_SWITCHED_PRM_SET", False)
    h.send_command("SET_LAW", CourseworkLaw.BETA_PD)
    h.invoke("run", 0)
    h.invoke("run", 0)
    second = _dipoles(h)[-1]
    law = cw.BetaPd(990.0, 0.06, switched=False)
    b = tuple(c * 1e-4 for c in B_GAUSS)
    law.dipole(1.01, W, b)
    assert second == pytest.approx(cw.clip_dipole(law.dipole(1.02, W, b)))
    assert second[0] != 0.0 and second[2] != 0.0


def test_wheels_pd_commands_eq26_torques_within_the_limits(h):
    """CWC-004: WHEELS_PD sends each wheel eq. 26's torque for q_BO = q_ON⁻¹ ⊗ q_BN, limited to
    WHEEL_TORQUE_LIMIT, and no dipole."""
    h.send_command("SET_LAW", CourseworkLaw.WHEELS_PD)
    h.clear_history()
    h.invoke("run", 0)
    torques = [c.args[0] for c in h.from_port("wheelTorqueSet")]
    law = cw.WheelsPd(5.0, 9.0, ((1.67e-3, 0, 0), (0, 1.67e-3, 0), (0, 0, 1.67e-3)), (0, 0, 0, 1), n=N,
                      shortest_path=True)
    expected = cw.limit_wheel_torque(law.torque((0, 0, 0, 1), W, (0, 0, 0)), (0, 0, 0))
    assert torques == pytest.approx(list(expected), rel=1e-12)
    assert all(abs(u) <= 1e-3 for u in torques)
    assert h.from_port("dipoleSet") == []


def test_set_target_refuses_a_non_unit_quaternion(h):
    """CWC-005: SET_TARGET takes a unit quaternion (OK, TargetSet) and refuses anything else with
    VALIDATION_ERROR and TargetRejected, keeping the old target."""
    h.send_command("SET_TARGET", 0.0, 1.0, 0.0, 0.0)
    h.assert_cmd_response(0, "SET_TARGET", CmdResponse.OK)
    h.assert_event("TargetSet", 0, 0.0, 1.0, 0.0, 0.0)
    for bad in ((0.0, 0.0, 0.0, 0.0), (1.0, 1.0, 0.0, 0.0), (math.nan, 0.0, 0.0, 1.0)):
        h.send_command("SET_TARGET", *bad)
    assert [r.response for r in h.cmd_responses[1:]] == [CmdResponse.VALIDATION_ERROR] * 3
    h.assert_event_count("TargetRejected", 3)


def test_a_failed_read_puts_the_actuators_safe_and_tells_the_ground(h):
    """CWC-006: a magnetometer read that fails sets rods and wheels to zero and raises
    SensorReadFailed (WARNING_HI, throttled); the next good cycle commands again."""
    h.send_command("SET_LAW", CourseworkLaw.CROSS_PRODUCT)
    h.set_port_return("magneticFieldGet", Result(None, Success.FAILURE))
    h.clear_history()
    h.invoke("run", 0)
    assert _dipoles(h) == [(0.0, 0.0, 0.0)]
    assert [c.args[0] for c in h.from_port("wheelTorqueSet")] == [0.0, 0.0, 0.0]
    h.assert_event("SensorReadFailed", 0, "magnetometer")


def test_a_fault_inside_the_cycle_is_an_event_not_silence(h):
    """CWC-007: a non-finite result (a gyro reading of NaN) never reaches the rods: actuators safe
    and a ControlFault event; the rate group sees no exception."""
    h.send_command("SET_LAW", CourseworkLaw.CROSS_PRODUCT)
    h.set_port_return("angularVelocityGet", Result(AngularVelocity(math.nan, 0.0, 0.0), Success.SUCCESS))
    h.clear_history()
    h.invoke("run", 0)
    assert _dipoles(h) == [(0.0, 0.0, 0.0)]
    assert h.events_named("ControlFault")


def test_wheel_error_defaults_to_the_shortest_path_and_report_is_the_named_option(h):
    """CWC-008: by default (WHEEL_ERROR = SHORTEST_PATH) the proportional term turns the body toward
    the target the short way — the torque about x opposes a positive rotation about x; WHEEL_ERROR
    = REPORT (eq. 25 as written) flips it, pushing away from the target (the long way round)."""
    h.set_port_return("angularVelocityGet", Result(AngularVelocity(0.0, 0.0, 0.0), Success.SUCCESS))
    h.set_port_return("attitudeGet", Result(AttitudeQuaternion(math.cos(0.1), math.sin(0.1), 0.0, 0.0, True, Time()),
                                            Success.SUCCESS))
    h.send_command("SET_LAW", CourseworkLaw.WHEELS_PD)
    h.clear_history()
    h.invoke("run", 0)
    shortest = [c.args[0] for c in h.from_port("wheelTorqueSet")]
    h.send_command("WHEEL_ERROR_PRM_SET", WheelError.REPORT)
    h.clear_history()
    h.invoke("run", 0)
    report = [c.args[0] for c in h.from_port("wheelTorqueSet")]
    assert report[0] == pytest.approx(-shortest[0]) and report[0] != 0.0
    # T is the torque the wheels take from the body: the body feels −T, toward the target when T_x > 0
    assert shortest[0] > 0.0


def test_momentum_dumping_commands_the_rods_across_the_field(h):
    """CWC-009: with DUMP_GAIN > 0 the wheel law also commands M = k (h × B)/|B|² (clipped), whose
    torque M × B opposes the wheels' momentum across the field; DUMP_GAIN = 0 commands no dipole."""
    h.set_port_return("wheelStateGet", Result(WheelState(0.0, 2e-3, 0.0, WheelMode.TORQUE, Time()), Success.SUCCESS))
    h.send_command("SET_LAW", CourseworkLaw.WHEELS_PD)
    h.send_command("DUMP_GAIN_PRM_SET", 0.01)
    h.clear_history()
    h.invoke("run", 0)
    b = tuple(c * 1e-4 for c in B_GAUSS)
    m = _dipoles(h)[-1]
    assert m == pytest.approx(cw.dumping_dipole(0.01, (2e-3, 2e-3, 2e-3), b), rel=1e-12)
    tau = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
    assert sum(t * 2e-3 for t in tau) < 0.0


def test_the_fused_conjugate_product_gives_the_floats_of_conjugating_then_multiplying():
    """q_BO = conj(q_ON) ⊗ q_BN in one step: bit for bit the product of the conjugate, over random
    unit and non-unit quaternions (negating is exact and a - (-b) rounds as a + b)."""
    import random

    from detumble.components.coursework_controller import _quat_conj_mul

    def mul(p, q):
        return (p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
                p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
                p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
                p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0])

    rng = random.Random(19)
    for _ in range(2000):
        p = tuple(rng.uniform(-2.0, 2.0) for _ in range(4))
        q = tuple(rng.uniform(-2.0, 2.0) for _ in range(4))
        assert _quat_conj_mul(p, q) == mul((p[0], -p[1], -p[2], -p[3]), q)


def test_the_scalar_last_conjugate_product_is_the_product_then_the_reordering():
    """q_BO built straight in the report's scalar-last order (what the wheel cycle hands its law) is
    bit for bit from_plant_quaternion(_quat_conj_mul(q_ON, q_BN)), signed zeros included."""
    import random

    from detumble.components.coursework_controller import _quat_conj_mul, _quat_conj_mul_scalar_last

    rng = random.Random(20)
    values = (0.0, -0.0, 1.0, -1.0, 0.5)
    for _ in range(4000):
        p = tuple(rng.choice(values) if rng.random() < 0.3 else rng.uniform(-2.0, 2.0) for _ in range(4))
        q = tuple(rng.choice(values) if rng.random() < 0.3 else rng.uniform(-2.0, 2.0) for _ in range(4))
        got = _quat_conj_mul_scalar_last(p, q)
        want = cw.from_plant_quaternion(_quat_conj_mul(p, q))
        assert got == want
        assert all(math.copysign(1.0, a) == math.copysign(1.0, b) for a, b in zip(got, want, strict=True))
