"""Svc.FileManager: every command against a real (temporary) file system, F´'s events and counts.

Everything happens under pytest's ``tmp_path``. Permission tests need a non-root user and are
skipped as root; the same status mapping is also checked with an injected PermissionError.
"""

from __future__ import annotations

import errno
import json
import os
import pathlib
import stat
import struct
import zlib

import pytest

from fprime_lite.osal.atomic import is_temporary_name
from fprime_lite import CmdResponse, Severity
from fprime_lite.wire.packets import encode_event
from fprime_lite.svc import file_manager as fm_module
from fprime_lite.svc.file_manager import (
    SHELL_NOT_RUN,
    DirectoryStatus,
    FileManager,
    FileStatus,
    FileSystemStatus,
    StringFormatStatus,
    file_crc,
    wait_status,
)

BASE = 0x5000
AS_ROOT = hasattr(os, "geteuid") and os.geteuid() == 0
needs_non_root = pytest.mark.skipif(AS_ROOT, reason="permission checks do not apply to root")


def make(fprime_harness, root, **kwargs):
    return fprime_harness(FileManager(root=root, base_id=BASE, **kwargs))


def run(h, command, *args):
    """Forget the history, send ``command`` and handle it."""
    h.clear_history()
    h.send_command(command, *args)
    h.dispatch_all()


def event_names(h):
    return [e.name for e in h.events]


def assert_ok(h, command):
    h.assert_cmd_response_size(1)
    h.assert_cmd_response(0, command, CmdResponse.OK)


def assert_failed(h, command):
    h.assert_cmd_response_size(1)
    h.assert_cmd_response(0, command, CmdResponse.EXECUTION_ERROR)


def leftovers(directory):
    """Temporary files the component left behind."""
    return [p.name for p in pathlib.Path(directory).iterdir() if is_temporary_name(p.name)]


# --- the F´ declarations ---------------------------------------------------------------------------

def test_commands_events_and_channels_have_fprime_ids(fprime_harness, tmp_path):
    comp = FileManager(root=tmp_path)
    opcodes = {c.name: c.opcode for c in comp.spec.commands}
    assert opcodes == {"CreateDirectory": 0, "MoveFile": 1, "RemoveDirectory": 2, "RemoveFile": 3,
                       "ShellCommand": 4, "AppendFile": 5, "FileSize": 6, "ListDirectory": 7,
                       "CalculateCrc": 8}
    assert all(c.kind == "async" for c in comp.spec.commands)
    args = {c.name: [(n, t.name, t.size if t.kind == "string" else None) for n, t in c.args]
            for c in comp.spec.commands}
    assert args["RemoveFile"] == [("fileName", "string", 256), ("ignoreErrors", "bool", None)]
    assert args["ShellCommand"] == [("command", "string", 256), ("logFileName", "string", 256)]
    assert args["ListDirectory"] == [("dirName", "string", 200)]
    assert args["CalculateCrc"] == [("filename", "string", 200)]
    events = {e.name: (e.local_id, e.severity) for e in comp.spec.own_events}
    assert len(events) == 31  # F´'s 30 and PathRefused (0x40, not in F´)
    assert events["PathRefused"] == (0x40, Severity.WARNING_HI)
    assert events["DirectoryCreateError"] == (0x00, Severity.WARNING_HI)
    assert events["ShellCommandFailed"] == (0x04, Severity.WARNING_HI)
    assert events["ShellCommandSucceeded"] == (0x07, Severity.ACTIVITY_HI)
    assert events["ShellCommandStarted"] == (0x0D, Severity.ACTIVITY_HI)
    assert events["FileSizeStarted"] == (0x14, Severity.ACTIVITY_HI)
    assert events["DirectoryListingSubdir"] == (0x19, Severity.ACTIVITY_HI)
    assert events["CalculateCrcSucceeded"] == (0x1C, Severity.ACTIVITY_HI)
    assert events["FileNameFormatError"] == (0x1D, Severity.WARNING_HI)
    assert sorted(local_id for local_id, _ in events.values()) == list(range(0x1E)) + [0x40]
    assert {c.name: c.local_id for c in comp.spec.own_channels} == {"CommandsExecuted": 0, "Errors": 1}
    assert comp.name == "fileManager"


def test_ping_is_answered(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    h.invoke("pingIn", 0x1234)
    h.dispatch_all()
    h.assert_from_port("pingOut", 0, 0x1234)


# --- CreateDirectory -------------------------------------------------------------------------------

def test_create_directory_creates_it(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "CreateDirectory", "logs")
    assert (tmp_path / "logs").is_dir()
    assert event_names(h) == ["CreateDirectoryStarted", "CreateDirectorySucceeded"]
    h.assert_event("CreateDirectorySucceeded", 0, "logs")
    assert_ok(h, "CreateDirectory")
    h.assert_tlm("CommandsExecuted", 0, 1)
    assert h.tlm_named("Errors") == []


def test_create_existing_directory_is_already_exists(fprime_harness, tmp_path):
    (tmp_path / "logs").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "CreateDirectory", "logs")
    h.assert_event("DirectoryCreateError", 0, "logs", FileSystemStatus.ALREADY_EXISTS)
    assert_failed(h, "CreateDirectory")
    h.assert_tlm("Errors", 0, 1)
    assert h.tlm_named("CommandsExecuted") == []


