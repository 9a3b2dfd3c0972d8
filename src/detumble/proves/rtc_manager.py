"""RtcManager as flown: the real-time clock — time set and read, one alarm.

The simulated RTC is the deployment's clock (``spacecraft.clock``): ``timeGetPort`` returns its time,
and TIME_SET moves the clock's epoch so that it reads the commanded UTC date and time from now on
(microseconds run on) — every later event and channel carries the new time, as on the board. The
command first validates every field (YearValidationFailed … SecondValidationFailed, then
TimeNotSet(EINVAL) and VALIDATION_ERROR), then calls every connected ``cancelSequences[i]``
(running sequences would otherwise see time jump), then logs TimeSet with the time before the change.

Alarm (one slot, ID 0): ALARM_SET(t) arms it for a future time (AlarmSet; AlarmNotSet(t, EALREADY)
when one is armed, AlarmNotSet(t, EINVAL) for a time not in the future); when the clock reaches it,
AlarmTriggered(0) and every connected ``alarmTriggered[i]``. ALARM_CANCEL(ID) disarms it
(AlarmCanceled, or AlarmNotCanceled(ID, 0) and EXECUTION_ERROR when none is armed); ALARM_LIST
reports the armed alarm as AlarmSet(0, t), or AlarmNotSet with an empty time. Error numbers are
the host's ``errno`` values (Zephyr's differ for EALREADY).
"""

from __future__ import annotations

import calendar
import datetime as _dt
import errno

from fprime_lite import (I32, U16, U32, Event, OutputPort, PassiveComponent, PortType, Severity, Struct,
                         sync_command, sync_input)
from fprime_lite.model.commands import CmdResponse
from fprime_lite.model.fw_ports import CmdSeqCancel, TimeGet
from fprime_lite.model.time import Time
from fprime_lite.deploy.scheduler import ScheduledCall

from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["RtcManager", "TimeData", "AlarmTriggeredPort"]

#: ``Drv.AlarmTriggered()``.
AlarmTriggeredPort = PortType("Drv.AlarmTriggered")


class TimeData(Struct, namespace="Drv"):
    """A UTC calendar time (flight ``Drv.TimeData``)."""

    Year: U32
    Month: U32
    Day: U32
    Hour: U32
    Minute: U32
    Second: U32


def _seconds(t: TimeData) -> int:
    return calendar.timegm((t.Year, t.Month, t.Day, t.Hour, t.Minute, t.Second, 0, 0, 0))


