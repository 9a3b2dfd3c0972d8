"""Svc.FileManager: ground commands that work on the flight computer's files and directories.

F´'s ``Svc.FileManager`` (instance ``fileManager`` in F´'s FileHandling subtopology), as F´ v4.2
declares it — the last v4 release with ``ShellCommand`` (F´ removed it after v4.2). Command names,
opcodes, argument names and string bounds, event names, ids, severities, arguments and formats and
the two channels are F´'s, so fprime-gds encodes and decodes them from the dictionary unchanged.

Each command logs its ``...Started`` event, performs the operation, then logs ``...Succeeded`` (or
the command's error event carrying the F´ ``Os`` status number), counts ``CommandsExecuted`` or
``Errors`` and answers OK or EXECUTION_ERROR — as F´'s ``FileManager.cpp`` does:

- ``CreateDirectory`` (0x00) makes one directory; an existing one is an error (ALREADY_EXISTS).
- ``MoveFile`` (0x01) renames; across file systems (EXDEV) a regular file is copied next to the
  destination, fsynced, renamed into place, then the source is removed.
- ``RemoveDirectory`` (0x02) removes an empty directory.
- ``RemoveFile`` (0x03) removes a file; with ``ignoreErrors`` a failure still logs
  ``FileRemoveError`` and counts an error, but answers OK.
- ``ShellCommand`` (0x04) runs a shell command with its output appended to ``logFileName``; the
  status reported is the wait status ``system()`` returns in F´ (exit code × 256, or the signal
  number). **Refused unless the component was built with ``allow_shell=True``.**
- ``AppendFile`` (0x05) appends ``source`` to ``target`` (created if missing).
- ``FileSize`` (0x06) reports the size in ``FileSizeSucceeded``.
- ``ListDirectory`` (0x07) logs one ``DirectoryListing`` / ``DirectoryListingSubdir`` event per
  entry, ``files_per_tick`` entries per ``schedIn`` tick (connect it to a rate group), then
  ``ListDirectorySucceeded``; the command is answered when the listing ends. A second
  ListDirectory during a listing is refused (``ListDirectoryError`` with Directory OTHER_ERROR, 10).
- ``CalculateCrc`` (0x08) reports the file's CRC-32 as F´'s ``Os::File::calculateCrc`` computes it
  (``zlib.crc32(data) ^ 0xFFFFFFFF``); like F´, it touches neither channel.

Every path is confined to ``root`` (topology arg; in a run started by ``fprime-lite run`` the run's
folder unless the topology names one; otherwise the current directory when the component is
built): relative paths are resolved under it, absolute ones must lie inside it, and a path that
leaves it — ``..``, an absolute path elsewhere, a symbolic link pointing outside — is refused with
``PathRefused`` (id 0x40, not in F´) and the command's own error event with status NO_PERMISSION
(3), EXECUTION_ERROR. Operations on a directory entry (CreateDirectory, MoveFile, RemoveDirectory,
RemoveFile) act on a link itself; the others (AppendFile, FileSize, ListDirectory, CalculateCrc,
ShellCommand's log file) follow links, which must stay inside ``root``. MoveFile onto an existing
file is refused (ALREADY_EXISTS, 1) unless the component was built with ``overwrite=True`` (F´
replaces it). ShellCommand, when allowed, runs in ``root`` but what the command itself does is not
confined. Events show the paths as commanded. Status numbers are F´'s enums, given here as
:class:`FileSystemStatus`, :class:`FileStatus` and :class:`DirectoryStatus`; the Python log line of
each failure names the status and the OS error.

**Modelled storage time** (``storage_bytes_per_s``, not in F´, off by default). On a board,
AppendFile and CalculateCrc keep the component busy while the storage moves the bytes; on a host's
page cache they take milliseconds. With a rate given, each successful AppendFile counts the
source's bytes twice (read, then written at the end of the target, as F´ appends) and each
CalculateCrc the file's bytes once, and sets ``modelled_busy_us`` to that many bytes at the rate:
a paced scheduler keeps the component busy that long in simulated time, so the messages queued for
it meanwhile (a Health ping) wait as they would for the board's FileManager thread, whatever the
host's disk (:meth:`~fprime_lite.deploy.scheduler.PacedScheduler.drain`; an unpaced run treats
every handler as instantaneous). The reference deployment gives PROVES's SD card on SPI at 24 MHz,
3,000,000 bytes/s (docs/ground.md).

Differences from F´:

- **ShellCommand is disabled by default.** Unless built with ``allow_shell=True`` it runs nothing:
  ``ShellCommandFailed`` with status 0xFFFFFFFF (what F´ reports when ``system()`` cannot run a
  shell) and the command text followed by ``[refused: ShellCommand is disabled in this
  deployment]``, EXECUTION_ERROR, ``Errors`` + 1. When allowed, the command runs with
  ``subprocess`` (``/bin/sh``, in ``root``, stdin closed) in its own process group, killed after
  ``shell_timeout_s`` (default 60 s; reported as killed by SIGKILL, status 9). F´ wraps the text in
  ``eval '...'`` (a command containing ``'`` breaks there) and has no timeout. A log file that
  cannot be opened: status 0xFFFFFFFF.
- **AppendFile is atomic**: the target's content then the source's go to a temporary file in the
  target's directory, which is fsynced and renamed over the target; the target is either fully
  appended or unchanged (F´ appends in place; a failure leaves a partial append). A symbolic-link
  target is resolved first; the new file keeps the target's permissions (hard links to the old
  file keep the old content).
- **MoveFile across file systems** copies through a fsynced temporary file (F´: plain copy then
  remove); a directory cannot be moved across file systems (EXDEV_ERROR).
- **Status numbers** use the specific F´ status where F´'s POSIX layer falls back to OTHER_ERROR:
  a non-empty directory is NOT_EMPTY (6), removing a directory with RemoveFile IS_DIR (5), EBUSY
  BUSY (10), EMFILE/ENFILE FILE_LIMIT (9), EINVAL and a NUL byte in a path INVALID_PATH (7); an
  empty path is DOESNT_EXIST (8) and never means ``root``. FileSize of a directory is IS_DIR
  (F´ reports what ``lseek`` says).
- **ListDirectory** reads the entry names when the command runs and lists them in name order (F´
  reads them as the listing proceeds, in directory order); entries are stat-ed (symbolic links
  followed) when they are listed. ``schedIn`` is sync and only queues a tick while a listing is in
  progress, at most one at a time (F´ v4.2 lists on the rate group's thread; later F´ queues one
  ``run`` message as here). ``FileNameFormatError`` is logged for an entry whose name is not UTF-8
  (status OTHER_ERROR); F´ logs it when the full path overflows its string (never here).
- Strings: event string arguments longer than their bound are cut (on a UTF-8 boundary) instead of
  being truncated by ``Fw::LogStringArg``; command strings are bounded by their declared size (F´
  also limits them to ``FW_CMD_STRING_MAX_SIZE``).
- ``FileSizeSucceeded.size`` and ``DirectoryListing.fileSize`` are ``FwSizeType``, declared here as
  U64 (same encoding). ``Fw.StringFormatStatus`` is declared in this module.
"""

