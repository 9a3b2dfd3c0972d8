"""DetumbleManager through its ports (detumble.md §3; seed 000 requirement table).

Time is the harness's test time only; ``tick`` runs the component once and then advances 20 ms
(the reference 50 Hz rate group). Rates in deg/s, fields in gauss, dipoles in A·m².
"""

import math

import pytest

from detumble.components.detumble_manager import DetumbleManager
from detumble.components.types import (AngularUnit, CoilShape, DetumbleMode, DetumbleState, DetumbleStrategy,
                            MagnetorquerFace,
                            DipoleMoment, HysteresisAxis, MagneticField, Result, Success, SystemMode,
                            TimeIntervalValue)
from fprime_lite import CmdResponse, ParamValid, Severity, Time, TimeBase

BASE = 0x1005A000
TICK_US = 20_000
START = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1000, 0)
COIL_PORTS = ("xPlus", "xMinus", "yPlus", "yMinus", "zMinus")
STARTS = [f"{c}Start" for c in COIL_PORTS]
STOPS = [f"{c}Stop" for c in COIL_PORTS]
# Dipole slope chosen so that m = −GAIN·Ḃ = (0.01, 0.03, 0.004) A·m² at GAIN = 3.0; by hand
# (test_magnetorquer) the X coils drive 22, the Y coils 66 and Z− −58 (X−/Y− negated: −22, −66).
DIPOLE = (0.01, 0.03, 0.004)
BDOT_G_PER_S = tuple(-m / 3.0 for m in DIPOLE)
HAND_LEVELS = (22, -22, 66, -66, -58)


class Sensors:
    """Stub providers: an angular rate and a magnetometer whose field is linear in time."""

    def __init__(self, h):
        self.h = h
        self.rate = 10.0
        self.rate_ok = True
        self.field_ok = True
        self.field_override = None
        self.slope = BDOT_G_PER_S  # G/s
        self.period = Result(TimeIntervalValue(seconds=0, useconds=10_000), Success.SUCCESS)

    def angular(self, unit):
        return Result(self.rate, Success.SUCCESS if self.rate_ok else Success.FAILURE)

    def field(self):
        t = self.h.test_time
        if self.field_override is not None:
            x, y, z = self.field_override
        else:
            s = (t.total_us - START.total_us) / 1e6
            x, y, z = (0.2 + self.slope[0] * s, -0.1 + self.slope[1] * s, 0.35 + self.slope[2] * s)
        return Result(MagneticField(x=x, y=y, z=z, timestamp=t),
                      Success.SUCCESS if self.field_ok else Success.FAILURE)


def make(fprime_harness, *, external=False, params=None, load=True):
    comp = DetumbleManager("detumbleManager", base_id=BASE)
    h = fprime_harness(comp, test_time=START)
    if not external:
        comp.output_port("dipoleMomentGet").disconnect(0)  # the harness connects every output; this one is optional
    for port in STARTS + STOPS:
        h.set_port_return(port, Success.SUCCESS)
    h.set_port_return("getSystemMode", SystemMode.NORMAL)
    sensors = Sensors(h)
    h.set_port_handler("angularVelocityMagnitudeGet", sensors.angular)
    h.set_port_handler("magneticFieldGet", sensors.field)
    h.set_port_handler("magneticFieldSamplingPeriodGet", lambda: sensors.period)
    for name, value in (params or {}).items():
        h.param_set(name, value)
    if load:
        h.load_parameters()
    h.sensors = sensors
    return h


def tick(h, n=1, dt_us=TICK_US):
    for _ in range(n):
        h.invoke("run", 0)
        h.advance_time(useconds=dt_us)


def calls_of_one_tick(h, dt_us=TICK_US):
    before = len(h.port_calls)
    tick(h, dt_us=dt_us)
    return [(c.port, c.args) for c in h.port_calls[before:]]


def enable(h):
    h.send_command("SET_MODE", DetumbleMode.AUTO)


def run_until(h, state, limit=200):
    """Tick until the component is in ``state`` (checked before each tick); return ticks used."""
    for n in range(limit):
        if h.component.state == state:
            return n
        tick(h)
    raise AssertionError(f"never reached {state.name}; in {h.component.state.name}")


def started_levels(calls):
    return tuple(args[0] for port, args in calls if port.endswith("Start"))


def stop_ports(calls):
    return [port for port, _ in calls if port.endswith("Stop")]


@pytest.fixture
def h(fprime_harness):
    return make(fprime_harness)


# --- declarations -----------------------------------------------------------------------------

