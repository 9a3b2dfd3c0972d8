"""GroundLink: wiring, uplink/downlink through a real TCP connection, drops, reconnects, fuzz.

The "ground" here is a TCP server the test opens on 127.0.0.1 (ephemeral port); it frames and
deframes with fprime-gds 4.4.1's own framers. Waits are bounded polls of real sockets.
"""

import pathlib
import socket
import struct
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fprime_lite import SimulatedClock
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.ground.downlink import GroundDecoder
from fprime_lite.wire.packets import encode_command
from fprime_lite.svc.cmd_dispatcher import CmdDispatcher
from fprime_lite.svc.event_manager import EventManager
from fprime_lite.svc.ground_link import (
    GroundLink,
    LinkState,
    parse_address,
)
from fprime_lite.deploy.com_stack import add_ground_link
from fprime_lite.svc.rate_groups import PassiveRateGroup
from fprime_lite.svc.time_source import TimeSource
from fprime_lite.svc.tlm_chan import TlmChan
from fprime_lite.model.time import Time
from fprime_lite.deploy.topology import Topology, TopologyError
from fprime_lite.deploy.topology_loader import load_topology

pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency: pip install -e .[test]")

ROOT = pathlib.Path(__file__).parents[3]
TOPOLOGY = ROOT / "deployments" / "proves_ref" / "topology.yaml"
DATA = ROOT / "tests" / "data" / "gds"
KEEPALIVE = b"sitting well"
TIMEOUT_S = 10.0
NO_OP = 0x01000100


@pytest.fixture(scope="module")
def gds_framers():
    from fprime_gds.common.communication.ccsds.chain import SpacePacketSpaceDataLinkFramerDeframer
    from fprime_gds.common.communication.framing import FpFramerDeframer
    from fprime_gds.common.models.dictionaries import Dictionaries

    Dictionaries.load_dictionaries_into_config(str(DATA / "minimal_dictionary.json"))
    return {"fprime": lambda: FpFramerDeframer("crc32"),
            "ccsds": lambda: SpacePacketSpaceDataLinkFramerDeframer(scid=None, vcid=1, frame_size=None)}


class Ground:
    """A stand-in GDS: a TCP server on loopback that frames and deframes like fprime-gds."""

    def __init__(self, framer, listen: bool = True):
        self.framer = framer
        self.server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.server.bind(("127.0.0.1", 0))
        self.port = self.server.getsockname()[1]
        self.conn = None
        self.pending = b""
        self.received: list[bytes] = []
        if listen:
            self.listen()

    def listen(self):
        self.server.listen(1)
        self.server.settimeout(TIMEOUT_S)

    def accept(self):
        self.conn, _ = self.server.accept()
        self.conn.settimeout(0.05)
        self.pending = b""

    def send(self, data: bytes):
        self.conn.sendall(data)

    def command(self, opcode: int, args: bytes = b"") -> bytes:
        return self.framer.frame(encode_command(opcode, args))

    def poll(self):
        try:
            data = self.conn.recv(65536)
        except socket.timeout:
            return
        self.pending += data
        packets, self.pending, _ = self.framer.deframe_all(self.pending, no_copy=False)
        self.received += packets

    def close(self):
        for s in (self.conn, self.server):
            if s is not None:
                s.close()


@pytest.fixture
def grounds(gds_framers):
    made = []

    def make(framing: str, listen: bool = True) -> Ground:
        g = Ground(gds_framers[framing](), listen)
        made.append(g)
        return g

    yield make
    for g in made:
        g.close()


@pytest.fixture
def links():
    made = []

    def make(*args, **kwargs) -> GroundLink:
        link = GroundLink(*args, **kwargs)
        made.append(link)
        return link

    yield make
    for link in made:
        link.close()


