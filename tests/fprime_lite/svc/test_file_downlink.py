"""Svc.FileDownlink: files leave as START, DATA…, END packets, a budget per Run tick, with F´'s
events, channels and command responses.

Packets are checked three ways: with fprime_lite's own decoder, with fprime-gds 4.4.1's
``FileDecoder`` and ``CFDPChecksum``, and by letting the GDS's ``FileDownlinker`` rebuild the file.
"""

from __future__ import annotations

import logging
import os
import random

import pytest

from fprime_lite import CmdResponse, Severity
from fprime_lite.wire.file_packet import (CancelPacket, CfdpChecksum, DataPacket, EndPacket, StartPacket,
                                     cfdp_checksum, decode_file_packet)
from fprime_lite.svc.file_downlink import (DEFAULT_DATA_SIZE, DEFAULT_PACKETS_PER_TICK, FileDownlink,
                                           OsFileStatus, SendFileResponse, SendFileStatus)

BASE = 0x5000200
U32_MAX = 0xFFFFFFFF


def make(fprime_harness, tmp_path, **kwargs):
    kwargs.setdefault("data_size", 100)
    kwargs.setdefault("packets_per_tick", 3)
    fd = FileDownlink("fileDownlink", base_id=BASE, root=tmp_path, **kwargs)
    return fd, fprime_harness(fd)


def write(tmp_path, name, size, seed=1) -> bytes:
    data = random.Random(seed).randbytes(size)
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return data


def command(h, name, *args, cmd_seq=0):
    h.send_command(name, *args, cmd_seq=cmd_seq)
    h.dispatch_all()


def tick(h) -> int:
    """One Run tick; returns the number of packets it sent."""
    before = len(h.from_port("bufferSendOut"))
    h.invoke("Run", 0)
    h.dispatch_all()
    return len(h.from_port("bufferSendOut")) - before


def raw_packets(h) -> list[bytes]:
    return [call.args[0] for call in h.from_port("bufferSendOut")]


def packets(h) -> list:
    out = []
    for raw in raw_packets(h):
        assert raw[:2] == b"\x00\x03"  # FW_PACKET_FILE descriptor on every packet
        out.append(decode_file_packet(raw, descriptor=True))
    return out


def responses(h, name):
    opcode = BASE + h.component.spec.command(name).opcode
    return [(r.cmd_seq, r.response) for r in h.cmd_responses if r.opcode == opcode]


# --- a whole file -----------------------------------------------------------------------------------

def test_send_file_goes_out_as_start_data_end_over_ticks_within_budget(fprime_harness, tmp_path):
    data = write(tmp_path, "img.bin", 1050)        # 11 DATA packets of <= 100 bytes
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "img.bin", "ground/img.bin", cmd_seq=7)
    assert h.cmd_responses == []                    # deferred until the transfer ends
    assert raw_packets(h) == []                     # nothing before a Run tick

    per_tick = []
    while not h.cmd_responses:
        per_tick.append(tick(h))
        assert len(per_tick) < 20
    assert per_tick == [3, 3, 3, 3, 1]              # 1 START + 11 DATA + 1 END, at most 3 a tick
    assert tick(h) == 0                             # idle afterwards

    sent = packets(h)
    assert sent[0] == StartPacket(0, 1050, "img.bin", "ground/img.bin")
    chunks = sent[1:-1]
    assert all(isinstance(p, DataPacket) for p in chunks)
    assert [p.sequence for p in chunks] == list(range(1, 12))
    assert [p.offset for p in chunks] == list(range(0, 1050, 100))
    assert all(len(p.data) <= 100 for p in chunks)
    assert b"".join(p.data for p in chunks) == data
    assert sent[-1] == EndPacket(12, cfdp_checksum(data))

    assert responses(h, "SendFile") == [(7, CmdResponse.OK)]
    h.assert_event("SendStarted", 0, 1050, "img.bin", "ground/img.bin")
    h.assert_event("FileSent", 0, "img.bin", "ground/img.bin")
    assert [e.name for e in h.events] == ["SendStarted", "FileSent"]
    assert h.tlm_values("FilesSent") == [1]
    assert h.tlm_values("PacketsSent") == list(range(1, 14))
    assert h.tlm_values("Warnings") == []


