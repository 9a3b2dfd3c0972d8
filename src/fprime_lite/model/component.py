"""Components: passive, queued and active, with their members declared in the class body.

A component class declares what it receives (decorated input-port and command methods) and what it
emits or owns (output ports, events, channels, parameters). The declarations are checked when the
class is created; a :class:`~fprime_lite.model.errors.DeclarationError` names the class and the member.
The framework then adds F´'s generated parts: the special ports (command, event, telemetry,
parameter, time), the ``P_PRM_SET``/``P_PRM_SAVE`` commands and the command dispatch.

Ids: every opcode, event id, channel id and parameter id is the instance's ``base_id`` plus a local
id. Local ids are given explicitly or assigned in declaration order (one more than the previous).
Members the framework generates come after those the class declares: parameter echoes
(:class:`~fprime_lite.model.params.ParamEcho`) without explicit ids, then the framework's own fault
and parameter events and the ``HandlerFaults`` channel (see :data:`FRAMEWORK_EVENTS`), numbered
from one past the largest local id of their kind so that no declared id moves (decision 0005).
"""

from __future__ import annotations

import copy
import functools
import logging
import threading
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

from fprime_lite.model.commands import CmdResponse, CommandDecl, CommandToken, resolve_command_args
from fprime_lite.model.errors import DeclarationError, FwAssertionError, SerializationError
from fprime_lite.model.events import BoundEvent, Event, Severity
from fprime_lite.model.fw_ports import SPECIAL_PORTS
from fprime_lite.model.params import BoundParam, Param, ParamValid
from fprime_lite.model.ports import InputPortArray, InputPortDecl, OutputPort, OutputPortArray, bind_input_entries
from fprime_lite.model.queues import MessageQueue
from fprime_lite.model.telemetry import BoundChannel, Channel, bind_channel
from fprime_lite.model.time import NO_CLOCK_READING, Time, simulated_clock_of
from fprime_lite.model.types import _U32, String, deserialize_values, fit_utf8

__all__ = ["Component", "PassiveComponent", "QueuedComponent", "ActiveComponent", "ComponentSpec",
           "FRAMEWORK_EVENTS", "FRAMEWORK_CHANNELS"]

log = logging.getLogger("fprime_lite")

_ZERO_TIME = Time()

#: Events the framework gives every component (the parameter ones only to components with parameters).
#: ``HandlerFault``: a handler raised in a deployment (a command, a queued message, a cycle run at
#: once, or a fault the component reports itself with :meth:`Component.report_fault`).
#: ``ParamSetRefused``: a PRM_SET value failed the parameter's validation (VALIDATION_ERROR).
#: ``ParamDefaulted``: the parameter file's value was refused; the default is in use.
_FAULT_THROTTLE = 10
FRAMEWORK_EVENTS: dict[str, Callable[[], Event]] = {
    "HandlerFault": lambda: Event(Severity.WARNING_HI, "Handler {} raised {}", port=String(40),
                                  exception=String(120), throttle=_FAULT_THROTTLE),
    "ParamSetRefused": lambda: Event(Severity.WARNING_LO, "{} PRM_SET refused: {}", param=String(40),
                                     reason=String(120)),
    "ParamDefaulted": lambda: Event(Severity.WARNING_HI, "{} parameter file value refused ({}); default loaded",
                                    param=String(40), reason=String(120)),
}
_PARAM_EVENTS = ("ParamSetRefused", "ParamDefaulted")
#: Channels the framework gives every component: ``HandlerFaults`` counts handler faults (U32).
FRAMEWORK_CHANNELS: dict[str, Callable[[], Channel[Any]]] = {
    "HandlerFaults": lambda: Channel(_U32, update="on change"),
}
_RESERVED = ({name for name, _, _ in SPECIAL_PORTS.values()} | {"name", "base_id"} | set(FRAMEWORK_EVENTS)
             | set(FRAMEWORK_CHANNELS))


