"""FileUplink: puts files sent from the ground back together on board.

F´'s ``Svc.FileUplink`` (instance ``fileUplink`` in F´'s FileHandling subtopology). The ground
system cuts a file into file packets (:mod:`fprime_lite.wire.file_packet`); the ground link removes each
packet's ``FW_PACKET_FILE`` descriptor and hands the rest to ``bufferSendIn``, one packet per call.
The component has two receive modes, START (the initial one: waiting for a file) and DATA (a file
is being received):

- **START** ``(size, source, destination)``: begins a file. A START that arrives in DATA mode
  abandons the file in progress (``InvalidReceiveMode``). If the destination cannot be opened for
  writing: ``FileOpenError`` and the component stays in START mode; otherwise it goes to DATA mode
  with the last sequence index set to 0. Each START re-arms the throttles of FileWriteError,
  InvalidReceiveMode, PacketOutOfBounds and PacketOutOfOrder (not PacketDuplicate), as F´ does.
- **DATA** ``(sequence, offset, bytes)``: in START mode, ``InvalidReceiveMode`` and the packet is
  ignored. A packet with the same index as the previous one, when that one was written, is a
  ``PacketDuplicate`` and is skipped (its bytes are not added twice to the checksum). Otherwise an
  index other than previous + 1 is a ``PacketOutOfOrder`` (the packet is still used, and its index
  becomes the previous one); bytes that would end beyond the size announced by START are a
  ``PacketOutOfBounds`` and are not written; the rest are written at their offset and added to the
  CFDP checksum.
- **END** ``(sequence, checksum)``: in DATA mode, the index is checked as for DATA, then the
  checksum the ground computed is compared with the one computed from the bytes written. Equal:
  the file is put in place, ``FilesReceived`` counts it, ``FileReceived`` is logged and the path is
  announced on ``fileAnnounce`` (if connected). Different: ``BadChecksum`` and ``FilesReceivedFailed``.
  In START mode: ``InvalidReceiveMode``. Either way the component returns to START mode.
- **CANCEL**: ``UplinkCanceled``; the file in progress (if any) is abandoned; START mode.

Bytes that are not a file packet are a ``DecodeError`` whose status is F´'s ``Fw::SerializeStatus``
(3 buffer empty — the packet is cut short, 4 format error, 5 size mismatch — a DATA packet's length
field disagrees with its bytes, 6 type mismatch — unknown packet type). Every packet that decodes
counts in ``PacketsReceived``; every warning (InvalidReceiveMode, FileOpenError, PacketOutOfBounds,
PacketOutOfOrder, PacketDuplicate, FileWriteError, BadChecksum) counts in ``Warnings``, whether or
not its event was throttled. The four channels are written on every change of their count. Nothing
raises out of a port.

Destination paths are confined to ``root`` (the constructor argument or topology arg; in a run
started by ``fprime-lite run`` the run's folder unless the topology names one; otherwise the current
directory when the component was built): a relative path is taken under ``root``, an absolute one
must lie inside it, and a path that leaves it — through ``..``, as an absolute path elsewhere, or
through a symbolic link pointing outside — is refused with ``PathRefused`` (Os::File status
NO_PERMISSION, 3) and ``FileOpenError``; the component stays in START mode. An existing file is
replaced only when the component was built with ``overwrite=True``; otherwise the START is refused
with ``PathRefused`` (FILE_EXISTS, 6) and ``FileOpenError``. A destination whose directory does not
exist, that is a directory, or whose directory cannot be written is a ``FileOpenError``;
directories are never created. At start-up (:meth:`clean_temporary_files`, called by the
deployment) temporary files that a killed process left under ``root`` are removed.

Which F´: the declarations and behaviour are those of F´ v4's current ``Svc/FileUplink`` (nasa/fprime
``devel``), which has the ``FilesReceivedFailed`` channel and the ``fileAnnounce`` port and does not
count a file with a bad checksum as received. F´ v4.0.0 had neither, and logged ``FileReceived``
(and counted ``FilesReceived``) even after ``BadChecksum``.

Differences from F´:

- **Files are replaced atomically.** F´ opens the destination itself (truncating it) and writes
  into it, so a failed or abandoned transfer leaves a partial or corrupt file where the old one
  was. Here the bytes go to a temporary file ``.fprime-lite-tmp.<pid>.<name>.<random>.part`` in the destination's
  directory; only an END whose checksum matches flushes and fsyncs it, gives it the old file's
  permissions (a new file gets ``0o666 & ~umask``) and ``os.replace``-s it over the destination,
  then fsyncs the directory. A bad checksum, a CANCEL, a new START in DATA mode or a write error
  deletes the temporary file and leaves any existing destination byte-for-byte as it was. A
  symbolic link at the destination is replaced by the file (F´ writes through it).
- **A write error ends the file's chances.** F´ logs ``FileWriteError`` and goes on writing later
  packets into the damaged file. Here the temporary file is deleted at once; the transfer stays
  in DATA mode (sequence, bounds, duplicate and checksum bookkeeping go on as in F´, where the
  later writes would succeed, but nothing more is written) and its END is a failure:
  ``BadChecksum`` if the checksums differ (F´'s outcome), and in every case
  ``FilesReceivedFailed`` is incremented and no ``FileReceived`` is logged. If putting the file in
  place at END fails (fsync or rename), that is also a ``FileWriteError`` and a failed file.
- No ``bufferSendOut`` port: our buffers are ``bytes``, there is nothing to hand back for
  deallocation.
- The ground link strips the ``FW_PACKET_FILE`` descriptor before ``bufferSendIn``, so F´'s
  descriptor checks do not happen here; ``InvalidPacketReceived`` (declared for the dictionary) is
  logged, with ``FW_PACKET_UNKNOWN`` (0xFF), only when something other than bytes arrives on the
  port. A DATA packet whose length field disagrees with its size is a ``DecodeError`` (5), as in F´;
  END and CANCEL packets with trailing bytes are accepted (F´ ignores them too). Paths that are not
  UTF-8 are a ``DecodeError`` (4) (F´ takes any bytes); every unknown packet type (4–255) is a
  ``DecodeError`` (6) (F´'s ``FilePacket`` reports 255, ``T_NONE``, that way and asserts on 4–254).
- Relative destinations resolve against ``root``, not the process's working directory, and every
  destination must stay inside ``root`` (F´ v4.2 has no such confinement: it opens what it is
  given). ``PathRefused`` (id 0x40) is not in F´. Overwriting needs ``overwrite=True`` (F´ always
  overwrites).
- File names in events are cut to their 40-byte bound on a UTF-8 character boundary (F´ cuts
  bytes). ``fileAnnounce`` carries the resolved (absolute) path rather than the path as uplinked.
- ``bufferSendIn`` blocks when the queue is full (a deterministic deployment handles the oldest
  packet to make room) instead of asserting: the ground link may hand over many packets per tick,
  and no file packet is lost.
"""

