"""TlmPacketizer (TPK-*): F´'s packet layout, send level, SEND_PKT, NoChan, TlmGet; the topology's
``telemetry_packets``; the stock fprime-gds decoding the packets through the dictionary."""

import json
import pathlib
import struct

import pytest

from fprime_lite import Time, TimeBase
from fprime_lite.deploy.topology import TopologyError
from fprime_lite.model.commands import CmdResponse
from fprime_lite.model.types import U8, U32, F64, String
from fprime_lite.svc.tlm_chan import TlmValid
from fprime_lite.svc.tlm_packetizer import PacketSpec, TlmPacketizer, max_serialized_size
from fprime_lite.model.time import TIME

ROOT = pathlib.Path(__file__).resolve().parents[3]
T1 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 10, 0)
T2 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 11, 500)
#: packet 5 (group 1) holds channels 0x10 (U32) and 0x20 (a 10-byte string); packet 9 (group 3) 0x20
PACKETS = [PacketSpec("A", 5, 1, ((0x10, 4), (0x20, 12))), PacketSpec("B", 9, 3, ((0x20, 12),))]


@pytest.fixture
def h(fprime_harness):
    t = TlmPacketizer("tlmSend", base_id=0x6000)
    t.set_packet_list(PACKETS, omitted=[0x30], start_level=1)
    return fprime_harness(t)


def sent(h):
    return [call.args[0] for call in h.from_port("PktSend")]


def tick(h):
    h.invoke("Run", 0)
    h.dispatch_all()


def test_packet_layout_is_f_primes(h):
    """TPK-001: U16 descriptor 4 | U16 id | Time | each channel's bytes in its fixed slot."""
    h.invoke("TlmRecv", 0x10, T1, struct.pack(">I", 7))
    h.invoke("TlmRecv", 0x20, T2, b"\x00\x02hi")
    tick(h)
    (packet,) = sent(h)  # only group 1 <= start level 1
    assert packet[:4] == struct.pack(">HH", 4, 5)
    assert packet[4:4 + TIME.size] == TIME.serialize(T2)  # the latest write's time
    assert packet[15:19] == struct.pack(">I", 7)
    assert packet[19:23] == b"\x00\x02hi" and len(packet) == 4 + 11 + 4 + 12


def test_sent_on_change_only(h):
    """TPK-002: a packet goes once per tick after a write to one of its channels, not again."""
    h.invoke("TlmRecv", 0x10, T1, struct.pack(">I", 1))
    tick(h)
    tick(h)
    assert len(sent(h)) == 1
    h.invoke("TlmRecv", 0x10, T2, struct.pack(">I", 2))
    tick(h)
    assert len(sent(h)) == 2 and sent(h)[1][15:19] == struct.pack(">I", 2)


def test_set_level_and_max_level(h):
    """TPK-003: SET_LEVEL lets higher groups down; above the largest group it warns (still OK)."""
    h.invoke("TlmRecv", 0x20, T1, b"\x00\x01x")
    h.send_command("SET_LEVEL", 3)
    h.send_command("SET_LEVEL", 4)
    h.dispatch_all()
    assert [r.response for r in h.cmd_responses] == [CmdResponse.OK, CmdResponse.OK]
    h.assert_event("LevelSet", 0, 3)
    h.assert_event_count("MaxLevelExceed", 1)
    h.assert_event("MaxLevelExceed", 0, 4, 3)
    assert h.tlm_values("SendLevel") == [3, 4]
    tick(h)
    assert sorted(struct.unpack(">H", p[2:4])[0] for p in sent(h)) == [5, 9]


def test_send_pkt(h):
    """TPK-004: SEND_PKT sends a packet of a group above the level once; an unknown id is refused."""
    h.send_command("SEND_PKT", 9)
    h.send_command("SEND_PKT", 77)
    h.dispatch_all()
    assert [r.response for r in h.cmd_responses] == [CmdResponse.OK, CmdResponse.VALIDATION_ERROR]
    h.assert_event("PacketSent", 0, 9)
    h.assert_event("PacketNotFound", 0, 77)
    tick(h)
    tick(h)
    assert [struct.unpack(">H", p[2:4])[0] for p in sent(h)] == [9]


def test_no_chan_once_and_omitted_silent(h):
    """TPK-005: a channel in no packet warns NoChan once; an omitted one is dropped silently."""
    for _ in range(3):
        h.invoke("TlmRecv", 0x40, T1, b"\x01")
        h.invoke("TlmRecv", 0x30, T1, b"\x01")
    h.assert_event_count("NoChan", 1)
    h.assert_event("NoChan", 0, 0x40)


def test_tlm_get_and_oversize_write(h):
    """TPK-006: TlmGet reads a written slot back (its full width); a write larger than its slot is
    refused and counted, never raised."""
    assert h.invoke("TlmGet", 0x10) == (TlmValid.INVALID, None, None)
    h.invoke("TlmRecv", 0x10, T1, struct.pack(">I", 9))
    assert h.invoke("TlmGet", 0x10) == (TlmValid.VALID, T1, struct.pack(">I", 9))
    h.invoke("TlmRecv", 0x10, T2, b"\x00" * 5)
    assert h.component.rejected_writes == 1
    assert h.invoke("TlmGet", 0x10) == (TlmValid.VALID, T1, struct.pack(">I", 9))


