"""PrmDb: get/set, the parameter file (with and without CRC), atomic save, staged load.

The compatibility tests run the real ``fprime-prm-write`` / ``fprime-prm-decode`` of fprime-gds
4.4.1 (installed with the test extras) as subprocesses.
"""

import json
import os
import pathlib
import shutil
import struct
import subprocess
import sys
import zlib

import pytest

from fprime_lite import CmdResponse, ParamValid, Severity
from fprime_lite.svc.prm_db import (ENTRY_DELIMITER, Merge, ParamFileCrcError, ParamFileError, PrmDb,
                                    PrmDbFileLoadState, PrmLoadAction, PrmReadError, PrmWriteError,
                                    decode_param_file, encode_param_file, param_file_crc)

DATA = pathlib.Path(__file__).parents[2] / "data"
GDS = DATA / "gds"
SVC_DICT = DATA / "svc" / "svc_dictionary.json"
GAINS = struct.pack(">ff", 1.5, 0.25) + struct.pack(">i", 1) + b"\x00\x02hi"
THRESHOLD = struct.pack(">I", 42)


def tool(name):
    path = pathlib.Path(sys.executable).parent / name
    found = str(path) if path.exists() else shutil.which(name)
    if found is None:
        pytest.skip(f"{name} (fprime-gds 4.4.1) is not installed; pip install -e .[test]")
    return found


