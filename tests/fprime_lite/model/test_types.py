"""fprime_lite.model.types: F´ types, their big-endian wire format, errors and JSON dictionary shapes.

Wire format (spec fprime_compat.md, "Serialization"): integers and floats at their natural size,
big-endian; bool one byte 0xFF/0x00; strings ``U16 length | UTF-8 bytes``; enums by their
representation type (default I32); structs and arrays their members in declaration order.
"""

import math
import re
import struct
import typing

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fprime_lite.model.errors import DeclarationError, SerializationError
from fprime_lite.model.types import (
    BOOL, F32, F64, I8, I16, I32, I64, U8, U16, U32, U64, Alias, AliasType, Array, ArrayType,
    EnumType, FwEnum, FwType, String, Struct, StructType, deserialize_values, fw_type,
    serialize_values,
)

PROPS = settings(max_examples=60, deadline=None)
FEW = settings(max_examples=25, deadline=None)

INT_TYPES = [U8, U16, U32, U64, I8, I16, I32, I64]
F32_MAX = struct.unpack(">f", b"\x7f\x7f\xff\xff")[0]


# --------------------------------------------------------------------------------------------
# Declarations used throughout
# --------------------------------------------------------------------------------------------

class Mode(FwEnum, namespace="Components", rep=U8):
    DISABLED = 0
    AUTO = 1
    MANUAL = 2


class Signed(FwEnum, namespace="Test"):  # default representation: I32
    NEG = -2
    ZERO = 0
    BIG = 100000


class Defaulted(FwEnum, namespace="Test", rep=I16, default="B"):
    A = -1
    B = 7


class Vec3(Struct, namespace="Drv"):
    x: F64
    y: F64
    z: F64


class Reversed(Struct):  # declaration order is not alphabetical
    zeta: U8
    alpha: U16
    mid: I8


class Mixed(Struct, namespace="Test"):
    flag: bool
    count: U16
    name: String(8)
    mode: Mode


class Outer(Struct, namespace="Test"):
    ident: U8
    inner: Mixed
    vec: Vec3
    level: I8


class Modes(Array, namespace="Test", elem=Mode, size=3):
    pass


class Names(Array, namespace="Test", elem=String(4), size=2):
    pass


class Points(Array, elem=Vec3, size=2):
    pass


OpCode = Alias("FwOpcodeType", U32)
NestedAlias = Alias("Test.Nested", OpCode)


def hx(s: str) -> bytes:
    return bytes.fromhex(s.replace(" ", ""))


def trunc_utf8(text: str, limit: int) -> str:
    """The longest prefix of ``text`` whose UTF-8 encoding is at most ``limit`` bytes."""
    out, used = [], 0
    for ch in text:
        n = len(ch.encode("utf-8"))
        if used + n > limit:
            break
        out.append(ch)
        used += n
    return "".join(out)


def bounded_text(limit: int, exact: bool = False):
    """Text of at most (or, with ``exact``, exactly) ``limit`` UTF-8 bytes, multi-byte included."""
    def fit(s):
        s = trunc_utf8(s, limit)
        if exact:
            s += "a" * (limit - len(s.encode("utf-8")))
        return s
    return st.text(alphabet=st.characters(codec="utf-8"), max_size=limit).map(fit)


def needs(needed, offset, left):
    return rf"needs {needed} byte\(s\) at offset {offset}, only {left} left"


# --------------------------------------------------------------------------------------------
# Exact wire bytes
# --------------------------------------------------------------------------------------------

PRIMITIVE_BYTES = [
    (U8, 0, "00"), (U8, 255, "FF"), (U8, 0x5A, "5A"),
    (U16, 0x1234, "12 34"), (U16, 0xFFFF, "FF FF"),
    (U32, 1, "00 00 00 01"), (U32, 0xDEADBEEF, "DE AD BE EF"),
    (U64, 1, "00 00 00 00 00 00 00 01"), (U64, 2**64 - 1, "FF" * 8),
    (U64, 0x0102030405060708, "01 02 03 04 05 06 07 08"),
    (I8, -1, "FF"), (I8, -128, "80"), (I8, 127, "7F"),
    (I16, -2, "FF FE"), (I16, 0x0102, "01 02"), (I16, -32768, "80 00"),
    (I32, -1, "FF FF FF FF"), (I32, -(2**31), "80 00 00 00"), (I32, 2**31 - 1, "7F FF FF FF"),
    (I64, -2, "FF FF FF FF FF FF FF FE"), (I64, -(2**63), "80" + "00" * 7),
    (F32, 1.0, "3F 80 00 00"), (F32, -2.0, "C0 00 00 00"), (F32, 0.0, "00 00 00 00"),
    (F32, -0.0, "80 00 00 00"), (F32, math.inf, "7F 80 00 00"), (F32, -math.inf, "FF 80 00 00"),
    (F32, F32_MAX, "7F 7F FF FF"), (F32, 0.5, "3F 00 00 00"),
    (F64, 1.0, "3F F0 00 00 00 00 00 00"), (F64, -2.5, "C0 04 00 00 00 00 00 00"),
    (F64, math.inf, "7F F0 00 00 00 00 00 00"),
    (BOOL, True, "FF"), (BOOL, False, "00"),
    (String(8), "ab", "00 02 61 62"), (String(8), "", "00 00"),
    (String(8), "é", "00 02 C3 A9"), (String(3), "abc", "00 03 61 62 63"),
    (String(4), "€", "00 03 E2 82 AC"),
]


@pytest.mark.parametrize("t,value,wire", PRIMITIVE_BYTES,
                         ids=[f"{t.name}-{v!r}" for t, v, _ in PRIMITIVE_BYTES])
def test_primitive_exact_wire_bytes(t, value, wire):
    data = t.serialize(value)
    assert data == hx(wire)
    back, end = t.deserialize(data)
    assert end == len(data)
    assert back == value
    if isinstance(value, float):
        assert math.copysign(1.0, back) == math.copysign(1.0, value)  # -0.0 keeps its sign


def test_primitive_deserialize_returns_python_types():
    assert type(U32.deserialize(hx("00000001"))[0]) is int
    assert type(F32.deserialize(hx("3F800000"))[0]) is float
    assert BOOL.deserialize(hx("FF"))[0] is True
    assert BOOL.deserialize(hx("00"))[0] is False
    assert type(String(4).deserialize(hx("0001 41"))[0]) is str


def test_floats_accept_ints_and_ints_accept_int_enums():
    assert F64.serialize(1) == hx("3FF0000000000000")
    assert F32.serialize(-2) == hx("C0000000")
    assert U8.serialize(Mode.MANUAL) == hx("02")


