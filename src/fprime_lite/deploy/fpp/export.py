"""Write fprime-lite components, types, ports and topologies as FPP text.

The inverse of :mod:`fprime_lite.deploy.fpp.loader`: what a component class declares (its
:class:`~fprime_lite.model.component.ComponentSpec`, with the ids the framework assigned) becomes an
FPP component definition with every id, opcode, severity, format, throttle, limit and default
written out, so that ``fpp-to-dict`` and ``fprime-lite dict`` build the same dictionary from it.
The reference deployments' FPP (``deployments/*/fpp/``) and the Svc definitions of the framework
(``framework/svc.fpp``) are written by it and checked against their Python sources by the tests
(``python -m fprime_lite.deploy.fpp.export --help``).
"""

from __future__ import annotations

import argparse
from decimal import Decimal
import math
import pathlib
import sys
from collections import defaultdict
from typing import Any, Iterable

from fprime_lite.deploy.dictionary import param_annotation
from fprime_lite.model.component import Component, ComponentSpec
from fprime_lite.model.errors import DeclarationError
from fprime_lite.model.events import Severity
from fprime_lite.model.ports import PortType
from fprime_lite.model.types import (AliasType, ArrayType, BoolType, EnumType, FloatType, FwType, IntType,
                                     StringType, StructType, fw_type)

__all__ = ["FRAMEWORK_DIR", "SVC_COMPONENT_NAMES", "HAND_WRITTEN_NAMES", "HAND_WRITTEN_PORTS", "fpp_name_of",
           "export_components", "export_topology", "default_out_dir", "fpp_type_name", "fpp_value", "framework_files"]

#: Where the framework's FPP (config.fpp, ports.fpp, svc.fpp) is installed with the package.
FRAMEWORK_DIR = pathlib.Path(__file__).with_name("framework")

#: fprime-lite's services and the F´ component each implements (the FPP names a topology uses).
SVC_COMPONENT_NAMES = {
    "fprime_lite.svc.cmd_dispatcher.CmdDispatcher": "Svc.CommandDispatcher",
    "fprime_lite.svc.cmd_sequencer.CmdSequencer": "Svc.CmdSequencer",
    "fprime_lite.svc.event_manager.EventManager": "Svc.EventManager",
    "fprime_lite.svc.file_downlink.FileDownlink": "Svc.FileDownlink",
    "fprime_lite.svc.file_manager.FileManager": "Svc.FileManager",
    "fprime_lite.svc.file_uplink.FileUplink": "Svc.FileUplink",
    "fprime_lite.svc.health.Health": "Svc.Health",
    "fprime_lite.svc.prm_db.PrmDb": "Svc.PrmDb",
    "fprime_lite.svc.rate_group_driver.RateGroupDriver": "Svc.RateGroupDriver",
    "fprime_lite.svc.rate_groups.ActiveRateGroup": "Svc.ActiveRateGroup",
    "fprime_lite.svc.text_logger.TextLogger": "Svc.PassiveTextLogger",
    "fprime_lite.svc.time_source.TimeSource": "Svc.PosixTime",
    "fprime_lite.svc.tlm_chan.TlmChan": "Svc.TlmChan",
    "fprime_lite.svc.tlm_packetizer.TlmPacketizer": "Svc.TlmPacketizer",
    "fprime_lite.svc.version.Version": "Svc.Version",
}

#: Types the hand-written framework files (config.fpp, ports.fpp) define.
HAND_WRITTEN_NAMES = frozenset({
    "TimeBase", "ComCfg.Apid", "Fw.TimeValue", "Fw.TlmValid", "Fw.ParamValid",
    "FwIdType", "FwOpcodeType", "FwChanIdType", "FwEventIdType", "FwPrmIdType", "FwPacketDescriptorType",
    "FwSizeStoreType", "FwTimeBaseStoreType", "FwTimeContextStoreType", "FwTlmPacketizeIdType"})