def run_tool(name, *args, cwd):
    result = subprocess.run([tool(name), *map(str, args)], cwd=cwd, capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    return result


def make(fprime_harness, path, **kwargs):
    h = fprime_harness(PrmDb("prmDb", path, base_id=0x300, **kwargs))
    return h


def record(prm_id, value):
    return bytes([ENTRY_DELIMITER]) + struct.pack(">II", 4 + len(value), prm_id) + value


# --- the file format -------------------------------------------------------------------------------

def test_encode_matches_prm_write_reference_file():
    """The reference file written by fprime-prm-write: ~crc32 header, then the records."""
    reference = (GDS / "params.dat").read_bytes()
    assert encode_param_file([(0x1000, GAINS), (0x1001, THRESHOLD)]) == reference
    assert struct.unpack(">I", reference[:4])[0] == zlib.crc32(reference[4:]) ^ 0xFFFFFFFF
    decoded = decode_param_file(reference)
    assert decoded.has_crc and decoded.records == [(0x1000, GAINS), (0x1001, THRESHOLD)]


def test_decode_file_without_crc():
    """Older F´ files have no CRC: records start at byte 0."""
    data = record(5, b"\x01") + record(6, b"")
    decoded = decode_param_file(data)
    assert not decoded.has_crc and decoded.records == [(5, b"\x01"), (6, b"")]


def test_crc_starting_with_delimiter_byte_is_recognised():
    """A CRC whose first byte is 0xA5 must not be mistaken for a CRC-less record."""
    for i in range(5000):
        body = record(i, b"x")
        if param_file_crc(body) >> 24 == ENTRY_DELIMITER:
            break
    else:
        pytest.fail("no CRC starting with 0xA5 found")
    data = encode_param_file([(i, b"x")])
    assert data[0] == ENTRY_DELIMITER
    assert decode_param_file(data).records == [(i, b"x")] and decode_param_file(data).has_crc


@pytest.mark.parametrize("mutate, stage, offset", [
    (lambda d: d[:-1], PrmReadError.PARAMETER_VALUE_SIZE, 0x26),    # truncated value
    (lambda d: d[:0x1d + 3], PrmReadError.RECORD_SIZE_SIZE, 0x1e),  # truncated inside a size
    (lambda d: d[:0x1d + 7], PrmReadError.PARAMETER_ID_SIZE, 0x22),  # truncated inside an id
    (lambda d: d[:0x1d] + b"\x00" + d[0x1e:], PrmReadError.DELIMITER_VALUE, 0x1d),  # bad delimiter
    (lambda d: d[:0x1e] + b"\x00\x00\x00\x02" + d[0x22:], PrmReadError.RECORD_SIZE_VALUE, 0x1e),
    (lambda d: d[:2], PrmReadError.CRC_SIZE, 2),
    (lambda d: b"", PrmReadError.CRC_SIZE, 0),
])
def test_decode_errors_name_stage_and_offset(mutate, stage, offset):
    data = mutate((GDS / "params.dat").read_bytes())
    with pytest.raises(ParamFileError) as err:
        decode_param_file(data)
    assert (err.value.stage, err.value.offset) == (stage, offset)
    assert f"at byte {offset}" in str(err.value)


def test_decode_bad_crc():
    data = bytearray((GDS / "params.dat").read_bytes())
    data[0x10] ^= 0x01  # a value bit: the structure is fine, the CRC is not
    with pytest.raises(ParamFileCrcError, match=r"stored CRC 0x3B48DC79 differs"):
        decode_param_file(bytes(data))


# --- get / set -------------------------------------------------------------------------------------

def test_get_and_set(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path / "p.dat")
    assert h.invoke("getPrm", 0x1000) == (ParamValid.INVALID, None)
    h.assert_event("PrmIdNotFound", 0, 0x1000)
    h.invoke("setPrm", 0x1000, b"\x01")
    h.invoke("setPrm", 0x1000, b"\x02")
    h.assert_event("PrmIdAdded", 0, 0x1000)
    h.assert_event("PrmIdUpdated", 0, 0x1000)
    assert h.invoke("getPrm", 0x1000) == (ParamValid.VALID, b"\x02")
    assert h.component.dirty


def test_not_found_is_throttled(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path / "p.dat")
    for i in range(8):
        h.invoke("getPrm", i)
    h.assert_event_count("PrmIdNotFound", 5)


def test_database_full(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path / "p.dat", capacity=2)
    for i in range(3):
        h.invoke("setPrm", i, b"")
    h.assert_event("PrmDbFull", 0, 2)
    assert h.events[-1].severity == Severity.WARNING_HI
    assert set(h.component.records()) == {0, 1}


@pytest.mark.parametrize("prm_id, value", [(1, None), (-1, b""), (1, bytes(507))])
def test_bad_set_is_refused_never_raised(fprime_harness, tmp_path, prm_id, value):
    h = make(fprime_harness, tmp_path / "p.dat")
    h.invoke("setPrm", prm_id, value)
    assert h.component.records() == {} and h.events == []


# --- reading the file at start-up ------------------------------------------------------------------

def test_read_file_written_by_prm_write(fprime_harness, tmp_path):
    """A file written by the real fprime-prm-write loads with the right ids and bytes."""
    out = tmp_path / "params.dat"
    run_tool("fprime-prm-write", "dat", GDS / "params.json", "--dictionary", GDS / "minimal_dictionary.json",
             "-o", out, cwd=tmp_path)
    h = make(fprime_harness, out)
    assert h.component.read_param_file()
    assert h.invoke("getPrm", 0x1000) == (ParamValid.VALID, GAINS)
    assert h.invoke("getPrm", 0x1001) == (ParamValid.VALID, THRESHOLD)
    h.assert_event("PrmFileLoadComplete", 0, "ACTIVE", 2, 2, 0)
    assert not h.component.dirty


def test_read_file_without_crc(fprime_harness, tmp_path):
    path = tmp_path / "old.dat"
    path.write_bytes(record(7, b"\x01\x02") + record(8, b"\x03"))
    h = make(fprime_harness, path)
    assert h.component.read_param_file()
    assert h.component.records() == {7: b"\x01\x02", 8: b"\x03"}


def test_missing_file(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path / "absent.dat")
    assert not h.component.read_param_file()
    h.assert_event("PrmFileReadError", 0, PrmReadError.OPEN, 0, 2)  # ENOENT
    assert h.invoke("getPrm", 0x1000) == (ParamValid.INVALID, None)


@pytest.mark.parametrize("corrupt, event, args", [
    (lambda d: d[:-3], "PrmFileReadError", (PrmReadError.PARAMETER_VALUE_SIZE, 1, 0x26)),
    (lambda d: d[:0x1d] + b"\x5a" + d[0x1e:], "PrmFileReadError", (PrmReadError.DELIMITER_VALUE, 1, 0x1d)),
    (lambda d: b"\x00" + d[1:], "PrmFileBadCrc", (0x0048DC79, 0x3B48DC79)),
    (lambda d: d[:5] + b"\xff" + d[6:], "PrmFileReadError",
     (PrmReadError.RECORD_SIZE_VALUE, 0, 5)),
])
def test_corrupt_file_reported_nothing_loaded_file_untouched(fprime_harness, tmp_path, corrupt, event, args):
    """A corrupt file: WARNING_HI event naming stage/record/offset (or the CRCs); nothing loaded;
    the file's bytes and modification time unchanged."""
    path = tmp_path / "params.dat"
    original = corrupt((GDS / "params.dat").read_bytes())
    path.write_bytes(original)
    before = os.stat(path)
    h = make(fprime_harness, path)
    assert not h.component.read_param_file()
    h.assert_event(event, 0, *args)
    assert h.events[0].severity == Severity.WARNING_HI
    h.assert_no_event("PrmFileLoadComplete")
    assert h.component.records() == {}
    assert path.read_bytes() == original
    assert os.stat(path).st_mtime_ns == before.st_mtime_ns
    assert sorted(os.listdir(tmp_path)) == ["params.dat"]


def test_read_error_message_is_logged(fprime_harness, tmp_path, caplog):
    path = tmp_path / "params.dat"
    path.write_bytes((GDS / "params.dat").read_bytes()[:-3])
    h = make(fprime_harness, path)
    with caplog.at_level("WARNING", logger="fprime_lite"):
        h.component.read_param_file()
    assert "PARAMETER_VALUE_SIZE at byte 38 (record 1): file ends inside the value of parameter 0x1001" \
        in caplog.text


# --- saving ----------------------------------------------------------------------------------------

def test_save_decodes_with_prm_decode(fprime_harness, tmp_path):
    """A file PrmDb saves decodes with the real fprime-prm-decode to the same values."""
    out = tmp_path / "saved.dat"
    h = make(fprime_harness, out)
    h.invoke("setPrm", 0x1001, THRESHOLD)
    h.invoke("setPrm", 0x1000, GAINS)
    h.send_command("PRM_SAVE_FILE", cmd_seq=3)
    h.dispatch_all()
    h.assert_cmd_response(0, "PRM_SAVE_FILE", CmdResponse.OK, cmd_seq=3)
    h.assert_event("PrmFileSaveComplete", 0, 2)
    assert not h.component.dirty
    assert out.read_bytes() == (GDS / "params.dat").read_bytes()  # id order = name order here
    run_tool("fprime-prm-decode", out, "--dictionary", GDS / "minimal_dictionary.json", "-f", "json",
             "-o", tmp_path / "decoded.json", cwd=tmp_path)
    assert json.loads((tmp_path / "decoded.json").read_text()) == json.loads((GDS / "params.json").read_text())


def test_save_orders_records_by_name_like_prm_write(fprime_harness, tmp_path):
    """With the parameter names known, PrmDb writes the same bytes as fprime-prm-write
    (records by full name: ALPHA 0x1001, NAME 0x1002, ZETA 0x1000 — not id order)."""
    params = {"SvcTest.demo": {"ZETA": 7, "ALPHA": 2.5, "NAME": "abc"}}
    (tmp_path / "p.json").write_text(json.dumps(params))
    run_tool("fprime-prm-write", "dat", tmp_path / "p.json", "--dictionary", SVC_DICT, "-o",
             tmp_path / "tool.dat", cwd=tmp_path)
    tool_bytes = (tmp_path / "tool.dat").read_bytes()
    assert [r[0] for r in decode_param_file(tool_bytes).records] == [0x1001, 0x1002, 0x1000]
    names = {p["id"]: p["name"] for p in json.loads(SVC_DICT.read_text())["parameters"]}
    h = make(fprime_harness, tmp_path / "ours.dat", param_names=names)
    h.invoke("setPrm", 0x1000, struct.pack(">I", 7))
    h.invoke("setPrm", 0x1002, b"\x00\x03abc")
    h.invoke("setPrm", 0x1001, struct.pack(">d", 2.5))
    h.send_command("PRM_SAVE_FILE")
    h.dispatch_all()
    assert (tmp_path / "ours.dat").read_bytes() == tool_bytes


def test_save_replaces_existing_file_and_keeps_mode(fprime_harness, tmp_path):
    path = tmp_path / "p.dat"
    path.write_bytes(b"old")
    os.chmod(path, 0o640)
    h = make(fprime_harness, path)
    h.invoke("setPrm", 1, b"\x01")
    h.send_command("PRM_SAVE_FILE")
    h.dispatch_all()
    assert decode_param_file(path.read_bytes()).records == [(1, b"\x01")]
    assert os.stat(path).st_mode & 0o777 == 0o640
    assert sorted(os.listdir(tmp_path)) == ["p.dat"]


def test_save_into_missing_directory_fails_cleanly(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path / "no" / "such" / "p.dat")
    h.invoke("setPrm", 1, b"\x01")
    h.send_command("PRM_SAVE_FILE")
    h.dispatch_all()
    h.assert_cmd_response(0, "PRM_SAVE_FILE", CmdResponse.EXECUTION_ERROR)
    h.assert_event("PrmFileWriteError", 0, PrmWriteError.OPEN, 0, 2)
    assert h.component.dirty


@pytest.mark.parametrize("victim, stage", [("fsync", PrmWriteError.PARAMETER_VALUE),
                                           ("replace", PrmWriteError.OPEN)])
def test_failed_save_leaves_old_file_intact(fprime_harness, tmp_path, monkeypatch, victim, stage):
    """A save that fails half-way (full disk, I/O error) leaves the old file byte-for-byte and no
    temporary file behind."""
    path = tmp_path / "params.dat"
    original = (GDS / "params.dat").read_bytes()
    path.write_bytes(original)
    h = make(fprime_harness, path)
    assert h.component.read_param_file()
    h.invoke("setPrm", 0x1001, struct.pack(">I", 99))

    def fail(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, victim, fail)
    h.send_command("PRM_SAVE_FILE")
    h.dispatch_all()
    monkeypatch.undo()
    h.assert_cmd_response(0, "PRM_SAVE_FILE", CmdResponse.EXECUTION_ERROR)
    args = h.events_named("PrmFileWriteError")[0]
    assert args[0] == stage and args[2] == 28
    assert path.read_bytes() == original
    assert sorted(os.listdir(tmp_path)) == ["params.dat"]


def test_round_trip_through_save_and_read(fprime_harness, tmp_path):
    path = tmp_path / "p.dat"
    h = make(fprime_harness, path)
    values = {i: bytes([i]) * i for i in range(1, 20)}
    for i, v in values.items():
        h.invoke("setPrm", i, v)
    h.send_command("PRM_SAVE_FILE")
    h.dispatch_all()
    h2 = make(fprime_harness, path)
    assert h2.component.read_param_file()
    assert h2.component.records() == values


# --- staged loading (PRM_LOAD_FILE / PRM_COMMIT_STAGED) ---------------------------------------------

def test_load_merge_then_commit(fprime_harness, tmp_path):
    other = tmp_path / "update.dat"
    other.write_bytes(encode_param_file([(2, b"\x22"), (3, b"\x33")]))
    h = make(fprime_harness, tmp_path / "p.dat")
    h.invoke("setPrm", 1, b"\x11")
    h.invoke("setPrm", 2, b"\x20")
    h.clear_history()
    h.send_command("PRM_LOAD_FILE", str(other), Merge.MERGE, cmd_seq=5)
    h.dispatch_all()
    h.assert_cmd_response(0, "PRM_LOAD_FILE", CmdResponse.OK, cmd_seq=5)
    h.assert_event("PrmDbCopyAllComplete", 0, "ACTIVE", "STAGING")
    h.assert_event("PrmFileLoadComplete", 0, "STAGING", 2, 1, 1)
    assert h.component.state == PrmDbFileLoadState.FILE_UPDATES_STAGED
    assert h.invoke("getPrm", 2) == (ParamValid.VALID, b"\x20")  # not active yet
    # While staged: set and save are refused.
    h.invoke("setPrm", 9, b"")
    h.assert_event("PrmDbFileLoadInvalidAction", 0, PrmDbFileLoadState.FILE_UPDATES_STAGED,
                   PrmLoadAction.SET_PARAMETER)
    h.send_command("PRM_SAVE_FILE")
    h.send_command("PRM_LOAD_FILE", str(other), Merge.RESET)
    h.send_command("PRM_COMMIT_STAGED", cmd_seq=6)
    h.dispatch_all()
    h.assert_cmd_response(1, "PRM_SAVE_FILE", CmdResponse.BUSY)
    h.assert_cmd_response(2, "PRM_LOAD_FILE", CmdResponse.BUSY)
    h.assert_cmd_response(3, "PRM_COMMIT_STAGED", CmdResponse.OK, cmd_seq=6)
    h.assert_event("PrmDbCommitComplete", 0)
    assert h.component.records() == {1: b"\x11", 2: b"\x22", 3: b"\x33"}
    assert h.component.state == PrmDbFileLoadState.IDLE


def test_load_reset_and_commit_without_load(fprime_harness, tmp_path):
    other = tmp_path / "update.dat"
    other.write_bytes(encode_param_file([(3, b"\x33")]))
    h = make(fprime_harness, tmp_path / "p.dat")
    h.invoke("setPrm", 1, b"\x11")
    h.send_command("PRM_COMMIT_STAGED")
    h.send_command("PRM_LOAD_FILE", str(other), Merge.RESET)
    h.send_command("PRM_COMMIT_STAGED")
    h.dispatch_all()
    h.assert_cmd_response(0, "PRM_COMMIT_STAGED", CmdResponse.VALIDATION_ERROR)
    h.assert_event("PrmDbFileLoadInvalidAction", 0, PrmDbFileLoadState.IDLE,
                   PrmLoadAction.COMMIT_STAGED_COMMAND)
    assert h.component.records() == {3: b"\x33"}


def test_load_of_corrupt_file_fails_and_returns_to_idle(fprime_harness, tmp_path):
    bad = tmp_path / "bad.dat"
    bad.write_bytes((GDS / "params.dat").read_bytes()[:-1])
    h = make(fprime_harness, tmp_path / "p.dat")
    h.invoke("setPrm", 1, b"\x11")
    h.send_command("PRM_LOAD_FILE", str(bad), Merge.MERGE)
    h.send_command("PRM_LOAD_FILE", "", Merge.MERGE)
    h.dispatch_all()
    h.assert_cmd_response(0, "PRM_LOAD_FILE", CmdResponse.EXECUTION_ERROR)
    h.assert_cmd_response(1, "PRM_LOAD_FILE", CmdResponse.VALIDATION_ERROR)
    h.assert_event("PrmFileReadError", 0, PrmReadError.PARAMETER_VALUE_SIZE, 1, 0x26)
    h.assert_event_count("PrmDbFileLoadFailed", 2)
    assert h.component.state == PrmDbFileLoadState.IDLE
    assert h.component.records() == {1: b"\x11"} and h.component.records(staging=True) == {}


def test_components_load_their_parameters_from_prm_db(tmp_path):
    """A component's prmGetOut wired to getPrm: load_parameters() takes the file's values."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("svc_dict_gen", DATA / "svc" / "make_svc_dictionary.py")
    gen = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = gen
    spec.loader.exec_module(gen)
    demo = gen.Demo("demo", base_id=0x1000)
    path = tmp_path / "p.dat"
    path.write_bytes(encode_param_file([(0x1001, struct.pack(">d", 9.5))]))
    db = PrmDb("prmDb", path)
    demo.output_port("prmGetOut").connect(0, db.input_port("getPrm"), 0)
    demo.output_port("prmSetOut").connect(0, db.input_port("setPrm"), 0)
    assert db.read_param_file()
    demo.load_parameters()
    assert (demo.ALPHA.value, demo.ALPHA.validity) == (9.5, ParamValid.VALID)
    assert demo.ZETA.validity == ParamValid.DEFAULT
    # P_PRM_SET then P_PRM_SAVE pushes the new value to PrmDb.
    demo.input_port("cmdIn").entries[0](demo.opcode("ZETA_PRM_SET"), 0, struct.pack(">I", 3))
    demo.input_port("cmdIn").entries[0](demo.opcode("ZETA_PRM_SAVE"), 0, b"")
    assert db.records()[0x1000] == struct.pack(">I", 3) and db.dirty
