"""The recorder's compiled packet layouts write what the general decoder writes, byte for byte (issue 32).

A recorder with a clock and no ``on_channel`` callback records telemetry through
:class:`~fprime_lite.ground.packet_layout.TelemetryLayout`; one with a callback decodes channel by
channel. Both get the same packets, with the values that differ between the two ways of writing if
anything does (NaN and infinities in plain floats and in structs written as JSON, -0.0, tiny and
huge numbers, enums, bools, strings with commas and quotes, formatted channels, arrays, a bad enum
value, a time stamp with useconds ≥ 10⁶, a struct with a time stamp member in three time bases, arrays
of one and three numbers, formatted numbers written with a %-conversion and one left to its template),
and
must leave identical files and counts (LAYOUT-001). The layouts' caches of number texts keep ints apart
from floats and 0.0 apart from -0.0 (LAYOUT-002).
"""

import math

import pytest

from fprime_lite import (BOOL, F32, F64, I16, U32, U64, Array, Channel, FwEnum, PassiveComponent, String, Struct,
                         Time, TimeBase)
from fprime_lite.deploy.topology import Topology
from fprime_lite.ground.downlink import GroundRecorder
from fprime_lite.ground.packet_layout import TelemetryLayout, fixed_size
from fprime_lite.model.fw_ports import Com
from fprime_lite.model.ports import OutputPort
from fprime_lite.model.types import U8
from fprime_lite.wire.packets import encode_telemetry


class Mode(FwEnum, namespace="T", rep=U8):
    OFF = 0
    ON = 1


class Vec(Struct, namespace="T"):
    x: F64
    y: F32
    n: I16


class Status(Struct, namespace="T"):
    mode: Mode
    flag: BOOL
    level: F64


class Stamped(Struct, namespace="T"):
    x: F64
    at: Time
    n: U32


class Triple(Array, namespace="T", elem=F64, size=3):
    pass


class Single(Array, namespace="T", elem=I16, size=1):
    pass


class Thing(PassiveComponent):
    Count = Channel(U32)
    Big = Channel(U64)
    Rate = Channel(F64)
    Small = Channel(F32)
    Stage = Channel(Mode)
    Armed = Channel(BOOL)
    Field = Channel(Vec)
    State = Channel(Status)
    Axis = Channel(Triple)
    Temp = Channel(F64, format="{.2f}")
    Stamp = Channel(Stamped)
    One = Channel(Single)
    Volts = Channel(F64, format="{.1f} V")
    Ticks = Channel(U32, format="{} us")
    Hex = Channel(U32, format="{x}")
    Label = Channel(String(20))


class Downlink(PassiveComponent):
    PktSend = OutputPort(Com)


class Clock:
    """Reception times the test sets."""

    def __init__(self):
        self.t = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1_000, 0)

    def now(self):
        return self.t


def _recorder(folder, slow: bool):
    topo = Topology("Demo")
    topo.add("Demo", Thing("thing", base_id=0x100))
    topo.add("Demo", Downlink("tlm"))
    clock = Clock()
    rec = GroundRecorder(topo, folder, clock=clock, on_channel=(lambda _c: None) if slow else None)
    rec.attach(topo, None, "Demo.tlm")
    return topo, rec, clock


def _record(thing, name, t, value):
    return thing.channel_id(name), t, _TYPES[name].serialize(value)


_TYPES = {"Count": U32, "Big": U64, "Rate": F64, "Small": F32, "Stage": Mode.__fprime_type__,
          "Armed": BOOL, "Field": Vec.__fprime_type__, "State": Status.__fprime_type__,
          "Axis": Triple.__fprime_type__, "Temp": F64,
          "Stamp": Stamped.__fprime_type__, "One": Single.__fprime_type__,
          "Volts": F64, "Ticks": U32, "Hex": U32, "Label": String(20)}

_FLOATS = [0.1, 0.0, -0.0, 2.0, 1e-300, 1.7976931348623157e308, math.nan, math.inf, -math.inf, 2.5e-7, 123456789.125]


