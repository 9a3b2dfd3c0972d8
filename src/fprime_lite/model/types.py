"""F´ data types and their big-endian serialization.

Every F´ type is an :class:`FwType` object that knows how to check a Python value, serialize it,
deserialize it and describe itself in the F´ JSON dictionary. The primitive types are module
constants (:data:`U8` … :data:`U64`, :data:`I8` … :data:`I64`, :data:`F32`, :data:`F64`,
:data:`BOOL`); bounded strings come from :func:`String`; enums, structs and arrays are declared as
Python classes::

    class DetumbleMode(FwEnum, namespace="Components", rep=U8):
        DISABLED = 0
        AUTO = 1

    class DipoleMoment(Struct, namespace="Drv"):
        x: F64
        y: F64
        z: F64

    class Vector3(Array, namespace="Components", elem=F64, size=3):
        pass

Wire format (F´'s, big-endian): integers and floats at their natural size; bool one byte, 0xFF
true and 0x00 false; strings a U16 byte length then UTF-8 bytes; enums as their representation type;
structs and arrays their members in declaration order with no padding or count.

Values that do not fit are rejected with :class:`~fprime_lite.model.errors.SerializationError`, never
wrapped or truncated.

For a static type checker the primitive constants are the Python types their values take
(``U32`` reads as ``int``, ``F64`` as ``float``, ``BOOL`` as ``bool``), so ``x: F64`` in a struct
or a command handler checks as a float; at run time they are the :class:`FwType` objects above.
:class:`FwType` is generic in that value type (``FwType[int]``), which is how ``Param(F64)`` and
``Channel(String(40))`` know the type of ``.value`` and ``.write()``.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import struct
import sys
from typing import (TYPE_CHECKING, Annotated, Any, Callable, ClassVar, Generic, TypeVar, Union, cast, get_origin,
                    overload)

from fprime_lite.model.errors import DeclarationError, SerializationError

__all__ = [
    "FwType", "IntType", "FloatType", "BoolType", "StringType", "EnumType", "StructType",
    "ArrayType", "AliasType", "FwEnum", "Struct", "Array", "String", "Alias", "fw_type",
    "U8", "U16", "U32", "U64", "I8", "I16", "I32", "I64", "F32", "F64", "BOOL",
    "serialize_values", "deserialize_values", "fit_utf8", "PRIMITIVE_TYPES", "FwTypeLike",
]


V = TypeVar("V")


class FwType(Generic[V]):
    """An F´ type: checks, serializes and describes values of one kind.

    Subclasses set :attr:`name` (the F´ spelling, e.g. ``U32`` or ``Components.DetumbleMode``) and
    :attr:`kind`, the family used to check event format placeholders.
    """

    name: str
    kind: str  # "integer" | "float" | "bool" | "string" | "enum" | "struct" | "array" | "time"

    def check(self, value: Any) -> V:
        """Return ``value`` normalised to this type, or raise SerializationError."""
        raise NotImplementedError

    def serialize(self, value: Any) -> bytes:
        """Check ``value`` and return its F´ big-endian bytes."""
        raise NotImplementedError

    def pack(self, value: Any) -> bytes:
        """Serialize a value that :meth:`check` already returned (skips checking it again)."""
        return self.serialize(value)

    def deserialize(self, data: bytes | bytearray | memoryview, offset: int = 0) -> tuple[V, int]:
        """Read one value at ``offset``; return ``(value, offset after it)``."""
        raise NotImplementedError

    @property
    def default(self) -> V:
        """The value a member of this type takes when none is given."""
        raise NotImplementedError

    def json_ref(self) -> dict:
        """The type reference used in the JSON dictionary wherever this type is named."""
        raise NotImplementedError

    def json_value(self, value: Any) -> Any:
        """``value`` in the JSON dictionary's form (enum constants by qualified name)."""
        return value

    def dependencies(self) -> list["FwType"]:
        """Named types this type refers to directly (for the dictionary's typeDefinitions)."""
        return []

    def json_definition(self) -> dict | None:
        """The typeDefinitions entry for a named type; None for primitives and strings."""
        return None

    def __repr__(self) -> str:
        return f"<F´ type {self.name}>"


