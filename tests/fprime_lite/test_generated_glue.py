"""Generated glue (issue 32, branch speedgen): what it changes must be nothing a component or the
ground can see.

A channel connected straight to TlmChan writes through a writer generated for it
(``fprime_lite.model.telemetry._writer_factory``); these tests fly one random script of writes,
(dis)connections, clock moves and bad values twice, once with the generated writers and once with
every write on the general path, and require the same stores, packets, errors and ``last`` values.
"""

from __future__ import annotations

import random
import types

import pytest

from fprime_lite import F64, U8, U32, Channel, FwEnum, PassiveComponent, Struct, Time, TimeBase
from fprime_lite.model import telemetry
from fprime_lite.model.time import SimulatedClock
from fprime_lite.svc.time_source import TimeSource
from fprime_lite.svc.tlm_chan import TlmChan

T_GIVEN = Time(TimeBase.TB_WORKSTATION_TIME, 0, 42, 7)


class GlueMode(FwEnum, namespace="Glue"):
    OFF = 0
    ON = 1


class GlueVec(Struct, namespace="Glue"):
    x: F64
    y: F64
    z: F64


class _Writer(PassiveComponent):
    Rate = Channel(F64)  # the "type" check
    Level = Channel(U8)  # the "int" check
    Count = Channel(U32, update="on change")
    Mode = Channel(GlueMode, update="on change")
    Flag = Channel(bool)  # the "none" check: the type's check on every write
    Vec = Channel(GlueVec)  # a snapshot channel


_VALUES = {
    "Rate": [0.5, 1.25, -3.0, 2, "x", None],
    "Level": [0, 7, 255, 256, -1, 3.0, True],
    "Count": [1, 1, 2, 2, 2**40, "2"],
    "Mode": [GlueMode.OFF, GlueMode.ON, GlueMode.ON, 1, 7],
    "Flag": [True, False, 1, "no"],
    "Vec": ["vec", "vec", (1.0, 2.0, 3.0), 5],
}


def _time_key(time: Time) -> tuple[int, int, int]:
    return int(time.time_base), time.context, time.total_us


def _fly(seed: int) -> list:
    """Run the seeded script; return everything observable, in order."""
    rng = random.Random(seed)
    clocks = [SimulatedClock(), SimulatedClock(epoch_us=5_000_000)]
    writer = _Writer("writer", base_id=0x100)
    stores = [TlmChan("tlmA"), TlmChan("tlmB")]
    sources = [TimeSource("timeA", clocks[0]), TimeSource("timeB", clocks[1])]
    packets: list = []
    for i, tlm in enumerate(stores):
        tlm.output_port("PktSend").connect_callable(0, lambda data, context, i=i: packets.append((i, data)), "ground")
    tlm_out, time_port = writer.output_port("tlmOut"), writer.output_port("timeCaller")
    tlm_out.connect(0, stores[0].input_port("TlmRecv"), 0)
    time_port.connect(0, sources[0].input_port("timeGetPort"), 0)
    vec = GlueVec(0.0, 0.0, 0.0)
    seen: list = []
    for _ in range(400):
        op = rng.random()
        if op < 0.70:
            name = rng.choice(list(_VALUES))
            value = rng.choice(_VALUES[name])
            if value == "vec":
                value = vec
            time = T_GIVEN if rng.random() < 0.1 else None
            channel = writer.channels[name]
            try:
                channel.write(value, time) if time is not None else channel.write(value)
                seen.append(("ok", name, repr(channel.last), channel.written))
            except Exception as exc:  # noqa: BLE001 - the error itself is what is compared
                seen.append(("raised", name, type(exc).__name__, str(exc)))
            if value is vec and rng.random() < 0.5:
                vec.x += 1.0  # a snapshot is taken at the write: mutating afterwards changes nothing stored
        elif op < 0.80:
            rng.choice(clocks).advance_us(rng.choice([0, 1, 20_000]))
        elif op < 0.85:
            tlm_out.disconnect(0)
            if rng.random() < 0.8:
                tlm_out.connect(0, rng.choice(stores).input_port("TlmRecv"), 0)
        elif op < 0.90:
            time_port.disconnect(0)
            pick = rng.random()
            if pick < 0.6:
                time_port.connect(0, rng.choice(sources).input_port("timeGetPort"), 0)
            elif pick < 0.8:
                time_port.connect_callable(0, lambda: T_GIVEN, "a fixed time")
        elif op < 0.95:
            stores[rng.randrange(2)].Run(0)
        else:
            clocks[0].epoch_us += 1_000_000  # an RTC set: a new generation of the clock's Time
        seen.append(sorted((i, cid, _time_key(entry[0]), entry[1] if entry[2] is None else entry[2](entry[1]))
                           for i, tlm in enumerate(stores) for cid, entry in tlm._latest.items()))
    for tlm in stores:
        tlm.Run(0)
    seen.append(packets)
    return seen