def test_response_ok_arrives_only_with_the_end_packet(fprime_harness, tmp_path):
    write(tmp_path, "a.bin", 250)                   # START, 3 DATA, END
    fd, h = make(fprime_harness, tmp_path, packets_per_tick=1)
    command(h, "SendFile", "a.bin", "a.bin")
    for _ in range(4):
        tick(h)
        assert h.cmd_responses == [] and fd.busy
    tick(h)
    assert isinstance(packets(h)[-1], EndPacket)
    h.assert_cmd_response(0, "SendFile", CmdResponse.OK)
    assert not fd.busy


def test_packets_decode_with_fprime_gds_file_decoder_and_checksum(fprime_harness, tmp_path):
    pytest.importorskip("fprime_gds")
    from fprime_gds.common.data_types.file_data import FilePacketType
    from fprime_gds.common.decoders.file_decoder import FileDecoder
    from fprime_gds.common.files.helpers import CFDPChecksum

    data = write(tmp_path, "log.txt", 1200, seed=3)
    _fd, h = make(fprime_harness, tmp_path, data_size=DEFAULT_DATA_SIZE, packets_per_tick=10)
    command(h, "SendFile", "log.txt", "downlinked.txt")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.OK)

    decoded = [FileDecoder().decode_api(raw[2:])[0] for raw in raw_packets(h)]
    kinds = [d.packetType for d in decoded]
    assert kinds == [FilePacketType.START] + [FilePacketType.DATA] * 3 + [FilePacketType.END]
    start = decoded[0]
    assert (start.seqID, start.size, start.sourcePath, start.destPath) == (0, 1200, b"log.txt",
                                                                          b"downlinked.txt")
    gds_sum = CFDPChecksum()
    rebuilt = bytearray(1200)
    for d in decoded[1:-1]:
        assert len(d.dataVar) <= DEFAULT_DATA_SIZE
        rebuilt[d.offset:d.offset + len(d.dataVar)] = d.dataVar
        gds_sum.update(d.dataVar, d.offset)
    assert [d.seqID for d in decoded] == [0, 1, 2, 3, 4]
    assert bytes(rebuilt) == data
    assert decoded[-1].hashValue[0] == gds_sum.value == cfdp_checksum(data)
    assert max(len(raw) for raw in raw_packets(h)) == 512   # a full DATA packet fills the com buffer


def test_fprime_gds_file_downlinker_rebuilds_the_file(fprime_harness, tmp_path):
    pytest.importorskip("fprime_gds")
    from fprime_gds.common.decoders.file_decoder import FileDecoder
    from fprime_gds.common.files.downlinker import FileDownlinker

    data = write(tmp_path, "src/science.dat", 3000, seed=9)
    _fd, h = make(fprime_harness, tmp_path, data_size=DEFAULT_DATA_SIZE, packets_per_tick=4)
    command(h, "SendFile", "src/science.dat", "science.dat")
    for _ in range(3):
        tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.OK)

    store = tmp_path / "ground"
    store.mkdir()
    downlinker = FileDownlinker(str(store), timeout=60.0)
    try:
        for raw in raw_packets(h):
            downlinker.data_callback(FileDecoder().decode_api(raw[2:])[0])
    finally:
        downlinker.timer.stop()
    assert downlinker.active is None                # END closed the transfer
    assert (store / "science.dat").read_bytes() == data


def test_relative_names_open_under_root_and_absolute_names_inside_root_too(fprime_harness, tmp_path):
    """FS-ROOT-5: a relative source opens under root; an absolute source inside root is sent and
    carried in START as written."""
    data = write(tmp_path, "deep/dir/x.bin", 40)
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "deep/dir/x.bin", "x.bin")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.OK)
    assert packets(h)[1].data == data
    absolute = str(tmp_path / "deep/dir/x.bin")
    command(h, "SendFile", absolute, "y.bin")
    tick(h)
    h.assert_cmd_response(1, "SendFile", CmdResponse.OK)
    assert StartPacket(0, 40, absolute, "y.bin") in packets(h)


