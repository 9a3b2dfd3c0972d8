"""Start-up asks its parts what they declare, never probes them by name (issue 26).

Every component has the start-up hooks ``clean_temporary_files()`` and ``use_command_lookup()``
(no-ops by default); a resource takes part in software restarts by deriving from ``ResetLine``; the
start-up sequence goes into the sequencer's one input port of type ``Svc.CmdSeqIn``, whatever its name.
"""
from __future__ import annotations

import itertools
import sys

import pytest

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.deploy.topology import TopologyError

_names = itertools.count()

MODULE = """\
from fprime_lite import PassiveComponent, sync_command
from fprime_lite.deploy.resources import ResetLine, topology_resource
from fprime_lite.model.fw_ports import CmdSeqIn
from fprime_lite.model.ports import sync_input

SEEN = []


class Runner(PassiveComponent):
    \"\"\"A sequencer of its own: its run port is not called seqRunIn.\"\"\"

    @sync_input(CmdSeqIn)
    def startHere(self, file_name):
        SEEN.append(("run", file_name))

    @sync_command()
    def NOOP(self):
        pass

    def clean_temporary_files(self):
        SEEN.append(("clean", self.name))
        return []

    def use_command_lookup(self, lookup):
        SEEN.append(("lookup", lookup("Demo.runner.NOOP")[0]))


class Plain(PassiveComponent):
    \"\"\"Declares none of the hooks: the defaults do nothing.\"\"\"


@topology_resource
class Line(ResetLine):
    def attach_flight_software(self, deployment):
        SEEN.append(("attach", type(deployment).__name__))

    def flight_software_reset(self):
        SEEN.append(("reset", None))


@topology_resource
class LooksLikeALine:
    \"\"\"Has the methods but does not derive from ResetLine: not asked.\"\"\"

    def attach_flight_software(self, deployment):
        SEEN.append(("probed", None))

    def flight_software_reset(self):
        SEEN.append(("probed", None))
"""

TOPOLOGY = """\
deployment: Demo
modules:
  Demo:
    instances:
      driver: {{type: fprime_lite.svc.rate_group_driver.RateGroupDriver, base_id: 0x100}}
      rg: {{type: fprime_lite.svc.rate_groups.PassiveRateGroup, base_id: 0x200}}
      runner: {{type: {module}.Runner, base_id: 0x300}}
      plain: {{type: {module}.Plain, base_id: 0x400}}
rate_groups:
  driver: Demo.driver
  base_rate_hz: 10
  groups:
    Demo.rg: {{divisor: 1}}
resources:
  line: {{type: {module}.Line}}
  lookalike: {{type: {module}.LooksLikeALine}}
startup: {{sequencer: {sequencer}, sequence: start.seq}}
"""


@pytest.fixture
def demo(tmp_path, monkeypatch):
    module = f"startup_hooks_demo_{next(_names)}"
    (tmp_path / f"{module}.py").write_text(MODULE)
    monkeypatch.syspath_prepend(tmp_path)
    (tmp_path / "start.seq").write_text("")

    def write(sequencer="Demo.runner"):
        path = tmp_path / "topology.yaml"
        path.write_text(TOPOLOGY.format(module=module, sequencer=sequencer))
        return path

    yield module, write
    sys.modules.pop(module, None)


def test_start_calls_the_declared_hooks_and_runs_the_sequence_through_the_cmd_seq_in_port(demo):
    """START-001: the hooks a component declares are called; the start-up sequence enters through
    the sequencer's CmdSeqIn port (here ``startHere``); a ResetLine resource is attached and told of
    a restart, a resource that merely has the same method names is not."""
    module, write = demo
    loaded = load_topology(write())
    seen = sys.modules[module].SEEN
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(0.1)
    runner = loaded.topology.instance("Demo.runner").component
    assert seen[0] == ("clean", "runner")
    assert ("lookup", runner.base_id + runner.spec.command("NOOP").opcode) in seen
    assert [s for s in seen if s[0] in {"run", "attach", "probed"}] == [
        ("attach", "Deployment"), ("run", str(loaded.startup_sequence))]
    seen.clear()
    deployment.restart_software()
    deployment.run_for(0.1)
    assert [s for s in seen if s[0] in {"run", "reset", "attach", "probed"}] == [
        ("reset", None), ("run", str(loaded.startup_sequence))]


def test_the_default_hooks_do_nothing(demo):
    """START-002: a component that declares no hook takes the base class's no-ops."""
    _, write = demo
    plain = load_topology(write()).topology.instance("Demo.plain").component
    assert plain.clean_temporary_files() == []
    assert plain.use_command_lookup(lambda name: (0, [])) is None


def test_a_sequencer_without_a_cmd_seq_in_port_is_refused_at_load(demo):
    """START-003: 'startup.sequencer' naming a component with no CmdSeqIn input port is a load error
    naming the file and line, not a failure when the run starts."""
    _, write = demo
    path = write("Demo.plain")
    with pytest.raises(TopologyError) as err:
        load_topology(path)
    assert err.value.problems == [f"{path}:17: 'startup.sequencer' Demo.plain (Plain) needs exactly one input "
                                  f"port of type Svc.CmdSeqIn to take the start-up sequence — name a CmdSequencer"]


def test_the_sequencer_takes_the_deployments_command_table_unless_it_has_one(tmp_path):
    """START-004: CmdSequencer.use_command_lookup fills an empty command_lookup and keeps a given one."""
    from fprime_lite.svc.cmd_sequencer import CmdSequencer

    def given(name):
        return (1, [])

    def deployments(name):
        return (2, [])

    empty = CmdSequencer("seq", base_dir=tmp_path)
    empty.use_command_lookup(deployments)
    assert empty.command_lookup is deployments
    kept = CmdSequencer("seq", base_dir=tmp_path, command_lookup=given)
    kept.use_command_lookup(deployments)
    assert kept.command_lookup is given