def _packets(thing):
    """Packets of a few recurring layouts with changing values (and two that no decoder accepts)."""
    packets = []
    for k, f in enumerate(_FLOATS * 2):
        t = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1_000 + k, 999_999 if k % 3 else 0)
        fixed = [("Count", k), ("Big", 2**64 - 1 - k), ("Rate", f), ("Small", 0.1 * k),
                 ("Stage", Mode(k % 2)), ("Armed", bool(k % 2)),
                 ("Field", Vec(x=f, y=1.5, n=-k)), ("State", Status(mode=Mode.ON, flag=k % 2 == 0, level=f)),
                 ("Axis", Triple([f, 1.0, -2.0])), ("Temp", 20.0 + k / 7),
                 ("Stamp", Stamped(x=f, at=Time((TimeBase.TB_WORKSTATION_TIME, TimeBase.TB_PROC_TIME,
                                                 TimeBase.TB_NONE)[k % 3], 0, 86_399 * k, 999_999 - k), n=k)),
                 ("One", Single([-k])), ("Volts", f), ("Ticks", 1000 * k), ("Hex", 255 + k)]
        packets.append(encode_telemetry([_record(thing, n, t, v) for n, v in fixed]))
        packets.append(encode_telemetry([_record(thing, n, t, v) for n, v in fixed[:4]]))
        packets.append(encode_telemetry([_record(thing, "Count", t, k),  # the array the only JSON of its packet
                                         _record(thing, "Axis", t, Triple([1.0, f, 2.0]))]))
        if k % 4 == 0:  # a string value: no fixed layout
            packets.append(encode_telemetry([_record(thing, "Label", t, f'a "b", c {k}'),
                                             _record(thing, "Rate", t, f)]))
    first = packets[0]
    stage_at = first.index(U32.serialize(thing.channel_id("Stage"))) + 4 + 11
    packets.append(first[:stage_at] + bytes([7]) + first[stage_at + 1:])  # Stage = 7: no such constant
    usec_at = 2 + 4 + 7
    packets.append(first[:usec_at] + U32.serialize(1_000_000) + first[usec_at + 4:])  # useconds ≥ 10⁶
    stamp_at = first.index(U32.serialize(thing.channel_id("Stamp"))) + 4 + 11 + 8 + 7
    packets.append(first[:stamp_at] + U32.serialize(1_000_000) + first[stamp_at + 4:])  # a member's useconds
    packets.append(packets[1])  # the layout again after the bad ones
    return packets


def _fly(folder, slow: bool):
    topo, rec, clock = _recorder(folder, slow)
    thing = topo.instance("Demo.thing").component
    tlm = topo.instance("Demo.tlm").component
    for i, packet in enumerate(_packets(thing)):
        clock.t = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1_000 + i // 3, 0)  # a few packets per reception
        tlm.PktSend[0](packet, 0)
    rec.close()
    return rec


def test_compiled_layouts_write_what_the_general_decoder_writes(tmp_path):
    """LAYOUT-001."""
    fast = _fly(tmp_path / "fast", slow=False)
    slow = _fly(tmp_path / "slow", slow=True)
    assert fast._layouts._layouts, "the compiled layouts were not used"
    assert slow.channel_updates > 0 and not slow._layouts._layouts
    for name in ("channels.csv", "channels_wide.csv"):
        assert (tmp_path / "fast" / name).read_bytes() == (tmp_path / "slow" / name).read_bytes(), name
    assert (fast.channel_updates, fast.undecodable) == (slow.channel_updates, slow.undecodable)
    assert slow.undecodable == 3
    lines = (tmp_path / "fast" / "channels.csv").read_text().splitlines()
    assert "1000.000000,Demo.thing.Field,\"{\"\"x\"\": 0.1, \"\"y\"\": 1.5, \"\"n\"\": 0}\"" in lines
    assert "1002.999999,Demo.thing.Field,\"{\"\"x\"\": -0.0, \"\"y\"\": 1.5, \"\"n\"\": -2}\"" in lines
    assert "1006.000000,Demo.thing.Field,\"{\"\"x\"\": NaN, \"\"y\"\": 1.5, \"\"n\"\": -6}\"" in lines
    assert "1006.000000,Demo.thing.Rate,nan" in lines
    compiled = {name for layouts in fast._layouts._layouts.values() for layout in layouts for name, _ in layout.simple}
    assert {"Demo.thing.Volts", "Demo.thing.Ticks"} <= compiled and "Demo.thing.Hex" not in compiled
    assert "1003.000000,Demo.thing.Volts,2.0 V" in lines and "1006.000000,Demo.thing.Volts,nan V" in lines
    assert "1003.000000,Demo.thing.Ticks,3000 us" in lines and "1003.000000,Demo.thing.Hex,102" in lines
    assert "1003.000000,Demo.thing.Axis,\"[2.0, 1.0, -2.0]\"" in lines and "1003.000000,Demo.thing.One,[-3]" in lines
    assert ("1003.000000,Demo.thing.Stamp,\"{\"\"x\"\": 2.0, \"\"at\"\": \"\"1970-01-03T23:59:57.999996Z\"\", "
            "\"\"n\"\": 3}\"") in lines
    assert ("1004.999999,Demo.thing.Stamp,\"{\"\"x\"\": 1e-300, \"\"at\"\": \"\"345596.999995\"\", "
            "\"\"n\"\": 4}\"") in lines


