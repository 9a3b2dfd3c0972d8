"""Svc.FileDownlink: sends on-board files to the ground as F´ file packets, a few per rate-group tick.

F´'s ``Svc.FileDownlink`` (instance ``fileDownlink`` of F´ v4's FileHandling subtopology), with its
commands, events and channels as F´ v4.0 declares them (names, opcodes, ids, severities, argument
types and string sizes, format strings), so fprime-gds 4.4.1 commands it and decodes what it says.

Requests. Operators ask with ``SendFile(sourceFileName, destFileName)`` or ``SendPartial(...,
startOffset, length)``; components ask through the ``sendFile`` port, which answers at once with a
:class:`SendFileResponse` (``STATUS_OK`` and a context number, or ``STATUS_ERROR`` when the file
queue is full) and reports the end of that transfer on ``FileComplete`` with the same context.
Requests wait in a file queue (``file_queue_depth``, F´'s FileHandling uses 10) and are sent one
file at a time, in order: a request that arrives while a file is going out is queued, not refused,
exactly as in F´. A command is answered when *its* transfer ends (a deferred response): OK once
END has gone out; EXECUTION_ERROR when the file cannot be opened or read, when the transfer is
cancelled, or when the queue is full; VALIDATION_ERROR when a partial range starts at or beyond
the end of the file (F´'s ``STATUS_INVALID``).

Packet flow. Each ``Run`` tick (a rate-group member) sends at most ``packets_per_tick`` packets out
of ``bufferSendOut``, each a ``Fw.BufferSend`` of ``U16 FW_PACKET_FILE | file packet`` bytes:

1. START (sequence 0): the size of the whole file, the source and destination names as given;
   then the SendStarted event with the number of bytes that will be sent;
2. DATA (sequence 1, 2, …): consecutive chunks of at most ``data_size`` bytes, each read from the
   file when it is sent (only one chunk is in memory), with its file offset;
3. END (next sequence): the CFDP checksum of the bytes sent, at their file offsets; then
   FilesSent, FileSent and the OK response.

The next queued file starts in the same tick if packets remain in the budget. A relative source
name is opened under ``root``; the packets and events carry it as the operator wrote it. Sources
are confined to ``root`` (topology arg; in a run started by ``fprime-lite run`` the run's folder
unless the topology names one): a name that leaves it — ``..``, an absolute path elsewhere, a
symbolic link pointing outside — is refused with ``PathRefused`` (Os::File NO_PERMISSION, 3) and
FileOpenError, and its request ends with EXECUTION_ERROR (``STATUS_ERROR``).

SendPartial, as F´: ``length`` 0 means to the end of the file; ``startOffset`` at or past the end
→ DownlinkPartialFail and VALIDATION_ERROR (an empty file is such a case, also for SendFile, as in
F´ v4.0); ``startOffset + length`` past the end → DownlinkPartialWarning and the range is cut at the
end of the file. Cancel (always answered OK) stops the file being sent: if data remains, a CANCEL
packet goes out on the next tick, DownlinkCanceled is logged and the transfer's requester gets
EXECUTION_ERROR; if all the data has gone already, the END packet follows as usual and the file
counts as sent (F´'s rule). Queued requests are not touched by Cancel.

Errors. A file that is missing, not a regular file, unreadable or over 4 GiB → FileOpenError
(Warnings + 1). A read that fails, comes back short, or finds the file's size changed since START →
FileReadError with F´'s ``Os::File::Status`` code (``BAD_SIZE`` 4 for size changes) then
SendDataFail (Warnings + 1). A source or destination name longer than the 255 bytes a START packet
can carry is refused at once with FileNameTooLong (only ``sendFile`` can pass such a name: the
commands' strings hold 100 bytes). Nothing raises out of a port or command: a receiver on
``bufferSendOut`` that raises fails the transfer (SendDataFail, EXECUTION_ERROR), one on
``FileComplete`` is logged, a ``sendFile`` call with bad arguments answers ``STATUS_INVALID``.

Differences from F´
-------------------
- **No buffer-return handshake, timeout or cooldown.** F´ sends one packet, waits in WAIT until
  that buffer comes back on ``bufferReturn`` (DownlinkTimeout after ``timeout`` ms), and rests for
  ``cooldown`` ms between files, because its buffers are borrowed memory. Here a packet is
  ``bytes`` handed on and kept by the receiver, so there is nothing to wait for: the
  ``packets_per_tick`` budget paces the link instead. There is no ``bufferReturn`` port, no
  ``configure(timeout, cooldown, cycleTime, fileQueueDepth)`` (the depth is a constructor
  argument) and DownlinkTimeout (id 4) is declared for the dictionary but never logged. The next
  queued file may start in the tick the previous one ended (F´: after the cooldown).
- **The request port is named ``sendFile``** (F´ v4: ``SendFile``, the name its SDD writes in lower
  case) because a Python class cannot hold both the ``SendFile`` command and a port of that name.
  Event and text-event ports are the framework's ``logOut`` / ``logTextOut`` (F´: ``eventOut`` /
  ``textEventOut``).
- **Failure responses.** F´'s default ``FILEDOWNLINK_COMMAND_FAILURES_DISABLED = true`` answers OK
  even to failed transfers, and F´ answers a cancelled transfer with OK (``STATUS_OK``) in every
  configuration. Here failures answer as F´ does with that option off (EXECUTION_ERROR, or
  VALIDATION_ERROR for DownlinkPartialFail) and a cancelled transfer answers EXECUTION_ERROR
  (``STATUS_ERROR`` on ``FileComplete``). ``command_failures_disabled=True`` gives F´'s default:
  every transfer, failed or cancelled, answers OK.
- **Cancel waits for the next tick** for the CANCEL packet and the DownlinkCanceled event (F´ waits
  for the next buffer return); the Cancel command itself is answered at once, as in F´.
- A file whose size changes while it is sent is caught by comparing its size before each chunk
  (F´ only notices a file that shrank, through a short read); growth is a FileReadError too.
- Names: ``sendFile`` accepts names up to 255 bytes (F´ asserts beyond its 100-byte strings);
  events carry the first 100 bytes. FileNameTooLong (id 0x40) is not in F´. A port call with a
  non-string name or an offset/length outside U32 answers ``STATUS_INVALID`` (F´ cannot receive one).
- ``Run`` drops a tick when the message queue is full (F´: assert).
- ``startOffset + length`` is computed without U32 wrap-around (F´ adds in U32).
- An unconnected ``bufferSendOut`` leaves requests queued (logged once) instead of asserting.
"""

