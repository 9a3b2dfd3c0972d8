"""Ground-side reassembly of downlinked files (what fprime-gds's downlinker does)."""

import os

from fprime_lite.wire.file_packet import (CancelPacket, DataPacket, EndPacket, StartPacket, cfdp_checksum,
                                     encode_file_packet)
from fprime_lite.ground.files import FileReceiver


def send_file(receiver, data, destination, chunk=7, checksum=None, end=True):
    packets = [StartPacket(0, len(data), "/flight/src.bin", destination)]
    packets += [DataPacket(1 + i // chunk, i, data[i:i + chunk]) for i in range(0, len(data), chunk)]
    if end:
        packets.append(EndPacket(len(packets), cfdp_checksum(data) if checksum is None else checksum))
    for p in packets:
        receiver.receive(encode_file_packet(p))


def test_a_file_lands_under_its_sanitised_destination_name(tmp_path):
    receiver = FileReceiver(tmp_path / "downlink")
    data = os.urandom(100)
    send_file(receiver, data, "logs/today.bin")
    (record,) = receiver.files
    assert record.status == "complete" and record.path == tmp_path / "downlink" / "logs_today.bin"
    assert record.path.read_bytes() == data
    assert sorted(p.name for p in (tmp_path / "downlink").iterdir()) == ["logs_today.bin"]  # no temp file left


def test_a_checksum_mismatch_keeps_the_bytes_and_says_so(tmp_path):
    receiver = FileReceiver(tmp_path)
    send_file(receiver, b"abcdefgh", "f.bin", checksum=1)
    (record,) = receiver.files
    assert record.status == "checksum mismatch" and "END says 0x00000001" in record.detail
    assert record.path.read_bytes() == b"abcdefgh"


def test_cancel_new_start_and_end_of_run_leave_nothing_half_written(tmp_path):
    receiver = FileReceiver(tmp_path)
    send_file(receiver, b"first file", "a.bin", end=False)
    receiver.receive(encode_file_packet(CancelPacket(9)))
    send_file(receiver, b"second file", "b.bin", end=False)
    send_file(receiver, b"third", "c.bin")  # a START while b.bin is still open
    send_file(receiver, b"fourth", "d.bin", end=False)
    receiver.close()
    assert [(f.destination, f.status) for f in receiver.files] == [
        ("a.bin", "canceled"), ("b.bin", "incomplete"), ("c.bin", "complete"), ("d.bin", "incomplete")]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.bin"]


def test_stray_and_malformed_packets_are_counted(tmp_path):
    receiver = FileReceiver(tmp_path)
    receiver.receive(encode_file_packet(DataPacket(0, 0, b"x")))  # no START before it
    receiver.receive(b"\x00\x03\x09")  # not a file packet
    assert receiver.bad_packets == 2 and receiver.files == []
