"""Housekeeping as flown: Watchdog, ResetManager, StartupManager, RtcManager."""

import datetime as dt

import pytest

from detumble.proves.reset_manager import ResetManager
from detumble.proves.rtc_manager import RtcManager, TimeData
from detumble.proves.startup_manager import StartupManager
from detumble.proves.watchdog import Watchdog
from fprime_lite import CmdResponse, Severity
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.model.fw_types import TimeIntervalValue
from detumble.drivers.spacecraft import SimulatedSpacecraft


@pytest.fixture
def craft(make_craft, tmp_path):
    c = make_craft()
    c.use_flash_dir(str(tmp_path / "flash"))
    return c


# --- Watchdog ----------------------------------------------------------------------------------

def test_watchdog_pets_and_counts(fprime_harness, craft):
    """WD-001: every run toggles the GPIO and counts WatchdogTransitions; STOP_WATCHDOG calls
    prepareForReboot, then stops (WatchdogStop); START_WATCHDOG resumes (WatchdogStart)."""
    h = fprime_harness(Watchdog("watchdog", craft, base_id=0x10015000))
    for _ in range(3):
        h.invoke("run", 0)
    assert h.tlm_values("WatchdogTransitions") == [1, 2, 3]
    h.send_command("STOP_WATCHDOG", cmd_seq=5)
    h.assert_cmd_response(0, "STOP_WATCHDOG", CmdResponse.OK, cmd_seq=5)
    h.assert_from_port_size("prepareForReboot", 1)
    h.assert_event_count("WatchdogStop", 1)
    h.invoke("run", 0)
    assert h.tlm_values("WatchdogTransitions") == [1, 2, 3]
    h.send_command("START_WATCHDOG")
    h.assert_event_count("WatchdogStart", 1)
    assert h.events[-1].severity == Severity.ACTIVITY_HI
    h.invoke("run", 0)
    assert h.tlm_values("WatchdogTransitions")[-1] == 4


def test_stopped_watchdog_resets_the_flight_computer(default_scenario):
    """WD-002: the hardware watchdog pulls the reset line timeout_s after the last pet; the stop
    port (no prepareForReboot) lets it expire; while petted it never does."""
    sched = Scheduler()
    craft = SimulatedSpacecraft.for_scheduler(default_scenario, sched)
    resets = []
    craft.reset_handler = resets.append
    wd = Watchdog("watchdog", craft, timeout_s=5.0)
    sched.call_every(1_000_000, lambda: wd.run(0), start_us=1_000_000)
    sched.run(until_us=30_000_000)
    assert resets == []
    wd.stop()                    # the last pet was the run at 30 s
    stopped_at = 30_000_000
    sched.run(until_us=stopped_at + 4_900_000)
    assert resets == []
    sched.run(until_us=stopped_at + 5_100_000)
    assert resets == ["watchdog"]


# --- ResetManager ------------------------------------------------------------------------------

@pytest.mark.parametrize("command, event, kind", [("COLD_RESET", "INITIATE_COLD_RESET", "cold"),
                                                  ("WARM_RESET", "INITIATE_WARM_RESET", "warm")])
def test_reset_commands(fprime_harness, craft, command, event, kind):
    """RST-001: COLD_RESET / WARM_RESET log INITIATE_*_RESET (ids 0 / 1), call prepareForReboot and
    pull the reset line; the command is never answered (the processor resets)."""
    resets = []
    craft.reset_handler = resets.append
    h = fprime_harness(ResetManager("resetManager", craft, base_id=0x10037000))
    assert h.component.event_id(event) == 0x10037000 + (0 if kind == "cold" else 1)
    h.send_command(command)
    h.assert_cmd_response_size(0)
    h.assert_event_count(event, 1)
    h.assert_from_port_size("prepareForReboot", 1)
    assert resets == [kind]
    h.invoke("coldReset")
    assert resets == [kind, "cold"]


def test_reset_without_flight_software_is_a_clear_error(craft):
    """RST-002: a reset line with nothing attached says so."""
    with pytest.raises(RuntimeError, match="no flight software"):
        craft.request_reset()


# --- StartupManager ----------------------------------------------------------------------------

