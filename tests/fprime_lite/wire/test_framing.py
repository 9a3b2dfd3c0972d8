"""Ground-link framings: byte layouts (tests/data/gds/gds_notes.md §d–e), round trips, noise, drops.

fprime-gds 4.4.1's own framers and deframers are the outside authority where it matters: the GDS
frames the uplink our deframers read, and deframes the downlink our framers write.
"""

import pathlib
import struct
import zlib

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fprime_lite.wire.framing import (
    CcsdsFraming,
    Dropped,
    DropReason,
    FprimeFraming,
    crc16_ccitt,
    make_framing,
)
from fprime_lite.wire.packets import encode_command

DATA = pathlib.Path(__file__).parents[2] / "data" / "gds"
KEEPALIVE = b"sitting well"
# MiniDep.demo.CONFIGURE 7 2.5 "hello" NOMINAL as the GDS encodes it (gds_notes.md §d)
CONFIGURE = bytes.fromhex("0000" "00001000" "00000007" "40200000" "0005" "68656c6c6f" "00000001")
NO_OP = encode_command(0x01000100)


def tc_frame(packet, apid=None, count=0, vcid=1, scid=0x44, packet_type=1, data_len=None):
    """A TC frame built by hand from the layout in the notes (not with the code under test)."""
    apid = int.from_bytes(packet[:2], "big") if apid is None else apid
    sp = struct.pack(">HHH", (packet_type << 12) | apid, 0xC000 | count,
                     len(packet) - 1 if data_len is None else data_len) + packet
    body = struct.pack(">HHB", (1 << 13) | scid, (vcid << 10) | (5 + len(sp) + 2 - 1), 0) + sp
    return body + struct.pack(">H", crc16_ccitt(body))


def fp_frame(packet, length=None):
    head = struct.pack(">II", 0xDEADBEEF, len(packet) if length is None else length) + packet
    return head + struct.pack(">I", zlib.crc32(head))


# --- layouts --------------------------------------------------------------------------------------

def test_crc16_is_ccitt_false():
    assert crc16_ccitt(b"123456789") == 0x29B1  # the catalogued check value of CRC-16/CCITT-FALSE


def test_fprime_frame_matches_the_notes_example():
    frame = FprimeFraming().frame_downlink([CONFIGURE])[0]
    assert frame == bytes.fromhex("deadbeef00000019") + CONFIGURE + bytes.fromhex("ef381c92")
    assert FprimeFraming().frame_uplink(CONFIGURE) == frame  # symmetric


def test_ccsds_uplink_frame_matches_the_notes_example():
    frame = CcsdsFraming().frame_uplink(CONFIGURE)
    assert frame[:11] == bytes.fromhex("2044042500" "1000c0000018")
    assert frame[11:-2] == CONFIGURE
    assert frame[-2:] == bytes.fromhex("63ac")
    second = CcsdsFraming()
    second.frame_uplink(NO_OP)
    assert second.frame_uplink(NO_OP)[5:9] == bytes.fromhex("1000c001")  # per-APID sequence count


def test_tm_frame_layout_one_event_packet_and_idle_fill():
    event = bytes.fromhex("0002" "00001000" "0002" "00" "00000064" "0003d090") + b"\x01\x02"
    frames = CcsdsFraming().frame_downlink([event])
    assert len(frames) == 1 and len(frames[0]) == 1024
    f = frames[0]
    assert f[:6] == bytes.fromhex("0442" "00" "00" "1800")  # SCID 0x44, VCID 1; MC 0, VC 0; FHP 0
    assert f[6:12] == struct.pack(">HHH", 2, 0xC000, len(event) - 1)  # TM Space Packet, APID 2
    assert f[12:12 + len(event)] == event
    idle = 12 + len(event)
    ident, seq, data_len = struct.unpack_from(">HHH", f, idle)
    assert ident == 0x7FF and seq >> 14 == 0b11
    assert idle + 6 + data_len + 1 == 1022  # the idle packet fills the data field exactly
    assert struct.unpack(">H", f[-2:])[0] == crc16_ccitt(f[:-2])


def test_tm_frames_count_and_point_at_the_first_header():
    framing = CcsdsFraming()
    big = b"\x00\x01" + bytes(1500)  # spans into a second frame
    frames = framing.frame_downlink([big, b"\x00\x02" + bytes(20)])
    assert [f[2:4] for f in frames] == [b"\x00\x00", b"\x01\x01"]  # MC and VC counts
    fhp = [struct.unpack_from(">H", f, 4)[0] & 0x7FF for f in frames]
    assert fhp[0] == 0
    assert fhp[1] == 6 + len(big) - 1016  # the second packet starts right after the first ends
    assert framing.frame_downlink([b"\x00\x01" + bytes(3000)])[1][4:6] == b"\x1f\xff"  # no header: 0x7FF