def test_declared_ids_severities_and_throttles(h):
    """Error Reporting / Parameter Telemetry: ids, severities and throttles as the flight FPP."""
    c = h.component
    assert c.param_id("GAIN") == BASE + 39 and c.param_id("DEADBAND_LOWER_THRESHOLD") == BASE + 1
    assert c.param_id("HYSTERESIS_AXIS") == BASE + 42 and c.param_id("Z_MINUS_SHAPE") == BASE + 37
    assert c.opcode("SET_MODE") == BASE
    assert c.event_id("EnableFailedSafeMode") == BASE and c.event_id("AngularVelocityRetrievalFailed") == BASE + 5
    assert c.channel_id("Mode") == BASE and c.channel_id("State") == BASE + 1
    spec = {e.name: e for e in c.spec.events}
    for name, severity, throttle in (
            ("EnableFailedSafeMode", Severity.WARNING_LO, 5), ("DetumbleStarted", Severity.ACTIVITY_LO, 1),
            ("DetumbleCompleted", Severity.ACTIVITY_LO, 1), ("MagneticFieldRetrievalFailed", Severity.WARNING_LO, 5),
            ("MagneticFieldSamplingPeriodRetrievalFailed", Severity.WARNING_LO, 5),
            ("AngularVelocityRetrievalFailed", Severity.WARNING_LO, 5), ("GainParamSet", Severity.ACTIVITY_HI, None)):
        assert (spec[name].severity, spec[name].throttle) == (severity, throttle), name
    # One echo event and one channel per parameter.
    for p in c.spec.params:
        stem = "".join(part.capitalize() for part in p.name.split("_"))
        assert f"{stem}ParamSet" in spec and c.spec.channel(f"{stem}Param")
    assert c.params["COOLDOWN_DURATION"].value == TimeIntervalValue(seconds=0, useconds=20_000)
    assert c.params["TORQUE_DURATION"].value == TimeIntervalValue(seconds=0, useconds=320_000)


# --- mode control -----------------------------------------------------------------------------

def test_mode_control_set_mode_command(h):
    """Mode Control: SET_MODE switches DISABLED ↔ AUTO; Mode and State are telemetered each run."""
    tick(h)
    assert h.tlm_values("Mode") == [DetumbleMode.DISABLED]
    assert h.tlm_values("State") == [DetumbleState.COOLDOWN]
    h.send_command("SET_MODE", DetumbleMode.AUTO, cmd_seq=4)
    h.assert_cmd_response(0, "SET_MODE", CmdResponse.OK, cmd_seq=4)
    tick(h, 3)
    assert h.tlm_values("Mode")[1:] == [DetumbleMode.AUTO] * 3
    assert h.tlm_values("State")[1:] == [DetumbleState.COOLDOWN, DetumbleState.COOLDOWN,
                                         DetumbleState.SENSING_ANGULAR_VELOCITY]
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    h.assert_cmd_response(1, "SET_MODE", CmdResponse.OK)
    tick(h)
    assert h.tlm_values("Mode")[-1] == DetumbleMode.DISABLED


def test_mode_and_state_written_first_on_every_run(h):
    """Mode Control: Mode then State open every run call's telemetry."""
    enable(h)
    for _ in range(4):
        before = len(h.telemetry)
        tick(h)
        assert [t.name for t in h.telemetry[before:before + 2]] == ["Mode", "State"]


def test_external_control_set_mode_port(h):
    """External Control: the setMode port sets the mode, with no command response."""
    h.invoke("setMode", DetumbleMode.AUTO)
    assert h.component.mode == DetumbleMode.AUTO
    h.assert_cmd_response_size(0)
    tick(h, 3)
    assert h.from_port("angularVelocityMagnitudeGet")  # the state machine is running
    h.invoke("setMode", DetumbleMode.DISABLED)
    assert h.component.mode == DetumbleMode.DISABLED


# --- system safe mode -------------------------------------------------------------------------

def drive_hysteresis(h, axis=HysteresisAxis.X_AXIS):
    h.component.params["HYSTERESIS_AXIS"].set(axis)
    h.sensors.rate = 800.0
    enable(h)
    run_until(h, DetumbleState.ACTUATING_HYSTERESIS)
    tick(h)  # actuate
    assert h.component.coils_driven


def test_system_safe_mode_disables_and_stops_coils(h):
    """System Safe Mode: SAFE_MODE forces DISABLED; the next run stops all five coils; NORMAL does
    not re-enable."""
    drive_hysteresis(h)
    h.invoke("systemModeChanged", SystemMode.SAFE_MODE)
    assert h.component.mode == DetumbleMode.DISABLED
    calls = calls_of_one_tick(h)
    assert stop_ports(calls) == STOPS and not started_levels(calls)
    h.invoke("systemModeChanged", SystemMode.NORMAL)
    assert h.component.mode == DetumbleMode.DISABLED
    tick(h)
    assert h.tlm_values("Mode")[-1] == DetumbleMode.DISABLED


def test_auto_refused_in_safe_mode_with_execution_error(h):
    """System Safe Mode / DEVIATION: SET_MODE(AUTO) in SAFE_MODE logs EnableFailedSafeMode and
    answers EXECUTION_ERROR (the flight code answers OK); the mode stays DISABLED."""
    h.set_port_return("getSystemMode", SystemMode.SAFE_MODE)
    h.send_command("SET_MODE", DetumbleMode.AUTO, cmd_seq=9)
    h.assert_cmd_response(0, "SET_MODE", CmdResponse.EXECUTION_ERROR, cmd_seq=9)
    h.assert_event_count("EnableFailedSafeMode", 1)
    assert h.component.mode == DetumbleMode.DISABLED
    # DISABLED is always accepted.
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    h.assert_cmd_response(1, "SET_MODE", CmdResponse.OK)
    # The setMode port refuses too, without a response.
    h.invoke("setMode", DetumbleMode.AUTO)
    assert h.component.mode == DetumbleMode.DISABLED
    h.assert_event_count("EnableFailedSafeMode", 2)
    h.assert_cmd_response_size(2)


def test_safe_mode_notification_refuses_auto_even_without_provider(h):
    """System Safe Mode: after a SAFE_MODE notification AUTO is refused until NORMAL arrives."""
    h.component.output_port("getSystemMode").disconnect(0)
    h.invoke("systemModeChanged", SystemMode.SAFE_MODE)
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.assert_cmd_response(0, "SET_MODE", CmdResponse.EXECUTION_ERROR)
    h.invoke("systemModeChanged", SystemMode.NORMAL)
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.assert_cmd_response(1, "SET_MODE", CmdResponse.OK)
    assert h.component.mode == DetumbleMode.AUTO


