"""FPP component definitions bound to Python classes that supply handlers only (docs/fpp.md), and
`fprime-lite new component NAME --fpp` (issue 30)."""

from __future__ import annotations

import subprocess
import sys

import pytest

pytest.importorskip("fpp", reason="FPP models need fprime-fpp-python (the test extra installs it)")

from fprime_lite import CmdResponse  # noqa: E402
from fprime_lite.deploy.fpp.loader import FppError, component_class  # noqa: E402
from fprime_lite.tools.cli import main  # noqa: E402
from fprime_lite.tools.skeleton import FPP_SPECIAL_PORTS  # noqa: E402


@pytest.fixture
def skeleton(tmp_path, capsys):
    assert main(["new", "component", "MyHeater", "--fpp", "--dir", str(tmp_path)]) == 0
    capsys.readouterr()
    return tmp_path


@pytest.mark.slow  # a pytest run in a subprocess (several seconds)
def test_the_fpp_skeleton_passes_its_own_harness_test(skeleton):
    """FPPC-001: `new component NAME --fpp` writes NAME.fpp, a handlers-only class and a harness
    test that passes as written."""
    assert sorted(p.name for p in skeleton.iterdir()) == ["my_heater.fpp", "my_heater.py", "test_my_heater.py"]
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(skeleton)],
                          cwd=skeleton, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "1 passed" in done.stdout


def test_the_fpp_declares_what_the_class_gets(skeleton, monkeypatch):
    """FPPC-002: the bound class has the FPP's members with the FPP's ids, opcodes and default."""
    monkeypatch.syspath_prepend(str(skeleton))
    cls = component_class(skeleton / "my_heater.fpp")
    spec = cls.__fprime_spec__
    assert [c.name for c in spec.commands] == ["RESET", "STEP_PRM_SET", "STEP_PRM_SAVE"]
    assert [c.opcode for c in spec.commands] == [0, 1, 2]
    assert spec.param("STEP").default == 1
    assert spec.event("Counted").format == "Count is now {}"
    assert spec.channel("Count").update == "on change"
    assert spec.inputs["run"].port_type.name == "Svc.Sched"


@pytest.mark.parametrize("old, new, expected", [
    ("def RESET(self)", "def RESET_LATER(self)", "my_heater.fpp:22:5: command RESET has no handler"),
    ("def run(self, context: int)", "def run(self)", "my_heater.fpp:19:5: input port run:"),
])
def test_a_handler_that_is_missing_or_does_not_fit_is_refused(skeleton, monkeypatch, old, new, expected):
    """FPPC-003: a missing handler, or one whose signature does not fit its port, is refused with
    the FPP file:line and the Python class's file:line."""
    monkeypatch.syspath_prepend(str(skeleton))
    module = skeleton / "my_heater.py"
    module.write_text(module.read_text().replace(old, new))
    with pytest.raises(FppError) as caught:
        component_class(skeleton / "my_heater.fpp")
    (problem,) = caught.value.problems
    assert problem.startswith(str(skeleton / expected)) or expected in problem, problem
    assert "my_heater.py:" in problem


@pytest.fixture
def fpp_deployment(tmp_path, capsys):
    """A deployment skeleton whose component is the FPP one: `type: fpp:counter.fpp:...`."""
    assert main(["new", "deployment", "Dep", "--dir", str(tmp_path)]) == 0
    folder = tmp_path / "Dep"
    for name in ("dep_counter.py", "dep_counter.md", "test_dep_counter.py"):  # the skeleton's own component
        (folder / name).unlink()
    assert main(["new", "component", "Counter", "--fpp", "--dir", str(folder)]) == 0
    topology = folder / "topology.yaml"
    text = topology.read_text()
    assert "{type: dep_counter.Counter," in text
    topology.write_text(text.replace("{type: dep_counter.Counter,", '{type: "fpp:counter.fpp:Components.Counter",'))
    capsys.readouterr()
    return folder


@pytest.mark.slow  # flies 3 simulated seconds
def test_a_yaml_topology_takes_an_fpp_component_and_flies_it(fpp_deployment, capsys):
    """FPPC-004: a YAML instance `type: fpp:FILE.fpp:Module.Component` is the FPP component bound to
    its handlers; the deployment checks, has its commands in the dictionary and flies."""
    from fprime_lite.tools import run

    topology = fpp_deployment / "topology.yaml"
    assert main(["check", str(topology)]) == 0
    out = fpp_deployment / "d.json"
    assert main(["dict", str(topology), "-o", str(out)]) == 0
    import json

    names = {c["name"] for c in json.loads(out.read_text())["commands"]}
    assert {"Dep.counter.RESET", "Dep.counter.STEP_PRM_SET"} <= names
    result = run(str(topology), duration_s=3, out=str(fpp_deployment / "run"))
    assert result.ok
    assert (result.events.name == "Dep.counter.Counted").sum() == 4  # ticks at 0, 1, 2 and 3 s


