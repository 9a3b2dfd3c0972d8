"""The F´ JSON dictionary of a topology, in the shape ``fpp-to-dict`` emits and fprime-gds loads.

Every name is the module-qualified instance name plus the member (``CdhCore.cmdDisp.CMD_NO_OP``).
All ten top-level keys are present even when empty. Type definitions hold every named type the
commands, events, channels and parameters use, plus the framework's aliases and enums
(``FwOpcodeType`` …, ``TimeBase``, ``ComCfg.Apid``) and constants (``ComCfg.SpacecraftId``,
``ComCfg.TmFrameFixedSize``), which fprime-gds reads to configure its codecs.

A parameter declared with ``units=`` carries them in its optional ``annotation`` (the one field F´'s
dictionary has for them: ``fpp-to-dict`` puts a parameter's ``@`` comment there, after ``default``),
as ``"units: N·m"``; fprime-gds 4.4.1 reads parameters without it and loads the dictionary unchanged.
"""

from __future__ import annotations

import json
from json.encoder import encode_basestring_ascii as _json_string

from fprime_lite import __version__
from fprime_lite.osal.atomic import atomic_write_text
from fprime_lite.model.commands import CmdResponse
from fprime_lite.model.params import Param
from fprime_lite.wire.com_cfg import CONSTANTS
from fprime_lite.wire.packets import Apid
from fprime_lite.model.time import TIME, TimeBase
from fprime_lite.deploy.topology import Topology
from fprime_lite.model.types import U8, U16, U32, U64, Alias, FwEnum, FwType, fw_type
from fprime_lite.model.errors import FprimeLiteError

__all__ = ["build_dictionary", "write_dictionary", "param_annotation", "dumps_indented", "FRAMEWORK_VERSION"]

#: The F´ release whose dictionary format and framework types we follow.
FRAMEWORK_VERSION = "4.0.0"
DICTIONARY_SPEC_VERSION = "1.0.0"

FwIdType = Alias("FwIdType", U32)
FRAMEWORK_ALIASES = [
    FwIdType,
    Alias("FwOpcodeType", FwIdType),
    Alias("FwChanIdType", FwIdType),
    Alias("FwEventIdType", FwIdType),
    Alias("FwPrmIdType", FwIdType),
    Alias("FwPacketDescriptorType", U16),
    Alias("FwSizeStoreType", U16),
    Alias("FwTimeBaseStoreType", U16),
    Alias("FwTimeContextStoreType", U8),
    Alias("FwTlmPacketizeIdType", U16),
]
_TIME_CONTEXT = FRAMEWORK_ALIASES[8]


class DpState(FwEnum, namespace="Fw", rep=U8):
    """F´ ``Fw.DpState`` (fprime-lite has no data products; fpp-to-dict lists it in every dictionary)."""

    UNTRANSMITTED = 0
    PARTIAL = 1
    TRANSMITTED = 2


class ProcType(FwEnum, namespace="Fw.DpCfg", rep=U8, default="PROC_TYPE_NONE"):
    """F´ ``Fw.DpCfg.ProcType`` (listed by fpp-to-dict in every dictionary, as ``Fw.DpState``)."""

    PROC_TYPE_NONE = 0x00
    PROC_TYPE_ZLIB_DEFLATE = 0x01
    PROC_TYPE_ONE = 0x02
    PROC_TYPE_TWO = 0x04


#: The data-product definitions fpp-to-dict puts in every dictionary (F´'s framework definitions
#: for data products), so that fprime-lite's dictionary is the one F´'s tool builds.
_DP_ALIASES = [Alias("FwDpIdType", FwIdType), Alias("FwDpPriorityType", U32)]
_FW_SIZE_TYPE = {"kind": "alias", "qualifiedName": "FwSizeType",
                 "type": {"name": "PlatformSizeType", "kind": "qualifiedIdentifier"},
                 "underlyingType": fw_type(U64).json_ref()}
_DP_CONSTANTS = [("Fw.DpCfg.CONTAINER_USER_DATA_SIZE", U64, 32)]



