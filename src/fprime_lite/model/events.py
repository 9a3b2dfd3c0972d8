"""Events: severities, declarations with FPP format strings, throttling, the text-event form.

Declared as attributes of a component class::

    DetumbleStarted = Event(Severity.ACTIVITY_LO, "Detumble started at {.2f} deg/s", w=F64,
                            throttle=1)

and emitted on an instance as ``self.DetumbleStarted(w)``. An event with ``throttle=N`` is
suppressed after N emissions until ``self.DetumbleStarted.clear_throttle()``.

Format strings use FPP's placeholders: ``{}`` (any type), ``{c}`` ``{d}`` ``{x}`` ``{o}`` (integers),
``{e}`` ``{f}`` ``{g}`` and ``{.Ne}`` ``{.Nf}`` ``{.Ng}`` (floats); ``{{`` and ``}}`` are literal
braces. The placeholder count must equal the argument count, and each placeholder must suit its
argument's type; both are checked when the class is created.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any, overload

from fprime_lite.model.errors import DeclarationError
from fprime_lite.model.types import FwEnum, FwType, _U32, fw_type

__all__ = ["Severity", "Event", "BoundEvent", "translate_format"]


class Severity(FwEnum, namespace="Fw", rep=_U32):
    """F´ event severities (``Fw.LogSeverity``)."""

    FATAL = 1
    WARNING_HI = 2
    WARNING_LO = 3
    COMMAND = 4
    ACTIVITY_HI = 5
    ACTIVITY_LO = 6
    DIAGNOSTIC = 7


_PLACEHOLDER = re.compile(r"\{\{|\}\}|\{([^{}]*)\}|[{}]")
_INT_SPECS = {"c", "d", "x", "o"}
_FLOAT_SPECS = {"e", "f", "g"}
_PRECISION = re.compile(r"^\.(\d+)([efg])$")


def translate_format(fmt: str, arg_types: list[FwType[Any]], where: str) -> str:
    """Turn an FPP format string into a ``str.format`` template, checking it against the arguments."""
    out = []
    pos = 0
    index = 0
    for m in _PLACEHOLDER.finditer(fmt):
        out.append(fmt[pos:m.start()])
        pos = m.end()
        token = m.group(0)
        if token in ("{{", "}}"):
            out.append(token)
            continue
        if token in ("{", "}"):
            raise DeclarationError(f"{where}: unmatched {token!r} in format {fmt!r}; write {token * 2} "
                                   f"for a literal brace")
        spec = m.group(1)
        if index >= len(arg_types):
            raise DeclarationError(
                f"{where}: format {fmt!r} has more placeholders than the {len(arg_types)} argument(s)")
        t = arg_types[index]
        kind = t.kind
        if spec == "":
            out.append("{}")
        elif spec in _INT_SPECS:
            if kind != "integer":
                raise DeclarationError(f"{where}: placeholder {{{spec}}} needs an integer argument, "
                                       f"argument {index + 1} is {t.name}")
            out.append("{:" + spec + "}")
        elif spec in _FLOAT_SPECS or _PRECISION.match(spec):
            if kind != "float":
                raise DeclarationError(f"{where}: placeholder {{{spec}}} needs a float argument, "
                                       f"argument {index + 1} is {t.name}")
            out.append("{:" + spec + "}")
        else:
            raise DeclarationError(
                f"{where}: unknown placeholder {{{spec}}} in format {fmt!r}; use {{}}, {{c}}, {{d}}, "
                f"{{x}}, {{o}}, {{e}}, {{f}}, {{g}} or {{.Nf}}-style precision")
        index += 1
    out.append(fmt[pos:])
    if index != len(arg_types):
        raise DeclarationError(
            f"{where}: format {fmt!r} has {index} placeholder(s) but the event has "
            f"{len(arg_types)} argument(s)")
    return "".join(out)


class Event:
    """Declares an event. ``args`` are given as keywords in order (or as ``args=[(name, type)]``)."""

    def __init__(self, severity: Severity, format: str, *, id: int | None = None,
                 throttle: int | None = None, args: list[tuple[str, Any]] | None = None,
                 **kwargs: Any):
        if not isinstance(severity, Severity):
            raise DeclarationError(f"event severity must be a Severity, got {severity!r}")
        if throttle is not None and (not isinstance(throttle, int) or throttle < 1):
            raise DeclarationError(f"event throttle must be a positive integer, got {throttle!r}")
        if id is not None and (not isinstance(id, int) or id < 0):
            raise DeclarationError(f"event id must be a non-negative integer, got {id!r}")
        self.severity = severity
        self.format = format
        self.requested_id = id
        self.local_id = -1  # assigned when the component class is built
        self.throttle = throttle
        self._raw_args = list(args or []) + list(kwargs.items())
        self.args: list[tuple[str, FwType[Any]]] = []
        self.template = ""
        self.name = ""
        self.attr = ""
        self.framework = False  # True for the members the framework gives every component

    if TYPE_CHECKING:  # what a checker sees: on an instance the attribute is the BoundEvent
        @overload
        def __get__(self, instance: None, owner: Any) -> Event: ...
        @overload
        def __get__(self, instance: object, owner: Any) -> BoundEvent: ...
        def __get__(self, instance: object, owner: Any) -> Event | BoundEvent: ...

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def finish(self, owner: str) -> None:
        """Resolve argument types and check the format (called when the class is built)."""
        where = f"{owner}.{self.name}"
        try:
            self.args = [(n, fw_type(t)) for n, t in self._raw_args]
        except DeclarationError as exc:
            raise DeclarationError(f"{where}: {exc}") from None
        self.template = translate_format(self.format, [t for _, t in self.args], where)

    @property
    def arg_types(self) -> list[FwType[Any]]:
        return [t for _, t in self.args]

    def render(self, values: Any) -> str:
        """The event's text with ``values`` substituted (enum constants by name)."""
        return self.template.format(*values)

    def __repr__(self) -> str:
        return f"Event {self.name} ({self.severity.name})"