#: Port types ports.fpp defines (FPP keeps port and type names apart: Fw.CmdResponse is both).
HAND_WRITTEN_PORTS = frozenset({
    "Fw.Cmd", "Fw.CmdReg", "Fw.CmdResponse", "Fw.Log", "Fw.LogText", "Fw.Tlm", "Fw.TlmGet", "Fw.PrmGet",
    "Fw.PrmSet", "Fw.Time", "Fw.Com", "Fw.BufferSend", "Fw.Signal", "Svc.Sched", "Svc.Cycle", "Svc.Ping",
    "Svc.FatalEvent", "Svc.CmdSeqIn", "Svc.CmdSeqCancel", "Svc.WatchDog", "Svc.FileAnnounce", "Svc.Version",
})

_SEVERITY = {Severity.FATAL: "fatal", Severity.WARNING_HI: "warning high", Severity.WARNING_LO: "warning low",
             Severity.COMMAND: "command", Severity.ACTIVITY_HI: "activity high",
             Severity.ACTIVITY_LO: "activity low", Severity.DIAGNOSTIC: "diagnostic"}
_SPECIAL_FPP = {"command recv": "command recv", "command reg": "command reg", "command resp": "command resp",
                "event": "event", "text event": "text event", "telemetry": "telemetry",
                "param get": "param get", "param set": "param set", "time get": "time get"}
#: FPP keywords that a name must be written with a ``$`` before.
_KEYWORDS = frozenset("""action active activity always array assert async at base block change choice command
component connections constant container cpu default diagnostic do drop else enter entry event exit external
false fatal format get guard guarded health high hook id if import include initial input instance interface
internal locate low match matching on opcode orange output packet packets param passive phase port priority
private product queue queued record recv red ref reg request resp save serial set severity signal size stack
state struct sync telemetry text throttle time topology true type update warning with yellow""".split())


def _ident(name: str) -> str:
    return f"${name}" if name in _KEYWORDS else name


def _qualified(name: str) -> str:
    return ".".join(_ident(part) for part in name.split("."))


def _string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def fpp_name_of(cls: type) -> str:
    """The FPP qualified name of component class ``cls``: ``__fprime_fpp_name__`` if the class
    sets it, the F´ name of a service (:data:`SVC_COMPONENT_NAMES`), else ``Components.<class>``."""
    explicit = cls.__dict__.get("__fprime_fpp_name__")
    if isinstance(explicit, str):
        return explicit
    return SVC_COMPONENT_NAMES.get(f"{cls.__module__}.{cls.__qualname__}", f"Components.{cls.__name__}")


def fpp_type_name(t: Any) -> str:
    """How FPP names type ``t`` where it is used (``U32``, ``string size 40``, ``Components.Vector3``)."""
    ft = fw_type(t)
    if isinstance(ft, StringType):
        return f"string size {ft.size}"
    if isinstance(ft, (IntType, FloatType, BoolType)):
        return ft.name
    if ft.name == "Fw.Time":
        return "Fw.TimeValue"
    return _qualified(ft.name)


def fpp_value(t: FwType[Any], value: Any) -> str:
    """``value`` of type ``t`` as an FPP expression."""
    return _json_expr(t, t.json_value(value))


def _json_expr(t: FwType[Any], value: Any) -> str:
    while isinstance(t, AliasType):
        t = t.target
    if isinstance(t, BoolType):
        return "true" if value else "false"
    if isinstance(t, FloatType):
        value = float(value)
        if not math.isfinite(value):
            raise ValueError(f"FPP has no literal for the float {value!r}")
        text = f"{Decimal(repr(value)):f}"  # no exponent: fpp-python's lexer refuses 5.5e-05
        return text if "." in text else text + ".0"
    if isinstance(t, IntType):
        return str(int(value))
    if isinstance(t, StringType):
        return _string(str(value))
    if isinstance(t, EnumType):
        return _qualified(str(value))
    if isinstance(t, ArrayType):
        return "[" + ", ".join(_json_expr(t.elem, v) for v in value) + "]"
    if isinstance(t, StructType):
        return "{ " + ", ".join(f"{_ident(n)} = {_json_expr(mt, value[n])}" for n, mt in t.members) + " }"
    if t.kind == "time" and isinstance(value, dict):
        return "{ " + ", ".join(f"{_ident(k)} = {_qualified(v) if isinstance(v, str) else v}"
                                for k, v in value.items()) + " }"
    raise ValueError(f"no FPP expression for a value of {t.name}")