def wait_for(condition, step=lambda: None, timeout=TIMEOUT_S):
    """Poll ``condition`` (running ``step`` between polls) until true; fail after ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        step()
        if condition():
            return
        time.sleep(0.005)
    raise AssertionError(f"condition not met within {timeout} s")


# --- addresses and wiring -----------------------------------------------------------------------

def test_parse_address():
    assert parse_address(None) == ("127.0.0.1", 50000)
    assert parse_address("127.0.0.1:50123") == ("127.0.0.1", 50123)
    assert parse_address("50001") == ("127.0.0.1", 50001)
    assert parse_address("gds.local") == ("gds.local", 50000)
    for bad in ("127.0.0.1:x", "127.0.0.1:0", "h:70000"):
        with pytest.raises(ValueError):
            parse_address(bad)


def test_wildcard_address_means_loopback(links):
    assert links(host="0.0.0.0").host == "127.0.0.1"
    assert links().host == "127.0.0.1"


def test_add_ground_link_wires_the_reference_deployment():
    loaded = load_topology(TOPOLOGY)
    link = add_ground_link(loaded.topology, port=50123, framing="fprime")
    wired = {str(c) for c in loaded.topology.connections}
    q = "ReferenceDeployment.comDriver"
    assert {f"CdhCore.events.PktSend[0] -> {q}.comIn[0]", f"CdhCore.tlmSend.PktSend[0] -> {q}.comIn[0]",
            f"{q}.commandOut[0] -> CdhCore.cmdDisp.seqCmdBuff[1]",  # index 0 is the sequencer's
            f"CdhCore.cmdDisp.seqCmdStatus[1] -> {q}.cmdResponseIn[0]",
            f"ReferenceDeployment.rateGroup50Hz.RateGroupMemberOut[1] -> {q}.schedIn[0]",
            f"{q}.logOut[0] -> CdhCore.events.LogRecv[0]", f"{q}.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]",
            f"{q}.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]"} <= wired
    assert link.port == 50123 and link.framing.name == "fprime"
    assert loaded.topology.problems() == []


def test_add_ground_link_refuses_a_taken_downlink():
    loaded = load_topology(TOPOLOGY)
    add_ground_link(loaded.topology)
    with pytest.raises(TopologyError, match="PktSend is already connected"):
        add_ground_link(loaded.topology, name="second", base_id=0x10080000)


# --- the link component over a real socket ----------------------------------------------------------

@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_uplink_and_downlink_through_a_real_connection(fprime_harness, grounds, links, framing):
    ground = grounds(framing)
    link = links("comDriver", base_id=0x1000, port=ground.port, framing=framing)
    h = fprime_harness(link)
    link.start_socket_task()
    ground.accept()
    assert link.wait_connected(TIMEOUT_S)
    ground.send(KEEPALIVE + ground.command(NO_OP) + KEEPALIVE + ground.command(0x42, b"\x07"))
    wait_for(lambda: len(h.from_port("commandOut")) == 2, step=lambda: h.invoke("schedIn", 0))
    assert [c.args[0] for c in h.from_port("commandOut")] == [encode_command(NO_OP), encode_command(0x42, b"\x07")]
    h.assert_event_count("LinkConnected", 1)
    h.assert_event("LinkConnected", 0, "127.0.0.1", ground.port)
    assert h.tlm_values("State")[-1] == LinkState.CONNECTED
    assert h.tlm_values("UplinkFrames")[-1] == 2
    assert h.tlm_values("UplinkSkippedBytes")[-1] == 2 * len(KEEPALIVE)

    downlink = [bytes.fromhex("0002 00000001 0002 00 00000001 00000000"), bytes.fromhex("0001") + bytes(30)]
    for packet in downlink:
        h.invoke("comIn", packet, 0)
    wait_for(lambda: len(ground.received) == 2, step=ground.poll)
    assert ground.received == downlink
    wait_for(lambda: h.tlm_values("DownlinkBytes") and h.tlm_values("DownlinkBytes")[-1] > 0,
             step=lambda: h.invoke("schedIn", 0))
    frames, sent = h.tlm_values("DownlinkFrames")[-1], h.tlm_values("DownlinkBytes")[-1]
    if framing == "fprime":
        assert frames == 2 and sent == sum(12 + len(p) for p in downlink)
    else:
        assert frames in (1, 2) and sent == 1024 * frames  # one batch, or one per packet


@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_bad_frames_are_dropped_with_throttled_events(fprime_harness, grounds, links, framing):
    ground = grounds(framing)
    link = links("comDriver", base_id=0x1000, port=ground.port, framing=framing, throttle_reset_s=60)
    h = fprime_harness(link)
    h.set_test_time(Time.from_us(1_000_000))
    link.start_socket_task()
    ground.accept()
    bad = bytearray(ground.command(NO_OP))
    bad[-1] ^= 0xFF
    ground.send(bytes(bad) * 8 + ground.command(NO_OP))
    wait_for(lambda: len(h.from_port("commandOut")) == 1, step=lambda: h.invoke("schedIn", 0))
    h.invoke("schedIn", 0)
    h.assert_event_count("InvalidChecksum", 5)  # throttled at 5
    assert h.tlm_values("UplinkDropped")[-1] == 8
    # A minute later the throttle is re-armed.
    h.set_test_time(Time.from_us(62_000_000))
    ground.send(bytes(bad))
    wait_for(lambda: len(h.events_named("InvalidChecksum")) == 6, step=lambda: h.invoke("schedIn", 0))
    assert h.tlm_values("UplinkDropped")[-1] == 9


def test_unknown_descriptor_and_bad_length_events(fprime_harness, grounds, links):
    ground = grounds("fprime")
    link = links("comDriver", base_id=0x1000, port=ground.port, framing="fprime")
    h = fprime_harness(link)
    link.start_socket_task()
    ground.accept()
    ground.send(ground.framer.frame(b"\x00\x07" + bytes(8)) + struct.pack(">II", 0xDEADBEEF, 99999))
    wait_for(lambda: h.events_named("UnknownDescriptor") and h.events_named("InvalidLength"),
             step=lambda: h.invoke("schedIn", 0))
    h.assert_event("UnknownDescriptor", 0, 22, 7)
    h.assert_event("InvalidLength", 0, 99999)
    assert h.from_port("commandOut") == []


@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_the_link_reconnects_and_keeps_the_downlink(fprime_harness, grounds, links, framing):
    ground = grounds(framing)
    link = links("comDriver", base_id=0x1000, port=ground.port, framing=framing, reconnect_min_s=0.05)
    h = fprime_harness(link)
    link.start_socket_task()
    ground.accept()
    wait_for(lambda: h.events_named("LinkConnected"), step=lambda: h.invoke("schedIn", 0))
    ground.conn.close()  # the ground goes away
    wait_for(lambda: h.events_named("LinkDisconnected"), step=lambda: h.invoke("schedIn", 0))
    assert h.events_named("LinkDisconnected")[0][0] == "the ground system closed the connection"
    h.invoke("comIn", bytes.fromhex("0001") + bytes(20), 0)  # queued while the link is down
    ground.accept()  # the link comes back by itself
    wait_for(lambda: len(ground.received) == 1, step=ground.poll)
    assert ground.received == [bytes.fromhex("0001") + bytes(20)]
    ground.send(ground.command(NO_OP))
    wait_for(lambda: len(h.from_port("commandOut")) == 1, step=lambda: h.invoke("schedIn", 0))
    assert h.tlm_values("Connections")[-1] == 2
    h.assert_event_count("LinkConnected", 2)


def test_the_link_waits_for_a_ground_system_that_is_not_up_yet(fprime_harness, grounds, links):
    ground = grounds("fprime", listen=False)  # the port is taken but nobody accepts yet
    link = links("comDriver", base_id=0x1000, port=ground.port, framing="fprime",
                 reconnect_min_s=0.01, reconnect_max_s=0.05)
    h = fprime_harness(link)
    link.start_socket_task()
    wait_for(lambda: link.connect_attempts >= 3)
    assert not link.connected
    h.invoke("schedIn", 0)
    assert h.tlm_values("State")[-1] == LinkState.DISCONNECTED
    h.assert_no_event("LinkDisconnected")  # failing to connect is not losing the link
    ground.listen()
    ground.accept()
    assert link.wait_connected(TIMEOUT_S)


def test_downlink_queue_overflow_drops_the_oldest(fprime_harness, links):
    link = links("comDriver", base_id=0x1000, port=9, max_downlink_packets=3)  # never started
    h = fprime_harness(link)
    for i in range(5):
        h.invoke("comIn", bytes([0, 1, i]), 0)
    assert list(link._downlink) == [bytes([0, 1, i]) for i in (2, 3, 4)]
    h.invoke("schedIn", 0)
    h.assert_event("DownlinkOverflow", 0, 2)
    assert h.tlm_values("DownlinkDropped")[-1] == 2


def test_commands_per_tick_are_bounded(fprime_harness, links):
    link = links("comDriver", base_id=0x1000, max_commands_per_tick=2)
    h = fprime_harness(link)
    link._received(b"".join(link.framing.frame_uplink(encode_command(NO_OP)) for _ in range(5)))
    h.invoke("schedIn", 0)
    assert len(h.from_port("commandOut")) == 2
    h.invoke("schedIn", 0)
    h.invoke("schedIn", 0)
    assert len(h.from_port("commandOut")) == 5


def _file_packets(link, n):
    from fprime_lite.wire.file_packet import DataPacket, encode_file_packet

    packets = [encode_file_packet(DataPacket(i, 4 * i, bytes([i]) * 4)) for i in range(n)]
    return packets, b"".join(link.framing.frame_uplink(p) for p in packets)


def test_file_packets_go_to_file_out_without_their_descriptor_bounded_per_tick(fprime_harness, links):
    link = links("comDriver", base_id=0x1000, max_file_packets_per_tick=3)
    h = fprime_harness(link)
    packets, frames = _file_packets(link, 7)
    link._received(frames + link.framing.frame_uplink(encode_command(NO_OP)))
    h.invoke("schedIn", 0)
    assert [c.args[0] for c in h.from_port("fileOut")] == [p[2:] for p in packets[:3]]
    assert len(h.from_port("commandOut")) == 1  # commands are not held up behind files
    h.invoke("schedIn", 0)
    h.invoke("schedIn", 0)
    assert [c.args[0] for c in h.from_port("fileOut")] == [p[2:] for p in packets]
    assert h.tlm_values("FilePacketsForwarded")[-1] == 7


def test_file_packets_behind_a_command_wait_for_the_next_tick(fprime_harness, links):
    """Stream order as on a board: files, a command (PROVES's CreateDirectory /seq), files received in
    one read: the files ahead of the command and the command go this tick, the files behind it the
    next, so the command's handlers run before the file it makes room for arrives."""
    link = links("comDriver", base_id=0x1000, max_file_packets_per_tick=10)
    h = fprime_harness(link)
    packets, _ = _file_packets(link, 4)
    frame = link.framing.frame_uplink
    link._received(frame(packets[0]) + frame(packets[1]) + frame(encode_command(NO_OP)) + frame(packets[2])
                   + frame(packets[3]))
    h.invoke("schedIn", 0)
    assert len(h.from_port("commandOut")) == 1
    assert [c.args[0] for c in h.from_port("fileOut")] == [p[2:] for p in packets[:2]]
    h.invoke("schedIn", 0)
    assert [c.args[0] for c in h.from_port("fileOut")] == [p[2:] for p in packets]


def test_file_packets_without_a_file_uplink_are_dropped_as_unknown(fprime_harness, links):
    link = links("comDriver", base_id=0x1000)
    h = fprime_harness(link, unconnected=("fileOut",))
    packets, frames = _file_packets(link, 2)
    link._received(frames)
    h.invoke("schedIn", 0)
    h.assert_event_count("UnknownDescriptor", 2)
    h.assert_event("UnknownDescriptor", 0, len(packets[0]), 3)
    assert h.tlm_values("UplinkDropped")[-1] == 2


def test_a_file_backlog_stops_reading_the_socket_until_the_deployment_catches_up(fprime_harness, grounds, links):
    """TCP flow control instead of dropping: with the backlog full nothing more is read."""
    ground = grounds("fprime")
    link = links("comDriver", base_id=0x1000, port=ground.port, framing="fprime", max_file_backlog=4,
                 max_file_packets_per_tick=2)
    h = fprime_harness(link)
    link.start_socket_task()
    ground.accept()
    frames = [ground.framer.frame(p) for p in _file_packets(link, 10)[0]]
    ground.send(b"".join(frames[:4]))
    wait_for(lambda: len(link._file_uplink) == 4)
    ground.send(b"".join(frames[4:]))
    time.sleep(0.3)  # the rest waits in the socket, unread
    assert len(link._file_uplink) == 4
    wait_for(lambda: len(h.from_port("fileOut")) == 10, step=lambda: h.invoke("schedIn", 0))
    offsets = [struct.unpack_from(">I", c.args[0], 5)[0] for c in h.from_port("fileOut")]
    assert offsets == [4 * i for i in range(10)]  # all of them, in order
    assert link.uplink_unroutable == 0 and link.uplink_overflow == 0


def test_file_in_queues_downlink_file_packets(fprime_harness, links):
    link = links("comDriver", base_id=0x1000, port=9)  # never started
    h = fprime_harness(link)
    h.invoke("fileIn", b"\x00\x03\x00\x00\x00\x00\x00")
    assert list(link._downlink) == [b"\x00\x03\x00\x00\x00\x00\x00"]


# --- in the reference deployment --------------------------------------------------------------------

@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_reference_deployment_answers_ground_commands(grounds, framing):
    ground = grounds(framing)
    loaded = load_topology(TOPOLOGY)
    link = add_ground_link(loaded.topology, port=ground.port, framing=framing)
    decoder = GroundDecoder(loaded.topology)
    deployment = Deployment(loaded)
    deployment.start()
    link.start_socket_task()
    try:
        ground.accept()
        ground.send(KEEPALIVE + ground.command(0xDEAD00) + KEEPALIVE + ground.command(NO_OP))

        def names():
            return [decoder.decode_event(p).name for p in ground.received if p[:2] == b"\x00\x02"]

        def answered():
            seen = names()
            return (sum(link.responses.values()) == 2 and "CdhCore.cmdDisp.NoOpReceived" in seen
                    and "CdhCore.cmdDisp.OpCodeCompleted" in seen[seen.index("CdhCore.cmdDisp.NoOpReceived"):])

        # The link's socket thread sends frames on its own schedule: wait until every event the
        # checks below look for has reached the ground, not just the first of them.
        wait_for(answered, step=lambda: (deployment.run_for(0.02), ground.poll()))
        assert link.responses == {"INVALID_OPCODE": 1, "OK": 1}
        events = names()
        assert "CdhCore.cmdDisp.InvalidCommand" in events
        assert "CdhCore.cmdDisp.OpCodeCompleted" in events[events.index("CdhCore.cmdDisp.NoOpReceived"):]
        assert "ReferenceDeployment.comDriver.LinkConnected" in events
        wait_for(lambda: any(c.name == "ReferenceDeployment.detumbleManager.Mode"
                             for p in ground.received if p[:2] == b"\x00\x01"
                             for c in decoder.decode_telemetry(p)),
                 step=lambda: (deployment.run_for(0.5), ground.poll()))
        assert sum(c.handler_faults for c in loaded.topology.components()) == 0
    finally:
        link.close()


# --- fuzz: random and mutated frames through the deframer and the command dispatcher ---------------

def _fuzz_deployment():
    clock = SimulatedClock()
    topo = Topology("FuzzDep")
    cmd_disp = CmdDispatcher("cmdDisp", base_id=0x100, queue_size=20)
    events = EventManager("events", base_id=0x200, queue_size=20)
    tlm = TlmChan("tlmSend", base_id=0x300, queue_size=20)
    for comp in (cmd_disp, events, tlm, TimeSource("chronoTime", base_id=0x400, clock=clock),
                 PassiveRateGroup("rateGroup", base_id=0x500, period_us=20_000)):
        topo.add("CdhCore", comp)
    topo.connect_patterns(command="CdhCore.cmdDisp", event="CdhCore.events", telemetry="CdhCore.tlmSend",
                          time="CdhCore.chronoTime")
    links = {}
    for name in ("fprime", "ccsds"):
        links[name] = add_ground_link(topo, framing=name, name=f"{name}Link", module="Com",
                                      base_id=0x1000 if name == "fprime" else 0x2000)
        if name == "fprime":  # the second link takes the downlink over from the first one
            for service in ("CdhCore.events", "CdhCore.tlmSend"):
                topo.instance(service).component.output_port("PktSend").disconnect(0)
    for comp in topo.components():
        comp.register_commands()
    queued = [cmd_disp, events, tlm]

    def drain():
        while any(c.dispatch_all() for c in queued):
            pass

    drain()
    return topo, links, drain, cmd_disp


FUZZ = {}
CLEAR_TRACKING = struct.pack(">I", 0x103)
COMMANDS = [encode_command(0x100), encode_command(0x101, b"\x00\x03abc"),
            encode_command(0x102, struct.pack(">ifB", -5, 1.5, 7)), encode_command(0x100, b"extra")]


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(framing=st.sampled_from(["fprime", "ccsds"]),
       picks=st.lists(st.integers(0, len(COMMANDS) - 1), min_size=1, max_size=6),
       mutations=st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 255)), max_size=3),
       noise=st.binary(max_size=40), garbage=st.binary(max_size=200))
