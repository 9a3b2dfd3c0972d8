"""PrmDb: the parameter database, loaded from and saved to an F´ parameter file.

F´'s ``Svc.PrmDb`` (instance ``prmDb`` in F´'s FileHandling subtopology). Components fetch their
parameters through ``getPrm`` at start-up and push new values through ``setPrm`` when commanded
(``P_PRM_SAVE``); ``PRM_SAVE_FILE`` writes the database to the parameter file.

File format (big-endian), as ``fprime-prm-write`` (fprime-gds 4.4.1) writes it::

    U32 CRC | { U8 0xA5 | U32 size = 4 + len(value) | U32 parameter id | value bytes }*

with ``CRC = zlib.crc32(records) ^ 0xFFFFFFFF``. Files of older F´ versions have no CRC: the records
start at byte 0. :func:`decode_param_file` tells them apart (a file whose first byte is not 0xA5
must have a CRC; one starting with 0xA5 is taken as CRC-less unless its first four bytes are the
CRC of the rest). Saved files always have the CRC, and their records are ordered as
``fprime-prm-write`` orders them — by fully-qualified parameter name when the names are known
(``param_names``), by id otherwise — so the two tools write identical files for identical values.

Robustness, beyond F´:

- a file that is corrupt, truncated or fails its CRC is reported (``PrmFileReadError`` naming the
  stage, the record number and the byte offset, or ``PrmFileBadCrc``), **nothing** is loaded
  from it (the whole file is checked before any record is used; F´ keeps the records read before
  the error), and the file is never modified;
- ``PRM_SAVE_FILE`` writes a temporary file in the same directory, flushes and fsyncs it, then
  ``os.replace``-s it over the old file and fsyncs the directory: a failed save (unwritable
  directory, full disk, …) answers EXECUTION_ERROR with ``PrmFileWriteError`` and leaves the old
  file exactly as it was; the temporary file (``.fprime-lite-tmp.<pid>.<name>.….part``) of a save
  interrupted by a kill is removed at the next start-up (:meth:`PrmDb.clean_temporary_files`).

F´ v4's staged loading is kept: ``PRM_LOAD_FILE(fileName, merge)`` loads a file into the *staging*
database (``MERGE``: on top of a copy of the active one, ``RESET``: alone) and
``PRM_COMMIT_STAGED`` makes it active. While a load is staged, ``setPrm`` and the other commands
are refused with ``PrmDbFileLoadInvalidAction``.
"""

from __future__ import annotations

import errno as _errno
import logging
import os
import stat as _stat
import struct
import zlib
from dataclasses import dataclass
from typing import Annotated, Iterable, Mapping

from fprime_lite.osal.atomic import clean_temporary_files, temporary_file
from fprime_lite.model.commands import CmdResponse, async_command
from fprime_lite.model.component import ActiveComponent
from fprime_lite.model.errors import FprimeLiteError, FwAssertionError
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Ping, PrmGet, PrmSet
from fprime_lite.model.params import ParamValid
from fprime_lite.model.ports import OutputPort, async_input, guarded_input
from fprime_lite.model.types import I32, U8, U32, FwEnum, String

__all__ = [
    "PrmDb", "PrmReadError", "PrmWriteError", "PrmDbFileLoadState", "PrmLoadAction", "Merge",
    "ParamFileError", "ParamFileCrcError", "ParamFile", "encode_param_file", "decode_param_file",
    "param_file_crc", "ENTRY_DELIMITER", "PARAM_BUFFER_MAX_SIZE", "PRMDB_NUM_DB_ENTRIES",
    "FILE_NAME_STRING_SIZE",
]

log = logging.getLogger("fprime_lite")

#: Byte that starts every record (F´ ``PRMDB_ENTRY_DELIMITER``).
ENTRY_DELIMITER = 0xA5
#: Largest serialized parameter value (F´ ``FW_PARAM_BUFFER_MAX_SIZE``).
PARAM_BUFFER_MAX_SIZE = 506
#: F´'s database size (``PRMDB_NUM_DB_ENTRIES``); fprime-lite's default capacity is larger.
PRMDB_NUM_DB_ENTRIES = 25
#: Bound of the PRM_LOAD_FILE file name (F´ ``FileNameStringSize``).
FILE_NAME_STRING_SIZE = 200

_U32 = struct.Struct(">I")
_ID_SIZE = 4


