"""Malformed topology files that used to crash or stall the loader (issue #16 finding 4), and what
``type:`` may name (finding 5): each gives ``file:line: what — what to do`` and nothing else."""

import os
import pathlib
import re
import shutil

import pytest

from fprime_lite.deploy.topology_loader import TopologyError, load_topology
from fprime_lite.deploy.topology_yaml.parse import MAX_DEPTH, MAX_FILE_BYTES, MAX_VALUES

REF_DIR = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref"

MINIMAL = """\
deployment: Demo
modules:
  Demo:
    instances:
      driver: {type: fprime_lite.svc.rate_group_driver.RateGroupDriver, base_id: 0x100}
      rg: {type: fprime_lite.svc.rate_groups.PassiveRateGroup, base_id: 0x200}
rate_groups:
  driver: Demo.driver
  base_rate_hz: 10
  groups:
    Demo.rg: {divisor: 1}
"""


@pytest.fixture(autouse=True, params=["libyaml", "python"])
def yaml_engine(request, monkeypatch):
    """Every case runs with libyaml (when PyYAML has it) and with PyYAML's pure-Python parser."""
    from fprime_lite.deploy.topology_yaml import parse

    if request.param == "python":
        monkeypatch.setattr(parse, "_FAST_LOADER", None)
    elif parse._FAST_LOADER is None:
        pytest.skip("PyYAML without libyaml")
    return request.param


def write(folder: pathlib.Path, data, name="topology.yaml") -> pathlib.Path:
    path = folder / name
    path.write_bytes(data.encode() if isinstance(data, str) else data)
    return path


def refused(path: pathlib.Path, pattern: str) -> list[str]:
    """Load ``path``; it must raise TopologyError whose problems are all located and one matches."""
    with pytest.raises(TopologyError) as err:
        load_topology(path)
    problems = err.value.problems
    for p in problems:
        assert re.match(r"^.+:\d+: .+ — .+", p, re.S), f"not 'file:line: what — what to do': {p!r}"
    assert any(re.search(pattern, p) for p in problems), f"no problem matched {pattern!r} in {problems}"
    return problems


def test_minimal_topology_loads(tmp_path):
    """TOPO-ROB-000: the base of these cases is valid, so each refusal below is the case's own."""
    loaded = load_topology(write(tmp_path, MINIMAL))
    assert set(loaded.topology.instances) == {"Demo.driver", "Demo.rg"}


def test_rate_group_without_members_is_an_empty_group(tmp_path):
    """TOPO-ROB-001: a rate group without 'members:' used to raise AttributeError; it is a group
    with no members, connected to its driver."""
    loaded = load_topology(write(tmp_path, MINIMAL))
    connections = {str(c) for c in loaded.topology.connections}
    assert "Demo.driver.CycleOut[0] -> Demo.rg.CycleIn[0]" in connections
    assert not [c for c in connections if "RateGroupMemberOut" in c]


def test_nul_byte(tmp_path):
    """TOPO-ROB-002: a NUL byte is named with its line."""
    refused(write(tmp_path, MINIMAL.replace("base_rate_hz: 10", "base_rate_hz: 1\x000")),
            r"topology\.yaml:9: the file contains a NUL byte — ")


def test_not_utf8(tmp_path):
    """TOPO-ROB-003: a byte that is not UTF-8 is named with its line."""
    refused(write(tmp_path, MINIMAL.encode().replace(b"Demo.rg: {", b"Demo.rg\xff: {")),
            r"topology\.yaml:11: byte 0xFF is not UTF-8 text — save the file as UTF-8")


def test_other_control_character(tmp_path):
    """TOPO-ROB-004: control characters YAML refuses are named with their line."""
    refused(write(tmp_path, MINIMAL.replace("base_id: 0x200", "base_id: 0x200\x07")),
            r"topology\.yaml:6: character '\\x07' is not allowed in YAML — remove it")


