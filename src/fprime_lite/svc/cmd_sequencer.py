"""Svc.CmdSequencer: runs command sequence files, one command at a time.

The F´ component of the same name, with its ports, commands, events and channels (names, ids,
arguments, severities). File formats are in :mod:`fprime_lite.wire.seqfile`: binary files exactly as
``fprime-seqgen`` writes them, and, when the sequencer is given a ``command_lookup``, the text
form (``.seq``), compiled when loaded.

Behaviour (as F´'s ``CmdSequencerImpl``):

- Loading checks, in order: file present, header, size against the buffer, records and CRC
  present, CRC, time base/context, records. Any failure logs its event (CS_FileNotFound,
  CS_FileInvalid, CS_FileSizeError, CS_FileCrcFailure, CS_TimeBaseMismatch, CS_RecordInvalid …),
  counts CS_Errors, and nothing runs.
- AUTO mode: each record is stepped when the previous command completed. A relative time tag is
  a delay from that moment; an absolute tag is compared with the time port's time (seconds since
  1970 for files from fprime-seqgen). A command whose time has come is sent at once out of
  ``comCmdOut``; otherwise it waits for a ``schedIn`` tick at or after its time.
- A command response other than OK logs CS_CommandError and aborts the sequence: ``seqDone``
  gets EXECUTION_ERROR, and so does a CS_RUN with ``block=BLOCK`` (and any CS_JOIN_WAIT).
- MANUAL (step) mode: CS_RUN only loads; CS_START sends the first command, CS_STEP each next one.
- With ``timeout_s > 0`` (F´'s ``setTimeout``), a command not answered within that many seconds of
  being sent (checked on ``schedIn``) logs CS_SequenceTimeout and cancels the sequence.

Differences from F´ are listed in ``docs/sequences.md``.
"""

from __future__ import annotations

import enum
from pathlib import Path
from typing import Annotated

from fprime_lite.model.commands import CmdResponse, CommandToken, async_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import CmdResponsePort, CmdSeqCancel, CmdSeqIn, Com, Ping, Sched
from fprime_lite.model.ports import OutputPort, async_input
from fprime_lite.wire.seqfile import (Descriptor, FileReadStage, Record, Sequence, SequenceCrcError,
                       SequenceEmpty, SequenceFormatError, SequenceRecordError,
                       SequenceRecordMismatch, SequenceSizeError, SequenceTextError,
                       SequenceTimeBaseMismatch, SequenceTimeContextMismatch, CommandLookup,
                       check_time, read_sequence)
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import I32, U8, U16, U32, FwEnum, String, fit_utf8
from fprime_lite.osal.confine import Confinement

__all__ = ["CmdSequencer", "BlockState", "SeqMode", "FileReadStage", "FILE_NAME_STRING_SIZE",
           "DEFAULT_BUFFER_SIZE"]

#: F´'s FileNameStringSize: the bound of CS_RUN/CS_VALIDATE file names.
FILE_NAME_STRING_SIZE = 200
#: Bytes of records + CRC a binary file may hold (F´ sizes this buffer with ``allocateBuffer``).
DEFAULT_BUFFER_SIZE = 64 * 1024
#: Event string arguments are ``string size 60``; longer file names are truncated, as F´ does.
_LOG_NAME_SIZE = 60
_LOG_NAME = String(_LOG_NAME_SIZE)
_TEXT_REASON = String(120)


class BlockState(FwEnum, namespace="Svc.CmdSequencer"):
    """CS_RUN's ``block`` argument: BLOCK answers when the sequence ends, NO_BLOCK at once."""

    BLOCK = 0
    NO_BLOCK = 1


class SeqMode(FwEnum, namespace="Svc.CmdSequencer"):
    """The stepping mode reported by CS_ModeSwitched."""

    STEP = 0
    AUTO = 1


class _RunMode(enum.Enum):
    STOPPED = 0
    RUNNING = 1


def _log_name(file_name: str) -> str:
    """``file_name`` cut to the 60 bytes an event string holds (on a UTF-8 boundary)."""
    return fit_utf8(file_name, _LOG_NAME_SIZE)