@pytest.mark.parametrize("source", ["/etc/passwd", "../secret.bin", "LINK/secret.bin", "LINKFILE"])
def test_sources_outside_root_are_refused(fprime_harness, tmp_path, source):
    """FS-ROOT-6 (issue #16 finding 6): ``SendFile /etc/passwd``, ``..``, and symbolic links pointing
    outside root are refused: PathRefused (NO_PERMISSION, 3), FileOpenError, EXECUTION_ERROR, and
    no file packet goes out."""
    root = tmp_path / "root"
    root.mkdir()
    (tmp_path / "secret.bin").write_bytes(b"secret")
    (root / "LINK").symlink_to(tmp_path, target_is_directory=True)
    (root / "LINKFILE").symlink_to(tmp_path / "secret.bin")
    _fd, h = make(fprime_harness, root)
    command(h, "SendFile", source, "stolen.bin")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.EXECUTION_ERROR)
    assert h.events_named("PathRefused")[0][:2] == (source, 3)
    assert h.events_named("FileOpenError") == [(source,)]
    assert packets(h) == []


def test_empty_file_is_f_prime_partial_fail_with_validation_error(fprime_harness, tmp_path):
    """F´ v4.0: startOffset 0 >= size 0 — DownlinkPartialFail, STATUS_INVALID, nothing sent."""
    (tmp_path / "empty.bin").write_bytes(b"")
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "empty.bin", "empty.bin")
    assert tick(h) == 0
    h.assert_cmd_response(0, "SendFile", CmdResponse.VALIDATION_ERROR)
    h.assert_event("DownlinkPartialFail", 0, "empty.bin", "empty.bin", 0, 0)
    assert h.tlm_values("PacketsSent") == [] and h.tlm_values("FilesSent") == []


# --- failures -----------------------------------------------------------------------------------------

def test_missing_file_is_file_open_error_and_execution_error(fprime_harness, tmp_path):
    fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "nope.bin", "nope.bin", cmd_seq=3)
    assert tick(h) == 0
    assert responses(h, "SendFile") == [(3, CmdResponse.EXECUTION_ERROR)]
    h.assert_event("FileOpenError", 0, "nope.bin")
    assert h.events[0].severity == Severity.WARNING_HI
    assert h.tlm_values("Warnings") == [1]
    assert not fd.busy


def test_directory_and_unreadable_file_are_file_open_errors(fprime_harness, tmp_path):
    (tmp_path / "adir").mkdir()
    locked = tmp_path / "locked.bin"
    locked.write_bytes(b"secret")
    locked.chmod(0)
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "adir", "adir", cmd_seq=1)
    command(h, "SendFile", "locked.bin", "locked.bin", cmd_seq=2)
    tick(h)
    assert responses(h, "SendFile")[0] == (1, CmdResponse.EXECUTION_ERROR)
    h.assert_event("FileOpenError", 0, "adir")
    if os.name == "posix" and os.geteuid() != 0:    # root reads mode-000 files
        assert responses(h, "SendFile")[1] == (2, CmdResponse.EXECUTION_ERROR)
        h.assert_event("FileOpenError", 1, "locked.bin")
        assert h.tlm_values("Warnings") == [1, 2]


def test_file_that_shrinks_while_sending_is_file_read_error(fprime_harness, tmp_path):
    write(tmp_path, "grow.bin", 500)
    fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "grow.bin", "grow.bin")
    tick(h)                                          # START + 2 DATA
    (tmp_path / "grow.bin").write_bytes(b"short")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.EXECUTION_ERROR)
    h.assert_event("FileReadError", 0, "grow.bin", int(OsFileStatus.BAD_SIZE))
    h.assert_event("SendDataFail", 0, "grow.bin", 200)
    assert h.tlm_values("Warnings") == [1]
    assert not any(isinstance(p, EndPacket) for p in packets(h))
    assert len(packets(h)) == 3 and not fd.busy


def test_file_that_grows_while_sending_is_file_read_error(fprime_harness, tmp_path):
    write(tmp_path, "log.bin", 500)
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "log.bin", "log.bin")
    tick(h)
    with open(tmp_path / "log.bin", "ab") as f:
        f.write(b"more")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.EXECUTION_ERROR)
    h.assert_event("FileReadError", 0, "log.bin", int(OsFileStatus.BAD_SIZE))
    h.assert_event("SendDataFail", 0, "log.bin", 200)