from __future__ import annotations

import collections
import logging
import os
import stat as _stat
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated

from fprime_lite.osal.confine import PathRefused
from fprime_lite.osal.os_status import FileStatus, file_status
from fprime_lite.model.commands import CmdResponse, CommandToken, async_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.svc.file_root import FileRoot
from fprime_lite.wire.file_packet import (MAX_PATH_BYTES, CancelPacket, CfdpChecksum, DataPacket, EndPacket,
                           StartPacket, encode_file_packet)
from fprime_lite.model.fw_ports import BufferSend, Ping, Sched
from fprime_lite.model.ports import OutputPort, PortType, async_input, guarded_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import I32, U32, FwEnum, String, Struct, fit_utf8

__all__ = ["DEFAULT_DATA_SIZE", "DEFAULT_FILE_QUEUE_DEPTH", "DEFAULT_PACKETS_PER_TICK",
           "FILE_DOWN_COMPLETE_PORTS", "FILE_NAME_SIZE", "FileDownlink", "OsFileStatus",
           "SendFileComplete", "SendFileRequest", "SendFileResponse", "SendFileStatus"]

log = logging.getLogger("fprime_lite")

#: Bound of the file names of F´'s commands, events and SendFileRequest port (``string size 100``).
FILE_NAME_SIZE = 100
#: F´ v4's DATA chunk: ``FILEDOWNLINK_INTERNAL_BUFFER_SIZE`` (= ``FW_FILE_BUFFER_MAX_SIZE`` =
#: ``FW_COM_BUFFER_MAX_SIZE`` = 512) minus the DATA header (11 bytes) and the packet descriptor
#: (2 bytes): every packet, descriptor included, fits the 512-byte com buffer.
DEFAULT_DATA_SIZE = 512 - 11 - 2
#: Packets per Run tick; see :class:`FileDownlink` for the reasoning.
DEFAULT_PACKETS_PER_TICK = 10
#: F´ FileHandling's ``FILE_DOWNLINK_FILE_QUEUE_DEPTH``.
DEFAULT_FILE_QUEUE_DEPTH = 10
#: F´'s ``FileDownCompletePorts``.
FILE_DOWN_COMPLETE_PORTS = 1

