"""F´'s ``Os`` status enums, declared once for every service: ``Os::FileSystem::Status``,
``Os::File::Status`` and ``Os::Directory::Status`` with the numbering of **F´ v4.2** (the release
every service of fprime_lite follows; ``docs/services.md``), and the mapping of OS errors onto them.

F´ v4.2's ``Os::File::Status`` has ``NO_MORE_RESOURCES`` (10) before ``OTHER_ERROR`` (11); F´ v4.0
ended at ``OTHER_ERROR`` = 10.
"""

from __future__ import annotations

import enum
import errno as _errno

__all__ = ["FileSystemStatus", "FileStatus", "DirectoryStatus", "filesystem_status", "file_status",
           "directory_status"]


class FileSystemStatus(enum.IntEnum):
    """F´ ``Os::FileSystem::Status`` (``Os.FileSystemStatus``): most commands' error status."""

    OP_OK = 0
    ALREADY_EXISTS = 1
    NO_SPACE = 2
    NO_PERMISSION = 3
    NOT_DIR = 4
    IS_DIR = 5
    NOT_EMPTY = 6
    INVALID_PATH = 7
    DOESNT_EXIST = 8
    FILE_LIMIT = 9
    BUSY = 10
    NO_MORE_FILES = 11
    BUFFER_TOO_SMALL = 12
    EXDEV_ERROR = 13
    OVERFLOW_ERROR = 14
    NOT_SUPPORTED = 15
    OTHER_ERROR = 16


class FileStatus(enum.IntEnum):
    """F´ ``Os::File::Status``: the status of ``CalculateCrcFailed``."""

    OP_OK = 0
    DOESNT_EXIST = 1
    NO_SPACE = 2
    NO_PERMISSION = 3
    BAD_SIZE = 4
    NOT_OPENED = 5
    FILE_EXISTS = 6
    NOT_SUPPORTED = 7
    INVALID_MODE = 8
    INVALID_ARGUMENT = 9
    NO_MORE_RESOURCES = 10
    OTHER_ERROR = 11


class DirectoryStatus(enum.IntEnum):
    """F´ ``Os::Directory::Status``: the status of ``ListDirectoryError``."""

    OP_OK = 0
    DOESNT_EXIST = 1
    NO_PERMISSION = 2
    NOT_OPENED = 3
    NOT_DIR = 4
    NO_MORE_FILES = 5
    FILE_LIMIT = 6
    BAD_DESCRIPTOR = 7
    ALREADY_EXISTS = 8
    NOT_SUPPORTED = 9
    OTHER_ERROR = 10


def _errno_of(exc: BaseException) -> int | None:
    return exc.errno if isinstance(exc, OSError) else None


_FS_BY_ERRNO: dict[int | None, FileSystemStatus] = {  # errno None (not an OSError): the default
    _errno.EEXIST: FileSystemStatus.ALREADY_EXISTS,
    _errno.ENOSPC: FileSystemStatus.NO_SPACE,
    _errno.EFBIG: FileSystemStatus.NO_SPACE,
    _errno.EDQUOT: FileSystemStatus.NO_SPACE,
    _errno.EACCES: FileSystemStatus.NO_PERMISSION,
    _errno.EPERM: FileSystemStatus.NO_PERMISSION,
    _errno.EROFS: FileSystemStatus.NO_PERMISSION,
    _errno.EFAULT: FileSystemStatus.NO_PERMISSION,
    _errno.ENOTDIR: FileSystemStatus.NOT_DIR,
    _errno.EISDIR: FileSystemStatus.IS_DIR,
    _errno.ENOTEMPTY: FileSystemStatus.NOT_EMPTY,
    _errno.ENAMETOOLONG: FileSystemStatus.INVALID_PATH,
    _errno.EINVAL: FileSystemStatus.INVALID_PATH,
    _errno.ENOENT: FileSystemStatus.DOESNT_EXIST,
    _errno.ELOOP: FileSystemStatus.DOESNT_EXIST,
    _errno.EMLINK: FileSystemStatus.FILE_LIMIT,
    _errno.EMFILE: FileSystemStatus.FILE_LIMIT,
    _errno.ENFILE: FileSystemStatus.FILE_LIMIT,
    _errno.EBUSY: FileSystemStatus.BUSY,
    _errno.ETXTBSY: FileSystemStatus.BUSY,
    _errno.ERANGE: FileSystemStatus.BUFFER_TOO_SMALL,
    _errno.EXDEV: FileSystemStatus.EXDEV_ERROR,
    _errno.EOVERFLOW: FileSystemStatus.OVERFLOW_ERROR,
    _errno.ENOSYS: FileSystemStatus.NOT_SUPPORTED,
    _errno.EOPNOTSUPP: FileSystemStatus.NOT_SUPPORTED,
    _errno.ENOTSUP: FileSystemStatus.NOT_SUPPORTED,
}

