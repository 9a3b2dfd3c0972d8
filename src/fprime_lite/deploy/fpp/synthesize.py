"""A component class from an FPP definition and a Python class that supplies handlers only.

An F´ team writes the component's interface in FPP and its behaviour in a ``.cpp``; here the
behaviour is a Python class deriving from :class:`~fprime_lite.model.component.PassiveComponent`
(or ``QueuedComponent`` / ``ActiveComponent``) with one method per input port and command, named
as in the FPP, and nothing declared. :func:`synthesize` builds the subclass that declares what the
FPP declares (ports, commands with their opcodes, events, channels, parameters with their ids and
defaults), checks each handler against its port or command, and returns it; the harness and the
topology loaders take it as any component class.

Types: the primitive types, strings, and the aliases, enums, arrays and structs the FPP model
defines (each made once per model as an ``FwEnum``, ``Array`` or ``Struct`` of the same qualified
name, with the FPP's defaults); a serial port or an abstract type is refused with the reason.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import inspect
import types as pytypes
from typing import Any, Callable

from fprime_lite.model import fw_ports
from fprime_lite.model.commands import async_command, guarded_command, sync_command
from fprime_lite.model.component import FRAMEWORK_CHANNELS, FRAMEWORK_EVENTS
from fprime_lite.model.errors import DeclarationError
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.params import Param
from fprime_lite.model.ports import InputPortDecl, OutputPort, PortType, async_input, guarded_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import (PRIMITIVE_TYPES, Array, ArrayType, FwEnum, FwType, String, Struct, StructType,
                                     fw_type)

__all__ = ["synthesize", "declares_nothing", "UnsupportedTypeError"]

#: FPP's primitive type names -> fprime-lite's types (the same spelling)
_PRIMITIVES: dict[str, FwType[Any]] = dict(PRIMITIVE_TYPES)
_SEVERITY = {"Fatal": Severity.FATAL, "WarningHigh": Severity.WARNING_HI, "WarningLow": Severity.WARNING_LO,
             "Command": Severity.COMMAND, "ActivityHigh": Severity.ACTIVITY_HI,
             "ActivityLow": Severity.ACTIVITY_LO, "Diagnostic": Severity.DIAGNOSTIC}
_FRAMEWORK_PORTS = {p.name: p for p in (getattr(fw_ports, n) for n in fw_ports.__all__) if isinstance(p, PortType)}


class UnsupportedTypeError(DeclarationError):
    """An FPP type that a handlers-only class cannot take (abstract types, serial ports)."""


def declares_nothing(cls: type) -> bool:
    """Whether ``cls`` declares no member of its own (only the framework's): a handlers-only class."""
    spec = getattr(cls, "__fprime_spec__", None)
    if spec is None:
        return False
    special = set(spec.special.values())
    return (not [c for c in spec.commands if c.kind not in ("set", "save")] and not spec.params
            and all(e.name in FRAMEWORK_EVENTS for e in spec.events)
            and all(c.name in FRAMEWORK_CHANNELS for c in spec.channels)
            and not set(spec.inputs) - special and not set(spec.outputs) - special)


class _Types:
    """FPP types to fprime-lite types, enums made once per model."""

    def __init__(self, analysis: Any):
        self.analysis = analysis
        #: the enums, arrays and structs made so far, by qualified name
        self.enums: dict[str, FwType[Any]] = {}

    def of(self, t: Any, where: str) -> FwType[Any]:
        text = str(t)
        kind = type(t).__name__
        if kind == "Alias":
            return self.of(t.underlying_type(), where)
        if kind in ("PrimitiveInt", "Float", "Boolean"):
            return _PRIMITIVES[text]
        if kind == "String":
            return String(int(t.serialized_size) - 2)  # a U16 length, then the bytes
        if kind == "Enum":
            name = self.analysis.get_qualified_name(t.def_symbol)
            if name not in self.enums:
                self.enums[name] = _annotate(_enum(name, t), t.node)
            return self.enums[name]
        if kind in ("Array", "Struct"):
            # the definition's own type: one reached through a command's argument may lack resolved sizes
            t = self.analysis.type_map.get(t.def_node_id, t)
            name = self.analysis.get_qualified_name(t.def_symbol)
            if name not in self.enums:
                made = self._array(name, t, where) if kind == "Array" else self._struct(name, t, where)
                _annotate(made, t.node)  # the dictionary's `annotation` of the definition, as fpp-to-dict's
                self.enums[name] = made
            return self.enums[name]
        raise UnsupportedTypeError(f"{where}: type {text} ({kind}) — a handlers-only class takes primitive, string, "
                                   f"alias, enum, array and struct types; declare this component's members in "
                                   f"Python instead")

    def _array(self, name: str, t: Any, where: str) -> FwType[Any]:
        elem = self.of(t.anon_array.elt_type, f"{where}: element of {name}")
        namespace, _, short = name.rpartition(".")
        size = t.array_size if t.array_size is not None else t.anon_array.size
        if size is None:
            raise UnsupportedTypeError(f"{where}: array {name} has no size the analyser resolved")
        cls = pytypes.new_class(short, (Array,), {"elem": elem, "size": int(size),
                                                  "namespace": namespace or None})
        array_type: FwType[Any] = fw_type(cls)
        if t.default is not None and isinstance(array_type, ArrayType) and array_type._defaults is not None:
            # the FPP's default elements (numbers, enums, strings): what the array's default is made of
            array_type._defaults = tuple(_value(elem, e) for e in t.default.anon_array.elements)
        return array_type

    def _struct(self, name: str, t: Any, where: str) -> FwType[Any]:
        members = [(member, self.of(mt, f"{where}: member {member} of {name}")) for member, mt in t.anon_struct.members]
        defaults = t.default.anon_struct.members if t.default is not None else {}
        namespace, _, short = name.rpartition(".")

        def body(ns: dict[str, Any]) -> None:
            ns["__annotations__"] = dict(members)
            for member, mt in members:
                if member in defaults:
                    value = _value(mt, defaults[member])
                    ns[member] = (dataclasses.field(default_factory=functools.partial(copy.deepcopy, value))
                                  if isinstance(mt, (ArrayType, StructType)) else value)

        return fw_type(pytypes.new_class(short, (Struct,), {"namespace": namespace or None}, body))


def _enum(name: str, t: Any) -> FwType[Any]:
    constants = {c.name: int(c.resolved_value.value[1]) for c in t.node.constants}
    namespace, _, short = name.rpartition(".")
    rep = _PRIMITIVES.get(str(t.rep_type).rsplit(".", 1)[-1], _PRIMITIVES["I32"])
    default = t.default
    default_name = default.value[0] if default is not None else next(iter(constants))
    body = dict(constants)
    meta: Any = type(FwEnum)
    cls = meta(short, (FwEnum,), _enum_namespace(short, body), namespace=namespace or None, rep=rep,
               default=default_name)
    return fw_type(cls)


def _enum_namespace(short: str, constants: dict[str, int]) -> Any:
    namespace = type(FwEnum).__prepare__(short, (FwEnum,))
    for key, value in constants.items():
        namespace[key] = value
    return namespace


def _copy(fn: Callable[..., Any], name: str) -> Any:
    """A copy of ``fn`` under ``name`` (so that decorating it leaves the user's class alone)."""
    clone = pytypes.FunctionType(fn.__code__, fn.__globals__, name, fn.__defaults__, fn.__closure__)
    clone.__kwdefaults__ = fn.__kwdefaults__
    clone.__annotations__ = dict(getattr(fn, "__annotations__", {}))
    clone.__qualname__ = getattr(fn, "__qualname__", name)
    clone.__doc__ = fn.__doc__
    return clone


def _port_type(port: Any, analysis: Any, types: _Types, where: str) -> PortType:
    node = port.ty.definition
    if node is None:
        raise UnsupportedTypeError(f"{where}: a serial port — a handlers-only class takes typed ports")
    name = analysis.get_qualified_name(analysis.symbol_map[node.node_id])
    if name in _FRAMEWORK_PORTS:
        return _FRAMEWORK_PORTS[name]
    args = {p.name: types.of(p.type_name.resolved_type, f"{where} argument {p.name}") for p in node.params}
    returned = node.return_type
    ret = types.of(returned.resolved_type, f"{where} return") if returned is not None else None
    return PortType(name, returns=ret, **args)


def synthesize(fpp_name: str, comp: Any, cls: type, analysis: Any, where: Callable[[Any], str]) -> type:
    """The subclass of ``cls`` declaring what FPP component ``comp`` declares; raise
    :class:`DeclarationError` (one line: the FPP place, what is wrong) when a handler is missing or
    does not fit."""
    types = _Types(analysis)
    body: dict[str, Any] = {"__module__": cls.__module__, "__qualname__": cls.__qualname__,
                            "__fprime_fpp_name__": fpp_name}

    def handler(name: str, node: Any, what: str) -> Callable[..., Any]:
        fn = getattr(cls, name, None)
        if not inspect.isfunction(fn):
            raise DeclarationError(f"{where(node)}: {what} {name} has no handler: give {cls.__qualname__} a method "
                                   f"{name}")
        return fn

    for name, port in comp.port_map.items():
        if type(port).__name__ != "General":
            continue
        port_type = _port_type(port, analysis, types, f"{where(port.node)}: port {name}")
        if type(port.kind).__name__ == "Output":
            body[name] = OutputPort(port_type, size=port.size)
            continue
        fn = _copy(handler(name, port.node, "input port"), name)
        try:
            InputPortDecl(port_type, "sync", port.size, name=name).check_handler(cls.__qualname__, fn)
        except DeclarationError as exc:
            raise DeclarationError(f"{where(port.node)}: input port {name}: {exc}") from None
        kind = type(port.kind).__name__  # SyncInput | GuardedInput | AsyncInput
        if kind == "AsyncInput":
            priority = getattr(port.kind, "priority", None) or 0
            queue_full = str(getattr(port.kind, "queue_full", "Assert")).rsplit(".", 1)[-1].lower()
            decorate = async_input(port_type, size=port.size, priority=priority, queue_full=queue_full)
        elif kind == "GuardedInput":
            decorate = guarded_input(port_type, size=port.size)
        else:
            decorate = sync_input(port_type, size=port.size)
        body[name] = decorate(fn)
    for opcode, command in comp.command_map.items():
        if type(command).__name__ != "NonParam":
            continue
        node = command.node
        fn = _copy(handler(command.name, node, "command"), command.name)
        params = [inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD)]
        params += [inspect.Parameter(p.name, inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                     annotation=types.of(p.type_name.resolved_type,
                                                         f"{where(node)}: {command.name}({p.name})"))
                   for p in node.params]
        user = [p for p in inspect.signature(getattr(cls, command.name)).parameters][1:]
        if user != [p.name for p in params[1:]]:
            declared = ", ".join(p.name for p in params[1:])
            raise DeclarationError(f"{where(node)}: command {command.name} takes ({declared}); "
                                   f"{cls.__qualname__}.{command.name} takes ({', '.join(user)})")
        fn.__signature__ = inspect.Signature(params)
        kind = type(command.kind).__name__  # Sync | Guarded | Async
        if kind == "Async":
            priority = getattr(command.kind, "priority", None) or 0
            queue_full = str(getattr(command.kind, "queue_full", "Assert")).rsplit(".", 1)[-1].lower()
            body[command.name] = async_command(opcode=opcode, priority=priority, queue_full=queue_full)(fn)
        elif kind == "Guarded":
            body[command.name] = guarded_command(opcode=opcode)(fn)
        else:
            body[command.name] = sync_command(opcode=opcode)(fn)
        _annotate(body[command.name].__fprime_command__, node)
    for event_id, event in comp.event_map.items():
        node = event.node
        if event.name in FRAMEWORK_EVENTS:
            continue
        args = [(p.name, types.of(p.type_name.resolved_type, f"{where(node)}: {event.name}({p.name})"))
                for p in node.params]
        throttle = event.throttle.count if event.throttle is not None else None
        body[event.name] = _annotate(Event(_SEVERITY[str(node.severity).rsplit(".", 1)[-1]], node.format,
                                           id=event_id, throttle=throttle, args=args), node)
    for channel_id, channel in comp.tlm_channel_map.items():
        if channel.name in FRAMEWORK_CHANNELS:
            continue
        update = "on change" if "OnChange" in str(channel.update) else "always"
        body[channel.name] = _annotate(Channel(types.of(channel.channel_type, f"{where(channel.node)}: {channel.name}"),
                                               id=channel_id, update=update), channel.node)
    for param_id, param in comp.param_map.items():
        ptype = types.of(param.param_type, f"{where(param.node)}: {param.name}")
        kwargs: dict[str, Any] = {"id": param_id, "set_opcode": param.set_opcode, "save_opcode": param.save_opcode}
        if param.default is not None:
            kwargs["default"] = _value(ptype, param.default)
        body[param.name] = _annotate(Param(ptype, **kwargs), param.node)
    body.update(_state_machines(comp, cls, analysis, where))
    try:
        return type(cls)(cls.__name__, (cls,), body)
    except DeclarationError as exc:
        raise DeclarationError(f"{where(comp.node)}: {exc}") from None