def test_name_too_long_for_start_packet_is_refused_with_event(fprime_harness, tmp_path):
    fd, h = make(fprime_harness, tmp_path)
    long_name = "d/" * 150                           # 300 bytes
    reply = h.invoke("sendFile", long_name, "ok.bin", 0, 0)
    assert reply == SendFileResponse(SendFileStatus.STATUS_INVALID, U32_MAX)
    h.assert_event("FileNameTooLong", 0, long_name[:100], 300, 255)
    reply = h.invoke("sendFile", "ok.bin", "é" * 128, 0, 0)   # 256 bytes of UTF-8
    assert reply.status == SendFileStatus.STATUS_INVALID
    h.assert_event("FileNameTooLong", 1, "é" * 50, 256, 255)
    assert fd.queued == 0 and tick(h) == 0
    # 255 bytes still fit a START packet
    write(tmp_path, "f" * 200, 10)
    assert h.invoke("sendFile", "f" * 200, "g" * 255, 0, 0).status == SendFileStatus.STATUS_OK
    tick(h)
    assert packets(h)[0] == StartPacket(0, 10, "f" * 200, "g" * 255)


def test_command_name_over_string_bound_is_format_error(fprime_harness, tmp_path):
    fd, h = make(fprime_harness, tmp_path)
    name = b"n" * 101
    args = len(name).to_bytes(2, "big") + name + b"\x00\x01x"
    h.send_raw_command(BASE + 0, args)
    h.dispatch_all()
    h.assert_cmd_response(0, "SendFile", CmdResponse.FORMAT_ERROR)
    assert fd.queued == 0


def test_receiver_that_raises_fails_the_transfer_without_escaping(fprime_harness, tmp_path):
    write(tmp_path, "a.bin", 300)
    fd, h = make(fprime_harness, tmp_path)
    calls = []

    def flaky(data):
        calls.append(data)
        if len(calls) == 2:
            raise RuntimeError("link buffer gone")

    h.set_port_handler("bufferSendOut", flaky)
    command(h, "SendFile", "a.bin", "a.bin")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.EXECUTION_ERROR)
    h.assert_event("SendDataFail", 0, "a.bin", 0)
    assert h.tlm_values("PacketsSent") == [1]
    assert not fd.busy
    # contained, and reported (decision 0005)
    assert fd.handler_faults == 1
    assert h.events_named("HandlerFault") == [("bufferSendOut (DataPacket)", "RuntimeError: link buffer gone")]


def test_command_failures_disabled_answers_ok_as_f_prime_default(fprime_harness, tmp_path):
    _fd, h = make(fprime_harness, tmp_path, command_failures_disabled=True)
    command(h, "SendFile", "missing.bin", "m.bin")
    tick(h)
    h.assert_cmd_response(0, "SendFile", CmdResponse.OK)
    h.assert_event("FileOpenError", 0, "missing.bin")


# --- cancel -------------------------------------------------------------------------------------------

def test_cancel_mid_transfer_sends_cancel_packet_and_execution_error(fprime_harness, tmp_path):
    write(tmp_path, "big.bin", 1000)
    fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "big.bin", "big.bin", cmd_seq=1)
    tick(h)                                          # START, DATA 1, DATA 2
    command(h, "Cancel", cmd_seq=2)
    assert responses(h, "Cancel") == [(2, CmdResponse.OK)]
    assert responses(h, "SendFile") == []
    assert tick(h) == 1
    assert packets(h)[-1] == CancelPacket(3)
    assert responses(h, "SendFile") == [(1, CmdResponse.EXECUTION_ERROR)]
    h.assert_event("DownlinkCanceled", 0, "big.bin", "big.bin")
    assert h.tlm_values("FilesSent") == []
    assert not any(isinstance(p, EndPacket) for p in packets(h))
    assert tick(h) == 0 and not fd.busy


def test_cancel_after_last_data_still_ends_the_file_as_f_prime(fprime_harness, tmp_path):
    data = write(tmp_path, "small.bin", 200)         # START, DATA, DATA | END
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "small.bin", "small.bin")
    tick(h)
    command(h, "Cancel")
    tick(h)
    assert packets(h)[-1] == EndPacket(3, cfdp_checksum(data))
    h.assert_cmd_response(1, "SendFile", CmdResponse.OK)
    h.assert_event("FileSent", 0, "small.bin", "small.bin")
    h.assert_no_event("DownlinkCanceled")