@pytest.mark.parametrize("seed", range(6))
def test_gen_001_generated_writers_store_send_and_raise_what_the_general_path_does(seed, monkeypatch):
    """GEN-001: the same script, generated writers against the general path only: the same entries
    in each TlmChan's table (time, value bytes), the same packets, the same errors, the same ``last``."""
    generated = _fly(seed)
    monkeypatch.setattr(telemetry.BoundChannel, "_specialise",
                        lambda self: setattr(self, "write", self._write_general))
    assert _fly(seed) == generated


def _connected() -> tuple[_Writer, TlmChan, SimulatedClock]:
    clock = SimulatedClock()
    writer, tlm, source = _Writer("writer", base_id=0x100), TlmChan("tlm"), TimeSource("time", clock)
    writer.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    writer.output_port("timeCaller").connect(0, source.input_port("timeGetPort"), 0)
    return writer, tlm, clock


def test_gen_002_a_channel_connected_to_tlm_chan_writes_through_its_generated_writer():
    """GEN-002: after its first write, every kind of channel above writes through a generated writer
    (the general path is what the writer falls back on, not what runs)."""
    writer, tlm, _ = _connected()
    for name, values in _VALUES.items():
        channel = writer.channels[name]
        value = GlueVec(1.0, 2.0, 3.0) if values[0] == "vec" else values[0]
        channel.write(value)
        assert channel.write.__qualname__ == "make.<locals>.write", name
        assert tlm.TlmGet(channel.id)[1] is channel.component.get_time()


def test_gen_003_a_store_tlm_value_replaced_on_the_instance_sees_every_write():
    """GEN-003: a TlmChan whose ``store_tlm_value`` was replaced on the instance (a tap) is called
    for every deferred write: no writer assigns to its table behind it."""
    writer, tlm, _ = _connected()
    calls = []

    def tap(self, chan_id, time, value, pack):
        calls.append((chan_id, value))
        TlmChan.store_tlm_value(self, chan_id, time, value, pack)

    tlm.store_tlm_value = types.MethodType(tap, tlm)  # type: ignore[method-assign]
    rate = writer.channels["Rate"]
    for value in (0.25, 0.5, 0.75):
        rate.write(value)
    assert calls == [(rate.id, 0.25), (rate.id, 0.5), (rate.id, 0.75)]


def test_gen_004_a_driver_subclass_is_asked_when_its_next_output_fires():
    """GEN-004: the timer reads a plain RateGroupDriver's firing table itself; a subclass's own
    ``ticks_to_next_output`` is still called for every wake-up it plans, and followed."""
    from fprime_lite.deploy.scheduler import Scheduler
    from fprime_lite.svc.rate_group_driver import Divider, RateGroupDriver, RateGroupTimer

    class EveryThirdTick(RateGroupDriver):
        asked = 0

        def ticks_to_next_output(self):
            self.asked += 1
            return (-self.tick) % 3  # fires on ticks 0, 3, 6... whatever the table says

    scheduler, fired = Scheduler(), []
    driver = EveryThirdTick("driver", dividers=[Divider(1)])
    driver.output_port("CycleOut").connect_callable(0, lambda t: fired.append(t.total_us), "sink")
    timer = RateGroupTimer(scheduler, driver, 1000)
    timer.start()
    scheduler.run(until_us=9_000)
    assert fired == [0, 3_000, 6_000, 9_000]
    assert driver.asked == 5  # the start, then after each of the four cycles
