"""StartupManager as flown: the boot count and the post-deployment quiescence wait.

On its first ``run`` after a boot it reads the boot count from BOOT_COUNT_FILE on the simulated
flash, increments it (at least 1) and writes it back (BootCountUpdateFailure if it cannot), and
reads — or, on the first boot, records — the quiescence start time in QUIESCENCE_START_FILE.
Every ``run`` writes BootCount and QuiescenceEndTime (start + QUIESCENCE_TIME).
WAIT_FOR_QUIESCENCE answers only once the quiescence end time has passed (or at once when ARMED is
false): a start-up sequence that issues it waits out the 45 minutes after deployment.
GET_BOOT_COUNT logs CurrentBootCount. ``completeSequence`` reports StartupSequenceFinished /
StartupSequenceFailed for the sequence ``sequenceStarted`` named.

Paths: the flight parameters are absolute flash paths (``/boot_count.bin``); here they are taken
inside ``spacecraft.flash_dir``. Deviation: ``runSequence`` is not connected in the reference
deployment, whose start-up sequence is run by the topology's ``startup`` block at start (see
``docs/topology.md``); connect it to run STARTUP_SEQUENCE_FILE from here instead.
"""

from __future__ import annotations

import os
import struct

from fprime_lite import (BOOL, I64, U64, Channel, CmdResponse, Event, OutputPort, Param, PassiveComponent, Sched,
                         Severity, String, sync_command, sync_input)
from fprime_lite.model.commands import CommandToken
from fprime_lite.model.fw_ports import CmdResponsePort, CmdSeqIn
from fprime_lite.model.fw_types import TimeIntervalValue
from fprime_lite.model.time import Time
from fprime_lite.osal.atomic import atomic_write_bytes

from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["StartupManager"]

_COUNT = struct.Struct(">Q")
_TIME = struct.Struct(">HBII")  # time base, context, seconds, microseconds (Fw::Time serialised)


class StartupManager(PassiveComponent):
    """Boot counting and quiescence for ``spacecraft`` (instance ``startupManager``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    boot_count: int
    quiescence_start: Time | None
    _waiting: CommandToken | None

    @sync_input(Sched)
    def run(self, context: int) -> None:
        if self.boot_count == 0:
            self.boot_count = self._boot_count(increment=True)
            self.quiescence_start = self._quiescence_start()
            if self.is_connected("runSequence", 0):
                self.runSequence[0](self.STARTUP_SEQUENCE_FILE.value)
        end = self.quiescence_end()
        if self._waiting is not None and (not self.ARMED.value or self.get_time().total_us >= end.total_us):
            token, self._waiting = self._waiting, None
            self.command_response(token, CmdResponse.OK)
        self.QuiescenceEndTime.write(end)
        self.BootCount.write(self.boot_count)

    runSequence = OutputPort(CmdSeqIn)

    @sync_input(CmdResponsePort)
    def completeSequence(self, opcode: int, cmd_seq: int, response: CmdResponse) -> None:
        if self._sequence_file == self.STARTUP_SEQUENCE_FILE.value:
            if response == CmdResponse.OK:
                self.StartupSequenceFinished()
            else:
                self.StartupSequenceFailed(response)

    @sync_input(CmdSeqIn)
    def sequenceStarted(self, file_name: str) -> None:
        self._sequence_file = file_name

    @sync_command()
    def WAIT_FOR_QUIESCENCE(self):
        """Answer OK once the quiescence period after the first boot has passed."""
        self._waiting = self.defer_command_response()

    @sync_command()
    def GET_BOOT_COUNT(self):
        self.CurrentBootCount(self._boot_count(increment=False))

    BootCount = Channel(U64)
    QuiescenceEndTime = Channel(Time, update="on change")

    CurrentBootCount = Event(Severity.ACTIVITY_LO, "Current boot count: {}", i=I64)
    BootCountUpdateFailure = Event(Severity.WARNING_LO, "Failed to update boot count file")
    QuiescenceFileInitFailure = Event(Severity.WARNING_LO, "Failed to initialize quiescence start time file")
    StartupSequenceFinished = Event(Severity.ACTIVITY_LO, "Start-up sequence finished successfully")
    StartupSequenceFailed = Event(Severity.WARNING_LO, "Start-up sequence failed with response code {}",
                                  response=CmdResponse)

    ARMED = Param(BOOL, default=True)
    QUIESCENCE_TIME = Param(TimeIntervalValue, default=TimeIntervalValue(seconds=45 * 60, useconds=0), units="s, µs")
    QUIESCENCE_START_FILE = Param(String(200), default="/quiescence_start.bin")
    STARTUP_SEQUENCE_FILE = Param(String(200), default="/seq/startup.bin")
    BOOT_COUNT_FILE = Param(String(200), default="/boot_count.bin")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self.boot_count = 0
        self.quiescence_start = None
        self._waiting = None
        self._sequence_file = ""

    def flash_path(self, flight_path: str) -> str:
        """Where a flight flash path lives in the simulated flash."""
        return os.path.join(self.spacecraft.flash_dir, flight_path.lstrip("/"))

    def quiescence_end(self) -> Time:
        start = self.quiescence_start if self.quiescence_start is not None else self.get_time()
        q = self.QUIESCENCE_TIME.value
        return Time.from_us(start.total_us + q.seconds * 1_000_000 + q.useconds, start.time_base, start.context)

    def _boot_count(self, *, increment: bool) -> int:
        path = self.flash_path(self.BOOT_COUNT_FILE.value)
        count = 0
        try:
            with open(path, "rb") as fh:
                data = fh.read()
            if len(data) == _COUNT.size:
                count = _COUNT.unpack(data)[0]
        except OSError:
            pass
        count = max(1, count + 1 if increment else count)
        try:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            atomic_write_bytes(path, _COUNT.pack(count))
        except OSError:
            self.BootCountUpdateFailure()
        return count

    def _quiescence_start(self) -> Time:
        path = self.flash_path(self.QUIESCENCE_START_FILE.value)
        try:
            with open(path, "rb") as fh:
                data = fh.read()
            if len(data) == _TIME.size:
                base, context, seconds, useconds = _TIME.unpack(data)
                if useconds < 1_000_000:
                    return Time.from_us(seconds * 1_000_000 + useconds, base, context)
        except OSError:
            pass
        now = self.get_time()
        try:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            atomic_write_bytes(path, _TIME.pack(int(now.time_base), now.context, now.total_us // 1_000_000,
                                                now.total_us % 1_000_000))
        except OSError:
            self.QuiescenceFileInitFailure()
        return now