@dataclass
class ComponentSpec:
    """Everything a component class declares, with local ids assigned."""

    class_name: str
    kind: str
    inputs: dict[str, InputPortDecl] = field(default_factory=dict)
    outputs: dict[str, OutputPort] = field(default_factory=dict)
    special: dict[str, str] = field(default_factory=dict)  # special kind -> port name
    commands: list[CommandDecl] = field(default_factory=list)
    events: list[Event] = field(default_factory=list)
    channels: list[Channel[Any]] = field(default_factory=list)
    params: list[Param[Any]] = field(default_factory=list)
    #: Parameter name -> (its echo event, its echo channel), for parameters declared with ``echo=``.
    echoes: dict[str, tuple[Event, Channel[Any]]] = field(default_factory=dict)

    def command(self, name: str) -> CommandDecl:
        for c in self.commands:
            if c.name == name:
                return c
        raise KeyError(f"{self.class_name} has no command {name!r}; it has "
                       f"{', '.join(c.name for c in self.commands) or 'none'}")

    def event(self, name: str) -> Event:
        return _find(self.events, name, self.class_name, "event")

    def channel(self, name: str) -> Channel[Any]:
        return _find(self.channels, name, self.class_name, "channel")

    def param(self, name: str) -> Param[Any]:
        return _find(self.params, name, self.class_name, "parameter")

    @property
    def own_events(self) -> list[Event]:
        """The events the class declares and its parameter echoes (not the framework's own)."""
        return [e for e in self.events if not e.framework]

    @property
    def own_channels(self) -> list[Channel[Any]]:
        """The channels the class declares and its parameter echoes (not the framework's own)."""
        return [c for c in self.channels if not c.framework]


def _find(items: Iterable[Any], name: str, owner: str, what: str) -> Any:
    for item in items:
        if item.name == name:
            return item
    raise KeyError(f"{owner} has no {what} {name!r}; it has {', '.join(i.name for i in items) or 'none'}")


def _is_declaration(value: Any) -> bool:
    return (isinstance(value, (OutputPort, Event, Channel, Param))
            or hasattr(value, "__fprime_input__") or hasattr(value, "__fprime_command__"))


class _ClassBody(dict[str, Any]):
    """Class namespace that refuses to declare the same member twice."""

    def __init__(self, class_name: str):
        super().__init__()
        self.class_name = class_name

    def __setitem__(self, key: str, value: Any) -> None:
        if key in self and (_is_declaration(self[key]) or _is_declaration(value)):
            raise DeclarationError(f"{self.class_name}.{key} is declared twice; give each member its own name")
        super().__setitem__(key, value)


def _assign_ids(owner: str, what: str, items: list[tuple[Any, str]], get: Callable[[Any], int | None],
                put: Callable[[Any, int], None], after: Iterable[list[tuple[Any, str]]] = ()) -> None:
    """Give each item its explicit id or the previous id + 1; reject duplicates.

    ``after`` holds groups of framework-generated items; each group is numbered from one past the
    largest id used before it, so nothing the class declares moves. The explicit ids of generated
    items are held back while the declared ones are numbered: an automatic id steps over them, as
    it would over those members listed in their places (a channel declared after the last one still
    takes the id after the generated ones that follow it).
    """
    later = [list(group) for group in after]
    reserved = {get(item) for group in later for item, _ in group} - {None}
    used: dict[int, str] = {}
    for group_number, group in enumerate([items, *later]):
        next_id = 0 if group_number == 0 else max(used, default=-1) + 1
        for item, label in group:
            explicit = get(item)
            local = next_id if explicit is None else explicit
            if explicit is None and group_number == 0:
                while local in reserved:
                    local += 1
            if local in used:
                raise DeclarationError(f"{owner}: {what} {local} (0x{local:X}) of {label} is already used by "
                                       f"{used[local]}; give one of them another {what}")
            used[local] = label
            put(item, local)
            next_id = local + 1


_SHADOWED_KINDS = (OutputPort, Event, Channel, Param)


def _members(klass: type) -> dict[str, Any]:
    """A class body as written, declarations included (see :func:`_move_out_declarations`)."""
    return klass.__dict__.get("__fprime_members__", klass.__dict__)


def _move_out_declarations(klass: type) -> None:
    """Take output-port, event, channel and parameter declarations out of ``klass``'s attributes.

    Each instance sets an attribute of the same name (the call slots, the bound event, …). While
    the class also has one, CPython 3.11 cannot specialise the instance attribute lookup, and every
    ``self.xOut[0](…)`` or ``self.Chan.write(…)`` pays ~15 ns more. The class body is kept in
    ``__fprime_members__`` for building specs; class-level reads still work through
    :meth:`ComponentMeta.__getattr__`.
    """
    body = klass.__dict__
    declared = [key for key, value in body.items() if isinstance(value, _SHADOWED_KINDS)]
    if not declared:
        return
    if "__fprime_members__" not in body:
        setattr(klass, "__fprime_members__", dict(body))
    for key in declared:
        delattr(klass, key)


