"""Parameters: declarations, validity, the generated PRM_SET / PRM_SAVE commands, loading.

Declared as attributes of a component class::

    GAIN = Param(F64, default=3.0, id=39)

and read on an instance as ``self.GAIN.value`` (``self.GAIN.validity`` says where it came from).
Each parameter ``P`` generates the commands ``P_PRM_SET(val)`` and ``P_PRM_SAVE``. At start-up the
deployment calls ``load_parameters()``: every parameter is fetched from PrmDb through the param-get
port, then the ``parameters_loaded()`` hook runs. A PRM_SET calls ``parameter_updated(local_id)``.
"""

from __future__ import annotations

from typing import Any

from fprime_lite.model.errors import DeclarationError, SerializationError, check_member_name
from fprime_lite.model.types import FwEnum, FwType, fw_type

__all__ = ["ParamValid", "Param"]

_NO_DEFAULT = object()


class ParamValid(FwEnum, namespace="Fw"):
    """Where a parameter's value came from (``Fw.ParamValid``)."""

    UNINIT = 0
    VALID = 1
    INVALID = 2
    DEFAULT = 3


class Param:
    """Declares a parameter of F´ type ``type_`` with an optional ``default``.

    ``name`` gives the parameter an F´ name other than its attribute's (see :class:`Channel`).
    """

    def __init__(self, type_: Any, *, default: Any = _NO_DEFAULT, id: int | None = None,  # noqa: A002
                 set_opcode: int | None = None, save_opcode: int | None = None, name: str | None = None):
        for label, value in (("id", id), ("set_opcode", set_opcode), ("save_opcode", save_opcode)):
            if value is not None and (not isinstance(value, int) or value < 0):
                raise DeclarationError(f"param {label} must be a non-negative integer, got {value!r}")
        self._raw_type = type_
        self._raw_default = default
        self.type: FwType | None = None
        self.default: Any = None
        self.has_default = default is not _NO_DEFAULT
        self.local_id = id
        self.set_opcode = set_opcode
        self.save_opcode = save_opcode
        self.fprime_name = check_member_name(name, "param")
        self.name = ""
        self.attr = ""

    def __set_name__(self, owner, name):
        self.name = name

    def finish(self, owner: str) -> None:
        where = f"{owner}.{self.name}"
        try:
            self.type = fw_type(self._raw_type)
        except DeclarationError as exc:
            raise DeclarationError(f"{where}: {exc}") from None
        if self.has_default:
            try:
                self.default = self.type.check(self._raw_default)
            except SerializationError as exc:
                raise DeclarationError(f"{where}: default {self._raw_default!r} does not fit: {exc}") from None
        else:
            self.default = self.type.default

    def __repr__(self):
        return f"Param {self.name} ({self.type.name if self.type else self._raw_type})"


class BoundParam:
    """A parameter of one component instance: its current value and validity."""

    __slots__ = ("component", "decl", "id", "value", "validity")

    def __init__(self, component, decl: Param, param_id: int):
        self.component = component
        self.decl = decl
        self.id = param_id
        self.value = decl.default
        self.validity = ParamValid.UNINIT

    @property
    def local_id(self) -> int:
        return self.decl.local_id

    def get(self) -> Any:
        """The current value (F´'s ``paramGet_P``)."""
        return self.value

    def set(self, value: Any, validity: ParamValid = ParamValid.VALID) -> None:
        """Set the component's copy (what PRM_SET does, without the command)."""
        self.value = self.decl.type.check(value)
        self.validity = validity

    def load(self, validity: ParamValid, data: bytes | None) -> None:
        """Take the value PrmDb returned; fall back to the default as F´'s loadParameters does."""
        if validity == ParamValid.VALID and data is not None:
            try:
                value, end = self.decl.type.deserialize(data)
                if end != len(data):
                    raise SerializationError(f"{len(data) - end} byte(s) left over")
                self.value = value
                self.validity = ParamValid.VALID
                return
            except SerializationError:
                pass
        self.value = self.decl.default
        self.validity = ParamValid.DEFAULT if self.decl.has_default else ParamValid.INVALID

    def __repr__(self):
        return f"<param {self.component.name}.{self.decl.name} = {self.value!r} ({self.validity.name})>"