def test_make_framing_accepts_gds_names():
    assert isinstance(make_framing("space-packet-space-data-link"), CcsdsFraming)
    assert isinstance(make_framing("fprime"), FprimeFraming)
    with pytest.raises(ValueError, match="unknown framing"):
        make_framing("raw")


# --- the GDS as authority ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def gds():
    pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency: pip install -e .[test]")
    from fprime_gds.common.models.dictionaries import Dictionaries

    Dictionaries.load_dictionaries_into_config(str(DATA / "minimal_dictionary.json"))
    from fprime_gds.common.communication.ccsds.chain import SpacePacketSpaceDataLinkFramerDeframer
    from fprime_gds.common.communication.framing import FpFramerDeframer

    return {"fprime": FpFramerDeframer("crc32"),
            "ccsds": SpacePacketSpaceDataLinkFramerDeframer(scid=None, vcid=1, frame_size=None)}


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_our_deframer_reads_what_the_gds_frames(gds, name):
    packets = [NO_OP, CONFIGURE, encode_command(0x1005A000, b"\x01")]
    stream = KEEPALIVE.join(gds[name].frame(p) for p in packets) + KEEPALIVE
    deframer = make_framing(name).uplink_deframer()
    out = []
    for i in range(0, len(stream), 7):  # arbitrary TCP segmentation
        out += deframer.push(stream[i:i + 7])
    assert out == packets
    assert deframer.skipped_bytes + deframer.buffered == 3 * len(KEEPALIVE)  # a possible partial start is held
    assert deframer.frames == 3 and deframer.dropped == 0


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
@pytest.mark.parametrize("sizes", [[17], [17, 30, 1000, 2500, 5], [1009], [1010], [1011], [1016 - 6 - 3]])
def test_the_gds_reads_what_we_frame(gds, name, sizes):
    packets = [b"\x00\x02" + bytes([n % 251]) * n for n in sizes]
    framing = make_framing(name)
    stream = b"".join(framing.frame_downlink(packets))
    stream += b"".join(framing.frame_downlink(packets[:1]))  # the next batch still lines up
    got, rest, discarded = gds[name].deframe_all(stream, no_copy=False)
    assert got == packets + packets[:1]
    assert rest == b"" and discarded == b""


# --- noise and drops ------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_keepalives_split_anywhere_are_skipped(name):
    framing = make_framing(name)
    stream = KEEPALIVE * 3 + framing.frame_uplink(NO_OP) + KEEPALIVE + framing.frame_uplink(CONFIGURE) + KEEPALIVE
    deframer = framing.uplink_deframer()
    out = []
    for b in stream:  # one byte at a time
        out += deframer.push(bytes([b]))
    assert out == [NO_OP, CONFIGURE]
    assert deframer.skipped_bytes == 5 * len(KEEPALIVE) - deframer.buffered
    assert deframer.buffered < 4


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_bad_crc_is_dropped_once_and_the_next_frame_survives(name):
    framing = make_framing(name)
    bad = bytearray(framing.frame_uplink(CONFIGURE))
    bad[-1] ^= 0x01
    deframer = framing.uplink_deframer()
    out = deframer.push(bytes(bad) + KEEPALIVE + framing.frame_uplink(NO_OP))
    assert len(out) == 2
    assert isinstance(out[0], Dropped) and out[0].reason is DropReason.BAD_CRC
    assert out[0].size == len(bad)
    assert out[1] == NO_OP
    assert deframer.dropped == 1


def test_fprime_length_too_large_is_dropped():
    deframer = FprimeFraming().uplink_deframer()
    out = deframer.push(struct.pack(">II", 0xDEADBEEF, 5000) + KEEPALIVE + fp_frame(NO_OP))
    assert out == [Dropped(DropReason.BAD_LENGTH, 8, 5000), NO_OP]


def test_fprime_empty_frame_is_a_bad_length():
    assert FprimeFraming().uplink_deframer().push(fp_frame(b"")) == [Dropped(DropReason.BAD_LENGTH, 12, 0)]


def test_ccsds_short_length_field_is_dropped():
    header = struct.pack(">HHB", (1 << 13) | 0x44, (1 << 10) | 8, 0)  # a 9-byte TC frame cannot hold a packet
    out = CcsdsFraming().uplink_deframer().push(header + bytes(20) + tc_frame(NO_OP))
    assert out == [Dropped(DropReason.BAD_LENGTH, 5, 9), NO_OP]