from __future__ import annotations

import enum
import logging
import os
import pathlib

from fprime_lite.osal.atomic import file_mode_for, fsync_directory, temporary_file
from fprime_lite.osal.confine import PathRefused
from fprime_lite.osal.os_status import FileStatus
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.svc.file_root import FileRoot
from fprime_lite.wire.file_packet import (CancelPacket, CfdpChecksum, DataPacket, EndPacket, FilePacketError,
                           FilePacketType, StartPacket, decode_file_packet)
from fprime_lite.model.fw_ports import BufferSend, Ping
from fprime_lite.wire.packets import Apid
from fprime_lite.model.ports import OutputPort, PortType, async_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import I32, U16, U32, Alias, String, fit_utf8

__all__ = ["FileUplink", "FileAnnounce", "ReceiveMode", "SerializeStatus", "FILE_NAME_ARG_SIZE"]

log = logging.getLogger("fprime_lite")

#: Bound of the ``fileName`` argument of FileUplink's events (FPP ``string size 40``).
FILE_NAME_ARG_SIZE = 40

FwPacketDescriptorType = Alias("FwPacketDescriptorType", U16)

#: Announce a file that was received whole (F´ ``Svc.FileAnnounce``).
FileAnnounce = PortType("Svc.FileAnnounce", file_name=str)

_U32_MAX = 0xFFFFFFFF
_DATA_FIXED = 11  # U8 type | U32 sequence | U32 offset | U16 size


class ReceiveMode(enum.IntEnum):
    """What the component expects next (the ``mode`` argument of InvalidReceiveMode)."""

    START = 0
    DATA = 1


class SerializeStatus(enum.IntEnum):
    """The ``Fw::SerializeStatus`` values DecodeError reports."""

    FW_DESERIALIZE_BUFFER_EMPTY = 3
    FW_DESERIALIZE_FORMAT_ERROR = 4
    FW_DESERIALIZE_SIZE_MISMATCH = 5
    FW_DESERIALIZE_TYPE_MISMATCH = 6


