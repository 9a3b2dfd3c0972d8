"""One writer per campaign folder: an advisory lock held while a campaign process writes its rows.

Two processes writing results parts into the same folder (a second ``--resume`` started while the first is
still running) would run the same runs twice and race on ``results.parquet`` and the manifest. The
lock is ``flock`` on ``OUT/.campaign.lock``, which records the holder's pid and host; the kernel drops
it when the holder exits, however it exits, so a killed campaign never leaves a stale lock behind.
Where ``fcntl`` does not exist (Windows) the folder is not locked.
"""

from __future__ import annotations

import contextlib
import os
import pathlib
import socket
from collections.abc import Iterator

from fprime_lite.tools.campaign.errors import CampaignError

try:
    import fcntl
except ImportError:  # pragma: no cover - not POSIX
    fcntl = None  # type: ignore[assignment]

__all__ = ["LOCK_NAME", "campaign_folder_lock"]

LOCK_NAME = ".campaign.lock"


@contextlib.contextmanager
def campaign_folder_lock(out: pathlib.Path) -> Iterator[None]:
    """Hold the campaign folder ``out`` (which must exist) for this process; a CampaignError naming the
    holder when another process holds it."""
    if fcntl is None:  # pragma: no cover - not POSIX
        yield
        return
    path = pathlib.Path(out) / LOCK_NAME
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.read(fd, 200).decode("utf-8", "replace").strip() or "another process"
            raise CampaignError([f"--out {out}: a campaign is already writing into this folder ({holder}) — wait for "
                                 "it to finish or stop it, then --resume"]) from None
        os.ftruncate(fd, 0)
        os.write(fd, f"pid {os.getpid()} on {socket.gethostname()}\n".encode())
        yield
    finally:
        os.close(fd)  # closing the descriptor releases the lock
