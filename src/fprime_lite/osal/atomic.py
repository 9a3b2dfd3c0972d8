"""Atomic file writes: readers see the old file or the new one, never a part of either.

The data goes to a temporary file in the destination's folder, is flushed and fsynced, then
renamed over the destination; the folder is fsynced so the rename survives a crash.

Temporary files are named ``.fprime-lite-tmp.<pid>.<name>.<random>.part`` (:func:`temporary_file`),
so that what a killed process left behind can be recognised and removed at the next start-up
(:func:`clean_temporary_files`): a temporary file whose process is gone (or has our own pid but
was not made by this process, i.e. an earlier process had the pid) is removed; one of a live
process, or one this process made, is left alone — so any component or recorder may clean its
folder when it starts, even while other writers of the same process are streaming there.
"""

from __future__ import annotations

import os
import pathlib
import re
import tempfile

__all__ = ["atomic_write_bytes", "atomic_write_json", "atomic_write_text", "file_mode_for", "fsync_directory",
           "temporary_file",
           "open_temporary", "is_temporary_name", "clean_temporary_files", "TEMP_PREFIX", "TEMP_SUFFIX"]

#: How every temporary file of an atomic write starts and ends.
TEMP_PREFIX = ".fprime-lite-tmp."
TEMP_SUFFIX = ".part"
_TEMP_NAME = re.compile(r"\.fprime-lite-tmp\.(\d+)\..*\.part\Z", re.DOTALL)
_NAME_CHARS = 64  # of the destination's name kept in the temporary name (well inside NAME_MAX)


#: Temporary files this process made (real paths), which clean_temporary_files never removes:
#: a writer of this process may still be streaming into one.
_ours: set[str] = set()


def temporary_file(directory, name: str) -> tuple[int, str]:
    """Create a recognisable temporary file in ``directory`` for the destination called ``name``:
    ``(fd, path)``, opened for writing, mode 0600 until the caller sets the final mode."""
    fd, path = tempfile.mkstemp(prefix=f"{TEMP_PREFIX}{os.getpid()}.{name[:_NAME_CHARS]}.", suffix=TEMP_SUFFIX,
                                dir=directory)
    _ours.add(os.path.realpath(path))
    return fd, path


def open_temporary(path, mode: str = "w", **kwargs):
    """``(file, temporary path)``: a recognisable temporary file beside ``path`` opened with
    ``mode`` (``open``'s ``kwargs``), with the mode ``path`` will have, for a writer that streams
    into it and renames it over ``path`` when done (``os.replace``)."""
    path = pathlib.Path(path)
    fd, tmp = temporary_file(path.parent, path.name)
    try:
        os.chmod(tmp, file_mode_for(path))
        return os.fdopen(fd, mode, **kwargs), pathlib.Path(tmp)
    except BaseException:
        os.close(fd)
        os.unlink(tmp)
        raise


def is_temporary_name(name: str) -> bool:
    """Whether ``name`` (a file name, not a path) is one :func:`temporary_file` makes."""
    return _TEMP_NAME.match(name) is not None


def _owner_gone(pid: int) -> bool:
    """Whether the process that made a temporary file is gone (call at start-up only: a file with
    our own pid is then an earlier process's)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except PermissionError:
        return False  # alive, another user's
    except (OverflowError, ValueError):
        return True  # not a possible pid
    return False


def clean_temporary_files(folder, *, recursive: bool = False, limit: int = 100_000) -> list[str]:
    """Remove the temporary files that dead processes left in ``folder`` (and its sub-folders when
    ``recursive``, without following links; at most ``limit`` entries are examined). Returns the
    paths removed; a folder that does not exist or cannot be read is skipped."""
    removed: list[str] = []
    seen = 0
    pending = [os.fspath(folder)]
    while pending and seen < limit:
        current = pending.pop()
        try:
            entries = list(os.scandir(current))
        except OSError:
            continue
        for entry in entries:
            seen += 1
            if seen > limit:
                break
            try:
                if entry.is_dir(follow_symlinks=False):
                    if recursive:
                        pending.append(entry.path)
                    continue
            except OSError:
                continue
            match = _TEMP_NAME.match(entry.name)
            if match and _owner_gone(int(match.group(1))) and os.path.realpath(entry.path) not in _ours:
                try:
                    os.unlink(entry.path)
                    removed.append(entry.path)
                except OSError:
                    pass
    return removed


def atomic_write_bytes(path, data: bytes) -> None:
    """Replace ``path`` with ``data`` atomically (creating parent folders)."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = temporary_file(path.parent, path.name)
    try:
        os.chmod(tmp, file_mode_for(path))
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    finally:
        _ours.discard(os.path.realpath(tmp))
    fsync_directory(path.parent)


def atomic_write_text(path, text: str) -> None:
    """Replace ``path`` with ``text`` (UTF-8) atomically."""
    atomic_write_bytes(path, text.encode("utf-8"))


def atomic_write_json(path, obj, *, indent: int = 1) -> None:
    """Replace ``path`` with ``obj`` as indented JSON (UTF-8, a final newline) atomically, creating parent folders
    (the study scripts' ``--json`` files)."""
    import json

    atomic_write_text(path, json.dumps(obj, indent=indent) + "\n")


def file_mode_for(path) -> int:
    """Keep an existing file's permissions; a new file gets the usual ``0o666 & ~umask``."""
    try:
        return pathlib.Path(path).stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def fsync_directory(folder) -> None:
    """Make a rename or a new file in ``folder`` durable (best effort: errors are ignored)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