class ComponentMeta(type):
    """Collects and checks a component class's declarations when the class is created."""

    @classmethod
    def __prepare__(cls, name: str, bases: tuple[type, ...], /, **kwargs: Any) -> dict[str, object]:
        return _ClassBody(name)

    def __new__(mcs, name: str, bases: tuple[type, ...], namespace: dict[str, Any], **kwargs: Any) -> ComponentMeta:
        cls = super().__new__(mcs, name, bases, dict(namespace), **kwargs)
        if not namespace.get("__fprime_abstract__", False):
            setattr(cls, "__fprime_spec__", _build_spec(cls))
        for klass in cls.__mro__[:-1]:  # this class and plain mixins that declare members
            _move_out_declarations(klass)
        return cls

    def __getattr__(cls, name: str) -> Any:
        """Class-level reads of a declaration (``MyComponent.xOut``) find it in the class bodies."""
        for klass in cls.__mro__:
            members = klass.__dict__.get("__fprime_members__")
            if members is not None and isinstance(members.get(name), _SHADOWED_KINDS):
                return members[name]
        raise AttributeError(f"type object {cls.__name__!r} has no attribute {name!r}")


def _build_spec(cls: Any) -> ComponentSpec:
    owner = cls.__name__
    merged: dict[str, Any] = {}
    for klass in reversed(cls.__mro__):
        for key, value in _members(klass).items():
            if _is_declaration(value):
                merged[key] = value
            elif key in merged and callable(value):
                merged[key] = value  # an override without decorator keeps the base declaration below
    spec = ComponentSpec(owner, cls.__fprime_kind__)
    ordered_commands: list[tuple[CommandDecl, str]] = []
    for key, value in merged.items():
        if key in _RESERVED:
            raise DeclarationError(f"{owner}.{key}: the name {key!r} is reserved by the framework")
        base_input = _declared_input(cls, key)
        base_command = _declared_command(cls, key)
        if base_input is not None:
            idecl = copy.copy(base_input)
            idecl.name = key
            idecl.check_handler(owner, getattr(cls, key))
            if idecl.kind == "async":
                if spec.kind == "passive":
                    raise DeclarationError(
                        f"{owner}.{key}: a passive component cannot have async input ports; derive "
                        f"from QueuedComponent or ActiveComponent, or make the port sync")
                if idecl.queue_full == "hook" and not callable(getattr(cls, f"{key}_overflow_hook", None)):
                    raise DeclarationError(f"{owner}.{key}: queue_full='hook' needs a method "
                                           f"{key}_overflow_hook(self, ...) taking the port's arguments")
            spec.inputs[key] = idecl
        elif base_command is not None:
            kdecl = copy.copy(base_command)
            kdecl.name = key
            resolve_command_args(owner, kdecl)
            if kdecl.kind == "async" and spec.kind == "passive":
                raise DeclarationError(f"{owner}.{key}: a passive component cannot have async commands; "
                                       f"derive from QueuedComponent or ActiveComponent, or use sync_command")
            ordered_commands.append((kdecl, f"command {key}"))
        elif isinstance(value, OutputPort):
            odecl = copy.copy(value)
            odecl.name = key
            spec.outputs[key] = odecl
        elif isinstance(value, Event):
            edecl = copy.copy(value)
            edecl.name = edecl.attr = key
            edecl.finish(owner)
            spec.events.append(edecl)
        elif isinstance(value, Channel):
            cdecl = copy.copy(value)
            cdecl.attr, cdecl.name = key, value.fprime_name or key
            cdecl.finish(owner)
            spec.channels.append(cdecl)
        elif isinstance(value, Param):
            pdecl = copy.copy(value)
            pdecl.attr, pdecl.name = key, value.fprime_name or key
            pdecl.finish(owner)
            spec.params.append(pdecl)
            prm = pdecl.name
            # F´ names a parameter's commands after the name in upper case (SafeModeEntryVoltage:
            # SAFEMODEENTRYVOLTAGE_PRM_SET), as fpp-to-dict's dictionary has them
            ordered_commands.append((CommandDecl(f"{prm.upper()}_PRM_SET", "set", [("val", pdecl.type)],
                                                 requested_opcode=pdecl.set_opcode, param=pdecl),
                                     f"command {prm.upper()}_PRM_SET"))
            ordered_commands.append((CommandDecl(f"{prm.upper()}_PRM_SAVE", "save", [],
                                                 requested_opcode=pdecl.save_opcode, param=pdecl),
                                     f"command {prm.upper()}_PRM_SAVE"))
            if pdecl.echo is not None:
                spec.echoes[prm] = _echo_members(owner, pdecl)
    generated_events = [event for event, _ in spec.echoes.values()]
    generated_channels = [channel for _, channel in spec.echoes.values()]
    framework_events = [_framework_member(name, FRAMEWORK_EVENTS[name], owner) for name in FRAMEWORK_EVENTS
                        if spec.params or name not in _PARAM_EVENTS]
    framework_channels = [_framework_member(name, make, owner) for name, make in FRAMEWORK_CHANNELS.items()]
    for what, members in (("event", spec.events + generated_events + framework_events),
                          ("channel", spec.channels + generated_channels + framework_channels),
                          ("parameter", spec.params)):
        seen_names: dict[str, str] = {}
        for member in members:
            if member.name in seen_names:
                raise DeclarationError(f"{owner}: {what}s {seen_names[member.name]} and {member.attr or member.name} "
                                       f"both have the F´ name {member.name!r}; give one of them another name")
            seen_names[member.name] = member.attr or member.name
    names: dict[str, CommandDecl] = {}
    for cmd, label in ordered_commands:
        if cmd.name in names:
            raise DeclarationError(f"{owner}: {label} clashes with the command generated for "
                                   f"parameter {cmd.name.rsplit('_PRM_', 1)[0]}; rename it")
        names[cmd.name] = cmd
    _assign_ids(owner, "opcode", ordered_commands, lambda d: d.requested_opcode,
                lambda d, v: setattr(d, "opcode", v))
    spec.commands = [d for d, _ in ordered_commands]

    def labelled(items: list[Any]) -> list[tuple[Any, str]]:
        return [(i, i.name) for i in items]

    def requested(d: Any) -> int | None:
        return d.requested_id

    def put(d: Any, v: int) -> None:
        d.local_id = v

    _assign_ids(owner, "event id", labelled(spec.events), requested, put,
                after=[labelled(generated_events), labelled(framework_events)])
    _assign_ids(owner, "channel id", labelled(spec.channels), requested, put,
                after=[labelled(generated_channels), labelled(framework_channels)])
    _assign_ids(owner, "parameter id", labelled(spec.params), requested, put)
    spec.events += generated_events + framework_events
    spec.channels += generated_channels + framework_channels

    special_kinds = ["time get"]
    if spec.commands:
        special_kinds += ["command recv", "command reg", "command resp"]
    if spec.events:
        special_kinds += ["event", "text event"]
    if spec.channels:
        special_kinds.append("telemetry")
    if spec.params:
        special_kinds += ["param get", "param set"]
    for kind in special_kinds:
        port_name, port_type, direction = SPECIAL_PORTS[kind]
        spec.special[kind] = port_name
        if direction == "input":
            spec.inputs[port_name] = InputPortDecl(port_type, "sync", name=port_name, handler=cls._command_in)
        else:
            out = OutputPort(port_type)
            out.name = port_name
            spec.outputs[port_name] = out
    return spec