def test_f32_nan_serializes_as_a_nan():
    data = F32.serialize(math.nan)
    assert len(data) == 4
    (raw,) = struct.unpack(">I", data)
    assert raw & 0x7F800000 == 0x7F800000 and raw & 0x007FFFFF  # exponent all ones, mantissa ≠ 0
    assert math.isnan(F32.deserialize(data)[0])
    assert math.isnan(F64.deserialize(F64.serialize(math.nan))[0])


def test_f32_value_rounding_to_max_accepted_just_beyond_rejected():
    # The largest F32 is (2 − 2^-23)·2^127; its ulp is 2^104. Anything below the midpoint to 2^128
    # rounds to it; the midpoint itself rounds (to even) up to infinity and overflows.
    assert F32.serialize(F32_MAX + 2.0**102) == hx("7F7FFFFF")
    assert F32.serialize(-(F32_MAX + 2.0**102)) == hx("FF7FFFFF")
    with pytest.raises(SerializationError, match=r"F32 value .* is out of range .*use F64"):
        F32.serialize(F32_MAX + 2.0**103)


def test_enum_serialized_by_its_representation_type():
    assert fw_type(Mode).rep is U8
    assert fw_type(Mode).serialize(Mode.AUTO) == hx("01")
    assert fw_type(Mode).serialize("MANUAL") == hx("02")  # by constant name
    assert fw_type(Mode).serialize(1) == hx("01")  # by numeric value
    assert fw_type(Signed).rep is I32
    assert fw_type(Signed).serialize(Signed.NEG) == hx("FFFFFFFE")
    assert fw_type(Signed).serialize(Signed.BIG) == hx("000186A0")
    assert fw_type(Defaulted).rep is I16
    assert fw_type(Defaulted).serialize(Defaulted.A) == hx("FFFF")
    member, end = fw_type(Signed).deserialize(hx("FFFFFFFE"))
    assert member is Signed.NEG and end == 4
    member, end = fw_type(Mode).deserialize(hx("02"))
    assert member is Mode.MANUAL and end == 1


def test_struct_members_in_declaration_order():
    t = fw_type(Reversed)
    assert [n for n, _ in t.members] == ["zeta", "alpha", "mid"]
    assert t.serialize(Reversed(zeta=1, alpha=0x0203, mid=-1)) == hx("01 0203 FF")
    assert t.serialize({"mid": -1, "alpha": 0x0203, "zeta": 1}) == hx("01 0203 FF")
    assert fw_type(Vec3).serialize(Vec3(1.0, 2.0, -0.0)) == hx(
        "3FF0000000000000 4000000000000000 8000000000000000")


def test_struct_with_strings_bool_and_enum_exact_bytes():
    t = fw_type(Mixed)
    value = Mixed(flag=True, count=0x0102, name="hi", mode=Mode.MANUAL)
    data = t.serialize(value)
    assert data == hx("FF 0102 0002 6869 02")
    back, end = t.deserialize(data)
    assert back == value and end == len(data)
    assert back.mode is Mode.MANUAL


def test_nested_struct_exact_bytes():
    value = Outer(ident=9, inner=Mixed(flag=False, count=3, name="é", mode="AUTO"),
                  vec=Vec3(1.0, 0.0, -2.5), level=-128)
    data = fw_type(Outer).serialize(value)
    assert data == hx("09" "00 0003 0002C3A9 01"
                      "3FF0000000000000 0000000000000000 C004000000000000" "80")
    back, end = fw_type(Outer).deserialize(data)
    assert end == len(data)
    assert back == Outer(ident=9, inner=Mixed(False, 3, "é", Mode.AUTO),
                         vec=Vec3(1.0, 0.0, -2.5), level=-128)


def test_array_of_enums_exact_bytes():
    t = fw_type(Modes)
    assert t.serialize([Mode.AUTO, Mode.DISABLED, Mode.MANUAL]) == hx("01 00 02")
    assert t.serialize(["MANUAL", 1, Mode.DISABLED]) == hx("02 01 00")
    back, end = t.deserialize(hx("02 02 01"))
    assert isinstance(back, Modes) and list(back) == [Mode.MANUAL, Mode.MANUAL, Mode.AUTO]
    assert end == 3


def test_array_of_strings_exact_bytes_no_count_prefix():
    t = fw_type(Names)
    data = t.serialize(Names(["ab", "cde"]))
    assert data == hx("0002 6162 0003 636465")
    assert t.serialize(["", "abcd"]) == hx("0000 0004 61626364")
    back, end = t.deserialize(data)
    assert list(back) == ["ab", "cde"] and end == len(data)


def test_array_of_structs_and_struct_dicts_in_arrays():
    t = fw_type(Points)
    data = t.serialize([{"x": 1.0}, Vec3(z=-2.0)])
    assert data == hx("3FF0000000000000" + "00" * 16 + "00" * 16 + "C000000000000000")
    back, _ = t.deserialize(data)
    assert list(back) == [Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.0, -2.0)]


def test_alias_serializes_as_its_target():
    assert OpCode.serialize(1) == hx("00000001")
    assert NestedAlias.serialize(0xDEADBEEF) == hx("DEADBEEF")
    assert NestedAlias.deserialize(hx("00000007 FF"), 0) == (7, 4)
    assert OpCode.kind == "integer" and OpCode.default == 0
    with pytest.raises(SerializationError, match=r"U32 value -1 is out of range"):
        NestedAlias.serialize(-1)


def test_serialize_values_concatenates_without_prefixes():
    data = serialize_values([U32, BOOL, String(10), fw_type(Mode), F32],
                            [7, True, "ok", Mode.AUTO, 1.0])
    assert data == hx("00000007 FF 0002 6F6B 01 3F800000")
    assert deserialize_values([U32, BOOL, String(10), fw_type(Mode), F32], data) == [
        7, True, "ok", Mode.AUTO, 1.0]
    assert serialize_values([], []) == b""
    assert deserialize_values([], b"") == []


def test_deserialize_accepts_bytearray_and_memoryview_and_offsets():
    data = hx("AA BB 0002 6162 FF 00000001")
    types = [String(2), BOOL, U32]
    for buf in (data, bytearray(data), memoryview(data)):
        assert deserialize_values(types, buf, offset=2) == ["ab", True, 1]
        assert String(2).deserialize(buf, 2) == ("ab", 6)
        assert BOOL.deserialize(buf, 6) == (True, 7)
        assert U32.deserialize(buf, 7) == (1, 11)


# --------------------------------------------------------------------------------------------
# Defaults, fw_type and declarations
# --------------------------------------------------------------------------------------------