from __future__ import annotations

import enum
import errno as _errno
import logging
import os
import shutil
import signal
import stat as _stat
import subprocess
import threading
import zlib
from dataclasses import dataclass
from typing import Annotated

from fprime_lite.osal.confine import PathRefused
from fprime_lite.osal.os_status import (DirectoryStatus, FileStatus, FileSystemStatus, directory_status,
                                        file_status, filesystem_status)
from fprime_lite.osal.atomic import fsync_directory, temporary_file
from fprime_lite.model.commands import CmdResponse, CommandToken, async_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.svc.file_root import FileRoot
from fprime_lite.model.fw_ports import Ping, Sched
from fprime_lite.model.ports import OutputPort, async_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import BOOL, U8, U32, U64, FwEnum, String, fit_utf8

__all__ = [
    "FileManager", "FileSystemStatus", "FileStatus", "DirectoryStatus", "StringFormatStatus",
    "filesystem_status", "file_status", "directory_status", "file_crc", "wait_status",
    "FILE_NAME_STRING_SIZE", "CMD_STRING_SIZE", "FILES_PER_RATE_TICK", "SHELL_NOT_RUN",
    "DEFAULT_SHELL_TIMEOUT_S",
]

log = logging.getLogger("fprime_lite")

#: F´'s ``FileNameStringSize``: ListDirectory / CalculateCrc arguments and their events.
FILE_NAME_STRING_SIZE = 200
#: The ``string size 256`` of F´ v4.2's original FileManager commands and events.
CMD_STRING_SIZE = 256
#: Directory entries listed per ``schedIn`` tick (F´ ``FileManagerConfig::FILES_PER_RATE_TICK``).
FILES_PER_RATE_TICK = 1
#: ShellCommand status when no shell ran (``system()`` returning -1, as a U32).
SHELL_NOT_RUN = 0xFFFFFFFF
DEFAULT_SHELL_TIMEOUT_S = 60.0
_SHELL_REFUSED = " [refused: ShellCommand is disabled in this deployment]"

_PATH = String(CMD_STRING_SIZE)
_PathArg = Annotated[str, _PATH]  # a command argument of type _PATH
_NAME = String(FILE_NAME_STRING_SIZE)
_CHUNK = 64 * 1024


