"""Generated snapshot writers (issue 32, branch fpart): a struct or array channel whose members all have one
always-valid Python type writes through a writer with its member tests written in
(``fprime_lite.model.telemetry._snapshot_writer_factory``) instead of calling the channel's quick check.

What it changes must be nothing a component or the ground can see: the tests fly one random script of
writes (valid values, values whose members were given another type afterwards, bad time members, values
of another class, nonsense), clock moves and TlmChan runs twice, once with the generated writers and once
with every write on the general path, and require the same stored member tuples (their types included),
the same packets, the same errors and the same ``last`` values.
"""

from __future__ import annotations

import random

import pytest

from fprime_lite import F64, Array, Channel, FwEnum, PassiveComponent, Struct, Time, TimeBase
from fprime_lite.model import telemetry
from fprime_lite.model.time import SimulatedClock
from fprime_lite.svc.time_source import TimeSource
from fprime_lite.svc.tlm_chan import TlmChan


class SnapMode(FwEnum, namespace="Snap"):
    OFF = 0
    ON = 1


class SnapVec(Struct, namespace="Snap"):
    x: F64
    y: F64
    z: F64


class SnapField(Struct, namespace="Snap"):  # three numbers and a time, as the IMU's MagneticField
    x: F64
    y: F64
    z: F64
    timestamp: Time


class SnapModeRate(Struct, namespace="Snap"):  # two members, one an enum
    mode: SnapMode
    rate: F64


class SnapArray(Array, elem=F64, size=3, namespace="Snap"):
    pass


class SnapOne(Array, elem=F64, size=1, namespace="Snap"):
    pass


class SnapLong(Array, elem=F64, size=20, namespace="Snap"):  # beyond _QUICK_MEMBERS_MAX: the check is called
    pass


class _Writer(PassiveComponent):
    Vec = Channel(SnapVec)
    Field = Channel(SnapField)
    ModeRate = Channel(SnapModeRate, update="on change")
    Values = Channel(SnapArray)
    VecOnChange = Channel(SnapVec, update="on change")
    One = Channel(SnapOne)
    Long = Channel(SnapLong)


_NAMES = ("Vec", "Field", "ModeRate", "Values", "VecOnChange")
_T = Time(TimeBase.TB_WORKSTATION_TIME, 0, 12, 5)


def _value(name: str, rng: random.Random):
    """A value for channel ``name``: mostly valid, sometimes one the quick tests must hand to the full check."""
    pick = rng.random()
    if name in ("Vec", "VecOnChange"):
        v = SnapVec(1.0, rng.choice([2.0, 2.5]), 3.0)
        if pick < 0.15:
            v.y = 2  # an int member: the full check converts it
        elif pick < 0.25:
            v.z = "3"  # a member no check accepts
        elif pick < 0.35:
            return rng.choice([(1.0, 2.0, 3.0), None, SnapArray([1.0, 2.0, 3.0])])
        return v
    if name == "Field":
        f = SnapField(0.5, -0.5, rng.choice([0.25, 0.75]), _T)
        if pick < 0.15:
            f.timestamp = Time(TimeBase.TB_WORKSTATION_TIME, 0, 2**33, 0)  # seconds beyond U32: refused
        elif pick < 0.25:
            f.timestamp = Time(int(TimeBase.TB_PROC_TIME), 0, 3, 0)  # an int base: as valid as the enum
        elif pick < 0.35:
            f.x = 1  # an int member
        elif pick < 0.4:
            f.timestamp = 5
        return f
    if name == "ModeRate":
        m = SnapModeRate(rng.choice([SnapMode.OFF, SnapMode.ON]), rng.choice([0.5, 1.0]))
        if pick < 0.15:
            m.mode = 1  # an int for the enum
        elif pick < 0.25:
            m.mode = 7  # no such member
        return m
    a = SnapArray([1.0, rng.choice([2.0, 4.0]), 3.0])
    if pick < 0.15:
        a[1] = 2  # an int element
    elif pick < 0.25:
        a[2] = "x"
    elif pick < 0.35:
        return rng.choice([[1.0, 2.0, 3.0], (1.0, 2.0), 4.0])
    return a


