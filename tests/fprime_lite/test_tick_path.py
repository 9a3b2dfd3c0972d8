"""The framework's per-tick shortcuts (issue #19, branch fwtick) keep F´'s behaviour.

Each shortcut is worked out when a connection is made or a setting changes, and re-worked out when
that happens again: these tests change the connection or the setting after the shortcut was first
taken and check that what a component sees is what the plain path gives.
"""

from __future__ import annotations

import struct

import pytest

from fprime_lite import F64, U32, Channel, PassiveComponent, Time, TimeBase
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.model.errors import UnconnectedPortError
from fprime_lite.model.fw_ports import Cycle
from fprime_lite.model.ports import OutputPort
from fprime_lite.model.time import SimulatedClock
from fprime_lite.svc.rate_group_driver import Divider, RateGroupDriver, RateGroupTimer
from fprime_lite.svc.tlm_chan import TlmChan, TlmValid

T1 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 10, 0)
T2 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 11, 500)


class _Writer(PassiveComponent):
    """Two channels and an output port: all the tests need of a component."""

    Rate = Channel(F64)
    Count = Channel(U32)
    cycleOut = OutputPort(Cycle)


# --- channel writes straight into TlmChan's table ------------------------------------------------

def test_tick_001_a_write_after_reconnecting_tlm_out_reaches_the_new_store_only():
    """TICK-001: a channel write stores into the table of the TlmChan its tlmOut connects to *now*:
    after a disconnect and a connect to another TlmChan, nothing more reaches the first one."""
    writer, first, second = _Writer("writer", base_id=0x100), TlmChan("first"), TlmChan("second")
    out = writer.output_port("tlmOut")
    out.connect(0, first.input_port("TlmRecv"), 0)
    rate = writer.channels["Rate"]
    rate.write(0.5, T1)
    assert first.TlmGet(rate.id) == (TlmValid.VALID, T1, struct.pack(">d", 0.5))
    out.disconnect(0)
    rate.write(0.75, T2)  # unconnected: dropped, as before
    out.connect(0, second.input_port("TlmRecv"), 0)
    rate.write(0.25, T2)
    assert first.TlmGet(rate.id) == (TlmValid.VALID, T1, struct.pack(">d", 0.5))
    assert second.TlmGet(rate.id) == (TlmValid.VALID, T2, struct.pack(">d", 0.25))
    assert writer.channels["Rate"].last == 0.25


def _two_writes_reach_the_store(tlm, calls):
    """Two writes of Count into ``tlm`` (a TlmChan that logs its store calls into ``calls``)."""
    writer = _Writer("writer", base_id=0x100)
    writer.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    count = writer.channels["Count"]
    count.write(7, T1)
    count.write(8, T2)
    assert calls == [(count.id, T1, 7), (count.id, T2, 8)]
    assert tlm.TlmGet(count.id) == (TlmValid.VALID, T2, struct.pack(">I", 8))


def test_tick_002b_an_override_of_store_tlm_value_is_called_without_opting_out():
    """TICK-002b: a subclass that only overrides ``store_tlm_value`` sees every deferred write with
    nothing else to set."""
    calls = []

    class CountingTlmChan(TlmChan):
        def store_tlm_value(self, chan_id, time, value, pack):
            calls.append((chan_id, time, value))
            super().store_tlm_value(chan_id, time, value, pack)

    _two_writes_reach_the_store(CountingTlmChan("tlm"), calls)


def test_tick_003_a_restarted_tlm_chan_gets_the_writes_in_its_new_table():
    """TICK-003: TlmChan re-initialised in place (a flight-software restart) and the writer's slot
    re-pointed at its new entry: writes land in the new table, not the one from before."""
    writer, tlm = _Writer("writer", base_id=0x100), TlmChan("tlm")
    out = writer.output_port("tlmOut")
    out.connect(0, tlm.input_port("TlmRecv"), 0)
    rate = writer.channels["Rate"]
    rate.write(1.0, T1)
    old_table = tlm._latest
    TlmChan.__init__(tlm, "tlm")
    out.disconnect(0)
    out.connect(0, tlm.input_port("TlmRecv"), 0)
    rate.write(2.0, T2)
    assert tlm._latest is not old_table
    assert tlm.TlmGet(rate.id) == (TlmValid.VALID, T2, struct.pack(">d", 2.0))
    assert old_table[rate.id][1] == 1.0


# --- the simulated clock's one Time per instant -----------------------------------------------------

def test_tick_004_the_clock_makes_a_new_time_whenever_what_it_is_made_of_changes():
    """TICK-004: ``now()`` gives one shared Time per instant, and a new one after the reading moves
    (by ``set_us``, ``advance_us`` or a direct assignment) or the epoch, base or context is set."""
    clock = SimulatedClock(epoch_us=1_000_000)
    clock.set_us(250)
    t = clock.now()
    assert clock.now() is t and (t.total_us, t.time_base, t.context) == (1_000_250, TimeBase.TB_WORKSTATION_TIME, 0)
    clock.advance_us(5)
    assert clock.now().total_us == 1_000_255
    clock.current_us = 300
    assert clock.now().total_us == 1_000_300
    generation = clock.generation
    clock.epoch_us += 2_000_000  # an RTC set
    assert clock.now().total_us == 3_000_300 and clock.generation == generation + 1
    clock.time_base = TimeBase.TB_PROC_TIME
    assert clock.now().time_base == TimeBase.TB_PROC_TIME
    clock.context = 3
    assert clock.now().context == 3 and clock.now().total_us == 3_000_300
    assert clock.generation == generation + 3


