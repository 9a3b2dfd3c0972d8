"""TlmChan: latest value per channel, sent on the Run tick in packets of bounded size."""

import struct

import pytest

from fprime_lite import Time, TimeBase
from fprime_lite.wire.packets import TLM_PACKET_MAX, decode_telemetry
from fprime_lite.svc.tlm_chan import TlmChan, TlmValid

T1 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 10, 0)
T2 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 11, 500)


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(TlmChan("tlmSend"))


def records(h, size=4):
    out = []
    for call in h.from_port("PktSend"):
        out.extend(decode_telemetry(call.args[0], lambda i, d, o: o + size))
    return out


def test_ports():
    t = TlmChan("tlmSend")
    assert t.input_port("Run").decl.kind == "async"
    assert t.input_port("TlmRecv").port_type.name == "Fw.Tlm"
    assert "PktSend" in t.output_ports


def test_latest_value_sent_once_per_tick(h):
    h.invoke("TlmRecv", 0x10, T1, b"\x00\x00\x00\x01")
    h.invoke("TlmRecv", 0x20, T1, b"\x00\x00\x00\x02")
    h.invoke("TlmRecv", 0x10, T2, b"\x00\x00\x00\x03")  # overwrites 0x10's value and time
    assert h.from_port("PktSend") == []                 # nothing before the tick
    h.invoke("Run", 0)
    h.dispatch_all()
    assert len(h.from_port("PktSend")) == 1
    assert records(h) == [(0x10, T2, b"\x00\x00\x00\x03"), (0x20, T1, b"\x00\x00\x00\x02")]
    assert h.from_port("PktSend")[0].args[1] == 0
    # Nothing new: the next tick sends nothing.
    h.invoke("Run", 0)
    h.dispatch_all()
    assert len(h.from_port("PktSend")) == 1
    # Only what changed is sent, in first-write order.
    h.invoke("TlmRecv", 0x20, T2, b"\x00\x00\x00\x04")
    h.invoke("Run", 0)
    h.dispatch_all()
    assert records(h)[-1] == (0x20, T2, b"\x00\x00\x00\x04")
    assert len(h.from_port("PktSend")) == 2