class CmdSequencer(ActiveComponent):
    """Runs sequence files (F´ ``Svc.CmdSequencer``).

    Args:
        name, base_id, queue_size: as every active component.
        command_lookup: ``lookup(full command name) -> (opcode, [FwType])`` used to compile text
            sequences (``*.seq``); without it only binary files run.
        timeout_s: seconds a command may stay unanswered before the sequence is cancelled
            (0 = no timeout, F´'s default).
        buffer_size: the largest ``size`` (records + CRC, bytes) a binary file may announce.
        base_dir: directory that relative file names are resolved against (default: the
            current directory).
    """

    # --- ports ------------------------------------------------------------------------------------
    pingOut = OutputPort(Ping)
    seqDone = OutputPort(CmdResponsePort)
    comCmdOut = OutputPort(Com)
    seqStartOut = OutputPort(CmdSeqIn)

    # --- channels (F´ ids) ------------------------------------------------------------------------
    CS_LoadCommands = Channel(U32, id=0)
    CS_CancelCommands = Channel(U32, id=1)
    CS_Errors = Channel(U32, id=2)
    CS_CommandsExecuted = Channel(U32, id=3)
    CS_SequencesCompleted = Channel(U32, id=4)

    # --- events (F´ ids, severities and formats) --------------------------------------------------
    CS_SequenceLoaded = Event(Severity.ACTIVITY_LO, "Loaded sequence {}", id=0, fileName=_LOG_NAME)
    CS_SequenceCanceled = Event(Severity.ACTIVITY_HI, "Sequence file {} canceled", id=1,
                                fileName=_LOG_NAME)
    CS_FileReadError = Event(Severity.WARNING_HI, "Error reading sequence file {}", id=2,
                             fileName=_LOG_NAME)
    CS_FileInvalid = Event(Severity.WARNING_HI, "Sequence file {} invalid. Stage: {} Error: {}", id=3,
                           fileName=_LOG_NAME, stage=FileReadStage, error=I32)
    CS_RecordInvalid = Event(Severity.WARNING_HI, "Sequence file {}: Record {} invalid. Err: {}", id=4,
                             fileName=_LOG_NAME, recordNumber=U32, error=I32)
    CS_FileSizeError = Event(Severity.WARNING_HI, "Sequence file {} too large. Size: {}", id=5,
                             fileName=_LOG_NAME, size=U32)
    CS_FileNotFound = Event(Severity.WARNING_HI, "Sequence file {} not found.", id=6,
                            fileName=_LOG_NAME)
    CS_FileCrcFailure = Event(Severity.WARNING_HI,
                              "Sequence file {} had invalid CRC. Stored 0x{x}, Computed 0x{x}.", id=7,
                              fileName=_LOG_NAME, storedCRC=U32, computedCRC=U32)
    CS_CommandComplete = Event(Severity.ACTIVITY_LO, "Sequence file {}: Command {} (opcode {}) complete",
                               id=8, fileName=_LOG_NAME, recordNumber=U32, opCode=U32)
    CS_SequenceComplete = Event(Severity.ACTIVITY_HI, "Sequence file {} complete", id=9,
                                fileName=_LOG_NAME)
    CS_CommandError = Event(Severity.WARNING_HI,
                            "Sequence file {}: Command {} (opcode {}) completed with error {}", id=10,
                            fileName=_LOG_NAME, recordNumber=U32, opCode=U32, errorStatus=U32)
    CS_InvalidMode = Event(Severity.WARNING_HI, "Invalid mode", id=11)
    CS_RecordMismatch = Event(Severity.WARNING_HI,
                              "Sequence file {} header records mismatch: {} in header, found {} extra bytes.",
                              id=12, fileName=_LOG_NAME, header_records=U32, extra_bytes=U32)
    CS_TimeBaseMismatch = Event(Severity.WARNING_HI,
                                "Sequence file {}: Current time base doesn't match sequence time: base: {} seq: {}",
                                id=13, fileName=_LOG_NAME, time_base=U16, seq_time_base=U16)
    CS_TimeContextMismatch = Event(Severity.WARNING_HI,
                                   "Sequence file {}: Current time context doesn't match sequence context: "
                                   "base: {} seq: {}",
                                   id=14, fileName=_LOG_NAME, currTimeBase=U8, seqTimeBase=U8)
    CS_PortSequenceStarted = Event(Severity.ACTIVITY_HI, "Local request for sequence {} started.", id=15,
                                   filename=_LOG_NAME)
    CS_UnexpectedCompletion = Event(Severity.WARNING_HI,
                                    "Command complete status received while no sequences active. Opcode: {}",
                                    id=16, opcode=U32)
    CS_ModeSwitched = Event(Severity.ACTIVITY_HI, "Sequencer switched to {} step mode", id=17,
                            mode=SeqMode)
    CS_NoSequenceActive = Event(Severity.WARNING_LO, "No sequence active.", id=18)
    CS_SequenceValid = Event(Severity.ACTIVITY_HI, "Sequence {} is valid.", id=19, filename=_LOG_NAME)
    CS_SequenceTimeout = Event(Severity.WARNING_HI, "Sequence {} timed out on command {}", id=20,
                               filename=_LOG_NAME, command=U32)
    CS_CmdStepped = Event(Severity.ACTIVITY_HI, "Sequence {} command {} stepped", id=21,
                          filename=_LOG_NAME, command=U32)
    CS_CmdStarted = Event(Severity.ACTIVITY_HI, "Sequence {} started", id=22, filename=_LOG_NAME)
    CS_JoinWaiting = Event(Severity.ACTIVITY_HI,
                           "Start waiting for sequence file {}: Command {} (opcode {}) to complete",
                           id=23, filename=_LOG_NAME, recordNumber=U32, opCode=U32)
    CS_JoinWaitingNotComplete = Event(Severity.WARNING_HI, "Still waiting for sequence file to complete",
                                      id=24)
    CS_NoRecords = Event(Severity.WARNING_LO, "Sequence file {} has no records. Ignoring.", id=25,
                         fileName=_LOG_NAME)
    #: Not in F´: a text (``.seq``) sequence does not compile. Line 0 = the whole file.
    CS_TextFileInvalid = Event(Severity.WARNING_HI, "Sequence file {} line {}: {}", id=0x40,
                               fileName=_LOG_NAME, lineNumber=U32, reason=_TEXT_REASON)

    def __init__(self, name: str, *, base_id: int = 0, queue_size: int = 10,
                 command_lookup: CommandLookup | None = None, timeout_s: int = 0,
                 buffer_size: int = DEFAULT_BUFFER_SIZE, base_dir: str | Path | None = None):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        if not isinstance(timeout_s, int) or timeout_s < 0:
            raise ValueError(f"{name}: timeout_s must be a non-negative integer number of seconds, "
                             f"got {timeout_s!r}")
        self.command_lookup = command_lookup
        self.timeout_s = timeout_s
        self.buffer_size = buffer_size
        self.base_dir = Path(base_dir) if base_dir is not None else None
        #: ``fprime-lite run --board-root``: file names are the board's, this folder its ``/``
        #: (absolute names are taken inside it, nothing outside it is read).
        self.board_root: Confinement | None = None
        self._run_mode = _RunMode.STOPPED
        self._step_mode = SeqMode.AUTO
        self._sequence: Sequence | None = None
        self._file_name = ""       # as given, for seqStartOut
        self._log_file_name = ""   # cut to 60 bytes, for events
        self._next = 0             # index of the next record
        self._record: Record | None = None
        self._timer_us: int | None = None       # when the current record's command is due
        self._timeout_us: int | None = None     # when the sent command times out
        self._awaiting = False                  # a command was sent and is not answered yet
        self._waiters: list[CommandToken] = []  # CS_RUN BLOCK and CS_JOIN_WAIT to answer at the end
        self._join_waiting = False
        self._executed = 0
        self._load_count = 0
        self._cancel_count = 0
        self._error_count = 0
        self._total_executed = 0
        self._completed_count = 0

    # --- state, for tests and for the deployment's summary ---------------------------------------

    @property
    def running(self) -> bool:
        return self._run_mode is _RunMode.RUNNING

    @property
    def step_mode(self) -> SeqMode:
        return self._step_mode

    @property
    def loaded(self) -> bool:
        """A sequence is loaded and has records left to run."""
        return self._has_more_records()

    # --- commands ---------------------------------------------------------------------------------

    @async_command(opcode=0)
    def CS_RUN(self, fileName: Annotated[str, String(FILE_NAME_STRING_SIZE)], block: BlockState):
        """Load ``fileName`` and, in AUTO mode, run it; BLOCK answers when the sequence ends."""
        if not self._require_run_mode(_RunMode.STOPPED):
            if self._join_waiting:
                self.CS_JoinWaitingNotComplete()
            return CmdResponse.EXECUTION_ERROR
        if not self._load(fileName):
            return CmdResponse.EXECUTION_ERROR
        if block == BlockState.BLOCK:
            self._waiters.append(self.defer_command_response())
        self._executed = 0
        if self._step_mode == SeqMode.AUTO:
            self._start()
        return CmdResponse.OK

    @async_command(opcode=1)
    def CS_VALIDATE(self, fileName: Annotated[str, String(FILE_NAME_STRING_SIZE)]):
        """Load ``fileName`` to check it, then unload it."""
        if not self._require_run_mode(_RunMode.STOPPED):
            return CmdResponse.EXECUTION_ERROR
        if not self._load(fileName):
            return CmdResponse.EXECUTION_ERROR
        self._sequence = None
        self.CS_SequenceValid(self._log_file_name)
        return CmdResponse.OK

    @async_command(opcode=2)
    def CS_CANCEL(self):
        """Stop the running sequence (it stays loaded, rewound)."""
        self._cancel_running()
        return CmdResponse.OK

    @async_command(opcode=3)
    def CS_START(self):
        """Start the loaded sequence (after CS_RUN in MANUAL mode, or after a cancel)."""
        if not self._has_more_records():
            self.CS_NoSequenceActive()
            return CmdResponse.EXECUTION_ERROR
        if not self._require_run_mode(_RunMode.STOPPED):
            return CmdResponse.EXECUTION_ERROR
        self._executed = 0
        self._start(started_event=True)
        return CmdResponse.OK

    @async_command(opcode=4)
    def CS_STEP(self):
        """MANUAL mode: send the next command (the previous one must have completed)."""
        if not self._require_run_mode(_RunMode.RUNNING):
            return CmdResponse.EXECUTION_ERROR
        if self._awaiting or self._timer_us is not None or not self._has_more_records():
            self.CS_InvalidMode()
            return CmdResponse.EXECUTION_ERROR
        self._step()
        if self._run_mode is not _RunMode.STOPPED:
            self.CS_CmdStepped(self._log_file_name, self._executed)
        return CmdResponse.OK

    @async_command(opcode=5)
    def CS_AUTO(self):
        """Run sequences through on their own (the default)."""
        return self._set_mode(SeqMode.AUTO)

    @async_command(opcode=6)
    def CS_MANUAL(self):
        """Run sequences one CS_STEP at a time."""
        return self._set_mode(SeqMode.STEP)

    @async_command(opcode=7)
    def CS_JOIN_WAIT(self):
        """Answer when the running sequence ends (at once when none runs)."""
        if self._run_mode is not _RunMode.RUNNING:
            self.CS_NoSequenceActive()
            return CmdResponse.OK
        self._join_waiting = True
        opcode = self._record.opcode if self._record is not None else None
        self.CS_JoinWaiting(self._log_file_name, self._executed, opcode or 0)
        self._waiters.append(self.defer_command_response())
        return None

    # --- input ports ------------------------------------------------------------------------------

    @async_input(CmdResponsePort)
    def cmdResponseIn(self, opcode, cmd_seq, response):
        """The dispatcher's answer to the command the sequencer sent."""
        if self._run_mode is _RunMode.STOPPED or not self._awaiting:
            self.CS_UnexpectedCompletion(opcode)
            return
        self._awaiting = False
        self._timeout_us = None
        if response != CmdResponse.OK:
            self.CS_CommandError(self._log_file_name, self._executed, opcode, int(response))
            self._error()
            self._cancel()
            return
        self._command_complete(opcode)
        if not self._has_more_records():
            self._run_mode = _RunMode.STOPPED
            self._sequence_complete()
        elif self._step_mode == SeqMode.AUTO:
            self._step()

    @async_input(Sched)
    def schedIn(self, context):
        """Rate-group tick: send a command whose time has come, or time out a silent one."""
        now = self.get_time().total_us
        if self._timer_us is not None and now >= self._timer_us:
            self._timer_us = None
            self._send(now)
        elif self._timeout_us is not None and now >= self._timeout_us:
            self.CS_SequenceTimeout(self._log_file_name, self._executed)
            self._cancel()

    def use_command_lookup(self, lookup: CommandLookup) -> None:
        """Start-up: compile text sequences with the deployment's commands, unless the topology gave
        a ``command_lookup`` of its own."""
        if self.command_lookup is None:
            self.command_lookup = lookup

    @async_input(CmdSeqIn)
    def seqRunIn(self, file_name):
        """Run ``file_name`` (empty: the sequence already loaded); the end is told on seqDone."""
        if not self._require_run_mode(_RunMode.STOPPED):
            self._seq_done(CmdResponse.EXECUTION_ERROR)
            return
        if file_name != "":
            if not self._load(file_name):
                self._seq_done(CmdResponse.EXECUTION_ERROR)
                return
        elif not self._has_more_records():
            self.CS_NoSequenceActive()
            self._error()
            self._seq_done(CmdResponse.EXECUTION_ERROR)
            return
        self._executed = 0
        if self._step_mode == SeqMode.AUTO:
            self._start()
        self.CS_PortSequenceStarted(self._log_file_name)

    @async_input(CmdSeqCancel)
    def seqCancelIn(self):
        """Another component cancels the running sequence (as CS_CANCEL; F´'s ``seqCancelIn``)."""
        self._cancel_running()

    def _cancel_running(self) -> None:
        if self._run_mode is _RunMode.RUNNING:
            self._cancel()
            self.CS_SequenceCanceled(self._log_file_name)
            self._cancel_count += 1
            self.CS_CancelCommands.write(self._cancel_count)
        else:
            self.CS_NoSequenceActive()

    @async_input(Ping)
    def pingIn(self, key):
        """Health ping: answer with the same key."""
        self.pingOut[0](key)

    # --- helpers ----------------------------------------------------------------------------------

    def _require_run_mode(self, mode: _RunMode) -> bool:
        if self._run_mode is mode:
            return True
        self.CS_InvalidMode()
        return False

    def _set_mode(self, mode: SeqMode) -> CmdResponse:
        if not self._require_run_mode(_RunMode.STOPPED):
            return CmdResponse.EXECUTION_ERROR
        self._step_mode = mode
        self.CS_ModeSwitched(mode)
        return CmdResponse.OK

    def _has_more_records(self) -> bool:
        return self._sequence is not None and self._next < len(self._sequence.records)

    def _error(self) -> None:
        self._error_count += 1
        self.CS_Errors.write(self._error_count)

    def _resolve(self, file_name: str) -> Path:
        if self.board_root is not None:
            return Path(self.board_root.contents(file_name))  # PathRefused is an OSError: CS_FileReadError
        path = Path(file_name)
        if self.base_dir is not None and not path.is_absolute():
            path = self.base_dir / path
        return path

    def _load(self, file_name: str) -> bool:
        """Read and validate ``file_name``; on success it is the loaded sequence."""
        # A sequence loaded earlier but never run (MANUAL mode) is replaced: whoever waits for
        # it will not see it end.
        self._answer_waiters(CmdResponse.EXECUTION_ERROR)
        self._sequence = None
        self._next = 0
        self._file_name = file_name
        self._log_file_name = name = _log_name(file_name)
        now = self.get_time()
        try:
            sequence = read_sequence(self._resolve(file_name), lookup=self.command_lookup,
                                     capacity=self.buffer_size,
                                     check_header=check_time(int(now.time_base), now.context))
        except FileNotFoundError:
            self.CS_FileNotFound(name)
        except OSError:
            self.CS_FileReadError(name)
        except SequenceFormatError as exc:
            self.CS_FileInvalid(name, exc.stage, exc.error)
        except SequenceSizeError as exc:
            self.CS_FileSizeError(name, exc.size)
        except SequenceCrcError as exc:
            self.CS_FileCrcFailure(name, exc.stored, exc.computed)
        except SequenceTimeBaseMismatch as exc:
            self.CS_TimeBaseMismatch(name, exc.current, exc.sequence)
        except SequenceTimeContextMismatch as exc:
            self.CS_TimeContextMismatch(name, exc.current, exc.sequence)
        except SequenceEmpty:
            self.CS_NoRecords(name)
            return False  # F´ does not count this as an error
        except SequenceRecordError as exc:
            self.CS_RecordInvalid(name, exc.record_number, int(exc.error))
        except SequenceRecordMismatch as exc:
            self.CS_RecordMismatch(name, exc.header_records, exc.extra_bytes)
            return False  # F´ does not count this as an error
        except SequenceTextError as exc:
            self.CS_TextFileInvalid(name, exc.line, fit_utf8(exc.reason, _TEXT_REASON.size))
        else:
            self._sequence = sequence
            self.CS_SequenceLoaded(name)
            self._load_count += 1
            self.CS_LoadCommands.write(self._load_count)
            return True
        self._error()
        return False

    def _start(self, *, started_event: bool = False) -> None:
        self._run_mode = _RunMode.RUNNING
        self._step()
        if started_event:
            self.CS_CmdStarted(self._log_file_name)
        if self.is_connected("seqStartOut", 0):
            self.seqStartOut[0](self._file_name)

    def _step(self) -> None:
        """Take the next record: end, send now, or set the timer for it."""
        assert self._sequence is not None  # only a loaded sequence runs
        record = self._sequence.records[self._next]
        self._next += 1
        self._record = record
        if record.descriptor == Descriptor.END_OF_SEQUENCE:
            self._run_mode = _RunMode.STOPPED
            self._sequence_complete()
            return
        now = self.get_time().total_us
        due = record.time_us + (now if record.descriptor == Descriptor.RELATIVE else 0)
        if now >= due:
            self._send(now)
        else:
            self._timer_us = due

    def _send(self, now_us: int) -> None:
        self._awaiting = True
        if self.timeout_s > 0 and self._step_mode == SeqMode.AUTO:
            self._timeout_us = now_us + self.timeout_s * 1_000_000
        assert self._record is not None  # _step set the record being sent
        self.comCmdOut[0](self._record.command, 0)

    def _command_complete(self, opcode: int) -> None:
        self.CS_CommandComplete(self._log_file_name, self._executed, opcode)
        self._executed += 1
        self._total_executed += 1
        self.CS_CommandsExecuted.write(self._total_executed)

    def _sequence_complete(self) -> None:
        self._completed_count += 1
        self._sequence = None
        self._next = 0
        self._record = None
        self.CS_SequenceComplete(self._log_file_name)
        self.CS_SequencesCompleted.write(self._completed_count)
        self._executed = 0
        self._seq_done(CmdResponse.OK)
        self._answer_waiters(CmdResponse.OK)

    def _cancel(self) -> None:
        """Stop: rewind the sequence, clear the timers, tell everyone waiting it failed."""
        self._next = 0
        self._record = None
        self._run_mode = _RunMode.STOPPED
        self._timer_us = None
        self._timeout_us = None
        self._awaiting = False
        self._executed = 0
        self._seq_done(CmdResponse.EXECUTION_ERROR)
        self._answer_waiters(CmdResponse.EXECUTION_ERROR)

    def _seq_done(self, response: CmdResponse) -> None:
        if self.is_connected("seqDone", 0):
            self.seqDone[0](0, 0, response)

    def _answer_waiters(self, response: CmdResponse) -> None:
        waiters, self._waiters = self._waiters, []
        self._join_waiting = False
        for token in waiters:
            self.command_response(token, response)
