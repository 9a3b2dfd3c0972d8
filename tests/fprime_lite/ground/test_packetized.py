"""The recorder decodes TlmPacketizer packets (src/fprime_lite/ground/packetized.py, docs/outputs.md
"channels.csv"): the layout from the packet set, a channel's value from its slot, updates by the
channel's update policy from its home packet, stamped with the packet's time."""

from __future__ import annotations

import csv
import pathlib
import struct

import pytest

from fprime_lite import Time, TimeBase
from fprime_lite.ground.downlink import channel_text
from fprime_lite.ground.packetized import PacketizedDecoder
from fprime_lite.model.errors import SerializationError
from fprime_lite.model.time import TIME
from fprime_lite.model.types import F32, U8, U32, String

ROOT = pathlib.Path(__file__).resolve().parents[3]
NAME = String(10)
#: id -> (name, F´ type, format template)
CHANNELS = {0x10: ("M.a.Count", U32, None), 0x20: ("M.a.Label", NAME, None), 0x30: ("M.b.Level", U8, None),
            0x40: ("M.b.Temp", F32, "{:.1f} C")}
POLICIES = {"M.a.Count": "always", "M.a.Label": "on change", "M.b.Level": "on change", "M.b.Temp": "always"}
#: packet 5 (group 1): Count, Label, Level; packet 9 (group 3): Label (again), Temp
PACKET_SET = {"name": "P", "omitted": [],
              "members": [{"name": "A", "id": 5, "group": 1, "members": ["M.a.Count", "M.a.Label", "M.b.Level"]},
                          {"name": "B", "id": 9, "group": 3, "members": ["M.a.Label", "M.b.Temp"]}]}


def _packet(packet_id: int, time: Time, *slots: bytes) -> bytes:
    return struct.pack(">HH", 4, packet_id) + TIME.serialize(time) + b"".join(slots)


def _label(text: str) -> bytes:
    """A string's slot: U16 length, the text, zero padding to the bound."""
    return (struct.pack(">H", len(text)) + text.encode()).ljust(2 + 10, b"\0")


def test_slots_decode_by_update_policy_from_the_home_packet():
    """RECPKT-001: each slot is decoded by the packet set's layout (a string in its padded slot, a
    format string applied); an `always` channel is an update at every arrival, an `on change` one
    only when its bytes change (a zeroed slot never written is none); a channel in two packets is
    an update of its home packet only (lowest group); every update has the packet's time."""
    decoder = PacketizedDecoder(PACKET_SET, CHANNELS, POLICIES, channel_text)
    t1, t2, t3 = (Time(TimeBase.TB_WORKSTATION_TIME, 0, s, 250) for s in (10, 11, 12))
    time, updates = decoder.decode(_packet(5, t1, struct.pack(">I", 7), _label("hi"), b"\0"))
    assert time == t1
    assert updates == [("M.a.Count", 7, "7"), ("M.a.Label", "hi", "hi")]  # Level: still the zeroed slot
    _, updates = decoder.decode(_packet(5, t2, struct.pack(">I", 7), _label("hi"), b"\x03"))
    assert updates == [("M.a.Count", 7, "7"), ("M.b.Level", 3, "3")]  # Label unchanged: no update
    time, updates = decoder.decode(_packet(9, t3, _label("other"), struct.pack(">f", 21.5)))
    assert time == t3 and updates == [("M.b.Temp", 21.5, "21.5 C")]  # Label's home is packet 5


def test_a_packet_that_does_not_fit_its_layout_is_refused():
    """RECPKT-002: a packet of another length than its layout, an id not in the set, or a time stamp
    with useconds >= 10^6 raises SerializationError (the recorder counts it undecodable)."""
    decoder = PacketizedDecoder(PACKET_SET, CHANNELS, POLICIES, channel_text)
    good = _packet(5, Time(TimeBase.TB_WORKSTATION_TIME, 0, 1, 0), bytes(4), _label(""), b"\0")
    decoder.decode(good)
    with pytest.raises(SerializationError, match="bytes, its layout"):
        decoder.decode(good + b"\0")
    with pytest.raises(SerializationError, match="packet id 6 is not in the packet set"):
        decoder.decode(good[:2] + struct.pack(">H", 6) + good[4:])
    bad_time = good[:4] + TIME.serialize(Time(TimeBase.TB_WORKSTATION_TIME, 0, 1, 0))[:-4] + struct.pack(">I", 10**6)
    with pytest.raises(SerializationError, match="useconds"):
        decoder.decode(bad_time + good[4 + TIME.size:])


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _channels(path: pathlib.Path) -> dict[str, list[tuple[str, str]]]:
    out: dict[str, list[tuple[str, str]]] = {}
    with path.open(newline="") as f:
        for row in csv.DictReader(f):
            out.setdefault(row["channel"], []).append((row["time"], row["value"]))
    return out


