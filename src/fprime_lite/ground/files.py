"""Ground-side reassembly of downlinked files, as fprime-gds's file downlinker does it.

:class:`FileReceiver` takes the file packets a deployment downlinks (``FW_PACKET_FILE``: START,
DATA…, END or CANCEL) and writes each file into one directory. As the GDS does, the destination
path of the START packet becomes a file name by replacing every ``/`` with ``_``. Data is written
to a hidden temporary file and renamed into place when the END packet arrives, so a half-received
file never sits under its final name; the END packet's CFDP checksum is compared with the bytes
received, and every file's outcome is listed in :attr:`FileReceiver.files`.
"""

from __future__ import annotations

import os
import pathlib
from dataclasses import dataclass

from fprime_lite.osal.atomic import clean_temporary_files, open_temporary
from fprime_lite.wire.file_packet import (CancelPacket, CfdpChecksum, DataPacket, EndPacket, FilePacketError,
                                          StartPacket, decode_file_packet)

__all__ = ["FileReceiver", "ReceivedFile"]


@dataclass
class ReceivedFile:
    """One downlinked file: where it went and how it ended.

    ``status``: ``receiving``, ``complete`` (checksum matched), ``checksum mismatch`` (kept, with
    the checksums in ``detail``), ``canceled`` or ``incomplete`` (a new START or the end of the run
    came first; nothing is kept).
    """

    source: str
    destination: str
    path: pathlib.Path
    size: int
    received_bytes: int = 0
    status: str = "receiving"
    detail: str = ""


class FileReceiver:
    """Writes downlinked files into ``directory`` (created on the first file)."""

    def __init__(self, directory):
        self.directory = pathlib.Path(directory)
        self.files: list[ReceivedFile] = []
        self.bad_packets = 0
        self._active: ReceivedFile | None = None
        self._tmp: pathlib.Path | None = None
        self._handle = None
        self._checksum = CfdpChecksum()
        clean_temporary_files(self.directory)  # files a killed receiver was reassembling

    def receive(self, packet: bytes) -> None:
        """Handle one file packet, descriptor first. Malformed or unexpected packets are counted."""
        decoded = decode_file_packet(packet, descriptor=True)
        if isinstance(decoded, FilePacketError):
            self.bad_packets += 1
        elif isinstance(decoded, StartPacket):
            self._start(decoded)
        elif self._active is None:
            self.bad_packets += 1  # DATA, END or CANCEL with no file open
        elif isinstance(decoded, DataPacket):
            self._data(decoded)
        elif isinstance(decoded, EndPacket):
            self._end(decoded)
        elif isinstance(decoded, CancelPacket):
            self._abandon("canceled")

    def close(self) -> None:
        """Give up a file still being received (end of the run)."""
        if self._active is not None:
            self._abandon("incomplete", "the run ended before its END packet")

    def _start(self, start: StartPacket) -> None:
        if self._active is not None:
            self._abandon("incomplete", "a new START arrived before its END packet")
        name = start.destination.replace("/", "_") or "unnamed"
        self.directory.mkdir(parents=True, exist_ok=True)
        record = ReceivedFile(start.source, start.destination, self.directory / name, start.file_size)
        self.files.append(record)
        self._active = record
        self._handle, self._tmp = open_temporary(record.path, "wb")
        self._checksum = CfdpChecksum()

    def _data(self, data: DataPacket) -> None:
        handle, record = self._handle, self._active
        assert handle is not None and record is not None  # only called while a file is open
        handle.seek(data.offset)
        handle.write(data.data)
        self._checksum.update(data.data, data.offset)
        record.received_bytes += len(data.data)

    def _end(self, end: EndPacket) -> None:
        record, handle, tmp = self._active, self._handle, self._tmp
        assert record is not None and handle is not None and tmp is not None  # a file is open
        handle.flush()
        os.fsync(handle.fileno())
        handle.close()
        os.replace(tmp, record.path)
        if end.checksum == self._checksum.value and record.received_bytes == record.size:
            record.status = "complete"
        else:
            record.status = "checksum mismatch"
            record.detail = (f"END says 0x{end.checksum:08X}, received bytes give 0x{self._checksum.value:08X}; "
                             f"{record.received_bytes} of {record.size} bytes")
        self._active = None

    def _abandon(self, status: str, detail: str = "") -> None:
        record, handle, tmp = self._active, self._handle, self._tmp
        assert record is not None and handle is not None and tmp is not None  # a file is open
        handle.close()
        tmp.unlink(missing_ok=True)
        record.status = status
        record.detail = detail
        self._active = None