def test_fuzz_deframer_and_command_path_never_fail(framing, picks, mutations, noise, garbage):
    if not FUZZ:
        FUZZ["dep"] = _fuzz_deployment()
    topo, links, drain, cmd_disp = FUZZ["dep"]
    link = links[framing]
    link.responses.clear()
    link._deframer.reset()  # a partial frame left by the previous example would join this stream
    forwarded0 = link.commands_forwarded
    stream = bytearray(garbage + noise.join(link.framing.frame_uplink(COMMANDS[i]) for i in picks))
    for where, value in mutations:
        stream[where % len(stream)] = value
    produced = [p for p in link.framing.uplink_deframer().push(bytes(stream)) if isinstance(p, bytes)]
    link._received(bytes(stream))
    while link._uplink or link._notices:
        link.schedIn(0)
        drain()
    link.schedIn(0)
    drain()
    forwarded = link.commands_forwarded - forwarded0
    assert forwarded == len(produced)
    if not any(p[2:6] == CLEAR_TRACKING for p in produced):  # that command forgets the others' answers
        assert sum(link.responses.values()) == forwarded
    assert cmd_disp.pending == {}
    assert sum(c.handler_faults for c in topo.components()) == 0


# --- command line ---------------------------------------------------------------------------------

def test_dict_gds_includes_the_link(tmp_path, capsys):
    import json

    from fprime_lite.tools.cli import main

    plain, with_link = tmp_path / "plain.json", tmp_path / "gds.json"
    assert main(["dict", str(TOPOLOGY), "-o", str(plain)]) == 0
    assert main(["dict", str(TOPOLOGY), "--gds", "-o", str(with_link)]) == 0
    names = {e["name"] for e in json.loads(with_link.read_text())["events"]}
    assert "ReferenceDeployment.comDriver.LinkConnected" in names
    assert not any("comDriver" in e["name"] for e in json.loads(plain.read_text())["events"])


