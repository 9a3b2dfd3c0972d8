"""AttitudeController through its ports: commands, events, mode transitions, actuation
(docs/components/attitude_controller.md, requirements ADCS-020…ADCS-040).

Time is the harness's test time; ``tick`` runs the component once and advances 20 ms (the 50 Hz rate
group), so one control cycle is 5 ticks (100 ms). Rates rad/s in the stubs (deg/s in parameters),
field gauss, dipole A·m², torque N·m, momentum N·m·s.
"""

import math

import pytest

from detumble.components.attitude_controller import AttitudeController
from detumble.components.attitude_types import (ControlAutonomy, ControlMode, MagPointingLaw, MagResidualMode,
                                                ModeChangeReason, PointingActuator, SpinLaw)
from detumble.components.types import (AttitudeQuaternion, DipoleMoment, MagneticField, Result, Success, SystemMode,
                                       WheelMode, WheelState)
from detumble.control.magnetic import project_dipole_weighted
from detumble.control.magnetic_pointing import field_steering_torque
from detumble.control.pointing import pd_torque
from detumble.control.quaternion import quat_from_axis_angle, quat_mul, rotate_b_to_n, rotate_n_to_b
from fprime_lite import CmdResponse, Time, TimeBase

BASE = 0x10070000
TICK_US = 20_000
START = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1000, 0)
STARTS = [f"{c}Start" for c in ("xPlus", "xMinus", "yPlus", "yMinus", "zMinus")]
STOPS = [f"{c}Stop" for c in ("xPlus", "xMinus", "yPlus", "yMinus", "zMinus")]
DEG = math.pi / 180


class World:
    """Stub sensors and wheels: what the controller reads is whatever the test puts here."""

    def __init__(self, h):
        self.h = h
        self.omega = (0.0, 0.0, 0.0)  # rad/s
        self.gyro_ok = True
        self.q = (1.0, 0.0, 0.0, 0.0)
        self.tracker_valid = True
        self.tracker_ok = True
        self.b = (0.2, -0.1, 0.35)  # gauss
        self.mag_ok = True
        self.momenta = [0.0, 0.0, 0.0]
        self.torques = [[], [], []]
        self.enabled = [[], [], []]
        self.dipole = None  # Result of dipoleMomentGet
        self._t_us = None
        self.sun = (0.0, 0.0, 1.0)  # the Sun vector in B the light sensors report
        self.sun_valid = True
        self.sun_stamp = None  # Time of the reading (None: now)
        self.system_mode = SystemMode.NORMAL

    def sun_vector(self):
        from detumble.components.attitude_types import SunVector
        x, y, z = self.sun
        stamp = self.sun_stamp if self.sun_stamp is not None else self.h.test_time
        return Result(SunVector(x, y, z, self.sun_valid, 1, stamp), Success.SUCCESS)

    def gyro(self):
        from detumble.components.attitude_types import AngularVelocity
        x, y, z = self.omega
        return Result(AngularVelocity(x=x, y=y, z=z), Success.SUCCESS if self.gyro_ok else Success.FAILURE)

    def tracker(self):
        """The attitude, kept consistent with the gyro: ``q`` is turned by ω over the time since the last read."""
        t = self.h.test_time.total_us
        if self._t_us is not None and t > self._t_us:
            w = self.omega
            n = math.sqrt(sum(c * c for c in w))
            if n > 0.0:
                self.q = quat_mul(self.q, quat_from_axis_angle(w, n * (t - self._t_us) / 1e6))
        self._t_us = t
        q = self.q
        return Result(AttitudeQuaternion(q0=q[0], q1=q[1], q2=q[2], q3=q[3], valid=self.tracker_valid,
                                         timestamp=self.h.test_time),
                      Success.SUCCESS if self.tracker_ok else Success.FAILURE)

    def field(self):
        x, y, z = self.b
        return Result(MagneticField(x=x, y=y, z=z, timestamp=self.h.test_time),
                      Success.SUCCESS if self.mag_ok else Success.FAILURE)

    def wheel_state(self, i):
        return lambda: Result(WheelState(speed=0.0, momentum=self.momenta[i], torque=0.0, mode=WheelMode.TORQUE,
                                         timestamp=self.h.test_time), Success.SUCCESS)

    def wheel_torque(self, i):
        def set_torque(torque):
            self.torques[i].append(torque)
            return Success.SUCCESS
        return set_torque

    def wheel_enable(self, i):
        def enable(on):
            self.enabled[i].append(on)
            return Success.SUCCESS
        return enable


# The coils' field-steering hold on the raw reading (MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0: the default before
# 2026-12-05): the tests of that law and of the coils' other modes; this harness gives no ephemeris for the on-board
# field model the default hold needs (its tests: tests/detumble/control/test_three_mode_field_model.py).
FIELD_STEERING_HOLD = {"MAG_BIAS_TIME": 0.0, "MAG_LQR_ANGLE": 0.0}


def make(fprime_harness, *, wheels=True, bdot_provider=False, params=None, sun=False, system_mode=False):
    comp = AttitudeController("attitudeController", base_id=BASE)
    h = fprime_harness(comp, test_time=START)
    world = World(h)
    for port in STARTS + STOPS:
        h.set_port_return(port, Success.SUCCESS)
    h.set_port_handler("angularVelocityGet", world.gyro)
    h.set_port_handler("attitudeGet", world.tracker)
    h.set_port_handler("magneticFieldGet", world.field)
    if sun:  # the ADCS light sensors' Sun vector: World.sun (B), its validity and read time
        h.set_port_handler("sunVectorGet", world.sun_vector)
    else:
        comp.output_port("sunVectorGet").disconnect(0)
    if system_mode:  # the ModeManager's mode: World.system_mode
        h.set_port_handler("getSystemMode", lambda: world.system_mode)
    else:
        comp.output_port("getSystemMode").disconnect(0)
    if bdot_provider:
        h.set_port_handler("dipoleMomentGet", lambda: world.dipole)
    else:
        comp.output_port("dipoleMomentGet").disconnect(0)
    for i in range(4):
        if wheels and i < 3:
            h.set_port_handler("wheelStateGet", world.wheel_state(i), index=i)
            h.set_port_handler("wheelTorqueSet", world.wheel_torque(i), index=i)
            h.set_port_handler("wheelEnableSet", world.wheel_enable(i), index=i)
        else:
            for port in ("wheelStateGet", "wheelTorqueSet", "wheelEnableSet"):
                comp.output_port(port).disconnect(i)
    for name, value in (params or {}).items():
        h.param_set(name, value)
    h.load_parameters()
    h.world = world
    h.comp = comp
    return h


def tick(h, n=1):
    for _ in range(n):
        h.invoke("run", 0)
        h.advance_time(useconds=TICK_US)


def seconds(h, s):
    tick(h, int(round(s / 0.02)))


def levels(h):
    """The latest drive level sent to each of X+, X−, Y+, Y−, Z−."""
    return tuple(h.from_port(p)[-1].args[0] for p in STARTS)


def modes(h):
    return [(e.args[0], e.args[1], e.args[2]) for e in h.events if e.name == "ControlModeChanged"]


def auto(h):
    h.send_command("SET_AUTO")
    h.assert_cmd_response(0, "SET_AUTO", CmdResponse.OK)


# --- start-up and the cycle ---------------------------------------------------------------------------

def test_starts_idle_and_manual_and_drives_nothing(fprime_harness):
    """ADCS-020: until commanded the controller is IDLE/MANUAL: no coil is driven, the wheels get zero torque,
    and Mode/Autonomy are telemetered every cycle."""
    h = make(fprime_harness)
    h.world.omega = (0.5, 0.0, 0.0)
    seconds(h, 1.0)
    assert h.from_port(STARTS[0]) == []
    assert all(t == 0.0 for wheel in h.world.torques for t in wheel)
    assert h.tlm_values("Mode")[-1] == ControlMode.IDLE
    assert h.tlm_values("Autonomy")[-1] == ControlAutonomy.MANUAL
    assert len(h.tlm_values("Mode")) == 10  # 10 Hz


def test_auto_starts_in_detumble_and_coils_are_off_on_the_last_tick_of_each_cycle(fprime_harness):
    """ADCS-021: SET_AUTO logs AutonomyChanged; the next cycle enters DETUMBLE (AUTO_START, the seed's
    "mission start"); coils are driven on tick 0 of each 5-tick cycle and stopped on tick 4, so the next
    magnetometer read is taken with the coils off."""
    h = make(fprime_harness)
    h.world.omega = (0.6, 0.0, 0.0)  # 34 deg/s
    auto(h)
    h.assert_event("AutonomyChanged", 0, ControlAutonomy.AUTO)
    tick(h)
    assert modes(h) == [(ControlMode.IDLE, ControlMode.DETUMBLE, ModeChangeReason.AUTO_START)]
    h.clear_history()
    h.world.b = (0.25, -0.1, 0.35)  # changes between cycles: B-dot has a derivative
    tick(h, 4)  # ticks 1-4 of the priming cycle: nothing driven, nothing to stop
    assert h.from_port("xPlusStart") == [] and h.from_port("xPlusStop") == []
    tick(h, 4)  # tick 0 of the next cycle drives, ticks 1-3 hold
    assert len(h.from_port("xPlusStart")) == 1 and h.from_port("xPlusStop") == []
    tick(h)  # tick 4: coils off
    assert len(h.from_port("xPlusStop")) == 1