def _type_definition(t: FwType[Any], short: str) -> str:
    if isinstance(t, AliasType):
        return f"type {_ident(short)} = {fpp_type_name(t.target)}"
    if isinstance(t, EnumType):
        constants = "\n".join(f"  {_ident(m.name)} = {int(m)}" for m in t.cls)
        return (f"enum {_ident(short)} : {t.rep.name} {{\n{constants}\n}} default "
                f"{_ident(str(t.json_value(t.default)).rsplit('.', 1)[1])}")
    if isinstance(t, StructType):
        members = "\n".join(f"  {_ident(n)}: {fpp_type_name(mt)}" for n, mt in t.members)
        return f"struct {_ident(short)} {{\n{members}\n}} default {fpp_value(t, t.default)}"
    if isinstance(t, ArrayType):
        return f"array {_ident(short)} = [{t.size}] {fpp_type_name(t.elem)} default {fpp_value(t, t.default)}"
    raise ValueError(f"{t.name} is not a named type")


def _as_fw_type(t: Any) -> FwType[Any] | None:
    try:
        return fw_type(t)
    except DeclarationError:
        return None


def _port_definition(port: PortType, short: str) -> str:
    """An FPP port definition; an argument or return value whose Python type is not an F´ type
    (a ``Result`` tuple, ``bytes``) is left out and named in the definition's annotation."""
    kept = [(n, t) for n, t in port.args if _as_fw_type(t) is not None]
    left_out = [n for n, t in port.args if _as_fw_type(t) is None]
    returns = _as_fw_type(port.returns) if port.returns is not None else None
    if port.returns is not None and returns is None:
        left_out.append(f"the return value ({getattr(port.returns, '__name__', port.returns)})")
    params = ", ".join(f"{_ident(n)}: {fpp_type_name(t)}" for n, t in kept)
    ret = f" -> {fpp_type_name(returns)}" if returns is not None else ""
    note = (f"@ fprime-lite: not F´ types in Python, left out here: {', '.join(left_out)}\n" if left_out else "")
    return note + (f"port {_ident(short)}({params}){ret}" if params else f"port {_ident(short)}{ret}")


def _formal(args: Iterable[tuple[str, Any]]) -> str:
    args = list(args)
    return "(" + ", ".join(f"{_ident(n)}: {fpp_type_name(t)}" for n, t in args) + ")" if args else ""