def test_cancel_when_idle_is_ok_and_leaves_queued_files(fprime_harness, tmp_path):
    write(tmp_path, "a.bin", 10)
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "Cancel")
    h.assert_cmd_response(0, "Cancel", CmdResponse.OK)
    command(h, "SendFile", "a.bin", "a.bin")
    command(h, "Cancel")                             # nothing is being sent yet
    tick(h)
    h.assert_cmd_response(2, "SendFile", CmdResponse.OK)
    assert h.events_named("DownlinkCanceled") == []


# --- partial downlink ---------------------------------------------------------------------------------

def test_send_partial_inside_the_file_sends_that_range(fprime_harness, tmp_path):
    data = write(tmp_path, "p.bin", 1000)
    _fd, h = make(fprime_harness, tmp_path, packets_per_tick=10)
    command(h, "SendPartial", "p.bin", "p_part.bin", 150, 230)
    tick(h)
    h.assert_cmd_response(0, "SendPartial", CmdResponse.OK)
    h.assert_event("SendStarted", 0, 230, "p.bin", "p_part.bin")
    sent = packets(h)
    assert sent[0] == StartPacket(0, 1000, "p.bin", "p_part.bin")   # F´ announces the whole size
    assert [(p.offset, len(p.data)) for p in sent[1:-1]] == [(150, 100), (250, 100), (350, 30)]
    assert b"".join(p.data for p in sent[1:-1]) == data[150:380]
    expected = CfdpChecksum()
    expected.update(data[150:380], 150)
    assert sent[-1] == EndPacket(4, expected.value)
    h.assert_no_event("DownlinkPartialWarning")


def test_send_partial_with_zero_length_goes_to_the_end(fprime_harness, tmp_path):
    data = write(tmp_path, "p.bin", 260)
    _fd, h = make(fprime_harness, tmp_path, packets_per_tick=10)
    command(h, "SendPartial", "p.bin", "p.bin", 60, 0)
    tick(h)
    h.assert_event("SendStarted", 0, 200, "p.bin", "p.bin")
    assert b"".join(p.data for p in packets(h)[1:-1]) == data[60:]
    h.assert_cmd_response(0, "SendPartial", CmdResponse.OK)


def test_send_partial_overlapping_the_end_warns_and_is_cut(fprime_harness, tmp_path):
    data = write(tmp_path, "p.bin", 1000)
    _fd, h = make(fprime_harness, tmp_path, packets_per_tick=10)
    command(h, "SendPartial", "p.bin", "p.bin", 900, 500)
    tick(h)
    h.assert_event("DownlinkPartialWarning", 0, 900, 500, 1000, "p.bin", "p.bin")
    assert h.events_named("DownlinkPartialWarning") and h.events[0].severity == Severity.WARNING_LO
    h.assert_event("SendStarted", 0, 100, "p.bin", "p.bin")
    assert b"".join(p.data for p in packets(h)[1:-1]) == data[900:]
    h.assert_cmd_response(0, "SendPartial", CmdResponse.OK)


def test_send_partial_beyond_the_end_fails_with_validation_error(fprime_harness, tmp_path):
    write(tmp_path, "p.bin", 1000)
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendPartial", "p.bin", "p.bin", 1000, 10, cmd_seq=4)
    command(h, "SendPartial", "p.bin", "p.bin", U32_MAX, U32_MAX, cmd_seq=5)
    assert tick(h) == 0
    assert responses(h, "SendPartial") == [(4, CmdResponse.VALIDATION_ERROR),
                                           (5, CmdResponse.VALIDATION_ERROR)]
    h.assert_event("DownlinkPartialFail", 0, "p.bin", "p.bin", 1000, 1000)
    h.assert_event("DownlinkPartialFail", 1, "p.bin", "p.bin", U32_MAX, 1000)
    assert h.tlm_values("Warnings") == []


# --- several requests ---------------------------------------------------------------------------------

