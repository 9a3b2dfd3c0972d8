"""Topology YAML: loading, wiring, validation messages with file:line, DOT/Mermaid export."""

import pathlib
import textwrap

import pytest

from fprime_lite.deploy.topology_loader import TopologyError, load_topology

REFERENCE = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"

PARTS = '''
from fprime_lite import (F64, U32, Channel, Event, OutputPort, Param, PassiveComponent, PortType,
                         Sched, Severity, sync_command, sync_input)
from fprime_lite.model.fw_ports import CmdReg, Cmd, CmdResponsePort, Log, LogText, Tlm, PrmGet, PrmSet, TimeGet
from fprime_lite.model.params import ParamValid
from fprime_lite.model.time import Time

Level = PortType("Demo.Level", value=F64)
Other = PortType("Demo.Other", value=U32)


class Sensor(PassiveComponent):
    levelOut = OutputPort(Level, required=True)
    Reading = Channel(F64)
    Spike = Event(Severity.WARNING_LO, "spike {f}", v=F64)
    GAIN = Param(F64, default=2.0)

    def __init__(self, name, *, base_id=0, gain_hint=1.0):
        super().__init__(name, base_id=base_id)
        self.gain_hint = gain_hint
        self.runs = []

    @sync_input(Sched)
    def run(self, context):
        self.runs.append(context)
        self.levelOut[0](1.0)

    @sync_command()
    def PING(self):
        pass


class Display(PassiveComponent):
    @sync_input(Level)
    def levelIn(self, value):
        pass

    @sync_input(Other)
    def otherIn(self, value):
        pass


class Dispatcher(PassiveComponent):
    compCmdSend = OutputPort(Cmd, size=4)

    def __init__(self, name, *, base_id=0):
        super().__init__(name, base_id=base_id)
        self.table = {}

    @sync_input(CmdReg, size=4)
    def compCmdReg(self, port_num, opcode):
        self.table[opcode] = port_num

    @sync_input(CmdResponsePort)
    def compCmdStat(self, opcode, cmd_seq, response):
        pass

    @sync_command()
    def NO_OP(self):
        pass


class Logger(PassiveComponent):
    @sync_input(Log)
    def LogRecv(self, id, time, severity, args):
        pass


class TlmStore(PassiveComponent):
    @sync_input(Tlm)
    def TlmRecv(self, id, time, value):
        pass


class Prm(PassiveComponent):
    @sync_input(PrmGet)
    def getPrm(self, id):
        return ParamValid.INVALID, None

    @sync_input(PrmSet)
    def setPrm(self, id, value):
        pass


class Clock(PassiveComponent):
    def __init__(self, name, *, base_id=0, clock=None):
        super().__init__(name, base_id=base_id)
        self.clock = clock

    @sync_input(TimeGet)
    def timeGetPort(self):
        return self.clock.now()
'''

GOOD = """\
deployment: Demo
modules:
  Core:
    instances:
      cmdDisp: {type: topo_parts.Dispatcher, base_id: 0x100}
      events: {type: topo_parts.Logger, base_id: 0x200}
      tlm: {type: topo_parts.TlmStore, base_id: 0x300}
      prm: {type: topo_parts.Prm, base_id: 0x400}
      time: {type: topo_parts.Clock, base_id: 0x500, args: {clock: $clock}}
  Demo:
    instances:
      driver: {type: fprime_lite.svc.rate_group_driver.RateGroupDriver, base_id: 0x600}
      rg10: {type: fprime_lite.svc.rate_groups.ActiveRateGroup, base_id: 0x700, queue_size: 5}
      sensor: {type: topo_parts.Sensor, base_id: 0x1000, args: {gain_hint: 4.5}}
      display: {type: topo_parts.Display, base_id: 0x2000}
patterns:
  command: Core.cmdDisp
  event: Core.events
  telemetry: Core.tlm
  param: Core.prm
  time: Core.time
connections:
  Readings:
    - Demo.sensor.levelOut -> Demo.display.levelIn
rate_groups:
  driver: Demo.driver
  base_rate_hz: 1000
  groups:
    Demo.rg10:
      divisor: 100
      members:
        - {port: Demo.sensor.run, context: 3}
"""


