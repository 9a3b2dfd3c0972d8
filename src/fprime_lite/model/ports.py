"""Typed ports: port types, input and output port declarations, and connections.

A :class:`PortType` is declared once and names the call's arguments (and return type, if the port
returns a value)::

    Sched = PortType("Svc.Sched", context=U32)
    GetSystemMode = PortType("Components.GetSystemMode", returns=SystemMode)

A component receives calls through decorated methods (:func:`sync_input`, :func:`guarded_input`,
:func:`async_input`) and makes calls through :class:`OutputPort` attributes. On an instance, an
output port attribute is the list of its call slots: index it and call, ``self.xPlusStart[0](level)``;
``self.is_connected("xPlusStart", 0)`` checks first. The port's connection state is the
:class:`OutputPortArray` that ``component.output_port(name)`` returns.

Binding happens at connect time: the output's slot holds the target's callable itself (for a sync
input of one port, the bound handler method), so a call through a connected port costs one list
index more than a plain method call. Handlers of single input ports take the port's arguments;
handlers of input port *arrays* (``size > 1``) receive ``port_num`` first, as in F´.
"""

from __future__ import annotations

import functools
import inspect
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, TypeVar, overload

from fprime_lite.model.errors import DeclarationError, PortConnectionError, UnconnectedPortError

__all__ = [
    "PortType", "InputPortDecl", "OutputPort", "OutputPortArray", "InputPortArray",
    "sync_input", "guarded_input", "async_input", "QUEUE_FULL_BEHAVIOURS",
]

QUEUE_FULL_BEHAVIOURS = ("assert", "block", "drop", "hook")


class PortType:
    """A named call signature shared by the two ends of a connection.

    Args:
        name: qualified F´ name, e.g. ``"Svc.Sched"``.
        returns: the type of the returned value, or None for a port that returns nothing.
        **args: argument names and their types, in call order.
    """

    def __init__(self, name: str, *, returns: Any = None, **args: Any):
        self.name = name
        self.args: list[tuple[str, Any]] = list(args.items())
        self.returns = returns

    @property
    def arg_names(self) -> list[str]:
        return [n for n, _ in self.args]

    def __repr__(self) -> str:
        sig = ", ".join(f"{n}: {getattr(t, 'name', getattr(t, '__name__', t))}" for n, t in self.args)
        ret = f" -> {getattr(self.returns, 'name', getattr(self.returns, '__name__', self.returns))}" \
            if self.returns is not None else ""
        return f"PortType {self.name}({sig}){ret}"


@dataclass
class InputPortDecl:
    """An input port declared by decorating its handler method."""

    port_type: PortType
    kind: str  # "sync" | "guarded" | "async"
    size: int = 1
    priority: int = 0
    queue_full: str = "assert"
    name: str = ""
    handler: Callable | None = None
    run_when_idle: bool = False  # async only: see async_input

    def check_handler(self, owner: str, fn: Callable) -> None:
        """Raise DeclarationError unless ``fn``'s signature fits the port type."""
        params = list(inspect.signature(fn).parameters.values())[1:]  # drop self
        if any(p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) for p in params):
            return
        expected = (["port_num"] if self.size > 1 else []) + self.port_type.arg_names
        if len(params) != len(expected):
            raise DeclarationError(
                f"{owner}.{self.name}: handler takes {len(params)} argument(s) "
                f"({', '.join(p.name for p in params) or 'none'}) but port type "
                f"{self.port_type.name} needs {len(expected)} ({', '.join(expected) or 'none'})"
                + ("; handlers of port arrays take port_num first" if self.size > 1 else ""))
        if self.kind == "async" and self.port_type.returns is not None:
            raise DeclarationError(
                f"{owner}.{self.name}: async input ports cannot return a value "
                f"({self.port_type.name} returns {self.port_type.returns!r}); make it sync or guarded")


F = TypeVar("F", bound=Callable[..., Any])


