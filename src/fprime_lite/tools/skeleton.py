"""``fprime-lite new component NAME`` / ``new deployment NAME``: skeletons that pass their own tests.

A component skeleton is three files in the chosen folder: ``<name>.py`` (a passive component with a
rate-group input, one command, one event, one channel and one parameter), ``test_<name>.py`` (its
harness test) and ``<name>.md`` (a documentation stub); with ``--fpp``, ``<name>.fpp`` (the same
component in FPP), ``<name>.py`` (its handlers only) and ``test_<name>.py``. A deployment skeleton is a new folder
``NAME/`` holding a component skeleton (``--component``, default ``Counter``), ``topology.yaml``
(CdhCore's command, event and telemetry services, a time source, and a 1 Hz rate group driving the
component and the telemetry channelizer), ``test_<name>_deployment.py`` (flies the topology for a few
simulated seconds through :func:`fprime_lite.tools.run`) and ``README.md``. In a deployment skeleton
the component's files and both tests carry the deployment's name (``my_sat_counter.py``,
``test_my_sat_counter.py``, ``test_my_sat_deployment.py``), so several skeletons live in one project and
one ``python -m pytest`` runs them all. ``python -m pytest`` in the folder passes right away. Nothing
existing is overwritten.
"""
from __future__ import annotations

import keyword
import pathlib
import re

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["SkeletonError", "new_component", "new_deployment", "module_name"]


class SkeletonError(FprimeLiteError):
    """The skeleton cannot be written (bad name, existing file, missing folder)."""


def module_name(class_name: str) -> str:
    """``MyHeater`` → ``my_heater``."""
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])", "_", class_name).lower()


def _check_name(name: str, what: str) -> None:
    if not name.isidentifier() or keyword.iskeyword(name) or not name[0].isupper():
        raise SkeletonError(f"{what} name {name!r} must be a Python class name starting with a capital "
                            f"letter (letters, digits, _), e.g. MyHeater")


_COMPONENT = '''"""{name}: a passive component (skeleton written by ``fprime-lite new component``).

Each tick of its rate group it adds ``STEP`` to a counter, writes it to the ``Count`` channel and
logs ``Counted``; the ``RESET`` command sets the counter back to zero. Replace the behaviour with
yours and keep the test beside it passing (docs: {module}.md).
"""
from fprime_lite import (U32, Channel, CmdResponse, Event, Param, PassiveComponent, Sched, Severity,
                         sync_command, sync_input)


class {name}(PassiveComponent):
    STEP = Param(U32, default=1)                                 # STEP_PRM_SET / STEP_PRM_SAVE
    Counted = Event(Severity.ACTIVITY_LO, "Count is now {{}}", count=U32)
    Count = Channel(U32)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.count = 0

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """Rate-group tick."""
        self.count += self.STEP.value
        self.Count.write(self.count)
        self.Counted(self.count)

    @sync_command()
    def RESET(self) -> CmdResponse:  # noqa: N802 - F´ command names are upper case
        """Set the counter back to zero."""
        self.count = 0
        return CmdResponse.OK
'''

#: the harness test both skeletons share (the FPP one adds a check of the FPP's opcodes)
_TEST_BODY = '''def test_each_tick_adds_step_and_reset_clears(fprime_harness):
    h = fprime_harness({name}("{instance}", base_id=0x1000))
    h.load_parameters()                                  # STEP takes its default, 1
    h.invoke("run", 0)
    h.invoke("run", 0)
    h.assert_tlm("Count", 1, 2)
    h.assert_event("Counted", 1, 2)
    h.send_command("RESET")
    h.assert_cmd_response(0, "RESET", CmdResponse.OK)
    h.param_set("STEP", 5, ParamValid.VALID)
    h.load_parameters()
    h.invoke_to_run(0, 0)                                # F´'s spelling: invoke_to_<port>(portNum, args)
    h.assertTlm_Count(2, 5)
'''

_COMPONENT_TEST = '''"""The harness test of {name} (skeleton written by ``fprime-lite new component``)."""
from fprime_lite import CmdResponse, ParamValid

from {module} import {name}


''' + _TEST_BODY