@pytest.mark.parametrize("bad", ["x" * 300 + ".yaml", "a\x00b.yaml"], ids=["300 characters", "NUL"])
@pytest.mark.parametrize("where", ["extends", "include", "sequence", "parameter_file"])
def test_unusable_paths(tmp_path, where, bad):
    """TOPO-ROB-005: a 300-character or NUL-containing path in extends/include/startup.sequence/
    parameter_file is refused before the file system sees it."""
    quoted = '"' + bad.replace("\x00", "\\0") + '"'
    if where == "extends":
        text = f"extends: {quoted}\n" + MINIMAL
        key = "'extends'"
    elif where == "include":
        text = MINIMAL.replace("  Demo:\n", f"  Other:\n    include: {quoted}\n  Demo:\n")
        key = "module 'Other': 'include'"
    elif where == "sequence":
        text = MINIMAL + f"startup: {{sequencer: Demo.rg, sequence: {quoted}}}\n"
        key = "'startup.sequence'"
    else:
        text = MINIMAL + f"parameter_file: {quoted}\n"
        key = "'parameter_file'"
    why = "has a name of 305 characters, more than 255" if "\x00" not in bad else "contains a NUL character"
    refused(write(tmp_path, text), rf"topology\.yaml:\d+: {re.escape(key)} {why}")


def test_integer_key_in_args(tmp_path):
    """TOPO-ROB-006: an integer key in 'args:' is not a keyword argument."""
    text = MINIMAL.replace("base_id: 0x200}", "base_id: 0x200, args: {1: 2}}")
    refused(write(tmp_path, text), r"topology\.yaml:6: instance Demo\.rg: argument name 1 must be an identifier — ")


@pytest.mark.parametrize("key", ["[a, b]", "{a: 1}"], ids=["list", "mapping"])
def test_collection_as_mapping_key(tmp_path, key):
    """TOPO-ROB-007: a list or mapping as a key (unhashable in Python) is a located problem."""
    text = MINIMAL.replace("rg: {type", f"? {key}\n      : 1\n      rg: {{type")
    refused(write(tmp_path, text), r"topology\.yaml:6: a mapping key must be a plain value, not a")


@pytest.mark.parametrize("tag", ["!!python/name:os.system", "!!python/object/apply:os.system ['id']",
                                 "!!python/object:os.stat_result {}", "!!set {a: null}"])
def test_python_and_other_tags(tmp_path, tag):
    """TOPO-ROB-008: tags outside the core schema are refused, with their line, and nothing runs."""
    text = MINIMAL.replace("base_rate_hz: 10", f"base_rate_hz: {tag}")
    refused(write(tmp_path, text), r"topology\.yaml:9: .*tag '.*' is not allowed")


def test_deep_nesting(tmp_path):
    """TOPO-ROB-009: 500-deep nesting used to end in RecursionError."""
    text = MINIMAL + "time: " + "[" * 500 + "]" * 500 + "\n"
    refused(write(tmp_path, text), rf"topology\.yaml:12: nesting deeper than {MAX_DEPTH} levels — ")


def test_self_referencing_alias(tmp_path):
    """TOPO-ROB-010: an alias inside the node it names used to end in RecursionError."""
    text = MINIMAL + "time: &loop {time_base: *loop}\n"
    refused(write(tmp_path, text), r"topology\.yaml:12: an alias refers to a node that contains it")


def test_alias_bomb(tmp_path):
    """TOPO-ROB-011: a 330-byte document expanding to 10^9 values is refused once it passes
    MAX_VALUES, instead of being expanded (it took 35 s at 10^8)."""
    text = "a: &a [" + ",".join(["x"] * 10) + "]\n"
    text += "".join(f"{b}: &{b} [" + ",".join([f"*{a}"] * 10) + "]\n"
                    for a, b in zip("abcdefgh", "bcdefghi", strict=True))
    assert len(text) < 360
    refused(write(tmp_path, text), rf"topology\.yaml:\d+: the document expands to more than {MAX_VALUES} values")