def test_defaults():
    for t in INT_TYPES:
        assert t.default == 0
    assert F32.default == 0.0 and F64.default == 0.0
    assert BOOL.default is False
    assert String(5).default == ""
    assert fw_type(Mode).default is Mode.DISABLED  # first constant unless declared
    assert fw_type(Defaulted).default is Defaulted.B
    assert fw_type(Vec3).default == Vec3(0.0, 0.0, 0.0)
    assert Mixed() == Mixed(False, 0, "", Mode.DISABLED)
    assert list(Modes()) == [Mode.DISABLED] * 3
    assert list(Names()) == ["", ""]
    assert fw_type(Outer).default == Outer(0, Mixed(), Vec3(), 0)


def test_struct_and_array_defaults_are_independent_objects():
    a, b = Outer(), Outer()
    assert a.inner is not b.inner and a.vec is not b.vec
    a.inner.count = 5
    assert b.inner.count == 0
    p, q = Points(), Points()
    assert p[0] is not q[0]


def test_fw_type_resolves_declarations():
    assert fw_type(U8) is U8
    assert fw_type(bool) is BOOL
    assert fw_type(float) is F64
    assert isinstance(fw_type(Mode), EnumType) and fw_type(Mode) is fw_type(Mode)
    assert isinstance(fw_type(Vec3), StructType) and fw_type(Vec3) is Vec3.__fprime_type__
    assert isinstance(fw_type(Modes), ArrayType)
    assert fw_type(OpCode) is OpCode and isinstance(OpCode, AliasType)
    assert String(8) is String(8) and String(8) == String(8) and String(8) != String(9)
    assert hash(String(8)) == hash(String(8))
    assert fw_type(Mixed).members[0][1] is BOOL
    assert fw_type(Modes).elem is fw_type(Mode) and fw_type(Modes).size == 3


def test_type_names_and_kinds():
    assert [t.name for t in INT_TYPES] == ["U8", "U16", "U32", "U64", "I8", "I16", "I32", "I64"]
    assert {t.kind for t in INT_TYPES} == {"integer"}
    assert (F32.kind, F64.kind, BOOL.kind, String(3).kind) == ("float", "float", "bool", "string")
    assert fw_type(Mode).name == "Components.Mode" and fw_type(Mode).kind == "enum"
    assert fw_type(Vec3).name == "Drv.Vec3" and fw_type(Vec3).kind == "struct"
    assert fw_type(Reversed).name == "Reversed"  # no namespace
    assert fw_type(Modes).name == "Test.Modes" and fw_type(Modes).kind == "array"
    assert fw_type(Points).name == "Points"
    assert repr(U32) == "<F´ type U32>"
    assert str(Mode.AUTO) == "AUTO"


def test_integer_bounds():
    expected = {"U8": (0, 255), "U16": (0, 65535), "U32": (0, 2**32 - 1), "U64": (0, 2**64 - 1),
                "I8": (-128, 127), "I16": (-32768, 32767), "I32": (-(2**31), 2**31 - 1),
                "I64": (-(2**63), 2**63 - 1)}
    for t in INT_TYPES:
        assert (t.min, t.max) == expected[t.name]
        assert t.size == t.bits // 8


def test_struct_classvar_annotations_are_not_members():
    class WithClassVar(Struct):
        a: U8
        scale: typing.ClassVar[float] = 2.0
        b: U16

    t = fw_type(WithClassVar)
    assert [n for n, _ in t.members] == ["a", "b"]
    assert t.serialize(WithClassVar(1, 2)) == hx("01 0002")
    assert t.deserialize(hx("01 0002")) == (WithClassVar(1, 2), 3)
    assert WithClassVar.scale == 2.0


def test_struct_explicit_member_default():
    class WithDefault(Struct):
        a: U8 = 7
        b: Mode = Mode.AUTO

    assert WithDefault() == WithDefault(7, Mode.AUTO)
    assert fw_type(WithDefault).serialize(WithDefault()) == hx("07 01")
    assert fw_type(WithDefault).json_definition()["default"] == {"a": 7, "b": "Components.Mode.AUTO"}


def test_struct_dependencies_and_array_dependencies():
    assert fw_type(Outer).dependencies() == [U8, fw_type(Mixed), fw_type(Vec3), I8]
    assert fw_type(Modes).dependencies() == [fw_type(Mode)]
    assert NestedAlias.dependencies() == [OpCode]
    assert fw_type(Mode).dependencies() == []
    assert U8.dependencies() == [] and U8.json_definition() is None
    assert String(3).json_definition() is None


# --------------------------------------------------------------------------------------------
# Error paths
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("t", INT_TYPES, ids=lambda t: t.name)
def test_int_bounds_pass_and_one_beyond_each_is_rejected(t):
    assert t.deserialize(t.serialize(t.min))[0] == t.min
    assert t.deserialize(t.serialize(t.max))[0] == t.max
    for bad in (t.min - 1, t.max + 1):
        msg = rf"^{t.name} value {bad} is out of range \[{t.min}, {t.max}\]$"
        with pytest.raises(SerializationError, match=msg):
            t.serialize(bad)
        with pytest.raises(SerializationError, match=msg):
            t.check(bad)


def test_int_never_wraps():
    with pytest.raises(SerializationError, match=r"U8 value 256 is out of range \[0, 255\]"):
        U8.serialize(256)
    with pytest.raises(SerializationError, match=r"U32 value -1 is out of range"):
        U32.serialize(-1)
    with pytest.raises(SerializationError, match=r"I8 value 128 is out of range \[-128, 127\]"):
        I8.serialize(128)


@pytest.mark.parametrize("t", INT_TYPES, ids=lambda t: t.name)
def test_int_rejects_bool_float_and_str(t):
    with pytest.raises(SerializationError, match=rf"^{t.name} expects an integer, got bool True$"):
        t.serialize(True)
    with pytest.raises(SerializationError, match=rf"{t.name} expects an integer, got bool False"):
        t.check(False)
    with pytest.raises(SerializationError, match=rf"{t.name} expects an integer, got float 1\.0"):
        t.serialize(1.0)
    with pytest.raises(SerializationError, match=rf"{t.name} expects an integer, got str '1'"):
        t.serialize("1")
    with pytest.raises(SerializationError, match=rf"{t.name} expects an integer, got NoneType None"):
        t.serialize(None)


@pytest.mark.parametrize("value", [1e39, -1e39, 3.5e38, -3.5e38, 2**128, 1.7976931348623157e308])
def test_f32_overflow_rejected(value):
    with pytest.raises(SerializationError,
                       match=r"F32 value .* is out of range \(\|x\| ≤ 3\.40282346\d*e\+38\); use F64"):
        F32.serialize(value)


