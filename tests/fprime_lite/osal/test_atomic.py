"""Atomic file writes: old or new content, never a part; permissions kept."""

import os
import stat

import pytest

from fprime_lite.osal.atomic import atomic_write_bytes, atomic_write_json, atomic_write_text


def test_new_file_gets_the_umask_mode_and_the_content(tmp_path):
    path = tmp_path / "sub" / "out.json"
    umask = os.umask(0o022)
    try:
        atomic_write_text(path, "hello\n")
    finally:
        os.umask(umask)
    assert path.read_text() == "hello\n"
    assert stat.S_IMODE(path.stat().st_mode) == 0o644
    assert [p.name for p in path.parent.iterdir()] == ["out.json"]  # no temporary left behind


def test_existing_file_keeps_its_mode(tmp_path):
    path = tmp_path / "params.dat"
    path.write_bytes(b"old")
    path.chmod(0o600)
    atomic_write_bytes(path, b"new")
    assert path.read_bytes() == b"new"
    assert stat.S_IMODE(path.stat().st_mode) == 0o600


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    path = tmp_path / "keep.txt"
    path.write_text("old")

    def broken_replace(src, dst):
        raise OSError("disk on fire")

    monkeypatch.setattr(os, "replace", broken_replace)
    with pytest.raises(OSError, match="disk on fire"):
        atomic_write_text(path, "new")
    monkeypatch.undo()
    assert path.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_json_goes_into_a_new_folder_indented_with_a_final_newline(tmp_path):
    """atomic_write_json (the study scripts' --json files): the folder is made, the text is the object indented by one
    space and ends with a newline, and it reads back as the same object."""
    import json

    target = tmp_path / "new" / "table.json"
    atomic_write_json(target, {"rows": [1.5, None]})
    assert target.read_text(encoding="utf-8") == '{\n "rows": [\n  1.5,\n  null\n ]\n}\n'
    assert json.loads(target.read_text(encoding="utf-8")) == {"rows": [1.5, None]}