def _short(data, offset: int, needed: int, what: str) -> SerializationError:
    left = max(len(data) - offset, 0)
    return SerializationError(
        f"cannot deserialize {what}: needs {needed} byte(s) at offset {offset}, only {left} left")


class IntType(FwType[int]):
    """A fixed-width integer: rejects values outside ``[min, max]`` instead of wrapping."""

    kind = "integer"

    def __init__(self, name: str, bits: int, signed: bool):
        self.name = name
        self.bits = bits
        self.signed = signed
        self.size = bits // 8
        self.min = -(1 << (bits - 1)) if signed else 0
        self.max = (1 << (bits - 1)) - 1 if signed else (1 << bits) - 1
        code = {8: "b", 16: "h", 32: "i", 64: "q"}[bits]
        self._struct = struct.Struct(">" + (code if signed else code.upper()))

    def check(self, value):
        if type(value) is int and self.min <= value <= self.max:
            return value  # the common case, without the general checks below
        if isinstance(value, bool) or not isinstance(value, int):
            raise SerializationError(
                f"{self.name} expects an integer, got {type(value).__name__} {value!r}")
        if not self.min <= value <= self.max:
            raise SerializationError(
                f"{self.name} value {value} is out of range [{self.min}, {self.max}]")
        return int(value)

    def serialize(self, value):
        return self._struct.pack(self.check(value))

    def pack(self, value):
        return self._struct.pack(value)

    def deserialize(self, data, offset=0):
        end = offset + self.size
        if end > len(data):
            raise _short(data, offset, self.size, self.name)
        return self._struct.unpack_from(data, offset)[0], end

    @property
    def default(self):
        return 0

    def json_ref(self):
        return {"name": self.name, "kind": "integer", "size": self.bits, "signed": self.signed}


_F32_MAX = struct.unpack(">f", b"\x7f\x7f\xff\xff")[0]


class FloatType(FwType[float]):
    """IEEE-754 single (F32) or double (F64). NaN and infinities are representable."""

    kind = "float"

    def __init__(self, name: str, bits: int):
        self.name = name
        self.bits = bits
        self.size = bits // 8
        self._struct = struct.Struct(">f" if bits == 32 else ">d")

    def check(self, value):
        if type(value) is float and self.bits == 64:
            return value  # every float is an F64
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SerializationError(
                f"{self.name} expects a number, got {type(value).__name__} {value!r}")
        try:
            value = float(value)
        except OverflowError:  # an int beyond any float's range
            raise SerializationError(
                f"{self.name} value is out of range: a {value.bit_length()}-bit integer "
                f"does not fit a float") from None
        if self.bits == 32 and math.isfinite(value) and abs(value) > _F32_MAX:
            # Values that would round to the largest F32 are accepted; anything larger overflows.
            try:
                self._struct.pack(value)
            except OverflowError:
                raise SerializationError(
                    f"F32 value {value!r} is out of range (|x| ≤ {_F32_MAX!r}); use F64") from None
        return value

    def serialize(self, value):
        return self._struct.pack(self.check(value))

    def pack(self, value):
        return self._struct.pack(value)

    def deserialize(self, data, offset=0):
        end = offset + self.size
        if end > len(data):
            raise _short(data, offset, self.size, self.name)
        return self._struct.unpack_from(data, offset)[0], end

    @property
    def default(self):
        return 0.0

    def json_ref(self):
        return {"name": self.name, "kind": "float", "size": self.bits}


class BoolType(FwType[bool]):
    """F´ bool: one byte, 0xFF for true and 0x00 for false. Any other byte is rejected."""

    kind = "bool"
    name = "bool"
    size = 1

    def check(self, value):
        if not isinstance(value, bool):
            raise SerializationError(f"bool expects True or False, got {value!r}")
        return value

    def serialize(self, value):
        return b"\xff" if self.check(value) else b"\x00"

    def deserialize(self, data, offset=0):
        if offset >= len(data):
            raise _short(data, offset, 1, "bool")
        byte = data[offset]
        if byte == 0xFF:
            return True, offset + 1
        if byte == 0x00:
            return False, offset + 1
        raise SerializationError(f"cannot deserialize bool: byte 0x{byte:02X} is neither 0xFF nor 0x00")

    @property
    def default(self):
        return False

    def json_ref(self):
        return {"name": "bool", "kind": "bool", "size": 8}