def test_f64_takes_what_f32_cannot():
    assert F64.deserialize(F64.serialize(1e39))[0] == 1e39
    assert F64.serialize(2**128) == struct.pack(">d", 2.0**128)


@pytest.mark.parametrize("t", [F32, F64], ids=lambda t: t.name)
def test_float_rejects_non_numbers_and_huge_ints(t):
    with pytest.raises(SerializationError, match=rf"^{t.name} expects a number, got bool True$"):
        t.serialize(True)
    with pytest.raises(SerializationError, match=rf"{t.name} expects a number, got str '1\.0'"):
        t.serialize("1.0")
    with pytest.raises(SerializationError, match=rf"{t.name} expects a number, got NoneType"):
        t.check(None)
    # An int too large for any float is rejected as a SerializationError, not an OverflowError.
    with pytest.raises(SerializationError, match=rf"{t.name} value is out of range: a 1329-bit integer"):
        t.serialize(10**400)


def test_bool_rejects_non_bools():
    for bad in (1, 0, "True", None, 1.0):
        with pytest.raises(SerializationError, match=rf"^bool expects True or False, got {re.escape(repr(bad))}$"):
            BOOL.serialize(bad)


@pytest.mark.parametrize("byte", [0x01, 0x7F, 0x80, 0xFE])
def test_bool_byte_neither_00_nor_ff_rejected(byte):
    with pytest.raises(SerializationError,
                       match=rf"cannot deserialize bool: byte 0x{byte:02X} is neither 0xFF nor 0x00"):
        BOOL.deserialize(bytes([byte]))


def test_string_bound_is_in_bytes():
    s4 = String(4)
    assert s4.serialize("abcd") == hx("0004 61626364")  # exactly at the bound
    assert s4.serialize("éé") == hx("0004 C3A9C3A9")  # 2 characters, 4 bytes
    with pytest.raises(SerializationError,
                       match=r"^string of 5 bytes exceeds its bound of 4 bytes; shorten it$"):
        s4.serialize("abcde")
    with pytest.raises(SerializationError, match=r"string of 6 bytes exceeds its bound of 4 bytes"):
        s4.check("ééé")  # 3 characters but 6 bytes
    with pytest.raises(SerializationError, match=r"string of 5 bytes exceeds its bound of 4 bytes"):
        s4.serialize("a😀")  # 😀 is 4 bytes


def test_string_rejects_non_str_and_unencodable_text():
    with pytest.raises(SerializationError, match=r"^string expects str, got bytes b'ab'$"):
        String(4).serialize(b"ab")
    with pytest.raises(SerializationError, match=r"string expects str, got int 5"):
        String(4).check(5)
    with pytest.raises(SerializationError, match=r"is not valid UTF-8 text \(surrogates not allowed\)"):
        String(4).serialize("\ud800")


@pytest.mark.parametrize("body", ["FF", "C3", "C328", "80", "EDA080", "F8888080"])
def test_string_non_utf8_bytes_rejected(body):
    raw = hx(body)
    data = len(raw).to_bytes(2, "big") + raw
    with pytest.raises(SerializationError, match=r"^cannot deserialize string: invalid UTF-8 \("):
        String(8).deserialize(data)


def test_string_deserialize_length_over_bound_rejected():
    with pytest.raises(SerializationError,
                       match=r"cannot deserialize string: length 5 exceeds its bound of 4 bytes"):
        String(4).deserialize(hx("0005") + b"hello")
    assert String(5).deserialize(hx("0005") + b"hello") == ("hello", 7)


@pytest.mark.parametrize("size", [0, -1, 65536])
def test_string_size_declaration_bounds(size):
    with pytest.raises(DeclarationError, match=rf"String size must be between 1 and 65535, got {size}"):
        String(size)


def test_string_largest_bound():
    big = "x" * 65535
    data = String(65535).serialize(big)
    assert data[:2] == hx("FFFF") and len(data) == 65537
    assert String(65535).deserialize(data) == (big, 65537)


def test_enum_check_rejects_values_that_are_not_constants():
    t = fw_type(Mode)
    with pytest.raises(SerializationError, match=r"^Components\.Mode has no constant with value 5; "
                                                 r"use one of DISABLED, AUTO, MANUAL$"):
        t.check(5)
    with pytest.raises(SerializationError, match=r"Components\.Mode has no constant with value -1"):
        t.serialize(-1)
    with pytest.raises(SerializationError,
                       match=r"Components\.Mode has no constant 'OFF'; use one of DISABLED, AUTO, MANUAL"):
        t.serialize("OFF")
    for bad in (True, 1.0, None, Signed.ZERO, Defaulted.B):
        with pytest.raises(SerializationError,
                           match=r"^Components\.Mode expects one of DISABLED, AUTO, MANUAL, got "):
            t.check(bad)


def test_enum_deserialize_rejects_unknown_value():
    with pytest.raises(SerializationError,
                       match=r"^cannot deserialize Components\.Mode: 7 is not one of its values "
                             r"\(DISABLED=0, AUTO=1, MANUAL=2\)$"):
        fw_type(Mode).deserialize(hx("07"))
    with pytest.raises(SerializationError, match=r"cannot deserialize Test\.Signed: 1 is not one of its values "
                                                 r"\(NEG=-2, ZERO=0, BIG=100000\)"):
        fw_type(Signed).deserialize(hx("00000001"))
    with pytest.raises(SerializationError,
                       match=r"^cannot deserialize Components\.Mode: 3 is not one of its values"):
        fw_type(Modes).deserialize(hx("00 01 03"))


def test_enum_constant_not_fitting_rep_is_a_declaration_error():
    class TooBig(FwEnum, rep=U8):
        A = 0
        B = 256

    with pytest.raises(DeclarationError,
                       match=r"^enum TooBig\.B = 256 does not fit its representation type U8 \[0, 255\]$"):
        fw_type(TooBig)

    class Negative(FwEnum, rep=U16):
        A = -1

    with pytest.raises(DeclarationError, match=r"enum Negative\.A = -1 does not fit .* U16 \[0, 65535\]"):
        fw_type(Negative)

    class TooBigForI32(FwEnum):
        A = 2**31

    with pytest.raises(DeclarationError, match=r"TooBigForI32\.A = 2147483648 does not fit .* I32"):
        fw_type(TooBigForI32)

    class FitsI8(FwEnum, rep=I8):
        LO = -128
        HI = 127

    assert fw_type(FitsI8).serialize(FitsI8.LO) == hx("80")