def test_a_yaml_reference_to_a_missing_fpp_file_is_refused(fpp_deployment, capsys):
    """FPPC-005: a reference to an FPP file that is not there is a topology problem with its line."""
    topology = fpp_deployment / "topology.yaml"
    topology.write_text(topology.read_text().replace("fpp:counter.fpp:", "fpp:nothere.fpp:"))
    assert main(["check", str(topology)]) == 2
    err = capsys.readouterr().err
    assert "topology.yaml:11:" in err and "nothere.fpp: no such FPP file" in err


_PACKET_TOPOLOGY = """module Dep {
  instance counter: Components.Counter base id 0x1000
  instance counter2: Components.Counter base id 0x2000
  %s Dep {
    instance counter
    instance counter2
    telemetry packets DepPackets {
      packet Counts id 1 group 1 {
        counter.Count
      }
      packet Other id 2 group 2 {
        counter2.Count
      }
    } omit {
    }
  }
}
"""


@pytest.mark.slow  # runs fpp-to-dict
def test_a_handlers_only_topology_with_packets_against_fpp_to_dict(tmp_path, capsys, monkeypatch):
    """FPPC-006: an FPP topology of handlers-only components with a telemetry packet set gives the
    dictionary fpp-to-dict gives (ids, opcodes, formats, packets), but for fprime-lite's own
    members and the ground-system definitions docs/fpp.md lists. fpp-python 3.4 takes packets only
    in a `deployment topology`, which fpp-to-dict 3.0 does not parse: each reads its own spelling."""
    import json
    import shutil

    from fprime_lite.deploy.dictionary import build_dictionary
    from fprime_lite.deploy.fpp import export
    from fprime_lite.deploy.fpp.dict_diff import dictionary_differences
    from fprime_lite.deploy.fpp.loader import load_fpp

    tool = shutil.which("fpp-to-dict")
    if tool is None:
        pytest.skip("fpp-to-dict is not installed (pip install 'fprime-lite[fpp]' installs fprime-fpp-to-dict)")
    assert main(["new", "component", "Counter", "--fpp", "--dir", str(tmp_path)]) == 0
    monkeypatch.syspath_prepend(str(tmp_path))
    (tmp_path / "ours.fpp").write_text(_PACKET_TOPOLOGY % "deployment topology")
    (tmp_path / "theirs.fpp").write_text(_PACKET_TOPOLOGY % "topology")
    ours = build_dictionary(load_fpp([tmp_path / "counter.fpp", tmp_path / "ours.fpp"]))  # type: ignore[arg-type]
    out = tmp_path / "out"
    out.mkdir()
    imports = ",".join(str(p) for p in export.framework_files())
    subprocess.run([tool, "-i", imports, str(tmp_path / "counter.fpp"), str(tmp_path / "theirs.fpp"), "-d", str(out)],
                   check=True, capture_output=True, timeout=120)
    theirs = json.loads((out / "DepTopologyDictionary.json").read_text())
    assert ours["telemetryPacketSets"] == theirs["telemetryPacketSets"]
    assert ours["telemetryPacketSets"][0]["members"][1]["members"] == ["Dep.counter2.Count"]
    own = [f"events Dep.{i}.{e}: only in ours" for i in ("counter", "counter2")
           for e in ("HandlerFault", "ParamDefaulted", "ParamSetRefused")]
    own += [f"telemetryChannels Dep.{i}.HandlerFaults: only in ours" for i in ("counter", "counter2")]
    ground = ["constants ComCfg.SpacecraftId: only in ours", "constants ComCfg.TmFrameFixedSize: only in ours"]
    ground += [f"typeDefinitions {t}: only in ours"
               for t in ("ComCfg.Apid", "Fw.CmdResponse", "FwIdType", "FwPrmIdType", "TimeBase")]
    assert sorted(dictionary_differences(ours, theirs)) == sorted(own + ground)