def test_ccsds_space_packet_longer_than_its_frame_is_a_bad_length():
    out = CcsdsFraming().uplink_deframer().push(tc_frame(NO_OP, data_len=40))
    assert out == [Dropped(DropReason.BAD_LENGTH, 5 + 6 + len(NO_OP) + 2, 6 + 41)]


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_file_packets_pass_and_other_descriptors_are_dropped(name):
    file_packet = b"\x00\x03" + bytes(10)  # FW_PACKET_FILE: for the file uplink
    telemetry = b"\x00\x01" + bytes(10)  # FW_PACKET_TELEM never comes up from the ground
    framing = make_framing(name)
    out = framing.uplink_deframer().push(framing.frame_uplink(file_packet) + framing.frame_uplink(telemetry)
                                         + framing.frame_uplink(NO_OP))
    assert len(out) == 3 and out[0] == file_packet and out[2] == NO_OP
    assert out[1].reason is DropReason.UNKNOWN_DESCRIPTOR and out[1].value == 1


def test_ccsds_other_virtual_channel_and_telemetry_packets_are_dropped():
    deframer = CcsdsFraming().uplink_deframer()
    out = deframer.push(tc_frame(NO_OP, vcid=5) + tc_frame(NO_OP, packet_type=0) + tc_frame(NO_OP))
    assert [getattr(o, "reason", o) for o in out] == [DropReason.UNKNOWN_DESCRIPTOR,
                                                      DropReason.UNKNOWN_DESCRIPTOR, NO_OP]


def test_ccsds_apid_must_match_the_descriptor():
    out = CcsdsFraming().uplink_deframer().push(tc_frame(NO_OP, apid=1))
    assert out == [Dropped(DropReason.UNKNOWN_DESCRIPTOR, 5 + 6 + len(NO_OP) + 2, 0)]


def test_other_spacecraft_is_noise():
    deframer = CcsdsFraming().uplink_deframer()
    assert deframer.push(tc_frame(NO_OP, scid=0x45)) == []
    assert deframer.dropped == 0


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_the_buffer_stays_bounded_on_endless_noise(name):
    deframer = make_framing(name).uplink_deframer()
    for _ in range(200):
        assert deframer.push(KEEPALIVE * 40) == []
    assert deframer.buffered < 4
    assert deframer.skipped_bytes == 200 * 40 * len(KEEPALIVE) - deframer.buffered


def test_reset_forgets_a_partial_frame():
    framing = FprimeFraming()
    deframer = framing.uplink_deframer()
    frame = framing.frame_uplink(NO_OP)
    assert deframer.push(frame[:9]) == []
    deframer.reset()
    assert deframer.push(frame[9:] + frame) == [NO_OP]


# --- fuzz: nothing raises, everything is accounted for ----------------------------------------------

def _check(deframer, out):
    for item in out:
        assert isinstance(item, (bytes, Dropped))
        if isinstance(item, bytes):
            assert item[:2] == b"\x00\x00"
    assert deframer.buffered <= 4095 + 12


@settings(max_examples=300, deadline=None)
@given(name=st.sampled_from(["fprime", "ccsds"]), chunks=st.lists(st.binary(max_size=300), max_size=20))
def test_fuzz_random_bytes_never_raise(name, chunks):
    deframer = make_framing(name).uplink_deframer()
    for chunk in chunks:
        _check(deframer, deframer.push(chunk))


@settings(max_examples=300, deadline=None)
@given(name=st.sampled_from(["fprime", "ccsds"]),
       packets=st.lists(st.binary(min_size=0, max_size=60), min_size=1, max_size=5),
       mutations=st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 255)), max_size=4),
       cut=st.integers(0, 10_000), noise=st.binary(max_size=30))
def test_fuzz_mutated_frames_never_raise_and_intact_frames_survive(name, packets, mutations, cut, noise):
    framing = make_framing(name)
    commands = [b"\x00\x00" + p for p in packets]
    frames = [framing.frame_uplink(c) for c in commands]
    stream = bytearray(noise.join(frames))
    touched = set()
    for where, value in mutations:
        if stream:
            i = where % len(stream)
            stream[i] = value
            touched.add(i)
    deframer = framing.uplink_deframer()
    k = cut % (len(stream) + 1)
    out = deframer.push(bytes(stream[:k])) + deframer.push(bytes(stream[k:]))
    _check(deframer, out)
    if not touched:
        assert [o for o in out if isinstance(o, bytes)] == commands
        assert deframer.dropped == 0


# --- resynchronisation (issue #16 finding 3) ---------------------------------------------------------

def _plausible_bad_header(name, claimed):
    """A header that passes every check but claims ``claimed`` bytes that will never come."""
    if name == "ccsds":
        return struct.pack(">HHB", (1 << 13) | 0x44, (1 << 10) | (claimed - 1), 0)
    return struct.pack(">II", 0xDEADBEEF, claimed)


THREE = [NO_OP, CONFIGURE, encode_command(0x42, b"\x07")]