_LENGTH16 = struct.Struct(">H")


def fit_utf8(text: str, size: int) -> str:
    """``text`` cut to at most ``size`` UTF-8 bytes on a character boundary, for a bounded string
    such as an event argument; characters UTF-8 cannot encode (lone surrogates) become ``?``."""
    return text.encode("utf-8", "replace")[:size].decode("utf-8", "ignore")


class StringType(FwType[str]):
    """A bounded string: U16 byte length then UTF-8 bytes; at most ``size`` bytes."""

    kind = "string"
    name = "string"

    def __init__(self, size: int):
        if not 0 < size <= 0xFFFF:
            raise DeclarationError(f"String size must be between 1 and 65535, got {size}")
        self.size = size

    def check(self, value):
        if not isinstance(value, str):
            raise SerializationError(f"string expects str, got {type(value).__name__} {value!r}")
        try:
            n = len(value.encode("utf-8"))
        except UnicodeEncodeError as exc:  # lone surrogates
            raise SerializationError(f"string {value!r} is not valid UTF-8 text ({exc.reason})") from None
        if n > self.size:
            raise SerializationError(
                f"string of {n} bytes exceeds its bound of {self.size} bytes; shorten it")
        return value

    def serialize(self, value):
        raw = self.check(value).encode("utf-8")
        return _LENGTH16.pack(len(raw)) + raw

    def deserialize(self, data, offset=0):
        if offset + 2 > len(data):
            raise _short(data, offset, 2, "string length")
        (n,) = _LENGTH16.unpack_from(data, offset)
        if n > self.size:
            raise SerializationError(
                f"cannot deserialize string: length {n} exceeds its bound of {self.size} bytes")
        start = offset + 2
        if start + n > len(data):
            raise _short(data, start, n, f"string of {n} bytes")
        try:
            text = bytes(data[start:start + n]).decode("utf-8")
        except UnicodeDecodeError as exc:
            raise SerializationError(f"cannot deserialize string: invalid UTF-8 ({exc})") from None
        return text, start + n

    @property
    def default(self):
        return ""

    def json_ref(self):
        return {"name": "string", "kind": "string", "size": self.size}

    def __eq__(self, other):
        return isinstance(other, StringType) and other.size == self.size

    def __hash__(self):
        return hash(("string", self.size))


_STRING_TYPES: dict[int, StringType] = {}


def String(size: int) -> StringType:
    """The bounded string type of at most ``size`` UTF-8 bytes (FPP ``string size N``)."""
    if size not in _STRING_TYPES:
        _STRING_TYPES[size] = StringType(size)
    return _STRING_TYPES[size]


_U8 = IntType("U8", 8, False)
_U16 = IntType("U16", 16, False)
_U32 = IntType("U32", 32, False)
_U64 = IntType("U64", 64, False)
_I8 = IntType("I8", 8, True)
_I16 = IntType("I16", 16, True)
_I32 = IntType("I32", 32, True)
_I64 = IntType("I64", 64, True)
_F32 = FloatType("F32", 32)
_F64 = FloatType("F64", 64)
_BOOL = BoolType()

if TYPE_CHECKING:  # a checker sees the Python type of the values (see the module docstring)
    U8 = int
    U16 = int
    U32 = int
    U64 = int
    I8 = int
    I16 = int
    I32 = int
    I64 = int
    F32 = float
    F64 = float
    BOOL = bool
else:
    U8, U16, U32, U64 = _U8, _U16, _U32, _U64
    I8, I16, I32, I64 = _I8, _I16, _I32, _I64
    F32, F64, BOOL = _F32, _F64, _BOOL

#: The primitive types by F´ name, typed as FwType objects (for code that handles them as values).
PRIMITIVE_TYPES: dict[str, FwType[Any]] = {t.name: t for t in (_U8, _U16, _U32, _U64, _I8, _I16, _I32, _I64,
                                                                 _F32, _F64, _BOOL)}

#: What a declaration accepts as a type: an FwType object, or a class standing for one (an FwEnum,
#: Struct or Array subclass, Time, ``bool``, ``float``; for a checker also ``U32``… as above).
FwTypeLike = Union[FwType[Any], type]


def _qualified(namespace: str | None, name: str) -> str:
    return f"{namespace}.{name}" if namespace else name


