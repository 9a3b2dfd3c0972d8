"""TcSecurityDeframer as flown, for its ground interface: the uplink's anti-replay sequence number.

On the board this component (one per link: ``ComCcsdsUart.tcSecurityDeframer``,
``ComCcsdsLora.tcSecurityDeframer``) authenticates every uplinked frame (CCSDS SDLS: security
header, sequence number, HMAC) and keeps the last accepted sequence number in a file. The
simulated link (``comDriver``) neither adds nor checks a security header, so here the component
keeps only that number: GET_SEQ_NUM reads it from the file (SequenceNumberGet), SET_SEQ_NUM writes
it (SequenceNumberSet); a file that cannot be read or written logs SequenceNumberReadFailed /
SequenceNumberWriteFailed with an ``Os.FileStatus`` and answers EXECUTION_ERROR. A missing file
reads as 0. The file is ``SEQ_NUM_FILE_PATH`` (flight default ``//sequence_number.txt``) on the
simulated flash, the number in decimal text.

Ground interface (flight ``Components.TcSecurityDeframer``, base id 0x2100B000 on the UART link):
commands GET_SEQ_NUM (0), SET_SEQ_NUM(seq_num) (1); channel CurrentSequenceNumber; events with the
flight ids (AuthenticationFailed 1, SequenceNumberInvalid 2, ParsingFailed 3, SpiInvalid 4,
SequenceNumberGet 6, SequenceNumberSet 7, SequenceNumberWriteFailed 8, SequenceNumberReadFailed 14);
parameters SEQ_NUM_WINDOW (50000), SEQ_NUM_FILE_PATH.
"""

from __future__ import annotations

import os
import types
from typing import Any

from fprime_lite import (I32, U32, Channel, CmdResponse, Event, FwEnum, Param, PassiveComponent, Severity, String,
                         sync_command)
from fprime_lite.osal.atomic import atomic_write_bytes
from fprime_lite.osal.os_status import FileStatus as _OsFileStatus

from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["TcSecurityDeframer", "PacketAuthenticatorStatus", "PacketParserStatus"]


def _fill_file_status(namespace) -> None:
    for member in _OsFileStatus:
        namespace[member.name] = member.value


#: F´'s ``Os.FileStatus`` as an F´ type (the events carry it), with the Os layer's members and values.
FileStatus: Any = types.new_class("FileStatus", (FwEnum,), {"namespace": "Os"}, _fill_file_status)


class PacketAuthenticatorStatus(FwEnum, namespace="Components"):
    Authenticated = 0
    VerifyError = 1


class PacketParserStatus(FwEnum, namespace="Components"):
    Ok = 0
    SpiParseError = 1
    SequenceNumberParseError = 2
    MacParseError = 3


class TcSecurityDeframer(PassiveComponent):
    """The uplink sequence number of one link of ``spacecraft``."""

    @sync_command()
    def GET_SEQ_NUM(self):
        """Read the sequence number from its file and log SequenceNumberGet."""
        try:
            seq = self.read_sequence_number()
        except (OSError, ValueError):
            self.SequenceNumberReadFailed(FileStatus.OTHER_ERROR)
            return CmdResponse.EXECUTION_ERROR
        self.CurrentSequenceNumber.write(seq)
        self.SequenceNumberGet(seq)

    @sync_command()
    def SET_SEQ_NUM(self, seq_num: U32):
        """Write ``seq_num`` to the file and log SequenceNumberSet."""
        try:
            path = self.path
            os.makedirs(os.path.dirname(path), exist_ok=True)
            atomic_write_bytes(path, str(int(seq_num)).encode())
        except OSError:
            self.SequenceNumberWriteFailed(FileStatus.OTHER_ERROR)
            return CmdResponse.EXECUTION_ERROR
        self.CurrentSequenceNumber.write(seq_num)
        self.SequenceNumberSet(seq_num)

    CurrentSequenceNumber = Channel(U32)

    AuthenticationFailed = Event(Severity.WARNING_HI, "Authentication failed: Status={}, PSA Return Code={}", id=1,
                                 auth_status=PacketAuthenticatorStatus, rc=I32, throttle=2)
    SequenceNumberInvalid = Event(Severity.WARNING_HI, "Sequence number less than last accepted or out of window: "
                                  "Received={}, LastAccepted={}, Window={}", id=2, packet_seq_num=U32, seq_num=U32,
                                  window=U32, throttle=2)
    ParsingFailed = Event(Severity.WARNING_HI, "Parsing failed: {}", id=3, parse_status=PacketParserStatus,
                          throttle=2)
    SpiInvalid = Event(Severity.WARNING_HI, "SPI invalid: Received={}", id=4, packet_spi=U32, throttle=2)
    SequenceNumberGet = Event(Severity.ACTIVITY_HI, "Sequence number is {}", id=6, seq_num=U32)
    SequenceNumberSet = Event(Severity.ACTIVITY_HI, "Sequence number set to {}", id=7, seq_num=U32)
    SequenceNumberWriteFailed = Event(Severity.WARNING_HI, "Failed to write sequence number, error: {}", id=8,
                                      status=FileStatus, throttle=2)
    SequenceNumberReadFailed = Event(Severity.WARNING_HI, "Failed to read sequence number, error: {}", id=14,
                                     status=FileStatus, throttle=2)

    SEQ_NUM_WINDOW = Param(U32, default=50000)
    SEQ_NUM_FILE_PATH = Param(String(200), default="//sequence_number.txt")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft

    @property
    def path(self) -> str:
        """``SEQ_NUM_FILE_PATH`` inside the simulated flash."""
        return os.path.join(self.spacecraft.flash_dir, self.SEQ_NUM_FILE_PATH.value.lstrip("/"))

    def read_sequence_number(self) -> int:
        """The persisted number (0 when there is no file); OSError/ValueError on an unreadable one."""
        try:
            with open(self.path, "rb") as fh:
                text = fh.read(32).decode("ascii").strip()
        except FileNotFoundError:
            return 0
        value = int(text)
        if not 0 <= value < 2**32:
            raise ValueError(f"sequence number {value} out of range")
        return value
