"""Checks of the parameter file and sequences a deployment starts with (issue #17): 'check'
reports a missing or undecodable parameter file or start-up sequence, with the topology line."""

import pathlib
import shutil

import pytest

from fprime_lite.deploy.flight_files import (deployment_file_problems, parameter_file_problems,
                                             sequence_file_problems)
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.prm_db import decode_param_file, encode_param_file
from fprime_lite.tools.cli import main
from fprime_lite.wire.seqfile import Record, Sequence, encode_binary

REF_DIR = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref"
MANAGER_BASE = 0x1005A000
GAIN_ID = MANAGER_BASE + 39  # DetumbleManager.GAIN, F64


@pytest.fixture
def dep(tmp_path):
    shutil.copytree(REF_DIR, tmp_path / "dep")
    return tmp_path / "dep"


@pytest.fixture(scope="module")
def topology():
    return load_topology(REF_DIR / "topology.yaml").topology


def test_reference_files_are_good(topology):
    """FF-001: the shipped parameter file and start-up sequence pass, so every refusal below is the
    case's own."""
    assert parameter_file_problems(REF_DIR / "flight_params.dat", topology) == []
    assert sequence_file_problems(REF_DIR / "startup.seq", topology) == []
    assert deployment_file_problems(load_topology(REF_DIR / "topology.yaml")) == []


def test_missing_and_unreadable_files(tmp_path, topology):
    """FF-002: a missing file or a folder is named, with what to do."""
    assert parameter_file_problems(tmp_path / "none.dat", topology) == [
        f"{tmp_path / 'none.dat'}: parameter file not found — give the path of an existing file"]
    assert sequence_file_problems(tmp_path, topology) == [
        f"{tmp_path}: sequence is not a regular file — give the path of a file"]


def test_parameter_file_that_does_not_decode(tmp_path, topology):
    """FF-003: a truncated parameter file (PrmDb would load nothing from it) is refused."""
    data = (REF_DIR / "flight_params.dat").read_bytes()
    path = tmp_path / "p.dat"
    path.write_bytes(data[:len(data) // 2])
    [problem] = parameter_file_problems(path, topology)
    assert problem.startswith(f"{path}: not a valid parameter file: ") and " — write it with" in problem


def test_parameter_file_with_unknown_id_or_bad_value(tmp_path, topology):
    """FF-004: a record whose id is no parameter of the topology, or whose value is not of the
    parameter's type (PrmDb would load the default, silently), is named."""
    path = tmp_path / "p.dat"
    path.write_bytes(encode_param_file([(0x7777, b"\x00"), (GAIN_ID, b"\x00\x01")]))
    problems = parameter_file_problems(path, topology)
    assert problems[0].startswith(f"{path}: record 0: parameter id 0x7777 is not a parameter of this deployment")
    assert problems[1].startswith(f"{path}: record 1: the value of ReferenceDeployment.detumbleManager.GAIN "
                                  f"(0x{GAIN_ID:X}) is not a F64")
    good = dict(decode_param_file((REF_DIR / "flight_params.dat").read_bytes()).records)
    path.write_bytes(encode_param_file([(GAIN_ID, good[GAIN_ID])]))
    assert parameter_file_problems(path, topology) == []


def test_sequences_with_unknown_commands_or_garbage(tmp_path, topology):
    """FF-005: a text sequence naming an unknown command, a garbage binary sequence, and a binary
    sequence with an opcode of another dictionary are named."""
    text = tmp_path / "bad.seq"
    text.write_text("R00:00:00 ReferenceDeployment.detumbleManager.SET_MOD AUTO\n")
    [problem] = sequence_file_problems(text, topology)
    assert problem.startswith(f"{text}:1: 'ReferenceDeployment.detumbleManager.SET_MOD' is not a command")
    garbage = tmp_path / "garbage.bin"
    garbage.write_bytes(b"\x01\x02\x03garbage")
    [problem] = sequence_file_problems(garbage, topology)
    assert problem.startswith(f"{garbage}: not a valid sequence: ") and " — fix the file" in problem
    foreign = tmp_path / "foreign.bin"
    foreign.write_bytes(encode_binary(Sequence([Record.for_command(1, 0, 0, 0x7777AAAA)])))
    [problem] = sequence_file_problems(foreign, topology)
    assert problem == (f"{foreign}: record 0: opcode 0x7777AAAA is not a command of this deployment — the "
                       f"sequence was built for another dictionary; rebuild it")
    args = tmp_path / "args.bin"
    args.write_bytes(encode_binary(Sequence([Record.for_command(1, 0, 0, MANAGER_BASE, b"\x00\x00\x00")])))
    [problem] = sequence_file_problems(args, topology)
    assert problem.startswith(f"{args}: record 0: the arguments of ReferenceDeployment.detumbleManager.SET_MODE "
                              f"do not decode")


def test_check_reports_a_missing_parameter_file(dep, capsys):
    """FF-006: 'fprime-lite check' used to pass a topology whose parameter_file does not exist."""
    (dep / "flight_params.dat").unlink()
    assert main(["check", str(dep / "topology.yaml")]) != 0
    err = capsys.readouterr().err
    line = next(i for i, t in enumerate((dep / "topology.yaml").read_text().splitlines(), 1)
                if t.startswith("parameter_file:"))
    assert f"topology.yaml:{line}: 'parameter_file': {dep / 'flight_params.dat'}: parameter file not found" in err


def test_check_reports_a_bad_start_up_sequence(dep, capsys):
    """FF-007: 'check' refuses a start-up sequence whose command is not in the dictionary."""
    (dep / "startup.seq").write_text("R00:00:00 ReferenceDeployment.detumbleManager.SET_MODDE AUTO\n")
    assert main(["check", str(dep / "topology.yaml")]) != 0
    assert "'startup.sequence': " in capsys.readouterr().err
    assert main(["check", str(REF_DIR / "topology.yaml")]) == 0