def _component_body(spec: ComponentSpec) -> list[str]:
    lines: list[str] = []
    special_names = set(spec.special.values())
    for kind, name in spec.special.items():
        lines.append(f"{_SPECIAL_FPP[kind]} port {_ident(name)}")
    for name, decl in spec.inputs.items():
        if name in special_names:
            continue
        size = f"[{decl.size}] " if decl.size != 1 else ""
        extra = ""
        if decl.kind == "async":
            extra = f" priority {decl.priority} {decl.queue_full}"
        lines.append(f"{decl.kind} input port {_ident(name)}: {size}{_qualified(decl.port_type.name)}{extra}")
    for name, out in spec.outputs.items():
        if name in special_names:
            continue
        size = f"[{out.size}] " if getattr(out, "size", 1) != 1 else ""
        lines.append(f"output port {_ident(name)}: {size}{_qualified(out.port_type.name)}")
    for c in spec.commands:
        if c.kind in ("set", "save"):
            continue
        extra = f" priority {c.priority} {c.queue_full}" if c.kind == "async" else ""
        lines.append(f"{c.kind} command {_ident(c.name)}{_formal(c.args)} opcode 0x{c.opcode:X}{extra}")
    for e in spec.events:
        throttle = f" throttle {e.throttle}" if e.throttle is not None else ""
        lines.append(f"event {_ident(e.name)}{_formal(e.args)} severity {_SEVERITY[e.severity]} "
                     f"id 0x{e.local_id:X} format {_string(e.format)}{throttle}")
    for ch in spec.channels:
        parts = [f"telemetry {_ident(ch.name)}: {fpp_type_name(ch.type)} id 0x{ch.local_id:X}",
                 f"update {ch.update}"]
        if ch.format is not None:
            parts.append(f"format {_string(ch.format)}")
        for side, levels in (("low", ch.low), ("high", ch.high)):
            if levels:
                parts.append(f"{side} {{ " + ", ".join(f"{level} {_json_expr(ch.type, v)}"
                                                       for level, v in levels.items()) + " }")
        lines.append(" ".join(parts))
    for p in spec.params:
        set_cmd = spec.command(f"{p.name.upper()}_PRM_SET")
        save_cmd = spec.command(f"{p.name.upper()}_PRM_SAVE")
        default = f" default {fpp_value(p.type, p.default)}" if p.has_default else ""
        if p.units is not None:  # the dictionary's parameter annotation (deploy/dictionary.py)
            lines.append(f"@ {param_annotation(p.units)}")
        lines.append(f"param {_ident(p.name)}: {fpp_type_name(p.type)}{default} id 0x{p.local_id:X} "
                     f"set opcode 0x{set_cmd.opcode:X} save opcode 0x{save_cmd.opcode:X}")
    return lines


class _Writer:
    """Collects definitions by FPP module and writes them nested."""

    def __init__(self) -> None:
        self.modules: dict[tuple[str, ...], list[str]] = defaultdict(list)

    def add(self, qualified: str, text: str) -> None:
        *module, _ = qualified.split(".")
        self.modules[tuple(module)].append(text)

    def text(self) -> str:
        out: list[str] = []
        for module in sorted(self.modules):
            depth = len(module)
            for level, part in enumerate(module):
                out.append("  " * level + f"module {_ident(part)} {{")
            for block in self.modules[module]:
                out.extend("  " * depth + line if line else "" for line in block.splitlines())
                out.append("")
            if out and out[-1] == "":
                out.pop()
            for level in reversed(range(depth)):
                out.append("  " * level + "}")
            out.append("")
        return "\n".join(out)


def _named_types(t: FwType[Any], found: dict[str, FwType[Any]]) -> None:
    if t.json_definition() is None or t.name in found:
        return
    found[t.name] = t
    for dep in t.dependencies():
        _named_types(dep, found)


def _spec_types(spec: ComponentSpec) -> list[FwType[Any]]:
    types: list[FwType[Any]] = []
    for c in spec.commands:
        types += [t for _, t in c.args]
    for e in spec.events:
        types += [t for _, t in e.args]
    types += [ch.type for ch in spec.channels] + [p.type for p in spec.params]
    for decl in list(spec.inputs.values()) + list(spec.outputs.values()):
        port = decl.port_type
        if port.name in HAND_WRITTEN_PORTS:
            continue
        types += [ft for ft in (_as_fw_type(t) for _, t in port.args) if ft is not None]
        returned = _as_fw_type(port.returns) if port.returns is not None else None
        if returned is not None:
            types.append(returned)
    return types


#: F´'s port matching (``match A with B``: the connections of A and B at one index go to one
#: component): the dispatcher sends a command on the index its opcodes were registered at, Health
#: pings on the index the answer comes back at. fprime-lite's patterns number them so too.
PORT_MATCHES = {"Svc.CommandDispatcher": [("compCmdSend", "compCmdReg")], "Svc.Health": [("PingSend", "PingReturn")]}