def test_boot_count_increments_per_boot(fprime_harness, craft):
    """SUM-001: the first run of each boot increments BOOT_COUNT_FILE on the flash (1, 2, …);
    GET_BOOT_COUNT logs CurrentBootCount without incrementing; BootCount is written every run."""
    for boot in (1, 2, 3):
        h = fprime_harness(StartupManager("startupManager", craft, base_id=0x1003B000))
        h.invoke("run", 0)
        h.invoke("run", 0)
        assert h.tlm_values("BootCount") == [boot, boot]
        h.send_command("GET_BOOT_COUNT")
        h.assert_event("CurrentBootCount", 0, boot)
    with open(f"{craft.flash_dir}/boot_count.bin", "rb") as fh:
        assert int.from_bytes(fh.read(), "big") == 3


def test_quiescence_wait(fprime_harness, craft):
    """SUM-002: WAIT_FOR_QUIESCENCE answers OK only when QUIESCENCE_TIME has passed since the first
    boot's start time (kept on the flash across boots); ARMED false answers at the next run;
    QuiescenceEndTime is start + QUIESCENCE_TIME."""
    h = fprime_harness(StartupManager("startupManager", craft))
    h.set_test_time(craft.now())
    h.param_set("QUIESCENCE_TIME", TimeIntervalValue(60, 0))
    h.load_parameters()
    h.invoke("run", 0)
    start = craft.now()
    assert h.tlm_values("QuiescenceEndTime")[0].total_us == start.total_us + 60_000_000
    h.send_command("WAIT_FOR_QUIESCENCE", cmd_seq=9)
    h.advance_time(59)
    h.invoke("run", 0)
    h.assert_cmd_response_size(0)
    h.advance_time(1)
    h.invoke("run", 0)
    h.assert_cmd_response(0, "WAIT_FOR_QUIESCENCE", CmdResponse.OK, cmd_seq=9)
    h2 = fprime_harness(StartupManager("startupManager", craft))   # next boot: same start time
    h2.set_test_time(craft.now())
    h2.param_set("QUIESCENCE_TIME", TimeIntervalValue(60, 0))
    h2.param_set("ARMED", False)
    h2.load_parameters()
    h2.invoke("run", 0)
    assert h2.component.quiescence_start.total_us == start.total_us
    h2.send_command("WAIT_FOR_QUIESCENCE")
    h2.invoke("run", 0)
    h2.assert_cmd_response(0, "WAIT_FOR_QUIESCENCE", CmdResponse.OK)


def test_startup_sequence_events(fprime_harness, craft):
    """SUM-003: completeSequence reports StartupSequenceFinished / Failed for STARTUP_SEQUENCE_FILE only."""
    h = fprime_harness(StartupManager("startupManager", craft))
    h.invoke("sequenceStarted", "/seq/startup.bin")
    h.invoke("completeSequence", 0, 0, CmdResponse.OK)
    h.invoke("completeSequence", 0, 0, CmdResponse.EXECUTION_ERROR)
    h.invoke("sequenceStarted", "/seq/other.bin")
    h.invoke("completeSequence", 0, 0, CmdResponse.OK)
    h.assert_event_count("StartupSequenceFinished", 1)
    h.assert_event("StartupSequenceFailed", 0, CmdResponse.EXECUTION_ERROR)


# --- RtcManager --------------------------------------------------------------------------------