def test_enable_failed_event_throttled_at_five_and_cleared_by_success(h):
    """Error Reporting: EnableFailedSafeMode is throttled after 5 and cleared by an accepted request."""
    h.set_port_return("getSystemMode", SystemMode.SAFE_MODE)
    for _ in range(7):
        h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.assert_event_count("EnableFailedSafeMode", 5)
    h.set_port_return("getSystemMode", SystemMode.NORMAL)
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.set_port_return("getSystemMode", SystemMode.SAFE_MODE)
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.assert_event_count("EnableFailedSafeMode", 6)


# --- safe disable -----------------------------------------------------------------------------

def test_safe_disable_mid_actuation_stops_and_resets_everything(h):
    """Safe Disable / DEVIATION: DISABLED stops all five coils, resets to COOLDOWN and clears the
    timers and the B window (the flight code keeps timers and samples)."""
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    tick(h, 3)
    assert h.component.torque_start_time is not None and h.component.bdot.sample_count == 5
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    calls = calls_of_one_tick(h)
    assert [p for p, _ in calls] == STOPS
    c = h.component
    assert c.state == DetumbleState.COOLDOWN and c.torque_start_time is None
    assert c.cooldown_start_time is None and c.bdot.sample_count == 0 and not c.coils_driven
    # Re-enabled, the cycle starts over with a full cooldown.
    enable(h)
    assert calls_of_one_tick(h) == [] and calls_of_one_tick(h) == []
    assert [p for p, _ in calls_of_one_tick(h)] == ["angularVelocityMagnitudeGet"]


def test_safe_disable_mid_sampling_empties_the_window(h):
    """Safe Disable: a disable during B sampling drops the partial window."""
    enable(h)
    run_until(h, DetumbleState.SENSING_MAGNETIC_FIELD)
    tick(h, 3)
    assert h.component.bdot.sample_count == 3
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    tick(h)
    assert h.component.bdot.sample_count == 0


def test_disabled_stops_coils_once_even_in_cooldown(h):
    """Safe Disable / DEVIATION: the first run in DISABLED stops all coils, also in COOLDOWN (the
    flight code only stopped when the state was not COOLDOWN); later DISABLED runs send the coils
    nothing, as flown, so a coil the ground starts through its driver stays on (PROVES's
    drv2605_test.py). Each new DISABLED spell stops them once again."""
    assert stop_ports(calls_of_one_tick(h)) == STOPS  # starts DISABLED, in COOLDOWN
    for _ in range(3):
        assert stop_ports(calls_of_one_tick(h)) == []
    h.assert_from_port_size("angularVelocityMagnitudeGet", 0)
    enable(h)
    calls_of_one_tick(h)
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    assert stop_ports(calls_of_one_tick(h)) == STOPS
    assert stop_ports(calls_of_one_tick(h)) == []


# --- cooldown timing --------------------------------------------------------------------------

def test_cooldown_exactly_at_duration_and_one_microsecond_before(h):
    """Cooldown Timing / DEVIATION: COOLDOWN lasts at least COOLDOWN_DURATION and ends exactly at
    it (≥; the flight code waits for strictly more)."""
    enable(h)
    tick(h, dt_us=19_999)  # records the start at START
    assert h.component.state == DetumbleState.COOLDOWN
    tick(h, dt_us=1)  # now = start + 19 999 µs: stays
    assert h.component.state == DetumbleState.COOLDOWN
    tick(h)  # now = start + 20 000 µs: leaves
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY
    h.assert_from_port_size("angularVelocityMagnitudeGet", 0)  # the transition acts next call
    tick(h)
    h.assert_from_port("angularVelocityMagnitudeGet", 0, AngularUnit.DEG_PER_SEC)


def test_cooldown_follows_the_parameter(fprime_harness):
    """Cooldown Timing: a 1.5 s COOLDOWN_DURATION holds the state for 1.5 s."""
    h = make(fprime_harness, params={"COOLDOWN_DURATION": TimeIntervalValue(seconds=1, useconds=500_000)})
    enable(h)
    tick(h, dt_us=1_499_999)
    tick(h, dt_us=1)
    assert h.component.state == DetumbleState.COOLDOWN
    tick(h)
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY


def test_cooldown_after_actuation_lasts_at_least_the_duration(h):
    """Cooldown Timing: after TORQUING, sensing only resumes ≥ COOLDOWN_DURATION later."""
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    run_until(h, DetumbleState.COOLDOWN)
    end_of_torque = h.test_time.total_us - TICK_US
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h)
    first_sense = h.from_port("angularVelocityMagnitudeGet")
    assert len(first_sense) == 2
    sensed_at = h.test_time.total_us - TICK_US
    assert sensed_at - end_of_torque >= 20_000


# --- B-dot --------------------------------------------------------------------------------------

