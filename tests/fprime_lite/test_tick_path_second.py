"""The framework's per-tick shortcuts of the second pass (issue #19, branch fwpath) keep F´'s behaviour.

Each test takes the shortcut first, then changes what it relies on (the clock's reading, the time
port's connection, a member's type, the range of an integer) and checks that what is stored or
raised is what the plain path gives: the time port's own answer, the type's own check.
"""

from __future__ import annotations

import struct

import pytest

from fprime_lite import F64, U8, U32, Array, Channel, PassiveComponent, Struct, Time, TimeBase
from fprime_lite.model.errors import SerializationError
from fprime_lite.model.fw_ports import Cycle
from fprime_lite.model.ports import OutputPort
from fprime_lite.model.time import NO_CLOCK_READING, SimulatedClock, simulated_clock_of
from fprime_lite.svc.rate_groups import ActiveRateGroup
from fprime_lite.svc.time_source import TimeSource
from fprime_lite.svc.tlm_chan import TlmChan, TlmValid

T1 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 10, 0)


def _f64_struct(name: str, n: int, *, stamped: bool = False) -> type:
    """A struct of ``n`` F64 members ``m0``… (and a Time member ``at`` last when ``stamped``)."""
    members: dict[str, object] = {f"m{i}": F64 for i in range(n)}
    if stamped:
        members["at"] = Time
    return type(name, (Struct,), {"__annotations__": members, "__module__": __name__}, namespace="TickTwo")


Triple = _f64_struct("Triple", 3)
Quad = _f64_struct("Quad", 4)
Five = _f64_struct("Five", 5)
Stamped5 = _f64_struct("Stamped5", 4, stamped=True)


class Vec3(Array, namespace="TickTwo", elem=F64, size=3):
    pass


class Vec4(Array, namespace="TickTwo", elem=F64, size=4):
    pass


class Pairs(Array, namespace="TickTwo", elem=Triple, size=2):
    pass


class _Writer(PassiveComponent):
    Rate = Channel(F64)
    Level = Channel(U8)
    Count = Channel(U32, update="on change")
    T3 = Channel(Triple)
    T4 = Channel(Quad)
    T5 = Channel(Five)
    S5 = Channel(Stamped5)
    V3 = Channel(Vec3)
    V4 = Channel(Vec4)
    cycleOut = OutputPort(Cycle)


def _wired(clock: SimulatedClock) -> tuple[_Writer, TlmChan, TimeSource]:
    writer, tlm, source = _Writer("writer", base_id=0x100), TlmChan("tlm"), TimeSource("time", clock)
    writer.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    writer.output_port("timeCaller").connect(0, source.input_port("timeGetPort"), 0)
    return writer, tlm, source


def _stamp(tlm: TlmChan, writer: _Writer, name: str) -> Time:
    valid, time, _ = tlm.TlmGet(writer.channels[name].id)
    assert valid == TlmValid.VALID
    return time


# --- time reads take the clock's Time of the instant, and only while that holds ---------------------

def test_tick_009_writes_are_stamped_with_what_the_time_port_answers_now():
    """TICK-009: a channel write (and ``get_time``) stamps with the time port's answer: the clock's
    one Time of the instant while the clock stays there, a new one after it moves or its epoch is
    set (an RTC set), the other clock's after a reconnection, the zero time once disconnected, and a
    custom time callable's own answer, called for every read."""
    clock = SimulatedClock(epoch_us=1_000_000)
    writer, tlm, _ = _wired(clock)
    rate = writer.channels["Rate"]
    clock.set_us(500)
    rate.write(1.0)
    first = _stamp(tlm, writer, "Rate")
    assert first is clock.now() and first.total_us == 1_000_500
    rate.write(2.0)
    assert _stamp(tlm, writer, "Rate") is first and writer.get_time() is first
    clock.set_us(700)  # the clock moves: a new Time, never the one of the previous instant
    rate.write(3.0)
    assert _stamp(tlm, writer, "Rate").total_us == 1_000_700
    clock.epoch_us = 5_000_000  # an RTC set at the same reading
    rate.write(4.0)
    assert _stamp(tlm, writer, "Rate").total_us == 5_000_700
    assert writer.get_time().total_us == 5_000_700

    other = SimulatedClock(time_base=TimeBase.TB_PROC_TIME, epoch_us=9_000_000)
    other.set_us(1)
    out = writer.output_port("timeCaller")
    out.disconnect(0)
    for value in (5.0, 5.5):  # every write after the disconnection, not only the first
        rate.write(value)
        assert _stamp(tlm, writer, "Rate") == Time() and writer.get_time() == Time()
    out.connect(0, TimeSource("other", other).input_port("timeGetPort"), 0)
    rate.write(6.0)
    assert _stamp(tlm, writer, "Rate") is other.now() and other.now().total_us == 9_000_001
    assert writer.get_time() is other.now()

    asked = []

    def custom() -> Time:
        asked.append(1)
        return T1

    out.disconnect(0)
    out.connect_callable(0, custom, "custom")
    rate.write(7.0)
    rate.write(8.0)
    assert writer.get_time() is T1 and _stamp(tlm, writer, "Rate") is T1 and len(asked) == 3