def _time_value_definition() -> dict:
    """``Fw.TimeValue``: how a time member of a struct or argument is described."""
    members = [("timeBase", fw_type(TimeBase)), ("timeContext", _TIME_CONTEXT), ("seconds", U32),
               ("useconds", U32)]
    return {
        "kind": "struct",
        "qualifiedName": TIME.json_ref()["name"],
        "members": {n: {"type": fw_type(t).json_ref(), "index": i} for i, (n, t) in enumerate(members)},
        "default": {"timeBase": fw_type(TimeBase).json_value(TimeBase.TB_NONE), "timeContext": 0,
                    "seconds": 0, "useconds": 0},
    }


class _TypeCollector:
    def __init__(self):
        self.definitions: dict[str, dict] = {}

    def add(self, t: FwType) -> dict:
        """Record ``t`` (and what it refers to); return its JSON reference."""
        if t is TIME:
            if t.json_ref()["name"] not in self.definitions:
                self.add(fw_type(TimeBase))
                self.add(_TIME_CONTEXT)
                self.definitions[t.json_ref()["name"]] = _time_value_definition()
            return t.json_ref()
        definition = t.json_definition()
        if definition is not None and t.name not in self.definitions:
            annotation = getattr(t, "annotation", None)  # an FPP definition's `@` comment, as fpp-to-dict
            if annotation:
                definition["annotation"] = annotation
            self.definitions[t.name] = definition
            for dep in t.dependencies():
                self.add(dep)
        return t.json_ref()


def param_annotation(units: str) -> str:
    """The ``annotation`` of a parameter declared with ``units=``."""
    return f"units: {units}"


def _annotation(member) -> str | None:
    """A member's ``annotation``: the ``@`` comment of its FPP definition (a component bound from
    FPP, docs/fpp.md), else a parameter's units (``units: …``), else none."""
    text = getattr(member, "annotation", None)
    if isinstance(text, str):
        return text
    units = getattr(member, "units", None)
    return param_annotation(units) if isinstance(member, Param) and units is not None else None


def _params(collector: _TypeCollector, args) -> list[dict]:
    return [{"name": n, "type": collector.add(t), "ref": False} for n, t in args]


def deployment_name(topology: Topology) -> str:
    """The dictionary's ``deploymentName``: the qualified name of the deployment's FPP topology, as
    ``fpp-to-dict`` writes it. A YAML deployment ``D`` is FPP topology ``D`` in module ``D`` (its
    instances are ``D.name``), so ``D.D``; an FPP model gives its topology's qualified name. The
    GDS takes the last segment."""
    qualified = getattr(topology, "topology_name", None)
    return str(qualified) if qualified else f"{topology.deployment}.{topology.deployment}"


def build_dictionary(topology: Topology, *, project_version: str = __version__) -> dict:
    """The JSON dictionary (as Python data) of every instance in ``topology``."""
    types = _TypeCollector()
    for alias in FRAMEWORK_ALIASES:
        types.add(alias)
    for framework_enum in (TimeBase, Apid, CmdResponse, DpState, ProcType):
        types.add(fw_type(framework_enum))
    for alias in _DP_ALIASES:
        types.add(alias)
    types.definitions["FwSizeType"] = _FW_SIZE_TYPE
    commands, events, channels, params = [], [], [], []
    for instance in topology.instances.values():
        comp = instance.component
        prefix = instance.qualified_name
        for c in comp.spec.commands:
            entry = {"name": f"{prefix}.{c.name}", "commandKind": c.kind, "opcode": comp.base_id + c.opcode,
                     "formalParams": _params(types, c.args)}
            if c.kind == "async":
                entry["priority"] = c.priority
                entry["queueFullBehavior"] = c.queue_full
            annotation = _annotation(c.param if c.param is not None else c)
            if annotation is not None:  # fpp-to-dict gives a parameter's commands its annotation
                entry["annotation"] = annotation
            commands.append(entry)
        for e in comp.spec.events:
            entry = {"name": f"{prefix}.{e.name}", "severity": e.severity.name, "id": comp.base_id + e.local_id,
                     "formalParams": _params(types, e.args), "format": e.format}
            if e.throttle is not None:
                entry["throttle"] = e.throttle
            if _annotation(e) is not None:
                entry["annotation"] = _annotation(e)
            events.append(entry)
        for ch in comp.spec.channels:
            entry = {"name": f"{prefix}.{ch.name}", "type": types.add(ch.type), "id": comp.base_id + ch.local_id,
                     "telemetryUpdate": ch.update}
            if ch.format is not None:
                entry["format"] = ch.format
            limits = {side: dict(levels) for side, levels in (("low", ch.low), ("high", ch.high)) if levels}
            if limits:
                entry["limits"] = limits
            if _annotation(ch) is not None:
                entry["annotation"] = _annotation(ch)
            channels.append(entry)
        for p in comp.spec.params:
            entry = {"name": f"{prefix}.{p.name}", "type": types.add(p.type), "id": comp.base_id + p.local_id}
            if p.has_default:
                entry["default"] = p.type.json_value(p.default)
            if _annotation(p) is not None:
                entry["annotation"] = _annotation(p)
            params.append(entry)
    return {
        "metadata": {
            "deploymentName": deployment_name(topology),
            "frameworkVersion": FRAMEWORK_VERSION,
            "projectVersion": project_version,
            "libraryVersions": [],
            "dictionarySpecVersion": DICTIONARY_SPEC_VERSION,
        },
        "typeDefinitions": list(types.definitions.values()),
        "constants": [{"kind": "constant", "qualifiedName": n, "type": fw_type(t).json_ref(), "value": v}
                      for n, t, v in CONSTANTS + _DP_CONSTANTS],
        "commands": sorted(commands, key=lambda c: c["opcode"]),
        "parameters": sorted(params, key=lambda p: p["id"]),
        "events": sorted(events, key=lambda e: e["id"]),
        "telemetryChannels": sorted(channels, key=lambda c: c["id"]),
        "records": [],
        "containers": [],
        # an FPP topology's packets (deploy/fpp/loader.py); a YAML topology has none
        "telemetryPacketSets": list(getattr(topology, "telemetry_packet_sets", [])),
    }