def _echo_members(owner: str, param: Param[Any]) -> tuple[Event, Channel[Any]]:
    """The ``…ParamSet`` event and ``…Param`` channel the framework declares for ``param``."""
    echo = param.echo
    assert echo is not None
    event = Event(Severity.ACTIVITY_HI, echo.event_format(param.name), id=echo.event_id, value=param.type)
    event.name = event.attr = echo.event_name(param.name)
    event.finish(owner)
    channel: Channel[Any] = Channel(param.type, id=echo.channel_id)
    channel.name = channel.attr = echo.channel_name(param.name)
    channel.finish(owner)
    return event, channel


def _framework_member(name: str, make: Callable[[], Any], owner: str) -> Any:
    member = make()
    member.name = member.attr = name
    member.framework = True
    member.finish(owner)
    return member


def _declared_input(cls: Any, key: str) -> Any:
    for klass in cls.__mro__:
        value = _members(klass).get(key)
        if value is not None and hasattr(value, "__fprime_input__"):
            return value.__fprime_input__
    return None


def _declared_command(cls: Any, key: str) -> Any:
    for klass in cls.__mro__:
        value = _members(klass).get(key)
        if value is not None and hasattr(value, "__fprime_command__"):
            return value.__fprime_command__
    return None


class Component(metaclass=ComponentMeta):
    """Base of all components. Use :class:`PassiveComponent`, :class:`QueuedComponent` or
    :class:`ActiveComponent`.

    Args:
        name: the instance name (F´ spelling, e.g. ``"detumbleManager"``).
        base_id: added to every local opcode, event, channel and parameter id.
    """

    __fprime_abstract__ = True
    __fprime_kind__ = "passive"
    __fprime_spec__: ComponentSpec

    # The framework's ports, set on each instance (annotations only: a class attribute of the same
    # name would stop CPython specialising the instance attribute lookup; see decision 0001).
    timeCaller: list[Callable[[], Time]]
    logOut: list[Callable[..., Any]]
    logTextOut: list[Callable[..., Any]]
    tlmOut: list[Callable[..., Any]]
    cmdRegOut: list[Callable[..., Any]]
    cmdResponseOut: list[Callable[..., Any]]
    prmGetOut: list[Callable[..., Any]]
    prmSetOut: list[Callable[..., Any]]

    def __init__(self, name: str, *, base_id: int = 0) -> None:
        if not isinstance(name, str) or not name.isidentifier():
            raise ValueError(f"component name must be an identifier, got {name!r}")
        if not isinstance(base_id, int) or not 0 <= base_id <= 0xFFFFFFFF:
            raise ValueError(f"{name}: base_id must be a U32, got {base_id!r}")
        spec = type(self).__fprime_spec__
        self.name = name
        self.base_id = base_id
        self._lock = threading.RLock()
        self.handler_faults = 0
        self._deferred = False
        self._current_command: CommandToken | None = None
        self._outputs: dict[str, OutputPortArray] = {}
        for decl in spec.outputs.values():
            port = OutputPortArray(self, decl)
            self._outputs[decl.name] = port
            setattr(self, decl.name, port.calls)  # the hot path: an exact list of call slots
        self._time_port = self._outputs["timeCaller"]
        # The time port's call the clock below was worked out for, and that clock (see _port_time).
        self._clock_now: Any = None
        self._clock: Any = NO_CLOCK_READING
        self._commands = {c.opcode: c for c in spec.commands}
        self._command_handlers = {c.opcode: getattr(self, c.name) for c in spec.commands
                                  if c.kind not in ("set", "save")}
        self._events: dict[str, BoundEvent] = {}
        for e in spec.events:
            event = BoundEvent(self, e, base_id + e.local_id)
            setattr(self, e.attr, event)
            self._events[e.name] = event
        self._channels: dict[str, BoundChannel[Any]] = {}
        for c in spec.channels:
            channel = bind_channel(self, c, base_id + c.local_id)
            setattr(self, c.attr, channel)
            self._channels[c.name] = channel
        self._params: dict[str, BoundParam[Any]] = {}
        for p in spec.params:
            param = BoundParam(self, p, base_id + p.local_id)
            setattr(self, p.attr, param)
            self._params[p.name] = param
        #: Parameter name -> its bound echo (event, channel).
        self._echoes = {prm: (self._events[e.name], self._channels[c.name]) for prm, (e, c) in spec.echoes.items()}
        self._inputs: dict[str, InputPortArray] = {}
        for idecl in spec.inputs.values():
            if idecl.name == spec.special.get("command recv"):
                entries: list[Callable[..., Any]] = [self._command_in]
            else:
                entries = bind_input_entries(self, idecl)
            self._inputs[idecl.name] = InputPortArray(self, idecl, entries)

    # --- ports ------------------------------------------------------------------------------------

    def input_port(self, name: str) -> InputPortArray:
        """The input port ``name`` (to connect an output to it)."""
        try:
            return self._inputs[name]
        except KeyError:
            raise KeyError(f"{type(self).__name__} {self.name!r} has no input port {name!r}; input ports: "
                           f"{', '.join(self._inputs) or 'none'}") from None

    def output_port(self, name: str) -> OutputPortArray:
        """The output port ``name`` (to connect it, or ask what it is connected to)."""
        try:
            return self._outputs[name]
        except KeyError:
            raise KeyError(f"{type(self).__name__} {self.name!r} has no output port {name!r}; output ports: "
                           f"{', '.join(self._outputs) or 'none'}") from None

    def is_connected(self, port: str, index: int = 0) -> bool:
        """Whether output ``port[index]`` is connected (F´'s ``isConnected_<port>_OutputPort``)."""
        try:
            targets = self._outputs[port].targets
        except KeyError:
            targets = self.output_port(port).targets  # raises the KeyError that names the ports
        return targets[index] is not None

    @property
    def input_ports(self) -> dict[str, InputPortArray]:
        return dict(self._inputs)

    @property
    def output_ports(self) -> dict[str, OutputPortArray]:
        return dict(self._outputs)

    @property
    def spec(self) -> ComponentSpec:
        return type(self).__fprime_spec__

    def get_time(self) -> Time:
        """The current time from the time-get port (a zero TB_NONE time when unconnected)."""
        call = self.timeCaller[0]
        clock = self._clock
        if call is self._clock_now and clock._now_at == clock.current_us:
            return clock._now  # what call() returns at this instant (see _port_time)
        return self._port_time(call)

    def _port_time(self, call: Callable[[], Time]) -> Time:
        """What the time port's slot ``call`` gives now (the zero TB_NONE time when unconnected).

        Also notes whether ``call`` is a :class:`~fprime_lite.model.time.SimulatedClock`'s own
        ``now`` (:func:`~fprime_lite.model.time.simulated_clock_of`): while the slot holds that very
        callable and the clock has made its Time of the present instant, the framework's time reads
        (``get_time``, channel writes, a rate group's cycle end) take that Time without the call.
        Any other callable, a reconnection or a disconnection is seen at the next read.
        """
        if self._time_port.targets[0] is None:
            return _ZERO_TIME
        if call is not self._clock_now:
            self._clock_now = call
            self._clock = simulated_clock_of(call)
        return call()

    # --- ids -------------------------------------------------------------------------------------

    def opcode(self, command: str) -> int:
        return self.base_id + self.spec.command(command).opcode

    def event_id(self, event: str) -> int:
        return self.base_id + self.spec.event(event).local_id

    def channel_id(self, channel: str) -> int:
        return self.base_id + self.spec.channel(channel).local_id

    def param_id(self, param: str) -> int:
        return self.base_id + self.spec.param(param).local_id

    @property
    def events(self) -> dict[str, BoundEvent]:
        return dict(self._events)

    @property
    def channels(self) -> dict[str, BoundChannel[Any]]:
        return dict(self._channels)

    @property
    def params(self) -> dict[str, BoundParam[Any]]:
        return dict(self._params)

    # --- faults ----------------------------------------------------------------------------------

    def report_fault(self, where: str, exc: BaseException) -> None:
        """Count a handler fault and make it visible: the log (with its traceback), the throttled
        WARNING_HI event ``HandlerFault(where, exception)`` and the ``HandlerFaults`` channel.

        The framework calls it for every fault it contains in a deployment; a component that
        contains a fault of its own (a cycle that must go on) calls it too. It never raises.
        """
        self.handler_faults += 1
        log.error("%s: %s raised", self.name, where, exc_info=(type(exc), exc, exc.__traceback__))
        try:
            text = f"{type(exc).__name__}: {exc}"
            self._events["HandlerFault"](fit_utf8(where, 40), fit_utf8(text, 120))
            self._channels["HandlerFaults"].write(self.handler_faults & 0xFFFFFFFF)
        except Exception:  # reporting a fault must not raise another
            log.exception("%s: reporting a fault failed", self.name)

    # --- start-up hooks (the deployment calls them on every component, in this order) --------------

    def clean_temporary_files(self) -> list[str]:
        """Start-up, first of all: remove the temporary files that a killed earlier run left
        half-written, and return their paths. The default removes nothing (a component that writes
        no files); PrmDb and the file services override it."""
        return []

    def use_command_lookup(self, lookup: Callable[[str], Any]) -> None:
        """Start-up, before commands are registered: the deployment's command table,
        ``lookup(name) -> (opcode, argument types)``, for a component that compiles command names
        (the sequencer's text sequences). The default ignores it."""

    # --- commands --------------------------------------------------------------------------------

    def register_commands(self) -> None:
        """Send every opcode out of the command-registration port (F´'s ``regCommands``)."""
        reg = self._outputs.get("cmdRegOut")
        if reg is None or not reg.is_connected(0):
            return
        for c in self.spec.commands:
            reg.calls[0](self.base_id + c.opcode)

    def _command_in(self, opcode: int, cmd_seq: int, args: bytes) -> None:
        decl = self._commands.get(opcode - self.base_id)
        if decl is None:
            self._respond(opcode, cmd_seq, CmdResponse.INVALID_OPCODE)
            return
        if decl.kind == "set":
            self._respond(opcode, cmd_seq, self._param_set(decl.param, args))
            return
        if decl.kind == "save":
            self._respond(opcode, cmd_seq, self._param_save(decl.param, args))
            return
        try:
            values = deserialize_values(decl.arg_types, args)
        except SerializationError as exc:
            log.info("%s: %s: malformed arguments: %s", self.name, decl.name, exc)
            self._respond(opcode, cmd_seq, CmdResponse.FORMAT_ERROR)
            return
        if decl.kind == "sync":
            self._run_command(decl, opcode, cmd_seq, values)
        elif decl.kind == "guarded":
            with self._lock:
                self._run_command(decl, opcode, cmd_seq, values)
        else:
            self._queue_command(decl, opcode, cmd_seq, values)

    def _queue_command(self, decl: CommandDecl, opcode: int, cmd_seq: int, values: list[Any]) -> None:
        raise FwAssertionError(f"{self.name}: async command {decl.name} on a component without a queue")

    def _run_command(self, decl: CommandDecl, opcode: int, cmd_seq: int, values: list[Any]) -> None:
        self._deferred = False
        self._current_command = CommandToken(opcode, cmd_seq)
        try:
            result = self._command_handlers[decl.opcode](*values)
        except Exception as exc:  # noqa: BLE001 - a handler fault answers EXECUTION_ERROR, it never escapes
            self.report_fault(decl.name, exc)
            result = CmdResponse.EXECUTION_ERROR
        finally:
            self._current_command = None
        if self._deferred:
            return
        if result is None:
            result = CmdResponse.OK
        if not isinstance(result, CmdResponse):
            raise FwAssertionError(f"{self.name}: command {decl.name} returned {result!r}; return a "
                                   f"CmdResponse or None")
        self._respond(opcode, cmd_seq, result)

    def defer_command_response(self) -> CommandToken:
        """Called inside a command handler: the response will come later through
        :meth:`command_response`. Returns the token to answer with."""
        if self._current_command is None:
            raise FwAssertionError(f"{self.name}: defer_command_response() called outside a command handler")
        self._deferred = True
        return self._current_command

    def command_response(self, token: CommandToken, response: CmdResponse) -> None:
        """Answer a deferred command."""
        self._respond(token.opcode, token.cmd_seq, response)

    def _respond(self, opcode: int, cmd_seq: int, response: CmdResponse) -> None:
        out = self._outputs["cmdResponseOut"]
        if out.targets[0] is not None:
            out.calls[0](opcode, cmd_seq, response)

    # --- parameters ------------------------------------------------------------------------------

    def _param_set(self, decl: Param[Any], args: bytes) -> CmdResponse:
        bound = self._params[decl.name]
        try:
            value, end = decl.type.deserialize(args)
            if end != len(args):
                raise SerializationError(f"{len(args) - end} byte(s) left over")
        except SerializationError as exc:
            log.info("%s: %s_PRM_SET: bad value: %s", self.name, decl.name.upper(), exc)
            return CmdResponse.VALIDATION_ERROR
        problem = decl.invalid_reason(value)
        if problem is not None:
            log.warning("%s: %s_PRM_SET refused: %s", self.name, decl.name.upper(), problem)
            self._events["ParamSetRefused"](fit_utf8(decl.name, 40), fit_utf8(problem, 120))
            return CmdResponse.VALIDATION_ERROR
        with self._lock:
            bound.value = value
            bound.validity = ParamValid.VALID
        echo = self._echoes.get(decl.name)
        if echo is not None:
            echo[0](value)
            echo[1].write(value)
        self.parameter_updated(decl.local_id)
        return CmdResponse.OK

    def _param_save(self, decl: Param[Any], args: bytes) -> CmdResponse:
        if args:
            return CmdResponse.FORMAT_ERROR
        out = self._outputs["prmSetOut"]
        if out.targets[0] is None:
            return CmdResponse.EXECUTION_ERROR
        bound = self._params[decl.name]
        with self._lock:
            data = decl.type.serialize(bound.value)
        out.calls[0](bound.id, data)
        return CmdResponse.OK

    def load_parameters(self) -> None:
        """Fetch every parameter through the param-get port, then run :meth:`parameters_loaded`.

        A value PrmDb has that does not deserialize or fails the parameter's validation is
        replaced by the default and reported (``ParamDefaulted``). Echo channels are written with
        the loaded values before the hook runs.
        """
        get = self._outputs.get("prmGetOut")
        for bound in self._params.values():
            if get is not None and get.targets[0] is not None:
                validity, data = get.calls[0](bound.id)
            else:
                validity, data = ParamValid.UNINIT, None
            problem = bound.load(validity, data)
            if problem is not None:
                log.warning("%s: parameter %s: the stored value is refused (%s); using the default %r",
                            self.name, bound.decl.name, problem, bound.value)
                self._events["ParamDefaulted"](fit_utf8(bound.decl.name, 40), fit_utf8(problem, 120))
        for name, (_, channel) in self._echoes.items():
            channel.write(self._params[name].value)
        self.parameters_loaded()

    def parameter_updated(self, local_id: int) -> None:
        """Hook: a parameter was set by command (``local_id`` is its local id)."""

    def parameters_loaded(self) -> None:
        """Hook: every parameter has been loaded at start-up."""

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r} base 0x{self.base_id:X}>"