def test_detumble_internal_bdot_uses_the_measured_spacing_and_drives_the_coils(fprime_harness):
    """ADCS-022: without a dipoleMomentGet provider, M = −K_BDOT (B_n − B_{n−1})/Δt with Δt the readings'
    own time stamps (0.1 s here); X and Y split the dipole over their two coils, X−/Y−/Z− drive negated."""
    h = make(fprime_harness)
    h.world.omega = (0.6, 0.0, 0.0)
    auto(h)
    tick(h, 5)  # first DETUMBLE cycle primes B
    h.world.b = (0.2 + 0.001, -0.1 - 0.002, 0.35 + 0.0001)  # ΔB over 0.1 s
    tick(h)
    m = tuple(-3.0 * d / 0.1 for d in (0.001, -0.002, 0.0001))
    cx = h.comp.X_COIL_MAX_DIPOLE.value
    cz = h.comp.Z_COIL_MAX_DIPOLE.value
    lx = round(0.5 * m[0] / cx * 127)
    ly = round(0.5 * m[1] / cx * 127)
    lz = round(m[2] / cz * 127)
    assert levels(h) == (lx, -lx, ly, -ly, -lz)
    assert h.tlm_values("CommandedDipole")[-1][0] == pytest.approx(2 * lx / 127 * cx)


def test_detumble_takes_the_bdot_provider_dipole_when_connected(fprime_harness):
    """ADCS-022: with BDotDetumble's dipoleMomentGet connected its dipole is flown (limits applied); its
    first (priming) failure is silent, a later failure logs DipoleMomentRetrievalFailed and stops the coils."""
    h = make(fprime_harness, bdot_provider=True)
    h.world.omega = (0.6, 0.0, 0.0)
    h.world.dipole = Result(DipoleMoment(x=0.0, y=0.0, z=0.0), Success.FAILURE)
    auto(h)
    tick(h, 5)
    h.assert_no_event("DipoleMomentRetrievalFailed")
    h.world.dipole = Result(DipoleMoment(x=0.05, y=-0.02, z=0.004), Success.SUCCESS)
    tick(h)
    cx, cz = h.comp.X_COIL_MAX_DIPOLE.value, h.comp.Z_COIL_MAX_DIPOLE.value
    assert levels(h) == (round(0.025 / cx * 127), -round(0.025 / cx * 127), round(-0.01 / cx * 127),
                         -round(-0.01 / cx * 127), -round(0.004 / cz * 127))
    tick(h, 4)
    h.world.dipole = Result(DipoleMoment(x=0.0, y=0.0, z=0.0), Success.FAILURE)
    tick(h)
    h.assert_event_count("DipoleMomentRetrievalFailed", 1)
    assert not h.comp.law.coils_driven


# --- AUTO transitions ---------------------------------------------------------------------------------

def test_detumble_exits_only_below_the_exit_rate_for_the_dwell(fprime_harness):
    """ADCS-023: DETUMBLE is left for SPIN_STABLE (RATE_LOW) only after |ω| < DETUMBLE_EXIT_RATE (1 °/s) for
    MODE_DWELL (5 s); 15 °/s (inside the 1…20 hysteresis band) keeps DETUMBLE, and a rate back above the exit
    threshold restarts the dwell."""
    h = make(fprime_harness)
    h.world.tracker_valid = False  # rates only; the filter then passes the gyro through
    h.world.omega = (15 * DEG, 0.0, 0.0)
    auto(h)
    seconds(h, 20)
    assert h.comp.mode == ControlMode.DETUMBLE
    h.world.omega = (0.8 * DEG, 0.0, 0.0)
    seconds(h, 4)
    h.world.omega = (1.1 * DEG, 0.0, 0.0)
    seconds(h, 0.2)
    h.world.omega = (0.8 * DEG, 0.0, 0.0)
    seconds(h, 4.8)
    assert h.comp.mode == ControlMode.DETUMBLE  # the dwell restarted
    seconds(h, 0.4)
    assert h.comp.mode == ControlMode.SPIN_STABLE
    assert modes(h)[-1] == (ControlMode.DETUMBLE, ControlMode.SPIN_STABLE, ModeChangeReason.RATE_LOW)


def test_high_rate_returns_to_detumble(fprime_harness):
    """ADCS-024: from SPIN_STABLE (and from POINTING) |ω| > DETUMBLE_ENTER_RATE (20 °/s) goes to DETUMBLE
    (RATE_HIGH); 19 °/s does not."""
    h = make(fprime_harness)
    h.send_command("FORCE_MODE", ControlMode.SPIN_STABLE)
    h.send_command("SET_AUTO")
    h.world.omega = (0.0, 19 * DEG, 0.0)
    seconds(h, 2)
    assert h.comp.mode == ControlMode.SPIN_STABLE
    h.world.omega = (0.0, 21 * DEG, 0.0)
    tick(h, 10)  # the cycle's rate is the mean of its five ticks
    assert modes(h)[-1] == (ControlMode.SPIN_STABLE, ControlMode.DETUMBLE, ModeChangeReason.RATE_HIGH)
    h.world.omega = (0.0, 0.0, 0.0)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.send_command("SET_AUTO")
    h.world.omega = (0.0, 21 * DEG, 0.0)
    tick(h, 10)
    assert modes(h)[-1] == (ControlMode.POINTING, ControlMode.DETUMBLE, ModeChangeReason.RATE_HIGH)


def spinning_auto(fprime_harness, **kw):
    h = make(fprime_harness, **kw)
    h.send_command("FORCE_MODE", ControlMode.SPIN_STABLE)
    h.send_command("SET_AUTO")
    return h


def test_stable_spin_leads_to_pointing_with_hysteresis(fprime_harness):
    """ADCS-025: SPIN_STABLE → POINTING (SPIN_STABLE_REACHED) after SPIN_STABLE_DWELL (60 s) with the rate
    within 5° of +Z and within 5 % of SPIN_RATE_TARGET; an excursion between the enter and reset thresholds
    (6°) pauses the timer, one beyond the reset threshold (9°) restarts it."""
    h = spinning_auto(fprime_harness)
    w = h.comp.SPIN_RATE_TARGET.value * DEG

    def tilt(deg):
        h.world.omega = (w * math.sin(deg * DEG), 0.0, w * math.cos(deg * DEG))

    tilt(2.0)
    seconds(h, 40)
    tilt(6.0)  # inside the hysteresis band: timer holds
    seconds(h, 10)
    tilt(2.0)
    seconds(h, 19)
    assert h.comp.mode == ControlMode.SPIN_STABLE
    seconds(h, 1.2)
    assert h.comp.mode == ControlMode.POINTING
    assert modes(h)[-1] == (ControlMode.SPIN_STABLE, ControlMode.POINTING, ModeChangeReason.SPIN_STABLE_REACHED)
    # with no target commanded, POINTING holds the attitude it had on entry
    h.assert_event_count("TargetSet", 1)

    h2 = spinning_auto(fprime_harness)
    h = h2
    tilt(2.0)
    seconds(h, 40)
    tilt(9.0)  # beyond the reset threshold: timer restarts
    seconds(h, 0.2)
    tilt(2.0)
    seconds(h, 59)
    assert h.comp.mode == ControlMode.SPIN_STABLE
    seconds(h, 1.2)
    assert h.comp.mode == ControlMode.POINTING


def test_rate_error_also_qualifies_the_spin(fprime_harness):
    """ADCS-025: a spin on +Z 10 % off SPIN_RATE_TARGET never qualifies for POINTING."""
    h = spinning_auto(fprime_harness)
    h.world.omega = (0.0, 0.0, 1.10 * h.comp.SPIN_RATE_TARGET.value * DEG)
    seconds(h, 120)
    assert h.comp.mode == ControlMode.SPIN_STABLE


def test_no_attitude_knowledge_keeps_spin_stable_with_a_throttled_event(fprime_harness):
    """ADCS-026: a stable spin without star-tracker solutions stays in SPIN_STABLE; NoAttitudeKnowledge is
    logged at most 5 times (throttled)."""
    h = spinning_auto(fprime_harness)
    h.world.tracker_valid = False
    h.world.omega = (0.0, 0.0, h.comp.SPIN_RATE_TARGET.value * DEG)
    seconds(h, 100)
    assert h.comp.mode == ControlMode.SPIN_STABLE
    h.assert_event_count("NoAttitudeKnowledge", 5)
    assert h.tlm_values("AttitudeValid")[-1] == 0


def pointing_then_tracker_lost(fprime_harness, autonomy, **kw):
    """POINTING (forced, then ``autonomy`` if given) for 1 s, then no star-tracker solution for 90.2 s: it is
    still POINTING at 89.9 s (ATTITUDE_TIMEOUT 90 s)."""
    h = make(fprime_harness, **kw)
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    if autonomy:
        h.send_command(autonomy)
    seconds(h, 1)
    h.world.tracker_valid = False
    seconds(h, 89.9)
    assert h.comp.mode == ControlMode.POINTING
    seconds(h, 0.3)
    return h


def test_attitude_loss_while_pointing_falls_back_to_spin_stable(fprime_harness):
    """ADCS-027: in POINTING, no new star-tracker solution for ATTITUDE_TIMEOUT (90 s on the gyro alone) logs
    AttitudeKnowledgeLost (WARNING_HI) and returns to SPIN_STABLE (ATTITUDE_LOST), in AUTO and in MANUAL."""
    for autonomy in ("SET_AUTO", None):
        h = pointing_then_tracker_lost(fprime_harness, autonomy)
        assert h.comp.mode == ControlMode.SPIN_STABLE
        h.assert_event_count("AttitudeKnowledgeLost", 1)
        assert modes(h)[-1][2] == ModeChangeReason.ATTITUDE_LOST


# --- commands -----------------------------------------------------------------------------------------

@pytest.mark.parametrize("mode", list(ControlMode))
def test_force_mode_sets_manual_and_holds(fprime_harness, mode):
    """ADCS-028: FORCE_MODE puts any mode (POINTING when attitude is known) and MANUAL autonomy, answers OK,
    logs ControlModeChanged(COMMAND) when the mode changes, and the triggers no longer act (35 °/s stays)."""
    h = make(fprime_harness, sun=True)
    tick(h)
    h.send_command("SET_AUTO")
    h.send_command("FORCE_MODE", mode)
    h.assert_cmd_response(1, "FORCE_MODE", CmdResponse.OK)
    assert h.comp.autonomy == ControlAutonomy.MANUAL and h.comp.mode == mode
    if mode != ControlMode.IDLE:
        assert modes(h)[-1] == (ControlMode.IDLE, mode, ModeChangeReason.COMMAND)
    h.world.omega = (35 * DEG, 0.0, 0.0)
    seconds(h, 1)
    assert h.comp.mode == mode or (mode == ControlMode.POINTING and h.comp.mode == ControlMode.SPIN_STABLE)