def write_dictionary(topology: Topology, path, **kwargs) -> dict:
    """Build the dictionary and write it to ``path`` atomically; return it."""
    dictionary = build_dictionary(topology, **kwargs)
    atomic_write_text(path, dumps_indented(dictionary) + "\n")
    return dictionary


class _NotPlainError(FprimeLiteError):
    """A value :func:`dumps_indented` leaves to ``json.dumps`` (never escapes it: the package's error root, as every
    fprime_lite error class derives from)."""


def dumps_indented(obj) -> str:
    """``json.dumps(obj, indent=2)``, the same text, in about half its time.

    With ``indent`` the json module writes through its pure-Python encoder (a generator per level and
    value): writing a deployment's dictionary took 150 M instructions, three quarters of what a run's
    outputs cost at its start (docs/performance.md, "Issue 32: what a run's outputs cost"). This
    writes the same layout with one list of pieces. It takes only the plain JSON types, exactly:
    ``dict`` with ``str`` keys, ``list``, ``tuple``, ``str``, ``int``, ``float`` (finite), ``bool``
    and ``None``; a document holding anything else (a subclass such as an IntEnum, a NaN, another
    kind of key, a cycle) is handed whole to ``json.dumps``, which decides what it becomes.
    """
    parts: list[str] = []
    append = parts.append
    int_text, float_text = int.__repr__, float.__repr__
    infinity = float("inf")

    def write(o, newline: str) -> None:  # newline: "\n" and the indent of the line o starts on
        t = type(o)
        if t is str:
            append(_json_string(o))
        elif o is None:
            append("null")
        elif o is True:
            append("true")
        elif o is False:
            append("false")
        elif t is int:
            append(int_text(o))
        elif t is float:
            if o != o or o == infinity or o == -infinity:
                raise _NotPlainError
            append(float_text(o))
        elif t is dict:
            if o:
                write_items(o.items(), "{", "}", newline, True)
            else:
                append("{}")
        elif t is list or t is tuple:
            if o:
                write_items(o, "[", "]", newline, False)
            else:
                append("[]")
        else:
            raise _NotPlainError

    def write_items(items, opening: str, closing: str, newline: str, keyed: bool) -> None:
        inner = newline + "  "
        separator = "," + inner
        append(opening + inner)
        first = True
        for item in items:
            if first:
                first = False
            else:
                append(separator)
            if keyed:
                key, item = item
                if type(key) is not str:
                    raise _NotPlainError
                append(_json_string(key))
                append(": ")
            write(item, inner)
        append(newline + closing)

    try:
        write(obj, "\n")
    except (_NotPlainError, RecursionError):
        return json.dumps(obj, indent=2)
    return "".join(parts)