_COMPONENT_DOC = '''# {name}

Skeleton written by `fprime-lite new component {name}`: say here what the component is for.

| member | kind | meaning |
|---|---|---|
| `run` | `Svc.Sched` sync input | one rate-group tick: adds `STEP` to the counter |
| `RESET` | sync command | sets the counter to zero |
| `Counted` | ACTIVITY_LO event | the counter after a tick |
| `Count` | U32 channel | the counter |
| `STEP` | U32 parameter, default 1 | added each tick |

Test: `python -m pytest test_{module}.py`.
'''

_TOPOLOGY = '''# {deployment}: skeleton written by `fprime-lite new deployment {deployment}` (docs/topology.md).
deployment: {deployment}
modules:
  CdhCore:
    include: fprime_lite:subtopologies/cdh_core.yaml     # cmdDisp, events, tlmSend, textLogger, …
  {deployment}:
    instances:
      rateGroupDriver: {{type: fprime_lite.svc.rate_group_driver.RateGroupDriver, base_id: 0x10000000}}
      rateGroup1Hz: {{type: fprime_lite.svc.rate_groups.ActiveRateGroup, base_id: 0x10001000, queue_size: 10}}
      timeSource: {{type: fprime_lite.svc.time_source.TimeSource, base_id: 0x10002000, args: {{clock: $clock}}}}
      {instance}: {{type: {module}.{component}, base_id: 0x10010000}}   # {module}.py beside this file
patterns:
  command: CdhCore.cmdDisp
  event: CdhCore.events
  telemetry: CdhCore.tlmSend
  time: {deployment}.timeSource
rate_groups:
  driver: {deployment}.rateGroupDriver
  base_rate_hz: 10
  groups:
    {deployment}.rateGroup1Hz:
      divisor: 10
      members:
        - {deployment}.{instance}.run
        - CdhCore.tlmSend.Run
'''

_DEPLOYMENT_TEST = '''"""Fly {deployment} for a few simulated seconds.

Skeleton written by ``fprime-lite new deployment``.
"""
import pathlib

from fprime_lite.tools import run

HERE = pathlib.Path(__file__).parent


def test_the_deployment_flies(tmp_path):
    result = run(HERE / "topology.yaml", duration_s=5, out=tmp_path / "run")
    assert result.ok, result.problems
    counts = result.telemetry["{deployment}.{instance}.Count"]
    assert counts.iloc[-1] == 6                          # ticks at t = 0, 1, …, 5 s with STEP = 1
    assert (result.events.name == "{deployment}.{instance}.Counted").sum() == 6
'''

_DEPLOYMENT_README = '''# {deployment}

Skeleton written by `fprime-lite new deployment {deployment}`.

    python -m pytest                       # the component's harness test and a short flight
    fprime-lite check topology.yaml
    fprime-lite run topology.yaml --duration 60

`{module}.py` is the component (`{module}.md`), `topology.yaml` wires it to CdhCore and a 1 Hz rate
group; the run writes `runs/<timestamp>/` (see fprime-lite's docs/outputs.md).
'''


#: the special ports of an FPP component with commands, events, telemetry and parameters (as F´'s
#: components spell them), indented for a component body
FPP_SPECIAL_PORTS = """    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
"""

_FPP_COMPONENT = """module Components {{

  @ {name}: a passive component (skeleton written by fprime-lite new component --fpp).
  @ Each rate-group tick adds STEP to a counter, writes Count and logs Counted; RESET zeroes it.
  @ The behaviour is in {module}.py (handlers only); this file is its interface.
  passive component {name} {{

""" + FPP_SPECIAL_PORTS + """
    @ One rate-group tick
    sync input port run: Svc.Sched

    @ Set the counter back to zero
    sync command RESET opcode 0x0

    @ The counter after a tick
    event Counted(count: U32) severity activity low id 0x0 format "Count is now {{}}"

    @ The counter
    telemetry Count: U32 id 0x0 update on change

    @ Added to the counter each tick
    param STEP: U32 default 1 id 0x0 set opcode 0x1 save opcode 0x2

  }}

}}
"""