def test_enum_other_declaration_errors():
    class BadDefault(FwEnum, default="C"):
        A = 0

    with pytest.raises(DeclarationError, match=r"enum BadDefault: default 'C' is not a constant"):
        fw_type(BadDefault)

    class BadRep(FwEnum, rep=F32):
        A = 0

    with pytest.raises(DeclarationError, match=r"enum BadRep: rep must be an integer type, got <F´ type F32>"):
        fw_type(BadRep)

    class NoConstants(FwEnum):
        pass

    with pytest.raises(DeclarationError, match=r"enum NoConstants has no constants"):
        fw_type(NoConstants)


TRUNCATED = [
    (U8, "", 0, 1, 0, 0, "U8"),
    (U16, "01", 0, 2, 0, 1, "U16"),
    (U32, "010203", 0, 4, 0, 3, "U32"),
    (U64, "01020304050607", 0, 8, 0, 7, "U64"),
    (I8, "", 0, 1, 0, 0, "I8"),
    (I16, "FF", 0, 2, 0, 1, "I16"),
    (I32, "FFFF", 0, 4, 0, 2, "I32"),
    (I64, "FF", 0, 8, 0, 1, "I64"),
    (F32, "3F8000", 0, 4, 0, 3, "F32"),
    (F64, "3FF0", 0, 8, 0, 2, "F64"),
    (BOOL, "", 0, 1, 0, 0, "bool"),
    (String(4), "00", 0, 2, 0, 1, "string length"),
    (String(4), "000461", 0, 4, 2, 1, "string of 4 bytes"),
    (fw_type(Mode), "", 0, 1, 0, 0, "U8"),
    (fw_type(Signed), "FFFFFF", 0, 4, 0, 3, "I32"),
    (fw_type(Vec3), "00" * 23, 0, 24, 0, 23, r"Drv\.Vec3"),  # all-numeric struct read at once
    (fw_type(Reversed), "01 02", 0, 4, 0, 2, "Reversed"),
    (fw_type(Mixed), "FF 0001 0003 6869", 0, 3, 5, 2, "string of 3 bytes"),
    (fw_type(Mixed), "FF 0001 0002 6869", 0, 1, 7, 0, "U8"),  # missing the enum
    (fw_type(Modes), "00 01", 0, 1, 2, 0, "U8"),
    (fw_type(Names), "0001 61 0002 62", 0, 2, 5, 1, "string of 2 bytes"),
    (U32, "AABBCCDDEE", 3, 4, 3, 2, "U32"),  # at an offset
    (U16, "AABB", 5, 2, 5, 0, "U16"),  # offset beyond the data
]


@pytest.mark.parametrize("t,data,offset,needed,at,left,what", TRUNCATED,
                         ids=[f"{row[0].name}-{i}" for i, row in enumerate(TRUNCATED)])
def test_truncated_buffer_says_needed_and_left(t, data, offset, needed, at, left, what):
    with pytest.raises(SerializationError,
                       match=rf"^cannot deserialize {what}: {needs(needed, at, left)}$"):
        t.deserialize(hx(data), offset)


def test_deserialize_values_truncated_and_leftover():
    data = hx("00000001 FF")
    with pytest.raises(SerializationError,
                       match=r"^1 unexpected byte\(s\) after the last value \(at offset 4\)$"):
        deserialize_values([U32], data)
    with pytest.raises(SerializationError, match=r"3 unexpected byte\(s\) after the last value \(at offset 2\)"):
        deserialize_values([U16], hx("0001 020304"), exact=True)
    assert deserialize_values([U32], data, exact=False) == [1]
    assert deserialize_values([U32, BOOL], data) == [1, True]
    with pytest.raises(SerializationError, match=rf"cannot deserialize U16: {needs(2, 5, 0)}"):
        deserialize_values([U32, BOOL, U16], data)


def test_serialize_values_count_mismatch():
    with pytest.raises(SerializationError, match=r"^expected 2 value\(s\), got 1$"):
        serialize_values([U8, U8], [1])
    with pytest.raises(SerializationError, match=r"expected 0 value\(s\), got 1"):
        serialize_values([], (1,))
    with pytest.raises(SerializationError, match=r"U8 value 300 is out of range"):
        serialize_values([U8, U8], [1, 300])


def test_struct_errors():
    t = fw_type(Vec3)
    with pytest.raises(SerializationError, match=r"^Drv\.Vec3 has no member\(s\) \['w'\]$"):
        t.serialize({"x": 1.0, "w": 2.0})
    with pytest.raises(SerializationError, match=r"Drv\.Vec3 has no member\(s\) \['a', 'b'\]"):
        t.check({"b": 1, "a": 2})
    with pytest.raises(SerializationError, match=r"^Drv\.Vec3 expects a Vec3, got \(1\.0, 2\.0, 3\.0\)$"):
        t.serialize((1.0, 2.0, 3.0))
    with pytest.raises(SerializationError, match=r"Drv\.Vec3 expects a Vec3, got Reversed"):
        t.serialize(Reversed())
    with pytest.raises(SerializationError,
                       match=r"^Test\.Mixed\.count: U16 value 70000 is out of range \[0, 65535\]$"):
        fw_type(Mixed).serialize(Mixed(count=70000))
    with pytest.raises(SerializationError, match=r"Test\.Mixed\.name: string of 9 bytes exceeds its bound of 8"):
        fw_type(Mixed).serialize({"name": "123456789"})
    with pytest.raises(SerializationError, match=r"Test\.Mixed\.flag: bool expects True or False, got 1"):
        fw_type(Mixed).serialize(Mixed(flag=1))
    with pytest.raises(SerializationError, match=r"Drv\.Vec3\.y: F64 expects a number, got str 'a'"):
        t.serialize(Vec3(y="a"))  # the all-numeric fast path checks too
    with pytest.raises(SerializationError, match=r"Test\.Outer\.inner: Test\.Mixed\.mode: Components\.Mode "
                                                 r"has no constant with value 9"):
        fw_type(Outer).serialize(Outer(inner=Mixed(mode=9)))


def test_struct_declaration_errors():
    with pytest.raises(DeclarationError, match=r"^struct Empty declares no members$"):
        class Empty(Struct):
            pass

    with pytest.raises(DeclarationError, match=r"^BadMember\.x: <class 'int'> is not an F´ type; use "):
        class BadMember(Struct):
            x: int