class PrmReadError(FwEnum, namespace="Svc.PrmDb", rep=U8):
    """Where reading a parameter file failed (F´ ``Svc.PrmDb.PrmReadError``)."""

    OPEN = 0
    DELIMITER = 1
    DELIMITER_SIZE = 2
    DELIMITER_VALUE = 3
    RECORD_SIZE = 4
    RECORD_SIZE_SIZE = 5
    RECORD_SIZE_VALUE = 6
    PARAMETER_ID = 7
    PARAMETER_ID_SIZE = 8
    PARAMETER_VALUE = 9
    PARAMETER_VALUE_SIZE = 10
    CRC = 11
    CRC_SIZE = 12
    CRC_BUFFER = 13
    SEEK_ZERO = 14


class PrmWriteError(FwEnum, namespace="Svc.PrmDb", rep=U8):
    """Where writing the parameter file failed (F´ ``Svc.PrmDb.PrmWriteError``)."""

    OPEN = 0
    DELIMITER = 1
    DELIMITER_SIZE = 2
    RECORD_SIZE = 3
    RECORD_SIZE_SIZE = 4
    PARAMETER_ID = 5
    PARAMETER_ID_SIZE = 6
    PARAMETER_VALUE = 7
    PARAMETER_VALUE_SIZE = 8
    CRC_PLACE = 9
    CRC_REAL = 10
    CURR_POSITION = 11
    SEEK_ZERO = 12
    SEEK_POSITION = 13


class PrmDbFileLoadState(FwEnum, namespace="Svc.PrmDb", rep=U8):
    """State of a commanded file load (F´ ``Svc.PrmDb.PrmDbFileLoadState``)."""

    IDLE = 0
    LOADING_FILE_UPDATES = 1
    FILE_UPDATES_STAGED = 2


class PrmLoadAction(FwEnum, namespace="Svc.PrmDb", rep=U8):
    """An action refused during a file load (F´ ``Svc.PrmDb.PrmLoadAction``)."""

    SET_PARAMETER = 0
    SAVE_FILE_COMMAND = 1
    LOAD_FILE_COMMAND = 2
    COMMIT_STAGED_COMMAND = 3


class Merge(FwEnum, namespace="Svc.PrmDb", rep=U8):
    """PRM_LOAD_FILE: load on top of the active parameters (MERGE) or alone (RESET)."""

    MERGE = 0
    RESET = 1


# --- the file format ------------------------------------------------------------------------------

class ParamFileError(FprimeLiteError):
    """A parameter file that cannot be loaded: ``stage``, ``record`` (0-based) and byte ``offset``."""

    def __init__(self, stage: PrmReadError, record: int, offset: int, message: str):
        super().__init__(f"{stage.name} at byte {offset} (record {record}): {message}")
        self.stage = stage
        self.record = record
        self.offset = offset


class ParamFileCrcError(ParamFileError):
    """The records are well formed but their CRC is not the one stored at byte 0."""

    def __init__(self, read_crc: int, computed_crc: int):
        super().__init__(PrmReadError.CRC, 0, 0,
                         f"stored CRC 0x{read_crc:08X} differs from the CRC of the records "
                         f"0x{computed_crc:08X}")
        self.read_crc = read_crc
        self.computed_crc = computed_crc


@dataclass
class ParamFile:
    """A decoded parameter file: ``records`` as ``(id, value bytes)`` in file order."""

    records: list[tuple[int, bytes]]
    has_crc: bool


def param_file_crc(records: bytes) -> int:
    """The CRC stored at the head of a parameter file: ``zlib.crc32(records) ^ 0xFFFFFFFF``."""
    return zlib.crc32(records) ^ 0xFFFFFFFF


def encode_param_file(records: Iterable[tuple[int, bytes]], *, with_crc: bool = True) -> bytes:
    """The bytes of a parameter file holding ``records`` (``(id, value bytes)``) in that order."""
    parts = []
    for prm_id, value in records:
        value = bytes(value)
        if len(value) > PARAM_BUFFER_MAX_SIZE:
            raise ValueError(f"parameter 0x{prm_id:X}: value of {len(value)} bytes exceeds "
                             f"{PARAM_BUFFER_MAX_SIZE} bytes")
        parts.append(bytes([ENTRY_DELIMITER]) + _U32.pack(_ID_SIZE + len(value)) + _U32.pack(prm_id) + value)
    body = b"".join(parts)
    return (_U32.pack(param_file_crc(body)) + body) if with_crc else body


