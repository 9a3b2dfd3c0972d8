"""Write ``svc_dictionary.json``: an F´ JSON dictionary (fpp-to-dict shape) of the standard services.

Used by ``tests/fprime_lite/svc/test_gds_compat.py`` to decode what the services send with
fprime-gds 4.4.1's own loaders and decoders. The committed JSON is the fixture; the test checks it
is still what this script produces, so regenerate it after changing a service's declarations::

    python tests/data/svc/make_svc_dictionary.py

Deployment ``SvcTest``: ``CdhCore.cmdDisp`` (base 0x100), ``CdhCore.events`` (0x200),
``FileHandling.prmDb`` (0x300) and a small ``SvcTest.demo`` component (0x1000) with channels,
events and parameters whose name order differs from their id order.
"""

from __future__ import annotations

import json
import pathlib
import sys

from fprime_lite import (F64, U8, U32, Channel, Event, FwEnum, Param, PassiveComponent, Severity,
                         String)
from fprime_lite.svc.cmd_dispatcher import CmdDispatcher
from fprime_lite.svc.event_manager import EventManager
from fprime_lite.svc.prm_db import PrmDb

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "svc_dictionary.json"
MINIMAL = HERE.parent / "gds" / "minimal_dictionary.json"


class DemoMode(FwEnum, namespace="SvcTestTypes", rep=U8):
    SAFE = 0
    NOMINAL = 1
    SCIENCE = 2


class Demo(PassiveComponent):
    """Channels, events and parameters of assorted types for the decoding tests."""

    Temperature = Channel(F64, format="{.2f}")
    Mode = Channel(DemoMode)
    Label = Channel(String(20))
    Count = Channel(U32)

    Reading = Event(Severity.ACTIVITY_HI, "Reading {.2f} in mode {} labelled {}",
                    args=[("celsius", F64), ("mode", DemoMode), ("label", String(20))])
    Alarm = Event(Severity.FATAL, "Alarm code {}", args=[("code", U32)])
    Chatter = Event(Severity.DIAGNOSTIC, "Chatter {}", args=[("n", U32)])

    ZETA = Param(U32, default=1)
    ALPHA = Param(F64, default=0.5)
    NAME = Param(String(16), default="x")


#: (qualified instance name, component class, base id, constructor kwargs)
INSTANCES = [
    ("CdhCore.cmdDisp", CmdDispatcher, 0x100),
    ("CdhCore.events", EventManager, 0x200),
    ("FileHandling.prmDb", PrmDb, 0x300),
    ("SvcTest.demo", Demo, 0x1000),
]

#: Framework type names copied from the GDS-verified minimal dictionary.
_FRAMEWORK_TYPES = {"FwIdType", "FwOpcodeType", "FwChanIdType", "FwEventIdType", "FwPrmIdType",
                    "FwPacketDescriptorType", "FwSizeStoreType", "FwTimeBaseStoreType",
                    "FwTimeContextStoreType", "FwTlmPacketizeIdType", "TimeBase", "ComCfg.Apid"}


def make_instance(cls, name, base_id):
    if cls is PrmDb:
        return cls(name, "unused.dat", base_id=base_id)
    return cls(name, base_id=base_id)


def _params(arg_list):
    return [{"name": n, "type": t.json_ref(), "ref": False} for n, t in arg_list]


def _collect(t, types: dict) -> None:
    for dep in t.dependencies():
        _collect(dep, types)
    definition = t.json_definition()
    if definition is not None and definition["qualifiedName"] not in types:
        types[definition["qualifiedName"]] = definition


def build() -> dict:
    minimal = json.loads(MINIMAL.read_text())
    types: dict[str, dict] = {d["qualifiedName"]: d for d in minimal["typeDefinitions"]
                              if d["qualifiedName"] in _FRAMEWORK_TYPES}
    commands, events, channels, parameters = [], [], [], []
    for qualified, cls, base in INSTANCES:
        comp = make_instance(cls, qualified.rsplit(".", 1)[1], base)
        spec = comp.spec
        for c in spec.commands:
            for _, t in c.args:
                _collect(t, types)
            commands.append({"name": f"{qualified}.{c.name}", "commandKind": c.kind,
                             "opcode": base + c.opcode, "formalParams": _params(c.args),
                             "priority": c.priority, "queueFullBehavior": c.queue_full})
        for e in spec.events:
            for _, t in e.args:
                _collect(t, types)
            entry = {"name": f"{qualified}.{e.name}", "severity": e.severity.name,
                     "id": base + e.local_id, "formalParams": _params(e.args), "format": e.format}
            if e.throttle is not None:
                entry["throttle"] = e.throttle
            events.append(entry)
        for ch in spec.channels:
            _collect(ch.type, types)
            entry = {"name": f"{qualified}.{ch.name}", "type": ch.type.json_ref(),
                     "id": base + ch.local_id, "telemetryUpdate": ch.update}
            if ch.format is not None:
                entry["format"] = ch.format
            channels.append(entry)
        for p in spec.params:
            _collect(p.type, types)
            parameters.append({"name": f"{qualified}.{p.name}", "type": p.type.json_ref(),
                               "id": base + p.local_id, "default": p.type.json_value(p.default)})
    return {
        "metadata": {"deploymentName": "SvcTest", "frameworkVersion": "4.0.0",
                     "projectVersion": "0.1.0", "libraryVersions": [], "dictionarySpecVersion": "1.0.0"},
        "typeDefinitions": list(types.values()),
        "constants": minimal["constants"],
        "commands": commands,
        "parameters": parameters,
        "events": events,
        "telemetryChannels": channels,
        "records": [],
        "containers": [],
        "telemetryPacketSets": [],
    }


def render() -> str:
    return json.dumps(build(), indent=1) + "\n"


if __name__ == "__main__":
    OUT.write_text(render())
    print(f"wrote {OUT}", file=sys.stderr)