def _event_name(path: str) -> str:
    """``path`` cut to the events' 40-byte bound, on a character boundary."""
    return fit_utf8(path, FILE_NAME_ARG_SIZE)


def _decode_status(raw: bytes, error: FilePacketError) -> SerializeStatus:
    """The status F´'s ``FilePacket::fromBuffer`` gives for bytes that failed to decode."""
    if len(raw) >= 5 and raw[0] > FilePacketType.CANCEL:
        return SerializeStatus.FW_DESERIALIZE_TYPE_MISMATCH
    if len(raw) >= _DATA_FIXED and raw[0] == FilePacketType.DATA:
        return SerializeStatus.FW_DESERIALIZE_SIZE_MISMATCH
    if "UTF-8" in error.reason:
        return SerializeStatus.FW_DESERIALIZE_FORMAT_ERROR
    return SerializeStatus.FW_DESERIALIZE_BUFFER_EMPTY


class _Transfer:
    """The file being received: where it goes, its temporary file and its running checksum."""

    __slots__ = ("name", "event_name", "size", "path", "temp", "fd", "checksum", "failed")

    def __init__(self, name: str, size: int, path: str):
        self.name = name
        self.event_name = _event_name(name)
        self.size = size
        self.path = path
        self.temp: str | None = None
        self.fd: int | None = None
        self.checksum = CfdpChecksum()
        self.failed = False