def test_full_bdot_cycle_call_by_call(h):
    """B-Dot Strategy: with defaults and exact 20 ms ticks: COOLDOWN (2 ticks) → 1 tick sensing ω →
    5 ticks sampling B → 17 ticks actuating (X+ 22, X− −22, Y+ 66, Y− −66, Z− −58, then all
    stopped) → COOLDOWN; coils off while B is sampled."""
    h.sensors.rate = 10.0
    enable(h)
    per_tick = [calls_of_one_tick(h) for _ in range(26)]
    assert per_tick[0] == [] and per_tick[1] == []  # cooldown: start, then 20 ms elapsed
    assert per_tick[2] == [("angularVelocityMagnitudeGet", (AngularUnit.DEG_PER_SEC,))]
    h.assert_event("DetumbleStarted", 0, 10.0)
    for n in range(3, 8):
        assert per_tick[n] == [("magneticFieldGet", ())], n
    assert h.tlm_values("TimeBetweenMagneticFieldReadings") == [TimeIntervalValue(seconds=0, useconds=80_000)]
    # Entry: the sampling period, then the five starts.
    assert per_tick[8][0] == ("magneticFieldSamplingPeriodGet", ())
    expected_starts = [(port, (level,)) for port, level in zip(STARTS, HAND_LEVELS, strict=True)]
    assert per_tick[8][1:] == expected_starts
    for n in range(9, 24):
        assert per_tick[n] == expected_starts, n
    # 17th actuating tick: 320 ms after the entry → start, then stop all, then COOLDOWN.
    assert per_tick[24] == expected_starts + [(port, ()) for port in STOPS]
    assert h.tlm_values("TorqueDuration") == [TimeIntervalValue(seconds=0, useconds=320_000)]
    assert per_tick[25] == []
    assert h.component.state == DetumbleState.COOLDOWN and h.component.bdot.sample_count == 0
    states = h.tlm_values("State")
    assert states[2:9] == [DetumbleState.SENSING_ANGULAR_VELOCITY] + [DetumbleState.SENSING_MAGNETIC_FIELD] * 5 \
        + [DetumbleState.ACTUATING_BDOT]
    assert h.tlm_values("DetumbleStrategy") == [DetumbleStrategy.BDOT]
    assert h.tlm_values("AngularVelocityMagnitude") == [10.0]


def test_torque_duration_exact_edge_and_one_microsecond_before(h):
    """B-Dot Strategy / Cooldown Timing: actuation ends when now − start ≥ TORQUE_DURATION, not
    1 µs earlier."""
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    tick(h, dt_us=319_999)  # entry at t_e
    calls = calls_of_one_tick(h, dt_us=1)  # t_e + 319 999 µs
    assert not stop_ports(calls) and h.component.state == DetumbleState.ACTUATING_BDOT
    calls = calls_of_one_tick(h)  # t_e + 320 000 µs
    assert stop_ports(calls) == STOPS and h.component.state == DetumbleState.COOLDOWN
    assert h.tlm_values("TorqueDuration") == [TimeIntervalValue(seconds=0, useconds=320_000)]


def test_bdot_uses_mean_timestamp_spacing(h):
    """DEVIATION (§6): Δt comes from the samples' timestamps (20 ms), not the 10 ms period, so the
    drive matches the hand values; the flight Δt would double Ḃ and the levels."""
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    assert started_levels(calls_of_one_tick(h)) == HAND_LEVELS


def test_configure_after_load_uses_loaded_coil_parameters(fprime_harness):
    """DEVIATION (start-up): parameters load before configure(), so the B-dot drive uses the loaded
    coil values (the flight code configured first and drove zero levels)."""
    # 26 Ω halves imax on X+: the 0.01 A·m² request becomes 2 · 21.85 = 43.7 → 44.
    h = make(fprime_harness, params={"X_PLUS_RESISTANCE": 26.0})
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    levels = started_levels(calls_of_one_tick(h))
    assert levels[0] == 44 and levels[1:] == HAND_LEVELS[1:]


def test_coils_never_on_while_sampling_b(h):
    """B-Dot Strategy: every magneticFieldGet happens with all coils stopped (after hysteresis and
    after a B-dot pulse)."""
    drive_hysteresis(h)
    h.sensors.rate = 10.0
    on = True
    for _ in range(120):
        before = len(h.port_calls)
        tick(h)
        for call in h.port_calls[before:]:
            if call.port.endswith("Start"):
                on = True
            elif call.port == "xPlusStop":
                on = False
            elif call.port == "magneticFieldGet":
                assert not on
    assert len(h.from_port("magneticFieldGet")) >= 10  # several full windows were checked


# --- hysteresis -------------------------------------------------------------------------------

@pytest.mark.parametrize("axis, levels", [
    (HysteresisAxis.X_AXIS, (127, -127, 0, 0, 0)),
    (HysteresisAxis.Y_AXIS, (0, 0, 127, -127, 0)),
    (HysteresisAxis.Z_AXIS, (0, 0, 0, 0, -127)),
])
def test_hysteresis_drive_pattern_per_axis(fprime_harness, axis, levels):
    """Hysteresis Strategy: above BDOT_MAX_THRESHOLD the HYSTERESIS_AXIS coils are driven full scale
    (X: X+ 127, X− −127; Y: Y+ 127, Y− −127; Z: Z− −127), then COOLDOWN at once."""
    h = make(fprime_harness, params={"HYSTERESIS_AXIS": axis})
    h.sensors.rate = 720.0  # at the threshold
    enable(h)
    run_until(h, DetumbleState.ACTUATING_HYSTERESIS)
    assert h.tlm_values("DetumbleStrategy") == [DetumbleStrategy.HYSTERESIS]
    calls = calls_of_one_tick(h)
    assert calls == [(port, (level,)) for port, level in zip(STARTS, levels, strict=True)]
    assert h.component.state == DetumbleState.COOLDOWN
    h.assert_event("DetumbleStarted", 0, 720.0)


