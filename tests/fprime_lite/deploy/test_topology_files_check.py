"""'fprime-lite check' validates the files a topology names (issue #17): a missing or undecodable
parameter file or start-up sequence is reported at the topology line that names it."""

import pathlib
import shutil

import pytest

from fprime_lite.deploy.preflight import PreflightError, check_parameter_file, check_sequence, topology_file_problems
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.prm_db import encode_param_file
from fprime_lite.tools.cli import main
from fprime_lite.wire.seqfile import Record, Sequence, encode_binary

REF_DIR = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref"
MANAGER_BASE = 0x1005A000
GAIN_ID = MANAGER_BASE + 39  # DetumbleManager.GAIN, F64


@pytest.fixture
def dep(tmp_path):
    shutil.copytree(REF_DIR, tmp_path / "dep")
    return tmp_path / "dep"


def _line(path: pathlib.Path, prefix: str) -> int:
    return next(i for i, t in enumerate(path.read_text().splitlines(), 1) if t.lstrip().startswith(prefix))


def test_reference_files_pass():
    """TFC-001: the shipped parameter file and start-up sequence pass, so each refusal below is the case's."""
    assert topology_file_problems(load_topology(REF_DIR / "topology.yaml")) == []


def test_missing_parameter_file_is_reported_at_its_line(dep, capsys):
    """TFC-002: 'fprime-lite check' used to pass a topology whose parameter_file does not exist."""
    (dep / "flight_params.dat").unlink()
    assert main(["check", str(dep / "topology.yaml")]) != 0
    line = _line(dep / "topology.yaml", "parameter_file:")
    assert f"topology.yaml:{line}: 'parameter_file': parameter file {dep / 'flight_params.dat'}: no such file" \
        in capsys.readouterr().err


def test_undecodable_parameter_file(dep, capsys):
    """TFC-003: a truncated parameter file, and one whose value is not of its parameter's type."""
    data = (dep / "flight_params.dat").read_bytes()
    (dep / "flight_params.dat").write_bytes(data[:len(data) // 2])
    assert main(["check", str(dep / "topology.yaml")]) != 0
    assert "'parameter_file': parameter file" in capsys.readouterr().err
    topology = load_topology(REF_DIR / "topology.yaml").topology
    (dep / "p.dat").write_bytes(encode_param_file([(GAIN_ID, b"\x00\x01")]))
    with pytest.raises(PreflightError, match=r"ReferenceDeployment\.detumbleManager\.GAIN\): the value does not "
                                             r"deserialize as F64"):
        check_parameter_file(topology, dep / "p.dat")


def test_bad_start_up_sequence(dep, capsys):
    """TFC-004: a start-up sequence naming an unknown command, or with a foreign opcode, is refused."""
    (dep / "startup.seq").write_text("R00:00:00 ReferenceDeployment.detumbleManager.SET_MODDE AUTO\n")
    assert main(["check", str(dep / "topology.yaml")]) != 0
    line = _line(dep / "topology.yaml", "sequence:")
    err = capsys.readouterr().err
    assert "'startup.sequence': sequence " in err and f"topology.yaml:{line}" in err
    topology = load_topology(REF_DIR / "topology.yaml").topology
    (dep / "foreign.bin").write_bytes(encode_binary(Sequence([Record.for_command(1, 0, 0, 0x7777AAAA)])))
    with pytest.raises(PreflightError, match=r"record 0 has opcode 0x7777AAAA, which is no command"):
        check_sequence(topology, dep / "foreign.bin", "ReferenceDeployment.cmdSeq")
    assert main(["check", str(REF_DIR / "topology.yaml")]) == 0