class AliasType(FwType[Any]):
    """A named alias of another type (FPP ``type FwOpcodeType = U32``); serializes as its target."""

    def __init__(self, qualified_name: str, target: Any):
        self.name = qualified_name
        self.target = fw_type(target)
        self.kind = self.target.kind

    def check(self, value):
        return self.target.check(value)

    def serialize(self, value):
        return self.target.serialize(value)

    def deserialize(self, data, offset=0):
        return self.target.deserialize(data, offset)

    @property
    def default(self):
        return self.target.default

    def json_ref(self):
        return {"name": self.name, "kind": "qualifiedIdentifier"}

    def json_value(self, value):
        return self.target.json_value(value)

    def dependencies(self):
        return [self.target]

    def json_definition(self):
        underlying = self.target
        while isinstance(underlying, AliasType):
            underlying = underlying.target
        return {"kind": "alias", "qualifiedName": self.name, "type": self.target.json_ref(),
                "underlyingType": underlying.json_ref()}


def Alias(qualified_name: str, target: Any) -> AliasType:
    """Declare an alias type, e.g. ``FwOpcodeType = Alias("FwOpcodeType", U32)``."""
    return AliasType(qualified_name, target)


class EnumType(FwType[Any]):
    """The F´ type of an :class:`FwEnum` class: serialized as its representation type."""

    kind = "enum"

    def __init__(self, cls: type["FwEnum"], rep: IntType, default: "FwEnum"):
        self.cls = cls
        self.rep = rep
        self.name = _qualified(getattr(cls, "__fprime_namespace__", None), cls.__name__)
        self._default = default
        self._by_value = {int(m): m for m in cls}

    def check(self, value):
        if type(value) is self.cls or isinstance(value, self.cls):
            return value
        if isinstance(value, enum.Enum) or isinstance(value, bool) or not isinstance(value, (int, str)):
            raise SerializationError(f"{self.name} expects one of {self._names()}, got {value!r}")
        if isinstance(value, str):
            try:
                return self.cls[value]
            except KeyError:
                raise SerializationError(
                    f"{self.name} has no constant {value!r}; use one of {self._names()}") from None
        member = self._by_value.get(value)
        if member is None:
            raise SerializationError(
                f"{self.name} has no constant with value {value}; use one of {self._names()}")
        return member

    def _names(self) -> str:
        return ", ".join(m.name for m in self.cls)

    def serialize(self, value):
        return self.rep.serialize(int(self.check(value)))

    def pack(self, value):
        return self.rep._struct.pack(value)

    def deserialize(self, data, offset=0):
        raw, end = self.rep.deserialize(data, offset)
        member = self._by_value.get(raw)
        if member is None:
            raise SerializationError(
                f"cannot deserialize {self.name}: {raw} is not one of its values "
                f"({', '.join(f'{m.name}={int(m)}' for m in self.cls)})")
        return member, end

    @property
    def default(self):
        return self._default

    def json_ref(self):
        return {"name": self.name, "kind": "qualifiedIdentifier"}

    def json_value(self, value):
        return f"{self.name}.{self.check(value).name}"

    def dependencies(self):
        return []

    def json_definition(self):
        return {
            "kind": "enum",
            "qualifiedName": self.name,
            "representationType": self.rep.json_ref(),
            "enumeratedConstants": [{"name": m.name, "value": int(m)} for m in self.cls],
            "default": self.json_value(self._default),
        }