def test_create_directory_without_parent_is_doesnt_exist(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "CreateDirectory", "a/b")
    h.assert_event("DirectoryCreateError", 0, "a/b", FileSystemStatus.DOESNT_EXIST)
    assert not (tmp_path / "a").exists()
    assert_failed(h, "CreateDirectory")


@needs_non_root
def test_create_directory_in_read_only_directory_is_no_permission(fprime_harness, tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        h = make(fprime_harness, tmp_path)
        run(h, "CreateDirectory", "ro/new")
        h.assert_event("DirectoryCreateError", 0, "ro/new", FileSystemStatus.NO_PERMISSION)
        assert_failed(h, "CreateDirectory")
    finally:
        ro.chmod(0o755)


def test_permission_error_maps_to_no_permission(fprime_harness, tmp_path, monkeypatch):
    """The mapping the permission tests check, with the error injected (also runs as root)."""
    def refuse(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(fm_module.os, "mkdir", refuse)
    h = make(fprime_harness, tmp_path)
    run(h, "CreateDirectory", "x")
    h.assert_event("DirectoryCreateError", 0, "x", FileSystemStatus.NO_PERMISSION)
    assert_failed(h, "CreateDirectory")


def test_unexpected_exception_is_other_error_and_a_reported_fault(fprime_harness, tmp_path, monkeypatch):
    """Not an OSError or ValueError (the file system's own answers): OTHER_ERROR, and the fault is
    reported (decision 0005: HandlerFault, HandlerFaults)."""
    def broken(*args, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(fm_module.os, "rmdir", broken)
    (tmp_path / "d").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveDirectory", "d")
    h.assert_event("DirectoryRemoveError", 0, "d", FileSystemStatus.OTHER_ERROR)
    assert_failed(h, "RemoveDirectory")
    assert h.component.handler_faults == 1
    assert h.events_named("HandlerFault") == [("RemoveDirectory", "RuntimeError: boom")]
    assert h.tlm_values("HandlerFaults") == [1]


# --- MoveFile --------------------------------------------------------------------------------------

def test_move_file_to_another_directory(fprime_harness, tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    (tmp_path / "a" / "f.bin").write_bytes(b"payload")
    h = make(fprime_harness, tmp_path)
    run(h, "MoveFile", "a/f.bin", "b/g.bin")
    assert not (tmp_path / "a" / "f.bin").exists()
    assert (tmp_path / "b" / "g.bin").read_bytes() == b"payload"
    assert event_names(h) == ["MoveFileStarted", "MoveFileSucceeded"]
    h.assert_event("MoveFileSucceeded", 0, "a/f.bin", "b/g.bin")
    assert_ok(h, "MoveFile")
    h.assert_tlm("CommandsExecuted", 0, 1)


def test_move_file_replaces_existing_destination_when_overwrite_is_on(fprime_harness, tmp_path):
    (tmp_path / "new").write_bytes(b"new")
    (tmp_path / "old").write_bytes(b"old")
    h = make(fprime_harness, tmp_path, overwrite=True)
    run(h, "MoveFile", "new", "old")
    assert (tmp_path / "old").read_bytes() == b"new" and not (tmp_path / "new").exists()
    assert_ok(h, "MoveFile")


def test_move_file_onto_an_existing_file_is_refused_by_default(fprime_harness, tmp_path):
    """FS-ROOT-7: overwriting is an explicit choice: MoveFile onto an existing file answers
    ALREADY_EXISTS (1) and changes neither file."""
    (tmp_path / "new").write_bytes(b"new")
    (tmp_path / "old").write_bytes(b"old")
    h = make(fprime_harness, tmp_path)
    run(h, "MoveFile", "new", "old")
    h.assert_event("FileMoveError", 0, "new", "old", FileSystemStatus.ALREADY_EXISTS)
    assert (tmp_path / "old").read_bytes() == b"old" and (tmp_path / "new").read_bytes() == b"new"
    assert_failed(h, "MoveFile")


def test_move_missing_file_is_doesnt_exist(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "MoveFile", "nothing", "there")
    h.assert_event("FileMoveError", 0, "nothing", "there", FileSystemStatus.DOESNT_EXIST)
    assert not (tmp_path / "there").exists()
    assert_failed(h, "MoveFile")
    h.assert_tlm("Errors", 0, 1)


def _cross_device(monkeypatch):
    """os.replace fails with EXDEV except for the component's own temporary files."""
    real_replace = os.replace

    def replace(src, dst):
        if not is_temporary_name(os.path.basename(src)):
            raise OSError(errno.EXDEV, "Invalid cross-device link")
        real_replace(src, dst)

    monkeypatch.setattr(fm_module.os, "replace", replace)


def test_move_file_across_file_systems_copies_then_removes(fprime_harness, tmp_path, monkeypatch):
    (tmp_path / "src").mkdir()
    (tmp_path / "dst").mkdir()
    source = tmp_path / "src" / "data.bin"
    source.write_bytes(bytes(range(256)) * 1000)
    source.chmod(0o640)
    (tmp_path / "dst" / "data.bin").write_bytes(b"stale")
    _cross_device(monkeypatch)
    h = make(fprime_harness, tmp_path, overwrite=True)
    run(h, "MoveFile", "src/data.bin", "dst/data.bin")
    assert not source.exists()
    moved = tmp_path / "dst" / "data.bin"
    assert moved.read_bytes() == bytes(range(256)) * 1000
    assert stat.S_IMODE(moved.stat().st_mode) == 0o640
    assert leftovers(tmp_path / "dst") == []
    assert_ok(h, "MoveFile")


def test_move_directory_across_file_systems_is_exdev_error(fprime_harness, tmp_path, monkeypatch):
    (tmp_path / "d").mkdir()
    (tmp_path / "d" / "f").write_bytes(b"x")
    _cross_device(monkeypatch)
    h = make(fprime_harness, tmp_path)
    run(h, "MoveFile", "d", "e")
    h.assert_event("FileMoveError", 0, "d", "e", FileSystemStatus.EXDEV_ERROR)
    assert (tmp_path / "d" / "f").read_bytes() == b"x" and not (tmp_path / "e").exists()
    assert_failed(h, "MoveFile")


# --- RemoveDirectory -------------------------------------------------------------------------------

def test_remove_empty_directory(fprime_harness, tmp_path):
    (tmp_path / "empty").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveDirectory", "empty")
    assert not (tmp_path / "empty").exists()
    assert event_names(h) == ["RemoveDirectoryStarted", "RemoveDirectorySucceeded"]
    assert_ok(h, "RemoveDirectory")


def test_remove_non_empty_directory_is_not_empty(fprime_harness, tmp_path):
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "keep.txt").write_text("keep")
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveDirectory", "full")
    h.assert_event("DirectoryRemoveError", 0, "full", FileSystemStatus.NOT_EMPTY)
    assert (tmp_path / "full" / "keep.txt").read_text() == "keep"
    assert_failed(h, "RemoveDirectory")


@pytest.mark.parametrize("setup, status", [
    (lambda p: None, FileSystemStatus.DOESNT_EXIST),
    (lambda p: (p / "target").write_text("file"), FileSystemStatus.NOT_DIR),
])
def test_remove_directory_errors(fprime_harness, tmp_path, setup, status):
    setup(tmp_path)
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveDirectory", "target")
    h.assert_event("DirectoryRemoveError", 0, "target", status)
    assert_failed(h, "RemoveDirectory")


# --- RemoveFile ------------------------------------------------------------------------------------

def test_remove_file(fprime_harness, tmp_path):
    (tmp_path / "f").write_text("x")
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveFile", "f", False)
    assert not (tmp_path / "f").exists()
    assert event_names(h) == ["RemoveFileStarted", "RemoveFileSucceeded"]
    assert_ok(h, "RemoveFile")
    h.assert_tlm("CommandsExecuted", 0, 1)


def test_remove_missing_file_fails(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveFile", "ghost", False)
    h.assert_event("FileRemoveError", 0, "ghost", FileSystemStatus.DOESNT_EXIST)
    assert_failed(h, "RemoveFile")
    h.assert_tlm("Errors", 0, 1)


def test_remove_missing_file_with_ignore_errors_answers_ok_but_counts_an_error(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveFile", "ghost", True)
    h.assert_event("FileRemoveError", 0, "ghost", FileSystemStatus.DOESNT_EXIST)
    h.assert_no_event("RemoveFileSucceeded")
    assert_ok(h, "RemoveFile")
    h.assert_tlm("Errors", 0, 1)
    assert h.tlm_named("CommandsExecuted") == []


def test_remove_file_on_a_directory_is_is_dir(fprime_harness, tmp_path):
    (tmp_path / "d").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveFile", "d", False)
    h.assert_event("FileRemoveError", 0, "d", FileSystemStatus.IS_DIR)
    assert (tmp_path / "d").is_dir()
    assert_failed(h, "RemoveFile")


@needs_non_root
def test_remove_file_in_read_only_directory_is_no_permission(fprime_harness, tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    (ro / "f").write_text("x")
    ro.chmod(0o555)
    try:
        h = make(fprime_harness, tmp_path)
        run(h, "RemoveFile", "ro/f", False)
        h.assert_event("FileRemoveError", 0, "ro/f", FileSystemStatus.NO_PERMISSION)
        assert (ro / "f").exists()
        assert_failed(h, "RemoveFile")
    finally:
        ro.chmod(0o755)


# --- AppendFile ------------------------------------------------------------------------------------

def test_append_file_appends_source_to_target(fprime_harness, tmp_path):
    (tmp_path / "part2").write_bytes(b"world")
    (tmp_path / "log").write_bytes(b"hello ")
    (tmp_path / "log").chmod(0o640)
    h = make(fprime_harness, tmp_path)
    run(h, "AppendFile", "part2", "log")
    assert (tmp_path / "log").read_bytes() == b"hello world"
    assert (tmp_path / "part2").read_bytes() == b"world"
    assert stat.S_IMODE((tmp_path / "log").stat().st_mode) == 0o640
    assert event_names(h) == ["AppendFileStarted", "AppendFileSucceeded"]
    h.assert_event("AppendFileSucceeded", 0, "part2", "log")
    assert leftovers(tmp_path) == []
    assert_ok(h, "AppendFile")
    h.assert_tlm("CommandsExecuted", 0, 1)


def test_append_file_creates_missing_target(fprime_harness, tmp_path):
    (tmp_path / "src").write_bytes(b"abc")
    h = make(fprime_harness, tmp_path)
    run(h, "AppendFile", "src", "new")
    assert (tmp_path / "new").read_bytes() == b"abc"
    assert_ok(h, "AppendFile")


def test_append_file_through_a_symlink_appends_to_the_linked_file(fprime_harness, tmp_path):
    (tmp_path / "real").write_bytes(b"1")
    (tmp_path / "link").symlink_to(tmp_path / "real")
    (tmp_path / "src").write_bytes(b"2")
    h = make(fprime_harness, tmp_path)
    run(h, "AppendFile", "src", "link")
    assert (tmp_path / "real").read_bytes() == b"12" and (tmp_path / "link").is_symlink()
    assert_ok(h, "AppendFile")


def test_append_missing_source_leaves_target_unchanged(fprime_harness, tmp_path):
    (tmp_path / "log").write_bytes(b"keep")
    h = make(fprime_harness, tmp_path)
    run(h, "AppendFile", "missing", "log")
    h.assert_event("AppendFileFailed", 0, "missing", "log", FileSystemStatus.DOESNT_EXIST)
    assert (tmp_path / "log").read_bytes() == b"keep"
    assert_failed(h, "AppendFile")
    h.assert_tlm("Errors", 0, 1)


def test_append_failing_while_writing_leaves_target_unchanged(fprime_harness, tmp_path, monkeypatch):
    """The disk fills up while the appended copy is written: the target is not touched."""
    (tmp_path / "src").write_bytes(b"x" * 200_000)
    (tmp_path / "log").write_bytes(b"original")

    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(fm_module.os, "fsync", full)
    h = make(fprime_harness, tmp_path)
    run(h, "AppendFile", "src", "log")
    h.assert_event("AppendFileFailed", 0, "src", "log", FileSystemStatus.NO_SPACE)
    assert (tmp_path / "log").read_bytes() == b"original"
    assert leftovers(tmp_path) == []
    assert_failed(h, "AppendFile")


def test_append_onto_a_directory_is_is_dir(fprime_harness, tmp_path):
    (tmp_path / "src").write_bytes(b"x")
    (tmp_path / "d").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "AppendFile", "src", "d")
    h.assert_event("AppendFileFailed", 0, "src", "d", FileSystemStatus.IS_DIR)
    assert list((tmp_path / "d").iterdir()) == []
    assert_failed(h, "AppendFile")


@needs_non_root
def test_append_into_read_only_directory_leaves_target_unchanged(fprime_harness, tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    (ro / "log").write_bytes(b"keep")
    (tmp_path / "src").write_bytes(b"more")
    ro.chmod(0o555)
    try:
        h = make(fprime_harness, tmp_path)
        run(h, "AppendFile", "src", "ro/log")
        h.assert_event("AppendFileFailed", 0, "src", "ro/log", FileSystemStatus.NO_PERMISSION)
        assert (ro / "log").read_bytes() == b"keep"
        assert_failed(h, "AppendFile")
    finally:
        ro.chmod(0o755)


# --- FileSize --------------------------------------------------------------------------------------

def test_file_size_reports_the_size(fprime_harness, tmp_path):
    (tmp_path / "f").write_bytes(b"\0" * 12345)
    h = make(fprime_harness, tmp_path)
    run(h, "FileSize", "f")
    assert event_names(h) == ["FileSizeStarted", "FileSizeSucceeded"]
    h.assert_event("FileSizeSucceeded", 0, "f", 12345)
    assert h.text_events[-1].text == "(fileManager) FileSizeSucceeded: The size of file f is 12345 B"
    assert_ok(h, "FileSize")
    h.assert_tlm("CommandsExecuted", 0, 1)


@pytest.mark.parametrize("setup, status", [
    (lambda p: None, FileSystemStatus.DOESNT_EXIST),
    (lambda p: (p / "f").mkdir(), FileSystemStatus.IS_DIR),
])
def test_file_size_errors(fprime_harness, tmp_path, setup, status):
    setup(tmp_path)
    h = make(fprime_harness, tmp_path)
    run(h, "FileSize", "f")
    h.assert_event("FileSizeError", 0, "f", status)
    assert_failed(h, "FileSize")
    h.assert_tlm("Errors", 0, 1)


@needs_non_root
def test_file_size_of_unreadable_file_is_no_permission(fprime_harness, tmp_path):
    (tmp_path / "secret").write_bytes(b"x")
    (tmp_path / "secret").chmod(0o000)
    h = make(fprime_harness, tmp_path)
    run(h, "FileSize", "secret")
    h.assert_event("FileSizeError", 0, "secret", FileSystemStatus.NO_PERMISSION)
    assert_failed(h, "FileSize")


# --- ListDirectory ---------------------------------------------------------------------------------

def tick(h, n=1):
    for _ in range(n):
        h.invoke("schedIn", 0)
        h.dispatch_all()


def test_list_directory_reports_one_entry_per_tick_then_answers(fprime_harness, tmp_path):
    d = tmp_path / "data"
    d.mkdir()
    (d / "a.bin").write_bytes(b"abc")
    (d / "b.txt").write_bytes(b"")
    (d / "sub").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "ListDirectory", "data")
    assert event_names(h) == ["ListDirectoryStarted"]
    h.assert_cmd_response_size(0)
    tick(h)
    assert event_names(h) == ["ListDirectoryStarted", "DirectoryListing"]
    tick(h, 2)
    h.assert_cmd_response_size(0)
    tick(h)
    assert event_names(h) == ["ListDirectoryStarted", "DirectoryListing", "DirectoryListing",
                              "DirectoryListingSubdir", "ListDirectorySucceeded"]
    h.assert_event("DirectoryListing", 0, "data", "a.bin", 3)
    h.assert_event("DirectoryListing", 1, "data", "b.txt", 0)
    h.assert_event("DirectoryListingSubdir", 0, "data", "sub")
    h.assert_event("ListDirectorySucceeded", 0, "data", 3)
    assert_ok(h, "ListDirectory")
    h.assert_tlm("CommandsExecuted", 0, 1)
    assert not h.component.listing_in_progress
    tick(h)  # idle ticks do nothing
    h.assert_events_size(5)


def test_list_directory_files_per_tick(fprime_harness, tmp_path):
    for i in range(5):
        (tmp_path / f"f{i}").write_bytes(b"x" * i)
    h = make(fprime_harness, tmp_path, files_per_tick=3)
    run(h, "ListDirectory", ".")
    tick(h)
    h.assert_event_count("DirectoryListing", 3)
    tick(h)
    h.assert_event_count("DirectoryListing", 5)
    h.assert_event("ListDirectorySucceeded", 0, ".", 5)
    assert_ok(h, "ListDirectory")


def test_list_empty_directory(fprime_harness, tmp_path):
    (tmp_path / "e").mkdir()
    h = make(fprime_harness, tmp_path)
    run(h, "ListDirectory", "e")
    tick(h)
    h.assert_event("ListDirectorySucceeded", 0, "e", 0)
    assert_ok(h, "ListDirectory")


@pytest.mark.parametrize("setup, status", [
    (lambda p: None, DirectoryStatus.DOESNT_EXIST),
    (lambda p: (p / "x").write_text("file"), DirectoryStatus.NOT_DIR),
])
def test_list_directory_errors(fprime_harness, tmp_path, setup, status):
    setup(tmp_path)
    h = make(fprime_harness, tmp_path)
    run(h, "ListDirectory", "x")
    h.assert_event("ListDirectoryError", 0, "x", status)
    assert_failed(h, "ListDirectory")
    h.assert_tlm("Errors", 0, 1)
    assert not h.component.listing_in_progress


def test_second_list_directory_while_listing_is_refused(fprime_harness, tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "f").write_bytes(b"1")
    h = make(fprime_harness, tmp_path)
    h.send_command("ListDirectory", "a", cmd_seq=1)
    h.send_command("ListDirectory", ".", cmd_seq=2)
    h.dispatch_all()
    h.assert_event("ListDirectoryError", 0, ".", DirectoryStatus.OTHER_ERROR)
    h.assert_cmd_response(0, "ListDirectory", CmdResponse.EXECUTION_ERROR, cmd_seq=2)
    tick(h, 2)
    h.assert_event("ListDirectorySucceeded", 0, "a", 1)
    h.assert_cmd_response(1, "ListDirectory", CmdResponse.OK, cmd_seq=1)


def test_sched_in_queues_at_most_one_step(fprime_harness, tmp_path):
    (tmp_path / "f").write_bytes(b"")
    h = make(fprime_harness, tmp_path)
    h.invoke("schedIn", 0)
    assert len(h.component.queue) == 0  # nothing to list: nothing queued
    run(h, "ListDirectory", ".")
    for _ in range(3):
        h.invoke("schedIn", 0)
    assert len(h.component.queue) == 1
    h.dispatch_all()
    h.assert_event_count("DirectoryListing", 1)


def test_list_directory_name_that_is_not_utf8_is_file_name_format_error(fprime_harness, tmp_path):
    d = tmp_path / "d"
    d.mkdir()
    try:
        fd = os.open(os.fsencode(str(d)) + b"/bad\xff", os.O_CREAT | os.O_WRONLY, 0o644)
    except OSError:
        pytest.skip("this file system refuses names that are not UTF-8")
    os.close(fd)
    h = make(fprime_harness, tmp_path)
    run(h, "ListDirectory", "d")
    tick(h, 2)
    h.assert_event("FileNameFormatError", 0, "bad\ufffd", StringFormatStatus.OTHER_ERROR)
    h.assert_event("ListDirectorySucceeded", 0, "d", 1)
    assert_ok(h, "ListDirectory")


# --- CalculateCrc ----------------------------------------------------------------------------------

def test_calculate_crc_reports_fprime_file_crc(fprime_harness, tmp_path):
    data = bytes(range(256)) * 700
    (tmp_path / "img.bin").write_bytes(data)
    h = make(fprime_harness, tmp_path)
    run(h, "CalculateCrc", "img.bin")
    expected = zlib.crc32(data) ^ 0xFFFFFFFF
    assert file_crc(tmp_path / "img.bin") == expected
    assert event_names(h) == ["CalculateCrcStarted", "CalculateCrcSucceeded"]
    h.assert_event("CalculateCrcSucceeded", 0, "img.bin", expected)
    assert h.text_events[-1].text.endswith(f"img.bin has CRC value 0x{expected:x}")
    assert_ok(h, "CalculateCrc")
    assert h.telemetry == []  # as F´: CalculateCrc counts nothing


@pytest.mark.parametrize("setup, status", [
    (lambda p: None, FileStatus.DOESNT_EXIST),
    (lambda p: (p / "f").mkdir(), FileStatus.OTHER_ERROR),
])
def test_calculate_crc_errors(fprime_harness, tmp_path, setup, status):
    setup(tmp_path)
    h = make(fprime_harness, tmp_path)
    run(h, "CalculateCrc", "f")
    h.assert_event("CalculateCrcFailed", 0, "f", status)
    assert_failed(h, "CalculateCrc")
    assert h.telemetry == []


# --- ShellCommand ----------------------------------------------------------------------------------

def test_shell_command_is_refused_by_default(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "ShellCommand", "touch ran", "out.log")
    assert not (tmp_path / "ran").exists() and not (tmp_path / "out.log").exists()
    assert event_names(h) == ["ShellCommandFailed"]
    text, status = h.events_named("ShellCommandFailed")[0]
    assert text.startswith("touch ran [refused:") and "disabled in this deployment" in text
    assert status == SHELL_NOT_RUN
    assert_failed(h, "ShellCommand")
    h.assert_tlm("Errors", 0, 1)


def test_shell_command_runs_when_allowed_and_appends_its_output(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path, allow_shell=True)
    run(h, "ShellCommand", "echo hi", "out.log")
    assert event_names(h) == ["ShellCommandStarted", "ShellCommandSucceeded"]
    h.assert_event("ShellCommandSucceeded", 0, "echo hi")
    assert_ok(h, "ShellCommand")
    h.assert_tlm("CommandsExecuted", 0, 1)
    run(h, "ShellCommand", "echo 'it''s' 1>&2; pwd", "out.log")
    assert (tmp_path / "out.log").read_text() == f"hi\nits\n{tmp_path}\n"
    assert_ok(h, "ShellCommand")


def test_shell_command_non_zero_exit_is_reported_as_wait_status(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path, allow_shell=True)
    run(h, "ShellCommand", "exit 3", "out.log")
    h.assert_event("ShellCommandFailed", 0, "exit 3", 3 << 8)
    assert_failed(h, "ShellCommand")
    h.assert_tlm("Errors", 0, 1)
    assert wait_status(3) == 768 and wait_status(-9) == 9


def test_shell_command_past_its_timeout_is_killed(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path, allow_shell=True, shell_timeout_s=0.2)
    run(h, "ShellCommand", "sleep 10; touch late", "out.log")
    h.assert_event("ShellCommandFailed", 0, "sleep 10; touch late", 9)  # killed by SIGKILL
    assert not (tmp_path / "late").exists()
    assert_failed(h, "ShellCommand")


def test_shell_command_with_unopenable_log_file_does_not_run(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path, allow_shell=True)
    run(h, "ShellCommand", "touch ran", "no/such/dir/out.log")
    h.assert_event("ShellCommandFailed", 0, "touch ran", SHELL_NOT_RUN)
    assert not (tmp_path / "ran").exists()
    assert_failed(h, "ShellCommand")


# --- paths, counts, robustness ---------------------------------------------------------------------

def test_relative_paths_resolve_under_root_and_absolute_ones_inside_root(fprime_harness, tmp_path, monkeypatch):
    root = tmp_path / "root"
    root.mkdir()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    h = make(fprime_harness, root)
    run(h, "CreateDirectory", "sub")
    assert (root / "sub").is_dir() and not (elsewhere / "sub").exists()
    run(h, "CreateDirectory", str(root / "abs"))
    assert (root / "abs").is_dir()
    h.assert_event("CreateDirectorySucceeded", 0, str(root / "abs"))


@pytest.mark.parametrize("command, args, error, outside_check", [
    ("RemoveFile", ["../victim.txt", False], "FileRemoveError", lambda t: (t / "victim.txt").exists()),
    ("RemoveFile", ["ABS/victim.txt", False], "FileRemoveError", lambda t: (t / "victim.txt").exists()),
    ("RemoveFile", ["LINK/victim.txt", False], "FileRemoveError", lambda t: (t / "victim.txt").exists()),
    ("CreateDirectory", ["../made"], "DirectoryCreateError", lambda t: not (t / "made").exists()),
    ("MoveFile", ["inside.txt", "../moved.txt"], "FileMoveError", lambda t: not (t / "moved.txt").exists()),
    ("MoveFile", ["LINK/victim.txt", "stolen.txt"], "FileMoveError", lambda t: (t / "victim.txt").exists()),
    ("AppendFile", ["inside.txt", "LINK/victim.txt"], "AppendFileFailed",
     lambda t: (t / "victim.txt").read_bytes() == b"victim"),
    ("FileSize", ["/etc/passwd"], "FileSizeError", lambda t: True),
    ("RemoveDirectory", ["LINK/keep"], "DirectoryRemoveError", lambda t: (t / "keep").is_dir()),
])
def test_paths_outside_root_are_refused(fprime_harness, tmp_path, command, args, error, outside_check):
    """FS-ROOT-8 (issue #16 finding 6): ``..``, absolute paths outside root and symbolic-link escapes are
    refused: PathRefused, the command's error event with NO_PERMISSION (3), EXECUTION_ERROR, and the
    file outside root is untouched."""
    root = tmp_path / "root"
    root.mkdir()
    (tmp_path / "victim.txt").write_bytes(b"victim")
    (tmp_path / "keep").mkdir()
    (root / "inside.txt").write_bytes(b"inside")
    (root / "LINK").symlink_to(tmp_path, target_is_directory=True)
    args = [a.replace("ABS", str(tmp_path)) if isinstance(a, str) else a for a in args]
    h = make(fprime_harness, root)
    run(h, command, *args)
    assert h.events_named("PathRefused")
    assert h.events_named(error)[0][-1] == 3  # NO_PERMISSION
    assert_failed(h, command)
    assert outside_check(tmp_path)


def test_removing_a_link_inside_root_removes_the_link_only(fprime_harness, tmp_path):
    """FS-ROOT-9: RemoveFile of a symbolic link inside root that points outside removes the link, never
    its target."""
    root = tmp_path / "root"
    root.mkdir()
    (tmp_path / "victim.txt").write_bytes(b"victim")
    (root / "link.txt").symlink_to(tmp_path / "victim.txt")
    h = make(fprime_harness, root)
    run(h, "RemoveFile", "link.txt", False)
    assert_ok(h, "RemoveFile")
    assert not (root / "link.txt").is_symlink() and (tmp_path / "victim.txt").read_bytes() == b"victim"


def test_default_root_is_the_current_directory_at_construction(fprime_harness, tmp_path, monkeypatch):
    (tmp_path / "first").mkdir()
    (tmp_path / "second").mkdir()
    monkeypatch.chdir(tmp_path / "first")
    h = fprime_harness(FileManager())
    monkeypatch.chdir(tmp_path / "second")
    (tmp_path / "first" / "f").write_bytes(b"12")
    run(h, "FileSize", "f")
    h.assert_event("FileSizeSucceeded", 0, "f", 2)


def test_empty_path_never_means_root(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "RemoveDirectory", "")
    h.assert_event("DirectoryRemoveError", 0, "", FileSystemStatus.DOESNT_EXIST)
    assert tmp_path.is_dir()
    assert_failed(h, "RemoveDirectory")


def test_path_with_nul_byte_is_invalid_path(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    run(h, "CreateDirectory", "a\0b")
    h.assert_event("DirectoryCreateError", 0, "a\0b", FileSystemStatus.INVALID_PATH)
    assert_failed(h, "CreateDirectory")


def test_path_longer_than_its_bound_is_a_format_error(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    opcode = h.component.opcode("FileSize")
    h.send_raw_command(opcode, struct.pack(">H", 257) + b"a" * 257)
    h.dispatch_all()
    h.assert_cmd_response(0, "FileSize", CmdResponse.FORMAT_ERROR)
    h.assert_events_size(0)


def test_commands_executed_and_errors_count_every_outcome(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    sequence = [("CreateDirectory", "d"), ("CreateDirectory", "d"), ("RemoveDirectory", "d"),
                ("RemoveFile", "none", True), ("FileSize", "none"), ("RemoveDirectory", "none")]
    for command, *args in sequence:
        h.send_command(command, *args)
    h.dispatch_all()
    assert h.tlm_values("CommandsExecuted") == [1, 2]
    assert h.tlm_values("Errors") == [1, 2, 3, 4]
    assert (h.component.commands_executed, h.component.errors) == (2, 4)
    assert [r.response for r in h.cmd_responses] == [
        CmdResponse.OK, CmdResponse.EXECUTION_ERROR, CmdResponse.OK, CmdResponse.OK,
        CmdResponse.EXECUTION_ERROR, CmdResponse.EXECUTION_ERROR]


def test_constructor_rejects_bad_settings(tmp_path):
    with pytest.raises(ValueError, match="shell_timeout_s"):
        FileManager(root=tmp_path, shell_timeout_s=0)
    with pytest.raises(ValueError, match="files_per_tick"):
        FileManager(root=tmp_path, files_per_tick=0)


# --- the ground system's view ----------------------------------------------------------------------

def test_fprime_gds_encodes_commands_and_decodes_events(fprime_harness, tmp_path):
    """fprime-gds 4.4.1 encodes FileManager commands from a dictionary of these declarations and
    decodes the events they cause (enum, bool, U64 and hex-formatted arguments included)."""
    pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency")
    from fprime_gds.common.data_types.cmd_data import CmdData
    from fprime_gds.common.decoders.event_decoder import EventDecoder
    from fprime_gds.common.encoders.cmd_encoder import CmdEncoder
    from fprime_gds.common.models.dictionaries import Dictionaries

    minimal = json.loads((pathlib.Path(__file__).parents[2] / "data" / "gds" / "minimal_dictionary.json")
                         .read_text())
    comp = FileManager(root=tmp_path, base_id=BASE)
    qualified = "FileHandling.fileManager"

    def params(args):
        return [{"name": n, "type": t.json_ref(), "ref": False} for n, t in args]

    types = {}
    for decl in [*comp.spec.commands, *comp.spec.events]:
        for _, t in decl.args:
            definition = t.json_definition()
            if definition is not None:
                types[definition["qualifiedName"]] = definition
    dictionary = {
        "metadata": {"deploymentName": "FmTest", "frameworkVersion": "4.2.0", "projectVersion": "0.1.0",
                     "libraryVersions": [], "dictionarySpecVersion": "1.0.0"},
        "typeDefinitions": [*minimal["typeDefinitions"], *types.values()],
        "constants": minimal["constants"],
        "commands": [{"name": f"{qualified}.{c.name}", "commandKind": c.kind, "opcode": BASE + c.opcode,
                      "formalParams": params(c.args)} for c in comp.spec.commands],
        "parameters": [],
        "events": [{"name": f"{qualified}.{e.name}", "severity": e.severity.name, "id": BASE + e.local_id,
                    "formalParams": params(e.args), "format": e.format} for e in comp.spec.events],
        "telemetryChannels": [{"name": f"{qualified}.{c.name}", "type": c.type.json_ref(),
                               "id": BASE + c.local_id, "telemetryUpdate": c.update}
                              for c in comp.spec.channels],
        "records": [], "containers": [], "telemetryPacketSets": [],
    }
    path = tmp_path / "dictionary.json"
    path.write_text(json.dumps(dictionary))
    gds = Dictionaries.load_dictionaries_into_config(str(path))

    h = fprime_harness(comp)
    packets = []
    comp.output_port("logOut").connect_callable(
        0, lambda i, t, s, args: packets.append(encode_event(i, t, args)[2:]), "downlink")

    def ground(name, *args):
        encoded = CmdEncoder().encode_api(CmdData(list(args), gds.command_name[f"{qualified}.{name}"]))
        opcode, = struct.unpack(">I", encoded[10:14])
        h.send_raw_command(opcode, encoded[14:])
        h.dispatch_all()

    (tmp_path / "f.bin").write_bytes(b"123456789")
    ground("FileSize", "f.bin")
    ground("CalculateCrc", "f.bin")
    ground("RemoveFile", "ghost", "True")
    ground("ShellCommand", "ls", "x.log")
    comp.FileNameFormatError("entry", StringFormatStatus.OVERFLOWED)
    decoded = [EventDecoder(gds.event_id).decode_api(p)[0] for p in packets]
    texts = [e.get_str().split(" : ", 1)[1] for e in decoded]
    crc = zlib.crc32(b"123456789") ^ 0xFFFFFFFF
    assert texts == [
        "Checking size of file f.bin...",
        "The size of file f.bin is 9 B",
        "Started CRC calculation for file f.bin",
        f"f.bin has CRC value 0x{crc:x}",
        "Removing file ghost...",
        "Could not remove file ghost, returned status 8",
        ("Shell command ls [refused: ShellCommand is disabled in this deployment] failed with status "
         f"{SHELL_NOT_RUN}"),
        "Failed to format full path for file entry with status OVERFLOWED",
    ]
    assert [r.response for r in h.cmd_responses] == [CmdResponse.OK, CmdResponse.OK, CmdResponse.OK,
                                                      CmdResponse.EXECUTION_ERROR]


def test_storage_rate_models_the_time_of_append_and_crc(fprime_harness, tmp_path):
    """Modelled storage: AppendFile counts the source's bytes twice (read, then written), CalculateCrc
    the file's once, at ``storage_bytes_per_s``; without a rate nothing is modelled; a bad rate is
    refused at construction."""
    (tmp_path / "src").write_bytes(b"x" * 3000)
    h = fprime_harness(FileManager("fileManager", root=tmp_path, storage_bytes_per_s=3_000_000))
    run(h, "AppendFile", "src", "dst")
    assert h.component.modelled_busy_us == 2_000  # 6,000 bytes at 3 MB/s
    h.component.modelled_busy_us = 0
    run(h, "CalculateCrc", "dst")
    assert h.component.modelled_busy_us == 1_000
    h.component.modelled_busy_us = 0
    run(h, "AppendFile", "missing", "dst")  # a failed append moves nothing
    assert h.component.modelled_busy_us == 0
    plain = make(fprime_harness, tmp_path)
    run(plain, "AppendFile", "src", "dst")
    assert plain.component.modelled_busy_us == 0
    for bad in (0, -1.0, True, "fast"):
        with pytest.raises(ValueError, match="storage_bytes_per_s"):
            FileManager("fileManager", root=tmp_path, storage_bytes_per_s=bad)