def _input_decorator(kind: str, port_type: PortType, size: int, priority: int = 0,
                     queue_full: str = "assert", run_when_idle: bool = False) -> Callable[[F], F]:
    if not isinstance(port_type, PortType):
        raise DeclarationError(f"{kind}_input needs a PortType, got {port_type!r}")
    if not isinstance(size, int) or size < 1:
        raise DeclarationError(f"{kind}_input size must be a positive integer, got {size!r}")
    if queue_full not in QUEUE_FULL_BEHAVIOURS:
        raise DeclarationError(
            f"queue_full must be one of {', '.join(QUEUE_FULL_BEHAVIOURS)}, got {queue_full!r}")

    def decorate(fn: F) -> F:
        setattr(fn, "__fprime_input__", InputPortDecl(port_type, kind, size, priority, queue_full,
                                                      name=fn.__name__, handler=fn, run_when_idle=run_when_idle))
        return fn

    return decorate


def sync_input(port_type: PortType, *, size: int = 1) -> Callable[[F], F]:
    """Declare a sync input port: the handler runs on the caller's thread."""
    return _input_decorator("sync", port_type, size)


def guarded_input(port_type: PortType, *, size: int = 1) -> Callable[[F], F]:
    """Declare a guarded input port: the handler runs on the caller's thread under the component lock."""
    return _input_decorator("guarded", port_type, size)


def async_input(port_type: PortType, *, size: int = 1, priority: int = 0, queue_full: str = "assert",
                run_when_idle: bool = False) -> Callable[[F], F]:
    """Declare an async input port: the call is queued and handled on ``dispatch()``.

    ``priority``: larger runs first. ``queue_full``: what a full queue does — ``assert`` raises
    QueueFullError, ``block`` waits (threaded components) or drains (deterministic ones), ``drop``
    discards the message, ``hook`` calls the component's ``<port>_overflow_hook(*args)``.

    ``run_when_idle``: when a deterministic scheduler drains the component (a deployment without
    threads), a call that finds the queue empty and the component not handling a message runs at
    once on the caller's thread instead of waiting for the drain — what a top-priority thread
    blocked on an empty queue does on a flight processor. Otherwise (a harness, a real thread, a
    busy component) the call is queued as usual. Rate groups' ``CycleIn`` uses it (decision 0004).
    """
    if not isinstance(run_when_idle, bool):
        raise DeclarationError(f"async_input run_when_idle must be True or False, got {run_when_idle!r}")
    return _input_decorator("async", port_type, size, priority, queue_full, run_when_idle)


class OutputPort:
    """Declares an output port (or port array of ``size`` indices) of a component.

    ``required=True`` makes a topology refuse to start while any index is left unconnected.
    """

    def __init__(self, port_type: PortType, *, size: int = 1, required: bool = False):
        if not isinstance(port_type, PortType):
            raise DeclarationError(f"OutputPort needs a PortType, got {port_type!r}")
        if not isinstance(size, int) or size < 1:
            raise DeclarationError(f"OutputPort size must be a positive integer, got {size!r}")
        self.port_type = port_type
        self.size = size
        self.required = required
        self.name = ""

    if TYPE_CHECKING:  # what a checker sees: on an instance the attribute is the list of call slots
        @overload
        def __get__(self, instance: None, owner: Any) -> OutputPort: ...
        @overload
        def __get__(self, instance: object, owner: Any) -> list[Callable[..., Any]]: ...
        def __get__(self, instance: object, owner: Any) -> OutputPort | list[Callable[..., Any]]: ...

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __repr__(self) -> str:
        return f"OutputPort({self.port_type.name}, size={self.size})"


class _Unconnected:
    """Stands in an unconnected output slot; calling it raises UnconnectedPortError."""

    __slots__ = ("where",)

    def __init__(self, where: str):
        self.where = where

    def __call__(self, *args, **kwargs):
        raise UnconnectedPortError(
            f"{self.where} is not connected; connect it in the topology, or check "
            f"is_connected() before calling")


class InputPortArray:
    """The input port ``name`` of one component instance: the callables connections bind to."""

    def __init__(self, component, decl: InputPortDecl, entries: list[Callable]):
        self.component = component
        self.decl = decl
        self.name = decl.name
        self.port_type = decl.port_type
        self.entries = entries

    def __len__(self):
        return len(self.entries)

    def describe(self, index: int) -> str:
        return f"{self.component.name}.{self.name}[{index}]"

    def __repr__(self):
        return f"<input port {self.component.name}.{self.name} ({self.port_type.name}, {self.decl.kind})>"