def test_tick_005_the_scheduler_still_refuses_to_move_its_clock_back():
    """TICK-005: the scheduler sets its clock's reading itself, but an event due before a reading
    moved forward by hand still raises as ``set_us`` does."""
    scheduler = Scheduler()
    ran = []
    scheduler.call_at(100, lambda: ran.append(scheduler.now_us))
    scheduler.call_at(200, lambda: ran.append(scheduler.now_us))
    scheduler.run(until_us=150)
    assert ran == [100] and scheduler.now_us == 150
    scheduler.clock.set_us(500)
    with pytest.raises(ValueError, match="cannot go backwards"):
        scheduler.run(until_us=600)


# --- the timer reads the driver's firing table --------------------------------------------------

def test_tick_006_new_dividers_are_what_the_timer_follows_even_when_set_inside_a_cycle():
    """TICK-006: replacing a running driver's dividers changes the base ticks it fires on as the
    driver's own table says — also when a rate group's member replaces them during a cycle, after
    the driver has read its table for that tick (the timer then reads the new table)."""
    scheduler = Scheduler()
    driver = RateGroupDriver("driver", dividers=[Divider(10)])
    fired = []

    def member(t):
        fired.append(t.total_us)
        if t.total_us == 20_000:
            driver.dividers = (Divider(4, 1),)

    driver.output_port("CycleOut").connect_callable(0, member, "sink")
    timer = RateGroupTimer(scheduler, driver, 1000)
    timer.start()
    scheduler.run(until_us=30_000)
    # base ticks 0, 10, 20 on the old table; from tick 21 on, tick % 4 == 1
    assert fired == [0, 10_000, 20_000, 21_000, 25_000, 29_000]
    driver.dividers = (Divider(10, 3),)  # between runs: the wake-up planned for tick 33 still fits
    scheduler.run(until_us=60_000)
    assert fired[6:] == [33_000, 43_000, 53_000]
    assert timer.cycles == 6 + 3


# --- is_connected in one call --------------------------------------------------------------------

def test_tick_007_is_connected_and_an_unconnected_call_fail_as_before():
    """TICK-007: ``is_connected`` follows (dis)connection, names the ports for an unknown one, and a
    call through an unconnected slot still raises UnconnectedPortError."""
    writer = _Writer("writer")
    assert not writer.is_connected("cycleOut", 0)
    with pytest.raises(UnconnectedPortError, match="writer.cycleOut"):
        writer.cycleOut[0](T1)
    writer.output_port("cycleOut").connect_callable(0, lambda t: None, "sink")
    assert writer.is_connected("cycleOut", 0)
    writer.output_port("cycleOut").disconnect(0)
    assert not writer.is_connected("cycleOut")
    with pytest.raises(KeyError, match="no output port 'nope'; output ports: .*cycleOut"):
        writer.is_connected("nope")


# --- struct channels with a time member: the quick check --------------------------------------------

def test_tick_008_a_time_member_is_accepted_and_refused_as_the_time_check_does():
    """TICK-008: a struct channel with a Time member (the magnetometer's reading) takes the quick
    path for a plain valid Time and refuses, with the time's own SerializationError, a time whose
    base, context or seconds do not fit (or are not plain ints), exactly as the full check."""
    from fprime_lite import Struct
    from fprime_lite.model.errors import SerializationError

    class Stamped(Struct, namespace="Tick"):
        x: F64
        y: F64
        at: Time

    class Sampler(PassiveComponent):
        Sample = Channel(Stamped)

    sampler, tlm = Sampler("sampler", base_id=0x200), TlmChan("tlm")
    sampler.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    channel = sampler.channels["Sample"]
    full_check = channel.decl.type.check

    def stamp(base, context, us):
        t = Time.__new__(Time)
        t.time_base, t.context, t.total_us = base, context, us
        return t

    last_second = (0xFFFFFFFF + 1) * 1_000_000 - 1
    good = [stamp(TimeBase.TB_WORKSTATION_TIME, 0, 5), stamp(0xFFFF, 0xFF, last_second), stamp(0, 0, 0)]
    for at in good:
        value = Stamped(1.0, -2.0, at)
        channel.write(value, T1)
        assert full_check(value) is value
        assert tlm.TlmGet(channel.id) == (TlmValid.VALID, T1, channel.decl.type.serialize(value))
    bad = [stamp(0x10000, 0, 5), stamp(-1, 0, 5), stamp(2, 0x100, 5), stamp(2, -1, 5), stamp(2, True, 5),
           stamp(2, 0, last_second + 1), stamp(2, 0, -1_000_000), stamp(2, 0, 5.0)]
    for at in bad:
        value = Stamped(1.0, -2.0, at)
        with pytest.raises(Exception) as expected:
            full_check(value)
        with pytest.raises(type(expected.value)):
            channel.write(value, T2)
    assert isinstance(expected.value, SerializationError)
    assert tlm.TlmGet(channel.id)[1] == T1  # nothing refused was stored