def test_force_pointing_is_refused_without_attitude_or_wheels(fprime_harness):
    """ADCS-028: FORCE_MODE POINTING answers EXECUTION_ERROR with NoAttitudeKnowledge before any star-tracker
    solution; with POINTING_ACTUATOR = WHEELS and no wheel it answers EXECUTION_ERROR with
    ModeUnavailableNoWheels(POINTING); the mode is unchanged both times."""
    h = make(fprime_harness)
    h.world.tracker_valid = False
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.EXECUTION_ERROR)
    h.assert_event_count("NoAttitudeKnowledge", 1)
    assert h.comp.mode == ControlMode.IDLE
    h = make(fprime_harness, wheels=False, params={"POINTING_ACTUATOR": PointingActuator.WHEELS})
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.EXECUTION_ERROR)
    h.assert_event("ModeUnavailableNoWheels", 0, ControlMode.POINTING)
    assert h.comp.mode == ControlMode.IDLE


def test_set_target_quaternion(fprime_harness):
    """ADCS-029: a unit target is accepted (OK, TargetSet, TargetQuaternion channel, stored with q0 ≥ 0); a
    non-unit one is refused with VALIDATION_ERROR and TargetNotUnitQuaternion(q, norm), at most 5 events,
    and the stored target does not change."""
    h = make(fprime_harness)
    h.send_command("SET_TARGET_QUATERNION", -0.7071068, 0.0, -0.7071068, 0.0)
    h.assert_cmd_response(0, "SET_TARGET_QUATERNION", CmdResponse.OK)
    assert h.comp.target == pytest.approx((0.70710678, 0.0, 0.70710678, 0.0))
    h.assert_event_count("TargetSet", 1)
    assert h.tlm_values("TargetQuaternion")[-1].q0 == pytest.approx(0.70710678)
    for k in range(7):
        h.send_command("SET_TARGET_QUATERNION", 0.5, 0.0, 0.0, 0.0)
        h.assert_cmd_response(1 + k, "SET_TARGET_QUATERNION", CmdResponse.VALIDATION_ERROR)
    h.assert_event_count("TargetNotUnitQuaternion", 5)
    assert h.events_named("TargetNotUnitQuaternion")[0][-1] == pytest.approx(0.5)
    h.send_command("SET_TARGET_QUATERNION", float("nan"), 0.0, 0.0, 1.0)
    h.assert_cmd_response(8, "SET_TARGET_QUATERNION", CmdResponse.VALIDATION_ERROR)
    assert h.comp.target == pytest.approx((0.70710678, 0.0, 0.70710678, 0.0))


def test_set_target_direction(fprime_harness):
    """ADCS-030: SET_TARGET_DIRECTION points body +Z along the inertial direction (1e-9 rad); a zero vector is
    refused (VALIDATION_ERROR, TargetDirectionInvalid) and so is a direction before attitude is known
    (EXECUTION_ERROR, NoAttitudeKnowledge)."""
    h = make(fprime_harness)
    h.world.tracker_valid = False
    tick(h)
    h.send_command("SET_TARGET_DIRECTION", 1.0, 0.0, 0.0)
    h.assert_cmd_response(0, "SET_TARGET_DIRECTION", CmdResponse.EXECUTION_ERROR)
    h.assert_event_count("NoAttitudeKnowledge", 1)
    h.world.tracker_valid = True
    h.world.q = quat_from_axis_angle((0.3, 0.2, 1.0), 0.8)
    tick(h, 5)
    h.send_command("SET_TARGET_DIRECTION", 0.0, 0.0, 0.0)
    h.assert_cmd_response(1, "SET_TARGET_DIRECTION", CmdResponse.VALIDATION_ERROR)
    h.assert_event("TargetDirectionInvalid", 0, 0.0, 0.0, 0.0)
    h.send_command("SET_TARGET_DIRECTION", 2.0, -1.0, 0.5)
    h.assert_cmd_response(2, "SET_TARGET_DIRECTION", CmdResponse.OK)
    z_n = rotate_b_to_n(h.comp.target, (0.0, 0.0, 1.0))
    d = (2.0, -1.0, 0.5)
    n = math.sqrt(sum(c * c for c in d))
    assert math.acos(min(1.0, sum(a * b / n for a, b in zip(z_n, d, strict=True)))) < 1e-6


# --- actuation ----------------------------------------------------------------------------------------

def pointing(fprime_harness, q=(1.0, 0.0, 0.0, 0.0), **kw):
    h = make(fprime_harness, **kw)
    h.world.q = q  # the filter starts on this fix
    tick(h, 5)
    h.send_command("SET_TARGET_QUATERNION", 1.0, 0.0, 0.0, 0.0)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.clear_history()
    return h


def test_pointing_on_wheels_applies_the_pd_torque_and_dumps_momentum(fprime_harness):
    """ADCS-031: in POINTING with wheels, an attitude +0.1 rad about x from the target and no rate requests
    τ = −K_p q_err.v (RequestedTorque); the wheels get u = −(τ − τ_mag) (body receives −u); with wheel momentum
    h the dipole's torque opposes h (magnetic dumping, K_DUMP); PointingError ≈ 5.73°."""
    h = pointing(fprime_harness, q=quat_from_axis_angle((1.0, 0.0, 0.0), 0.1))
    h.world.momenta = [1e-3, 0.0, 0.0]
    tick(h, 5)
    kp = h.comp.K_P.value
    tau = h.tlm_values("RequestedTorque")[-1]
    assert tau[0] == pytest.approx(-kp * math.sin(0.05), rel=1e-6)
    m = h.comp.dipole
    b = tuple(c * 1e-4 for c in h.world.b)
    tau_mag = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
    assert tau_mag[0] < 0.0  # opposes h_x > 0
    u = h.world.torques[0][-1]
    assert u == pytest.approx(-(tau[0] - 0.8 * tau_mag[0]), rel=1e-6)
    assert h.tlm_values("PointingError")[-1] == pytest.approx(math.degrees(0.1), rel=1e-2)
    assert all(h.world.enabled[i] == [True] for i in range(3))  # enabled once, before the first torque


def test_pointing_on_magnetorquers_projects_the_pd_torque(fprime_harness):
    """ADCS-032: with POINTING_ACTUATOR = MAGNETORQUERS the wheels stay at zero and the dipole is the
    coil-weighted projection of τ = −K_P_MAG q_err.v − K_D_MAG ω (before rounding to drive levels: within one
    level), so m × B is τ's part ⟂ B."""
    h = pointing(fprime_harness, q=quat_from_axis_angle((0.0, 1.0, 0.0), 0.2),
                 params={"POINTING_ACTUATOR": PointingActuator.MAGNETORQUERS, **FIELD_STEERING_HOLD,
                         "MAG_SETTLE_TIME": 0.0})
    tick(h, 5)
    assert all(t == 0.0 for t in h.world.torques[1])
    assert any(c != 0.0 for c in h.tlm_values("RequestedTorque")[-1])
    tau = tuple(h.tlm_values("RequestedTorque")[-1])
    m, _ = project_dipole_weighted(tau, tuple(c * 1e-4 for c in h.world.b), h.comp.law.coil_limits())
    cx = h.comp.X_COIL_MAX_DIPOLE.value
    assert all(abs(a - e) <= 2 * cx / 127 for a, e in zip(h.comp.dipole, m, strict=True))


def _coils_in_a_turning_field(fprime_harness, r: float, b0: float):
    """A coil-pointing harness 0.2 rad about y from the identity, its field (gauss) turning at ``r`` rad/s in N on a
    cone (``b0`` in the x–y plane, 0.1 along z), run 60 s so the field-line rate estimate has settled."""
    h = make(fprime_harness, params={"POINTING_ACTUATOR": PointingActuator.MAGNETORQUERS, **FIELD_STEERING_HOLD,
                                     "MAG_FIELD_RATE_BANDWIDTH": 0.2, "MAG_SETTLE_TIME": 30.0})
    h.world.q = quat_from_axis_angle((0.0, 1.0, 0.0), 0.2)
    t0 = h.test_time.total_us

    def turning_field():
        t = (h.test_time.total_us - t0) / 1e6
        b_n = (b0 * math.cos(r * t), b0 * math.sin(r * t), 0.1)
        x, y, z = rotate_n_to_b(h.world.q, b_n)
        return Result(MagneticField(x=x, y=y, z=z, timestamp=h.test_time), Success.SUCCESS)

    h.set_port_handler("magneticFieldGet", turning_field)
    seconds(h, 60)
    return h