def test_array_errors():
    t = fw_type(Modes)
    with pytest.raises(SerializationError, match=r"^Test\.Modes expects exactly 3 elements, got 2$"):
        t.serialize([0, 1])
    with pytest.raises(SerializationError, match=r"Test\.Modes expects exactly 3 elements, got 4"):
        t.check([0, 1, 2, 0])
    with pytest.raises(SerializationError, match=r"Test\.Modes expects exactly 3 elements, got 1"):
        Modes([0])
    with pytest.raises(SerializationError, match=r"^Test\.Modes expects a sequence of 3 Components\.Mode$"):
        t.serialize("abc")
    with pytest.raises(SerializationError, match=r"Test\.Modes expects a sequence of 3"):
        t.serialize(7)
    with pytest.raises(SerializationError,
                       match=r"^Test\.Modes element: Components\.Mode has no constant with value 9; "):
        t.serialize([0, 1, 9])
    with pytest.raises(SerializationError, match=r"Components\.Mode has no constant 'X'"):
        Modes([0, 1, "X"])
    with pytest.raises(SerializationError, match=r"Test\.Names element: string of 5 bytes exceeds its bound of 4"):
        fw_type(Names).serialize(["ok", "toolo"])
    arr = Modes()
    arr.append(Mode.AUTO)  # a mutated array is re-checked
    with pytest.raises(SerializationError, match=r"Test\.Modes expects exactly 3 elements, got 4"):
        t.serialize(arr)


def test_array_declaration_errors():
    with pytest.raises(DeclarationError,
                       match=r"^array NoSize needs class keywords elem=<type> and size=<n>$"):
        class NoSize(Array, elem=U8):
            pass

    with pytest.raises(DeclarationError, match=r"array NoElem needs class keywords elem=<type> and size=<n>"):
        class NoElem(Array, size=3):
            pass

    with pytest.raises(DeclarationError, match=r"array ZeroSize: size must be a positive integer, got 0"):
        class ZeroSize(Array, elem=U8, size=0):
            pass

    with pytest.raises(DeclarationError, match=r"array FloatSize: size must be a positive integer, got 2\.0"):
        class FloatSize(Array, elem=U8, size=2.0):
            pass

    with pytest.raises(DeclarationError, match=r"^array BadElem: <class 'str'> is not an F´ type; "):
        class BadElem(Array, elem=str, size=2):
            pass


@pytest.mark.parametrize("obj", [42, int, str, "U32", None, Struct, Array, list])
def test_fw_type_on_a_non_type_lists_what_to_use(obj):
    msg = (rf"^{re.escape(repr(obj))} is not an F´ type; use U8…U64, I8…I64, F32, F64, bool, "
           r"String\(n\), or an FwEnum, Struct or Array subclass$")
    with pytest.raises(DeclarationError, match=msg):
        fw_type(obj)


def test_alias_of_a_non_type_is_a_declaration_error():
    with pytest.raises(DeclarationError, match=r"<class 'int'> is not an F´ type"):
        Alias("Bad", int)


def test_fwtype_base_is_abstract():
    t = FwType()
    for call in (lambda: t.check(1), lambda: t.serialize(1), lambda: t.deserialize(b""),
                 lambda: t.default, lambda: t.json_ref()):
        with pytest.raises(NotImplementedError):
            call()


# --------------------------------------------------------------------------------------------
# JSON dictionary shapes
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("t,bits,signed", [(U8, 8, False), (U16, 16, False), (U32, 32, False),
                                           (U64, 64, False), (I8, 8, True), (I16, 16, True),
                                           (I32, 32, True), (I64, 64, True)],
                         ids=lambda v: getattr(v, "name", str(v)))
def test_json_ref_integers(t, bits, signed):
    assert t.json_ref() == {"name": t.name, "kind": "integer", "size": bits, "signed": signed}


def test_json_ref_other_primitives():
    assert U32.json_ref() == {"name": "U32", "kind": "integer", "size": 32, "signed": False}
    assert F32.json_ref() == {"name": "F32", "kind": "float", "size": 32}
    assert F64.json_ref() == {"name": "F64", "kind": "float", "size": 64}
    assert BOOL.json_ref() == {"name": "bool", "kind": "bool", "size": 8}
    assert String(40).json_ref() == {"name": "string", "kind": "string", "size": 40}


def test_json_ref_named_types():
    for t, name in [(fw_type(Mode), "Components.Mode"), (fw_type(Vec3), "Drv.Vec3"),
                    (fw_type(Modes), "Test.Modes"), (OpCode, "FwOpcodeType")]:
        assert t.json_ref() == {"name": name, "kind": "qualifiedIdentifier"}


def test_json_definition_enum():
    assert fw_type(Mode).json_definition() == {
        "kind": "enum",
        "qualifiedName": "Components.Mode",
        "representationType": {"name": "U8", "kind": "integer", "size": 8, "signed": False},
        "enumeratedConstants": [{"name": "DISABLED", "value": 0}, {"name": "AUTO", "value": 1},
                                {"name": "MANUAL", "value": 2}],
        "default": "Components.Mode.DISABLED",
    }
    d = fw_type(Defaulted).json_definition()
    assert d["representationType"] == {"name": "I16", "kind": "integer", "size": 16, "signed": True}
    assert d["enumeratedConstants"] == [{"name": "A", "value": -1}, {"name": "B", "value": 7}]
    assert d["default"] == "Test.Defaulted.B"
    assert fw_type(Signed).json_definition()["representationType"]["name"] == "I32"
    assert fw_type(Mode).json_value(1) == "Components.Mode.AUTO"
    assert fw_type(Mode).json_value("MANUAL") == "Components.Mode.MANUAL"


def test_json_definition_struct():
    assert fw_type(Mixed).json_definition() == {
        "kind": "struct",
        "qualifiedName": "Test.Mixed",
        "members": {
            "flag": {"type": {"name": "bool", "kind": "bool", "size": 8}, "index": 0},
            "count": {"type": {"name": "U16", "kind": "integer", "size": 16, "signed": False},
                      "index": 1},
            "name": {"type": {"name": "string", "kind": "string", "size": 8}, "index": 2},
            "mode": {"type": {"name": "Components.Mode", "kind": "qualifiedIdentifier"}, "index": 3},
        },
        "default": {"flag": False, "count": 0, "name": "", "mode": "Components.Mode.DISABLED"},
    }
    members = fw_type(Reversed).json_definition()["members"]
    assert [(n, m["index"]) for n, m in members.items()] == [("zeta", 0), ("alpha", 1), ("mid", 2)]
    outer = fw_type(Outer).json_definition()
    assert outer["members"]["inner"] == {
        "type": {"name": "Test.Mixed", "kind": "qualifiedIdentifier"}, "index": 1}
    assert outer["default"] == {
        "ident": 0,
        "inner": {"flag": False, "count": 0, "name": "", "mode": "Components.Mode.DISABLED"},
        "vec": {"x": 0.0, "y": 0.0, "z": 0.0},
        "level": 0,
    }