def test_packets_are_split_at_the_size_limit(h):
    record_size = 4 + 11 + 8
    n = 60
    for i in range(n):
        h.invoke("TlmRecv", 0x100 + i, T1, struct.pack(">d", i))
    h.invoke("Run", 0)
    h.dispatch_all()
    packets = [c.args[0] for c in h.from_port("PktSend")]
    per_packet = (TLM_PACKET_MAX - 2) // record_size
    assert [len(p) for p in packets[:-1]] == [2 + per_packet * record_size] * (len(packets) - 1)
    assert all(len(p) <= TLM_PACKET_MAX for p in packets)
    assert len(packets) == -(-n // per_packet)
    got = records(h, size=8)
    assert [r[0] for r in got] == [0x100 + i for i in range(n)]
    assert [struct.unpack(">d", r[2])[0] for r in got] == list(range(n))


def test_oversize_record_sent_alone(h):
    h.invoke("TlmRecv", 1, T1, b"\x01")
    h.invoke("TlmRecv", 2, T1, bytes(600))
    h.invoke("TlmRecv", 3, T1, b"\x03")
    h.invoke("Run", 0)
    h.dispatch_all()
    sizes = [len(c.args[0]) for c in h.from_port("PktSend")]
    assert sizes == [2 + 16, 2 + 15 + 600, 2 + 16]
    assert h.component.oversize_records == 1


def test_an_oversize_record_first_in_a_tick_makes_no_empty_packet(h):
    """The first record of a tick too big for a packet goes alone into the first packet: no packet of a
    descriptor without records before it."""
    h.invoke("TlmRecv", 2, T1, bytes(600))
    h.invoke("TlmRecv", 3, T1, b"\x03")
    h.invoke("Run", 0)
    h.dispatch_all()
    assert [len(c.args[0]) for c in h.from_port("PktSend")] == [2 + 15 + 600, 2 + 16]
    assert h.component.oversize_records == 1


def test_tlm_get(h):
    assert h.invoke("TlmGet", 0x10) == (TlmValid.INVALID, None, None)
    h.invoke("TlmRecv", 0x10, T1, b"\x07")
    assert h.invoke("TlmGet", 0x10) == (TlmValid.VALID, T1, b"\x07")


@pytest.mark.parametrize("time, value", [("nope", b"\x00"), (T1, None), (T1, 5.0)])
def test_bad_writes_are_counted_never_raised(h, time, value):
    h.invoke("TlmRecv", 0x10, time, value)
    h.invoke("Run", 0)
    h.dispatch_all()
    assert h.from_port("PktSend") == []
    assert h.component.rejected_writes == 1


def test_components_write_through_tlm_out():
    """A component's tlmOut wired to TlmRecv: its channel writes reach the packet."""
    from fprime_lite.svc.cmd_dispatcher import CmdDispatcher

    disp = CmdDispatcher("cmdDisp", base_id=0x100)
    tlm = TlmChan("tlmSend")
    disp.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    sent = []
    tlm.output_port("PktSend").connect_callable(0, lambda data, ctx: sent.append(data), "ground")
    disp.input_port("run").entries[0](0)
    disp.dispatch_all()
    tlm.input_port("Run").entries[0](0)
    tlm.dispatch_all()
    recs = decode_telemetry(sent[0], lambda i, d, o: o + 4)
    assert [r[0] for r in recs] == [0x102, 0x101, 0x100]  # CommandsDropped, CommandErrors, CommandsDispatched


def test_ping(h):
    h.invoke("pingIn", 9)
    h.dispatch_all()
    assert h.from_port("pingOut")[0].args == (9,)


def test_a_rewrite_of_the_same_value_is_sent_again(h):
    """Every write counts as an update, as in F´ (a channel written each cycle is downlinked each tick)."""
    for _ in range(2):
        h.invoke("TlmRecv", 0x10, T1, b"\x05")
        h.invoke("Run", 0)
        h.dispatch_all()
    assert records(h, size=1) == [(0x10, T1, b"\x05"), (0x10, T1, b"\x05")]


def test_writers_on_other_threads_lose_nothing_and_never_break_a_tick():
    """TlmRecv takes no lock: writes from several threads during Run ticks must still all land."""
    import threading

    tlm = TlmChan("tlmSend")
    sent = []
    tlm.output_port("PktSend").connect_callable(0, lambda data, ctx: sent.append(data), "ground")
    recv, run = tlm.input_port("TlmRecv").entries[0], tlm.input_port("Run").entries[0]
    n_threads, n_writes = 4, 3000
    start = threading.Barrier(n_threads + 1)

    def writer(k):
        start.wait()
        for i in range(n_writes):
            recv(0x1000 + 100 * k + i % 50, T1, struct.pack(">I", i))  # new channels appear mid-tick too

    threads = [threading.Thread(target=writer, args=(k,)) for k in range(n_threads)]
    for t in threads:
        t.start()
    start.wait()
    while any(t.is_alive() for t in threads):
        run(0)
        tlm.dispatch_all()
    run(0)
    tlm.dispatch_all()
    latest = {}
    for packet in sent:
        for chan_id, _, value in decode_telemetry(packet, lambda i, d, o: o + 4):
            latest[chan_id] = struct.unpack(">I", value)[0]
    expected = {0x1000 + 100 * k + c: max(i for i in range(n_writes) if i % 50 == c)
                for k in range(n_threads) for c in range(50)}
    assert latest == expected  # every channel's last write reached the ground
    assert tlm.rejected_writes == 0


# --- values stored by channel writes and packed at downlink (issue #19) ---------------------------

def _deferred_fixture():
    from fprime_lite import (BOOL, F64, U32, Array, Channel, FwEnum, PassiveComponent, Sched, String, Struct,
                             sync_input)

    class Colour(FwEnum, namespace="Test"):
        RED = 0
        GREEN = 7

    class Vec(Struct, namespace="Test"):
        x: F64
        y: F64
        z: F64

    class Stamped(Struct, namespace="Test"):
        v: F64
        colour: Colour
        at: Time

    class Nested(Struct, namespace="Test"):
        inner: Vec
        n: U32

    class Triple(Array, elem=U32, size=3, namespace="Test"):
        pass

    class Quat(Array, elem=F64, size=4, namespace="Test"):
        pass

    class Writer(PassiveComponent):
        Count = Channel(U32)
        Rate = Channel(F64)
        Paint = Channel(Colour)
        Flag = Channel(BOOL)
        Label = Channel(String(20))
        Vector = Channel(Vec)
        Sample = Channel(Stamped)
        Deep = Channel(Nested)
        Many = Channel(Triple)
        Attitude = Channel(Quat)

        @sync_input(Sched)
        def run(self, context):
            pass

    writer, tlm = Writer("writer", base_id=0x100), TlmChan("tlmSend")
    writer.output_port("tlmOut").connect(0, tlm.input_port("TlmRecv"), 0)
    sent = []
    tlm.output_port("PktSend").connect_callable(0, lambda data, ctx: sent.append(data), "ground")
    return writer, tlm, sent, (Colour, Vec, Stamped, Nested, Triple, Quat)


def test_channel_values_are_packed_at_downlink_into_the_bytes_of_the_write():
    """TLM-DEFER-002: every kind of channel written through a tlmOut wired to TlmRecv is downlinked
    (and read by TlmGet) as the bytes of the value written — a struct changed after its write
    included — and numbers, enums, booleans, strings and structs of those are stored unpacked."""
    writer, tlm, sent, (Colour, Vec, Stamped, Nested, Triple, Quat) = _deferred_fixture()
    at = Time(TimeBase.TB_WORKSTATION_TIME, 0, 3, 250)
    vec, stamped, nested = Vec(1.5, -2.0, 3.25), Stamped(0.5, Colour.GREEN, at), Nested(Vec(1.0, 2.0, 3.0), 9)
    written = {"Count": 7, "Rate": 0.125, "Paint": Colour.GREEN, "Flag": True, "Label": "detumbling",
               "Vector": vec, "Sample": stamped, "Deep": nested, "Many": Triple([1, 2, 3]),
               "Attitude": Quat([1, 0.0, -0.5, 0.25])}
    expected = {}
    for name, value in written.items():
        channel = writer.channels[name]
        expected[channel.id] = channel.decl.type.serialize(value)
        channel.write(value, T1)
    vec.x = 99.0  # the struct objects change after their writes: the downlink keeps what was written
    stamped.colour = Colour.RED
    nested.inner.x = 99.0
    written["Many"][0] = 5
    packers = {writer.channels[n].id: tlm._latest[writer.channels[n].id][2] for n in written}
    assert [n for n in written if packers[writer.channels[n].id] is None] == ["Deep"]
    for chan_id, value in expected.items():
        assert tlm.TlmGet(chan_id) == (TlmValid.VALID, T1, value)
    tlm.input_port("Run").entries[0](0)
    tlm.dispatch_all()
    sizes = {cid: len(v) for cid, v in expected.items()}
    recs = decode_telemetry(sent[0], lambda i, d, o: o + sizes[i])
    assert {chan_id: (time, value) for chan_id, time, value in recs} == {cid: (T1, v) for cid, v in expected.items()}


def test_a_struct_write_checks_its_members_as_before():
    """TLM-DEFER-003: a struct channel's quick path still refuses a member of the wrong kind and
    converts an int given for an F64 member, as the struct's check does."""
    from fprime_lite.model.errors import SerializationError

    writer, tlm, _, (Colour, Vec, Stamped, _n, _t, Quat) = _deferred_fixture()
    with pytest.raises(SerializationError, match="Vec.y"):
        writer.channels["Vector"].write(Vec(1.0, "fast", 3.0), T1)
    with pytest.raises(SerializationError, match="Stamped.at"):
        writer.channels["Sample"].write(Stamped(1.0, Colour.RED, "noon"), T1)
    writer.channels["Vector"].write(Vec(1, 2.0, 3.0), T1)
    assert tlm.TlmGet(writer.channels["Vector"].id)[2] == struct.pack(">ddd", 1.0, 2.0, 3.0)
    assert writer.channels["Vector"].last == Vec(1.0, 2.0, 3.0)
    with pytest.raises(SerializationError, match="Quat element"):
        writer.channels["Attitude"].write([1.0, 0.0, None, 0.0], T1)


def test_a_tap_on_the_tlm_out_slot_still_sees_every_write_as_bytes():
    """TLM-DEFER-004: a callable put in a connected tlmOut slot in front of TlmRecv (a tap, as the
    ground recorder puts on PktSend) receives each write as F´ bytes and TlmChan still stores it."""
    writer, tlm, _, _types = _deferred_fixture()
    slot = writer.output_port("tlmOut").calls
    downstream, seen = slot[0], []
    rate = writer.channels["Rate"]
    rate.write(0.5, T1)  # bound to the store first
    assert tlm._latest[rate.id][2] is not None

    def tap(chan_id, time, value):
        seen.append((chan_id, time, value))
        downstream(chan_id, time, value)

    slot[0] = tap
    rate.write(0.25, T2)
    assert seen == [(rate.id, T2, struct.pack(">d", 0.25))]
    assert tlm.TlmGet(rate.id) == (TlmValid.VALID, T2, struct.pack(">d", 0.25))