def test_hysteresis_drive_stays_on_then_stops_when_leaving(h):
    """Hysteresis Strategy: the drive stays on through cooldown while HYSTERESIS persists; leaving it
    for B-dot stops the coils first."""
    drive_hysteresis(h)
    before = len(h.port_calls)
    run_until(h, DetumbleState.ACTUATING_HYSTERESIS)
    assert not stop_ports([(c.port, c.args) for c in h.port_calls[before:]])
    tick(h)
    h.sensors.rate = 100.0
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    calls = calls_of_one_tick(h)
    assert calls == [("angularVelocityMagnitudeGet", (AngularUnit.DEG_PER_SEC,))] + [(p, ()) for p in STOPS]
    assert h.component.state == DetumbleState.SENSING_MAGNETIC_FIELD


def test_idle_stops_a_running_drive_and_logs_completion_once(h):
    """Hysteresis Strategy / Deadband Activation: dropping below the lower threshold stops the drive,
    logs DetumbleCompleted once, and stays sensing."""
    drive_hysteresis(h)
    h.sensors.rate = 1.0
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    calls = calls_of_one_tick(h)
    assert stop_ports(calls) == STOPS
    h.assert_event("DetumbleCompleted", 0, 1.0)
    for _ in range(5):
        assert calls_of_one_tick(h) == [("angularVelocityMagnitudeGet", (AngularUnit.DEG_PER_SEC,))]
    h.assert_event_count("DetumbleCompleted", 1)  # throttle 1
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY


# --- deadband at component level ---------------------------------------------------------------

def test_deadband_memory_through_the_component(h):
    """Deadband Activation: after idling, 6 deg/s stays IDLE; 9 deg/s starts B-dot; B-dot then
    continues at 6 deg/s and stops below 5 deg/s. Started/Completed are logged once per episode."""
    h.sensors.rate = 4.0
    enable(h)
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h)
    h.sensors.rate = 6.0
    tick(h, 3)
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY
    h.assert_event_count("DetumbleStarted", 0)
    h.sensors.rate = 9.0
    tick(h)
    assert h.component.state == DetumbleState.SENSING_MAGNETIC_FIELD
    h.sensors.rate = 6.0
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h)
    assert h.component.state == DetumbleState.SENSING_MAGNETIC_FIELD  # continues inside the band
    h.assert_event_count("DetumbleStarted", 1)  # one episode, one start event
    h.sensors.rate = 4.9
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h)
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY
    assert h.events_named("DetumbleCompleted") == [(4.0,), (4.9,)]
    assert h.tlm_values("DetumbleStrategy")[-1] == DetumbleStrategy.IDLE
    # A new episode logs DetumbleStarted again (Completed cleared its throttle).
    h.sensors.rate = 50.0
    tick(h)
    h.assert_event_count("DetumbleStarted", 2)


def test_changed_thresholds_take_effect(h):
    """Deadband Activation: a new DEADBAND_UPPER_THRESHOLD applies at the next decision."""
    h.sensors.rate = 4.0
    enable(h)
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h)
    h.param_set("DEADBAND_UPPER_THRESHOLD", 6.5)
    h.param_send("DEADBAND_UPPER_THRESHOLD")
    h.sensors.rate = 7.0
    tick(h)
    assert h.component.state == DetumbleState.SENSING_MAGNETIC_FIELD


# --- error reporting --------------------------------------------------------------------------

def test_angular_velocity_failure_event_stays_and_throttles(h):
    """Error Reporting: a failed |ω| read logs AngularVelocityRetrievalFailed (throttle 5) and stays
    in SENSING_ANGULAR_VELOCITY; a good read clears the throttle."""
    h.sensors.rate_ok = False
    enable(h)
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h, 8)
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY
    h.assert_event_count("AngularVelocityRetrievalFailed", 5)
    h.assert_from_port_size("angularVelocityMagnitudeGet", 8)
    assert h.tlm_values("AngularVelocityMagnitude") == [] and h.tlm_values("DetumbleStrategy") == []
    h.sensors.rate_ok = True
    h.sensors.rate = 1.0
    tick(h)
    h.sensors.rate_ok = False
    tick(h)
    h.assert_event_count("AngularVelocityRetrievalFailed", 6)
    assert h.events[-1].severity == Severity.WARNING_LO


def test_unconnected_rate_provider_is_a_retrieval_failure(h):
    """Error Reporting: an unconnected angularVelocityMagnitudeGet counts as a failed read."""
    h.component.output_port("angularVelocityMagnitudeGet").disconnect(0)
    enable(h)
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    tick(h)
    h.assert_event_count("AngularVelocityRetrievalFailed", 1)


def test_magnetic_field_failure_event_and_retry(h):
    """Error Reporting: a failed B read logs MagneticFieldRetrievalFailed, adds no sample and stays."""
    enable(h)
    run_until(h, DetumbleState.SENSING_MAGNETIC_FIELD)
    tick(h, 2)
    h.sensors.field_ok = False
    tick(h, 7)
    assert h.component.bdot.sample_count == 2
    assert h.component.state == DetumbleState.SENSING_MAGNETIC_FIELD
    h.assert_event_count("MagneticFieldRetrievalFailed", 5)
    h.sensors.field_ok = True
    tick(h, 3)
    assert h.component.state == DetumbleState.ACTUATING_BDOT


