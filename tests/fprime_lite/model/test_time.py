"""fprime_lite.model.time: Time, TimeInterval, TimeBase, the 11-byte Fw::Time wire format and the clocks.

Time values are F´'s ``Fw::Time`` ``{time_base U16, context U8, seconds U32, useconds U32}``,
serialized big-endian in that order; times of different bases are incomparable unless one of them
is ``TB_DONT_CARE``. No test sleeps; the only wall-clock use is one WallClock monotonicity check.
"""

import operator

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fprime_lite.model.errors import SerializationError
from fprime_lite.model.time import (
    TIME, US_PER_S, Clock, SimulatedClock, Time, TimeBase, TimeInterval, WallClock,
)
from fprime_lite.model.types import U8, U16, U32, FwEnum, deserialize_values, fw_type, serialize_values

PROPS = settings(max_examples=80, deadline=None)

WS = TimeBase.TB_WORKSTATION_TIME
PROC = TimeBase.TB_PROC_TIME
NONE = TimeBase.TB_NONE
DONT_CARE = TimeBase.TB_DONT_CARE


def hx(s: str) -> bytes:
    return bytes.fromhex(s.replace(" ", ""))


# --------------------------------------------------------------------------------------------
# TimeBase
# --------------------------------------------------------------------------------------------

def test_time_base_enum():
    assert issubclass(TimeBase, FwEnum)
    assert [(m.name, int(m)) for m in TimeBase] == [
        ("TB_NONE", 0), ("TB_PROC_TIME", 1), ("TB_WORKSTATION_TIME", 2), ("TB_DONT_CARE", 0xFFFF)]
    t = fw_type(TimeBase)
    assert t.rep is U16
    assert t.serialize(DONT_CARE) == hx("FFFF")
    assert t.json_definition()["representationType"] == {
        "name": "U16", "kind": "integer", "size": 16, "signed": False}
    assert t.json_definition()["default"] == "TimeBase.TB_NONE"


# --------------------------------------------------------------------------------------------
# Time values
# --------------------------------------------------------------------------------------------

def test_time_fields_and_views():
    t = Time(PROC, 3, 5, 250)
    assert (t.time_base, t.context, t.seconds, t.useconds) == (PROC, 3, 5, 250)
    assert t.total_us == 5_000_250
    assert t.to_float() == 5.00025
    assert str(t) == "5.000250"
    assert repr(t) == "Time(TB_PROC_TIME, 3, 5, 250)"
    assert repr(Time(7, 0, 1, 0)) == "Time(7, 0, 1, 0)"  # unknown base shown by number
    assert Time() == Time(NONE, 0, 0, 0)
    assert US_PER_S == 1_000_000


def test_time_useconds_normalised():
    t = Time(WS, 0, 1, 2_500_000)
    assert (t.seconds, t.useconds) == (3, 500_000)
    assert t == Time(WS, 0, 3, 500_000)
    assert hash(t) == hash(Time(WS, 0, 3, 500_000))
    assert Time(WS, 0, 0, US_PER_S) == Time(WS, 0, 1, 0)
    assert Time(WS, 0, 0, 999_999).seconds == 0


def test_time_from_us():
    t = Time.from_us(3_000_001)
    assert (t.time_base, t.context, t.seconds, t.useconds) == (WS, 0, 3, 1)
    assert Time.from_us(7, PROC, 9) == Time(PROC, 9, 0, 7)
    assert Time.from_us(0, NONE) == Time()


def test_negative_times_rejected():
    with pytest.raises(ValueError, match=r"^time cannot be negative: -1 s 0 us$"):
        Time(WS, 0, -1, 0)
    with pytest.raises(ValueError, match=r"time cannot be negative: 5 s -1 us"):
        Time(WS, 0, 5, -1)
    with pytest.raises(ValueError, match=r"^time cannot be negative: -5 us$"):
        Time.from_us(-5)


def test_time_equality_and_hash():
    a = Time(WS, 1, 10, 5)
    assert a == Time(WS, 1, 10, 5)
    assert a != Time(WS, 2, 10, 5)  # context is part of equality
    assert a != Time(PROC, 1, 10, 5)  # so is the base (unequal, not an error)
    assert a != Time(WS, 1, 10, 6)
    assert (a == 10) is False and a != "10.000005"
    assert Time(2, 1, 10, 5) == a and hash(Time(2, 1, 10, 5)) == hash(a)  # base as a plain int
    assert len({a, Time(WS, 1, 10, 5), Time(WS, 1, 0, 10 * US_PER_S + 5), Time(WS, 0, 10, 5)}) == 2