class RtcManager(PassiveComponent):
    """The RTC of ``spacecraft`` (instance ``rtcManager``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    _alarm: tuple[TimeData, ScheduledCall] | None

    @sync_command()
    def TIME_SET(self, t: TimeData):
        """Set the RTC to UTC ``t``."""
        if not self._valid(t):
            self.TimeNotSet(errno.EINVAL)
            return CmdResponse.VALIDATION_ERROR
        before = self.get_time()
        for i in range(3):
            if self.is_connected("cancelSequences", i):
                self.cancelSequences[i]()
        clock = self.spacecraft.clock
        now_us = clock.epoch_us + clock.current_us
        clock.epoch_us += _seconds(t) * 1_000_000 + now_us % 1_000_000 - now_us
        self.TimeSet(before.total_us // 1_000_000, before.total_us % 1_000_000)
        return CmdResponse.OK

    @sync_command()
    def ALARM_SET(self, t: TimeData):
        """Arm the alarm for UTC ``t``."""
        if self._alarm is not None:
            self.AlarmNotSet(t, errno.EALREADY)
            return CmdResponse.EXECUTION_ERROR
        try:
            due_s = _seconds(t)
        except (ValueError, OverflowError):
            due_s = -1
        now_s = self.get_time().total_us // 1_000_000
        if due_s <= now_s:
            self.AlarmNotSet(t, errno.EINVAL)
            return CmdResponse.EXECUTION_ERROR
        scheduler = self.spacecraft.scheduler()
        if scheduler is None:
            self.AlarmHardwareError(0, -errno.ENODEV)
            return CmdResponse.EXECUTION_ERROR
        clock = self.spacecraft.clock
        due_us = due_s * 1_000_000 - clock.epoch_us
        self._alarm = (t, scheduler.call_at(max(due_us, scheduler.now_us), self._ring))
        self.AlarmSet(0, t)
        return CmdResponse.OK

    @sync_command()
    def ALARM_CANCEL(self, ID: U16):
        """Disarm the alarm."""
        if self._alarm is None:
            self.AlarmNotCanceled(ID, 0)
            return CmdResponse.EXECUTION_ERROR
        self._alarm[1].cancel()
        self._alarm = None
        self.AlarmCanceled(ID)
        return CmdResponse.OK

    @sync_command()
    def ALARM_LIST(self):
        """Report the armed alarm."""
        if self._alarm is not None:
            self.AlarmSet(0, self._alarm[0])
        else:
            self.AlarmNotSet(TimeData(0, 0, 0, 0, 0, 0), 0)

    DeviceNotReady = Event(Severity.WARNING_HI, "RTC not ready", id=0, throttle=1)
    TimeSet = Event(Severity.ACTIVITY_HI, "Time set on RTC, previous time: {}.{}", id=3, seconds=U32, useconds=U32)
    TimeNotSet = Event(Severity.WARNING_HI, "Time not set on RTC: {}", id=4, rc=I32)
    YearValidationFailed = Event(Severity.WARNING_HI, "Provided year is invalid should be >= 1900: {}", id=5,
                                 year=U32)
    MonthValidationFailed = Event(Severity.WARNING_HI, "Provided month is invalid should be in [1, 12]: {}", id=6,
                                  month=U32)
    DayValidationFailed = Event(Severity.WARNING_HI, "Provided day is invalid should be in [1, 31]: {}", id=7, day=U32)
    HourValidationFailed = Event(Severity.WARNING_HI, "Provided hour is invalid should be in [0, 23]: {}", id=8,
                                 hour=U32)
    MinuteValidationFailed = Event(Severity.WARNING_HI, "Provided minute is invalid should be in [0, 59]: {}", id=9,
                                   minute=U32)
    SecondValidationFailed = Event(Severity.WARNING_HI, "Provided second is invalid should be in [0, 59]: {}", id=10,
                                   second=U32)
    AlarmSet = Event(Severity.ACTIVITY_HI, "Alarm set on RTC with ID {}, time: {}", id=11, ID=U16, t=TimeData)
    AlarmNotSet = Event(Severity.WARNING_HI, "Alarm not set on RTC for time: {}, return code: {}", id=12, t=TimeData,
                        rc=I32)
    AlarmTriggered = Event(Severity.ACTIVITY_HI, "Alarm with ID {} triggered", id=13, ID=U16)
    AlarmCanceled = Event(Severity.ACTIVITY_HI, "Alarm with ID {} canceled", id=14, ID=U16)
    AlarmNotCanceled = Event(Severity.WARNING_HI, "Alarm with ID {} not canceled, return code: {}", id=15, ID=U16,
                             rc=I32)
    AlarmHardwareError = Event(Severity.WARNING_HI, "Alarm with ID {} had a hardware error, return code: {}", id=16,
                               ID=U16, rc=I32)

    cancelSequences = OutputPort(CmdSeqCancel, size=3)
    alarmTriggered = OutputPort(AlarmTriggeredPort, size=1)

    @sync_input(TimeGet)
    def timeGetPort(self) -> Time:
        """The RTC's time (the simulated clock's)."""
        return self.spacecraft.clock.now()

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self._alarm = None

    def utc_now(self) -> _dt.datetime:
        """The RTC's present time as an aware UTC datetime."""
        return _dt.datetime.fromtimestamp(self.spacecraft.clock.now().total_us / 1e6, _dt.timezone.utc)

    def _valid(self, t: TimeData) -> bool:
        checks = ((t.Year >= 1900, self.YearValidationFailed, t.Year),
                  (1 <= t.Month <= 12, self.MonthValidationFailed, t.Month),
                  (1 <= t.Day <= 31, self.DayValidationFailed, t.Day),
                  (t.Hour <= 23, self.HourValidationFailed, t.Hour),
                  (t.Minute <= 59, self.MinuteValidationFailed, t.Minute),
                  (t.Second <= 59, self.SecondValidationFailed, t.Second))
        ok = True
        for good, event, value in checks:
            if not good:
                event(value)
                ok = False
        return ok

    def _ring(self) -> None:
        self._alarm = None
        self.AlarmTriggered(0)
        if self.is_connected("alarmTriggered", 0):
            self.alarmTriggered[0]()