def export_components(classes: Iterable[type[Component]], *, skip: frozenset[str] = HAND_WRITTEN_NAMES,
                      skip_ports: frozenset[str] = HAND_WRITTEN_PORTS, also: Iterable[FwType[Any]] = ()) -> str:
    """FPP text defining ``classes``, the named types and port types they use and the types ``also``,
    except the types named in ``skip`` and the ports named in ``skip_ports`` (defined elsewhere)."""
    writer = _Writer()
    types: dict[str, FwType[Any]] = {}
    for t in also:
        _named_types(t, types)
    ports: dict[str, PortType] = {}
    components: dict[str, tuple[type, ComponentSpec]] = {}
    for cls in classes:
        spec = cls.__fprime_spec__
        components[fpp_name_of(cls)] = (cls, spec)
        for t in _spec_types(spec):
            _named_types(t, types)
        for decl in list(spec.inputs.values()) + list(spec.outputs.values()):
            ports.setdefault(decl.port_type.name, decl.port_type)

    def skipped(name: str) -> bool:
        return name in skip or name == "Fw.Time"

    nested: dict[str, list[str]] = defaultdict(list)
    for name, t in sorted(types.items()):
        if skipped(name):
            continue
        owner, short = name.rsplit(".", 1) if "." in name else ("", name)
        if owner in components:
            nested[owner].append(_type_definition(t, short))
        else:
            writer.add(name, _type_definition(t, short))
    for name, port in sorted(ports.items()):
        if name in skip_ports:
            continue
        writer.add(name, _port_definition(port, name.rsplit(".", 1)[-1]))
    for name, (cls, spec) in components.items():
        body = nested[name] + _component_body(spec) + [f"match {a} with {b}" for a, b in PORT_MATCHES.get(name, ())]
        inner = "\n".join("  " + line if line else "" for block in body for line in block.splitlines())
        dotted = f"{cls.__module__}.{cls.__qualname__}"
        binding = "" if dotted in SVC_COMPONENT_NAMES else f"@ fprime-lite: {dotted}\n"  # loader.py's rule 2
        writer.add(name, f"{binding}{spec.kind} component {_ident(name.rsplit('.', 1)[-1])} {{\n{inner}\n}}")
    return writer.text()


def export_topology(topology: Any, *, name: str | None = None) -> str:
    """FPP text of ``topology``'s instances (base ids, queue sizes) and of a topology that lists
    them with every connection (``fprime_lite.deploy.topology.Topology``)."""
    writer = _Writer()
    for instance in topology.instances.values():
        comp = instance.component
        queue = getattr(comp, "_queue", None)
        size = f" queue size {queue.depth}" if queue is not None else ""
        writer.add(instance.qualified_name, f"instance {_ident(comp.name)}: {_qualified(fpp_name_of(type(comp)))} "
                                            f"base id 0x{comp.base_id:08X}{size}")
    deployment = name or topology.deployment

    def ref(qualified: str) -> str:
        """An instance as the topology (inside module ``deployment``) names it: the deployment's own
        instances unqualified, since inside the topology its own name denotes the topology."""
        module, _, short = qualified.rpartition(".")
        return _ident(short) if module == deployment else _qualified(qualified)

    groups: dict[str, list[str]] = defaultdict(list)
    for c in topology.connections:
        group = c.group.replace("pattern:", "Pattern_") or "Connections"
        group = "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in group)
        groups[group].append(f"{ref(c.source)}.{_ident(c.source_port)}[{c.source_index}] -> "
                             f"{ref(c.target)}.{_ident(c.target_port)}[{c.target_index}]")
    lines = [f"instance {ref(q)}" for q in topology.instances]
    for group, conns in groups.items():
        lines.append(f"connections {_ident(group)} {{")
        lines += ["  " + c for c in conns]
        lines.append("}")
    packet_sets = list(getattr(topology, "telemetry_packet_sets", []) or [])
    for packet_set in packet_sets:
        lines += _packet_set_lines(packet_set, ref)
    body = "\n".join("  " + line for line in lines)
    # fpp-python 3.4 takes telemetry packets only in a deployment topology (docs/fpp.md)
    keyword = "deployment topology" if packet_sets else "topology"
    writer.add(f"{deployment}.{deployment}", f"{keyword} {_ident(deployment)} {{\n{body}\n}}")
    return writer.text()