@pytest.mark.parametrize("argv, message", [
    (["--framing", "fprime"], "--framing applies to the ground link: add --gds"),
    (["--gds", "127.0.0.1:http"], "the port must be a number"),
])
def test_run_rejects_bad_ground_options(tmp_path, capsys, argv, message):
    from fprime_lite.tools.cli import main

    assert main(["run", str(TOPOLOGY), "--out", str(tmp_path / "o"), *argv]) == 2
    assert message in capsys.readouterr().err


def test_realtime_run_is_paced_to_the_wall_clock(tmp_path, capsys):
    import json

    from fprime_lite.tools.cli import main

    t0 = time.monotonic()
    assert main(["run", str(TOPOLOGY), "--realtime", "--duration", "0.5", "--out", str(tmp_path / "o"),
                 "--no-plots"]) == 0
    assert time.monotonic() - t0 >= 0.5
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["sim_seconds"] == 0.5
    assert 0.8 < summary["real_time_factor"] <= 1.05
    assert "largest lag behind the wall clock" in capsys.readouterr().out


# --- resynchronisation (issue #16 finding 3) -------------------------------------------------------

def _bogus_header(framing):
    """A header that passes every check but claims more bytes than will ever come."""
    if framing == "ccsds":
        return struct.pack(">HHB", (1 << 13) | 0x44, (1 << 10) | 1023, 0)  # a 1024-byte TC frame
    return struct.pack(">II", 0xDEADBEEF, 4000)