_NAME = String(FILE_NAME_SIZE)
_U32_MAX = 0xFFFFFFFF


class SendFileStatus(FwEnum, namespace="Svc"):
    """Status of a request made through the ``sendFile`` port (F´ ``Svc.SendFileStatus``)."""

    STATUS_OK = 0
    STATUS_ERROR = 1
    STATUS_INVALID = 2
    STATUS_BUSY = 3


class SendFileResponse(Struct, namespace="Svc"):
    """What ``sendFile`` returns and ``FileComplete`` reports (F´ ``Svc.SendFileResponse``)."""

    status: SendFileStatus
    context: U32


#: Ask FileDownlink to send ``sourceFileName`` (from ``offset``, ``length`` bytes; 0 = to the end).
SendFileRequest = PortType("Svc.SendFileRequest", returns=SendFileResponse, sourceFileName=_NAME,
                           destFileName=_NAME, offset=U32, length=U32)
#: The end of a transfer requested through ``sendFile``, with the request's context.
SendFileComplete = PortType("Svc.SendFileComplete", resp=SendFileResponse)


#: F´'s ``Os::File::Status`` (v4.2 numbering, declared once in :mod:`fprime_lite.osal.os_status`).
OsFileStatus = FileStatus


def _os_status(exc: OSError) -> FileStatus:
    return file_status(exc)


def _cut(text: str, size: int = FILE_NAME_SIZE) -> str:
    """``text`` cut to ``size`` UTF-8 bytes on a character boundary (event string arguments)."""
    return fit_utf8(text, size)


def _name_bytes(name: str) -> int | None:
    """UTF-8 length of ``name``, or None when it cannot be encoded (lone surrogates)."""
    try:
        return len(name.encode("utf-8"))
    except UnicodeEncodeError:
        return None


@dataclass
class _Request:
    """One queued file: from a command (``token``) or from the ``sendFile`` port (``context``)."""

    source: str
    dest: str
    offset: int
    length: int
    token: CommandToken | None = None
    context: int = _U32_MAX


class _Transfer:
    """The file being sent."""

    __slots__ = ("cancel", "checksum", "end", "file", "log_dest", "log_source", "offset", "request",
                 "sequence", "size")

    def __init__(self, request: _Request, file, size: int, end: int):
        self.request = request
        self.file = file
        self.size = size            # whole file, as START announces it
        self.end = end              # one past the last byte to send
        self.offset = request.offset  # next byte to send
        self.sequence = 1           # START was 0
        self.checksum = CfdpChecksum()
        self.cancel = False
        self.log_source = _cut(request.source)
        self.log_dest = _cut(request.dest)