def _fly(seed: int) -> list:
    """Run the seeded script; return everything observable, in order."""
    rng = random.Random(seed)
    clock = SimulatedClock()
    writer, tlm, source = _Writer("writer", base_id=0x200), TlmChan("tlm"), TimeSource("time", clock)
    packets: list = []
    tlm.output_port("PktSend").connect_callable(0, lambda data, context: packets.append(data), "ground")
    writer.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    writer.output_port("timeCaller").connect(0, source.input_port("timeGetPort"), 0)
    seen: list = []
    for _ in range(300):
        op = rng.random()
        if op < 0.8:
            name = rng.choice(_NAMES)
            channel = writer.channels[name]
            value = _value(name, rng)
            try:
                channel.write(value, _T) if rng.random() < 0.1 else channel.write(value)
                seen.append(("ok", name, repr(channel.last), type(channel.last).__name__, channel.written))
            except Exception as exc:  # noqa: BLE001 - the error itself is what is compared
                seen.append(("raised", name, type(exc).__name__, str(exc)))
            if rng.random() < 0.3 and isinstance(value, SnapVec):
                value.x = 9.0  # mutated after the write: what was stored must not change
        elif op < 0.92:
            clock.advance_us(rng.choice([0, 1, 20_000]))
        else:
            tlm.Run(0)
        # the stored entries themselves: the member tuple with its members' types, and its bytes
        seen.append(sorted((cid, entry[0].total_us, repr(entry[1]), [type(m).__name__ for m in entry[1]]
                            if isinstance(entry[1], tuple) else None, entry[2](entry[1]))
                           for cid, entry in tlm._latest.items()))
    tlm.Run(0)
    seen.append(packets)
    return seen


@pytest.mark.parametrize("seed", range(5))
def test_tick_020_snapshot_writers_store_send_and_raise_what_the_general_path_does(seed, monkeypatch):
    """TICK-020: the same script, generated snapshot writers against the general path only: the same
    stored member tuples (types included), bytes, packets, errors and ``last`` values."""
    generated = _fly(seed)
    monkeypatch.setattr(telemetry.BoundChannel, "_specialise",
                        lambda self: setattr(self, "write", self._write_general))
    assert _fly(seed) == generated


def test_tick_021_a_snapshot_channel_writes_through_the_member_testing_writer():
    """TICK-021: every channel above (3 and 4 members, a time member, an enum member, an array, on change
    or not) writes through the snapshot writer with its member tests written in, not through a call
    of the quick check."""
    clock = SimulatedClock()
    writer, tlm, source = _Writer("writer", base_id=0x200), TlmChan("tlm"), TimeSource("time", clock)
    writer.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    writer.output_port("timeCaller").connect(0, source.input_port("timeGetPort"), 0)
    for name in _NAMES:
        channel = writer.channels[name]
        for _ in range(3):  # the first write finds the store; the writer is made then
            channel.write(_value(name, random.Random(0)))  # seed 0: a valid value of every channel
        assert channel.write.__code__.co_filename.startswith("<channel writer snapshot "), name
        assert tlm._latest[channel.id][1] == tuple(channel._members_of(channel.last)), name
    one, long = writer.channels["One"], writer.channels["Long"]
    for value in (SnapOne([0.5]), SnapOne([0.25])):
        one.write(value)
    assert one.write.__code__.co_filename == "<channel writer snapshot 1>"
    assert tlm._latest[one.id][1] == (0.25,)
    bad = SnapOne([0.5])
    bad[0] = 1  # an int element: the member test fails, the array type's own check decides what is stored
    one.write(bad)
    checked = tuple(SnapOne.__fprime_type__.check(bad))
    assert tlm._latest[one.id][1] == checked and [type(m) for m in tlm._latest[one.id][1]] == [type(m) for m in checked]
    for value in (SnapLong([float(i) for i in range(20)]), SnapLong([2.0] * 20)):
        long.write(value)
    assert long.write.__code__.co_filename == "<channel writer none snapshot>"
    assert tlm._latest[long.id][1] == (2.0,) * 20