def test_too_many_values_without_aliases(tmp_path):
    """TOPO-ROB-023: a large flat document is refused while it is composed, not after."""
    text = MINIMAL + "time: [" + ",".join(["0"] * (MAX_VALUES + 10)) + "]\n"
    refused(write(tmp_path, text), rf"topology\.yaml:12: the document expands to more than {MAX_VALUES} values")


def test_duplicate_key(tmp_path):
    """TOPO-ROB-012: a key given twice is named, with the first line, instead of silently dropped."""
    text = MINIMAL.replace("deployment: Demo\n", "deployment: Demo\ndeployment: Other\n")
    refused(write(tmp_path, text), r"topology\.yaml:2: duplicate key 'deployment' \(first at line 1\)")


def test_number_too_long_to_read(tmp_path):
    """TOPO-ROB-013: an integer of 5000 digits (beyond Python's int-from-text limit) is a message."""
    text = MINIMAL.replace("base_id: 0x200", "base_id: " + "9" * 5000)
    refused(write(tmp_path, text), r"topology\.yaml:6: value '9{40}…' cannot be read")


def test_hex_integer_too_wide_to_print(tmp_path):
    """TOPO-ROB-025: a 5000-digit hex integer converts, but its decimal form raised ValueError in the
    messages that show it (found by the long fuzz campaign); it is refused where it is written."""
    text = MINIMAL.replace("base_id: 0x200", "base_id: 0x" + "f" * 5000)
    refused(write(tmp_path, text), r"topology\.yaml:6: integer '0xf{38}…' has more than 128 bits — ")


def test_unreadable_files(tmp_path):
    """TOPO-ROB-014: a folder given as include, and an oversize file, are messages."""
    (tmp_path / "dir.yaml").mkdir()
    text = MINIMAL.replace("  Demo:\n", "  Other:\n    include: dir.yaml\n  Demo:\n")
    refused(write(tmp_path, text), r"include file 'dir\.yaml' not found")
    big = write(tmp_path, MINIMAL + "#" * MAX_FILE_BYTES, name="big.yaml")
    with pytest.raises(TopologyError, match=rf"big\.yaml: the file is larger than {MAX_FILE_BYTES} bytes — "):
        load_topology(big)


@pytest.mark.skipif(not pathlib.Path("/proc/self/mem").exists(), reason="needs Linux /proc")
def test_include_that_cannot_be_read(tmp_path):
    """TOPO-ROB-021: an include that exists but cannot be read is reported at the line naming it."""
    text = MINIMAL.replace("  Demo:\n", "  Other:\n    include: /proc/self/mem\n  Demo:\n")
    refused(write(tmp_path, text), r"topology\.yaml:4: '/proc/self/mem': cannot read the file \(.*\) — ")


def test_unusable_topology_path():
    """TOPO-ROB-015: the topology path itself may be over-long or contain NUL."""
    with pytest.raises(TopologyError, match="the topology path has a name of 300 characters"):
        load_topology("x" * 300)
    with pytest.raises(TopologyError, match="the topology path contains a NUL character"):
        load_topology("a\x00b")


# --- what 'type:' may name (finding 5) -------------------------------------------------------------

@pytest.mark.parametrize("type_path, why", [
    ("os.system", "is in the Python standard library"),
    ("subprocess.run", "is in the Python standard library"),
    ("antigravity.fly", "is in the Python standard library"),
    ("detumble.sim.scenario.load_scenario", "is not a topology resource — a resource is a class or factory marked"),
    ("fprime_lite.svc.health.Health", "is not a topology resource"),
])
def test_resource_type_must_declare_itself(tmp_path, monkeypatch, type_path, why):
    """TOPO-ROB-016: 'resources: {x: {type: os.system, args: {command: ...}}}' used to run the
    command while loading (so during 'check') and report OK; now only classes or factories marked
    with @topology_resource are built, and the command never runs."""
    monkeypatch.chdir(tmp_path)
    text = MINIMAL + 'resources:\n  x: {type: ' + type_path + ', args: {command: "echo ran > ran.txt"}}\n'
    refused(write(tmp_path, text), rf"topology\.yaml:13: resource 'x': type '{re.escape(type_path)}' {why}")
    assert not (tmp_path / "ran.txt").exists()


