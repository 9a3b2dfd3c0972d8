"""CmdDispatcher: routes command packets to the component that registered each opcode.

F´'s ``Svc.CommandDispatcher`` (instance ``cmdDisp`` in a deployment). At start-up every component
sends its opcodes out of its ``cmdRegOut`` port into ``compCmdReg[i]``; opcode ``o`` registered on
index ``i`` is afterwards dispatched through ``compCmdSend[i]``, which the topology connects to the
same component's ``cmdIn``. The dispatcher's own commands are registered the same way, through a
self-connection ``cmdDisp.cmdRegOut -> cmdDisp.compCmdReg[k]`` and ``cmdDisp.compCmdSend[k] ->
cmdDisp.cmdIn`` (as in F´'s CdhCore subtopology).

Command sources (the ground link, sequencers) call ``seqCmdBuff[j](packet, context)`` with an F´
command packet ``U16 FW_PACKET_COMMAND | U32 opcode | arguments``. The dispatcher gives every
dispatched command a sequence number, remembers ``(opcode, context, j)`` in its tracking table, and
when the component answers (``compCmdStat``), sends the response back out of ``seqCmdStatus[j]``
with the source's ``context`` in place of the sequence number — exactly as F´ does.

Nothing a command source sends can raise out of ``seqCmdBuff``: a malformed packet is reported by
``MalformedCommand`` and answered ``VALIDATION_ERROR``, an unknown opcode by ``InvalidCommand`` and
``INVALID_OPCODE``, a full tracking table by ``TooManyCommands`` and ``EXECUTION_ERROR``.

Requirements (F´ ``Svc/CmdDispatcher/docs/sdd.md``):

- CD-001 dispatch a command to the component that registered its opcode;
- CD-002 track each dispatched command and return its status to the source that sent it;
- CD-003 report registration, dispatch, completion and errors with events;
- CD-004 count dispatched commands and command errors in telemetry;
- CD-005 provide NO-OP commands to check the command path end to end.
"""

from __future__ import annotations

import logging
import struct
from typing import Annotated

from fprime_lite.model.commands import CmdResponse, async_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.errors import FwAssertionError
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Cmd, CmdReg, CmdResponsePort, Com, Ping, Sched
from fprime_lite.wire.packets import Apid
from fprime_lite.model.ports import OutputPort, async_input, guarded_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import F32, I32, U8, U32, FwEnum, String

__all__ = ["CmdDispatcher", "DeserialStatus", "COMMAND_PORTS", "SEQUENCE_PORTS",
           "SEQUENCER_TABLE_SIZE", "COM_BUFFER_MAX_SIZE"]

log = logging.getLogger("fprime_lite")

#: Size of ``compCmdReg`` / ``compCmdSend`` (F´ ``CmdDispatcherComponentCommandPorts``).
COMMAND_PORTS = 64
#: Size of ``seqCmdBuff`` / ``seqCmdStatus`` (F´ ``CmdDispatcherSequencePorts``).
SEQUENCE_PORTS = 8
#: Commands that may be in flight at once (F´ ``CMD_DISPATCHER_SEQUENCER_TABLE_SIZE``).
SEQUENCER_TABLE_SIZE = 25
#: Largest command packet accepted, descriptor included (F´ ``FW_COM_BUFFER_MAX_SIZE``).
COM_BUFFER_MAX_SIZE = 512

_CMD_HEADER = struct.Struct(">HI")
_U32_MAX = 0xFFFFFFFF


class DeserialStatus(FwEnum, namespace="Fw"):
    """Why a buffer did not deserialize (F´ ``Fw.DeserialStatus``, I32)."""

    OK = 0
    BUFFER_EMPTY = 3
    FORMAT_ERROR = 4
    SIZE_MISMATCH = 5
    TYPE_MISMATCH = 6