_FPP_HANDLERS = '''"""{name}'s behaviour: handlers only, as a .cpp has them; the interface is {module}.fpp.

fprime-lite binds this class to the FPP component ``Components.{name}`` by the naming rule (class
{name} in {module}.py beside {module}.fpp) and declares what the FPP declares (docs/fpp.md of
fprime-lite). The members (``self.STEP``, ``self.Count``, ``self.Counted``) come from the FPP.
"""
from fprime_lite import CmdResponse, PassiveComponent


class {name}(PassiveComponent):
    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.count = 0

    def run(self, context: int) -> None:
        """Rate-group tick (input port run: Svc.Sched)."""
        self.count += self.STEP.value
        self.Count.write(self.count)
        self.Counted(self.count)

    def RESET(self) -> CmdResponse:  # noqa: N802 - F´ command names are upper case
        """Command RESET: set the counter back to zero."""
        self.count = 0
        return CmdResponse.OK
'''

_FPP_TEST = '''"""The harness test of {name} (skeleton written by ``fprime-lite new component --fpp``)."""
import pathlib

from fprime_lite import CmdResponse, ParamValid
from fprime_lite.deploy.fpp.loader import component_class

#: {name} as {module}.fpp declares it, with the handlers of {module}.py
{name} = component_class(pathlib.Path(__file__).with_name("{module}.fpp"))


''' + _TEST_BODY + '''    assert h.component.opcode("STEP_PRM_SET") == 0x1001  # the opcodes the FPP gives
'''


def _write_new(files: dict[pathlib.Path, str]) -> list[pathlib.Path]:
    existing = [str(p) for p in files if p.exists()]
    if existing:
        raise SkeletonError(f"{', '.join(existing)} already exist(s) — choose another name or folder; "
                            f"nothing was written")
    for path, text in files.items():
        path.write_text(text, encoding="utf-8")
    return list(files)


def _component_files(name: str, folder: pathlib.Path, module: str | None = None) -> dict[pathlib.Path, str]:
    module = module or module_name(name)
    fields = {"name": name, "module": module, "instance": name[0].lower() + name[1:]}
    return {folder / f"{module}.py": _COMPONENT.format(**fields),
            folder / f"test_{module}.py": _COMPONENT_TEST.format(**fields),
            folder / f"{module}.md": _COMPONENT_DOC.format(**fields)}


def new_component(name: str, folder=".", *, fpp: bool = False) -> list[pathlib.Path]:
    """Write the skeleton of component ``name`` into ``folder`` (which must exist); with ``fpp``, its
    interface as ``<name>.fpp`` and a Python class with the handlers only (docs/fpp.md)."""
    _check_name(name, "component")
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise SkeletonError(f"{folder}: no such folder — create it first or give --dir")
    if not fpp:
        return _write_new(_component_files(name, folder))
    module = module_name(name)
    fields = {"name": name, "module": module, "instance": name[0].lower() + name[1:]}
    return _write_new({folder / f"{module}.fpp": _FPP_COMPONENT.format(**fields),
                       folder / f"{module}.py": _FPP_HANDLERS.format(**fields),
                       folder / f"test_{module}.py": _FPP_TEST.format(**fields)})


def new_deployment(name: str, parent=".", component: str = "Counter") -> list[pathlib.Path]:
    """Create folder ``parent/name`` holding a deployment skeleton with one ``component``."""
    _check_name(name, "deployment")
    _check_name(component, "component")
    parent = pathlib.Path(parent)
    if not parent.is_dir():
        raise SkeletonError(f"{parent}: no such folder — create it first or give --dir")
    folder = parent / name
    if folder.exists():
        raise SkeletonError(f"{folder} already exists — choose another name; nothing was written")
    # every module and test file is named after the deployment too: two skeletons in one project
    # must not share a test file name (pytest refuses two test_deployment.py) or a module name (the
    # second `from counter import Counter` would get the first folder's)
    module = f"{module_name(name)}_{module_name(component)}"
    fields = {"deployment": name, "component": component, "module": module,
              "instance": component[0].lower() + component[1:]}
    files = _component_files(component, folder, module)
    files[folder / "topology.yaml"] = _TOPOLOGY.format(**fields)
    files[folder / f"test_{module_name(name)}_deployment.py"] = _DEPLOYMENT_TEST.format(**fields)
    files[folder / "README.md"] = _DEPLOYMENT_README.format(**fields)
    folder.mkdir()
    return _write_new(files)