def test_time_ordering_same_base():
    times = [Time(WS, 0, 2, 0), Time(WS, 0, 1, 999_999), Time(WS, 0, 0, 0), Time(WS, 0, 1, 0)]
    assert sorted(times) == [Time(WS, 0, 0, 0), Time(WS, 0, 1, 0), Time(WS, 0, 1, 999_999),
                             Time(WS, 0, 2, 0)]
    a, b = Time(WS, 0, 1, 0), Time(WS, 0, 1, 1)
    assert a < b and a <= b and b > a and b >= a
    assert not (b < a) and not (b <= a) and not (a > b) and not (a >= b)
    assert a <= Time(WS, 0, 1, 0) and a >= Time(WS, 0, 1, 0)
    # ordering is by time only: context does not matter
    assert Time(WS, 5, 1, 0) < Time(WS, 0, 2, 0)


def test_time_ordering_against_non_times_is_a_type_error():
    with pytest.raises(TypeError):
        Time(WS, 0, 1, 0) < 5  # noqa: B015
    with pytest.raises(TypeError):
        Time(WS, 0, 1, 0) >= TimeInterval(1)  # noqa: B015


@pytest.mark.parametrize("op", [operator.lt, operator.le, operator.gt, operator.ge])
def test_different_bases_are_incomparable(op):
    a, b = Time(NONE, 0, 1, 0), Time(PROC, 0, 2, 0)
    with pytest.raises(ValueError,
                       match=r"^cannot compare times of different bases \(TB_NONE and TB_PROC_TIME\)$"):
        op(a, b)
    with pytest.raises(ValueError, match=r"cannot compare times of different bases \(7 and TB_WORKSTATION_TIME\)"):
        op(Time(7, 0, 0, 0), Time(WS, 0, 0, 0))


def test_different_bases_cannot_be_subtracted():
    with pytest.raises(ValueError,
                       match=r"cannot compare times of different bases \(TB_WORKSTATION_TIME and TB_PROC_TIME\)"):
        Time(WS, 0, 5, 0) - Time(PROC, 0, 1, 0)


def test_dont_care_compares_with_any_base():
    dc = Time(DONT_CARE, 0, 5, 0)
    for base in (NONE, PROC, WS, 7):
        assert Time(base, 0, 1, 0) < dc and dc > Time(base, 0, 1, 0)
        assert Time(base, 0, 5, 0) <= dc and dc >= Time(base, 0, 5, 0)
        assert dc - Time(base, 0, 1, 0) == TimeInterval(4)
        assert Time(base, 0, 6, 0) - dc == TimeInterval(1)
        assert Time(base, 0, 5, 0) != dc  # comparable, but not equal: bases differ


def test_time_plus_interval():
    t = Time(PROC, 4, 1, 900_000) + TimeInterval(2, 200_000)
    assert t == Time(PROC, 4, 4, 100_000)
    assert (t.time_base, t.context) == (PROC, 4)
    assert Time(WS, 0, 1, 0) + TimeInterval() == Time(WS, 0, 1, 0)


def test_time_minus_interval():
    t = Time(PROC, 4, 3, 100_000) - TimeInterval(1, 200_000)
    assert t == Time(PROC, 4, 1, 900_000) and t.time_base == PROC and t.context == 4
    assert Time(WS, 0, 1, 0) - TimeInterval(1) == Time(WS, 0, 0, 0)
    with pytest.raises(ValueError, match=r"^0\.500000 minus TimeInterval\(1, 0\) would be before the epoch$"):
        Time(WS, 0, 0, 500_000) - TimeInterval(1)


def test_time_minus_time():
    d = Time(WS, 0, 5, 100) - Time(WS, 3, 2, 200)
    assert isinstance(d, TimeInterval)
    assert d == TimeInterval(2, 999_900)
    assert Time(WS, 0, 5, 0) - Time(WS, 0, 5, 0) == TimeInterval()