class OutputPortArray:
    """The output port ``name`` of one component instance: its call slots and what they connect to.

    ``calls`` is a plain ``list`` with one callable per index; the component's attribute of the
    same name *is* that list, so ``self.xPlusStart[0](level)`` costs one list index more than a
    method call (a ``list`` subclass would miss CPython's fast path for ``list[int]``).
    """

    def __init__(self, component, decl: OutputPort):
        self.component = component
        self.name = decl.name
        self.port_type = decl.port_type
        self.required = decl.required
        self.targets: list[tuple[InputPortArray, int] | str | None] = [None] * decl.size
        self.calls: list[Callable] = [_Unconnected(self.describe(i)) for i in range(decl.size)]
        self.version = 0  # bumped on every (dis)connection, for callers that cache what is connected

    def __len__(self) -> int:
        return len(self.calls)

    def __getitem__(self, index: int) -> Callable:
        return self.calls[index]

    def describe(self, index: int) -> str:
        return f"output port {self.component.name}.{self.name}[{index}]"

    def is_connected(self, index: int = 0) -> bool:
        return self.targets[index] is not None

    def _check_index(self, index: int) -> None:
        if not 0 <= index < len(self.calls):
            raise PortConnectionError(
                f"{self.component.name}.{self.name} has indices 0..{len(self.calls) - 1}; "
                f"index {index} does not exist", "use an index within the port array")

    def connect(self, index: int, target: InputPortArray, target_index: int = 0) -> None:
        """Connect output index ``index`` to ``target[target_index]``; types must match."""
        self._check_index(index)
        src = f"{self.component.name}.{self.name}[{index}]"
        if not isinstance(target, InputPortArray):
            raise PortConnectionError(f"cannot connect {src} to {target!r}: not an input port")
        if not 0 <= target_index < len(target):
            raise PortConnectionError(
                f"cannot connect {src} to {target.component.name}.{target.name}[{target_index}]: "
                f"{target.name} has indices 0..{len(target) - 1}", "use an index within the port array")
        dst = target.describe(target_index)
        if target.port_type is not self.port_type:
            raise PortConnectionError(
                f"cannot connect {src} ({self.port_type.name}) to {dst} ({target.port_type.name}): "
                f"port types differ", "connect ports of the same port type")
        if self.targets[index] is not None:
            raise PortConnectionError(
                f"cannot connect {src} to {dst}: it is already connected to {self.target_name(index)}",
                "an output index connects to one input only (use another index)")
        self.calls[index] = target.entries[target_index]
        self.targets[index] = (target, target_index)
        self.version += 1

    def connect_callable(self, index: int, fn: Callable, label: str) -> None:
        """Bind index ``index`` to a plain callable (test harnesses, simulation adapters)."""
        self._check_index(index)
        self.calls[index] = fn
        self.targets[index] = label
        self.version += 1

    def disconnect(self, index: int) -> None:
        self._check_index(index)
        self.calls[index] = _Unconnected(self.describe(index))
        self.targets[index] = None
        self.version += 1

    def target_name(self, index: int) -> str | None:
        target = self.targets[index]
        if target is None or isinstance(target, str):
            return target
        port, j = target
        return port.describe(j)

    def __repr__(self):
        return f"<output port {self.component.name}.{self.name} ({self.port_type.name}, size {len(self)})>"


def bind_input_entries(component, decl: InputPortDecl) -> list[Callable]:
    """Make the callables that connections to ``component``'s input ``decl`` will hold."""
    handler = getattr(component, decl.name)
    entries: list[Callable] = []
    for i in range(decl.size):
        call = functools.partial(handler, i) if decl.size > 1 else handler
        if decl.kind == "guarded":
            call = _guarded(component, call)
        elif decl.kind == "async":
            call = component._make_enqueuer(decl, call, i)
        entries.append(call)
    return entries


def _guarded(component, call: Callable) -> Callable:
    lock = component._lock

    def guarded_call(*args):
        with lock:
            return call(*args)

    return guarded_call