class FileUplink(FileRoot, ActiveComponent):
    """F´'s file uplink (``Svc.FileUplink``).

    Args:
        name: instance name (``fileUplink`` in F´'s FileHandling).
        base_id: added to the local event ids (0–10) and channel ids (0–3).
        queue_size: depth of the message queue (F´'s FileHandling uses 10).
        root: the directory every destination must lie in; relative destinations are taken from
            it (default: the current directory at construction, or the run's folder — see
            :meth:`set_default_root`).
        overwrite: whether a file may replace an existing one (default: refused).
        in_place: with ``overwrite``, a file received whole is written into an existing regular
            destination file (same inode: a reader holding it open sees the new content, as with
            F´'s in-place write) instead of renamed over it; the destination changes only once the
            checksum matched, but a crash during that last copy leaves it partly written.
            ``fprime-lite run --file-root`` sets both (F´'s FileHandling suite needs it).
    """

    pingOut = OutputPort(Ping)
    #: The path of each file received whole (optional).
    fileAnnounce = OutputPort(FileAnnounce)

    # --- telemetry (F´ ids; FPP's default update: always) ----------------------------------------

    FilesReceived = Channel(U32, id=0)
    PacketsReceived = Channel(U32, id=1)
    Warnings = Channel(U32, id=2)
    FilesReceivedFailed = Channel(U32, id=3)

    # --- events (F´ ids, severities, arguments, formats and throttles) --------------------------

    BadChecksum = Event(Severity.WARNING_HI,
                        "Bad checksum value during receipt of file {}: computed 0x{x}, read 0x{x}", id=0,
                        args=[("fileName", String(FILE_NAME_ARG_SIZE)), ("computed", U32), ("read", U32)])
    FileOpenError = Event(Severity.WARNING_HI, "Could not open file {}", id=1,
                          args=[("fileName", String(FILE_NAME_ARG_SIZE))])
    FileReceived = Event(Severity.ACTIVITY_HI, "Received file {}", id=2,
                         args=[("fileName", String(FILE_NAME_ARG_SIZE))])
    FileWriteError = Event(Severity.WARNING_HI, "Could not write to file {}", id=3, throttle=5,
                           args=[("fileName", String(FILE_NAME_ARG_SIZE))])
    InvalidReceiveMode = Event(Severity.WARNING_HI, "Packet type {} received in mode {}", id=4, throttle=5,
                               args=[("packetType", FwPacketDescriptorType), ("mode", U32)])
    PacketOutOfBounds = Event(Severity.WARNING_HI, "Packet {} out of bounds for file {}", id=5, throttle=5,
                              args=[("packetIndex", U32), ("fileName", String(FILE_NAME_ARG_SIZE))])
    PacketOutOfOrder = Event(Severity.WARNING_HI, "Received packet {} after packet {}", id=6, throttle=20,
                             args=[("packetIndex", U32), ("lastPacketIndex", U32)])
    PacketDuplicate = Event(Severity.WARNING_HI, "Received a duplicate of packet {}", id=7, throttle=20,
                            args=[("packetIndex", U32)])
    UplinkCanceled = Event(Severity.ACTIVITY_HI, "Received CANCEL packet", id=8)
    DecodeError = Event(Severity.WARNING_HI, "Unable to decode file packet. Status: {}", id=9,
                        args=[("status", I32)])
    InvalidPacketReceived = Event(Severity.WARNING_HI, "Invalid packet received. Wrong packet type: {}",
                                  id=10, args=[("packetType", FwPacketDescriptorType)])
    #: Not in F´: a destination outside ``root`` (status NO_PERMISSION) or an existing file without
    #: ``overwrite`` (FILE_EXISTS).
    PathRefused = Event(Severity.WARNING_HI, "File {} refused (Os::File status {}): {}", id=0x40,
                        args=[("fileName", String(FILE_NAME_ARG_SIZE)), ("status", I32),
                              ("reason", String(FILE_NAME_ARG_SIZE))])

    def __init__(self, name: str = "fileUplink", *, base_id: int = 0, queue_size: int = 10,
                 root: str | os.PathLike | None = None, overwrite: bool = False, in_place: bool = False):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        self._init_root(root)
        self.overwrite = bool(overwrite)
        self.in_place = bool(in_place)
        self._mode = ReceiveMode.START
        self._last_sequence = 0
        #: None before the first DATA packet of a file (F´ MAX_STATUS), else whether it was written.
        self._last_write_ok: bool | None = None
        self._file: _Transfer | None = None
        self._files_received = 0
        self._packets_received = 0
        self._warnings = 0
        self._files_failed = 0
        #: Exceptions caught by the safety net of ``bufferSendIn`` (a bug, never expected).
        self.internal_errors = 0

    # --- ports ---------------------------------------------------------------------------------

    @async_input(BufferSend, queue_full="block")
    def bufferSendIn(self, fwBuffer: bytes) -> None:
        """Handle one file packet (without its ``FW_PACKET_FILE`` descriptor); never raises."""
        try:
            self._receive(fwBuffer)
        except Exception as exc:  # noqa: BLE001 - the safety net: a port never raises
            self.internal_errors += 1
            self.report_fault("bufferSendIn", exc)  # the file in progress is abandoned
            try:
                self._go_to_start_mode()
            except Exception as reset:  # noqa: BLE001 - reported, never raised
                self.report_fault("bufferSendIn: reset", reset)

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    # --- root ----------------------------------------------------------------------------------

    @property
    def root(self) -> str:
        """The directory every path lies in (symbolic links resolved)."""
        return self.root_path



    # --- inspection ----------------------------------------------------------------------------

    @property
    def receive_mode(self) -> ReceiveMode:
        return self._mode

    @property
    def last_sequence_index(self) -> int:
        return self._last_sequence

    @property
    def temporary_path(self) -> str | None:
        """The temporary file of the transfer in progress (None when there is none)."""
        return self._file.temp if self._file is not None else None

    def discard(self) -> None:
        """Abandon the file in progress (deleting its temporary file), e.g. at shutdown."""
        self._go_to_start_mode()

    # --- packet handling -----------------------------------------------------------------------

    def _receive(self, buffer) -> None:
        if not isinstance(buffer, (bytes, bytearray, memoryview)):
            log.warning("%s: bufferSendIn got %s, not bytes", self.name, type(buffer).__name__)
            self.InvalidPacketReceived(int(Apid.FW_PACKET_UNKNOWN))
            return
        raw = bytes(buffer)
        packet = decode_file_packet(raw)
        if isinstance(packet, FilePacketError):
            status = _decode_status(raw, packet)
            log.warning("%s: not a file packet (%s): %s", self.name, status.name, packet.reason)
            self.DecodeError(int(status))
            return
        if isinstance(packet, DataPacket) and len(raw) != _DATA_FIXED + len(packet.data):
            log.warning("%s: DATA packet %d says %d bytes but carries %d", self.name, packet.sequence,
                        len(packet.data), len(raw) - _DATA_FIXED)
            self.DecodeError(int(SerializeStatus.FW_DESERIALIZE_SIZE_MISMATCH))
            return
        if isinstance(packet, StartPacket):
            self._handle_start(packet)
        elif isinstance(packet, DataPacket):
            self._handle_data(packet)
        elif isinstance(packet, EndPacket):
            self._handle_end(packet)
        elif isinstance(packet, CancelPacket):
            self._handle_cancel()

    def _handle_start(self, packet: StartPacket) -> None:
        for event in (self.FileWriteError, self.InvalidReceiveMode, self.PacketOutOfBounds,
                      self.PacketOutOfOrder):
            event.clear_throttle()
        self._count_packet()
        if self._mode != ReceiveMode.START:
            self._abandon()
            self._warn_receive_mode(FilePacketType.START)
        try:
            path = self._resolve(packet.destination)
        except PathRefused as refused:
            log.warning("%s: START refused: %s (root %s)", self.name, refused, self.root)
            self._refuse(packet.destination, FileStatus.NO_PERMISSION, refused.reason)
            return
        except ValueError:  # a NUL byte: the open below reports it
            path = os.path.join(self.root, packet.destination)
        if not self.overwrite and os.path.lexists(path):
            log.warning("%s: START refused: %s exists and overwrite is off", self.name, path)
            self._refuse(packet.destination, FileStatus.FILE_EXISTS, "exists; overwrite is off")
            return
        transfer = _Transfer(packet.destination, packet.file_size, path)
        self._file = transfer
        problem = self._open(transfer)
        if problem is None:
            self._go_to_data_mode()
        else:
            log.warning("%s: cannot receive %r into %s: %s", self.name, packet.destination, transfer.path,
                        problem)
            self._warn(self.FileOpenError, transfer.event_name)
            self._go_to_start_mode()

    def _refuse(self, destination: str, status: FileStatus, reason: str) -> None:
        name = _event_name(destination)
        self.PathRefused(name, int(status), fit_utf8(reason, FILE_NAME_ARG_SIZE))
        self._warn(self.FileOpenError, name)
        self._go_to_start_mode()

    def _handle_data(self, packet: DataPacket) -> None:
        self._count_packet()
        if self._mode != ReceiveMode.DATA:
            self._warn_receive_mode(FilePacketType.DATA)
            return
        transfer = self._file
        assert transfer is not None  # DATA mode always has a transfer
        sequence = packet.sequence
        if self._last_write_ok and sequence == self._last_sequence:
            self._warn(self.PacketDuplicate, sequence)
            return
        self._check_sequence(sequence)
        offset = packet.offset
        if offset + len(packet.data) > transfer.size:
            self._warn(self.PacketOutOfBounds, sequence, transfer.event_name)
            return
        # After a write error the temporary file is gone: later packets are only accounted for, as
        # if written, so that sequence, duplicate and checksum outcomes stay those of F´.
        problem = None if transfer.failed else self._write(transfer, offset, packet.data)
        if problem is None:
            transfer.checksum.update(packet.data, offset)
            self._last_write_ok = True
            return
        log.warning("%s: writing %d bytes at offset %d of %s failed: %s; the file will not be kept",
                    self.name, len(packet.data), offset, transfer.path, problem)
        self._warn(self.FileWriteError, transfer.event_name)
        transfer.failed = True
        self._last_write_ok = False
        self._delete_temporary(transfer)

    def _handle_end(self, packet: EndPacket) -> None:
        self._count_packet()
        if self._mode == ReceiveMode.DATA:
            transfer = self._file
            assert transfer is not None  # DATA mode always has a transfer
            self._check_sequence(packet.sequence)
            computed = transfer.checksum.value
            if computed != packet.checksum:
                log.warning("%s: %s: checksum 0x%08X computed, 0x%08X sent; the file is not kept",
                            self.name, transfer.path, computed, packet.checksum)
                self._warn(self.BadChecksum, transfer.event_name, computed, packet.checksum)
                self._file_failed()
            elif transfer.failed:
                self._file_failed()
            else:
                problem = self._commit(transfer)
                if problem is None:
                    self._files_received += 1
                    self.FilesReceived.write(self._files_received)
                    self.FileReceived(transfer.event_name)
                    if self.is_connected("fileAnnounce", 0):
                        self.fileAnnounce[0](transfer.path)
                else:
                    log.warning("%s: cannot put %s in place: %s", self.name, transfer.path, problem)
                    self._warn(self.FileWriteError, transfer.event_name)
                    self._file_failed()
        else:
            self._warn_receive_mode(FilePacketType.END)
        self._go_to_start_mode()

    def _handle_cancel(self) -> None:
        self._count_packet()
        self.UplinkCanceled()
        self._go_to_start_mode()

    # --- state and counters --------------------------------------------------------------------

    def _check_sequence(self, sequence: int) -> None:
        if sequence != (self._last_sequence + 1) & _U32_MAX:
            self._warn(self.PacketOutOfOrder, sequence, self._last_sequence)
        self._last_sequence = sequence

    def _go_to_start_mode(self) -> None:
        self._abandon()
        self._mode = ReceiveMode.START
        self._last_sequence = 0
        self._last_write_ok = None

    def _go_to_data_mode(self) -> None:
        self._mode = ReceiveMode.DATA
        self._last_sequence = 0
        self._last_write_ok = None

    def _abandon(self) -> None:
        """Drop the file in progress: its temporary file (if any) is deleted."""
        transfer, self._file = self._file, None
        if transfer is not None:
            self._delete_temporary(transfer)

    def _count_packet(self) -> None:
        self._packets_received = (self._packets_received + 1) & _U32_MAX
        self.PacketsReceived.write(self._packets_received)

    def _file_failed(self) -> None:
        self._files_failed = (self._files_failed + 1) & _U32_MAX
        self.FilesReceivedFailed.write(self._files_failed)

    def _warn(self, event, *args) -> None:
        """Log a warning event (maybe throttled) and count it in ``Warnings`` either way."""
        event(*args)
        self._warnings = (self._warnings + 1) & _U32_MAX
        self.Warnings.write(self._warnings)

    def _warn_receive_mode(self, packet_type: FilePacketType) -> None:
        self._warn(self.InvalidReceiveMode, int(packet_type), int(self._mode))

    # --- the file system -----------------------------------------------------------------------

    def _resolve(self, destination: str) -> str:
        """The confined path of the destination's directory entry (raises PathRefused)."""
        if not destination:
            return self.root  # reported as an empty destination by _open
        return self._confinement.entry(destination)

    def _open(self, transfer: _Transfer) -> str | None:
        """Create the transfer's temporary file; None, or what went wrong."""
        path = transfer.path
        if not transfer.name:
            return "the destination path is empty"
        try:
            if os.path.isdir(path):
                return "the destination is a directory"
            directory, base = os.path.split(path)
            fd, temp = temporary_file(directory, base)
        except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the path
            return str(exc)
        transfer.fd = fd
        transfer.temp = temp
        return None

    @staticmethod
    def _write(transfer: _Transfer, offset: int, data: bytes) -> str | None:
        """Write ``data`` at ``offset`` of the temporary file; None, or what went wrong."""
        assert transfer.fd is not None  # open until committed or failed; failed transfers are not written
        view = memoryview(data)
        try:
            while view:
                n = os.pwrite(transfer.fd, view, offset)
                if n <= 0:
                    return "the file system accepted no bytes"
                view = view[n:]
                offset += n
        except OSError as exc:
            return str(exc)
        return None

    def _commit(self, transfer: _Transfer) -> str | None:
        """Make the temporary file durable and rename it over the destination; None, or the problem."""
        fd, transfer.fd = transfer.fd, None
        assert fd is not None and transfer.temp is not None  # a transfer that did not fail is open
        if not self.overwrite and os.path.lexists(transfer.path):
            os.close(fd)
            return "the destination appeared during the transfer and overwrite is off"
        if self.in_place and self.overwrite and os.path.isfile(transfer.path) \
                and not os.path.islink(transfer.path):
            return self._copy_in_place(fd, transfer)
        try:
            try:
                os.fchmod(fd, file_mode_for(pathlib.Path(transfer.path)))
                os.fsync(fd)
            finally:
                os.close(fd)
            os.replace(transfer.temp, transfer.path)
        except OSError as exc:
            return str(exc)
        transfer.temp = None
        fsync_directory(pathlib.Path(transfer.path).parent)
        return None

    def _copy_in_place(self, fd: int, transfer: _Transfer) -> str | None:
        """``in_place``: copy the verified temporary file into the existing destination (truncated
        first), fsync it and delete the temporary file; None, or the problem."""
        try:
            try:
                with open(transfer.path, "r+b") as dest:
                    dest.truncate(0)
                    offset = 0
                    while chunk := os.pread(fd, 1 << 16, offset):
                        dest.write(chunk)
                        offset += len(chunk)
                    dest.flush()
                    os.fsync(dest.fileno())
            finally:
                os.close(fd)
        except OSError as exc:
            return str(exc)
        self._delete_temporary(transfer)
        return None

    def _delete_temporary(self, transfer: _Transfer) -> None:
        fd, transfer.fd = transfer.fd, None
        if fd is not None:
            try:
                os.close(fd)
            except OSError:
                pass
        temp, transfer.temp = transfer.temp, None
        if temp is not None:
            try:
                os.unlink(temp)
            except FileNotFoundError:
                pass
            except OSError as exc:
                log.warning("%s: cannot delete the temporary file %s: %s", self.name, temp, exc)