@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_commands_behind_a_bogus_header_survive_a_disconnect(fprime_harness, grounds, links, framing):
    """GL-RESYNC-5: the finding's campaign step — a header claiming 1024 (CCSDS) / 4000 (fprime)
    bytes, 3 valid commands, then the ground disconnects: all 3 reach commandOut, IncompleteFrame is
    logged and UplinkDroppedBytes counts the header's bytes (with an UplinkBytesDropped event)."""
    ground = grounds(framing)
    link = links("comDriver", base_id=0x1000, port=ground.port, framing=framing, reconnect_min_s=0.05,
                 partial_frame_timeout_s=60.0)  # only the disconnect may release them here
    h = fprime_harness(link)
    link.start_socket_task()
    ground.accept()
    commands = [ground.command(NO_OP), ground.command(0x42, b"\x07"), ground.command(0x43)]
    ground.send(_bogus_header(framing) + b"".join(commands))
    ground.conn.close()
    wait_for(lambda: len(h.from_port("commandOut")) == 3, step=lambda: h.invoke("schedIn", 0))
    assert [c.args[0] for c in h.from_port("commandOut")] == [
        encode_command(NO_OP), encode_command(0x42, b"\x07"), encode_command(0x43)]
    h.invoke("schedIn", 0)
    assert h.events_named("IncompleteFrame")
    assert h.tlm_values("UplinkDroppedBytes")[-1] == len(_bogus_header(framing))
    assert h.events_named("UplinkBytesDropped")[-1] == (len(_bogus_header(framing)), len(_bogus_header(framing)))


@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_commands_behind_a_bogus_header_arrive_while_the_link_stays_up(fprime_harness, grounds, links, framing):
    """GL-RESYNC-6: the same with the link kept up and keep-alives following: the partial frame is
    abandoned after partial_frame_timeout_s and the 3 commands are dispatched (before: they waited
    until the keep-alives filled the claimed length)."""
    ground = grounds(framing)
    link = links("comDriver", base_id=0x1000, port=ground.port, framing=framing, partial_frame_timeout_s=0.2)
    h = fprime_harness(link)
    link.start_socket_task()
    ground.accept()
    commands = [ground.command(NO_OP), ground.command(0x42, b"\x07"), ground.command(0x43)]
    ground.send(_bogus_header(framing) + b"".join(commands) + KEEPALIVE)

    polls = [0]

    def keep_alive():  # one keep-alive per ~50 ms: in 3 s far fewer bytes than either header claims
        h.invoke("schedIn", 0)
        polls[0] += 1
        if polls[0] % 10 == 0:
            ground.send(KEEPALIVE)

    wait_for(lambda: len(h.from_port("commandOut")) == 3, step=keep_alive, timeout=3.0)
    assert h.events_named("IncompleteFrame")