@pytest.mark.parametrize("type_path", ["os.path.join", "shutil.rmtree", "builtins.eval"])
def test_instance_type_must_be_a_component_class(tmp_path, type_path):
    """TOPO-ROB-017: an instance's type is a component class, never another callable."""
    text = MINIMAL.replace("fprime_lite.svc.rate_groups.PassiveRateGroup", type_path)
    refused(write(tmp_path, text), rf"topology\.yaml:6: instance Demo\.rg: type '{re.escape(type_path)}' is")


def test_dunder_type_paths_are_refused(tmp_path):
    """TOPO-ROB-018: a type path cannot walk into dunder attributes (``x.__class__.__subclasses__``)."""
    text = MINIMAL.replace("fprime_lite.svc.rate_groups.PassiveRateGroup",
                           "fprime_lite.svc.rate_groups.__builtins__")
    refused(write(tmp_path, text), r"type 'fprime_lite\.svc\.rate_groups\.__builtins__' must be a dotted import path")


def test_the_reference_resources_are_marked():
    """TOPO-ROB-019: the detumble application's resources declare themselves, so the reference
    deployment still loads."""
    from fprime_lite.deploy.resources import resource_role
    from detumble.drivers.spacecraft import make_spacecraft
    from detumble.reports.detumble_report import DetumbleRunReport

    assert resource_role(make_spacecraft) == "simulation" and resource_role(DetumbleRunReport) == "report"
    assert set(load_topology(REF_DIR / "topology.yaml").resources) >= {"spacecraft", "report"}


def test_loading_writes_nothing(tmp_path, monkeypatch):
    """TOPO-ROB-020: loading the reference deployment (what 'check' does) creates no file, in the
    current folder or beside the topology."""
    shutil.copytree(REF_DIR, tmp_path / "dep")
    monkeypatch.chdir(tmp_path)
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    load_topology(tmp_path / "dep" / "topology.yaml")
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before
    assert os.listdir(tmp_path) == ["dep"]


def test_check_runs_nothing_and_says_why(tmp_path, monkeypatch, capsys):
    """TOPO-ROB-022: 'fprime-lite check' on the os.system topology of issue #16 exits non-zero with
    the located reason, and the command never runs; an over-long topology path is a one-line message."""
    from fprime_lite.tools.cli import main

    monkeypatch.chdir(tmp_path)
    path = write(tmp_path, MINIMAL + 'resources:\n  x: {type: os.system, args: {command: "id > ran.txt"}}\n')
    assert main(["check", str(path)]) != 0
    assert f"{path}:13: resource 'x': type 'os.system' is in the Python standard library" in capsys.readouterr().err
    assert not (tmp_path / "ran.txt").exists()
    assert main(["check", "x" * 300]) != 0
    err = capsys.readouterr().err
    assert "Traceback" not in err and "x" * 300 in err


def test_thousands_of_mistakes_are_summarised(tmp_path):
    """TOPO-ROB-024: 20 000 unknown keys give the first problems and one summary line, not 20 000
    messages (each with a spelling suggestion to compute)."""
    from fprime_lite.deploy.topology_yaml.parse import MAX_PROBLEMS

    text = MINIMAL + "".join(f"k{i}: {i}\n" for i in range(20000))
    problems = refused(write(tmp_path, text), r"topology\.yaml:12: unknown key 'k0' in the topology file")
    assert len(problems) == MAX_PROBLEMS + 1
    assert re.search(rf"topology\.yaml:{12 + MAX_PROBLEMS}: {20000 - MAX_PROBLEMS} more problem\(s\) not shown — ",
                     problems[-1])