def _parse_records(data: bytes, start: int) -> list[tuple[int, bytes]]:
    records: list[tuple[int, bytes]] = []
    offset = start
    n = len(data)
    while offset < n:
        index = len(records)
        if data[offset] != ENTRY_DELIMITER:
            raise ParamFileError(PrmReadError.DELIMITER_VALUE, index, offset,
                                 f"delimiter is 0x{data[offset]:02X}, expected 0x{ENTRY_DELIMITER:02X}")
        if offset + 5 > n:
            raise ParamFileError(PrmReadError.RECORD_SIZE_SIZE, index, offset + 1,
                                 f"file ends inside the record size ({n - offset - 1} of 4 bytes)")
        size, = _U32.unpack_from(data, offset + 1)
        if size < _ID_SIZE or size > PARAM_BUFFER_MAX_SIZE + _ID_SIZE:
            raise ParamFileError(PrmReadError.RECORD_SIZE_VALUE, index, offset + 1,
                                 f"record size {size} is outside {_ID_SIZE}..{PARAM_BUFFER_MAX_SIZE + _ID_SIZE}")
        if offset + 9 > n:
            raise ParamFileError(PrmReadError.PARAMETER_ID_SIZE, index, offset + 5,
                                 f"file ends inside the parameter id ({n - offset - 5} of 4 bytes)")
        prm_id, = _U32.unpack_from(data, offset + 5)
        end = offset + 5 + size
        if end > n:
            raise ParamFileError(PrmReadError.PARAMETER_VALUE_SIZE, index, offset + 9,
                                 f"file ends inside the value of parameter 0x{prm_id:X} "
                                 f"({n - offset - 9} of {size - _ID_SIZE} bytes)")
        records.append((prm_id, bytes(data[offset + 9:end])))
        offset = end
    return records


def decode_param_file(data: bytes) -> ParamFile:
    """Decode a parameter file, with or without its leading CRC; raise :class:`ParamFileError`."""
    data = bytes(data)
    n = len(data)
    if n == 0:
        raise ParamFileError(PrmReadError.CRC_SIZE, 0, 0, "the file is empty; expected a 4-byte CRC")
    if data[0] != ENTRY_DELIMITER:
        return ParamFile(_decode_with_crc(data), True)
    # Starts like a record: an older CRC-less file, or a CRC whose first byte happens to be 0xA5.
    crc_matches = n >= 4 and _U32.unpack_from(data)[0] == param_file_crc(data[4:])
    if crc_matches:
        try:
            return ParamFile(_parse_records(data, 4), True)
        except ParamFileError:
            pass
    try:
        return ParamFile(_parse_records(data, 0), False)
    except ParamFileError as no_crc_error:
        if n >= 4 and not crc_matches:
            try:
                _parse_records(data, 4)
            except ParamFileError:
                raise no_crc_error from None
            raise ParamFileCrcError(_U32.unpack_from(data)[0], param_file_crc(data[4:])) from None
        raise


def _decode_with_crc(data: bytes) -> list[tuple[int, bytes]]:
    if len(data) < 4:
        raise ParamFileError(PrmReadError.CRC_SIZE, 0, len(data),
                             f"the file is {len(data)} byte(s), too short for its 4-byte CRC")
    records = _parse_records(data, 4)  # structure first: its errors name the offset
    read_crc, = _U32.unpack_from(data)
    computed = param_file_crc(data[4:])
    if read_crc != computed:
        raise ParamFileCrcError(read_crc, computed)
    return records


# --- the component --------------------------------------------------------------------------------