def test_sampling_period_failure_abandons_the_cycle_without_a_pulse(h):
    """Error Reporting / DEVIATION: a failed sampling-period read logs
    MagneticFieldSamplingPeriodRetrievalFailed, stops the coils, empties the window and returns to
    COOLDOWN with no actuation (the flight code still fires one stale pulse)."""
    h.sensors.period = Result(TimeIntervalValue(), Success.FAILURE)
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    calls = calls_of_one_tick(h)
    assert calls == [("magneticFieldSamplingPeriodGet", ())] + [(p, ()) for p in STOPS]
    h.assert_event_count("MagneticFieldSamplingPeriodRetrievalFailed", 1)
    assert h.component.state == DetumbleState.COOLDOWN and h.component.bdot.sample_count == 0
    assert h.component.torque_start_time is None
    h.assert_from_port_size("xPlusStart", 0)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_rate_is_a_failed_read_and_keeps_coils_safe(h, bad):
    """Error Reporting: a NaN/inf |ω| never raises, selects nothing, logs
    AngularVelocityRetrievalFailed and stops a running hysteresis drive."""
    drive_hysteresis(h)
    h.sensors.rate = bad
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    calls = calls_of_one_tick(h)
    assert stop_ports(calls) == STOPS and not started_levels(calls)
    h.assert_event_count("AngularVelocityRetrievalFailed", 1)
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY
    assert h.tlm_values("AngularVelocityMagnitude") == [800.0]
    assert h.component.handler_faults == 0


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_field_is_a_failed_read(h, bad):
    """Error Reporting: a NaN/inf B component never raises or enters the window; it logs
    MagneticFieldRetrievalFailed and the coils stay off."""
    enable(h)
    run_until(h, DetumbleState.SENSING_MAGNETIC_FIELD)
    h.sensors.field_override = (0.2, bad, 0.1)
    tick(h, 3)
    assert h.component.bdot.sample_count == 0
    h.assert_event_count("MagneticFieldRetrievalFailed", 3)
    h.assert_from_port_size("xPlusStart", 0)
    assert h.component.handler_faults == 0


def test_a_raising_provider_never_escapes_run(h):
    """Error Reporting: an exception inside a provider does not escape run; the coils are stopped
    and the cycle restarts from COOLDOWN."""
    def broken(unit):
        raise RuntimeError("gyro bus fault")
    drive_hysteresis(h)
    h.set_port_handler("angularVelocityMagnitudeGet", broken)
    run_until(h, DetumbleState.SENSING_ANGULAR_VELOCITY)
    calls = calls_of_one_tick(h)  # must not raise
    assert stop_ports(calls) == STOPS
    assert h.component.handler_faults == 1 and h.component.state == DetumbleState.COOLDOWN


def test_clock_going_backwards_restarts_the_cooldown(fprime_harness):
    """Cooldown Timing: a clock that jumps back restarts the cooldown instead of raising."""
    h = make(fprime_harness)
    enable(h)
    tick(h)
    h.set_test_time(Time(TimeBase.TB_WORKSTATION_TIME, 0, 10, 0))
    tick(h)
    assert h.component.state == DetumbleState.COOLDOWN
    tick(h)
    assert h.component.state == DetumbleState.SENSING_ANGULAR_VELOCITY


# --- parameters ---------------------------------------------------------------------------------

def test_parameter_telemetry_after_configuration(fprime_harness):
    """Parameter Telemetry: after parameters load, every parameter channel (all five coils,
    including the per-coil Turns channels) is written once with the loaded value."""
    h = make(fprime_harness, params={"X_MINUS_WIDTH": 0.05, "Y_TURNS": 90.0,
                                     "Z_MINUS_SHAPE": CoilShape.RECTANGULAR}, load=False)
    assert h.telemetry == []
    h.load_parameters()
    c = h.component
    for name, bound in c.params.items():
        stem = "".join(part.capitalize() for part in name.split("_"))
        assert h.tlm_values(f"{stem}Param") == [bound.value], name
    assert h.tlm_values("XMinusWidthParam") == [0.05]
    assert h.tlm_values("YPlusTurnsParam") == [90.0] and h.tlm_values("YMinusTurnsParam") == [90.0]
    assert h.tlm_values("XPlusTurnsParam") == [96.0] and h.tlm_values("ZMinusTurnsParam") == [153.0]
    assert h.tlm_values("ZMinusShapeParam") == [CoilShape.RECTANGULAR]
    assert c.params["Y_TURNS"].validity == ParamValid.VALID
    assert c.magnetorquers["y_minus"].turns == 90.0


def test_parameter_set_echoes_that_parameter_only(h):
    """Parameter Telemetry / DEVIATION: setting DEADBAND_UPPER_THRESHOLD logs only its own
    ParamSet event (the flight code's missing breaks also logged DEADBAND_LOWER and GAIN)."""
    h.clear_history()
    h.param_set("DEADBAND_UPPER_THRESHOLD", 9.5)
    h.param_send("DEADBAND_UPPER_THRESHOLD", cmd_seq=2)
    h.assert_cmd_response(0, "DEADBAND_UPPER_THRESHOLD_PRM_SET", CmdResponse.OK, cmd_seq=2)
    assert [e.name for e in h.events] == ["DeadbandUpperThresholdParamSet"]
    h.assert_event("DeadbandUpperThresholdParamSet", 0, 9.5)
    assert h.events[0].severity == Severity.ACTIVITY_HI
    assert [t.name for t in h.telemetry] == ["DeadbandUpperThresholdParam"]
    h.clear_history()
    h.param_set("COOLDOWN_DURATION", TimeIntervalValue(seconds=0, useconds=40_000))
    h.param_send("COOLDOWN_DURATION")
    assert h.events_named("CooldownDurationParamSet") == [(TimeIntervalValue(seconds=0, useconds=40_000),)]
    assert len(h.events) == 1