def test_second_send_file_while_busy_is_queued_and_answered_after_its_own_end(fprime_harness, tmp_path):
    first = write(tmp_path, "one.bin", 250, seed=1)   # 5 packets
    second = write(tmp_path, "two.bin", 120, seed=2)  # 4 packets
    fd, h = make(fprime_harness, tmp_path)
    command(h, "SendFile", "one.bin", "one.bin", cmd_seq=1)
    tick(h)
    command(h, "SendFile", "two.bin", "two.bin", cmd_seq=2)
    assert h.cmd_responses == [] and fd.queued == 1
    assert tick(h) == 3                              # DATA, END of one; START of two
    assert responses(h, "SendFile") == [(1, CmdResponse.OK)]
    assert tick(h) == 3
    assert responses(h, "SendFile") == [(1, CmdResponse.OK), (2, CmdResponse.OK)]
    sent = packets(h)
    assert [type(p).__name__ for p in sent] == ["StartPacket", "DataPacket", "DataPacket", "DataPacket",
                                                "EndPacket", "StartPacket", "DataPacket", "DataPacket",
                                                "EndPacket"]
    assert b"".join(p.data for p in sent[1:4]) == first
    assert sent[5] == StartPacket(0, 120, "two.bin", "two.bin")
    assert b"".join(p.data for p in sent[6:8]) == second
    assert sent[8] == EndPacket(3, cfdp_checksum(second))
    assert h.tlm_values("FilesSent") == [1, 2]


def test_file_queue_full_refuses_with_execution_error(fprime_harness, tmp_path):
    fd, h = make(fprime_harness, tmp_path, file_queue_depth=2)
    for seq in (1, 2, 3):
        command(h, "SendFile", "x.bin", "x.bin", cmd_seq=seq)
    assert responses(h, "SendFile") == [(3, CmdResponse.EXECUTION_ERROR)]
    assert h.invoke("sendFile", "x.bin", "x.bin", 0, 0) == SendFileResponse(SendFileStatus.STATUS_ERROR,
                                                                             U32_MAX)
    assert fd.queued == 2


def test_send_file_port_answers_context_and_reports_completion(fprime_harness, tmp_path):
    data = write(tmp_path, "a.bin", 150)
    _fd, h = make(fprime_harness, tmp_path, packets_per_tick=10)
    assert h.invoke("sendFile", "a.bin", "a.bin", 0, 0) == SendFileResponse(SendFileStatus.STATUS_OK, 0)
    assert h.invoke("sendFile", "gone.bin", "g.bin", 0, 0) == SendFileResponse(SendFileStatus.STATUS_OK, 1)
    assert h.invoke("sendFile", "a.bin", "a.bin", 100, 0) == SendFileResponse(SendFileStatus.STATUS_OK, 2)
    tick(h)
    done = [call.args[0] for call in h.from_port("FileComplete")]
    assert done == [SendFileResponse(SendFileStatus.STATUS_OK, 0),
                    SendFileResponse(SendFileStatus.STATUS_ERROR, 1),
                    SendFileResponse(SendFileStatus.STATUS_OK, 2)]
    assert h.cmd_responses == []
    sent = packets(h)
    assert len(sent) == 7                            # 4 for the whole file, none for the missing one
    assert sent[4:6] == [StartPacket(0, 150, "a.bin", "a.bin"), DataPacket(1, 100, data[100:])]


def test_send_file_port_refuses_bad_arguments(fprime_harness, tmp_path):
    fd, h = make(fprime_harness, tmp_path)
    invalid = SendFileResponse(SendFileStatus.STATUS_INVALID, U32_MAX)
    assert h.invoke("sendFile", b"a.bin", "a.bin", 0, 0) == invalid
    assert h.invoke("sendFile", "a.bin", "\udcff", 0, 0) == invalid
    assert h.invoke("sendFile", "a.bin", "a.bin", -1, 0) == invalid
    assert h.invoke("sendFile", "a.bin", "a.bin", 0, 1 << 32) == invalid
    assert fd.queued == 0


# --- the component itself -----------------------------------------------------------------------------