def test_the_framework_definitions_can_come_from_the_user(skeleton, capsys, monkeypatch):
    """FPPC-007: --no-framework-fpp leaves fprime-lite's framework FPP out: the model must then get
    F´'s definitions from the user's files (-i), here the same files given by hand."""
    from fprime_lite.deploy.fpp import export

    monkeypatch.syspath_prepend(str(skeleton))
    fpp_file = str(skeleton / "my_heater.fpp")
    assert main(["check", fpp_file, "--no-framework-fpp"]) == 2
    assert "in scope" in capsys.readouterr().err  # Svc.Sched, FwOpcodeType … are not defined without them
    imports = ",".join(str(p) for p in export.framework_files())
    assert main(["check", fpp_file, "--no-framework-fpp", "-i", imports]) == 0
    assert "Components.MyHeater → my_heater.MyHeater" in capsys.readouterr().out


def test_fpp_connection_patterns_connect_the_special_ports(tmp_path, capsys, monkeypatch):
    """FPPC-008: an FPP topology's command, event and telemetry patterns, resolved by F´'s analyser
    against fprime-lite's services (Svc.CommandDispatcher …), connect a component's special ports."""
    from fprime_lite.deploy.fpp.loader import load_fpp

    assert main(["new", "component", "Counter", "--fpp", "--dir", str(tmp_path)]) == 0
    monkeypatch.syspath_prepend(str(tmp_path))
    (tmp_path / "top.fpp").write_text("""module Dep {
  instance cmdDisp: Svc.CommandDispatcher base id 0x100 queue size 10
  instance events: Svc.EventManager base id 0x200 queue size 10
  instance tlmSend: Svc.TlmChan base id 0x300 queue size 10
  instance counter: Components.Counter base id 0x1000
  topology Dep {
    instance cmdDisp
    instance events
    instance tlmSend
    instance counter
    command connections instance cmdDisp
    event connections instance events
    telemetry connections instance tlmSend
  }
}
""")
    model = load_fpp([tmp_path / "counter.fpp", tmp_path / "top.fpp"])
    counter = {c for c in model.connections if "Dep.counter" in (c[0], c[3])}
    # the analyser's numbers: the dispatcher's own commands at 0, the counter's at 1, registration and
    # dispatch at one index (svc.fpp: match compCmdSend with compCmdReg)
    assert counter == {("Dep.cmdDisp", "compCmdSend", 1, "Dep.counter", "cmdIn", 0),
                       ("Dep.counter", "cmdRegOut", 0, "Dep.cmdDisp", "compCmdReg", 1),
                       ("Dep.counter", "cmdResponseOut", 0, "Dep.cmdDisp", "compCmdStat", 0),
                       ("Dep.counter", "logOut", 0, "Dep.events", "LogRecv", 0),
                       ("Dep.counter", "tlmOut", 0, "Dep.tlmSend", "TlmRecv", 0)}
    assert model.instances["Dep.cmdDisp"].queue_size == 10


_SHAPES_FPP = """module Components {
  @ Three numbers
  array Vec = [3] F64 default [1.0, 2.0, 3.0]
  @ A labelled point
  struct Pt { x: U32, label: string size 8, v: Vec } default { x = 7 }

  passive component Shapes {
""" + FPP_SPECIAL_PORTS + """
    sync input port run: Svc.Sched
    sync command SET_POINT(p: Pt) opcode 0x0
    event Moved(p: Pt) severity activity low id 0x0 format "moved to {}"
    telemetry Where: Vec id 0x0
    param START: Pt id 0x0 set opcode 0x1 save opcode 0x2
  }
}
"""

_SHAPES_PY = '''from fprime_lite import CmdResponse, PassiveComponent


class Shapes(PassiveComponent):
    def run(self, context: int) -> None:
        self.Where.write(self.START.value.v)

    def SET_POINT(self, p) -> CmdResponse:  # noqa: N802 - F´ command names are upper case
        self.Moved(p)
        return CmdResponse.OK
'''

_SHAPES_TOPOLOGY = """module Dep {
  instance shapes: Components.Shapes base id 0x1000
  topology Dep {
    instance shapes
  }
}
"""


def test_a_handlers_only_class_takes_array_and_struct_types(tmp_path, monkeypatch, fprime_harness):
    """FPPC-009: FPP arrays and structs (with the FPP's defaults, an array inside a struct) become
    fprime-lite Array and Struct types of the same qualified names: a struct command argument, an
    event carrying it, an array channel and a struct parameter with its default fly in the harness."""
    (tmp_path / "shapes.fpp").write_text(_SHAPES_FPP)
    (tmp_path / "shapes.py").write_text(_SHAPES_PY)
    monkeypatch.syspath_prepend(str(tmp_path))
    cls = component_class(tmp_path / "shapes.fpp")
    spec = cls.__fprime_spec__
    assert spec.channel("Where").type.name == "Components.Vec"
    start = spec.param("START")
    assert start.type.name == "Components.Pt"
    assert (start.default.x, start.default.label, list(start.default.v)) == (7, "", [1.0, 2.0, 3.0])
    h = fprime_harness(cls("shapes", base_id=0x1000))
    h.load_parameters()
    h.invoke("run", 0)
    h.assert_tlm("Where", 0, [1.0, 2.0, 3.0])
    point = start.type.cls(x=3, label="here", v=[4.0, 5.0, 6.0])
    h.send_command("SET_POINT", point)
    h.assert_cmd_response(0, "SET_POINT", CmdResponse.OK)
    h.assert_event("Moved", 0, point)