def test_coil_parameter_set_reconfigures_that_coil(h):
    """DEVIATION (re-configuration): X_MINUS_RESISTANCE set by command re-configures the X− coil:
    26 Ω halves imax, so the 0.01 A·m² request drives −44 instead of −22."""
    h.param_set("X_MINUS_RESISTANCE", 26.0)
    h.param_send("X_MINUS_RESISTANCE")
    h.assert_event("XMinusResistanceParamSet", 0, 26.0)
    assert h.tlm_values("XMinusResistanceParam")[-1] == 26.0
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    levels = started_levels(calls_of_one_tick(h))
    assert levels == (22, -44, 66, -66, -58)


def test_turns_parameter_set_updates_both_coils_and_their_channels(h):
    """Parameter Telemetry: X_TURNS set → XTurnsParamSet, XTurnsParam and both per-coil Turns
    channels; both X coils re-configured."""
    h.clear_history()
    h.param_set("X_TURNS", 48.0)
    h.param_send("X_TURNS")
    assert [e.name for e in h.events] == ["XTurnsParamSet"]
    assert sorted(t.name for t in h.telemetry) == ["XMinusTurnsParam", "XPlusTurnsParam", "XTurnsParam"]
    assert all(t.value == 48.0 for t in h.telemetry)
    c = h.component
    assert c.magnetorquers["x_plus"].turns == 48.0 and c.magnetorquers["x_minus"].turns == 48.0
    assert c.magnetorquers["y_plus"].turns == 96.0


# --- external dipole provider -------------------------------------------------------------------

def test_connected_dipole_provider_replaces_internal_bdot(fprime_harness):
    """BDot-001 (integration): with dipoleMomentGet connected its dipole drives the coils; it is
    read once per actuation, at entry while the coils are off."""
    h = make(fprime_harness, external=True)
    h.set_port_return("dipoleMomentGet", Result(DipoleMoment(x=-0.03, y=0.01, z=-0.004), Success.SUCCESS))
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    first = calls_of_one_tick(h)
    assert [p for p, _ in first[:2]] == ["magneticFieldSamplingPeriodGet", "dipoleMomentGet"]
    assert started_levels(first) == (-66, 66, 22, -22, 58)
    run_until(h, DetumbleState.COOLDOWN)
    h.assert_from_port_size("dipoleMomentGet", 1)


@pytest.mark.parametrize("reply", [
    Result(DipoleMoment(), Success.FAILURE),
    Result(DipoleMoment(x=math.nan, y=0.0, z=0.0), Success.SUCCESS),
])
def test_dipole_provider_failure_skips_the_pulse(fprime_harness, reply):
    """Error Reporting: a failed or non-finite provider dipole logs DipoleMomentRetrievalFailed and
    returns to COOLDOWN without driving the coils."""
    h = make(fprime_harness, external=True)
    h.set_port_return("dipoleMomentGet", reply)
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    calls = calls_of_one_tick(h)
    assert not started_levels(calls) and stop_ports(calls) == STOPS
    h.assert_event_count("DipoleMomentRetrievalFailed", 1)
    assert h.component.state == DetumbleState.COOLDOWN


def test_every_declared_channel_is_written(h):
    """Parameter Telemetry / DEVIATION: every declared channel is written during start-up and one
    B-dot cycle (several were never written in the flight code)."""
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    run_until(h, DetumbleState.COOLDOWN)
    written = {t.name for t in h.telemetry}
    declared = {c.name for c in h.component.spec.own_channels}
    assert declared - written == set()


# --- actuator health (issue #16 finding 2; addition to the PROVES design) ----------------------
# A coil whose stop answers FAILURE is reported WARNING_HI and isolated until ENABLE_COIL.

TORQUE_TICKS = 17  # ticks of one ACTUATING_BDOT period with the default TORQUE_DURATION (320 ms)


def calls_to(h, port, since):
    return [c for c in h.port_calls[since:] if c.port == port]


def one_cycle(h):
    """From wherever the manager is, run until the end of the next torque period."""
    run_until(h, DetumbleState.ACTUATING_BDOT)
    run_until(h, DetumbleState.COOLDOWN, limit=TORQUE_TICKS + 2)


def test_failed_stop_isolates_the_coil_within_one_torque_period(h):
    """Actuator Health: the X+ stop answers FAILURE at the end of a torque period → CoilStopFailed
    (WARNING_HI) naming X_PLUS in that same tick, IsolatedCoils bit 0 set, CoilStopFailures = 1."""
    h.set_port_return("xPlusStop", Success.FAILURE)
    enable(h)
    one_cycle(h)
    h.assert_event("CoilStopFailed", 0, MagnetorquerFace.X_PLUS)
    assert h.component.spec.event("CoilStopFailed").severity == Severity.WARNING_HI
    assert h.tlm_values("IsolatedCoils")[-1] == 0b1
    assert h.tlm_values("CoilStopFailures")[-1] == 1
    assert h.component.isolated_faces == (MagnetorquerFace.X_PLUS,)