def _packet_set_lines(packet_set: dict, ref: Any) -> list[str]:
    """FPP's ``telemetry packets NAME { packet P id N group G { inst.Chan … } … } omit { … }`` of one
    dictionary-shaped packet set (``deploy/topology_yaml/packets.py``), channels named as ``ref``
    names their instances."""
    def channel(name: str) -> str:
        instance, _, chan = name.rpartition(".")
        return f"{ref(instance)}.{_ident(chan)}"

    lines = [f"telemetry packets {_ident(packet_set['name'])} {{"]
    for packet in packet_set["members"]:
        lines.append(f"  packet {_ident(packet['name'])} id {packet['id']} group {packet['group']} {{")
        lines += [f"    {channel(name)}" for name in packet["members"]]
        lines.append("  }")
    lines.append("} omit {")
    lines += [f"  {channel(name)}" for name in packet_set["omitted"]]
    lines.append("}")
    return lines


_HEADER = ("# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export{args}) from {source}.\n"
           "# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.\n\n")


def framework_svc_text() -> str:
    """``framework/svc.fpp``: fprime-lite's services as F´ component definitions, with the Fw and
    Svc types they use."""
    import importlib

    classes = []
    for dotted in SVC_COMPONENT_NAMES:
        module, _, cls = dotted.rpartition(".")
        classes.append(getattr(importlib.import_module(module), cls))
    from fprime_lite.model import fw_types

    fw = [fw_type(getattr(fw_types, name)) for name in fw_types.__all__]
    return (_HEADER.format(args=" --framework", source="the services in src/fprime_lite/svc/ and the Fw types "
                                                       "of src/fprime_lite/model/fw_types.py")
            + export_components(classes, also=fw))


def default_out_dir(topology_path: str | pathlib.Path) -> pathlib.Path:
    """Where the FPP form of a topology YAML goes: ``fpp/`` beside ``topology.yaml``, ``fpp_NAME/``
    beside a variant ``topology_NAME.yaml`` (``deployments/proves_ref/fpp_packetized/``)."""
    path = pathlib.Path(topology_path)
    stem = path.stem
    return path.parent / ("fpp" if stem == "topology" else f"fpp_{stem.removeprefix('topology_')}")


def deployment_texts(topology_path: str | pathlib.Path,
                     out_dir: str | pathlib.Path | None = None) -> dict[str, str]:
    """The FPP files of the deployment a topology YAML describes: ``components.fpp`` (its own
    components, types and ports: everything not in the framework's FPP), ``topology.fpp`` (with its
    telemetry packet set, if it has one) and ``run.yaml`` (its paths relative to ``out_dir``, default
    :func:`default_out_dir`)."""
    from fprime_lite.deploy.topology_loader import load_topology

    loaded = load_topology(topology_path)
    topology = loaded.topology
    own = []
    seen: set[type] = set()
    for instance in topology.instances.values():
        cls = type(instance.component)
        if cls not in seen and f"{cls.__module__}.{cls.__qualname__}" not in SVC_COMPONENT_NAMES:
            seen.add(cls)
            own.append(cls)
    framework_types, framework_ports = _framework_names()
    source = str(topology_path)
    header = _HEADER.format(args=f" {source}", source=source)
    return {"components.fpp": header + export_components(own, skip=HAND_WRITTEN_NAMES | framework_types,
                                                           skip_ports=HAND_WRITTEN_PORTS | framework_ports),
            "topology.fpp": header + export_topology(topology),
            "run.yaml": run_file_text(topology_path, out_dir)}