class PassiveComponent(Component):
    """A component with no queue and no thread: sync and guarded inputs only."""

    __fprime_abstract__ = True
    __fprime_kind__ = "passive"

    def _make_enqueuer(self, decl: InputPortDecl, call: Callable[..., Any], index: int) -> Callable[..., Any]:
        raise FwAssertionError(f"{self.name}: passive components have no queue")


class QueuedComponent(Component):
    """A component with a message queue and no thread: async calls wait until :meth:`dispatch`."""

    __fprime_abstract__ = True
    __fprime_kind__ = "queued"

    def __init__(self, name: str, *, base_id: int = 0, queue_size: int = 10):
        self._queue = MessageQueue(name, queue_size)
        self._thread: threading.Thread | None = None
        self._handling = False  # a message's handler is running (it may queue more)
        #: Set by a deterministic scheduler that drains this queue after every event: ports
        #: declared ``run_when_idle`` may then run at once instead of being queued.
        self.drained_by_scheduler = False
        super().__init__(name, base_id=base_id)

    def _make_enqueuer(self, decl: InputPortDecl, call: Callable[..., Any], index: int) -> Callable[..., Any]:
        queue = self._queue
        priority = decl.priority
        queue_full = decl.queue_full
        label = f"{self.name}.{decl.name}[{index}]"
        overflow = getattr(self, f"{decl.name}_overflow_hook", None)
        if overflow is not None and decl.size > 1:
            overflow = _with_port_num(overflow, index)

        try_push = queue.try_push

        def enqueue(*args: Any) -> None:
            if not try_push(priority, call, args):
                queue.put(priority, call, args, queue_full=queue_full, port=label, overflow=overflow,
                          run_inline=self.dispatch, threaded=self._thread is not None)

        if not decl.run_when_idle:
            return enqueue

        heap = queue._heap

        port_name = decl.name

        def run_or_enqueue(*args: Any) -> None:
            if self.drained_by_scheduler and not heap and not self._handling and self._thread is None:
                self._handling = True
                try:
                    call(*args)
                except Exception as exc:  # noqa: BLE001 - as on a component thread: reported, never fatal
                    self.report_fault(port_name, exc)
                finally:
                    self._handling = False
            else:
                enqueue(*args)

        return run_or_enqueue

    def _queue_command(self, decl: CommandDecl, opcode: int, cmd_seq: int, values: list[Any]) -> None:
        accepted = self._queue.put(decl.priority, self._run_command, (decl, opcode, cmd_seq, values),
                                   queue_full=decl.queue_full, port=f"{self.name}.{decl.name}",
                                   overflow=lambda *a: None, run_inline=self.dispatch,
                                   threaded=self._thread is not None)
        if not accepted:
            self._respond(opcode, cmd_seq, CmdResponse.EXECUTION_ERROR)

    @property
    def queue(self) -> MessageQueue:
        return self._queue

    def dispatch(self) -> bool:
        """Handle the next queued message; return False when the queue was empty."""
        message = self._queue.get()
        if message is None:
            return False
        call, args = message
        outer, self._handling = self._handling, True  # dispatch may run inside a handler (a full queue)
        try:
            call(*args)
        finally:
            self._handling = outer
        return True

    def dispatch_all(self, limit: int | None = None, *, contain_faults: bool = False) -> int:
        """Handle queued messages until the queue is empty (or ``limit``); return how many.

        With ``contain_faults`` (what a deployment's scheduler asks), a handler that raises is
        reported (:meth:`report_fault`) and the messages behind it still run; otherwise (a harness)
        the exception propagates.
        """
        queue = self._queue
        if not queue._heap:  # the common case when drained after every event
            return 0
        n = 0
        outer, self._handling = self._handling, True
        try:
            while (limit is None or n < limit) and queue._heap:
                message = queue.get()
                if message is None:  # another thread took it
                    break
                call, args = message
                n += 1
                if contain_faults:
                    try:
                        call(*args)
                    except Exception as exc:  # noqa: BLE001 - as on a component thread: reported, never fatal
                        self.report_fault(_port_of(call), exc)
                else:
                    call(*args)
        finally:
            self._handling = outer
        return n