def test_time_set_moves_the_clock(fprime_harness, craft):
    """RTC-001: TIME_SET sets the RTC (the deployment clock) to the UTC time given, cancels the
    sequences and logs TimeSet with the previous time; timeGetPort returns the new time."""
    h = fprime_harness(RtcManager("rtcManager", craft, base_id=0x10016000))
    craft.clock.set_us(2_500_000)
    before = craft.now()
    h.set_test_time(before)
    h.send_command("TIME_SET", TimeData(2026, 12, 1, 12, 30, 5), cmd_seq=3)
    h.assert_cmd_response(0, "TIME_SET", CmdResponse.OK, cmd_seq=3)
    h.assert_event("TimeSet", 0, before.total_us // 1_000_000, before.total_us % 1_000_000)
    h.assert_from_port_size("cancelSequences", 3)
    assert h.component.utc_now() == dt.datetime(2026, 12, 1, 12, 30, 5, 500_000, tzinfo=dt.timezone.utc)
    assert h.invoke("timeGetPort").total_us == craft.clock.now().total_us


def test_time_set_validation(fprime_harness, craft):
    """RTC-002: every invalid field has its own WARNING_HI event (flight ids 5..10), then
    TimeNotSet(EINVAL) and VALIDATION_ERROR; the clock is untouched."""
    h = fprime_harness(RtcManager("rtcManager", craft, base_id=0x10016000))
    epoch = craft.clock.epoch_us
    h.send_command("TIME_SET", TimeData(1899, 13, 0, 24, 60, 60))
    h.assert_cmd_response(0, "TIME_SET", CmdResponse.VALIDATION_ERROR)
    assert [e.name for e in h.events] == ["YearValidationFailed", "MonthValidationFailed", "DayValidationFailed",
                                          "HourValidationFailed", "MinuteValidationFailed",
                                          "SecondValidationFailed", "TimeNotSet"]
    assert h.component.event_id("SecondValidationFailed") == 0x10016000 + 10
    h.assert_event("TimeNotSet", 0, 22)
    assert craft.clock.epoch_us == epoch


def test_alarm(fprime_harness, default_scenario):
    """RTC-003: ALARM_SET arms one alarm for a future time; it rings (AlarmTriggered(0),
    alarmTriggered) when the clock gets there; a second ALARM_SET, a past time, ALARM_LIST and
    ALARM_CANCEL behave as flown."""
    sched = Scheduler()
    craft = SimulatedSpacecraft.for_scheduler(default_scenario, sched)
    craft.clock.epoch_us = 1_780_000_000 * 1_000_000
    h = fprime_harness(RtcManager("rtcManager", craft))
    h.set_test_time(craft.now())
    now = dt.datetime.fromtimestamp(1_780_000_000, dt.timezone.utc)
    soon = now + dt.timedelta(seconds=30)
    t = TimeData(soon.year, soon.month, soon.day, soon.hour, soon.minute, soon.second)
    h.send_command("ALARM_SET", t)
    h.assert_cmd_response(0, "ALARM_SET", CmdResponse.OK)
    h.assert_event("AlarmSet", 0, 0, t)
    h.send_command("ALARM_SET", t)
    h.assert_cmd_response(1, "ALARM_SET", CmdResponse.EXECUTION_ERROR)
    h.send_command("ALARM_LIST")
    h.assert_event("AlarmSet", 1, 0, t)
    sched.run(until_us=29_000_000)
    h.assert_no_event("AlarmTriggered")
    sched.run(until_us=31_000_000)
    h.assert_event("AlarmTriggered", 0, 0)
    h.assert_from_port_size("alarmTriggered", 1)
    past = TimeData(now.year, now.month, now.day, now.hour, now.minute, now.second)
    h.send_command("ALARM_SET", past)
    h.assert_event("AlarmNotSet", 1, past, 22)
    h.send_command("ALARM_CANCEL", 0)
    h.assert_event("AlarmNotCanceled", 0, 0, 0)
    h.send_command("ALARM_SET", TimeData(soon.year + 1, 1, 1, 0, 0, 0))
    h.send_command("ALARM_CANCEL", 0)
    h.assert_event("AlarmCanceled", 0, 0)
    h.send_command("ALARM_LIST")
    h.assert_event("AlarmNotSet", 2, TimeData(0, 0, 0, 0, 0, 0), 0)


def test_startup_manager_flash_failures_and_sequence(fprime_harness, craft, tmp_path):
    """SUM-004: an unwritable boot-count or quiescence file logs BootCountUpdateFailure /
    QuiescenceFileInitFailure (the count is still at least 1); the first run asks runSequence for
    STARTUP_SEQUENCE_FILE."""
    import os
    os.makedirs(os.path.join(craft.flash_dir, "boot_count.bin"))        # a directory: cannot be written
    os.makedirs(os.path.join(craft.flash_dir, "quiescence_start.bin"))
    h = fprime_harness(StartupManager("startupManager", craft))
    h.invoke("run", 0)
    h.assert_event_count("BootCountUpdateFailure", 1)
    h.assert_event_count("QuiescenceFileInitFailure", 1)
    assert h.component.boot_count == 1
    assert [c.args for c in h.from_port("runSequence")] == [("/seq/startup.bin",)]


def test_rtc_alarm_without_a_scheduler_is_a_hardware_error(fprime_harness, craft):
    """RTC-004: with no scheduler to ring it the alarm cannot be armed: AlarmHardwareError(0, -ENODEV)."""
    import errno
    h = fprime_harness(RtcManager("rtcManager", craft))
    h.send_command("ALARM_SET", TimeData(2100, 1, 1, 0, 0, 0))
    h.assert_cmd_response(0, "ALARM_SET", CmdResponse.EXECUTION_ERROR)
    h.assert_event("AlarmHardwareError", 0, 0, -errno.ENODEV)