_FILE_BY_ERRNO: dict[int | None, FileStatus] = {
    _errno.ENOENT: FileStatus.DOESNT_EXIST,
    _errno.ENOSPC: FileStatus.NO_SPACE,
    _errno.EFBIG: FileStatus.NO_SPACE,
    _errno.EACCES: FileStatus.NO_PERMISSION,
    _errno.EPERM: FileStatus.NO_PERMISSION,
    _errno.EEXIST: FileStatus.FILE_EXISTS,
    _errno.EBADF: FileStatus.NOT_OPENED,
    _errno.ENOSYS: FileStatus.NOT_SUPPORTED,
    _errno.EOPNOTSUPP: FileStatus.NOT_SUPPORTED,
    _errno.ENOTSUP: FileStatus.NOT_SUPPORTED,
    _errno.EINVAL: FileStatus.INVALID_ARGUMENT,
    _errno.EMFILE: FileStatus.NO_MORE_RESOURCES,
    _errno.ENFILE: FileStatus.NO_MORE_RESOURCES,
}

_DIR_BY_ERRNO: dict[int | None, DirectoryStatus] = {
    _errno.ENOENT: DirectoryStatus.DOESNT_EXIST,
    _errno.EACCES: DirectoryStatus.NO_PERMISSION,
    _errno.EPERM: DirectoryStatus.NO_PERMISSION,
    _errno.ENOTDIR: DirectoryStatus.NOT_DIR,
    _errno.EEXIST: DirectoryStatus.ALREADY_EXISTS,
    _errno.EMFILE: DirectoryStatus.FILE_LIMIT,
    _errno.ENFILE: DirectoryStatus.FILE_LIMIT,
    _errno.EBADF: DirectoryStatus.BAD_DESCRIPTOR,
    _errno.ENOSYS: DirectoryStatus.NOT_SUPPORTED,
    _errno.EOPNOTSUPP: DirectoryStatus.NOT_SUPPORTED,
}


def filesystem_status(exc: BaseException) -> FileSystemStatus:
    """The F´ ``Os::FileSystem`` status for an exception of a file-system call."""
    if isinstance(exc, ValueError):  # a NUL byte in a path
        return FileSystemStatus.INVALID_PATH
    return _FS_BY_ERRNO.get(_errno_of(exc), FileSystemStatus.OTHER_ERROR)


def file_status(exc: BaseException) -> FileStatus:
    """The F´ ``Os::File`` status for an exception of opening or reading a file."""
    if isinstance(exc, ValueError):
        return FileStatus.INVALID_ARGUMENT
    return _FILE_BY_ERRNO.get(_errno_of(exc), FileStatus.OTHER_ERROR)


def directory_status(exc: BaseException) -> DirectoryStatus:
    """The F´ ``Os::Directory`` status for an exception of opening or reading a directory."""
    return _DIR_BY_ERRNO.get(_errno_of(exc), DirectoryStatus.OTHER_ERROR)