def test_declarations_match_f_prime_v4(fprime_harness, tmp_path):
    fd = FileDownlink()
    assert fd.name == "fileDownlink"
    assert fd.data_size == DEFAULT_DATA_SIZE == 499 and fd.packets_per_tick == DEFAULT_PACKETS_PER_TICK
    assert fd.root == type(tmp_path)(os.getcwd())
    spec = fd.spec
    assert [(c.name, c.opcode, c.kind, [n for n, _ in c.args]) for c in spec.commands] == [
        ("SendFile", 0, "async", ["sourceFileName", "destFileName"]),
        ("Cancel", 1, "async", []),
        ("SendPartial", 2, "async", ["sourceFileName", "destFileName", "startOffset", "length"]),
    ]
    assert all(t.size == 100 for c in spec.commands for _, t in c.args if t.kind == "string")
    events = {e.name: (e.local_id, e.severity, [n for n, _ in e.args]) for e in spec.own_events}
    assert events == {
        "FileOpenError": (0, Severity.WARNING_HI, ["fileName"]),
        "FileReadError": (1, Severity.WARNING_HI, ["fileName", "status"]),
        "FileSent": (2, Severity.ACTIVITY_HI, ["sourceFileName", "destFileName"]),
        "DownlinkCanceled": (3, Severity.ACTIVITY_HI, ["sourceFileName", "destFileName"]),
        "DownlinkTimeout": (4, Severity.WARNING_HI, ["sourceFileName", "destFileName"]),
        "DownlinkPartialWarning": (5, Severity.WARNING_LO,
                                   ["startOffset", "length", "filesize", "sourceFileName", "destFileName"]),
        "DownlinkPartialFail": (6, Severity.WARNING_HI,
                                ["sourceFileName", "destFileName", "startOffset", "filesize"]),
        "SendDataFail": (7, Severity.WARNING_HI, ["sourceFileName", "byteOffset"]),
        "SendStarted": (8, Severity.ACTIVITY_HI, ["fileSize", "sourceFileName", "destFileName"]),
        "FileNameTooLong": (0x40, Severity.WARNING_HI, ["fileName", "size", "limit"]),
        "PathRefused": (0x41, Severity.WARNING_HI, ["fileName", "status", "reason"]),
    }
    assert [(c.name, c.local_id, c.type.name) for c in spec.own_channels] == [
        ("FilesSent", 0, "U32"), ("PacketsSent", 1, "U32"), ("Warnings", 2, "U32")]
    assert set(spec.inputs) >= {"Run", "sendFile", "pingIn"}
    assert set(spec.outputs) >= {"bufferSendOut", "FileComplete", "pingOut"}


def test_text_events_use_f_prime_formats(fprime_harness, tmp_path):
    write(tmp_path, "p.bin", 100)
    _fd, h = make(fprime_harness, tmp_path)
    command(h, "SendPartial", "p.bin", "q.bin", 50, 80)
    tick(h)
    texts = [t.text for t in h.text_events]
    assert texts[0] == ("(fileDownlink) DownlinkPartialWarning: Offset 50 plus length 80 is greater than "
                        "source size 100 for partial downlink of file p.bin to file q.bin. ")
    assert texts[1] == "(fileDownlink) SendStarted: Downlink of 50 bytes started from p.bin to q.bin"


def test_constructor_rejects_bad_budgets(tmp_path):
    for kwargs in ({"packets_per_tick": 0}, {"data_size": 0}, {"data_size": 65536},
                   {"file_queue_depth": 0}, {"packets_per_tick": 1.5}):
        with pytest.raises(ValueError):
            FileDownlink(root=tmp_path, **kwargs)


def test_unconnected_buffer_send_out_keeps_requests_queued(fprime_harness, tmp_path, caplog):
    write(tmp_path, "a.bin", 10)
    fd = FileDownlink(root=tmp_path)
    h = fprime_harness(fd, unconnected=("bufferSendOut",))
    with caplog.at_level(logging.WARNING, logger="fprime_lite"):
        h.invoke("Run", 0)
        h.dispatch_all()
        assert caplog.records == []  # nothing to send: nothing to warn about
        command(h, "SendFile", "a.bin", "a.bin")
        for _ in range(2):
            h.invoke("Run", 0)
            h.dispatch_all()
    assert fd.queued == 1 and h.cmd_responses == [] and fd.handler_faults == 0
    assert [r.getMessage() for r in caplog.records] == [
        "fileDownlink: bufferSendOut is not connected; file requests stay queued"]  # once