def _port_of(call: Any) -> str:
    """The port (handler) name of a queued call, for a fault report."""
    while isinstance(call, functools.partial):
        call = call.func
    return str(getattr(call, "__fprime_port__", None) or getattr(call, "__name__", None) or repr(call))


def _with_port_num(fn: Callable[..., Any], index: int) -> Callable[..., Any]:
    def hook(*args: Any) -> Any:
        return fn(index, *args)
    return hook


_EXIT: Any = object()


class ActiveComponent(QueuedComponent):
    """A component with a queue and, optionally, its own thread.

    By default an active component is dispatched deterministically by whoever runs the deployment
    (the scheduler drains its queue). :meth:`start` gives it a real thread instead.
    """

    __fprime_abstract__ = True
    __fprime_kind__ = "active"

    def start(self) -> None:
        """Run the component's queue on its own thread until :meth:`exit`."""
        if self._thread is not None:
            raise FwAssertionError(f"{self.name}: already started")
        self._thread = threading.Thread(target=self._thread_loop, name=self.name, daemon=True)
        self._thread.start()

    def _thread_loop(self) -> None:
        while True:
            message = self._queue.get(block=True)
            if message is None:
                continue
            call, args = message
            if call is _EXIT:
                return
            try:
                call(*args)
            except Exception as exc:  # noqa: BLE001 - a thread must not die on a handler fault
                self.report_fault(_port_of(call), exc)

    def exit(self, timeout: float | None = 5.0) -> None:
        """Stop the thread after the messages already queued (no-op when not started)."""
        if self._thread is None:
            return
        self._queue.put(-(1 << 30), _EXIT, (), queue_full="block", port=f"{self.name} exit",
                        threaded=True)
        self._thread.join(timeout)
        self._thread = None