def _state_machines(comp: Any, cls: type, analysis: Any, where: Callable[[Any], str]) -> dict[str, Any]:
    """The members that run the component's FPP state machine instances (:mod:`.state_machine`)."""
    if not comp.state_machine_instance_map:
        return {}
    from fprime_lite.deploy.fpp.state_machine import compile_state_machine, state_machine_members

    compiled: dict[str, Any] = {}  # (F´'s analyser refuses an instance in a passive component)
    instances = []
    for name, instance in comp.state_machine_instance_map.items():
        sm = analysis.state_machine_map[instance.symbol]
        qualified = analysis.get_qualified_name(instance.symbol)
        if qualified not in compiled:
            compiled[qualified] = compile_state_machine(sm, analysis, where)
        queue_full = str(instance.queue_full or "Assert").rsplit(".", 1)[-1].lower()
        instances.append((name, compiled[qualified], int(instance.priority or 0), queue_full, where(instance.node)))
    members = state_machine_members(cls, instances, lambda n: n)
    members["__fprime_state_machines__"] = tuple(name for name, *_ in instances)
    return members


def _annotate(decl: Any, node: Any) -> Any:
    """Give ``decl`` the FPP member's ``@`` annotation, which the dictionary carries as fpp-to-dict
    does (``annotation``; a parameter's commands carry the parameter's)."""
    text = "\n".join(list(node.pre_annotation) + list(node.post_annotation))
    if text:
        decl.annotation = text
    return decl


def _value(t: FwType[Any], value: Any) -> Any:
    """An FPP value as the Python value of ``t``."""
    resolved = fw_type(t)
    if isinstance(resolved, ArrayType):
        return resolved.cls([_value(resolved.elem, e) for e in value.anon_array.elements])
    if isinstance(resolved, StructType):
        given = value.anon_struct.members
        return resolved.cls(**{n: _value(mt, given[n]) for n, mt in resolved.members if n in given})
    raw = getattr(value, "value", value)
    if isinstance(fw_type(t), type(String(1))):
        return str(raw)
    cls = getattr(t, "cls", None)
    if cls is not None:  # an enum constant: (name, value)
        return cls[raw[0]]
    if fw_type(t).kind == "float":
        return float(raw)
    if fw_type(t).kind == "bool":
        return bool(raw)
    return int(raw)