class PrmDb(ActiveComponent):
    """F´'s parameter database (``Svc.PrmDb``).

    Args:
        name: instance name (``prmDb`` in F´'s FileHandling).
        file_path: the parameter file read by :meth:`read_param_file` and written by PRM_SAVE_FILE.
        base_id: added to the local opcodes (0–2) and event ids (0–12).
        queue_size: depth of the message queue.
        capacity: how many parameters each database holds (F´: 25).
        param_names: parameter id -> fully-qualified name (``Dep.inst.NAME``), which orders saved
            records as fprime-prm-write does; see :meth:`set_param_names`.
    """

    pingOut = OutputPort(Ping)

    # Instance state, declared here so the command handlers above __init__ see the types.
    _active: dict[int, bytes]
    _staging: dict[int, bytes]
    _state: PrmDbFileLoadState

    # --- commands ------------------------------------------------------------------------------

    @async_command(opcode=0)
    def PRM_SAVE_FILE(self):
        """Save the active parameters to the parameter file (atomically)."""
        if self._state != PrmDbFileLoadState.IDLE:
            self.PrmDbFileLoadInvalidAction(self._state, PrmLoadAction.SAVE_FILE_COMMAND)
            return CmdResponse.BUSY
        with self._lock:
            records = self._ordered(self._active)
        data = encode_param_file(records)
        failure = self._write_atomically(data, len(records))
        if failure is not None:
            stage, record, error, text = failure
            log.warning("%s: PRM_SAVE_FILE: cannot write %s: %s", self.name, self.file_path, text)
            self.PrmFileWriteError(stage, record, error)
            return CmdResponse.EXECUTION_ERROR
        self._dirty = False
        self.PrmFileSaveComplete(len(records))
        return CmdResponse.OK

    @async_command(opcode=1)
    def PRM_LOAD_FILE(self, fileName: Annotated[str, String(FILE_NAME_STRING_SIZE)], merge: Merge):
        """Load ``fileName`` into the staging database; PRM_COMMIT_STAGED makes it active."""
        if self._state != PrmDbFileLoadState.IDLE:
            self.PrmDbFileLoadInvalidAction(self._state, PrmLoadAction.LOAD_FILE_COMMAND)
            return CmdResponse.BUSY
        if not fileName:
            self.PrmDbFileLoadFailed()
            return CmdResponse.VALIDATION_ERROR
        self._state = PrmDbFileLoadState.LOADING_FILE_UPDATES
        with self._lock:
            if merge == Merge.MERGE:
                self._staging = dict(self._active)
            else:
                self._staging = {}
        if merge == Merge.MERGE:
            self.PrmDbCopyAllComplete("ACTIVE", "STAGING")
        if self._load_into(fileName, "STAGING"):
            self._state = PrmDbFileLoadState.FILE_UPDATES_STAGED
            return CmdResponse.OK
        self.PrmDbFileLoadFailed()
        with self._lock:
            self._staging = {}
        self._state = PrmDbFileLoadState.IDLE
        return CmdResponse.EXECUTION_ERROR

    @async_command(opcode=2)
    def PRM_COMMIT_STAGED(self):
        """Make the staged parameters (from PRM_LOAD_FILE) the active ones."""
        if self._state != PrmDbFileLoadState.FILE_UPDATES_STAGED:
            self.PrmDbFileLoadInvalidAction(self._state, PrmLoadAction.COMMIT_STAGED_COMMAND)
            return CmdResponse.VALIDATION_ERROR
        with self._lock:
            self._active, self._staging = self._staging, {}
            self._dirty = True
        self._state = PrmDbFileLoadState.IDLE
        self.PrmDbCommitComplete()
        return CmdResponse.OK

    # --- events (F´ v4 ids, severities and formats) --------------------------------------------

    PrmIdNotFound = Event(Severity.WARNING_LO, "Parameter ID 0x{x} not found", id=0, throttle=5,
                          args=[("Id", U32)])
    PrmIdUpdated = Event(Severity.ACTIVITY_HI, "Parameter ID 0x{x} updated", id=1, args=[("Id", U32)])
    PrmDbFull = Event(Severity.WARNING_HI, "Parameter DB full when adding ID 0x{x} ", id=2,
                      args=[("Id", U32)])
    PrmIdAdded = Event(Severity.ACTIVITY_HI, "Parameter ID 0x{x} added", id=3, args=[("Id", U32)])
    PrmFileWriteError = Event(Severity.WARNING_HI,
                              "Parameter write failed in stage {} with record {} and error {}", id=4,
                              args=[("stage", PrmWriteError), ("record", I32), ("error", I32)])
    PrmFileSaveComplete = Event(Severity.ACTIVITY_HI, "Parameter file save completed. Wrote {} records.",
                                id=5, args=[("records", U32)])
    PrmFileReadError = Event(Severity.WARNING_HI,
                             "Parameter file read failed in stage {} with record {} and error {}", id=6,
                             args=[("stage", PrmReadError), ("record", I32), ("error", I32)])
    PrmFileLoadComplete = Event(
        Severity.ACTIVITY_HI,
        "Parameter file load completed. Database: {}, Records: {} ({} added and {} updated).", id=7,
        args=[("databaseString", String(80)), ("recordsTotal", U32), ("recordsAdded", U32),
              ("recordsUpdated", U32)])
    PrmDbCommitComplete = Event(Severity.ACTIVITY_HI,
                                "Parameter DB commit complete, staged updates are now active.", id=8)
    PrmDbCopyAllComplete = Event(
        Severity.ACTIVITY_HI, "All parameters copied. Source database: {}, Destination database: {}.",
        id=9, args=[("databaseStringSrc", String(80)), ("databaseStringDest", String(80))])
    PrmDbFileLoadFailed = Event(
        Severity.WARNING_HI,
        "Parameter file load failed. Clearing staging database and abandoning parameter file load.", id=10)
    PrmDbFileLoadInvalidAction = Event(
        Severity.WARNING_LO,
        "Invalid action during parameter file load. Current state: {}, Action (Invalid for current "
        "state): {}.", id=11,
        args=[("currentState", PrmDbFileLoadState), ("attemptedAction", PrmLoadAction)])
    PrmFileBadCrc = Event(Severity.WARNING_HI, "Parameter file failed CRC. Read: 0x{x} Computed: 0x{x}",
                          id=12, args=[("readCrc", U32), ("compCrc", U32)])

    def __init__(self, name: str = "prmDb", file_path: str | os.PathLike = "PrmDb.dat", *,
                 base_id: int = 0, queue_size: int = 10, capacity: int = 256,
                 param_names: Mapping[int, str] | None = None):
        super().__init__(name, base_id=base_id, queue_size=queue_size)
        if not isinstance(capacity, int) or capacity < 1:
            raise ValueError(f"{name}: capacity must be a positive integer, got {capacity!r}")
        self.file_path = os.fspath(file_path)
        self.capacity = capacity
        self._active = {}
        self._staging = {}
        self._state = PrmDbFileLoadState.IDLE
        self._dirty = False
        self._names: dict[int, str] = dict(param_names or {})

    def clean_temporary_files(self) -> list[str]:
        """Start-up: remove the temporary files a killed save left next to the parameter file."""
        removed = clean_temporary_files(os.path.dirname(os.path.abspath(self.file_path)))
        if removed:
            log.info("%s: removed %d temporary file(s) of an interrupted save", self.name, len(removed))
        return removed

    # --- ports ---------------------------------------------------------------------------------

    @guarded_input(PrmGet)
    def getPrm(self, prm_id: int) -> tuple:
        """``(ParamValid.VALID, value bytes)``, or ``(ParamValid.INVALID, None)`` + PrmIdNotFound."""
        value = self._active.get(prm_id)
        if value is None:
            self.PrmIdNotFound(prm_id & 0xFFFFFFFF if isinstance(prm_id, int) else 0)
            return ParamValid.INVALID, None
        return ParamValid.VALID, value

    @guarded_input(PrmSet)
    def setPrm(self, prm_id: int, value: bytes) -> None:
        """Store ``value`` (serialized) for ``prm_id`` in the active database; mark it unsaved."""
        if self._state != PrmDbFileLoadState.IDLE:
            self.PrmDbFileLoadInvalidAction(self._state, PrmLoadAction.SET_PARAMETER)
            return
        try:
            value = bytes(value)
            valid_id = isinstance(prm_id, int) and 0 <= prm_id <= 0xFFFFFFFF
        except (TypeError, ValueError):
            valid_id = False
        if not valid_id or len(value) > PARAM_BUFFER_MAX_SIZE:
            log.warning("%s: setPrm: refused id %r with a value of %s: ids are U32 and values at most "
                        "%d bytes", self.name, prm_id,
                        f"{len(value)} bytes" if isinstance(value, bytes) else repr(value),
                        PARAM_BUFFER_MAX_SIZE)
            return
        outcome = self._update(self._active, prm_id, value)
        if outcome == "full":
            self.PrmDbFull(prm_id)
            return
        self._dirty = True
        (self.PrmIdAdded if outcome == "added" else self.PrmIdUpdated)(prm_id)

    @async_input(Ping)
    def pingIn(self, key: int) -> None:
        """Health ping: answer with the same key."""
        if self.is_connected("pingOut", 0):
            self.pingOut[0](key)

    # --- start-up ------------------------------------------------------------------------------

    def read_param_file(self) -> bool:
        """Load the parameter file into the active database (F´ ``readParamFile``; start-up only).

        Returns True when the file was loaded. On any problem the event says what and where,
        nothing is loaded, and the file is left untouched.
        """
        if self._state != PrmDbFileLoadState.IDLE:
            raise FwAssertionError(f"{self.name}: read_param_file() during a commanded load "
                                   f"({self._state.name}); call it at start-up")
        with self._lock:
            self._active = {}
            self._staging = {}
            self._dirty = False
        return self._load_into(self.file_path, "ACTIVE")

    def set_param_names(self, names: Mapping[int, str]) -> None:
        """Tell PrmDb the fully-qualified name of each parameter id (orders saved records)."""
        self._names = dict(names)

    # --- inspection ----------------------------------------------------------------------------

    @property
    def dirty(self) -> bool:
        """True when the active parameters differ from what was last loaded or saved."""
        return self._dirty

    @property
    def state(self) -> PrmDbFileLoadState:
        return self._state

    def records(self, staging: bool = False) -> dict[int, bytes]:
        """A copy of the active (or staging) database: id -> serialized value."""
        with self._lock:
            return dict(self._staging if staging else self._active)

    # --- helpers -------------------------------------------------------------------------------

    def _update(self, db: dict[int, bytes], prm_id: int, value: bytes) -> str:
        with self._lock:
            if prm_id in db:
                db[prm_id] = value
                return "updated"
            if len(db) >= self.capacity:
                return "full"
            db[prm_id] = value
            return "added"

    def _load_into(self, path: str, which: str) -> bool:
        """Read ``path`` whole, check it, then apply it to the ACTIVE or STAGING database."""
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as exc:
            log.warning("%s: cannot open parameter file %s: %s", self.name, path, exc)
            self.PrmFileReadError(PrmReadError.OPEN, 0, exc.errno or _errno.EIO)
            return False
        try:
            decoded = decode_param_file(data)
        except ParamFileCrcError as exc:
            log.warning("%s: parameter file %s not loaded: %s", self.name, path, exc)
            self.PrmFileBadCrc(exc.read_crc, exc.computed_crc)
            return False
        except ParamFileError as exc:
            log.warning("%s: parameter file %s not loaded: %s", self.name, path, exc)
            self.PrmFileReadError(exc.stage, exc.record, min(exc.offset, 0x7FFFFFFF))
            return False
        added = updated = 0
        db = self._active if which == "ACTIVE" else self._staging
        for prm_id, value in decoded.records:
            outcome = self._update(db, prm_id, value)
            if outcome == "added":
                added += 1
            elif outcome == "updated":
                updated += 1
            else:
                self.PrmDbFull(prm_id)
        self.PrmFileLoadComplete(which, len(decoded.records), added, updated)
        return True

    def _ordered(self, db: dict[int, bytes]) -> list[tuple[int, bytes]]:
        """Records in fprime-prm-write's order: by full name; unnamed ids after, by id."""
        names = self._names
        return sorted(db.items(), key=lambda kv: (kv[0] not in names, names.get(kv[0], ""), kv[0]))

    def _write_atomically(self, data: bytes, n_records: int):
        """Replace the parameter file by ``data``; None, or ``(stage, record, errno, text)``."""
        path = os.path.abspath(self.file_path)
        directory, base = os.path.split(path)
        try:
            mode = _stat.S_IMODE(os.stat(path).st_mode)
        except OSError:
            mode = 0o644
        try:
            fd, tmp = temporary_file(directory, base)
        except OSError as exc:
            return PrmWriteError.OPEN, 0, exc.errno or _errno.EIO, f"cannot create a temporary file: {exc}"
        try:
            try:
                with os.fdopen(fd, "wb") as f:
                    f.write(data)
                    f.flush()
                    os.fsync(f.fileno())
                os.chmod(tmp, mode)
            except OSError as exc:
                return (PrmWriteError.PARAMETER_VALUE, n_records, exc.errno or _errno.EIO,
                        f"cannot write the temporary file {tmp}: {exc}")
            try:
                os.replace(tmp, path)
            except OSError as exc:
                return PrmWriteError.OPEN, 0, exc.errno or _errno.EIO, f"cannot replace {path}: {exc}"
        finally:
            if os.path.exists(tmp):
                try:
                    os.unlink(tmp)
                except OSError:
                    pass
        try:
            dir_fd = os.open(directory, os.O_RDONLY)
        except OSError:
            return None
        try:
            os.fsync(dir_fd)
        except OSError:
            pass  # the file is already in place; some file systems refuse fsync on directories
        finally:
            os.close(dir_fd)
        return None