def test_json_definition_array():
    assert fw_type(Modes).json_definition() == {
        "kind": "array",
        "qualifiedName": "Test.Modes",
        "size": 3,
        "elementType": {"name": "Components.Mode", "kind": "qualifiedIdentifier"},
        "default": ["Components.Mode.DISABLED"] * 3,
    }
    assert fw_type(Names).json_definition() == {
        "kind": "array", "qualifiedName": "Test.Names", "size": 2,
        "elementType": {"name": "string", "kind": "string", "size": 4}, "default": ["", ""]}
    assert fw_type(Points).json_definition()["default"] == [{"x": 0.0, "y": 0.0, "z": 0.0}] * 2
    assert fw_type(Modes).json_value([2, 1, 0]) == [
        "Components.Mode.MANUAL", "Components.Mode.AUTO", "Components.Mode.DISABLED"]


def test_json_definition_alias():
    u32 = {"name": "U32", "kind": "integer", "size": 32, "signed": False}
    assert OpCode.json_definition() == {"kind": "alias", "qualifiedName": "FwOpcodeType",
                                        "type": u32, "underlyingType": u32}
    assert NestedAlias.json_definition() == {
        "kind": "alias", "qualifiedName": "Test.Nested",
        "type": {"name": "FwOpcodeType", "kind": "qualifiedIdentifier"}, "underlyingType": u32}
    mode_alias = Alias("Test.ModeAlias", Mode)
    assert mode_alias.kind == "enum"
    assert mode_alias.json_value(Mode.AUTO) == "Components.Mode.AUTO"
    assert mode_alias.json_definition()["underlyingType"] == {
        "name": "Components.Mode", "kind": "qualifiedIdentifier"}


# --------------------------------------------------------------------------------------------
# Property tests
# --------------------------------------------------------------------------------------------

def assert_round_trip(t, value, expect=None):
    """serialize → deserialize gives the value back, consuming exactly the bytes produced."""
    data = t.serialize(value)
    back, end = t.deserialize(data)
    assert end == len(data)
    assert t.serialize(back) == data
    expect = value if expect is None else expect
    if isinstance(expect, float) and math.isnan(expect):
        assert math.isnan(back)
    else:
        assert back == expect
    # the same value at an offset, in the middle of other bytes
    padded = b"\xa5" * 3 + data + b"\x5a" * 2
    assert t.deserialize(padded, 3) == (back, 3 + len(data)) or (
        isinstance(back, float) and math.isnan(back))
    return data


@pytest.mark.parametrize("t", INT_TYPES, ids=lambda t: t.name)
@PROPS
@given(data=st.data())
def test_prop_int_round_trip_full_range(t, data):
    value = data.draw(st.one_of(st.integers(t.min, t.max),
                                st.sampled_from([t.min, t.max, 0, t.min + 1, t.max - 1])))
    wire = assert_round_trip(t, value)
    assert len(wire) == t.size
    assert wire == value.to_bytes(t.size, "big", signed=t.signed)


@pytest.mark.parametrize("t", INT_TYPES, ids=lambda t: t.name)
@FEW
@given(data=st.data())
def test_prop_int_out_of_range_rejected(t, data):
    value = data.draw(st.one_of(st.integers(max_value=t.min - 1), st.integers(min_value=t.max + 1)))
    with pytest.raises(SerializationError, match=rf"{t.name} value -?\d+ is out of range"):
        t.serialize(value)


@PROPS
@given(st.floats(width=32))
def test_prop_f32_round_trip_of_float32_values(value):
    wire = assert_round_trip(F32, value)
    assert len(wire) == 4
    if not math.isnan(value):
        assert wire == struct.pack(">f", value)
        back = F32.deserialize(wire)[0]
        assert math.copysign(1.0, back) == math.copysign(1.0, value)


@PROPS
@given(st.floats(min_value=-F32_MAX, max_value=F32_MAX))
def test_prop_f32_rounds_in_range_doubles_to_nearest(value):
    wire = F32.serialize(value)
    assert wire == struct.pack(">f", value)
    assert F32.deserialize(wire)[0] == struct.unpack(">f", struct.pack(">f", value))[0]


@PROPS
@given(st.floats(min_value=F32_MAX + 2.0**103, allow_infinity=False), st.booleans())
def test_prop_f32_beyond_range_rejected(value, negative):
    value = -value if negative else value
    with pytest.raises(SerializationError, match=r"F32 value .* is out of range"):
        F32.serialize(value)


@PROPS
@given(st.floats())
def test_prop_f64_round_trip(value):
    wire = assert_round_trip(F64, value)
    assert len(wire) == 8
    if not math.isnan(value):
        assert wire == struct.pack(">d", value)


@FEW
@given(st.booleans())
def test_prop_bool_round_trip(value):
    assert assert_round_trip(BOOL, value) == (b"\xff" if value else b"\x00")


@PROPS
@given(size=st.integers(1, 64), data=st.data())
def test_prop_string_round_trip_up_to_bound(size, data):
    text = data.draw(bounded_text(size))
    wire = assert_round_trip(String(size), text)
    raw = text.encode("utf-8")
    assert wire == len(raw).to_bytes(2, "big") + raw
    assert len(raw) <= size


@PROPS
@given(st.text(alphabet=st.characters(codec="utf-8"), min_size=1, max_size=30))
def test_prop_string_exactly_at_bound_passes_one_byte_less_fails(text):
    n = len(text.encode("utf-8"))
    wire = assert_round_trip(String(n), text)
    assert len(wire) == n + 2
    if n > 1:
        with pytest.raises(SerializationError,
                           match=rf"string of {n} bytes exceeds its bound of {n - 1} bytes"):
            String(n - 1).serialize(text)
        # a wire string longer than the bound is rejected on the way in, too
        with pytest.raises(SerializationError,
                           match=rf"length {n} exceeds its bound of {n - 1} bytes"):
            String(n - 1).deserialize(wire)


@FEW
@given(st.sampled_from(list(Mode) + list(Signed) + list(Defaulted)))
def test_prop_enum_round_trip(member):
    t = fw_type(type(member))
    wire = assert_round_trip(t, member)
    assert t.deserialize(wire)[0] is member
    assert wire == int(member).to_bytes(t.rep.size, "big", signed=t.rep.signed)
    assert t.serialize(member.name) == wire and t.serialize(int(member)) == wire


@FEW
@given(st.integers(-(2**31), 2**31 - 1).filter(lambda v: v not in (-2, 0, 100000)))
def test_prop_enum_non_constant_rejected_both_ways(value):
    t = fw_type(Signed)
    with pytest.raises(SerializationError, match=rf"Test\.Signed has no constant with value {value}"):
        t.serialize(value)
    with pytest.raises(SerializationError,
                       match=rf"cannot deserialize Test\.Signed: {value} is not one of its values"):
        t.deserialize(I32.serialize(value))