class StringFormatStatus(FwEnum, namespace="Fw", rep=U8):
    """F´ ``Fw.StringFormatStatus`` (the status of ``FileNameFormatError``)."""

    SUCCESS = 0
    OVERFLOWED = 1
    INVALID_FORMAT_STRING = 2
    SIZE_OVERFLOW = 3
    OTHER_ERROR = 4


def file_crc(path) -> int:
    """The CRC F´'s ``Os::File::calculateCrc`` gives a file: CRC-32 without the final inversion."""
    crc = 0
    with _open_regular(path) as f:
        while chunk := f.read(_CHUNK):
            crc = zlib.crc32(chunk, crc)
    return crc ^ 0xFFFFFFFF


def wait_status(returncode: int) -> int:
    """``subprocess`` return code -> what ``system()`` returns (exit code << 8, or the signal)."""
    if returncode >= 0:
        return (returncode & 0xFF) << 8
    return (-returncode) & 0x7F


def _describe(status: enum.IntEnum, exc: BaseException | None) -> str:
    return f"status {int(status)} ({status.name}){f': {exc}' if exc is not None else ''}"


@dataclass
class _Listing:
    """A ListDirectory in progress."""

    dir_name: str                      # as commanded (events)
    path: str                          # resolved
    names: list[str]
    token: CommandToken
    index: int = 0
    entries: int = 0