def test_magnetorquer_pointing_steers_with_the_measured_field_line_rate(fprime_harness):
    """ADCS-060: MAG_POINTING_LAW = FIELD_STEERING (default): with the field turning at 2e-3 rad/s (0.115 °/s) in N,
    FieldLineRate reads that rate within 5 % after 60 s at MAG_FIELD_RATE_BANDWIDTH 0.2 rad/s (the estimator runs in
    every mode while the attitude is known), and RequestedTorque is field_steering_torque of the controller's
    attitude, rate, field and field-line rate with K_P_MAG, K_D_MAG, MAG_STEER_RHO, MAG_STEER_ZETA (1e-12 N·m);
    SEED_PD requests seed 003's PD."""
    r = 2.0e-3
    b0 = 0.4  # gauss
    h = _coils_in_a_turning_field(fprime_harness, r, b0)
    h.send_command("SET_TARGET_QUATERNION", 1.0, 0.0, 0.0, 0.0)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    tick(h, 5)
    c = h.comp
    expected_rate = r * b0 / math.hypot(b0, 0.1)  # |db̂/dt| of the tilted cone
    assert h.tlm_values("FieldLineRate")[-1] == pytest.approx(math.degrees(expected_rate), rel=0.05)
    tau, _ = field_steering_torque(c.target, c.law.filter.q, c.law.omega, c.law.b_tesla, c.law.bdot_hat_B,
                                   c.K_P_MAG.value, c.K_D_MAG.value, c.MAG_STEER_RHO.value, c.MAG_STEER_ZETA.value,
                                   c.MAG_FIELD_RATE_MIN.value)
    assert all(abs(a - e) < 1e-12 for a, e in zip(h.tlm_values("RequestedTorque")[-1], tau, strict=True))
    assert any(abs(a - p) > 1e-9 for a, p in zip(tau, pd_torque(c.target, c.law.filter.q, c.law.omega, c.K_P_MAG.value,
                                                                 c.K_D_MAG.value)[0], strict=True))
    h.send_command("MAG_POINTING_LAW_PRM_SET", MagPointingLaw.SEED_PD)
    tick(h, 5)
    pd, _ = pd_torque(c.target, c.law.filter.q, c.law.omega, c.K_P_MAG.value, c.K_D_MAG.value)
    assert all(abs(a - e) < 1e-12 for a, e in zip(h.tlm_values("RequestedTorque")[-1], pd, strict=True))


@pytest.mark.parametrize("bad", [{"MAG_STEER_RHO_LARGE": -0.1}, {"MAG_STEER_RHO_LARGE": 10.5},
                                 {"MAG_STEER_RHO_LARGE": math.nan}, {"MAG_STEER_RHO_FROM": -1.0},
                                 {"MAG_STEER_RHO_FROM": 181.0}, {"MAG_STEER_RHO_FROM": math.inf},
                                 {"MAG_STEER_RHO_AT": -1.0}, {"MAG_STEER_RHO_AT": 181.0},
                                 {"MAG_STEER_RHO_AT": math.nan}])
def test_scheduled_rho_parameters_have_ranges(fprime_harness, bad):
    """ADCS-150: MAG_STEER_RHO_LARGE outside 0…10, MAG_STEER_RHO_FROM or MAG_STEER_RHO_AT outside 0…180° (or any
    of them not finite) are refused by PRM_SET (VALIDATION_ERROR) and the value in use is kept."""
    assert_refused_and_kept(fprime_harness, bad)


def test_magnetorquer_pointing_schedules_rho_on_the_error(fprime_harness):
    """ADCS-151: MAG_STEER_RHO_LARGE is 0 (no schedule) by default; set to 4 with MAG_STEER_RHO_FROM 5° and
    MAG_STEER_RHO_AT 10°, at an error of 11.5° RequestedTorque is field_steering_torque with those three (1e-12 N·m),
    which differs from the unscheduled law's."""
    h = _coils_in_a_turning_field(fprime_harness, 2.0e-3, 0.4)
    assert h.comp.MAG_STEER_RHO_LARGE.value == 0.0
    for name, value in (("MAG_STEER_RHO_LARGE", 4.0), ("MAG_STEER_RHO_FROM", 5.0), ("MAG_STEER_RHO_AT", 10.0)):
        h.send_command(f"{name}_PRM_SET", value)
    h.send_command("SET_TARGET_QUATERNION", 1.0, 0.0, 0.0, 0.0)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    tick(h, 5)
    c = h.comp
    args = (c.target, c.law.filter.q, c.law.omega, c.law.b_tesla, c.law.bdot_hat_B, c.K_P_MAG.value, c.K_D_MAG.value,
            c.MAG_STEER_RHO.value, c.MAG_STEER_ZETA.value, c.MAG_FIELD_RATE_MIN.value)
    tau, _ = field_steering_torque(*args, 4.0, 5.0, 10.0)
    assert all(abs(a - e) < 1e-12 for a, e in zip(h.tlm_values("RequestedTorque")[-1], tau, strict=True))
    plain, _ = field_steering_torque(*args)
    assert max(abs(a - p) for a, p in zip(tau, plain, strict=True)) > 1e-9


def test_magnetorquer_pointing_waits_for_the_gyro_bias_to_settle(fprime_harness):
    """ADCS-061: POINTING on the coils requests nothing and drives no coil until the attitude has been known for
    MAG_SETTLE_TIME (here 10 s; the steering's along-field gain would turn a still-settling gyro-bias estimate into
    a spin-up), then it requests the law's torque."""
    h = pointing(fprime_harness, q=quat_from_axis_angle((0.0, 1.0, 0.0), 0.2),
                 params={"POINTING_ACTUATOR": PointingActuator.MAGNETORQUERS, **FIELD_STEERING_HOLD,
                         "MAG_SETTLE_TIME": 10.0})
    seconds(h, 9)
    assert all(list(t) == [0.0, 0.0, 0.0] for t in h.tlm_values("RequestedTorque"))
    assert all(lv == 0 for p in STARTS for call in h.from_port(p) for lv in call.args)
    assert h.comp.mode == ControlMode.POINTING
    seconds(h, 2)
    assert any(c != 0.0 for c in h.tlm_values("RequestedTorque")[-1])
    assert any(lv != 0 for p in STARTS for call in h.from_port(p) for lv in call.args)


def test_residual_dipole_feed_forward_by_mode(fprime_harness):
    """ADCS-062: POINTING on the coils cancels the residual dipole: the commanded dipole is the law's projection minus
    m_res / duty (duty 0.8; within two drive levels), with m_res MAG_RESIDUAL_DIPOLE_X/Y/Z under PARAMETER, the
    on-board estimate under ESTIMATE once it exists (the parameters before), nothing under OFF; ResidualDipole
    telemeters the one in use. An estimate beyond the coil limits is refused (ResidualDipoleEstimateRefused,
    throttled) and the parameters are used instead."""
    m_par = (8.0e-3, -6.0e-3, 1.0e-3)
    h = pointing(fprime_harness, q=quat_from_axis_angle((0.0, 1.0, 0.0), 0.2),
                 params={"POINTING_ACTUATOR": PointingActuator.MAGNETORQUERS, **FIELD_STEERING_HOLD,
                         "MAG_SETTLE_TIME": 0.0,
                         "MAG_RESIDUAL_MODE": MagResidualMode.PARAMETER, "MAG_RESIDUAL_DIPOLE_X": m_par[0],
                         "MAG_RESIDUAL_DIPOLE_Y": m_par[1], "MAG_RESIDUAL_DIPOLE_Z": m_par[2]})
    c = h.comp
    cx, cz = c.X_COIL_MAX_DIPOLE.value, c.Z_COIL_MAX_DIPOLE.value
    tol = (2 * cx / 127, 2 * cx / 127, 2 * cz / 127)  # one drive level on each of two coils (X, Y) or the Z− coil

    def check(m_ff):
        tick(h, 5)
        tau = tuple(h.tlm_values("RequestedTorque")[-1])
        m, _ = project_dipole_weighted(tau, tuple(v * 1e-4 for v in h.world.b), c.law.coil_limits())
        expected = tuple(m[i] - m_ff[i] / 0.8 for i in range(3))
        assert all(abs(c.dipole[i] - expected[i]) <= tol[i] for i in range(3))
        assert tuple(h.tlm_values("ResidualDipole")[-1]) == pytest.approx(m_ff, abs=1e-15)

    check(m_par)
    h.send_command("MAG_RESIDUAL_MODE_PRM_SET", MagResidualMode.OFF)
    check((0.0, 0.0, 0.0))
    h.send_command("MAG_RESIDUAL_MODE_PRM_SET", MagResidualMode.ESTIMATE)
    c.law.residual_estimator.estimate = None
    tick(h, 5)
    c.law.residual_estimator.estimate = None  # no estimate yet (the harness world cannot make one): the parameters
    check(m_par)
    est = (-7.0e-3, 5.0e-3, -1.0e-3)
    c.law.residual_estimator.estimate = est
    check(est)
    h.assert_event_count("ResidualDipoleEstimateRefused", 0)
    c.law.residual_estimator.estimate = (0.5, 0.0, 0.0)  # beyond the X coils' 0.116 A·m²
    check(m_par)
    c.law.residual_estimator.estimate = (math.nan, 0.0, 0.0)
    for _ in range(10):
        check(m_par)
    h.assert_event_count("ResidualDipoleEstimateRefused", 5)  # throttled


def test_residual_dipole_estimator_runs_only_while_the_coils_point(fprime_harness):
    """ADCS-063: the estimator is fed (its windows count up, MAG_RESIDUAL_WINDOW long) only in POINTING on the coils
    past MAG_SETTLE_TIME with MAG_RESIDUAL_MODE = ESTIMATE; with the wheels pointing, during the settle wait or under
    another mode it is not, and its sums are kept."""
    h = pointing(fprime_harness, params={"POINTING_ACTUATOR": PointingActuator.MAGNETORQUERS, **FIELD_STEERING_HOLD,
                                         "MAG_SETTLE_TIME": 10.0, "MAG_RESIDUAL_WINDOW": 5.0})
    est = h.comp.law.residual_estimator
    seconds(h, 9)
    assert est.windows == 0
    seconds(h, 12)
    assert est.windows == 2 and est.window_s == 5.0
    h.send_command("MAG_RESIDUAL_MODE_PRM_SET", MagResidualMode.PARAMETER)
    seconds(h, 12)
    assert est.windows == 2
    h.send_command("MAG_RESIDUAL_MODE_PRM_SET", MagResidualMode.ESTIMATE)
    h.send_command("POINTING_ACTUATOR_PRM_SET", PointingActuator.WHEELS)
    seconds(h, 12)
    assert est.windows == 2
    h.send_command("POINTING_ACTUATOR_PRM_SET", PointingActuator.MAGNETORQUERS)
    seconds(h, 12)
    assert est.windows == 4


