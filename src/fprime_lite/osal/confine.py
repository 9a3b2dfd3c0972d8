"""Confining file services to one root directory.

Every path a ground command or a file packet names is resolved against the service's root and
must stay inside it. A path is refused when, after resolution:

- it leaves the root through ``..`` components,
- it is absolute and outside the root (an absolute path inside the root is fine),
- a symbolic link on the way (or at the end, for operations that open the file's contents) points
  outside the root.

A board root (``board=True``) makes the root stand in for a flight computer's own ``/``: an absolute
path ``/seq/a.bin`` names ``ROOT/seq/a.bin`` and a relative one resolves against the root (a board
has no other working directory), so a suite written for a board's file system runs unchanged while
nothing outside the root is reachable (``/..`` still leaves it and is refused).

The check resolves the path the way the OS will (``os.path.realpath``) and the service then works
on the *resolved* path, so what was checked is what is used. A symbolic link swapped in between
the check and the use (by someone with write access inside the root) is not guarded against.
"""

from __future__ import annotations

import errno
import os

__all__ = ["PathRefused", "Confinement"]


class PathRefused(PermissionError):
    """A path that is not allowed: ``reason`` says why in a few words (for an event). A
    PermissionError (EACCES), so the F´ status of every OS layer maps it to NO_PERMISSION."""

    def __init__(self, path: str, reason: str):
        super().__init__(errno.EACCES, reason, path)
        self.path = path
        self.reason = reason

    def __str__(self) -> str:
        return f"{self.path!r}: {self.reason}"


class Confinement:
    """Resolves paths under ``root`` and refuses those that would leave it.

    Args:
        root: the directory the service may use (created if missing; symbolic links in it are
            resolved once, here).
        base: the directory relative paths are resolved against (default: ``root``); it must lie
            inside ``root`` (created if missing). A conformance run confines a service to ``/tmp``
            while its relative paths still name files in the run's folder.
        board: the root stands in for the board's ``/``: absolute paths are taken inside it (``base``
            must then be the root itself).
    """

    def __init__(self, root: str | os.PathLike, base: str | os.PathLike | None = None, board: bool = False):
        os.makedirs(os.fspath(root), exist_ok=True)
        self.root = os.path.realpath(os.fspath(root))
        if base is None:
            self.base = self.root
        else:
            os.makedirs(os.fspath(base), exist_ok=True)
            self.base = os.path.realpath(os.fspath(base))
            if self.base != self.root and not self.base.startswith(self.root.rstrip(os.sep) + os.sep):
                raise ValueError(f"the base folder {self.base} is not inside the root {self.root}")
        if board and self.base != self.root:
            raise ValueError(f"a board root resolves relative paths against itself, not {self.base}")
        self.board = board

    def contents(self, path: str) -> str:
        """The real path of what ``path`` names, for reading or writing its contents (symbolic links
        followed all the way). Raises :class:`PathRefused`."""
        self._check_text(path)
        return self._inside(path, os.path.realpath(self._join(path)))

    def entry(self, path: str) -> str:
        """The path of the directory entry ``path`` names, for removing, renaming or creating it:
        the folder is resolved, the last name is not (a link is the link itself). Raises
        :class:`PathRefused`."""
        self._check_text(path)
        lexical = os.path.normpath(self._join(path))
        folder, name = os.path.split(lexical)
        real = os.path.join(os.path.realpath(folder), name)
        if real == self.root:
            raise PathRefused(path, "is the root itself")
        return self._inside(path, real)

    def _join(self, path: str) -> str:
        """``path`` joined to the base; on a board root an absolute path is taken inside the root."""
        if self.board and os.path.isabs(path):
            return os.path.join(self.root, path.lstrip(os.sep))
        return os.path.join(self.base, path)

    def _inside(self, path: str, real: str) -> str:
        if real != self.root and not real.startswith(self.root.rstrip(os.sep) + os.sep):
            raise PathRefused(path, "outside the root")
        return real

    @staticmethod
    def _check_text(path: str) -> None:
        if not isinstance(path, str):
            raise PathRefused(repr(path), "not a text path")
        if "\0" in path:
            raise ValueError(f"{path!r}: embedded null byte")  # as the OS calls would say