@pytest.mark.slow  # two 10 s flights of proves_ref
def test_the_packetized_proves_ref_records_the_tlmchan_deployments_channels(tmp_path):
    """RECPKT-003: `run` of topology_packetized.yaml writes, for the channels of the packets that come
    down (send level 1), the values the TlmChan deployment's channels.csv has, each with the time
    stamp of a packet that came down; the differences are those docs/outputs.md names: the rate
    groups' wall-clock RgMaxTime, and an `always` channel whose home packet goes down before it is
    first written (the zeroed slot: 0)."""
    from fprime_lite.tools.api import load
    from fprime_lite.tools.runner import run_deployment

    packetized = load(str(ROOT / "deployments/proves_ref/topology_packetized.yaml"))
    port = packetized.topology.instance("CdhCore.tlmSend").component.output_port("PktSend")
    packet_times = set()
    downstream = port.calls[0] if port.is_connected(0) else None

    def tap(data, context=0):
        time = TIME.deserialize(data, 4)[0]
        packet_times.add(f"{time.seconds}.{time.useconds:06d}")
        return downstream(data, context) if downstream is not None else None
    if downstream is not None:
        port.calls[0] = tap
    else:
        port.connect_callable(0, tap, "test")
    run_deployment(packetized, tmp_path / "packetized", duration_s=10.0, plots=False, quiet=True)
    run_deployment(load(str(ROOT / "deployments/proves_ref/topology.yaml")), tmp_path / "tlmchan", duration_s=10.0,
                   plots=False, quiet=True)
    ours, theirs = _channels(tmp_path / "packetized" / "channels.csv"), _channels(tmp_path / "tlmchan" / "channels.csv")
    (packet_set,) = packetized.topology.telemetry_packet_sets
    sent = {n for p in packet_set["members"] if p["group"] <= 1 for n in p["members"]}
    assert set(ours) <= sent and {t for rows in ours.values() for t, _ in rows} <= packet_times
    values = {name: [v for _, v in rows] for name, rows in ours.items()}
    expected = {name: [v for _, v in rows] for name, rows in theirs.items()}
    compared = sorted(n for n in sent if not n.endswith(".RgMaxTime"))
    same = [n for n in compared if values.get(n) == expected.get(n)]
    assert len(same) >= 10 and any(len(values.get(n, [])) >= 10 for n in same)
    zeroed = {n: values[n] for n in compared if n not in same}
    # written after its packet first went down / never written: the zeroed slot, then TlmChan's values
    assert set(zeroed) == {"ReferenceDeployment.detumbleManager.AngularVelocityMagnitude",
                           "ComCcsdsUart.tcSecurityDeframer.CurrentSequenceNumber"}
    for name, got in zeroed.items():
        lead = len(got) - len(expected.get(name, []))
        assert lead >= 1 and got[lead:] == expected.get(name, []) and {float(v) for v in got[:lead]} == {0.0}
    # channels_wide.csv holds each channel's latest value: at the end, the last one channels.csv has
    with (tmp_path / "packetized" / "channels_wide.csv").open(newline="") as f:
        header, *rows = list(csv.reader(f))
    unformatted = {f"{i.qualified_name}.{c.name}" for i in packetized.topology.instances.values()
                   for c in i.component.spec.channels if c.format is None}
    checked = 0
    for name in same:
        columns = [k for k, h in enumerate(header) if h == name or h.startswith(name + " [")]
        if name in values and name in unformatted and len(columns) == 1 and _is_number(values[name][-1]):
            assert rows[-1][columns[0]] == values[name][-1], name
            checked += 1
    assert checked >= 5
