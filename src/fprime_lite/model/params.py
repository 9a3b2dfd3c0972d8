"""Parameters: declarations, validity, validation, echoes, the generated PRM_SET / PRM_SAVE commands.

Declared as attributes of a component class::

    GAIN = Param(F64, default=3.0, id=39, low=0.0, high=100.0)

and read on an instance as ``self.GAIN.value`` (``self.GAIN.validity`` says where it came from).
Each parameter ``P`` generates the commands ``P_PRM_SET(val)`` and ``P_PRM_SAVE`` (the name in upper
case, as F´ spells them: ``Gain`` gives ``GAIN_PRM_SET``). At start-up the
deployment calls ``load_parameters()``: every parameter is fetched from PrmDb through the param-get
port, then the ``parameters_loaded()`` hook runs. A PRM_SET calls ``parameter_updated(local_id)``.

Validation (optional): ``low``/``high`` (inclusive bounds; a bound also refuses NaN), ``finite``
(refuse NaN and ±inf) and ``validate`` (a function of the value returning ``None`` when it is
acceptable, else the reason). A PRM_SET whose value fails answers VALIDATION_ERROR and changes
nothing; a PrmDb value that fails is replaced by the default. Either way the component emits the
framework event ``ParamInvalid`` (see :mod:`fprime_lite.model.component`).

Echo (optional, the PROVES pattern): ``echo=ParamEcho(...)`` makes the framework declare an event
``<Stem>ParamSet(value)`` (ACTIVITY_HI, emitted after every accepted PRM_SET) and a channel
``<Stem>Param`` (written after every accepted PRM_SET and once when parameters are loaded), where
``<Stem>`` is the F´ name in camel case (``X_PLUS_VOLTAGE`` → ``XPlusVoltage``).
"""

from __future__ import annotations

import builtins

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Generic, TypeVar, overload

from fprime_lite.model.errors import DeclarationError, SerializationError, check_member_name, check_units
from fprime_lite.model.types import FwEnum, FwType, fw_type

__all__ = ["ParamValid", "Param", "ParamEcho", "BoundParam", "camel_stem"]

V = TypeVar("V")

_NO_DEFAULT: Any = object()


class ParamValid(FwEnum, namespace="Fw"):
    """Where a parameter's value came from (``Fw.ParamValid``)."""

    UNINIT = 0
    VALID = 1
    INVALID = 2
    DEFAULT = 3


def camel_stem(param_name: str) -> str:
    """``X_PLUS_VOLTAGE`` → ``XPlusVoltage``: the stem of a parameter's echo event and channel."""
    return "".join(part.capitalize() for part in param_name.split("_"))


@dataclass(frozen=True)
class ParamEcho:
    """How the framework echoes a parameter to the ground.

    ``event_id``/``channel_id`` are local ids (``None``: numbered after every member the class
    declares itself). ``unit`` ends the event text (``"X parameter set to {} m."``); ``format``
    replaces the whole text; ``event``/``channel`` replace the generated names.
    """

    event_id: int | None = None
    channel_id: int | None = None
    unit: str | None = None
    format: str | None = None
    event: str | None = None
    channel: str | None = None

    def event_name(self, param: str) -> str:
        return self.event or f"{camel_stem(param)}ParamSet"

    def channel_name(self, param: str) -> str:
        return self.channel or f"{camel_stem(param)}Param"

    def event_format(self, param: str) -> str:
        if self.format is not None:
            return self.format
        unit = f" {self.unit}" if self.unit else ""
        return f"{param} parameter set to {{}}{unit}."