def test_tick_010_a_clock_subclass_with_its_own_now_is_always_called():
    """TICK-010: only a SimulatedClock's own ``now`` is read without the call; a clock class that
    defines its own ``now`` (or any other callable) is asked on every read."""

    class ShiftedClock(SimulatedClock):
        def now(self) -> Time:
            return Time.from_us(super().now().total_us + 7)

    assert simulated_clock_of(SimulatedClock().now) is not NO_CLOCK_READING
    assert simulated_clock_of(ShiftedClock().now) is NO_CLOCK_READING
    assert simulated_clock_of(lambda: T1) is NO_CLOCK_READING
    clock = ShiftedClock()
    writer, tlm, _ = _wired(clock)
    clock.set_us(100)
    clock.now()  # its Time of the instant is made: a shortcut would hand out 100, not 107
    writer.channels["Rate"].write(1.0)
    writer.channels["Rate"].write(2.0)
    assert _stamp(tlm, writer, "Rate").total_us == 107
    assert writer.get_time().total_us == 107


def test_tick_011_a_rate_group_cycle_ends_at_the_time_port_answer():
    """TICK-011: a rate group stamps ``RgMaxTime`` with its time port's answer at the cycle's end,
    which a member that moves the clock (or re-points the port) changes."""
    clock = SimulatedClock()
    group, tlm = ActiveRateGroup("group", base_id=0x300, contexts=[0]), TlmChan("tlm")
    group.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    group.output_port("timeCaller").connect(0, TimeSource("time", clock).input_port("timeGetPort"), 0)
    moves = [200, 0]

    def member(context: int) -> None:
        clock.now()
        clock.set_us(clock.current_us + moves.pop(0))

    group.output_port("RateGroupMemberOut").connect_callable(0, member, "member")
    clock.set_us(1_000)
    group.CycleIn(clock.now())
    assert tlm.TlmGet(group.channels["RgMaxTime"].id)[1].total_us == 1_200
    group.output_port("timeCaller").disconnect(0)
    group.CycleIn(clock.now())
    assert tlm.TlmGet(group.channels["RgMaxTime"].id)[1] == Time()


# --- integer channels: the range test is the type's -------------------------------------------------

def test_tick_012_an_integer_write_is_checked_as_the_type_checks():
    """TICK-012: an integer channel takes an int within the type's range as it is and refuses one
    outside it, a bool, a float and an int beyond U8 with the type's own SerializationError; an int
    subclass is stored as the plain int the type's check makes."""
    writer, tlm, _ = _wired(SimulatedClock())
    level, count = writer.channels["Level"], writer.channels["Count"]
    u8 = level.decl.type
    for good in (0, 255, 17):
        level.write(good, T1)
        assert tlm.TlmGet(level.id) == (TlmValid.VALID, T1, struct.pack(">B", good))
    for bad in (256, -1, 1 << 70, True, 3.0):
        with pytest.raises(SerializationError) as expected:
            u8.check(bad)
        with pytest.raises(SerializationError, match=str(expected.value).replace("[", r"\[")):
            level.write(bad, T1)
    assert level.last == 17
    level.write(TimeBase.TB_PROC_TIME, T1)  # an IntEnum member: the check's int(value)
    assert type(level.last) is int and level.last == 1
    count.write(5, T1)
    with pytest.raises(SerializationError, match="out of range"):
        count.write(1 << 32, T1)
    count.write(5, T1)  # unchanged: an on-change channel sends nothing new
    assert count.last == 5 and tlm.TlmGet(count.id)[2] == struct.pack(">I", 5)


# --- struct and array snapshots: every member position is tested ------------------------------------

