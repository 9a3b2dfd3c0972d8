"""FsFormat as flown: formats the flight computer's file system.

FORMAT empties the simulated flash (``spacecraft.flash_dir``: the persisted state of the mode
manager, the boot count, the antenna's deployed flag, the sequence number …) and logs
FileSystemFormatted; when something cannot be removed it logs FileSystemFormatFailed and answers
EXECUTION_ERROR. As on the board, components that keep state in memory go on with it until the next
reset, when they find an empty flash (a first boot).

Ground interface (flight ``Components.FsFormat``, base id 0x10078000): command FORMAT (0); events
FileSystemFormatted (ACTIVITY_HI), FileSystemFormatFailed (WARNING_HI). With ``run --board-root DIR``
(what ``conformance --board-root`` passes) DIR is both the board's ``/`` for the file services and the
simulated flash, so FORMAT also erases uplinked files such as ``/seq/*.bin``, as on the board.
Deviation: without a board root, the folder the file services use (the run folder) is not the
simulated flash and is kept.
"""

from __future__ import annotations

import os
import shutil

from fprime_lite import CmdResponse, Event, PassiveComponent, Severity, sync_command

from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["FsFormat"]


class FsFormat(PassiveComponent):
    """Formats the simulated flash of ``spacecraft`` (instance ``fsFormat``)."""

    @sync_command()
    def FORMAT(self):
        """Remove everything in the simulated flash."""
        root = self.spacecraft.flash_dir
        try:
            for entry in os.scandir(root):
                if entry.is_dir(follow_symlinks=False):
                    shutil.rmtree(entry.path)
                else:
                    os.unlink(entry.path)
        except OSError:
            self.FileSystemFormatFailed()
            return CmdResponse.EXECUTION_ERROR
        self.FileSystemFormatted()

    FileSystemFormatted = Event(Severity.ACTIVITY_HI, "File System formatted successfully")
    FileSystemFormatFailed = Event(Severity.WARNING_HI, "File System format failed")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