def test_max_serialized_size():
    """TPK-007: slot widths: numbers their size, strings U16 length plus bound."""
    assert [max_serialized_size(t) for t in (U8, U32, F64, String(40))] == [1, 4, 8, 42]


def test_packet_too_large_refused():
    """TPK-008: a packet larger than a Com buffer is refused at set-up, naming it."""
    t = TlmPacketizer(packet_max=20)
    with pytest.raises(ValueError, match="packet A .* split it"):
        t.set_packet_list(PACKETS[:1], [], 1)


_TOPOLOGY = """
deployment: Dep
extends: {base}
modules:
  CdhCore:
    instances:
      tlmSend: {{type: fprime_lite.svc.tlm_packetizer.TlmPacketizer, base_id: 0x01006000, queue_size: 10}}
telemetry_packets:
{packets}
"""


def _load(tmp_path, packets):
    from fprime_lite.deploy.topology_loader import load_topology

    path = tmp_path / "t.yaml"
    path.write_text(_TOPOLOGY.format(base=ROOT / "deployments/proves_ref/topology.yaml", packets=packets))
    return load_topology(path)


def test_yaml_packets_checked(tmp_path):
    """TPK-009: the topology's packet set is checked: unknown channels (with a suggestion), channels
    in no packet and not omitted, repeated ids, a non-packetizer instance."""
    with pytest.raises(TopologyError) as err:
        _load(tmp_path, """  name: P
  instance: CdhCore.tlmSend
  packets:
    A: {id: 1, group: 1, channels: [CdhCore.cmdDisp.CommandsDispatchd]}
    B: {id: 1, group: 1, channels: []}
  omit: []""")
    text = str(err.value)
    assert "no channel 'CdhCore.cmdDisp.CommandsDispatchd'" in text and "CommandsDispatched" in text
    assert "id 1 is already another packet's" in text
    assert "in no packet and not omitted: CdhCore.cmdDisp.CommandsDispatched," in text  # every problem at once
    with pytest.raises(TopologyError, match="in no packet and not omitted: .* and .* more"):
        _load(tmp_path, "  name: P\n  instance: CdhCore.tlmSend\n  packets: {}\n  omit: []")
    with pytest.raises(TopologyError, match="CdhCore.cmdDisp is a CmdDispatcher, which does not packetize"):
        _load(tmp_path, "  name: P\n  instance: CdhCore.cmdDisp\n  packets: {}\n  omit: rest")


def test_proves_ref_packetized_decoded_by_stock_gds():
    """TPK-010: proves_ref with PROVES's packets: the dictionary lists the set as fpp-to-dict does,
    and the stock fprime-gds decodes a short run's packets to the values the channels hold."""
    pytest.importorskip("fprime_gds")
    from fprime_gds.common.decoders.pkt_decoder import PktDecoder
    from fprime_gds.common.models.dictionaries import Dictionaries

    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.dictionary import build_dictionary
    from fprime_lite.deploy.topology_loader import load_topology

    loaded = load_topology(ROOT / "deployments/proves_ref/topology_packetized.yaml")
    dictionary = build_dictionary(loaded.topology)
    (packet_set,) = dictionary["telemetryPacketSets"]
    assert packet_set["name"] == "ReferenceDeploymentPackets"
    health = next(p for p in packet_set["members"] if p["name"] == "Health")
    assert health["id"] == 2 and "CdhCore.cmdDisp.CommandsDispatched" in health["members"]
    assert "CdhCore.version.FrameworkVersion" in packet_set["omitted"]
    dicts = Dictionaries()
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "dict.json"
        path.write_text(json.dumps(dictionary))
        dicts.load_dictionaries(str(path), None, None)
    decoder = PktDecoder(dicts.packet, dicts.channel_id)
    tlm_send = loaded.topology.instance("CdhCore.tlmSend").component
    packets = []
    tlm_send.output_port("PktSend").connect_callable(0, lambda data, context=0: packets.append(bytes(data)), "test")
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(2.0)
    group_1 = {p["id"] for p in packet_set["members"] if p["group"] <= 1}
    assert group_1 == {1, 2, 3}  # Beacon, Health, HealthWarnings
    sent_ids = {struct.unpack(">H", p[2:4])[0] for p in packets}
    assert {1, 2} <= sent_ids <= group_1  # HealthWarnings only once one of its channels is written
    decoded = {}
    for packet in packets:
        assert struct.unpack(">H", packet[:2])[0] == 4
        for channel in decoder.decode_api(packet[2:]):
            decoded[channel.template.get_full_name()] = bytes(channel.get_val_obj().serialize())
    channels = {f"{i.qualified_name}.{c.name}": i.component.base_id + c.local_id
                for i in loaded.topology.instances.values() for c in i.component.spec.channels}
    assert set(decoded) == {n for p in packet_set["members"] if p["id"] in sent_ids for n in p["members"]}
    assert int.from_bytes(decoded["ReferenceDeployment.startupManager.BootCount"], "big") == 1
    for name, value in decoded.items():  # the GDS's value, serialized again, is what the slot holds
        valid, _, raw = tlm_send.TlmGet(channels[name])
        assert valid == TlmValid.VALID and raw.startswith(value), name