@pytest.fixture
def parts(tmp_path, monkeypatch):
    (tmp_path / "topo_parts.py").write_text(PARTS)
    monkeypatch.syspath_prepend(str(tmp_path))
    yield tmp_path
    import sys
    sys.modules.pop("topo_parts", None)


def write(tmp_path, text, name="topology.yaml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def test_good_topology_builds_connects_and_runs(parts):
    dep = load_topology(write(parts, GOOD))
    topo = dep.topology
    sensor = topo.instance("Demo.sensor").component
    assert sensor.gain_hint == 4.5 and sensor.base_id == 0x1000
    assert topo.instance("Demo.rg10").component.queue.depth == 5
    assert "Demo.sensor.levelOut[0] -> Demo.display.levelIn[0]" in {str(c) for c in topo.connections}
    disp = topo.instance("Core.cmdDisp").component
    # Command pattern: registration and dispatch share one index per client.
    sensor.register_commands()
    disp.register_commands()
    index = disp.table[0x1000 + sensor.spec.command("PING").opcode]
    assert disp.output_port("compCmdSend").target_name(index) == "sensor.cmdIn[0]"
    assert disp.output_port("compCmdSend").target_name(disp.table[0x100]) == "cmdDisp.cmdIn[0]"
    assert sensor.output_port("timeCaller").target_name(0) == "time.timeGetPort[0]"
    assert sensor.output_port("prmGetOut").target_name(0) == "prm.getPrm[0]"
    # Rate group: 10 Hz from a 1 kHz base, context 3.
    dep.scheduler.drain_after_each_event(topo.instance("Demo.rg10").component)
    dep.timer.start(0)
    dep.scheduler.run(until_us=1_000_000)
    assert sensor.runs == [3] * 11


def test_dot_and_mermaid_export(parts):
    topo = load_topology(write(parts, GOOD)).topology
    dot = topo.to_dot()
    assert 'subgraph "cluster_Demo"' in dot
    assert '"Demo.sensor" -> "Demo.display" [label="levelOut[0] → levelIn[0]"]' in dot
    assert "timeGetPort" not in dot and "timeGetPort" in topo.to_dot(include_patterns=True)
    mermaid = topo.to_mermaid()
    assert mermaid.startswith("flowchart LR") and "subgraph Core" in mermaid
    assert '-->|"levelOut → levelIn"|' in mermaid


BAD = [
    ("unknown top key", GOOD.replace("patterns:", "patern:"),
     r"topology\.yaml:16: unknown key 'patern' in the topology file — did you mean 'patterns'\?"),
    ("unknown instance key", GOOD.replace("{type: topo_parts.Display, base_id: 0x2000}",
                                          "{type: topo_parts.Display, bse_id: 0x2000}"),
     r"topology\.yaml:15: unknown key 'bse_id' in instance Demo\.display — did you mean 'base_id'\?"),
    ("unknown module", GOOD.replace("topo_parts.Display", "topo_partz.Display"),
     r"topology\.yaml:15: instance Demo\.display: cannot import module 'topo_partz'"),
    ("unknown class", GOOD.replace("topo_parts.Display", "topo_parts.Dsplay"),
     r"topology\.yaml:15: instance Demo\.display: module 'topo_parts' has no 'Dsplay' — did you mean "
     r"'topo_parts\.Display'\?"),
    ("not a component", GOOD.replace("topo_parts.Display", "topo_parts.Level"),
     r"topology\.yaml:15: instance Demo\.display: type 'topo_parts\.Level' is not a component class"),
    ("unknown port", GOOD.replace("display.levelIn", "display.levelInn"),
     r"topology\.yaml:24: Display Demo\.display has no input port 'levelInn' — did you mean 'levelIn'\?"),
    ("type mismatch", GOOD.replace("display.levelIn", "display.otherIn"),
     r"topology\.yaml:24: cannot connect sensor\.levelOut\[0\] \(Demo\.Level\) to display\.otherIn\[0\] "
     r"\(Demo\.Other\): port types differ — connect ports of the same port type"),
    ("output connected twice", GOOD.replace("    - Demo.sensor.levelOut -> Demo.display.levelIn\n",
                                            "    - Demo.sensor.levelOut -> Demo.display.levelIn\n"
                                            "    - Demo.sensor.levelOut[0] -> Demo.display.levelIn\n"),
     r"topology\.yaml:25: cannot connect sensor\.levelOut\[0\] to display\.levelIn\[0\]: it is already "
     r"connected to display\.levelIn\[0\] — an output index connects to one input only"),
    ("id collision", GOOD.replace("base_id: 0x2000}", "base_id: 0x2000}\n      sensor2: {type: topo_parts.Sensor, "
                                                     "base_id: 0x1001}"),
     r"topology\.yaml:16: opcode 0x1001 of Demo\.sensor2\.GAIN_PRM_SET is also used by Demo\.sensor\.GAIN_PRM_SAVE "
     r"\(declared at .*topology\.yaml:14\) — give the instances base ids further apart"),
    ("required port unconnected", GOOD.replace("connections:\n  Readings:\n    - Demo.sensor.levelOut -> "
                                               "Demo.display.levelIn\n", ""),
     r"topology\.yaml:14: required output port Demo\.sensor\.levelOut\[0\] is not connected — connect it in "
     r"'connections'"),
    ("bad endpoint syntax", GOOD.replace("Demo.sensor.levelOut -> Demo.display.levelIn", "sensor.levelOut -> display"),
     r"topology\.yaml:24: 'sensor\.levelOut ' is not a port reference — write Module\.instance\.port"),
    ("unknown instance in connection", GOOD.replace("Demo.display.levelIn", "Demo.dsplay.levelIn"),
     r"topology\.yaml:24: unknown instance 'Demo\.dsplay' — did you mean 'Demo\.display'\?"),
    ("bad base id", GOOD.replace("base_id: 0x2000", "base_id: -4"),
     r"topology\.yaml:15: instance Demo\.display: base_id must be an integer in 0\.\.0xFFFFFFFF, got -4"),
    ("queue on passive", GOOD.replace("base_id: 0x2000}", "base_id: 0x2000, queue_size: 3}"),
     r"topology\.yaml:15: instance Demo\.display: Display is passive and has no queue — remove queue_size"),
    ("bad rate", GOOD.replace("base_rate_hz: 1000", "base_rate_hz: 0"),
     r"topology\.yaml:27: 'rate_groups\.base_rate_hz' must be a positive number \(Hz\)"),
    ("bad offset", GOOD.replace("divisor: 100", "divisor: 100\n      offset: 100"),
     r"topology\.yaml:31: rate group 'Demo\.rg10': offset must be an integer in 0\.\.99"),
    ("unknown resource", GOOD.replace("$clock", "$clok"),
     r"topology\.yaml:9: instance Core\.time: unknown resource '\$clok' — resources: \$clock, \$scheduler"),
    ("pattern to wrong instance", GOOD.replace("event: Core.events", "event: Core.tlm"),
     r"topology\.yaml:18: pattern 'event': Core\.tlm \(TlmStore\) lacks port\(s\) LogRecv"),
    ("invalid yaml", GOOD.replace("  Readings:\n", "  Readings: [\n"),
     r"topology\.yaml:\d+: invalid YAML: .* — fix the syntax"),
    ("bad constructor args", GOOD.replace("{gain_hint: 4.5}", "{gain_hnt: 4.5}"),
     r"topology\.yaml:14: instance Demo\.sensor: cannot create Sensor with args \['gain_hnt'\]"),
]


@pytest.mark.parametrize("why, text, message", BAD, ids=[b[0] for b in BAD])
def test_malformed_topologies_name_file_line_and_fix(parts, why, text, message):
    with pytest.raises(TopologyError) as err:
        load_topology(write(parts, text))
    assert any(__import__("re").search(message, p) for p in err.value.problems), \
        f"{why}: no problem matched {message!r} in {err.value.problems}"


def test_every_problem_is_reported_at_once(parts):
    text = GOOD.replace("bse", "x").replace("topo_parts.Display", "topo_parts.Nope").replace("patterns:", "patern:")
    with pytest.raises(TopologyError) as err:
        load_topology(write(parts, text))
    assert len(err.value.problems) >= 2
    assert str(err.value).startswith(f"{len(err.value.problems)} problems in the topology:")


def test_missing_file_and_non_mapping(parts):
    with pytest.raises(TopologyError, match=r"nope\.yaml: no such topology file"):
        load_topology(parts / "nope.yaml")
    with pytest.raises(TopologyError, match=r"topology\.yaml:1: the topology file must be a mapping, got a list"):
        load_topology(write(parts, "- a\n- b\n"))


def test_include_a_subtopology_module(parts):
    write(parts, """\
    instances:
      cmdDisp: {type: topo_parts.Dispatcher, base_id: 0x100}
      events: {type: topo_parts.Logger, base_id: 0x200}
      tlm: {type: topo_parts.TlmStore, base_id: 0x300}
      prm: {type: topo_parts.Prm, base_id: 0x400}
      time: {type: topo_parts.Clock, base_id: 0x500, args: {clock: $clock}}
    """, name="core.yaml")
    text = GOOD.replace("""  Core:
    instances:
      cmdDisp: {type: topo_parts.Dispatcher, base_id: 0x100}
      events: {type: topo_parts.Logger, base_id: 0x200}
      tlm: {type: topo_parts.TlmStore, base_id: 0x300}
      prm: {type: topo_parts.Prm, base_id: 0x400}
      time: {type: topo_parts.Clock, base_id: 0x500, args: {clock: $clock}}
""", """  Core:
    include: core.yaml
""")
    topo = load_topology(write(parts, text)).topology
    assert topo.instance("Core.cmdDisp").where.endswith("core.yaml:2")
    bad = text.replace("include: core.yaml", "include: missing.yaml")
    with pytest.raises(TopologyError, match=r"topology\.yaml:4: module 'Core': include file 'missing\.yaml' not found"):
        load_topology(write(parts, bad))


def test_health_pattern_pings_every_component_that_answers_pings():
    """FPP's health pattern: one PingSend/PingReturn index and one ping entry per answering instance;
    a component that stops answering is reported late."""
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology import HEALTH_FATAL_CYCLES, HEALTH_WARN_CYCLES

    loaded = load_topology(REFERENCE)
    topo = loaded.topology
    health = topo.instance("CdhCore.health").component
    names = [e.name for e in health.entries]
    # F´ v4 names a ping entry by the qualified instance name with '_' (F´'s Health suite commands
    # HLTH_PING_ENABLE FileHandling_fileManager)
    assert {"CdhCore_cmdDisp", "CdhCore_events", "CdhCore_tlmSend", "FileHandling_prmDb", "FileHandling_fileManager",
            "ReferenceDeployment_rateGroup50Hz", "ReferenceDeployment_cmdSeq"} <= set(names)
    assert "CdhCore_health" not in names
    assert all((e.warn_cycles, e.fatal_cycles) == (HEALTH_WARN_CYCLES, HEALTH_FATAL_CYCLES) for e in health.entries)
    index = names.index("ReferenceDeployment_cmdSeq")
    assert health.output_port("PingSend").target_name(index) == "cmdSeq.pingIn[0]"
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(10)
    assert health.warnings == 0
    seq = topo.instance("ReferenceDeployment.cmdSeq").component
    seq.output_port("pingOut").calls[0] = lambda key: None  # stops answering
    deployment.run_for(HEALTH_WARN_CYCLES + 1)
    assert health.warnings == 1
    assert [t.entry.name for t in health._trackers if t.cycle_count > 1] == ["ReferenceDeployment_cmdSeq"]


def test_options_for_a_role_no_resource_holds_are_refused(tmp_path):
    """TOPO-ROLE-001: role options (run --scenario …) on a topology without a resource of that role
    are an error naming the role, not silently ignored."""
    from fprime_lite.deploy.topology import TopologyError
    from fprime_lite.deploy.topology_loader import load_topology

    path = tmp_path / "t.yaml"
    path.write_text("deployment: Plain\nmodules:\n  Plain:\n    instances: {}\n")
    with pytest.raises(TopologyError, match="no resource holds the role 'simulation'"):
        load_topology(path, role_overrides={"simulation": {"scenario": "case_a"}})


def test_role_options_reach_the_resource_holding_the_role(tmp_path):
    """TOPO-ROLE-002: the simulation role's options reach the reference deployment's spacecraft,
    whatever the resource is called."""
    from fprime_lite.deploy.topology_loader import load_topology

    loaded = load_topology(REFERENCE, role_overrides={"simulation": {"settings": ["orbit.altitude_km=500"]}})
    assert loaded.resources["spacecraft"].scenario.orbit.altitude_km == 500
