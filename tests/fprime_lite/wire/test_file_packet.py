"""File packets and the CFDP checksum, against fprime-gds 4.4.1's own file encoder, decoder and checksum."""

import os
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fprime_lite.wire.file_packet import (CancelPacket, CfdpChecksum, DataPacket, EndPacket, FilePacketError,
                                     StartPacket, cfdp_checksum, decode_file_packet, encode_file_packet)

pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency: pip install -e .[test]")

from fprime_gds.common.data_types import file_data as gds
from fprime_gds.common.decoders.file_decoder import FileDecoder
from fprime_gds.common.encoders.file_encoder import FileEncoder
from fprime_gds.common.files.helpers import CFDPChecksum

PAIRS = [
    (StartPacket(0, 1234, "/tmp/src.bin", "/seq/dst.bin"),
     gds.StartPacketData(0, 1234, "/tmp/src.bin", "/seq/dst.bin")),
    (DataPacket(1, 512, b"\x00\x01binary\xff"), gds.DataPacketData(1, 512, b"\x00\x01binary\xff")),
    (EndPacket(2, 0xDEADBEEF), gds.EndPacketData(2, 0xDEADBEEF)),
    (CancelPacket(3), gds.CancelPacketData(3)),
]


@pytest.mark.parametrize("ours, theirs", PAIRS, ids=["start", "data", "end", "cancel"])
def test_our_packets_are_byte_identical_to_what_the_gds_uplinks(ours, theirs):
    gds_bytes = FileEncoder().encode_api(theirs)
    assert encode_file_packet(ours) == gds_bytes[8:]  # the GDS prefixes a 4-byte marker and a U32 length
    assert decode_file_packet(gds_bytes[8:], descriptor=True) == ours
    assert decode_file_packet(gds_bytes[10:]) == ours


@pytest.mark.parametrize("ours, theirs", PAIRS, ids=["start", "data", "end", "cancel"])
def test_the_gds_decodes_our_downlinked_packets(ours, theirs):
    decoded = FileDecoder().decode_api(encode_file_packet(ours, descriptor=False))[0]
    assert type(decoded) is type(theirs) and decoded.seqID == ours.sequence
    if isinstance(ours, StartPacket):
        assert (decoded.size, decoded.sourcePath, decoded.destPath) == (1234, b"/tmp/src.bin", b"/seq/dst.bin")
    elif isinstance(ours, DataPacket):
        assert (decoded.offset, decoded.dataVar) == (512, ours.data)
    elif isinstance(ours, EndPacket):
        assert decoded.hashValue == (0xDEADBEEF,)


def test_checksum_matches_the_gds_for_any_chunking():
    rng = random.Random(7)
    data = os.urandom(5000)
    ours, theirs = CfdpChecksum(), CFDPChecksum()
    offset = 0
    while offset < len(data):
        n = rng.randint(1, 97)  # odd sizes: chunks start at every alignment
        ours.update(data[offset:offset + n], offset)
        theirs.update(data[offset:offset + n], offset)
        offset += n
    assert ours.value == theirs.value == cfdp_checksum(data)


def test_checksum_by_hand():
    # Words 0x01020304 + 0x05000000 (the last byte sits in the top byte of its word).
    assert cfdp_checksum(b"\x01\x02\x03\x04\x05") == 0x06020304
    assert cfdp_checksum(b"") == 0
    assert cfdp_checksum(b"\xff\xff\xff\xff" * 2) == 0xFFFFFFFE  # wraps mod 2**32


@pytest.mark.parametrize("data, reason", [
    (b"\x00\x03\x01", "shorter than a file packet header"),
    (b"\x00\x03\x07\x00\x00\x00\x00", "unknown file packet type 7"),
    (b"\x00\x03\x01\x00\x00\x00\x00\x00\x00\x00\x00\x00\x09abc", "says 9 bytes but carries 3"),
    (b"\x00\x03\x00\x00\x00\x00\x00\x00\x00\x00\x10\x05ab", "source path says 5 bytes but 2 remain"),
    (b"\x00\x03\x02\x00\x00\x00\x00\x01", "END packet too short"),
    (b"\x00\x01\x02\x00\x00\x00\x00", "descriptor 0001 is not FW_PACKET_FILE"),
])
def test_malformed_packets_are_explained_not_raised(data, reason):
    result = decode_file_packet(data, descriptor=True)
    assert isinstance(result, FilePacketError) and reason in result.reason


def test_paths_longer_than_a_u8_length_are_refused_when_encoding():
    with pytest.raises(ValueError, match="source path is 300 bytes; a file packet holds at most 255"):
        encode_file_packet(StartPacket(0, 0, "x" * 300, "y"))


@settings(max_examples=300, deadline=None)
@given(st.binary(max_size=300))
def test_decoding_never_raises(data):
    for descriptor in (False, True):
        result = decode_file_packet(data, descriptor=descriptor)
        assert isinstance(result, (FilePacketError, StartPacket, DataPacket, EndPacket, CancelPacket))