@pytest.mark.parametrize("bad", [{"MAG_RESIDUAL_DIPOLE_X": 0.06}, {"MAG_RESIDUAL_DIPOLE_Z": -0.06},
                                 {"MAG_RESIDUAL_WINDOW": 1.0}, {"MAG_RESIDUAL_WINDOW": 1000.0}])
def test_residual_dipole_parameters_have_ranges(fprime_harness, bad):
    """ADCS-062: MAG_RESIDUAL_DIPOLE_* outside ±0.05 A·m² and MAG_RESIDUAL_WINDOW outside 5…600 s are refused by
    PRM_SET (VALIDATION_ERROR) and the value in use is kept."""
    assert_refused_and_kept(fprime_harness, bad)


def assert_refused_and_kept(fprime_harness, bad: dict) -> None:
    """``{name: value}``'s PRM_SET is refused with VALIDATION_ERROR and the value in use is kept."""
    h = make(fprime_harness)
    ((name, value),) = bad.items()
    before = getattr(h.comp, name).value
    h.send_command(f"{name}_PRM_SET", value)
    h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)
    assert getattr(h.comp, name).value == before


def test_spin_stable_seed_damper_requests_nothing_from_rest(fprime_harness):
    """ADCS-033: SPIN_LAW = SEED_KANE_DAMPER flies the seed's equations as written: from rest its state is only
    driven by the torque it produced itself, so the requested torque stays zero and no coil is driven (the
    body keeps tumbling at 8 °/s); DamperState reads 0."""
    h = make(fprime_harness, params={"SPIN_LAW": SpinLaw.SEED_KANE_DAMPER})
    h.world.omega = (8 * DEG, 2 * DEG, 1 * DEG)
    h.send_command("FORCE_MODE", ControlMode.SPIN_STABLE)
    seconds(h, 10)
    assert all(v == 0.0 for v in h.tlm_values("DamperState"))
    assert all(list(t) == [0.0, 0.0, 0.0] for t in h.tlm_values("RequestedTorque"))
    assert all(lv == 0 for call in h.from_port("xPlusStart") for lv in call.args)


def test_spin_stable_rate_regulator_drives_toward_the_target_spin(fprime_harness):
    """ADCS-033: the default SPIN_LAW (RATE_REGULATOR) requests τ = −k_t ω_⊥ − k_s (ω_z − ω_s) ẑ; its achievable
    part (⟂ B) does negative work on the rate error."""
    h = make(fprime_harness)
    h.world.omega = (3 * DEG, 0.0, 0.5 * DEG)
    h.send_command("FORCE_MODE", ControlMode.SPIN_STABLE)
    tick(h, 5)
    tau = h.tlm_values("RequestedTorque")[-1]
    ws = h.comp.SPIN_RATE_TARGET.value * DEG
    kt, ks = h.comp.SPIN_K_TRANSVERSE.value, h.comp.SPIN_K_RATE.value
    assert tau[0] == pytest.approx(-kt * 3 * DEG, rel=1e-3)  # the filter's bias estimate is still ~0
    assert tau[2] == pytest.approx(-ks * (0.5 * DEG - ws), rel=1e-3)
    m = h.comp.dipole
    b = tuple(c * 1e-4 for c in h.world.b)
    t_mag = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
    err = (3 * DEG, 0.0, 0.5 * DEG - ws)
    assert sum(a * e for a, e in zip(t_mag, err, strict=True)) < 0.0


def test_the_cycle_rate_is_the_mean_of_its_ticks(fprime_harness):
    """ADCS-034: the rate a cycle uses is the mean of the gyro readings of the ticks since the last cycle and
    its own (five at 50 Hz): readings 1, 2, 3, 4 and then 5 °/s on x give 3 °/s (AngularRate)."""
    h = make(fprime_harness)
    h.world.tracker_valid = False
    tick(h, 1)
    for k in range(1, 6):
        h.world.omega = (k * DEG, 0.0, 0.0)
        tick(h)
    assert h.tlm_values("AngularRate")[-1] == pytest.approx(3.0, rel=1e-9)


def test_sensor_failures_are_reported_and_throttled(fprime_harness):
    """ADCS-034: gyro and magnetometer read failures log GyroRetrievalFailed / MagneticFieldRetrievalFailed,
    5 times at most; with no field the coils stay off; a good read clears the throttle."""
    h = make(fprime_harness)
    h.world.gyro_ok = False
    h.world.mag_ok = False
    h.send_command("FORCE_MODE", ControlMode.SPIN_STABLE)
    seconds(h, 2)
    h.assert_event_count("GyroRetrievalFailed", 5)
    h.assert_event_count("MagneticFieldRetrievalFailed", 5)
    assert not h.comp.law.coils_driven
    h.world.gyro_ok = True
    tick(h, 5)
    h.world.gyro_ok = False
    tick(h, 5)
    h.assert_event_count("GyroRetrievalFailed", 6)


def test_wheel_limit_event(fprime_harness):
    """ADCS-035: a wheel near its momentum limit pushed further gets zero torque and WheelLimitReached is
    logged (throttled to 5)."""
    h = pointing(fprime_harness, q=quat_from_axis_angle((1.0, 0.0, 0.0), -0.5))  # τ_x > 0 → u_x < 0
    h.world.momenta = [-0.99 * h.comp.WHEEL_MAX_MOMENTUM.value, 0.0, 0.0]
    seconds(h, 2)
    assert h.world.torques[0][-1] == 0.0
    h.assert_event_count("WheelLimitReached", 5)


def test_a_changed_wheel_limit_reaches_the_next_allocation(fprime_harness):
    """ADCS-035: the allocator is kept between cycles, but a WHEEL_MAX_TORQUE set by command limits the very next
    cycle's wheel torques (and INERTIA_ZZ the rate observer's model): nothing cached outlives its parameter."""
    limit = 1.0e-4  # N·m: below the slew's K_D × SLEW_RATE_LIMIT (2.8e-4 N·m), so the allocation saturates
    h = pointing(fprime_harness, q=quat_from_axis_angle((1.0, 0.0, 0.0), -0.5), params={"WHEEL_MAX_TORQUE": limit})
    tick(h, 5)
    assert max(abs(w[-1]) for w in h.world.torques) == pytest.approx(limit)
    h.send_command("WHEEL_MAX_TORQUE_PRM_SET", limit / 4)
    h.assert_cmd_response(0, "WHEEL_MAX_TORQUE_PRM_SET", CmdResponse.OK)
    h.send_command("INERTIA_ZZ_PRM_SET", 3.0e-3)
    tick(h, 5)
    assert max(abs(w[-1]) for w in h.world.torques) == pytest.approx(limit / 4)
    assert h.comp.law.rate_observer.inertia[2][2] == 3.0e-3


def test_idle_stops_everything(fprime_harness):
    """ADCS-036: FORCE_MODE IDLE from POINTING stops the coils at once and sets every wheel torque to zero."""
    h = pointing(fprime_harness, q=quat_from_axis_angle((1.0, 0.0, 0.0), 0.3))
    h.world.momenta = [1e-3, 0.0, 0.0]
    tick(h, 6)  # tick 0 of the second cycle: coils on
    assert h.comp.law.coils_driven
    h.send_command("FORCE_MODE", ControlMode.IDLE)
    assert not h.comp.law.coils_driven
    assert all(w[-1] == 0.0 for w in h.world.torques)


# --- attitude estimation and the derivative term's rate (docs/studies/attitude_knowledge.md) ---------------

def test_mekf_is_the_default_and_a_switch_keeps_the_attitude(fprime_harness):
    """ADCS-037: the default estimator is the MEKF: AttitudeSigma3 (deg) is written and falls as fixes arrive;
    ESTIMATOR → COMPLEMENTARY logs EstimatorSelected, keeps the attitude, its bias and validity (no loss of
    POINTING), and AttitudeSigma3 is no longer written; back to MEKF starts its covariance from the tracker's noise
    and the initial bias σ (the complementary filter has no covariance to hand over)."""
    from detumble.components.attitude_types import AttitudeEstimator
    from detumble.control.attitude_filter import AttitudeFilter
    from detumble.control.mekf import Mekf

    h = pointing(fprime_harness, q=quat_from_axis_angle((0.0, 0.0, 1.0), 0.01))
    assert isinstance(h.comp.law.filter, Mekf)
    seconds(h, 2.0)
    sig = h.tlm_values("AttitudeSigma3")
    assert sig and sig[-1] < sig[0]
    q_before = h.comp.law.filter.q
    h.param_set("ESTIMATOR", AttitudeEstimator.COMPLEMENTARY)
    h.load_parameters()
    h.clear_history()
    h.world.tracker_valid = False  # no new fix: the switch itself must carry the attitude
    tick(h, 5)
    assert isinstance(h.comp.law.filter, AttitudeFilter)
    assert h.events_named("EstimatorSelected") == [(AttitudeEstimator.COMPLEMENTARY,)]
    assert quat_angle_between(h.comp.law.filter.q, q_before) < 1e-6
    assert h.comp.mode == ControlMode.POINTING and h.tlm_values("AttitudeValid")[-1] == 1
    assert h.tlm_values("AttitudeSigma3") == []
    h.param_set("ESTIMATOR", AttitudeEstimator.MEKF)
    h.load_parameters()
    tick(h, 5)
    assert isinstance(h.comp.law.filter, Mekf)
    # P_θθ = R at the switch, then one 0.1 s step on the gyro (no fix): + Δt² σ_b0² + σ_g² Δt²/5 + …
    f = h.comp.law.filter
    dt = 0.1
    step = dt * dt * (f.initial_bias_sigma ** 2 + f.gyro_noise ** 2 / 5) + f.bias_walk ** 2 * dt ** 3 / 3
    expected = 3 * math.sqrt(sum(f.tracker_noise()[i][i] for i in range(3)) + 3 * step)
    assert f.attitude_sigma3_rad == pytest.approx(expected, rel=1e-6)


def quat_angle_between(a, b):
    from detumble.control.quaternion import quat_angle, quat_error

    return quat_angle(quat_error(a, b))