def test_ping_is_answered_with_its_key(fprime_harness, tmp_path):
    _fd, h = make(fprime_harness, tmp_path)
    h.invoke("pingIn", 0xC0FFEE)
    h.dispatch_all()
    h.assert_from_port("pingOut", 0, 0xC0FFEE)


def test_fprime_gds_encodes_commands_and_decodes_events_and_channels_by_our_declarations(tmp_path,
                                                                                          monkeypatch):
    """A dictionary built from the declarations (as the svc fixture is) lets the GDS command the
    component and decode its events (with F´'s texts) and channels."""
    pytest.importorskip("fprime_gds")
    import importlib.util
    import pathlib
    import sys

    from fprime_gds.common.data_types.cmd_data import CmdData
    from fprime_gds.common.decoders.ch_decoder import ChDecoder
    from fprime_gds.common.decoders.event_decoder import EventDecoder
    from fprime_gds.common.encoders.cmd_encoder import CmdEncoder
    from fprime_gds.common.models.dictionaries import Dictionaries

    from fprime_lite.wire.packets import decode_command, encode_event, encode_telemetry

    maker = pathlib.Path(__file__).parents[2] / "data" / "svc" / "make_svc_dictionary.py"
    spec = importlib.util.spec_from_file_location("_file_downlink_dictionary", maker)
    gen = importlib.util.module_from_spec(spec)
    monkeypatch.setitem(sys.modules, spec.name, gen)
    spec.loader.exec_module(gen)
    monkeypatch.setattr(gen, "INSTANCES", [("FileHandling.fileDownlink", FileDownlink, BASE)])
    dictionary = tmp_path / "dictionary.json"
    dictionary.write_text(gen.render())
    gds = Dictionaries.load_dictionaries_into_config(str(dictionary))

    data = write(tmp_path, "p.bin", 1000)
    fd = FileDownlink(base_id=BASE, root=tmp_path)
    events, channels, answers, sent = [], [], [], []
    fd.output_port("logOut").connect_callable(0, lambda i, t, s, a: events.append(encode_event(i, t, a)), "gds")
    fd.output_port("tlmOut").connect_callable(0, lambda i, t, v: channels.append(encode_telemetry([(i, t, v)])),
                                              "gds")
    fd.output_port("cmdResponseOut").connect_callable(0, lambda *a: answers.append(a), "cmdDisp")
    fd.output_port("bufferSendOut").connect_callable(0, sent.append, "link")

    template = gds.command_name["FileHandling.fileDownlink.SendPartial"]
    assert template.get_op_code() == BASE + 2
    ground = CmdEncoder().encode_api(CmdData(["p.bin", "down/p.bin", "900", "500"], template))
    opcode, args = decode_command(ground[8:])
    fd.input_port("cmdIn").entries[0](opcode, 11, args)
    fd.dispatch_all()
    fd.input_port("Run").entries[0](0)
    fd.dispatch_all()
    assert answers == [(BASE + 2, 11, CmdResponse.OK)]
    assert len(sent) == 3                            # START, one 100-byte DATA (of <= 499), END
    assert decode_file_packet(sent[1], descriptor=True) == DataPacket(1, 900, data[900:])

    decoded = [EventDecoder(gds.event_id).decode_api(p[2:])[0] for p in events]
    assert [e.get_template().get_full_name() for e in decoded] == [
        "FileHandling.fileDownlink.DownlinkPartialWarning", "FileHandling.fileDownlink.SendStarted",
        "FileHandling.fileDownlink.FileSent"]
    assert [a.val for a in decoded[0].get_args()] == [900, 500, 1000, "p.bin", "down/p.bin"]
    assert decoded[0].get_str().split(" : ", 1)[1] == (
        "Offset 900 plus length 500 is greater than source size 1000 for partial downlink of file "
        "p.bin to file down/p.bin. ")
    assert decoded[2].get_str().split(" : ", 1)[1] == "Sent file p.bin to file down/p.bin"
    values = {}
    for packet in channels:
        for ch in ChDecoder(gds.channel_id).decode_api(packet[2:]):
            values[ch.get_template().get_full_name()] = ch.get_val()
    assert values == {"FileHandling.fileDownlink.PacketsSent": 3, "FileHandling.fileDownlink.FilesSent": 1}