def test_time_minus_later_time_is_an_error():
    with pytest.raises(ValueError, match=r"^2\.000000 is later than 1\.000000; subtract the earlier time$"):
        Time(WS, 0, 1, 0) - Time(WS, 0, 2, 0)
    with pytest.raises(ValueError, match=r"1\.000001 is later than 1\.000000"):
        Time(WS, 0, 1, 0) - Time(WS, 0, 1, 1)


def test_time_arithmetic_with_wrong_types():
    t = Time(WS, 0, 1, 0)
    with pytest.raises(TypeError):
        t + t
    with pytest.raises(TypeError):
        t + 1
    with pytest.raises(TypeError):
        t - 1
    with pytest.raises(TypeError):
        TimeInterval(1) + t


def test_time_is_immutable():
    t = Time(WS, 0, 1, 0)
    with pytest.raises(AttributeError):
        t.seconds = 5
    with pytest.raises(AttributeError):
        t.extra = 1


# --------------------------------------------------------------------------------------------
# TimeInterval
# --------------------------------------------------------------------------------------------

def test_interval_normalised_and_views():
    i = TimeInterval(1, 1_500_000)
    assert (i.seconds, i.useconds, i.total_us) == (2, 500_000, 2_500_000)
    assert i.to_float() == 2.5
    assert repr(i) == "TimeInterval(2, 500000)"
    assert TimeInterval.from_us(1_000_001) == TimeInterval(1, 1)
    assert TimeInterval() == TimeInterval.from_us(0)


def test_interval_negative_rejected():
    with pytest.raises(ValueError, match=r"^a time interval cannot be negative: -1 s 0 us$"):
        TimeInterval(-1)
    with pytest.raises(ValueError, match=r"a time interval cannot be negative: 0 s -1 us"):
        TimeInterval(0, -1)
    with pytest.raises(ValueError, match=r"^a time interval cannot be negative: -1 us$"):
        TimeInterval.from_us(-1)


def test_interval_equality_ordering_and_sum():
    a, b = TimeInterval(1, 0), TimeInterval(0, 1_000_001)
    assert a < b and a <= b and b > a and b >= a and a <= TimeInterval(1) and a >= TimeInterval(1)
    assert a == TimeInterval(0, US_PER_S) and hash(a) == hash(TimeInterval(0, US_PER_S))
    assert a != b and a != 1 and a != Time(WS, 0, 1, 0)
    assert a + b == TimeInterval(2, 1)
    assert sorted([b, a, TimeInterval()]) == [TimeInterval(), a, b]
    with pytest.raises(TypeError):
        a + 1


@pytest.mark.parametrize("op", ["<", "<=", ">", ">="])
def test_interval_ordering_against_non_intervals_is_a_type_error(op):
    with pytest.raises(TypeError):
        eval(f"TimeInterval(1) {op} 5")
    with pytest.raises(TypeError):
        eval(f"TimeInterval(1) {op} Time(WS, 0, 1, 0)")


# --------------------------------------------------------------------------------------------
# Fw::Time serialization
# --------------------------------------------------------------------------------------------

def test_time_type_identity():
    assert fw_type(Time) is TIME
    assert TIME.kind == "time" and TIME.name == "Fw.Time" and TIME.size == 11
    assert TIME.json_ref() == {"name": "Fw.TimeValue", "kind": "qualifiedIdentifier"}
    assert TIME.default == Time()


@pytest.mark.parametrize("value,wire", [
    (Time(WS, 3, 0x01020304, 999_999), "0002 03 01020304 000F423F"),
    (Time(), "0000 00 00000000 00000000"),
    (Time(PROC, 0, 1, 1), "0001 00 00000001 00000001"),
    (Time(DONT_CARE, 0xFF, 0xFFFFFFFF, 999_999), "FFFF FF FFFFFFFF 000F423F"),
    (Time(0x1234, 0x56, 100, 500_000), "1234 56 00000064 0007A120"),
], ids=repr)
def test_time_exact_wire_bytes(value, wire):
    data = TIME.serialize(value)
    assert len(data) == 11
    assert data == hx(wire)
    back, end = TIME.deserialize(data)
    assert back == value and end == 11
    assert (back.time_base, back.context, back.seconds, back.useconds) == (
        value.time_base, value.context, value.seconds, value.useconds)


def test_time_wire_is_u16_u8_u32_u32():
    t = Time(WS, 7, 123, 456)
    assert TIME.serialize(t) == U16.serialize(2) + U8.serialize(7) + U32.serialize(123) + U32.serialize(456)