@pytest.mark.parametrize("bad", [{"GYRO_NOISE": -1.0}, {"RATE_OBSERVER_GAIN": 0.0}, {"TRACKER_NOISE_ABOUT": 1e9}])
def test_estimator_parameters_have_ranges(fprime_harness, bad):
    """ADCS-038: noise and gain parameters outside their documented range are refused by PRM_SET (VALIDATION_ERROR)."""
    h = make(fprime_harness)
    ((name, value),) = bad.items()
    h.send_command(f"{name}_PRM_SET", value)
    h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)


def test_the_derivative_term_uses_the_rate_observer(fprime_harness):
    """ADCS-039: with RATE_SOURCE = OBSERVER a gyro step (1 °/s in the cycle's last reading: 0.2 °/s in its mean)
    moves the D term's rate by only the observer's pull 1 − e^(−L·0.1 s) (L = RATE_OBSERVER_GAIN) of it: the
    difference of the requested torques of the two sources is −K_D (1 − pull) ω, within 1e-3 relative (the
    attitude, K_P and the integral are the same)."""
    from detumble.components.attitude_types import RateSource

    taus = {}
    for source in (RateSource.GYRO, RateSource.OBSERVER):
        h = pointing(fprime_harness, params={"RATE_SOURCE": source})
        h.world.tracker_valid = False
        tick(h, 10)
        h.world.omega = (1.0 * DEG, 0.0, 0.0)
        tick(h, 5)
        taus[source] = h.tlm_values("RequestedTorque")[-1][0]
        gain, kd = h.comp.RATE_OBSERVER_GAIN.value, h.comp.K_D.value
    pull = 1.0 - math.exp(-gain * 0.1)
    w = DEG / 5  # the step reaches the cycle's mean in its last reading only: 1 °/s / 5
    assert taus[RateSource.GYRO] - taus[RateSource.OBSERVER] == pytest.approx(-kd * (1 - pull) * w, rel=1e-3)


def test_a_non_positive_definite_inertia_is_refused_once(fprime_harness):
    """ADCS-039: INERTIA_XY = 1 kg·m² (far above the moments) is not a positive definite inertia: the observer keeps
    its previous model and InertiaModelRefused is logged once (throttle 1), however many cycles follow."""
    h = make(fprime_harness, params={"INERTIA_XY": 1.0})
    before = h.comp.law.rate_observer.inertia
    tick(h, 30)
    assert h.comp.law.rate_observer.inertia == before and before[0][1] == pytest.approx(2.0e-5)
    assert len(h.events_named("InertiaModelRefused")) == 1


def test_three_value_finite_check_answers_as_the_general_one():
    """_finite3 (the component's check of a reading's x, y, z) answers as the law's _finite does: finite numbers,
    NaN, ±inf, non-numbers."""
    import itertools
    from types import SimpleNamespace

    from detumble.components.attitude_controller import _finite3
    from detumble.control.three_mode import _finite

    values = (0.0, -1.5, 3, math.nan, math.inf, -math.inf, None, "1.0", True)
    for x, y, z in itertools.product(values, repeat=3):
        assert _finite3(SimpleNamespace(x=x, y=y, z=z)) == _finite(x, y, z), (x, y, z)


def test_a_cycle_reads_each_wheel_once_and_a_command_reads_them_afresh(fprime_harness):
    """ADCS-080: pointing on the wheels, a control cycle reads each wheel's state once (the sensing step's
    reading decides, for the rest of the cycle, whether the wheels answer: the residual-dipole tracker and the
    actuator choice reuse it), while FORCE_MODE POINTING between cycles reads the wheels at that moment: a wheel
    that stopped answering after the last cycle gets the command refused (EXECUTION_ERROR,
    ModeUnavailableNoWheels)."""
    h = make(fprime_harness, params={"POINTING_ACTUATOR": PointingActuator.WHEELS})
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.OK)
    reads = len(h.from_port("wheelStateGet"))
    tick(h, 5)  # one 10 Hz cycle (CYCLE_TICKS 5)
    assert h.comp.mode == ControlMode.POINTING and h.comp.law.cycles == 2
    calls = h.from_port("wheelStateGet")[reads:]
    assert sorted(c.index for c in calls) == [0, 1, 2]
    assert len(h.from_port("wheelTorqueSet")) >= 3  # it did point on them
    h.send_command("FORCE_MODE", ControlMode.IDLE)
    h.set_port_handler("wheelStateGet", lambda: Result(None, Success.FAILURE), index=1)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.assert_cmd_response(2, "FORCE_MODE", CmdResponse.EXECUTION_ERROR)
    h.assert_event("ModeUnavailableNoWheels", 0, ControlMode.POINTING)
    assert h.comp.mode == ControlMode.IDLE


def test_a_fault_in_run_reaches_the_ground_and_makes_the_actuators_safe(fprime_harness):
    """ADCS-081: an exception inside ``run`` (here the gyro port raising while the controller points on its wheels
    with the coils dumping momentum) is contained and reported through report_fault (decision 0005): the
    HandlerFault event names ``run`` and the exception, the HandlerFaults channel counts it, the coils are stopped
    and every wheel is sent zero torque; the next tick runs again."""
    h = pointing(fprime_harness, q=quat_from_axis_angle((1.0, 0.0, 0.0), 0.1))
    h.world.momenta = [1e-3, 0.0, 0.0]
    tick(h, 6)  # the second cycle's first tick: the coils drive
    assert h.comp.law.coils_driven and any(t[-1] != 0.0 for t in h.world.torques)
    stops = [len(h.from_port(p)) for p in STOPS]

    def broken():
        raise RuntimeError("gyro bus hung")

    h.set_port_handler("angularVelocityGet", broken)
    h.invoke("run", 0)
    h.assert_event("HandlerFault", 0, "run", "RuntimeError: gyro bus hung")
    assert h.tlm_values("HandlerFaults") == [1] and h.comp.handler_faults == 1
    assert [len(h.from_port(p)) for p in STOPS] == [n + 1 for n in stops]
    assert [t[-1] for t in h.world.torques] == [0.0, 0.0, 0.0]
    assert not h.comp.law.coils_driven
    h.set_port_handler("angularVelocityGet", h.world.gyro)
    tick(h, 6)
    assert h.comp.handler_faults == 1 and any(t[-1] != 0.0 for t in h.world.torques)


def _ephemeris_port(h, ok=True):
    """Connect ephemerisGet to a fixed circular-orbit sample (or a failing one)."""
    from detumble.components.attitude_types import Ephemeris

    a = 6.798e6
    v = math.sqrt(3.986004415e14 / a)
    h.set_port_handler("ephemerisGet", lambda: Result(Ephemeris(a, 0.0, 0.0, 0.0, v, 0.0, 0.3, 0.0, 1.0, 0.0),
                                                      Success.SUCCESS if ok else Success.FAILURE))