class BoundEvent:
    """An event of one component instance: call it to emit; keeps the throttle count."""

    __slots__ = ("component", "decl", "id", "count", "_types", "_severity", "_log_port", "_text_port")

    def __init__(self, component: Any, decl: Event, event_id: int) -> None:
        self.component = component
        self.decl = decl
        self.id = event_id
        self.count = 0
        self._types = decl.arg_types
        self._severity = decl.severity
        self._log_port = component.output_port("logOut")
        self._text_port = component.output_port("logTextOut")

    def __call__(self, *args: Any) -> bool:
        """Emit the event; return False when the throttle suppressed it."""
        decl = self.decl
        types = self._types
        if len(args) != len(types):
            raise TypeError(f"{self.component.name}.{decl.name} takes {len(types)} argument(s) "
                            f"({', '.join(n for n, _ in decl.args)}), got {len(args)}")
        throttle = decl.throttle
        if throttle is not None and self.count >= throttle:
            return False  # as F´: a throttled event does nothing more (its arguments are not looked at)
        values = [t.check(v) for t, v in zip(types, args, strict=True)]
        if throttle is not None:
            self.count += 1
        comp = self.component
        log_connected = self._log_port.targets[0] is not None
        text_connected = self._text_port.targets[0] is not None
        if not (log_connected or text_connected):
            return True
        time = comp.get_time()
        if log_connected:
            payload = b"".join(t.pack(v) for t, v in zip(types, values, strict=True))
            comp.logOut[0](self.id, time, self._severity, payload)
        if text_connected:
            comp.logTextOut[0](self.id, time, self._severity, f"({comp.name}) {decl.name}: {decl.render(values)}")
        return True

    def clear_throttle(self) -> None:
        """Let a throttled event be emitted again."""
        self.count = 0

    @property
    def throttled(self) -> bool:
        return self.decl.throttle is not None and self.count >= self.decl.throttle