class Param(Generic[V]):
    """Declares a parameter of F´ type ``type_`` with an optional ``default``.

    ``name`` gives the parameter an F´ name other than its attribute's (see :class:`Channel`).
    ``low``, ``high``, ``finite`` and ``validate`` restrict the values a PRM_SET or the parameter
    file may give it; ``echo`` asks the framework for its ``…ParamSet`` event and ``…Param`` channel.
    ``units`` (e.g. ``"N·m"``, with the frame where it matters) is documentation for the ground, as a
    channel's: ``fprime-lite params --list`` shows it and the dictionary carries it as the parameter's
    ``annotation`` (``"units: N·m"``). It changes no value, id or file byte.
    """

    type: FwType[V]
    default: V

    @overload
    def __init__(self, type_: FwType[V], *, default: Any = ..., id: int | None = ...,
                 set_opcode: int | None = ..., save_opcode: int | None = ..., name: str | None = ...,
                 low: Any = ..., high: Any = ..., finite: bool = ...,
                 validate: Callable[[V], str | None] | None = ..., echo: ParamEcho | None = ...,
                 units: str | None = ...) -> None: ...

    @overload
    def __init__(self, type_: builtins.type[V], *, default: Any = ..., id: int | None = ...,
                 set_opcode: int | None = ..., save_opcode: int | None = ..., name: str | None = ...,
                 low: Any = ..., high: Any = ..., finite: bool = ...,
                 validate: Callable[[V], str | None] | None = ..., echo: ParamEcho | None = ...,
                 units: str | None = ...) -> None: ...

    def __init__(self, type_: Any, *, default: Any = _NO_DEFAULT, id: int | None = None,
                 set_opcode: int | None = None, save_opcode: int | None = None, name: str | None = None,
                 low: Any = None, high: Any = None, finite: bool = False,
                 validate: Callable[[Any], str | None] | None = None, echo: ParamEcho | None = None,
                 units: str | None = None) -> None:
        for label, value in (("id", id), ("set_opcode", set_opcode), ("save_opcode", save_opcode)):
            if value is not None and (not isinstance(value, int) or value < 0):
                raise DeclarationError(f"param {label} must be a non-negative integer, got {value!r}")
        if validate is not None and not callable(validate):
            raise DeclarationError(f"param validate must be a function of the value, got {validate!r}")
        if echo is not None and not isinstance(echo, ParamEcho):
            raise DeclarationError(f"param echo must be a ParamEcho(...), got {echo!r}")
        self._raw_type = type_
        self._raw_default = default
        self.has_default = default is not _NO_DEFAULT
        self.requested_id = id
        self.local_id = -1  # assigned when the component class is built
        self.set_opcode = set_opcode
        self.save_opcode = save_opcode
        self.fprime_name = check_member_name(name, "param")
        self.low = low
        self.high = high
        self.finite = bool(finite)
        self.validate = validate
        self.echo = echo
        self.units = check_units(units, "param")
        self.name = ""
        self.attr = ""

    if TYPE_CHECKING:  # what a checker sees: on an instance the attribute is the BoundParam
        @overload
        def __get__(self, instance: None, owner: Any) -> Param[V]: ...
        @overload
        def __get__(self, instance: object, owner: Any) -> BoundParam[V]: ...
        def __get__(self, instance: object, owner: Any) -> Param[V] | BoundParam[V]: ...

    def __set_name__(self, owner: builtins.type, name: str) -> None:
        self.name = name

    def finish(self, owner: str) -> None:
        where = f"{owner}.{self.name}"
        try:
            self.type = fw_type(self._raw_type)
        except DeclarationError as exc:
            raise DeclarationError(f"{where}: {exc}") from None
        if (self.low is not None or self.high is not None or self.finite) and self.type.kind not in ("integer",
                                                                                                      "float"):
            raise DeclarationError(f"{where}: low=, high= and finite= apply to numeric parameters; "
                                   f"{self.type.name} is not one (use validate=)")
        for label, bound in (("low", self.low), ("high", self.high)):
            if bound is not None:
                try:
                    self.type.check(bound)
                except SerializationError as exc:
                    raise DeclarationError(f"{where}: {label}={bound!r} is not a {self.type.name}: {exc}") from None
        if self.low is not None and self.high is not None and not self.low <= self.high:
            raise DeclarationError(f"{where}: low={self.low!r} is above high={self.high!r}")
        if self.has_default:
            try:
                self.default = self.type.check(self._raw_default)
            except SerializationError as exc:
                raise DeclarationError(f"{where}: default {self._raw_default!r} does not fit: {exc}") from None
            problem = self.invalid_reason(self.default)
            if problem is not None:
                raise DeclarationError(f"{where}: default {self.default!r} is not valid: {problem}")
        else:
            self.default = self.type.default

    def invalid_reason(self, value: Any) -> str | None:
        """Why ``value`` (already of the parameter's type) is refused, or None when it is accepted."""
        if self.finite or self.low is not None or self.high is not None:
            if isinstance(value, float) and not math.isfinite(value):
                return f"{value!r} is not a finite number"
        if self.low is not None and not value >= self.low:
            return f"{value!r} is below the minimum {self.low!r}"
        if self.high is not None and not value <= self.high:
            return f"{value!r} is above the maximum {self.high!r}"
        if self.validate is not None:
            return self.validate(value)
        return None

    def __repr__(self) -> str:
        t = getattr(self, "type", None)
        return f"Param {self.name} ({t.name if t is not None else self._raw_type})"


class BoundParam(Generic[V]):
    """A parameter of one component instance: its current value and validity."""

    __slots__ = ("component", "decl", "id", "value", "validity")

    def __init__(self, component: Any, decl: Param[V], param_id: int) -> None:
        self.component = component
        self.decl = decl
        self.id = param_id
        self.value: V = decl.default
        self.validity = ParamValid.UNINIT

    @property
    def local_id(self) -> int:
        return self.decl.local_id

    def get(self) -> V:
        """The current value (F´'s ``paramGet_P``)."""
        return self.value

    def set(self, value: Any, validity: ParamValid = ParamValid.VALID) -> None:
        """Set the component's copy (what PRM_SET does, without the command or validation)."""
        self.value = self.decl.type.check(value)
        self.validity = validity

    def load(self, validity: ParamValid, data: bytes | None) -> str | None:
        """Take the value PrmDb returned; fall back to the default as F´'s loadParameters does.

        Returns why a value PrmDb had was refused (it does not deserialize, or fails validation),
        or None when it was taken or PrmDb had none.
        """
        problem = None
        if validity == ParamValid.VALID and data is not None:
            try:
                value, end = self.decl.type.deserialize(data)
                if end != len(data):
                    raise SerializationError(f"{len(data) - end} byte(s) left over")
            except SerializationError as exc:
                problem = str(exc)
            else:
                problem = self.decl.invalid_reason(value)
                if problem is None:
                    self.value = value
                    self.validity = ParamValid.VALID
                    return None
        self.value = self.decl.default
        self.validity = ParamValid.DEFAULT if self.decl.has_default else ParamValid.INVALID
        return problem

    def __repr__(self) -> str:
        return f"<param {self.component.name}.{self.decl.name} = {self.value!r} ({self.validity.name})>"