@pytest.mark.parametrize("us", [US_PER_S, US_PER_S + 1, 0xFFFFFFFF])
def test_time_deserialize_rejects_useconds_of_a_second_or_more(us):
    data = hx("0002 00 00000001") + us.to_bytes(4, "big")
    with pytest.raises(SerializationError,
                       match=rf"^cannot deserialize Fw\.Time: useconds {us} ≥ 1000000$"):
        TIME.deserialize(data)


def test_time_deserialize_truncated():
    data = TIME.serialize(Time(WS, 0, 1, 2))
    for cut in range(11):
        with pytest.raises(SerializationError,
                           match=rf"^cannot deserialize Fw\.Time: needs 11 byte\(s\) at offset 0, "
                                 rf"only {cut} left$"):
            TIME.deserialize(data[:cut])
    with pytest.raises(SerializationError, match=r"needs 11 byte\(s\) at offset 2, only 10 left"):
        TIME.deserialize(b"\x00\x00" + data[:10], 2)


def test_time_serialize_rejects_what_does_not_fit():
    with pytest.raises(SerializationError, match=r"^Fw\.Time expects a Time, got 5$"):
        TIME.serialize(5)
    with pytest.raises(SerializationError, match=r"Fw\.Time expects a Time, got TimeInterval\(1, 0\)"):
        TIME.check(TimeInterval(1))
    with pytest.raises(SerializationError, match=r"U32 value 4294967296 is out of range"):
        TIME.serialize(Time(WS, 0, 2**32, 0))
    with pytest.raises(SerializationError, match=r"U8 value 256 is out of range \[0, 255\]"):
        TIME.serialize(Time(WS, 256, 0, 0))
    with pytest.raises(SerializationError, match=r"U16 value 65536 is out of range \[0, 65535\]"):
        TIME.serialize(Time(0x10000, 0, 0, 0))
    assert TIME.serialize(Time(WS, 0, 2**32 - 1, 999_999)) == hx("0002 00 FFFFFFFF 000F423F")


def test_time_among_other_values():
    # a telemetry record: U32 id | Time | value
    data = serialize_values([U32, TIME, U16], [0x101, Time(WS, 0, 10, 20), 7])
    assert data == hx("00000101" "0002 00 0000000A 00000014" "0007")
    assert deserialize_values([U32, TIME, U16], data) == [0x101, Time(WS, 0, 10, 20), 7]


times = st.builds(Time, st.integers(0, 0xFFFF), st.integers(0, 0xFF),
                  st.integers(0, 0xFFFFFFFF), st.integers(0, US_PER_S - 1))


@PROPS
@given(times, st.binary(max_size=4))
def test_prop_time_round_trip(value, prefix):
    data = TIME.serialize(value)
    assert len(data) == 11
    assert data == (value.time_base.to_bytes(2, "big") + value.context.to_bytes(1, "big")
                    + value.seconds.to_bytes(4, "big") + value.useconds.to_bytes(4, "big"))
    back, end = TIME.deserialize(prefix + data + b"\x00", len(prefix))
    assert back == value and hash(back) == hash(value)
    assert end == len(prefix) + 11


# --------------------------------------------------------------------------------------------
# Arithmetic properties
# --------------------------------------------------------------------------------------------

us_values = st.integers(0, 10**13)


@PROPS
@given(us_values, us_values, st.sampled_from([NONE, PROC, WS]), st.integers(0, 255))
def test_prop_time_interval_arithmetic(t_us, i_us, base, context):
    t = Time.from_us(t_us, base, context)
    i = TimeInterval.from_us(i_us)
    later = t + i
    assert later.total_us == t_us + i_us
    assert (later.time_base, later.context) == (base, context)
    assert later - t == i
    assert later - i == t
    assert later >= t and (later > t) == (i_us > 0)
    assert 0 <= later.useconds < US_PER_S
    assert later.seconds * US_PER_S + later.useconds == later.total_us


@PROPS
@given(us_values, us_values)
def test_prop_ordering_matches_microseconds(a_us, b_us):
    a, b = Time.from_us(a_us), Time.from_us(b_us)
    assert (a < b) == (a_us < b_us)
    assert (a <= b) == (a_us <= b_us)
    assert (a == b) == (a_us == b_us)
    assert (a > b) == (a_us > b_us)
    assert (hash(a) == hash(b)) or a != b
    if a_us >= b_us:
        assert (a - b).total_us == a_us - b_us
    else:
        with pytest.raises(ValueError, match=r"is later than .*; subtract the earlier time"):
            a - b


