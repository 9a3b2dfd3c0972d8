"""Ground-side decoding and the recorder's tap on the downlink."""


from fprime_lite import F64, U32, Channel, Event, FwEnum, PassiveComponent, Severity, Time, TimeBase
from fprime_lite.model.fw_ports import Com
from fprime_lite.ground.downlink import GroundRecorder, format_time
from fprime_lite.wire.packets import encode_event, encode_telemetry
from fprime_lite.model.ports import sync_input
from fprime_lite.deploy.topology import Topology
from fprime_lite.model.types import U8


class Phase(FwEnum, namespace="T", rep=U8):
    IDLE = 0
    BUSY = 1


class Thing(PassiveComponent):
    Hot = Event(Severity.WARNING_LO, "hot at {.1f}", t=F64)
    Count = Channel(U32)
    Stage = Channel(Phase)
    Temp = Channel(F64, format="{.2f}")


class Downlink(PassiveComponent):
    """Stands in for an event manager / channelizer: has a PktSend, and a link to send to."""

    from fprime_lite.model.ports import OutputPort
    PktSend = OutputPort(Com)


class Link(PassiveComponent):
    def __init__(self, name):
        super().__init__(name)
        self.sent = []

    @sync_input(Com)
    def comIn(self, data, context):
        self.sent.append(data)


T0 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 1_748_736_000, 250_000)  # 2025-06-01T00:00:00.25Z


def make(tmp_path, link=False):
    topo = Topology("Demo")
    topo.add("Demo", Thing("thing", base_id=0x100))
    topo.add("Demo", Downlink("events"))
    topo.add("Demo", Downlink("tlm"))
    link_comp = None
    if link:
        link_comp = Link("link")
        topo.add("Demo", link_comp)
        topo.connect("Demo.events", "PktSend", 0, "Demo.link", "comIn", 0)
    rec = GroundRecorder(topo, tmp_path)
    rec.attach(topo, "Demo.events", "Demo.tlm")
    return topo, rec, link_comp


def test_events_and_channels_are_decoded_to_the_logs(tmp_path):
    topo, rec, _ = make(tmp_path)
    thing = topo.instance("Demo.thing").component
    events = topo.instance("Demo.events").component
    tlm = topo.instance("Demo.tlm").component
    events.PktSend[0](encode_event(thing.event_id("Hot"), T0, F64.serialize(81.25)), 0)
    tlm.PktSend[0](encode_telemetry([(thing.channel_id("Count"), T0, U32.serialize(7)),
                                     (thing.channel_id("Stage"), T0, U8.serialize(1)),
                                     (thing.channel_id("Temp"), T0, F64.serialize(3.14159))]), 0)
    rec.close()
    assert (tmp_path / "events.log").read_text() == \
        "2025-06-01T00:00:00.250000Z Demo.thing.Hot WARNING_LO hot at 81.2\n"
    assert (tmp_path / "channels.csv").read_text().splitlines() == [
        "time,channel,value", "1748736000.250000,Demo.thing.Count,7", "1748736000.250000,Demo.thing.Stage,BUSY",
        "1748736000.250000,Demo.thing.Temp,3.14"]
    assert rec.events_by_severity == {"WARNING_LO": 1}


def test_undecodable_packets_are_counted_not_raised(tmp_path):
    topo, rec, _ = make(tmp_path)
    events = topo.instance("Demo.events").component
    events.PktSend[0](b"\x00\x02\x00\x00\x09\x99" + bytes(11), 0)  # unknown event id
    events.PktSend[0](b"\x00\x07", 0)  # unknown descriptor
    rec.close()
    assert rec.undecodable == 2


def test_recorder_taps_a_connected_downlink_without_taking_it_over(tmp_path):
    topo, rec, link = make(tmp_path, link=True)
    thing = topo.instance("Demo.thing").component
    packet = encode_event(thing.event_id("Hot"), T0, F64.serialize(1.0))
    topo.instance("Demo.events").component.PktSend[0](packet, 0)
    rec.close()
    assert link.sent == [packet]
    assert rec.events_by_name == {"Demo.thing.Hot": 1}
    assert topo.instance("Demo.events").component.output_port("PktSend").target_name(0) == \
        "ground recorder, then link.comIn[0]"


def test_format_time_for_other_bases():
    assert format_time(Time(TimeBase.TB_PROC_TIME, 0, 12, 5)) == "12.000005"