def test_moving_target_commands_are_validated_and_reported(fprime_harness):
    """ADCS-090: SET_TARGET_NADIR / _SUN / _GROUND_STATION: a parallel axis pair is refused (VALIDATION_ERROR,
    TargetAxesInvalid), so is a station off the Earth (VALIDATION_ERROR, TargetStationInvalid) and a target without
    an ephemeris (EXECUTION_ERROR, NoEphemeris); accepted ones answer OK with their event, and the cycle's telemetry
    names the active reference (ActiveTarget) and its rate (ReferenceRate: the orbit rate for nadir)."""
    from detumble.components.attitude_types import BodyAxis, PointingReference

    h = make(fprime_harness)
    _ephemeris_port(h, ok=False)
    h.send_command("SET_TARGET_NADIR", BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    h.assert_cmd_response(0, "SET_TARGET_NADIR", CmdResponse.EXECUTION_ERROR)
    h.assert_event_count("NoEphemeris", 1)
    _ephemeris_port(h)
    h.send_command("SET_TARGET_NADIR", BodyAxis.PLUS_Z, BodyAxis.MINUS_Z)
    h.assert_cmd_response(1, "SET_TARGET_NADIR", CmdResponse.VALIDATION_ERROR)
    h.assert_event("TargetAxesInvalid", 0, BodyAxis.PLUS_Z, BodyAxis.MINUS_Z)
    h.send_command("SET_TARGET_GROUND_STATION", 95.0, 10.0, 0.0, BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    h.assert_cmd_response(2, "SET_TARGET_GROUND_STATION", CmdResponse.VALIDATION_ERROR)
    h.assert_event("TargetStationInvalid", 0, 95.0, 10.0, 0.0)
    h.send_command("SET_TARGET_SUN", BodyAxis.PLUS_X, BodyAxis.PLUS_Z)
    h.assert_cmd_response(3, "SET_TARGET_SUN", CmdResponse.OK)
    h.assert_event("TargetSunSet", 0, BodyAxis.PLUS_X, BodyAxis.PLUS_Z)
    h.send_command("SET_TARGET_GROUND_STATION", 40.0, -105.0, 1600.0, BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    h.assert_cmd_response(4, "SET_TARGET_GROUND_STATION", CmdResponse.OK)
    h.send_command("SET_TARGET_NADIR", BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    h.assert_cmd_response(5, "SET_TARGET_NADIR", CmdResponse.OK)
    h.assert_event("TargetNadirSet", 0, BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    tick(h, 5)
    assert h.tlm_values("ActiveTarget")[-1] == PointingReference.NADIR
    n = math.sqrt(3.986004415e14 / 6.798e6 ** 3)
    assert h.tlm_values("ReferenceRate")[-1][1] == pytest.approx(-math.degrees(n), rel=1e-9)
    assert h.comp.law.target_spec.kind == 1


def test_a_moving_target_feeds_its_rate_forward_on_the_wheels(fprime_harness):
    """ADCS-091: pointing on the wheels, on a nadir target's attitude but not turning: the D term acts on the rate
    relative to the reference, so the wheels are asked |τ| = K_D n (2.3e-6 N·m, 0.1 %) along the orbit normal; an
    inertial target at the same attitude asks nothing (below 1e-9 N·m)."""
    from detumble.components.attitude_types import BodyAxis, RateSource
    from detumble.control.targets import Ephemeris, NadirTarget

    a = 6.798e6
    v = math.sqrt(3.986004415e14 / a)
    n = v / a
    h = make(fprime_harness, params={"RATE_SOURCE": RateSource.GYRO, "K_I": 0.0, "K_DUMP": 0.0})
    _ephemeris_port(h)
    ref = NadirTarget().reference(Ephemeris((a, 0.0, 0.0), (0.0, v, 0.0), 0.3, (0.0, 1.0, 0.0)))
    h.world.q = ref.q_RN
    tick(h, 6)  # the attitude known
    h.send_command("SET_TARGET_NADIR", BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    h.send_command("FORCE_MODE", ControlMode.POINTING)
    h.assert_cmd_response(1, "FORCE_MODE", CmdResponse.OK)
    tick(h, 10)
    tau = h.comp.law.torque_request
    assert math.sqrt(sum(c * c for c in tau)) == pytest.approx(2.0e-3 * n, rel=1e-3)
    assert tau[1] == pytest.approx(-2.0e-3 * n, rel=1e-3)  # ω_r = (0, −n, 0): τ = −K_D (0 − ω_r)
    h.send_command("SET_TARGET_QUATERNION", *ref.q_RN)
    tick(h, 5)
    assert max(abs(c) for c in h.comp.law.torque_request) < 1e-9


# --- SUN_SAFE (issue 27: the light sensors' Sun vector) ---------------------------------------------

def test_sun_safe_by_command_needs_the_light_sensors_and_turns_the_axis_to_the_sun(fprime_harness):
    """ADCS-100: FORCE_MODE SUN_SAFE without a Sun vector source is refused (EXECUTION_ERROR, SunSensorsUnavailable,
    mode unchanged); with one it is entered (SunSafeEntered(COMMAND), MANUAL) and, the Sun along +X and the body
    at rest, the wheels are asked for a torque about +Z × +X = +Y at the capped turn rate, τ = K_D·ω_c ŷ; the
    ground sees SunVectorEstimate and SunPointingError (90°). SUN_SAFE_AXIS = MINUS_Z turns the other way."""
    h = make(fprime_harness)
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
    h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.EXECUTION_ERROR)
    h.assert_event_count("SunSensorsUnavailable", 1)
    assert h.comp.mode == ControlMode.IDLE
    for axis, sign in (("PLUS_Z", 1.0), ("MINUS_Z", -1.0)):
        h = make(fprime_harness, sun=True, params={"SUN_SAFE_AXIS": axis})
        h.world.sun = (1.0, 0.0, 0.0)
        tick(h)
        h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
        h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.OK)
        h.assert_event_count("SunSafeEntered", 1)
        assert h.events_named("SunSafeEntered")[0][0] == ModeChangeReason.COMMAND
        tick(h, 5)
        kd = h.comp.SUN_SAFE_K_D.value
        rate = min(h.comp.SUN_SAFE_K_P.value / kd * math.pi / 2, h.comp.SLEW_RATE_LIMIT.value * DEG)
        tau = h.tlm_values("RequestedTorque")[-1]
        assert tau[0] == pytest.approx(0.0, abs=1e-12) and tau[2] == pytest.approx(0.0, abs=1e-12)
        assert tau[1] == pytest.approx(sign * kd * rate, rel=1e-9)
        assert h.world.torques[1][-1] == pytest.approx(-tau[1], rel=1e-9)  # the y wheel: its reaction is τ
        assert h.tlm_values("SunPointingError")[-1] == pytest.approx(90.0)
        assert list(h.tlm_values("SunVectorEstimate")[-1]) == pytest.approx([1.0, 0.0, 0.0])


def test_attitude_loss_goes_to_sun_safe_and_knowledge_brings_pointing_back(fprime_harness):
    """ADCS-101: with the light sensors connected, POINTING without a star-tracker fix for ATTITUDE_TIMEOUT goes to
    SUN_SAFE (ATTITUDE_LOST; AttitudeKnowledgeLost and SunSafeEntered), in AUTO and MANUAL; fixes again for
    SUN_SAFE_EXIT_DWELL (10 s) hand back to POINTING (KNOWLEDGE_RESTORED; SunSafeExited). One entered by command
    stays in SUN_SAFE with the attitude known."""
    for autonomy in ("SET_AUTO", None):
        h = pointing_then_tracker_lost(fprime_harness, autonomy, sun=True)
        assert h.comp.mode == ControlMode.SUN_SAFE
        assert modes(h)[-1] == (ControlMode.POINTING, ControlMode.SUN_SAFE, ModeChangeReason.ATTITUDE_LOST)
        h.assert_event_count("AttitudeKnowledgeLost", 1)
        h.assert_event_count("SunSafeEntered", 1)
        h.world.tracker_valid = True
        seconds(h, 9.8)
        assert h.comp.mode == ControlMode.SUN_SAFE
        seconds(h, 0.4)
        assert h.comp.mode == ControlMode.POINTING
        assert modes(h)[-1] == (ControlMode.SUN_SAFE, ControlMode.POINTING, ModeChangeReason.KNOWLEDGE_RESTORED)
        exited = h.events_named("SunSafeExited")
        assert len(exited) == 1 and exited[0][0] == ControlMode.POINTING
    h = make(fprime_harness, sun=True)
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
    seconds(h, 30)
    assert h.comp.mode == ControlMode.SUN_SAFE and h.tlm_values("AttitudeValid")[-1] == 1


def test_the_mode_managers_safe_mode_holds_sun_safe(fprime_harness):
    """ADCS-102: the ModeManager's SAFE_MODE (getSystemMode) takes SPIN_STABLE or POINTING to SUN_SAFE
    (SYSTEM_SAFE_MODE) in MANUAL and AUTO and holds it with the attitude known; back in NORMAL, the attitude known
    for SUN_SAFE_EXIT_DWELL returns it to POINTING (KNOWLEDGE_RESTORED). IDLE stays IDLE."""
    for start in (ControlMode.POINTING, ControlMode.SPIN_STABLE):
        h = make(fprime_harness, sun=True, system_mode=True)
        tick(h)
        h.send_command("FORCE_MODE", start)
        seconds(h, 1)
        h.world.system_mode = SystemMode.SAFE_MODE
        seconds(h, 0.2)
        assert modes(h)[-1] == (start, ControlMode.SUN_SAFE, ModeChangeReason.SYSTEM_SAFE_MODE)
        seconds(h, 60)
        assert h.comp.mode == ControlMode.SUN_SAFE
        h.world.system_mode = SystemMode.NORMAL
        seconds(h, 10.2)
        assert modes(h)[-1] == (ControlMode.SUN_SAFE, ControlMode.POINTING, ModeChangeReason.KNOWLEDGE_RESTORED)
    h = make(fprime_harness, sun=True, system_mode=True)
    h.world.system_mode = SystemMode.SAFE_MODE
    seconds(h, 2)
    assert h.comp.mode == ControlMode.IDLE


def test_sun_safe_damps_in_eclipse_and_carries_the_sun_on_the_gyro(fprime_harness):
    """ADCS-103: between readings the Sun vector is carried on the gyro (1 s at 0.05 rad/s about +Z turns the
    inertial +X to (cos, −sin, 0) in B); with no valid reading for SUN_VECTOR_TIMEOUT (eclipse) it is dropped and
    SUN_SAFE only damps, τ = −K_D ω."""
    h = make(fprime_harness, sun=True, params={"SUN_VECTOR_TIMEOUT": 5.0})
    h.world.sun = (1.0, 0.0, 0.0)
    h.world.sun_stamp = h.world.h.test_time  # one reading, held: the sensors stop updating
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
    h.world.omega = (0.0, 0.0, 0.05)
    tick(h, 5)
    s0 = h.tlm_values("SunVectorEstimate")[-1]
    seconds(h, 1)
    s1 = h.tlm_values("SunVectorEstimate")[-1]
    turn = math.atan2(s0[0] * s1[1] - s0[1] * s1[0], s0[0] * s1[0] + s0[1] * s1[1])
    assert turn == pytest.approx(-0.05, rel=1e-6)
    h.world.sun_valid = False
    seconds(h, 6)
    kd = h.comp.SUN_SAFE_K_D.value
    tau = h.tlm_values("RequestedTorque")[-1]
    assert list(tau) == pytest.approx([0.0, 0.0, -kd * 0.05], abs=1e-15)
    assert h.comp.mode == ControlMode.SUN_SAFE


def test_gyroscopic_and_gravity_gradient_feed_forward_on_the_wheels(fprime_harness):
    """ADCS-096: with WHEEL_FEED_FORWARD = REFERENCE_GYROSCOPIC_GRAVITY the wheel law on an inertial target adds
    ``ω × (I ω + h_w) − 3 μ/r³ r̂ × (I r̂)`` (the INERTIA_* model, the ephemeris' position at the estimated
    attitude) to the requested torque of the same cycle under the default REFERENCE; the gravity-gradient part is the
    plant's formula (``sim.torques``) at the true attitude to 1 %."""
    from detumble.components.attitude_types import RateSource, WheelFeedForward
    from detumble.control.pointing import gravity_gradient_torque, gyroscopic_torque
    from detumble.sim import torques

    q = quat_from_axis_angle((0.3, -0.8, 0.5), 0.7)
    runs = {}
    for ff in (WheelFeedForward.REFERENCE, WheelFeedForward.REFERENCE_GYROSCOPIC_GRAVITY):
        h = make(fprime_harness, params={"RATE_SOURCE": RateSource.GYRO, "K_I": 0.0, "K_DUMP": 0.0,
                                         "WHEEL_FEED_FORWARD": ff})
        _ephemeris_port(h)
        h.world.q = q
        h.world.omega = (0.004, -0.002, 0.003)
        h.world.momenta = [1.0e-3, -5.0e-4, 2.0e-4]
        tick(h, 5)
        h.send_command("SET_TARGET_QUATERNION", *q)
        h.send_command("FORCE_MODE", ControlMode.POINTING)
        tick(h, 10)
        runs[ff] = h
    base, full = runs[WheelFeedForward.REFERENCE], runs[WheelFeedForward.REFERENCE_GYROSCOPIC_GRAVITY]
    law = full.comp.law
    inertia = law.rate_observer.inertia
    r_B = rotate_n_to_b(law.filter.q, (6.798e6, 0.0, 0.0))
    gg = gravity_gradient_torque(inertia, r_B, 3.986004415e14)
    gyro = gyroscopic_torque(inertia, law.omega, (1.0e-3, -5.0e-4, 2.0e-4))
    diff = [a - b for a, b in zip(full.comp.law.torque_request, base.comp.law.torque_request, strict=True)]
    expected = [g - t for g, t in zip(gyro, gg, strict=True)]
    assert max(abs(gg[i]) for i in range(3)) > 1e-10  # the attitude is chosen so that the term is not zero
    for i in range(3):
        assert diff[i] == pytest.approx(expected[i], rel=1e-9, abs=1e-18)
    # the plant's formula at the true attitude (the estimate trails the turning stub by ~0.1°)
    plant = torques.gravity_gradient_torque(3.986004415e14, rotate_n_to_b(full.world.q, (6.798e6, 0.0, 0.0)), inertia)
    for i in range(3):
        assert gg[i] == pytest.approx(plant[i], rel=1e-2)


@pytest.mark.parametrize("bad", [{"SUN_SPIN_RATE": 0.0}, {"SUN_SPIN_RATE": 12.0}, {"SUN_SPIN_RATE": math.nan},
                                 {"SUN_BIAS_TIME": 0.5}, {"SUN_BIAS_TIME": 4000.0},
                                 {"SUN_HOLD_ANGLE": -1.0}, {"SUN_HOLD_ANGLE": 91.0}, {"SUN_HOLD_DWELL": -1.0},
                                 {"SUN_HOLD_DWELL": math.inf}, {"SUN_HOLD_SPIN_RATE": 0.0},
                                 {"SUN_HOLD_SPIN_RATE": 11.0}, {"SUN_HOLD_RAMP": 0.0}, {"SUN_HOLD_RAMP": math.nan},
                                 {"SUN_HOLD_FIELD_ANGLE": -1.0}, {"SUN_HOLD_FIELD_ANGLE": 89.5},
                                 {"SUN_HOLD_FIELD_ANGLE": math.inf}, {"SUN_HOLD_TIP_ANGLE": -0.1},
                                 {"SUN_HOLD_TIP_ANGLE": 11.0}, {"SUN_HOLD_TIP_ANGLE": math.nan}])
def test_sun_safe_ground_parameters_have_ranges(fprime_harness, bad):
    """ADCS-106: SUN_SPIN_RATE outside 0.1…10 °/s, SUN_BIAS_TIME outside 1…3600 s, SUN_HOLD_ANGLE outside 0…90°,
    SUN_HOLD_DWELL outside 0…36000 s, SUN_HOLD_SPIN_RATE outside 0.1…10 °/s, SUN_HOLD_RAMP outside 1e-4…1 °/s²,
    SUN_HOLD_FIELD_ANGLE outside 0…89°, SUN_HOLD_TIP_ANGLE outside 0…10° (or
    any of them not finite) are refused by PRM_SET (VALIDATION_ERROR) and the value in use is kept."""
    assert_refused_and_kept(fprime_harness, bad)


def test_sun_safe_spin_rate_and_bias_time_act_from_the_ground(fprime_harness):
    """ADCS-107: on the coils, SUN_SAFE with the Sun on +Z and the body at rest asks only for the spin about +Z,
    τ_z = SPIN_K_RATE · SUN_SPIN_RATE (rad/s): 3 °/s by default, 1.5 °/s after SUN_SPIN_RATE_PRM_SET 1.5 (OK, from
    the next cycle); SUN_BIAS_TIME_PRM_SET 40 becomes the Sun-vector bias observer's time constant."""
    h = make(fprime_harness, sun=True, params={"POINTING_ACTUATOR": "MAGNETORQUERS", **FIELD_STEERING_HOLD})
    h.world.sun = (0.0, 0.0, 1.0)
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
    h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.OK)
    seconds(h, 2)
    k = h.comp.SPIN_K_RATE.value
    assert h.comp.law.torque_request[2] == pytest.approx(k * 3.0 * DEG, rel=1e-6)
    h.send_command("SUN_SPIN_RATE_PRM_SET", 1.5)
    h.assert_cmd_response(1, "SUN_SPIN_RATE_PRM_SET", CmdResponse.OK)
    h.send_command("SUN_BIAS_TIME_PRM_SET", 40.0)
    h.assert_cmd_response(2, "SUN_BIAS_TIME_PRM_SET", CmdResponse.OK)
    seconds(h, 2)
    assert h.comp.law.torque_request[2] == pytest.approx(k * 1.5 * DEG, rel=1e-6)
    assert h.comp.law.sun_bias.time_s == 40.0


def test_sun_hold_field_angle_acts_from_the_ground(fprime_harness):
    """ADCS-120: the coils' spin-down ramp waits while the field is closer to SUN_SAFE_AXIS than
    SUN_HOLD_FIELD_ANGLE. The Sun on +Z, held for SUN_HOLD_DWELL (set to 1 s), the field 70° from +Z: at the default
    80° the spin command stays at SUN_SPIN_RATE (τ_z = SPIN_K_RATE · 3 °/s); after SUN_HOLD_FIELD_ANGLE_PRM_SET 60
    (OK) it ramps at SUN_HOLD_RAMP (set to 0.1 °/s²) down to SUN_HOLD_SPIN_RATE (1.5 °/s)."""
    h = make(fprime_harness, sun=True, params={"POINTING_ACTUATOR": "MAGNETORQUERS", **FIELD_STEERING_HOLD,
                                               "SUN_HOLD_DWELL": 1.0,
                                               "SUN_HOLD_RAMP": 0.1})
    h.world.sun = (0.0, 0.0, 1.0)
    c, s = math.cos(math.radians(70.0)), math.sin(math.radians(70.0))
    h.world.b = (0.3 * s, 0.0, 0.3 * c)  # gauss, 70° from +Z
    tick(h)
    h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
    h.assert_cmd_response(0, "FORCE_MODE", CmdResponse.OK)
    seconds(h, 20)
    k = h.comp.SPIN_K_RATE.value
    assert h.comp.law.sun_hold.lowered  # the Sun held: lowering began, but the field is too near the axis
    assert h.comp.law.sun_hold.command_deg_s == 3.0
    assert h.comp.law.torque_request[2] == pytest.approx(k * 3.0 * DEG, rel=1e-6)
    assert h.comp.SUN_HOLD_FIELD_ANGLE.value == 80.0
    h.send_command("SUN_HOLD_FIELD_ANGLE_PRM_SET", 60.0)
    h.assert_cmd_response(1, "SUN_HOLD_FIELD_ANGLE_PRM_SET", CmdResponse.OK)
    seconds(h, 5)
    assert 2.4 <= h.comp.law.sun_hold.command_deg_s <= 2.6  # 5 s at 0.1 °/s²
    seconds(h, 20)
    assert h.comp.law.sun_hold.command_deg_s == 1.5
    assert h.comp.law.torque_request[2] == pytest.approx(k * 1.5 * DEG, rel=1e-6)


@pytest.mark.parametrize("bad", [{"INTEGRAL_RATE_GATE": -0.01}, {"INTEGRAL_RATE_GATE": 10.5},
                                 {"INTEGRAL_RATE_GATE": math.nan}, {"INTEGRAL_RATE_GATE": math.inf}])
def test_integral_rate_gate_has_a_range(fprime_harness, bad):
    """ADCS-143: INTEGRAL_RATE_GATE outside 0…10 °/s (or not finite) is refused by PRM_SET (VALIDATION_ERROR) and the
    value in use is kept; 0, its default, turns the gate off."""
    assert_refused_and_kept(fprime_harness, bad)


@pytest.mark.parametrize("bad", [{"RATE_OBSERVER_DIPOLE_TIME": -1.0}, {"RATE_OBSERVER_DIPOLE_TIME": 3601.0},
                                 {"RATE_OBSERVER_DIPOLE_TIME": math.nan}, {"RATE_OBSERVER_DIPOLE_TIME": math.inf}])
def test_rate_observer_dipole_time_has_a_range(fprime_harness, bad):
    """ADCS-173: RATE_OBSERVER_DIPOLE_TIME outside 0…3600 s (or not finite) is refused by PRM_SET (VALIDATION_ERROR)
    and the value in use is kept; 0 leaves the residual dipole out of the rate observer (the default is 20 s,
    ADCS-180)."""
    assert_refused_and_kept(fprime_harness, bad)


def test_rate_observer_dipole_time_is_on_by_default_and_shipped(fprime_harness):
    """ADCS-180: the rate observer's residual-dipole estimate is on by default since issue 27
    (RATE_OBSERVER_DIPOLE_TIME 20 s, docs/studies/robust_rates.md): the controller's defaults, the component's
    parameter as it starts and adcs_ref's shipped parameter file (id 0x51 of the attitude controller) all carry 20 s."""
    import pathlib
    import struct

    from detumble.control.attitude_defaults import DEFAULTS
    from fprime_lite.svc.prm_db import decode_param_file

    assert DEFAULTS["RATE_OBSERVER_DIPOLE_TIME"] == 20.0
    h = make(fprime_harness)
    assert h.comp.RATE_OBSERVER_DIPOLE_TIME.value == 20.0
    shipped = pathlib.Path(__file__).resolve().parents[3] / "deployments" / "adcs_ref" / "flight_params.dat"
    records = dict(decode_param_file(shipped.read_bytes()).records)
    assert records[0x1005C000 + 0x51] == struct.pack(">d", 20.0)