@pytest.mark.slow  # runs fpp-to-dict
def test_array_and_struct_definitions_as_fpp_to_dict_lists_them(tmp_path, monkeypatch):
    """FPPC-010: the dictionary's definitions of an FPP array and struct made for a handlers-only
    class, and the struct parameter's default, are fpp-to-dict's."""
    import json
    import shutil

    from fprime_lite.deploy.dictionary import build_dictionary
    from fprime_lite.deploy.fpp import export
    from fprime_lite.deploy.fpp.loader import load_fpp

    tool = shutil.which("fpp-to-dict")
    if tool is None:
        pytest.skip("fpp-to-dict is not installed (pip install 'fprime-lite[fpp]' installs fprime-fpp-to-dict)")
    (tmp_path / "shapes.fpp").write_text(_SHAPES_FPP)
    (tmp_path / "shapes.py").write_text(_SHAPES_PY)
    (tmp_path / "dep.fpp").write_text(_SHAPES_TOPOLOGY)
    monkeypatch.syspath_prepend(str(tmp_path))
    files = [tmp_path / "shapes.fpp", tmp_path / "dep.fpp"]
    ours = build_dictionary(load_fpp(files))  # type: ignore[arg-type]
    out = tmp_path / "out"
    out.mkdir()
    subprocess.run([tool, "-i", ",".join(str(p) for p in export.framework_files()), *map(str, files), "-d", str(out)],
                   check=True, capture_output=True, timeout=120)
    theirs = json.loads((out / "DepTopologyDictionary.json").read_text())

    def pick(d: dict, section: str, key: str, names: tuple[str, ...]) -> list[dict]:
        return [e for e in d[section] if e[key] in names]
    for section, key, names in (("typeDefinitions", "qualifiedName", ("Components.Vec", "Components.Pt")),
                                ("parameters", "name", ("Dep.shapes.START",)),
                                ("telemetryChannels", "name", ("Dep.shapes.Where",)),
                                ("events", "name", ("Dep.shapes.Moved",))):
        mine = sorted(pick(ours, section, key, names), key=lambda e: e[key])
        assert len(mine) == len(names) and mine == sorted(pick(theirs, section, key, names), key=lambda e: e[key])


def test_a_state_machine_instance_binds_in_an_active_component_and_is_refused_in_a_passive_one(skeleton, monkeypatch):
    """FPPC-011: the skeleton made active with a state machine instance binds and starts in the
    machine's initial state (test_fpp_state_machines.py flies FPP's semantics); in a passive
    component F´'s analyser refuses the instance at its FPP line (its signals need a queue)."""
    monkeypatch.syspath_prepend(str(skeleton))
    fpp_file, module = skeleton / "my_heater.fpp", skeleton / "my_heater.py"
    text = fpp_file.read_text().replace("module Components {\n", "module Components {\n\n  state machine Light {\n"
                                        "    initial enter Off\n    state Off\n  }\n", 1)
    text = text.replace("passive component MyHeater {", "active component MyHeater {")
    text = text.replace("    sync input port run: Svc.Sched", "    state machine instance light: Light\n"
                                                                 "    async input port run: Svc.Sched")
    fpp_file.write_text(text)
    module.write_text(module.read_text().replace("PassiveComponent", "ActiveComponent"))
    heater = component_class(fpp_file)("heater", base_id=0x10)
    assert heater.light_getState().name == "Off"
    fpp_file.write_text(text.replace("active component MyHeater {", "passive component MyHeater {")
                        .replace("async input port run", "sync input port run"))
    module.write_text(module.read_text().replace("ActiveComponent", "PassiveComponent"))
    with pytest.raises(FppError) as caught:
        component_class(fpp_file)
    assert any("my_heater.fpp:24:5" in p and "passive component may not have state machine instances" in p
               for p in caught.value.problems), caught.value.problems  # F´'s analyser's own refusal
