"""F´'s Os status enums, declared once (issue #11 item 3): every service uses the v4.2 numbering."""

import errno

from fprime_lite.osal import os_status
from fprime_lite.osal.confine import PathRefused
from fprime_lite.svc import file_downlink, file_manager


def test_every_service_uses_the_one_declaration():
    """OS-STATUS-1: FileDownlink's and FileManager's Os::File::Status are the osal declaration."""
    assert file_downlink.OsFileStatus is os_status.FileStatus
    assert file_manager.FileStatus is os_status.FileStatus
    assert file_manager.FileSystemStatus is os_status.FileSystemStatus
    assert file_manager.DirectoryStatus is os_status.DirectoryStatus


def test_file_status_has_the_v4_2_numbering():
    """OS-STATUS-2: F´ v4.2's Os::File::Status: NO_MORE_RESOURCES 10 before OTHER_ERROR 11."""
    assert [(m.name, m.value) for m in os_status.FileStatus] == [
        ("OP_OK", 0), ("DOESNT_EXIST", 1), ("NO_SPACE", 2), ("NO_PERMISSION", 3), ("BAD_SIZE", 4),
        ("NOT_OPENED", 5), ("FILE_EXISTS", 6), ("NOT_SUPPORTED", 7), ("INVALID_MODE", 8),
        ("INVALID_ARGUMENT", 9), ("NO_MORE_RESOURCES", 10), ("OTHER_ERROR", 11)]


def test_a_refused_path_maps_to_no_permission_in_every_layer():
    """OS-STATUS-3: PathRefused is a PermissionError (EACCES): NO_PERMISSION in File, FileSystem and
    Directory statuses."""
    refused = PathRefused("../x", "outside the root")
    assert refused.errno == errno.EACCES
    assert os_status.file_status(refused) == os_status.FileStatus.NO_PERMISSION
    assert os_status.filesystem_status(refused) == os_status.FileSystemStatus.NO_PERMISSION
    assert os_status.directory_status(refused) == os_status.DirectoryStatus.NO_PERMISSION