finite64 = st.floats(allow_nan=False)
vec3s = st.builds(Vec3, finite64, finite64, finite64)
mixeds = st.builds(Mixed, st.booleans(), st.integers(0, 65535), bounded_text(8),
                   st.sampled_from(list(Mode)))
outers = st.builds(Outer, st.integers(0, 255), mixeds, vec3s, st.integers(-128, 127))


@PROPS
@given(outers)
def test_prop_nested_struct_round_trip(value):
    t = fw_type(Outer)
    wire = assert_round_trip(t, value)
    name_len = len(value.inner.name.encode("utf-8"))
    assert len(wire) == 1 + (1 + 2 + 2 + name_len + 1) + 24 + 1
    # the nested members are the members' own bytes, concatenated in declaration order
    assert wire == (U8.serialize(value.ident) + fw_type(Mixed).serialize(value.inner)
                    + fw_type(Vec3).serialize(value.vec) + I8.serialize(value.level))
    # and the same as a dict
    as_dict = {"ident": value.ident, "inner": value.inner, "vec": value.vec, "level": value.level}
    assert t.serialize(as_dict) == wire


@FEW
@given(st.lists(st.sampled_from(list(Mode)), min_size=3, max_size=3))
def test_prop_array_of_enums_round_trip(items):
    t = fw_type(Modes)
    wire = assert_round_trip(t, Modes(items))
    assert wire == bytes(int(m) for m in items)
    assert t.serialize(items) == wire


@PROPS
@given(st.lists(bounded_text(4, exact=True), min_size=2, max_size=2),
       st.lists(bounded_text(4), min_size=2, max_size=2))
def test_prop_array_of_strings_at_and_under_bound(at_bound, under_bound):
    t = fw_type(Names)
    for items in (at_bound, under_bound):
        wire = assert_round_trip(t, Names(items))
        assert wire == b"".join(String(4).serialize(s) for s in items)
    assert all(len(s.encode("utf-8")) == 4 for s in at_bound)
    assert len(t.serialize(at_bound)) == 2 * (2 + 4)


ANY_TYPED_VALUE = st.sampled_from([
    (U8, st.integers(0, 255)), (U16, st.integers(0, 65535)), (U32, st.integers(0, 2**32 - 1)),
    (U64, st.integers(0, 2**64 - 1)), (I8, st.integers(-128, 127)),
    (I16, st.integers(-(2**15), 2**15 - 1)), (I32, st.integers(-(2**31), 2**31 - 1)),
    (I64, st.integers(-(2**63), 2**63 - 1)), (F32, st.floats(width=32, allow_nan=False)),
    (F64, finite64), (BOOL, st.booleans()), (String(6), bounded_text(6)),
    (fw_type(Mode), st.sampled_from(list(Mode))), (fw_type(Signed), st.sampled_from(list(Signed))),
    (fw_type(Vec3), vec3s), (fw_type(Mixed), mixeds), (fw_type(Outer), outers),
    (fw_type(Modes), st.lists(st.sampled_from(list(Mode)), min_size=3, max_size=3).map(Modes)),
    (fw_type(Names), st.lists(bounded_text(4), min_size=2, max_size=2).map(Names)),
    (OpCode, st.integers(0, 2**32 - 1)),
]).flatmap(lambda ts: st.tuples(st.just(ts[0]), ts[1]))


@PROPS
@given(st.lists(ANY_TYPED_VALUE, max_size=8), st.binary(max_size=5), st.binary(min_size=1, max_size=3))
def test_prop_concatenated_values_deserialize_in_sequence(pairs, prefix, suffix):
    types = [t for t, _ in pairs]
    values = [v for _, v in pairs]
    pieces = [t.serialize(v) for t, v in pairs]
    data = serialize_values(types, values)
    assert data == b"".join(pieces)
    buf = prefix + data + suffix
    # each deserializer consumes exactly the bytes its serializer produced
    offset = len(prefix)
    for t, v, piece in zip(types, values, pieces, strict=True):
        back, end = t.deserialize(buf, offset)
        assert end == offset + len(piece)
        assert back == v
        offset = end
    assert offset == len(prefix) + len(data)
    assert deserialize_values(types, prefix + data, offset=len(prefix)) == values
    assert deserialize_values(types, buf, offset=len(prefix), exact=False) == values
    with pytest.raises(SerializationError,
                       match=rf"{len(suffix)} unexpected byte\(s\) after the last value "
                             rf"\(at offset {len(prefix) + len(data)}\)"):
        deserialize_values(types, buf, offset=len(prefix))


@PROPS
@given(ANY_TYPED_VALUE, st.data())
def test_prop_every_strict_prefix_is_reported_truncated(pair, data):
    t, value = pair
    wire = t.serialize(value)
    cut = data.draw(st.integers(0, len(wire) - 1))
    with pytest.raises(SerializationError, match=r"cannot deserialize .*: needs \d+ byte\(s\) at offset "
                                                 r"\d+, only \d+ left"):
        t.deserialize(wire[:cut])


def test_fit_utf8_cuts_on_a_character_boundary_and_replaces_lone_surrogates():
    from fprime_lite.model.types import fit_utf8

    assert fit_utf8("abc", 10) == "abc"
    assert fit_utf8("aé", 2) == "a"  # 'é' is two bytes: never half of it
    assert fit_utf8("éé", 3) == "é"
    assert fit_utf8("a\udc80b", 10) == "a?b"


class Floats(Array, namespace="Test", elem=F64, size=3):
    pass


def test_arrays_of_exact_valid_elements_are_kept_and_others_checked():
    """TYP-ARR-FAST: an F64 array of floats (or an enum array of its members) keeps its elements
    as given; an int is still converted, anything else refused, and the one-call pack gives the
    bytes of the element-by-element serialize."""
    exact = Floats([1.5, -0.0, float("inf")])
    assert list(exact) == [1.5, -0.0, float("inf")] and all(type(v) is float for v in exact)
    mixed = Floats([1.5, 2, 3.0])
    assert list(mixed) == [1.5, 2.0, 3.0] and type(mixed[1]) is float
    with pytest.raises(SerializationError, match="F64 expects a number"):
        Floats([1.0, "2", 3.0])
    with pytest.raises(SerializationError, match="F64 expects a number"):
        Floats([1.0, True, 3.0])
    modes = Modes([Mode(0), Mode(1), Mode(0)])
    assert all(type(m) is Mode for m in modes)
    t = fw_type(Floats)
    assert t.pack(mixed) == b"".join(F64.serialize(v) for v in mixed) == struct.pack(">ddd", 1.5, 2.0, 3.0)