def test_number_texts_keep_ints_floats_and_zeros_apart():
    """LAYOUT-002: one layout meets 2 as an int and 2.0 as a float, 0.0 and then -0.0 in one slot."""
    thing = Thing("thing", base_id=0x100)
    t = Time(TimeBase.TB_WORKSTATION_TIME, 0, 5, 0)
    channels = [(thing.channel_id("Count"), "Count", U32, None), (thing.channel_id("Rate"), "Rate", F64, None)]
    layout = TelemetryLayout(channels, lambda v, _t: str(v))
    texts = []
    for count, rate in [(2, 0.0), (2, 2.0), (7, -0.0), (0, 0.0), (3, -0.0), (2, 7.0)]:
        decoded = layout.decode(encode_telemetry([_record(thing, "Count", t, count), _record(thing, "Rate", t, rate)]))
        assert decoded is not None
        texts.append(decoded[0].replace("5.000000,", "").splitlines())
    assert texts == [["Count,2", "Rate,0.0"], ["Count,2", "Rate,2.0"], ["Count,7", "Rate,-0.0"],
                     ["Count,0", "Rate,0.0"], ["Count,3", "Rate,-0.0"], ["Count,2", "Rate,7.0"]]


def test_a_layout_refuses_a_packet_of_other_channels():
    thing = Thing("thing", base_id=0x100)
    t = Time(TimeBase.TB_WORKSTATION_TIME, 0, 5, 0)
    channels = [(thing.channel_id("Count"), "Count", U32, None), (thing.channel_id("Rate"), "Rate", F64, None)]
    layout = TelemetryLayout(channels, lambda v, _t: str(v))
    same = encode_telemetry([_record(thing, "Count", t, 1), _record(thing, "Rate", t, 2.0)])
    other = encode_telemetry([_record(thing, "Count", t, 1), _record(thing, "Big", t, 2)])  # as long, other id
    assert layout.decode(same) is not None
    assert len(other) == len(same) and layout.decode(other) is None
    late = same[:13] + U32.serialize(1_000_000) + same[17:]  # the first record's useconds
    assert layout.decode(late) is None


@pytest.mark.parametrize("ftype, size", [(U32, 4), (Vec.__fprime_type__, 14), (Status.__fprime_type__, 10),
                                         (Triple.__fprime_type__, 24), (String(20), None)])
def test_fixed_size(ftype, size):
    assert fixed_size(ftype) == size


@pytest.mark.parametrize("value", [0.1, -0.0, 1e-300, 1.7976931348623157e308, math.nan, math.inf, -math.inf, 0, -7,
                                   2**64 - 1, "", "ON", 'a "b", c', "line\nbreak", "cr\rx", "comma,"])
def test_csv_cell_is_what_csv_writes(value):
    import csv
    import io
    from fprime_lite.ground.wide_table import csv_cell
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([value, ""])
    assert csv_cell(value) == buffer.getvalue()[:-2]