class FileManager(FileRoot, ActiveComponent):
    """Ground commands on files and directories (F´ ``Svc.FileManager``).

    Args:
        name: instance name (``fileManager`` in F´'s FileHandling subtopology).
        root: directory that relative paths are resolved against (default: the current directory
            when the component is built).
        base_id: added to the local opcodes (0–8), event ids (0–0x1D) and channel ids (0–1).
        queue_size: depth of the message queue.
        allow_shell: run ShellCommand; when False (the default) it is refused.
        shell_timeout_s: a shell command still running after this many seconds is killed (its
            whole process group); None waits for ever.
        files_per_tick: directory entries ListDirectory reports per ``schedIn`` tick.
    """

    pingOut = OutputPort(Ping)

    # --- channels (F´ ids) ------------------------------------------------------------------------
    CommandsExecuted = Channel(U32, id=0)
    Errors = Channel(U32, id=1)

    # --- events (F´ v4.2 ids, severities, arguments and formats) ---------------------------------
    DirectoryCreateError = Event(Severity.WARNING_HI, "Could not create directory {}, returned status {}",
                                 id=0x00, dirName=_PATH, status=U32)
    DirectoryRemoveError = Event(Severity.WARNING_HI, "Could not remove directory {}, returned status {}",
                                 id=0x01, dirName=_PATH, status=U32)
    FileMoveError = Event(Severity.WARNING_HI, "Could not move file {} to file {}, returned status {}",
                          id=0x02, sourceFileName=_PATH, destFileName=_PATH, status=U32)
    FileRemoveError = Event(Severity.WARNING_HI, "Could not remove file {}, returned status {}",
                            id=0x03, fileName=_PATH, status=U32)
    ShellCommandFailed = Event(Severity.WARNING_HI, "Shell command {} failed with status {}", id=0x04,
                               command=_PATH, status=U32)
    AppendFileFailed = Event(Severity.WARNING_HI, "Appending {} onto {} failed with status {}", id=0x05,
                             source=_PATH, target=_PATH, status=U32)
    AppendFileSucceeded = Event(Severity.ACTIVITY_HI, "Appended {} to the end of {}", id=0x06,
                                source=_PATH, target=_PATH)
    ShellCommandSucceeded = Event(Severity.ACTIVITY_HI, "Shell command {} succeeded", id=0x07,
                                  command=_PATH)
    CreateDirectorySucceeded = Event(Severity.ACTIVITY_HI, "Created directory {} successfully", id=0x08,
                                     dirName=_PATH)
    RemoveDirectorySucceeded = Event(Severity.ACTIVITY_HI, "Removed directory {} successfully", id=0x09,
                                     dirName=_PATH)
    MoveFileSucceeded = Event(Severity.ACTIVITY_HI, "Moved file {} to file {} successfully", id=0x0A,
                              sourceFileName=_PATH, destFileName=_PATH)
    RemoveFileSucceeded = Event(Severity.ACTIVITY_HI, "Removed file {} successfully", id=0x0B,
                                fileName=_PATH)
    AppendFileStarted = Event(Severity.ACTIVITY_HI, "Appending file {} to the end of {}...", id=0x0C,
                              source=_PATH, target=_PATH)
    ShellCommandStarted = Event(Severity.ACTIVITY_HI, "Running shell command {}...", id=0x0D,
                                command=_PATH)
    CreateDirectoryStarted = Event(Severity.ACTIVITY_HI, "Creating directory {}...", id=0x0E,
                                   dirName=_PATH)
    RemoveDirectoryStarted = Event(Severity.ACTIVITY_HI, "Removing directory {}...", id=0x0F,
                                   dirName=_PATH)
    MoveFileStarted = Event(Severity.ACTIVITY_HI, "Moving file {} to file {}...", id=0x10,
                            sourceFileName=_PATH, destFileName=_PATH)
    RemoveFileStarted = Event(Severity.ACTIVITY_HI, "Removing file {}...", id=0x11, fileName=_PATH)
    FileSizeSucceeded = Event(Severity.ACTIVITY_HI, "The size of file {} is {} B", id=0x12,
                              fileName=_PATH, size=U64)
    FileSizeError = Event(Severity.WARNING_HI, "Failed to get the size of file {}, returned status {}",
                          id=0x13, fileName=_PATH, status=U32)
    FileSizeStarted = Event(Severity.ACTIVITY_HI, "Checking size of file {}...", id=0x14, fileName=_PATH)
    ListDirectoryStarted = Event(Severity.ACTIVITY_HI, "Listing contents of directory {}...", id=0x15,
                                 dirName=_NAME)
    ListDirectorySucceeded = Event(Severity.ACTIVITY_HI, "Directory {} contains {} files", id=0x16,
                                   dirName=_NAME, fileCount=U32)
    ListDirectoryError = Event(Severity.WARNING_HI, "Failed to list directory {}, returned status {}",
                               id=0x17, dirName=_NAME, status=U32)
    DirectoryListing = Event(Severity.ACTIVITY_HI, "Directory {}: {} ({} bytes)", id=0x18,
                             dirName=_NAME, fileName=_NAME, fileSize=U64)
    DirectoryListingSubdir = Event(Severity.ACTIVITY_HI, "Directory {}: {}", id=0x19,
                                   dirName=_NAME, subdirName=_NAME)
    CalculateCrcStarted = Event(Severity.ACTIVITY_HI, "Started CRC calculation for file {}", id=0x1A,
                                fileName=_NAME)
    CalculateCrcFailed = Event(Severity.WARNING_HI, "Failed CRC calculation for file {}, returned status {}",
                               id=0x1B, fileName=_NAME, status=U32)
    CalculateCrcSucceeded = Event(Severity.ACTIVITY_HI, "{} has CRC value 0x{x}", id=0x1C,
                                  fileName=_NAME, crc=U32)
    FileNameFormatError = Event(Severity.WARNING_HI, "Failed to format full path for file {} with status {}",
                                id=0x1D, fileName=_NAME, status=StringFormatStatus)
    #: Not in F´: a path outside ``root`` (the command's error event follows with NO_PERMISSION).
    PathRefused = Event(Severity.WARNING_HI, "Path {} refused: {}", id=0x40, path=_PATH, reason=String(40))

    def __init__(self, name: str = "fileManager", *, root: str | os.PathLike | None = None,
                 base_id: int = 0, queue_size: int = 10, allow_shell: bool = False,
                 shell_timeout_s: float | None = DEFAULT_SHELL_TIMEOUT_S,
                 files_per_tick: int = FILES_PER_RATE_TICK, overwrite: bool = False,
                 storage_bytes_per_s: float | None = None):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        if storage_bytes_per_s is not None and (isinstance(storage_bytes_per_s, bool)
                                                or not isinstance(storage_bytes_per_s, (int, float))
                                                or not storage_bytes_per_s > 0):
            raise ValueError(f"{name}: storage_bytes_per_s must be a positive number of bytes per second or None "
                             f"(not modelled), got {storage_bytes_per_s!r}")
        #: Bytes per second the modelled storage moves (None: its time is not modelled).
        self.storage_bytes_per_s = storage_bytes_per_s
        #: Simulated µs the last operation keeps the component busy (read and cleared by a paced scheduler).
        self.modelled_busy_us = 0
        if shell_timeout_s is not None and (isinstance(shell_timeout_s, bool)
                                            or not isinstance(shell_timeout_s, (int, float))
                                            or not shell_timeout_s > 0):
            raise ValueError(f"{name}: shell_timeout_s must be a positive number of seconds or None, "
                             f"got {shell_timeout_s!r}")
        if isinstance(files_per_tick, bool) or not isinstance(files_per_tick, int) or files_per_tick < 1:
            raise ValueError(f"{name}: files_per_tick must be a positive integer, got {files_per_tick!r}")
        self._init_root(root)
        self.overwrite = bool(overwrite)
        self.allow_shell = bool(allow_shell)
        self.shell_timeout_s = shell_timeout_s
        self.files_per_tick = files_per_tick
        self._commands_executed = 0
        self._errors = 0
        self._listing: _Listing | None = None
        self._tick_lock = threading.Lock()
        self._tick_queued = False

    # --- inspection -------------------------------------------------------------------------------

    @property
    def commands_executed(self) -> int:
        """The CommandsExecuted count."""
        return self._commands_executed

    @property
    def errors(self) -> int:
        """The Errors count."""
        return self._errors

    @property
    def listing_in_progress(self) -> bool:
        return self._listing is not None

    @property
    def root(self) -> str:
        """The directory every path lies in (symbolic links resolved)."""
        return self.root_path



    def resolve(self, path: str, *, entry: bool = False) -> str:
        """The confined real path a command argument names (relative under ``root``; absolute must be
        inside it). ``entry``: the directory entry itself (a final link is not followed). Raises
        PathRefused (a PermissionError) with the PathRefused event for a path outside ``root``."""
        if path == "":
            raise FileNotFoundError(_errno.ENOENT, "empty path", path)
        try:
            return self._confinement.entry(path) if entry else self._confinement.contents(path)
        except PathRefused as refused:
            log.warning("%s: %s refused (root %s)", self.name, refused, self.root)
            self.PathRefused(fit_utf8(path, CMD_STRING_SIZE), fit_utf8(refused.reason, 40))
            raise

    # --- ports ------------------------------------------------------------------------------------

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    @sync_input(Sched)
    def schedIn(self, context: int) -> None:
        """Rate-group tick: while a listing is in progress, queue one listing step (at most one)."""
        if self._listing is None:
            return
        with self._tick_lock:
            if self._tick_queued:
                return
            self._tick_queued = True
        queued = self.queue.put(0, self._listing_tick, (), queue_full="drop", port=f"{self.name}.schedIn",
                                threaded=self._thread is not None)
        if not queued:
            with self._tick_lock:
                self._tick_queued = False

    # --- commands ---------------------------------------------------------------------------------

    @async_command(opcode=0x00)
    def CreateDirectory(self, dirName: _PathArg):
        """Create the directory ``dirName`` (its parent must exist; it must not)."""
        self.CreateDirectoryStarted(fit_utf8(dirName, CMD_STRING_SIZE))
        status, cause = self._fs("CreateDirectory", lambda: os.mkdir(self.resolve(dirName, entry=True)))
        if status:
            self._log_failure("CreateDirectory", dirName, status, cause)
            self.DirectoryCreateError(fit_utf8(dirName, CMD_STRING_SIZE), status)
        else:
            self.CreateDirectorySucceeded(fit_utf8(dirName, CMD_STRING_SIZE))
        return self._finish(status)

    @async_command(opcode=0x01)
    def MoveFile(self, sourceFileName: _PathArg, destFileName: _PathArg):
        """Rename ``sourceFileName`` to ``destFileName`` (copy then remove across file systems)."""
        src, dst = fit_utf8(sourceFileName, CMD_STRING_SIZE), fit_utf8(destFileName, CMD_STRING_SIZE)
        self.MoveFileStarted(src, dst)
        status, cause = self._fs("MoveFile", lambda: self._move(self.resolve(sourceFileName, entry=True),
                                                                self.resolve(destFileName, entry=True)))
        if status:
            self._log_failure("MoveFile", f"{sourceFileName} -> {destFileName}", status, cause)
            self.FileMoveError(src, dst, status)
        else:
            self.MoveFileSucceeded(src, dst)
        return self._finish(status)

    @async_command(opcode=0x02)
    def RemoveDirectory(self, dirName: _PathArg):
        """Remove the empty directory ``dirName``."""
        self.RemoveDirectoryStarted(fit_utf8(dirName, CMD_STRING_SIZE))
        status, cause = self._fs("RemoveDirectory", lambda: os.rmdir(self.resolve(dirName, entry=True)))
        if status:
            self._log_failure("RemoveDirectory", dirName, status, cause)
            self.DirectoryRemoveError(fit_utf8(dirName, CMD_STRING_SIZE), status)
        else:
            self.RemoveDirectorySucceeded(fit_utf8(dirName, CMD_STRING_SIZE))
        return self._finish(status)

    @async_command(opcode=0x03)
    def RemoveFile(self, fileName: _PathArg, ignoreErrors: BOOL):
        """Remove the file ``fileName``; with ``ignoreErrors`` a failure still answers OK."""
        name = fit_utf8(fileName, CMD_STRING_SIZE)
        self.RemoveFileStarted(name)
        status, cause = self._fs("RemoveFile", lambda: os.remove(self.resolve(fileName, entry=True)))
        if status:
            self._log_failure("RemoveFile", fileName, status, cause)
            self.FileRemoveError(name, status)
            if ignoreErrors:
                # As F´: counted as an error, never as an executed command, and answered OK.
                self._count_error()
                return CmdResponse.OK
        else:
            self.RemoveFileSucceeded(name)
        return self._finish(status)

    @async_command(opcode=0x04)
    def ShellCommand(self, command: _PathArg, logFileName: _PathArg):
        """Run ``command`` with the shell, appending its output to ``logFileName`` (if allowed)."""
        if not self.allow_shell:
            log.warning("%s: ShellCommand refused (the deployment did not allow shell commands; build "
                        "FileManager with allow_shell=True to run them): %r", self.name, command)
            self.ShellCommandFailed(fit_utf8(command + _SHELL_REFUSED, CMD_STRING_SIZE), SHELL_NOT_RUN)
            return self._finish(FileSystemStatus.OTHER_ERROR)
        text = fit_utf8(command, CMD_STRING_SIZE)
        self.ShellCommandStarted(text)
        status = self._system(command, logFileName)
        if status == 0:
            self.ShellCommandSucceeded(text)
            return self._finish(FileSystemStatus.OP_OK)
        self.ShellCommandFailed(text, status)
        return self._finish(FileSystemStatus.OTHER_ERROR)

    @async_command(opcode=0x05)
    def AppendFile(self, source: _PathArg, target: _PathArg):
        """Append ``source`` to ``target`` atomically (``target`` is created if missing)."""
        src, dst = fit_utf8(source, CMD_STRING_SIZE), fit_utf8(target, CMD_STRING_SIZE)
        self.AppendFileStarted(src, dst)
        appended = 0

        def append():
            nonlocal appended
            appended = self._append(self.resolve(source), self.resolve(target))

        status, cause = self._fs("AppendFile", append)
        self._storage_time(2 * appended)  # F´ reads the source and writes it at the target's end
        if status:
            self._log_failure("AppendFile", f"{source} -> {target}", status, cause)
            self.AppendFileFailed(src, dst, status)
        else:
            self.AppendFileSucceeded(src, dst)
        return self._finish(status)

    @async_command(opcode=0x06)
    def FileSize(self, fileName: _PathArg):
        """Report the size of ``fileName`` in FileSizeSucceeded."""
        name = fit_utf8(fileName, CMD_STRING_SIZE)
        self.FileSizeStarted(name)
        size = 0

        def measure():
            nonlocal size
            with _open_regular(self.resolve(fileName)) as f:  # F´ opens the file to read its size
                size = os.fstat(f.fileno()).st_size

        status, cause = self._fs("FileSize", measure)
        if status:
            self._log_failure("FileSize", fileName, status, cause)
            self.FileSizeError(name, status)
        else:
            self.FileSizeSucceeded(name, size)
        return self._finish(status)

    @async_command(opcode=0x07)
    def ListDirectory(self, dirName: Annotated[str, String(FILE_NAME_STRING_SIZE)]):
        """List ``dirName``, ``files_per_tick`` entries per ``schedIn`` tick; answered at the end."""
        name = fit_utf8(dirName, FILE_NAME_STRING_SIZE)
        if self._listing is not None:
            log.warning("%s: ListDirectory %s refused: %s is still being listed", self.name, dirName,
                        self._listing.dir_name)
            self.ListDirectoryError(name, DirectoryStatus.OTHER_ERROR)
            return self._finish(FileSystemStatus.OTHER_ERROR)
        self.ListDirectoryStarted(name)
        try:
            path = self.resolve(dirName)
            names = sorted(os.listdir(path))
        except Exception as exc:  # noqa: BLE001 - every failure is reported, none escapes
            if not isinstance(exc, (OSError, ValueError)):  # not the file system's answer: a fault
                self.report_fault("ListDirectory", exc)
            status = directory_status(exc)
            self._log_failure("ListDirectory", dirName, status, exc)
            self.ListDirectoryError(name, status)
            return self._finish(FileSystemStatus.OTHER_ERROR)
        self._listing = _Listing(dirName, path, names, self.defer_command_response())
        return None

    @async_command(opcode=0x08)
    def CalculateCrc(self, filename: Annotated[str, String(FILE_NAME_STRING_SIZE)]):
        """Report the CRC of ``filename`` (F´'s ``Os::File`` CRC); no channel is updated."""
        name = fit_utf8(filename, FILE_NAME_STRING_SIZE)
        self.CalculateCrcStarted(name)
        try:
            path = self.resolve(filename)
            crc = file_crc(path)
            self._storage_time(os.path.getsize(path))
        except Exception as exc:  # noqa: BLE001 - every failure is reported, none escapes
            status = file_status(exc)
            if not isinstance(exc, (OSError, ValueError)):  # not the file system's answer: a fault
                self.report_fault("CalculateCrc", exc)
            self._log_failure("CalculateCrc", filename, status, exc)
            self.CalculateCrcFailed(name, status)
            return CmdResponse.EXECUTION_ERROR
        self.CalculateCrcSucceeded(name, crc)
        return CmdResponse.OK

    # --- directory listing ------------------------------------------------------------------------

    def _listing_tick(self) -> None:
        with self._tick_lock:
            self._tick_queued = False
        listing = self._listing
        if listing is None:
            return
        try:
            for _ in range(self.files_per_tick):
                if listing.index >= len(listing.names):
                    self._listing = None
                    self.ListDirectorySucceeded(fit_utf8(listing.dir_name, FILE_NAME_STRING_SIZE),
                                                listing.entries)
                    self._count(FileSystemStatus.OP_OK)
                    self.command_response(listing.token, CmdResponse.OK)
                    return
                entry = listing.names[listing.index]
                listing.index += 1
                listing.entries += 1
                self._list_entry(listing, entry)
        except Exception as exc:  # noqa: BLE001 - a tick must never raise into the rate group
            self.report_fault("ListDirectory tick", exc)
            self._listing = None
            self.ListDirectoryError(fit_utf8(listing.dir_name, FILE_NAME_STRING_SIZE),
                                    DirectoryStatus.OTHER_ERROR)
            self._count(FileSystemStatus.OTHER_ERROR)
            self.command_response(listing.token, CmdResponse.EXECUTION_ERROR)

    def _list_entry(self, listing: _Listing, entry: str) -> None:
        dir_name = fit_utf8(listing.dir_name, FILE_NAME_STRING_SIZE)
        try:
            entry.encode("utf-8")
        except UnicodeEncodeError:  # a name that is not UTF-8 (surrogate-escaped by os.listdir)
            shown = entry.encode("utf-8", errors="surrogateescape").decode("utf-8", errors="replace")
            log.warning("%s: ListDirectory %s: entry %r has a name that is not UTF-8", self.name,
                        listing.dir_name, shown)
            self.FileNameFormatError(fit_utf8(shown, FILE_NAME_STRING_SIZE), StringFormatStatus.OTHER_ERROR)
            return
        shown = fit_utf8(entry, FILE_NAME_STRING_SIZE)
        try:
            info = os.stat(os.path.join(listing.path, entry))
        except OSError:
            info = None  # vanished or unreadable: listed as a file of size 0, as F´ does
        if info is not None and _stat.S_ISDIR(info.st_mode):
            self.DirectoryListingSubdir(dir_name, shown)
        else:
            size = info.st_size if info is not None and _stat.S_ISREG(info.st_mode) else 0
            self.DirectoryListing(dir_name, shown, size)

    # --- file operations --------------------------------------------------------------------------

    def _move(self, src: str, dst: str) -> None:
        if not self.overwrite and os.path.lexists(dst) and not _same_entry(src, dst):
            raise FileExistsError(_errno.EEXIST, "the destination exists and overwrite is off", dst)
        try:
            os.replace(src, dst)
            return
        except OSError as exc:
            if exc.errno != _errno.EXDEV:
                raise
        # Across file systems: copy a regular file next to the destination, then remove the source.
        info = os.stat(src)
        if not _stat.S_ISREG(info.st_mode):
            raise OSError(_errno.EXDEV, "only regular files can be moved across file systems", src)
        with open(src, "rb") as source:
            self._write_replacing(dst, [source], _stat.S_IMODE(info.st_mode))
        os.remove(src)

    def _storage_time(self, nbytes: int) -> None:
        """The modelled storage's time for ``nbytes`` (nothing when no rate is given)."""
        if self.storage_bytes_per_s is not None and nbytes > 0:
            self.modelled_busy_us = round(nbytes / self.storage_bytes_per_s * 1e6)

    def _append(self, src: str, dst: str) -> int:
        """Append; the number of bytes appended (the source's size)."""
        if os.path.islink(dst):
            dst = os.path.realpath(dst)
        with _open_regular(src) as source:
            appended = os.fstat(source.fileno()).st_size
            try:
                current = _open_regular(dst)
            except FileNotFoundError:
                current = None  # created, as F´ does (createMissingDest)
            try:
                if current is not None:
                    mode = _stat.S_IMODE(os.fstat(current.fileno()).st_mode)
                    parts = [current, source]
                else:
                    mode = 0o666 & ~_umask()
                    parts = [source]
                self._write_replacing(dst, parts, mode)
            finally:
                if current is not None:
                    current.close()
        return appended

    def _write_replacing(self, dst: str, sources, mode: int) -> None:
        """Write the ``sources`` (open binary files) one after the other to a temporary file in
        ``dst``'s directory, fsync it and rename it over ``dst``; on failure ``dst`` is untouched."""
        directory = os.path.dirname(dst) or "."
        fd, tmp = temporary_file(directory, os.path.basename(dst))
        try:
            with os.fdopen(fd, "wb") as out:
                for source in sources:
                    shutil.copyfileobj(source, out, _CHUNK)
                out.flush()
                os.fsync(out.fileno())
            os.chmod(tmp, mode)
            os.replace(tmp, dst)
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise
        fsync_directory(directory)

    def _system(self, command: str, log_file_name: str) -> int:
        """Run ``command`` as F´'s ``system("eval '...' 1>>log 2>&1")`` would; the wait status."""
        try:
            log_path = self.resolve(log_file_name)
            with open(log_path, "ab") as out:
                proc = subprocess.Popen(command, shell=True, cwd=self.root, stdin=subprocess.DEVNULL,
                                        stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
                try:
                    returncode = proc.wait(timeout=self.shell_timeout_s)
                except subprocess.TimeoutExpired:
                    log.warning("%s: ShellCommand %r still running after %s s: killed", self.name,
                                command, self.shell_timeout_s)
                    _kill_group(proc)
                    returncode = proc.wait()
        except Exception as exc:  # noqa: BLE001 - cannot open the log file or start the shell
            if not isinstance(exc, (OSError, ValueError)):  # not the system's answer: a fault
                self.report_fault("ShellCommand", exc)
            log.warning("%s: ShellCommand %r not run: %s", self.name, command, exc)
            return SHELL_NOT_RUN
        status = wait_status(returncode)
        if status:
            log.info("%s: ShellCommand %r: return code %d (wait status %d)", self.name, command,
                     returncode, status)
        return status

    # --- helpers ----------------------------------------------------------------------------------

    def _fs(self, command: str, operation) -> tuple[FileSystemStatus, BaseException | None]:
        """Run ``operation`` of ``command``; ``(OP_OK, None)`` or the F´ status of what it raised
        (anything but the file system's own ``OSError``/``ValueError`` is a fault, reported)."""
        try:
            operation()
        except (OSError, ValueError) as exc:
            return filesystem_status(exc), exc
        except Exception as exc:  # noqa: BLE001 - nothing escapes a command
            self.report_fault(command, exc)
            return FileSystemStatus.OTHER_ERROR, exc
        return FileSystemStatus.OP_OK, None

    def _log_failure(self, command: str, what: str, status: enum.IntEnum, cause) -> None:
        log.warning("%s: %s %s failed: %s", self.name, command, what, _describe(status, cause))

    def _count(self, status: FileSystemStatus) -> None:
        """F´'s ``emitTelemetry``: OK counts an executed command, anything else an error."""
        if status == FileSystemStatus.OP_OK:
            self._commands_executed = (self._commands_executed + 1) & 0xFFFFFFFF
            self.CommandsExecuted.write(self._commands_executed)
        else:
            self._count_error()

    def _count_error(self) -> None:
        self._errors = (self._errors + 1) & 0xFFFFFFFF
        self.Errors.write(self._errors)

    def _finish(self, status: FileSystemStatus) -> CmdResponse:
        """Count the outcome and give the command response (F´'s ``sendCommandResponse``)."""
        self._count(status)
        return CmdResponse.OK if status == FileSystemStatus.OP_OK else CmdResponse.EXECUTION_ERROR


def _same_entry(a: str, b: str) -> bool:
    """Whether two paths name the same directory entry (a rename onto itself changes nothing)."""
    try:
        return os.path.samestat(os.lstat(a), os.lstat(b))
    except OSError:
        return False


def _open_regular(path: str):
    """Open ``path`` to read, without blocking on a FIFO: a directory raises IsADirectoryError,
    anything else that is not a regular file EINVAL (F´ would block or read a device for ever)."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        mode = os.fstat(fd).st_mode
        if _stat.S_ISDIR(mode):
            raise IsADirectoryError(_errno.EISDIR, "is a directory", path)
        if not _stat.S_ISREG(mode):
            raise OSError(_errno.EINVAL, "not a regular file", path)
    except BaseException:
        os.close(fd)
        raise
    return os.fdopen(fd, "rb")


def _umask() -> int:
    """The process umask, read without changing it where /proc allows."""
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    umask = os.umask(0o022)  # elsewhere: read it by setting it (briefly) and restoring it
    os.umask(umask)
    return umask


def _kill_group(proc: subprocess.Popen) -> None:
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except OSError:
        try:
            proc.kill()
        except OSError:
            pass