class FwEnum(enum.IntEnum):
    """Base class of F´ enums. Class keywords: ``namespace``, ``rep`` (default I32), ``default``.

    Members are plain ``IntEnum`` members; their numeric values are what goes on the wire.
    """

    __fprime_namespace__: ClassVar[str | None]
    __fprime_rep__: ClassVar[IntType]
    __fprime_default_name__: ClassVar[str | None]
    __fprime_type__: ClassVar[EnumType]

    def __init_subclass__(cls, namespace: str | None = None, rep: Any = None,
                          default: str | None = None, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.__fprime_namespace__ = namespace
        cls.__fprime_rep__ = rep or _I32
        cls.__fprime_default_name__ = default

    def __str__(self) -> str:
        return self.name


def _finish_enum(cls: type[FwEnum]) -> EnumType:
    """Build the EnumType of an FwEnum class once its members exist."""
    rep = cls.__fprime_rep__
    if not isinstance(rep, IntType):
        raise DeclarationError(f"enum {cls.__name__}: rep must be an integer type, got {rep!r}")
    members = list(cls)
    if not members:
        raise DeclarationError(f"enum {cls.__name__} has no constants")
    for m in members:
        if not rep.min <= int(m) <= rep.max:
            raise DeclarationError(
                f"enum {cls.__name__}.{m.name} = {int(m)} does not fit its representation "
                f"type {rep.name} [{rep.min}, {rep.max}]")
    default_name = cls.__fprime_default_name__
    if default_name is None:
        default = members[0]
    elif default_name in cls.__members__:
        default = cls[default_name]
    else:
        raise DeclarationError(f"enum {cls.__name__}: default {default_name!r} is not a constant")
    return EnumType(cls, rep, default)


def _resolve_annotation(owner: type, name: str, annotation: Any) -> "FwType":
    if isinstance(annotation, str):
        module = sys.modules.get(owner.__module__)
        namespace = dict(vars(module)) if module else {}
        try:
            annotation = eval(annotation, namespace, dict(vars(owner)))  # own source
        except Exception as exc:  # noqa: BLE001 - reported as a declaration error
            raise DeclarationError(
                f"{owner.__name__}.{name}: cannot resolve type annotation {annotation!r}: {exc}") from None
    try:
        return fw_type(annotation)
    except DeclarationError as exc:
        raise DeclarationError(f"{owner.__name__}.{name}: {exc}") from None


class StructType(FwType[Any]):
    """The F´ type of a :class:`Struct` class: members serialized in declaration order."""

    kind = "struct"

    def __init__(self, cls: type, members: list[tuple[str, FwType]]):
        self.cls = cls
        self.members = members
        self.name = _qualified(getattr(cls, "__fprime_namespace__", None), cls.__name__)
        self._fixed = None
        if all(isinstance(t, (IntType, FloatType)) for _, t in members):
            self._fixed = struct.Struct(">" + "".join(cast(Union[IntType, FloatType], t)._struct.format[1:]
                                                      for _, t in members))

    def check(self, value):
        if isinstance(value, dict):
            unknown = set(value) - {n for n, _ in self.members}
            if unknown:
                raise SerializationError(f"{self.name} has no member(s) {sorted(unknown)}")
            value = self.cls(**value)
        elif not isinstance(value, self.cls):
            raise SerializationError(f"{self.name} expects a {self.cls.__name__}, got {value!r}")
        converted = None  # members whose checked form differs (an enum given by name, an int for F64)
        for name, t in self.members:
            member = getattr(value, name)
            try:
                checked = t.check(member)
            except SerializationError as exc:
                raise SerializationError(f"{self.name}.{name}: {exc}") from None
            if checked is not member:
                converted = converted or {}
                converted[name] = checked
        if converted:
            value = self.cls(**{n: converted.get(n, getattr(value, n)) for n, _ in self.members})
        return value

    def serialize(self, value):
        return self.pack(self.check(value))

    def pack(self, value):
        if self._fixed is not None:
            return self._fixed.pack(*[getattr(value, n) for n, _ in self.members])
        return b"".join(t.pack(getattr(value, n)) for n, t in self.members)

    def deserialize(self, data, offset=0):
        if self._fixed is not None:
            end = offset + self._fixed.size
            if end > len(data):
                raise _short(data, offset, self._fixed.size, self.name)
            return self.cls(*self._fixed.unpack_from(data, offset)), end
        values = []
        for _, t in self.members:
            v, offset = t.deserialize(data, offset)
            values.append(v)
        return self.cls(*values), offset

    @property
    def default(self):
        return self.cls()

    def json_ref(self):
        return {"name": self.name, "kind": "qualifiedIdentifier"}

    def json_value(self, value):
        return {n: t.json_value(getattr(value, n)) for n, t in self.members}

    def dependencies(self):
        return [t for _, t in self.members]

    def json_definition(self):
        return {
            "kind": "struct",
            "qualifiedName": self.name,
            "members": {n: {"type": t.json_ref(), "index": i} for i, (n, t) in enumerate(self.members)},
            "default": self.json_value(self.default),
        }


def _default_of(t: FwType[Any]) -> Callable[[], Any]:
    def make() -> Any:
        return t.default
    return make


class Struct:
    """Base class of F´ structs. Members are annotated with F´ types; class keyword ``namespace``.

    The class becomes a dataclass: ``MagneticField(x=0.1, y=0.0, z=0.3)``; unspecified members take
    their type's default. Struct members are written in declaration order.
    """

    __fprime_type__: ClassVar[StructType]
    __fprime_namespace__: ClassVar[str | None]

    if TYPE_CHECKING:  # the members (and so the constructor) are made when the subclass is created
        def __init__(self, *args: Any, **kwargs: Any) -> None: ...

    def __init_subclass__(cls, namespace: str | None = None, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.__fprime_namespace__ = namespace
        annotations = cls.__dict__.get("__annotations__", {})
        if not annotations:
            raise DeclarationError(f"struct {cls.__name__} declares no members")
        members = []
        for name, annotation in annotations.items():
            if (annotation == "ClassVar" or str(annotation).startswith("ClassVar")
                    or annotation is ClassVar or get_origin(annotation) is ClassVar):
                continue
            t = _resolve_annotation(cls, name, annotation)
            members.append((name, t))
            if name not in cls.__dict__:
                default = t.default
                if isinstance(t, (StructType, ArrayType)):
                    setattr(cls, name, dataclasses.field(default_factory=_default_of(t)))
                else:
                    setattr(cls, name, default)
        dataclasses.dataclass(cls)
        cls.__fprime_type__ = StructType(cls, members)


class ArrayType(FwType[Any]):
    """The F´ type of an :class:`Array` class: ``size`` elements, no length prefix."""

    kind = "array"

    def __init__(self, cls: type, elem: FwType, size: int):
        self.cls = cls
        self.elem = elem
        self.size = size
        self.name = _qualified(getattr(cls, "__fprime_namespace__", None), cls.__name__)
        #: One struct for the whole array when its elements are plain numbers (else None).
        self._fixed = (struct.Struct(">" + elem._struct.format[1:] * size)
                       if isinstance(elem, (IntType, FloatType)) else None)
        #: The Python type whose every value is a valid element as it is (F64: float), or None.
        self._exact_elem = float if elem is _F64 else elem.cls if isinstance(elem, EnumType) else None
        #: The default elements when they are immutable values (numbers, booleans, enums, strings),
        #: shared by every default array; None for struct and array elements (a fresh one each).
        self._defaults = (tuple(elem.default for _ in range(size))
                          if isinstance(elem, (IntType, FloatType, BoolType, EnumType, StringType)) else None)

    def check(self, value):
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
            raise SerializationError(f"{self.name} expects a sequence of {self.size} {self.elem.name}")
        if len(value) != self.size:
            raise SerializationError(
                f"{self.name} expects exactly {self.size} elements, got {len(value)}")
        try:
            items = [self.elem.check(v) for v in value]
        except SerializationError as exc:
            raise SerializationError(f"{self.name} element: {exc}") from None
        return value if isinstance(value, self.cls) else self.cls(items)

    def serialize(self, value):
        return b"".join(self.elem.serialize(v) for v in self.check(value))

    def pack(self, value):
        if self._fixed is not None:  # numbers: what each element's serialize gives, in one call
            return self._fixed.pack(*value)
        return self.serialize(value)

    def deserialize(self, data, offset=0):
        items = []
        for _ in range(self.size):
            v, offset = self.elem.deserialize(data, offset)
            items.append(v)
        return self.cls(items), offset

    @property
    def default(self):
        return self.cls()

    def json_ref(self):
        return {"name": self.name, "kind": "qualifiedIdentifier"}

    def json_value(self, value):
        return [self.elem.json_value(v) for v in value]

    def dependencies(self):
        return [self.elem]

    def json_definition(self):
        return {"kind": "array", "qualifiedName": self.name, "size": self.size,
                "elementType": self.elem.json_ref(), "default": self.json_value(self.default)}


class Array(list):
    """Base class of F´ arrays. Class keywords: ``elem`` (element type), ``size``, ``namespace``.

    ``Vector3()`` is the default array; ``Vector3([1.0, 2.0, 3.0])`` checks length and elements.
    """

    __fprime_type__: ClassVar[ArrayType]
    __fprime_namespace__: ClassVar[str | None]

    def __init_subclass__(cls, elem: Any = None, size: int | None = None,
                          namespace: str | None = None, **kwargs):
        super().__init_subclass__(**kwargs)
        if elem is None or size is None:
            raise DeclarationError(f"array {cls.__name__} needs class keywords elem=<type> and size=<n>")
        if not isinstance(size, int) or size < 1:
            raise DeclarationError(f"array {cls.__name__}: size must be a positive integer, got {size!r}")
        cls.__fprime_namespace__ = namespace
        try:
            elem_type = fw_type(elem)
        except DeclarationError as exc:
            raise DeclarationError(f"array {cls.__name__}: {exc}") from None
        cls.__fprime_type__ = ArrayType(cls, elem_type, size)

    def __init__(self, items=None):
        # list.__init__ called directly (no super() object): arrays are built on the tick path,
        # e.g. a controller's Vector3 telemetry every cycle.
        t = type(self).__fprime_type__
        if items is None:
            defaults = t._defaults
            list.__init__(self, defaults if defaults is not None else [t.elem.default for _ in range(t.size)])
            return
        if type(items) is not list and type(items) is not tuple:  # a caller's sequence is only read
            items = list(items)
        if len(items) != t.size:
            raise SerializationError(f"{t.name} expects exactly {t.size} elements, got {len(items)}")
        exact = t._exact_elem
        if exact is not None:  # e.g. floats for F64: each element's check would return it unchanged
            for v in items:
                if type(v) is not exact:
                    break
            else:
                list.__init__(self, items)
                return
        check = t.elem.check
        list.__init__(self, [check(v) for v in items])


@overload
def fw_type(obj: FwType[V]) -> FwType[V]: ...
@overload
def fw_type(obj: type[V]) -> FwType[V]: ...
@overload
def fw_type(obj: Any) -> FwType[Any]: ...


def fw_type(obj: Any) -> FwType[Any]:
    """The :class:`FwType` that ``obj`` stands for in a declaration.

    Accepts FwType objects, FwEnum/Struct/Array subclasses, :class:`~fprime_lite.model.time.Time`,
    the Python shorthands ``bool`` (F´ bool) and ``float`` (F64), and ``Annotated[T, fw]`` (the
    FwType ``fw``): ``name: Annotated[str, String(40)]`` is a bounded string a type checker reads
    as ``str`` (a call such as ``String(40)`` cannot be an annotation for a checker).
    """
    if isinstance(obj, FwType):
        return obj
    if get_origin(obj) is Annotated:  # Annotated[str, String(40)]: the F´ type is the metadata
        for meta in obj.__metadata__:
            if isinstance(meta, FwType):
                return meta
        return fw_type(obj.__origin__)
    if isinstance(obj, type):
        if issubclass(obj, FwEnum):
            t = obj.__dict__.get("__fprime_type__")
            if t is None:
                t = _finish_enum(obj)
                obj.__fprime_type__ = t
            return t
        t = getattr(obj, "__fprime_type__", None)
        if isinstance(t, FwType):
            return t
        if obj is bool:
            return _BOOL
        if obj is float:
            return _F64
    raise DeclarationError(
        f"{obj!r} is not an F´ type; use U8…U64, I8…I64, F32, F64, bool, String(n), "
        f"or an FwEnum, Struct or Array subclass")


def serialize_values(types: list[FwType], values: list | tuple) -> bytes:
    """Serialize ``values`` back to back (event and command arguments: no count, no sizes)."""
    if len(types) != len(values):
        raise SerializationError(f"expected {len(types)} value(s), got {len(values)}")
    return b"".join(t.serialize(v) for t, v in zip(types, values, strict=True))


def deserialize_values(types: list[FwType], data: bytes | bytearray | memoryview,
                       offset: int = 0, *, exact: bool = True) -> list:
    """Deserialize consecutive values; with ``exact``, leftover bytes are an error."""
    values = []
    for t in types:
        v, offset = t.deserialize(data, offset)
        values.append(v)
    if exact and offset != len(data):
        raise SerializationError(
            f"{len(data) - offset} unexpected byte(s) after the last value (at offset {offset})")
    return values