class FileDownlink(FileRoot, ActiveComponent):
    """Sends files to the ground as F´ file packets (F´ ``Svc.FileDownlink``).

    Args:
        name, base_id, queue_size: as every active component (F´ FileHandling: queue size 10).
        root: directory that relative source names are opened under (default: the current
            directory when the component is made).
        packets_per_tick: most packets sent per ``Run`` tick. The default, 10, sends ≈5 KiB per
            tick: ≈50 KiB/s from a 10 Hz rate group (a 1 MiB file in about 20 s), ≈5 KiB/s at
            1 Hz, while one tick's work stays a fraction of a millisecond and a tick adds little
            to the ground link's downlink queue (2048 packets) — file traffic cannot crowd out
            events and telemetry there.
        data_size: most file bytes per DATA packet; default 499, F´ v4's (see
            :data:`DEFAULT_DATA_SIZE`). At most 65535 (DATA's U16 length).
        file_queue_depth: requests that may wait (F´ FileHandling: 10); a request beyond that is
            refused (EXECUTION_ERROR, or ``STATUS_ERROR`` on the port).
        command_failures_disabled: F´'s ``FILEDOWNLINK_COMMAND_FAILURES_DISABLED``: answer OK (and
            ``STATUS_OK``) even when a transfer fails or is cancelled. Off by default here.
    """

    # --- ports ------------------------------------------------------------------------------------
    bufferSendOut = OutputPort(BufferSend)
    FileComplete = OutputPort(SendFileComplete, size=FILE_DOWN_COMPLETE_PORTS)
    pingOut = OutputPort(Ping)

    # --- channels (F´ ids) ------------------------------------------------------------------------
    FilesSent = Channel(U32, id=0x00)
    PacketsSent = Channel(U32, id=0x01)
    Warnings = Channel(U32, id=0x02)

    # --- events (F´ ids, severities and formats) --------------------------------------------------
    FileOpenError = Event(Severity.WARNING_HI, "Could not open file {}", id=0x00, fileName=_NAME)
    FileReadError = Event(Severity.WARNING_HI, "Could not read file {} with status {}", id=0x01,
                          fileName=_NAME, status=I32)
    FileSent = Event(Severity.ACTIVITY_HI, "Sent file {} to file {}", id=0x02,
                     sourceFileName=_NAME, destFileName=_NAME)
    DownlinkCanceled = Event(Severity.ACTIVITY_HI, "Canceled downlink of file {} to file {}", id=0x03,
                             sourceFileName=_NAME, destFileName=_NAME)
    #: Declared as F´ v4.0 does; never logged here (no buffer to wait for, see the module docstring).
    DownlinkTimeout = Event(Severity.WARNING_HI,
                            "Timeout occurred during downlink of file {} to file {}. Downlink has been canceled.",
                            id=0x04, sourceFileName=_NAME, destFileName=_NAME)
    DownlinkPartialWarning = Event(
        Severity.WARNING_LO,
        "Offset {} plus length {} is greater than source size {} for partial downlink of file {} to file {}. ",
        id=0x05, startOffset=U32, length=U32, filesize=U32, sourceFileName=_NAME, destFileName=_NAME)
    DownlinkPartialFail = Event(
        Severity.WARNING_HI,
        "Error occurred during partial downlink of file {} to file {}. Offset {} greater than or equal "
        "to source filesize {}.",
        id=0x06, sourceFileName=_NAME, destFileName=_NAME, startOffset=U32, filesize=U32)
    SendDataFail = Event(Severity.WARNING_HI, "Failed to send data packet from file {} at byte offset {}.",
                         id=0x07, sourceFileName=_NAME, byteOffset=U32)
    SendStarted = Event(Severity.ACTIVITY_HI, "Downlink of {} bytes started from {} to {}", id=0x08,
                        fileSize=U32, sourceFileName=_NAME, destFileName=_NAME)
    #: Not in F´: a name longer than a START packet can carry (255 bytes); the request is refused.
    FileNameTooLong = Event(Severity.WARNING_HI,
                            "File name {} is {} bytes; a file packet carries at most {} bytes", id=0x40,
                            fileName=_NAME, size=U32, limit=U32)
    #: Not in F´: a source outside ``root``; the request is refused.
    PathRefused = Event(Severity.WARNING_HI, "File {} refused (Os::File status {}): {}", id=0x41,
                        fileName=_NAME, status=I32, reason=String(40))

    def __init__(self, name: str = "fileDownlink", *, base_id: int = 0, queue_size: int = 10,
                 root: str | os.PathLike | None = None,
                 packets_per_tick: int = DEFAULT_PACKETS_PER_TICK,
                 data_size: int = DEFAULT_DATA_SIZE,
                 file_queue_depth: int = DEFAULT_FILE_QUEUE_DEPTH,
                 command_failures_disabled: bool = False):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        for label, value, high in (("packets_per_tick", packets_per_tick, None),
                                   ("data_size", data_size, 0xFFFF),
                                   ("file_queue_depth", file_queue_depth, None)):
            if isinstance(value, bool) or not isinstance(value, int) or value < 1 \
                    or (high is not None and value > high):
                bound = f" and at most {high}" if high is not None else ""
                raise ValueError(f"{name}: {label} must be an integer of at least 1{bound}, got {value!r}")
        self._init_root(root)
        self.packets_per_tick = packets_per_tick
        self.data_size = data_size
        self.file_queue_depth = file_queue_depth
        self.command_failures_disabled = bool(command_failures_disabled)
        self._requests: collections.deque[_Request] = collections.deque()
        self._transfer: _Transfer | None = None
        self._context = 0            # next sendFile context (U32, wraps)
        self._files_sent = 0
        self._packets_sent = 0
        self._warnings = 0
        self._unconnected_logged = False

    # --- root ------------------------------------------------------------------------------------

    @property
    def root(self) -> Path:
        """The directory every source lies in (symbolic links resolved)."""
        return Path(self.root_path)


    # --- state, for tests and summaries ----------------------------------------------------------

    @property
    def busy(self) -> bool:
        """A file is being sent."""
        return self._transfer is not None

    @property
    def queued(self) -> int:
        """Requests waiting behind the current file."""
        return len(self._requests)

    # --- commands ---------------------------------------------------------------------------------

    @async_command(opcode=0x00)
    def SendFile(self, sourceFileName: Annotated[str, String(FILE_NAME_SIZE)],
                 destFileName: Annotated[str, String(FILE_NAME_SIZE)]):
        """Queue ``sourceFileName`` for downlink to ``destFileName``; answered when it has been sent."""
        return self._command_request(sourceFileName, destFileName, 0, 0)

    @async_command(opcode=0x01)
    def Cancel(self):
        """Stop the file being sent, if any (queued files stay queued). Always OK."""
        transfer = self._transfer
        if transfer is not None:
            transfer.cancel = True
        return CmdResponse.OK

    @async_command(opcode=0x02)
    def SendPartial(self, sourceFileName: Annotated[str, String(FILE_NAME_SIZE)],
                    destFileName: Annotated[str, String(FILE_NAME_SIZE)], startOffset: U32, length: U32):
        """Queue ``length`` bytes (0: to the end) of ``sourceFileName`` from ``startOffset``."""
        return self._command_request(sourceFileName, destFileName, startOffset, length)

    # --- input ports ------------------------------------------------------------------------------

    @guarded_input(SendFileRequest)
    def sendFile(self, sourceFileName, destFileName, offset, length):
        """A component asks for a file (``length`` 0: to the end); the end comes on FileComplete."""
        for value in (offset, length):
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= _U32_MAX:
                log.warning("%s: sendFile: offset and length must be U32 integers, got %r, %r",
                            self.name, offset, length)
                return SendFileResponse(SendFileStatus.STATUS_INVALID, _U32_MAX)
        for value in (sourceFileName, destFileName):
            if not isinstance(value, str) or _name_bytes(value) is None:
                log.warning("%s: sendFile: file names must be UTF-8 text, got %r, %r",
                            self.name, sourceFileName, destFileName)
                return SendFileResponse(SendFileStatus.STATUS_INVALID, _U32_MAX)
        if not self._names_fit(sourceFileName, destFileName):
            return SendFileResponse(SendFileStatus.STATUS_INVALID, _U32_MAX)
        with self._lock:
            if len(self._requests) >= self.file_queue_depth:
                log.warning("%s: sendFile: file queue full (%d); %r refused", self.name,
                            self.file_queue_depth, sourceFileName)
                return SendFileResponse(SendFileStatus.STATUS_ERROR, _U32_MAX)
            context = self._context
            self._context = (context + 1) & _U32_MAX
            self._requests.append(_Request(sourceFileName, destFileName, offset, length, context=context))
        return SendFileResponse(SendFileStatus.STATUS_OK, context)

    @async_input(Sched, queue_full="drop")
    def Run(self, context):
        """Rate-group tick: send up to ``packets_per_tick`` packets, starting queued files as needed."""
        if not self.is_connected("bufferSendOut", 0):
            if self._requests and not self._unconnected_logged:  # quiet until there is a file to send
                self._unconnected_logged = True
                log.warning("%s: bufferSendOut is not connected; file requests stay queued", self.name)
            return
        budget = self.packets_per_tick
        while budget > 0:
            transfer = self._transfer
            if transfer is None:
                with self._lock:
                    request = self._requests.popleft() if self._requests else None
                if request is None:
                    break
                if self._begin(request):
                    budget -= 1
                continue
            if transfer.offset < transfer.end:
                if transfer.cancel:
                    self._send_cancel(transfer)
                else:
                    self._send_data(transfer)
            else:
                self._send_end(transfer)
            budget -= 1

    @async_input(Ping)
    def pingIn(self, key):
        """Health ping: answer with the same key."""
        self.pingOut[0](key)

    # --- requests ---------------------------------------------------------------------------------

    def _command_request(self, source: str, dest: str, offset: int, length: int) -> CmdResponse | None:
        if not self._names_fit(source, dest):
            return CmdResponse.VALIDATION_ERROR
        with self._lock:
            if len(self._requests) >= self.file_queue_depth:
                log.warning("%s: file queue full (%d); %r refused", self.name, self.file_queue_depth, source)
                return CmdResponse.EXECUTION_ERROR
            self._requests.append(_Request(source, dest, offset, length, token=self.defer_command_response()))
        return None

    def _names_fit(self, source: str, dest: str) -> bool:
        """Both names fit a START packet; else FileNameTooLong for the first that does not."""
        for name in (source, dest):
            size = _name_bytes(name)
            if size is not None and size > MAX_PATH_BYTES:
                self.FileNameTooLong(_cut(name), size, MAX_PATH_BYTES)
                return False
        return True

    def _resolve(self, source: str) -> Path:
        """The confined real path of ``source`` (raises PathRefused)."""
        return Path(self._confinement.contents(source))

    # --- the transfer -----------------------------------------------------------------------------

    def _begin(self, request: _Request) -> bool:
        """Open the file, check the range, send START. True when START went out."""
        log_source = _cut(request.source)
        try:
            self._resolve(request.source)
        except PathRefused as refused:
            log.warning("%s: %s refused (root %s)", self.name, refused, self.root)
            self.PathRefused(log_source, int(FileStatus.NO_PERMISSION), fit_utf8(refused.reason, 40))
            file = None
        except ValueError:
            file = None  # a NUL byte: cannot be opened
        else:
            file = self._open(request.source)
        if file is None:
            self.FileOpenError(log_source)
            self._warning()
            self._finish_request(request, SendFileStatus.STATUS_ERROR)
            return False
        try:
            size = os.fstat(file.fileno()).st_size
        except OSError:
            size = None
        if size is None or size > _U32_MAX:
            file.close()
            self.FileOpenError(log_source)
            self._warning()
            self._finish_request(request, SendFileStatus.STATUS_ERROR)
            return False
        start, length = request.offset, request.length
        if start >= size:
            file.close()
            self.DownlinkPartialFail(log_source, _cut(request.dest), start, size)
            self._finish_request(request, SendFileStatus.STATUS_INVALID)
            return False
        if start + length > size:
            self.DownlinkPartialWarning(start, length, size, log_source, _cut(request.dest))
            length = size - start
        end = start + length if length > 0 else size
        transfer = _Transfer(request, file, size, end)
        self._transfer = transfer
        if not self._send(transfer, StartPacket(0, size, request.source, request.dest)):
            return False
        self.SendStarted(end - start, transfer.log_source, transfer.log_dest)
        return True

    def _open(self, source: str):
        """The file opened for reading (unbuffered), or None. Never blocks on a FIFO."""
        try:
            fd = os.open(self._resolve(source), os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                         | getattr(os, "O_BINARY", 0))
        except (OSError, ValueError) as exc:  # ValueError: an embedded NUL
            log.info("%s: cannot open %r: %s", self.name, source, exc)
            return None
        try:
            if not _stat.S_ISREG(os.fstat(fd).st_mode):
                log.info("%s: %r is not a regular file", self.name, source)
                os.close(fd)
                return None
            return os.fdopen(fd, "rb", buffering=0)
        except OSError as exc:
            log.info("%s: cannot open %r: %s", self.name, source, exc)
            os.close(fd)
            return None

    def _send_data(self, transfer: _Transfer) -> None:
        offset = transfer.offset
        count = min(self.data_size, transfer.end - offset)
        data, status = self._read(transfer, offset, count)
        if status is not OsFileStatus.OP_OK:
            self.FileReadError(transfer.log_source, int(status))
            self._warning()
            self.SendDataFail(transfer.log_source, offset)
            self._finish(transfer, SendFileStatus.STATUS_ERROR)
            return
        transfer.checksum.update(data, offset)
        sequence = transfer.sequence
        if self._send(transfer, DataPacket(sequence, offset, data)):
            transfer.sequence = (sequence + 1) & _U32_MAX
            transfer.offset = offset + count

    @staticmethod
    def _read(transfer: _Transfer, offset: int, count: int) -> tuple[bytes, OsFileStatus]:
        """``count`` bytes at ``offset``; BAD_SIZE when the file changed size or came back short."""
        file = transfer.file
        try:
            if os.fstat(file.fileno()).st_size != transfer.size:
                return b"", OsFileStatus.BAD_SIZE
            file.seek(offset)
            parts = []
            left = count
            while left > 0:
                part = file.read(left)
                if not part:
                    break
                parts.append(part)
                left -= len(part)
        except OSError as exc:
            return b"", _os_status(exc)
        if left:
            return b"", OsFileStatus.BAD_SIZE
        return b"".join(parts), OsFileStatus.OP_OK

    def _send_end(self, transfer: _Transfer) -> None:
        if self._send(transfer, EndPacket(transfer.sequence, transfer.checksum.value)):
            self._files_sent = (self._files_sent + 1) & _U32_MAX
            self.FilesSent.write(self._files_sent)
            self.FileSent(transfer.log_source, transfer.log_dest)
            self._finish(transfer, SendFileStatus.STATUS_OK)

    def _send_cancel(self, transfer: _Transfer) -> None:
        if self._send(transfer, CancelPacket(transfer.sequence)):
            self.DownlinkCanceled(transfer.log_source, transfer.log_dest)
            self._finish(transfer, SendFileStatus.STATUS_ERROR)

    def _send(self, transfer: _Transfer, packet) -> bool:
        """Hand one packet to ``bufferSendOut``; a receiver that raises fails the transfer."""
        try:
            self.bufferSendOut[0](encode_file_packet(packet, descriptor=True))
        except Exception as exc:  # noqa: BLE001 - a downstream fault must not escape the rate group
            self.report_fault(f"bufferSendOut ({type(packet).__name__})", exc)
            self.SendDataFail(transfer.log_source, transfer.offset & _U32_MAX)
            self._finish(transfer, SendFileStatus.STATUS_ERROR)
            return False
        self._packets_sent = (self._packets_sent + 1) & _U32_MAX
        self.PacketsSent.write(self._packets_sent)
        return True

    def _finish(self, transfer: _Transfer, status: SendFileStatus) -> None:
        try:
            transfer.file.close()
        except OSError:
            pass
        if self._transfer is transfer:
            self._transfer = None
        self._finish_request(transfer.request, status)

    def _finish_request(self, request: _Request, status: SendFileStatus) -> None:
        """Answer the requester: the command's deferred response, or FileComplete for a port request."""
        if self.command_failures_disabled:
            status = SendFileStatus.STATUS_OK
        if request.token is not None:
            self.command_response(request.token, _CMD_RESPONSE[status])
            return
        response = SendFileResponse(status, request.context)
        for index in range(FILE_DOWN_COMPLETE_PORTS):
            if self.is_connected("FileComplete", index):
                try:
                    self.FileComplete[index](response)
                except Exception as exc:  # noqa: BLE001 - a listener's fault must not escape the downlink
                    self.report_fault(f"FileComplete[{index}]", exc)

    def _warning(self) -> None:
        """F´'s ``Warnings::warning()``: count a FileOpenError or FileReadError."""
        self._warnings = (self._warnings + 1) & _U32_MAX
        self.Warnings.write(self._warnings)


#: F´'s ``statusToCmdResp``.
_CMD_RESPONSE = {
    SendFileStatus.STATUS_OK: CmdResponse.OK,
    SendFileStatus.STATUS_ERROR: CmdResponse.EXECUTION_ERROR,
    SendFileStatus.STATUS_INVALID: CmdResponse.VALIDATION_ERROR,
    SendFileStatus.STATUS_BUSY: CmdResponse.BUSY,
}