def run_file_text(topology_path: str | pathlib.Path, out_dir: str | pathlib.Path | None = None) -> str:
    """The run file (``deploy/fpp/run.py``) of the FPP form of a topology YAML: its resources,
    constructor arguments, rate-group divisors, parameter file, start-up sequence and run settings,
    paths relative to ``out_dir`` (default :func:`default_out_dir`), and which TlmPacketizer instance
    flies its packet set from which send level."""
    import json
    import os

    import yaml

    from fprime_lite.deploy.topology_yaml.files import read_document, resolve_path
    from fprime_lite.deploy.topology_yaml.problems import Problems

    path = pathlib.Path(topology_path)
    folder = pathlib.Path(out_dir) if out_dir is not None else default_out_dir(path)
    problems = Problems()
    doc = json.loads(json.dumps(read_document(path, problems)))  # plain data, extends merged
    problems.raise_if_any()

    def relative(value: str) -> str:
        return os.path.relpath(resolve_path(value, path.parent), folder)

    run: dict = {key: doc[key] for key in ("resources", "parameter_file", "startup", "time", "run") if key in doc}
    if "parameter_file" in run:
        run["parameter_file"] = relative(run["parameter_file"])
    if isinstance(run.get("startup"), dict) and "sequence" in run["startup"]:
        run["startup"]["sequence"] = relative(run["startup"]["sequence"])
    modules = {}
    for module, body in (doc.get("modules") or {}).items():
        args = {name: {"args": entry["args"]} for name, entry in (body.get("instances") or {}).items()
                if isinstance(entry, dict) and entry.get("args")}
        if args:
            modules[module] = {"instances": args}
    if modules:
        run["modules"] = modules
    if "rate_groups" in doc:
        groups = doc["rate_groups"]
        run["rate_groups"] = {"base_rate_hz": groups["base_rate_hz"],
                              "groups": {name: {"divisor": g["divisor"]} for name, g in groups["groups"].items()}}
    packets = doc.get("telemetry_packets")
    if isinstance(packets, dict):  # the packets themselves are in topology.fpp
        run["telemetry_packets"] = {key: packets[key] for key in ("name", "instance", "start_level") if key in packets}
    header = (f"# What the FPP form of {path} does not say (docs/fpp.md \"Running an FPP topology\"): written by\n"
              f"# python -m fprime_lite.deploy.fpp.export {path}\n")
    return header + yaml.safe_dump(run, sort_keys=False, width=110)


def _framework_names() -> tuple[frozenset[str], frozenset[str]]:
    """The qualified names of the types and of the ports the framework's FPP defines (so that a
    deployment's FPP does not define them again)."""
    import fpp

    analysis = fpp.analyze([str(p) for p in framework_files()]).analysis
    symbols = list(analysis.symbol_map.values())
    ports = frozenset(analysis.get_qualified_name(s) for s in symbols if isinstance(s, fpp.Symbol.Port))
    types = frozenset(analysis.get_qualified_name(s) for s in symbols if not isinstance(s, fpp.Symbol.Port))
    return types, ports


def framework_files() -> list[pathlib.Path]:
    """The framework's FPP files, in the order they are read."""
    return [FRAMEWORK_DIR / "config.fpp", FRAMEWORK_DIR / "ports.fpp", FRAMEWORK_DIR / "svc.fpp"]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m fprime_lite.deploy.fpp.export",
                                     description="Write the framework's svc.fpp, or a deployment's FPP, "
                                                 "from the Python.")
    parser.add_argument("topology", nargs="?", help="a topology YAML: write its components.fpp and topology.fpp")
    parser.add_argument("--framework", action="store_true", help="write framework/svc.fpp")
    parser.add_argument("-o", "--out", help="output folder (default: fpp/ beside topology.yaml, fpp_NAME/ beside "
                                            "topology_NAME.yaml)")
    args = parser.parse_args(argv)
    if args.framework:
        (FRAMEWORK_DIR / "svc.fpp").write_text(framework_svc_text())
        print(f"wrote {FRAMEWORK_DIR / 'svc.fpp'}")
    if args.topology:
        out = pathlib.Path(args.out) if args.out else default_out_dir(args.topology)
        out.mkdir(parents=True, exist_ok=True)
        for name, text in deployment_texts(args.topology, out).items():
            (out / name).write_text(text)
            print(f"wrote {out / name}")
    if not args.framework and not args.topology:
        parser.print_usage(sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