@pytest.mark.parametrize("name, claimed", [("ccsds", 1024), ("fprime", 4000)])
def test_valid_frames_behind_a_plausible_bad_header_survive_a_disconnect(name, claimed):
    """GL-RESYNC-1: a header claiming 1024 (CCSDS) / 4000 (fprime) bytes, then 3 valid commands, then
    the connection drops: reset() abandons the partial frame as INCOMPLETE and delivers the 3."""
    framing = make_framing(name)
    deframer = framing.uplink_deframer()
    frames = b"".join(framing.frame_uplink(c) for c in THREE)
    assert deframer.push(_plausible_bad_header(name, claimed) + frames) == []  # still waiting
    assert deframer.pending_offset == 0
    out = deframer.reset()
    assert [o for o in out if isinstance(o, bytes)] == THREE
    drops = [o for o in out if isinstance(o, Dropped)]
    assert [d.reason for d in drops] == [DropReason.INCOMPLETE]
    header = len(_plausible_bad_header(name, claimed))
    assert deframer.dropped_bytes == header  # only the bad header's bytes were lost
    assert deframer.buffered == 0 and deframer.pending_offset is None


@pytest.mark.parametrize("name, claimed", [("ccsds", 1024), ("fprime", 4000)])
def test_expire_resynchronises_while_the_link_stays_up(name, claimed):
    """GL-RESYNC-2: the same bad header followed by the commands and keep-alives (fewer bytes than
    it claims): expire() delivers the 3 commands; a later frame deframes normally."""
    framing = make_framing(name)
    deframer = framing.uplink_deframer()
    stream = _plausible_bad_header(name, claimed) + b"".join(framing.frame_uplink(c) + KEEPALIVE for c in THREE)
    assert deframer.push(stream) == []
    out = deframer.expire()
    assert [o for o in out if isinstance(o, bytes)] == THREE
    assert deframer.push(framing.frame_uplink(NO_OP)) == [NO_OP]
    assert deframer.expire() == []  # nothing pending: nothing to abandon


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_dropped_bytes_count_the_rejected_frame_only(name):
    """GL-RESYNC-3: a frame with a bad CRC, a keep-alive, a good frame: dropped_bytes is the bad frame's
    length, skipped_bytes the keep-alive's."""
    framing = make_framing(name)
    bad = bytearray(framing.frame_uplink(CONFIGURE))
    bad[-1] ^= 0x01
    deframer = framing.uplink_deframer()
    out = deframer.push(bytes(bad) + KEEPALIVE + framing.frame_uplink(NO_OP))
    assert out[-1] == NO_OP
    assert deframer.dropped_bytes == len(bad)
    assert deframer.skipped_bytes == len(KEEPALIVE)


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_a_partial_frame_cut_by_a_disconnect_is_reported(name):
    """GL-RESYNC-4: a good frame cut in half by a disconnect is dropped as INCOMPLETE (with the bytes
    that had arrived), never delivered."""
    framing = make_framing(name)
    frame = framing.frame_uplink(CONFIGURE)
    deframer = framing.uplink_deframer()
    assert deframer.push(frame[:10]) == []
    out = deframer.reset()
    assert out == [Dropped(DropReason.INCOMPLETE, 10, 10)]


@pytest.mark.parametrize("name", ["fprime", "ccsds"])
def test_campaign_of_bogus_headers_and_disconnects_loses_no_valid_command(name):
    """GL-RESYNC-7 (the finding's campaign): 50 connection cycles, each with 1–3 plausible bogus
    headers (claiming up to the largest frame) mixed among 3–6 valid commands and keep-alives, pushed
    in random pieces, then a disconnect: every valid command is delivered, in order."""
    import random

    rng = random.Random(50)
    framing = make_framing(name)
    deframer = framing.uplink_deframer()
    sent, delivered = [], []
    for cycle in range(50):
        parts = []
        for i in range(rng.randint(3, 6)):
            command = encode_command(0x1000 + cycle, bytes([i]) * rng.randint(0, 40))
            sent.append(command)
            parts.append(framing.frame_uplink(command))
        for _ in range(rng.randint(1, 3)):
            claimed = rng.randint(60, 1024) if name == "ccsds" else rng.randint(60, 4095)
            parts.insert(rng.randrange(len(parts) + 1), _plausible_bad_header(name, claimed))
        parts.insert(rng.randrange(len(parts) + 1), KEEPALIVE)
        stream = b"".join(parts)
        cuts = sorted(rng.sample(range(len(stream)), 3))
        for a, b in zip([0] + cuts, cuts + [len(stream)], strict=True):
            delivered += [o for o in deframer.push(stream[a:b]) if isinstance(o, bytes)]
        delivered += [o for o in deframer.reset() if isinstance(o, bytes)]
    assert delivered == sent