@PROPS
@given(st.integers(0, 10**6), st.integers(0, 10**9))
def test_prop_normalisation(seconds, useconds):
    t = Time(PROC, 0, seconds, useconds)
    i = TimeInterval(seconds, useconds)
    for v in (t, i):
        assert v.total_us == seconds * US_PER_S + useconds
        assert 0 <= v.useconds < US_PER_S
        assert v.seconds == seconds + useconds // US_PER_S
    assert t == Time(PROC, 0, t.seconds, t.useconds)
    assert i == TimeInterval(i.seconds, i.useconds)


# --------------------------------------------------------------------------------------------
# Clocks
# --------------------------------------------------------------------------------------------

def test_simulated_clock_defaults():
    clock = SimulatedClock()
    assert clock.now_us() == 0
    t = clock.now()
    assert t == Time(WS, 0, 0, 0)
    assert (t.time_base, t.context) == (WS, 0)


def test_simulated_clock_now_carries_base_context_and_epoch():
    clock = SimulatedClock(PROC, 7, epoch_us=1_000_000_000, start_us=250)
    assert clock.now_us() == 250  # excludes the epoch
    t = clock.now()
    assert (t.time_base, t.context) == (PROC, 7)
    assert t.total_us == 1_000_000_250
    assert (t.seconds, t.useconds) == (1000, 250)
    assert t == Time(PROC, 7, 1000, 250)
    assert Clock.now(clock) == t  # the generic Clock.now agrees with the fast path


def test_simulated_clock_set_and_advance():
    clock = SimulatedClock(epoch_us=5)
    clock.set_us(1_500_000)
    assert clock.now_us() == 1_500_000 and clock.now() == Time(WS, 0, 1, 500_005)
    clock.set_us(1_500_000)  # setting the same time is allowed
    clock.advance_us(0)
    assert clock.now_us() == 1_500_000
    clock.advance_us(600_000)
    assert clock.now_us() == 2_100_000
    assert clock.now() == Time(WS, 0, 2, 100_005)


def test_simulated_clock_only_moves_when_told():
    clock = SimulatedClock(start_us=42)
    assert clock.now() == clock.now()
    assert [clock.now_us() for _ in range(3)] == [42, 42, 42]


def test_simulated_clock_refuses_to_go_backwards():
    clock = SimulatedClock(start_us=10)
    with pytest.raises(ValueError, match=r"^simulated time cannot go backwards \(5 < 10 us\)$"):
        clock.set_us(5)
    assert clock.now_us() == 10
    with pytest.raises(ValueError, match=r"^cannot advance time by a negative amount \(-1 us\)$"):
        clock.advance_us(-1)
    assert clock.now_us() == 10


def test_simulated_clock_times_are_snapshots():
    clock = SimulatedClock()
    before = clock.now()
    clock.advance_us(3)
    after = clock.now()
    assert before == Time(WS, 0, 0, 0) and after == Time(WS, 0, 0, 3)
    assert after - before == TimeInterval(0, 3)


@PROPS
@given(st.lists(st.integers(0, 10**9), max_size=10), st.integers(0, 10**12))
def test_prop_simulated_clock_accumulates(steps, epoch):
    clock = SimulatedClock(NONE, 1, epoch_us=epoch)
    previous = clock.now()
    for step in steps:
        clock.advance_us(step)
        now = clock.now()
        assert now - previous == TimeInterval.from_us(step)
        previous = now
    assert clock.now_us() == sum(steps)
    assert clock.now().total_us == epoch + sum(steps)


def test_clock_base_is_abstract():
    with pytest.raises(NotImplementedError):
        Clock().now_us()
    with pytest.raises(NotImplementedError):
        Clock().now()


def test_wall_clock_monotonic_and_stamped():
    clock = WallClock(PROC, 2, epoch_us=5_000_000)
    a = clock.now_us()
    b = clock.now_us()
    assert 0 <= a <= b
    t = clock.now()
    assert (t.time_base, t.context) == (PROC, 2)
    assert t.total_us >= 5_000_000 + b