def test_an_isolated_coil_is_never_driven_while_the_others_are(h):
    """Actuator Health: after isolation no start or stop reaches X+ for three more B-dot cycles, the
    four other coils are started and stopped as before, and the event is not repeated."""
    h.set_port_return("xPlusStop", Success.FAILURE)
    enable(h)
    one_cycle(h)
    since = len(h.port_calls)
    for _ in range(3):
        one_cycle(h)
    assert calls_to(h, "xPlusStart", since) == [] and calls_to(h, "xPlusStop", since) == []
    for start, stop in zip(STARTS[1:], STOPS[1:], strict=True):
        assert len(calls_to(h, start, since)) == 3 * TORQUE_TICKS, start
        assert len(calls_to(h, stop, since)) == 3, stop
    assert len([e for e in h.events if e.name == "CoilStopFailed"]) == 1


def test_enable_coil_returns_it_to_service(h):
    """Actuator Health: ENABLE_COIL X_PLUS answers OK with CoilEnabled; X+ is driven in the next
    cycle; if its stop fails again it is isolated again."""
    h.set_port_return("xPlusStop", Success.FAILURE)
    enable(h)
    one_cycle(h)
    h.send_command("ENABLE_COIL", MagnetorquerFace.X_PLUS)
    h.assert_cmd_response(len(h.cmd_responses) - 1, "ENABLE_COIL", CmdResponse.OK)
    h.assert_event("CoilEnabled", 0, MagnetorquerFace.X_PLUS)
    assert h.tlm_values("IsolatedCoils")[-1] == 0
    h.set_port_return("xPlusStop", Success.SUCCESS)
    since = len(h.port_calls)
    one_cycle(h)
    assert len(calls_to(h, "xPlusStart", since)) == TORQUE_TICKS and len(calls_to(h, "xPlusStop", since)) == 1
    assert h.component.isolated_faces == ()
    h.set_port_return("xPlusStop", Success.FAILURE)
    one_cycle(h)
    assert h.component.isolated_faces == (MagnetorquerFace.X_PLUS,)


def test_isolate_coil_command_stops_once_then_leaves_it_alone(h):
    """Actuator Health: ISOLATE_COIL Z_MINUS sends one stop, answers OK with CoilIsolatedByCommand,
    and Z− gets no further call in a whole B-dot cycle."""
    enable(h)
    since = len(h.port_calls)
    h.send_command("ISOLATE_COIL", MagnetorquerFace.Z_MINUS)
    h.assert_cmd_response(len(h.cmd_responses) - 1, "ISOLATE_COIL", CmdResponse.OK)
    h.assert_event("CoilIsolatedByCommand", 0, MagnetorquerFace.Z_MINUS)
    assert len(calls_to(h, "zMinusStop", since)) == 1
    since = len(h.port_calls)
    one_cycle(h)
    assert calls_to(h, "zMinusStart", since) == [] and calls_to(h, "zMinusStop", since) == []
    assert h.tlm_values("IsolatedCoils")[-1] == 1 << 5


def test_stop_failure_when_disabled_mid_actuation_isolates_too(h):
    """Actuator Health: coils on in ACTUATING_BDOT, then SET_MODE DISABLED with the Y− stop answering
    FAILURE: Y− is isolated at that run; the next DISABLED spell stops the other coils and sends Y−
    nothing."""
    enable(h)
    run_until(h, DetumbleState.ACTUATING_BDOT)
    tick(h, 3)  # coils on
    h.set_port_return("yMinusStop", Success.FAILURE)
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    tick(h)
    h.assert_event("CoilStopFailed", 0, MagnetorquerFace.Y_MINUS)
    since = len(h.port_calls)
    tick(h, 5)  # stopped once already: nothing more while DISABLED
    assert calls_to(h, "yMinusStop", since) == [] and calls_to(h, "yPlusStop", since) == []
    enable(h)
    tick(h)
    h.send_command("SET_MODE", DetumbleMode.DISABLED)
    tick(h, 3)
    assert calls_to(h, "yMinusStop", since) == [] and len(calls_to(h, "yPlusStop", since)) == 1


def test_a_failing_stop_of_a_coil_that_was_never_on_isolates_nothing(h):
    """Actuator Health: an unpowered or uninitialised driver answers FAILURE to everything; in mode
    DISABLED (no start sent) and through B-dot cycles whose starts fail, its failing stops isolate
    nothing — the coil was never switched on."""
    h.set_port_return("zMinusStop", Success.FAILURE)
    h.set_port_return("zMinusStart", Success.FAILURE)
    tick(h, 5)
    enable(h)
    for _ in range(3):
        one_cycle(h)
    assert h.component.isolated_faces == () and not h.events_named("CoilStopFailed")


def test_successful_stops_never_isolate(h):
    """Actuator Health: with every stop answering SUCCESS, ten cycles isolate nothing and emit no
    CoilStopFailed (the detection cannot fire on healthy coils)."""
    enable(h)
    for _ in range(10):
        one_cycle(h)
    assert h.component.isolated_faces == () and not [e for e in h.events if e.name == "CoilStopFailed"]


def test_magnetorquer_face_is_the_coil_layout():
    """Actuator Health: the command/event enum has exactly coil_layout's coil faces, names and numbers."""
    from detumble.control.coil_layout import COIL_FACES
    assert [(f.name, int(f)) for f in MagnetorquerFace] == [(f.name, int(f)) for f in COIL_FACES]