@pytest.mark.parametrize("name, make", [
    ("T3", lambda v: Triple(*v)), ("T4", lambda v: Quad(*v)), ("T5", lambda v: Five(*v)),
    ("V3", lambda v: _raw_array(Vec3, v)),
    ("V4", lambda v: _raw_array(Vec4, v)),
])
def test_tick_013_each_member_of_a_snapshot_value_is_checked(name, make):
    """TICK-013: a struct or array channel refuses a bool at any member position with the type's
    own error (the quick test looks at every position), stores an int member as the float the
    full check makes of it, and stores plain floats as they are."""
    writer, tlm, _ = _wired(SimulatedClock())
    channel = writer.channels[name]
    t = channel.decl.type
    n = len(t.members) if hasattr(t, "members") else t.size
    plain = [0.5 * (i + 1) for i in range(n)]
    channel.write(make(plain), T1)
    assert tlm.TlmGet(channel.id)[2] == t.serialize(make(plain))
    for i in range(n):
        bad = list(plain)
        bad[i] = True
        with pytest.raises(SerializationError) as expected:
            t.check(make(bad))
        with pytest.raises(SerializationError, match=str(expected.value).replace("[", r"\[")):
            channel.write(make(bad), T1)
        as_int = list(plain)
        as_int[i] = 3
        channel.write(make(as_int), T1)
        stored = tlm._latest[channel.id][1]
        assert stored[i] == 3.0 and tlm.TlmGet(channel.id)[2] == t.serialize(make(as_int))
        if hasattr(t, "members"):  # a struct's check converts the member: a float is stored
            assert type(stored[i]) is float
    assert tlm.TlmGet(channel.id)[2] == t.serialize(make(as_int))


def _raw_array(cls, values):
    """An array holding ``values`` as they are (no element conversion), as a caller may build."""
    a = cls.__new__(cls)
    list.extend(a, values)
    return a


# --- arrays built on the tick path ---------------------------------------------------------------

def test_tick_014_array_construction_checks_and_copies_as_before():
    """TICK-014: an array copies the caller's list or tuple (never keeps it), converts ints to F64
    floats, refuses a bool or a wrong length with the type's error, takes any iterable, and gives
    each default array of structs its own struct elements."""
    items = [1.0, 2.0, 3.0]
    v = Vec3(items)
    items[0] = 9.0
    assert v == [1.0, 2.0, 3.0] and type(v) is Vec3
    assert Vec3((1.0, 2.0, 3.0)) == [1.0, 2.0, 3.0]
    assert Vec3(x for x in (1.0, 2.0, 3.0)) == [1.0, 2.0, 3.0]
    converted = Vec3([1, 2.0, 3])
    assert [type(x) for x in converted] == [float, float, float]
    with pytest.raises(SerializationError, match="element|expects a number"):
        Vec3([1.0, True, 3.0])
    with pytest.raises(SerializationError, match="exactly 3 elements, got 2"):
        Vec3((1.0, 2.0))
    assert Vec3() == [0.0, 0.0, 0.0]
    a, b = Pairs(), Pairs()
    assert a[0] == Triple() and a[0] is not a[1] and a[0] is not b[0]
    a[0].m0 = 5.0
    assert b[0].m0 == 0.0 and Pairs()[0].m0 == 0.0


def _raw_time(base, context, us) -> Time:
    """A Time with these fields as they are (no normalisation), as a caller could make one."""
    t = Time.__new__(Time)
    t.time_base, t.context, t.total_us = base, context, us
    return t


def test_tick_016_a_long_struct_with_a_time_member_refuses_what_the_time_check_refuses():
    """TICK-016: a struct of more than four members with a Time member (the loop of the quick check,
    e.g. the star tracker's attitude) stores a plain valid time and refuses, as the full check does,
    a time whose base, context or µs do not fit."""
    writer, tlm, _ = _wired(SimulatedClock())
    channel = writer.channels["S5"]
    t = channel.decl.type
    good = Stamped5(1.0, 2.0, 3.0, 4.0, _raw_time(TimeBase.TB_WORKSTATION_TIME, 0, 5))
    channel.write(good, T1)
    assert tlm.TlmGet(channel.id) == (TlmValid.VALID, T1, t.serialize(good))
    beyond = (0xFFFFFFFF + 1) * 1_000_000
    for fields in ((0x10000, 0, 5), (2, 0x100, 5), (2, 0, beyond), (2, 0, 5.0)):
        value = Stamped5(1.0, 2.0, 3.0, 4.0, _raw_time(*fields))
        with pytest.raises(Exception) as expected:
            t.check(value)
        with pytest.raises(type(expected.value)):
            channel.write(value, T1)
    assert tlm.TlmGet(channel.id)[2] == t.serialize(good)