class CmdDispatcher(ActiveComponent):
    """F´'s command dispatcher (``Svc.CommandDispatcher``).

    Args:
        name: instance name, ``cmdDisp`` in deployments.
        base_id: added to the local opcodes (0–3), event ids (0–11) and channel ids (0–2).
        queue_size: depth of the message queue (commands, responses, command packets).
        tracking_size: how many dispatched commands may await their response at once.
    """

    # --- ports ---------------------------------------------------------------------------------

    #: ``compCmdSend[i]`` carries the commands whose opcodes were registered on ``compCmdReg[i]``.
    compCmdSend = OutputPort(Cmd, size=COMMAND_PORTS)
    #: ``seqCmdStatus[j]`` answers the commands that arrived on ``seqCmdBuff[j]``.
    seqCmdStatus = OutputPort(CmdResponsePort, size=SEQUENCE_PORTS)
    pingOut = OutputPort(Ping)

    # --- commands ------------------------------------------------------------------------------

    @async_command(opcode=0)
    def CMD_NO_OP(self):
        """No-op command: answers OK and logs NoOpReceived."""
        self.NoOpReceived()

    @async_command(opcode=1)
    def CMD_NO_OP_STRING(self, arg1: Annotated[str, String(40)]):
        """No-op command with a string, echoed by NoOpStringReceived."""
        self.NoOpStringReceived(arg1)

    @async_command(opcode=2)
    def CMD_TEST_CMD_1(self, arg1: I32, arg2: F32, arg3: U8):
        """Test command: echoes its three arguments with TestCmd1Args."""
        self.TestCmd1Args(arg1, arg2, arg3)

    @async_command(opcode=3)
    def CMD_CLEAR_TRACKING(self):
        """Forget every command awaiting a response (recovers from components that never answer)."""
        with self._lock:
            self._tracking.clear()

    # --- events (F´ ids, severities and formats) -----------------------------------------------

    OpCodeRegistered = Event(Severity.DIAGNOSTIC, "Opcode 0x{x} registered to port {} slot {}", id=0,
                             args=[("Opcode", U32), ("port", I32), ("slot", I32)])
    OpCodeDispatched = Event(Severity.COMMAND, "Opcode 0x{x} dispatched to port {}", id=1,
                             args=[("Opcode", U32), ("port", I32)])
    OpCodeCompleted = Event(Severity.COMMAND, "Opcode 0x{x} completed", id=2, args=[("Opcode", U32)])
    OpCodeError = Event(Severity.COMMAND, "Opcode 0x{x} completed with error {}", id=3,
                        args=[("Opcode", U32), ("error", CmdResponse)])
    MalformedCommand = Event(Severity.WARNING_HI, "Received malformed command packet. Status: {}", id=4,
                             args=[("Status", DeserialStatus)])
    InvalidCommand = Event(Severity.WARNING_HI, "Invalid opcode 0x{x} received", id=5,
                           args=[("Opcode", U32)])
    TooManyCommands = Event(Severity.WARNING_HI, "Too many outstanding commands. opcode=0x{x}", id=6,
                            args=[("Opcode", U32)])
    NoOpReceived = Event(Severity.ACTIVITY_HI, "Received a NO-OP command", id=7)
    NoOpStringReceived = Event(Severity.ACTIVITY_HI, "Received a NO-OP string={}", id=8,
                               args=[("message", String(40))])
    TestCmd1Args = Event(Severity.ACTIVITY_HI, "TEST_CMD_1 args: I32: {}, F32: {f}, U8: {}", id=9,
                         args=[("arg1", I32), ("arg2", F32), ("arg3", U8)])
    OpCodeReregistered = Event(Severity.DIAGNOSTIC, "Opcode 0x{x} is already registered to port {}",
                               id=10, args=[("Opcode", U32), ("port", I32)])
    CommandDroppedQueueOverflow = Event(
        Severity.WARNING_HI, "Opcode 0x{x} was dropped due to buffer overflow and not processed. Context {}",
        id=11, throttle=5, args=[("OpCode", U32), ("Context", U32)])

    # --- telemetry -----------------------------------------------------------------------------

    CommandsDispatched = Channel(U32, id=0, update="on change")
    CommandErrors = Channel(U32, id=1, update="on change")
    CommandsDropped = Channel(U32, id=2, update="on change")

    def __init__(self, name: str = "cmdDisp", *, base_id: int = 0, queue_size: int = 20,
                 tracking_size: int = SEQUENCER_TABLE_SIZE):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        if not isinstance(tracking_size, int) or tracking_size < 1:
            raise ValueError(f"{name}: tracking_size must be a positive integer, got {tracking_size!r}")
        self.tracking_size = tracking_size
        #: opcode -> compCmdSend index, in registration order (the "slot" is the position).
        self._dispatch_table: dict[int, int] = {}
        #: cmd sequence number -> (opcode, source context, seqCmdStatus index).
        self._tracking: dict[int, tuple[int, int, int]] = {}
        self._seq = 0
        self.commands_dispatched = 0
        self.command_errors = 0
        self.commands_dropped = 0

    # --- registration --------------------------------------------------------------------------

    @guarded_input(CmdReg, size=COMMAND_PORTS)
    def compCmdReg(self, port_num: int, opcode: int) -> None:
        """Register ``opcode`` for dispatch through ``compCmdSend[port_num]`` (CD-001)."""
        existing = self._dispatch_table.get(opcode)
        if existing is None:
            slot = len(self._dispatch_table)
            self._dispatch_table[opcode] = port_num
            self.OpCodeRegistered(opcode, port_num, slot)
        elif existing == port_num:
            self.OpCodeReregistered(opcode, port_num)
        else:
            raise FwAssertionError(
                f"{self.name}.compCmdReg[{port_num}]: opcode 0x{opcode:X} is already registered on "
                f"compCmdReg[{existing}] ({self.output_port('compCmdSend').target_name(existing) or 'unconnected'}); "
                f"two components share an opcode — give them distinct base ids")

    @property
    def dispatch_table(self) -> dict[int, int]:
        """A copy of the registrations: opcode -> ``compCmdSend`` index."""
        return dict(self._dispatch_table)

    @property
    def pending(self) -> dict[int, tuple[int, int, int]]:
        """A copy of the tracking table: sequence number -> (opcode, context, source index)."""
        with self._lock:
            return dict(self._tracking)

    # --- command packets -----------------------------------------------------------------------

    @async_input(Com, size=SEQUENCE_PORTS, queue_full="hook")
    def seqCmdBuff(self, port_num: int, data: bytes, context: int) -> None:
        """Dispatch the command packet ``data``; answer on ``seqCmdStatus[port_num]`` (CD-001, CD-002)."""
        opcode, args, status = _parse_command(data)
        if status is not DeserialStatus.OK:
            self.MalformedCommand(status)
            self._answer(port_num, opcode, context, CmdResponse.VALIDATION_ERROR)
            return
        entry = self._dispatch_table.get(opcode)
        if entry is None or not self.is_connected("compCmdSend", entry):
            self.InvalidCommand(opcode)
            self._count_error()
            self._answer(port_num, opcode, context, CmdResponse.INVALID_OPCODE)
            self._next_seq()
            return
        seq = self._seq
        tracked = self.is_connected("seqCmdStatus", port_num)
        if tracked:
            with self._lock:
                full = len(self._tracking) >= self.tracking_size
                if not full:
                    self._tracking[seq] = (opcode, context, port_num)
            if full:
                self.TooManyCommands(opcode)
                self._answer(port_num, opcode, context, CmdResponse.EXECUTION_ERROR)
                return
        try:
            self.compCmdSend[entry](opcode, seq, args)
        except Exception as exc:  # noqa: BLE001 - a faulty target must not take the dispatcher down
            self.report_fault(f"compCmdSend[{entry}] 0x{opcode:X}", exc)
            with self._lock:
                self._tracking.pop(seq, None)
            self.OpCodeError(opcode, CmdResponse.EXECUTION_ERROR)
            self._count_error()
            self._answer(port_num, opcode, context, CmdResponse.EXECUTION_ERROR)
            self._next_seq()
            return
        self.OpCodeDispatched(opcode, entry)
        self.commands_dispatched = (self.commands_dispatched + 1) & _U32_MAX
        self.CommandsDispatched.write(self.commands_dispatched)
        self._next_seq()

    def seqCmdBuff_overflow_hook(self, port_num: int, data: bytes, context: int) -> None:
        """The queue was full: the packet is dropped, counted and reported (F´ overflow hook)."""
        opcode, _, status = _parse_command(data)
        self.commands_dropped = (self.commands_dropped + 1) & _U32_MAX
        self.CommandDroppedQueueOverflow(opcode if status is DeserialStatus.OK else 0, context & _U32_MAX)
        self.CommandsDropped.write(self.commands_dropped)

    @async_input(CmdResponsePort)
    def compCmdStat(self, opcode: int, cmd_seq: int, response) -> None:
        """A component answered command ``cmd_seq``: log it and tell its source (CD-002, CD-003)."""
        try:
            response = CmdResponse(response)
        except ValueError:
            log.warning("%s: compCmdStat: response %r to opcode 0x%X is not a CmdResponse; "
                        "treating it as EXECUTION_ERROR", self.name, response, opcode)
            response = CmdResponse.EXECUTION_ERROR
        if response == CmdResponse.OK:
            self.OpCodeCompleted(opcode)
        else:
            self._count_error()
            self.OpCodeError(opcode, response)
        with self._lock:
            entry = self._tracking.pop(cmd_seq, None)
        if entry is None:
            return
        tracked_opcode, context, source = entry
        if tracked_opcode != opcode:
            log.warning("%s: compCmdStat: sequence %d was opcode 0x%X but the response names 0x%X",
                        self.name, cmd_seq, tracked_opcode, opcode)
        self._answer(source, opcode, context, response)

    # --- housekeeping --------------------------------------------------------------------------

    @async_input(Sched)
    def run(self, context: int) -> None:
        """Rate-group tick: write the three counters (F´ v4 writes them here)."""
        self.CommandsDropped.write(self.commands_dropped)
        self.CommandErrors.write(self.command_errors)
        self.CommandsDispatched.write(self.commands_dispatched)

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    def _answer(self, port_num: int, opcode: int, context: int, response: CmdResponse) -> None:
        if self.is_connected("seqCmdStatus", port_num):
            self.seqCmdStatus[port_num](opcode, context, response)

    def _count_error(self) -> None:
        self.command_errors = (self.command_errors + 1) & _U32_MAX
        self.CommandErrors.write(self.command_errors)

    def _next_seq(self) -> None:
        self._seq = (self._seq + 1) & _U32_MAX


def _parse_command(data) -> tuple[int, bytes, DeserialStatus]:
    """``(opcode, argument bytes, status)`` of a command packet; never raises."""
    try:
        raw = bytes(data)
    except (TypeError, ValueError):
        return 0, b"", DeserialStatus.FORMAT_ERROR
    if len(raw) < 2:
        return 0, b"", DeserialStatus.BUFFER_EMPTY
    descriptor = int.from_bytes(raw[:2], "big")
    if descriptor != Apid.FW_PACKET_COMMAND:
        return 0, b"", DeserialStatus.TYPE_MISMATCH
    if len(raw) < _CMD_HEADER.size:
        return 0, b"", DeserialStatus.BUFFER_EMPTY
    _, opcode = _CMD_HEADER.unpack_from(raw)
    if len(raw) > COM_BUFFER_MAX_SIZE:
        return opcode, b"", DeserialStatus.SIZE_MISMATCH
    return opcode, raw[_CMD_HEADER.size:], DeserialStatus.OK
