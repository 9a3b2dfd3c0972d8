"""FileUplink: reassembling uplinked files, F´'s warnings and counters, atomic replacement.

Every test writes inside its own ``tmp_path`` (the component's ``root``); the fuzz test only lets
relative destination names through.
"""

import errno
import os
import pathlib
import random
import stat
import tempfile

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fprime_lite import Severity
from fprime_lite.wire.file_packet import (CancelPacket, DataPacket, EndPacket, StartPacket, cfdp_checksum,
                                     decode_file_packet, encode_file_packet)
from fprime_lite.svc.file_uplink import FileUplink, ReceiveMode
from fprime_lite.testing import ComponentHarness

BASE = 0x500


def enc(packet) -> bytes:
    """A file packet as the ground link hands it over: without its descriptor."""
    return encode_file_packet(packet, descriptor=False)


def file_packets(content: bytes, destination: str, chunk: int = 100, *, checksum=None, first_seq=0):
    """START, DATA…, END for ``content``, with the GDS's sequence numbering (START 0, DATA 1…)."""
    seq = first_seq
    packets = [StartPacket(seq, len(content), "ground/" + os.path.basename(destination), destination)]
    for offset in range(0, len(content), chunk):
        seq += 1
        packets.append(DataPacket(seq, offset, content[offset:offset + chunk]))
    seq += 1
    packets.append(EndPacket(seq, cfdp_checksum(content) if checksum is None else checksum))
    return packets


def make(fprime_harness, root, *, overwrite=True, **kwargs):
    """Most tests replace existing files, as F´ always does: overwrite on unless a test says so."""
    return fprime_harness(FileUplink(base_id=BASE, root=root, overwrite=overwrite), **kwargs)


def send(h, *packets):
    """Queue each packet (objects are encoded, bytes go as they are) and handle them all."""
    for p in packets:
        h.invoke("bufferSendIn", p if isinstance(p, (bytes, bytearray)) else enc(p))
    h.dispatch_all()


def warnings_logged(h):
    return [e.name for e in h.events if e.severity is Severity.WARNING_HI]


def content(n: int, seed: int = 1) -> bytes:
    return random.Random(seed).randbytes(n)


# --- the nominal path ------------------------------------------------------------------------------

def test_whole_file_in_several_data_packets_arrives_byte_identical(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    data = content(1037)
    packets = file_packets(data, "image.bin", chunk=300)  # 4 DATA packets, the last one short
    send(h, *packets)
    assert (tmp_path / "image.bin").read_bytes() == data
    assert os.listdir(tmp_path) == ["image.bin"]  # no temporary file left
    h.assert_event("FileReceived", 0, "image.bin")
    h.assert_events_size(1)
    h.assert_tlm_count("FilesReceived", 1)
    h.assert_tlm("FilesReceived", 0, 1)
    assert h.tlm_values("PacketsReceived") == list(range(1, len(packets) + 1))
    h.assert_tlm_count("Warnings", 0)
    h.assert_tlm_count("FilesReceivedFailed", 0)
    h.assert_from_port("fileAnnounce", 0, str(tmp_path / "image.bin"))
    assert h.component.receive_mode is ReceiveMode.START


def test_received_file_counts_and_event_ids(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    first, second = file_packets(b"alpha" * 50, "a.txt"), file_packets(b"beta" * 10, "b.txt", chunk=7)
    send(h, *first, *second)
    assert h.tlm_values("FilesReceived") == [1, 2]
    assert h.tlm_values("PacketsReceived") == list(range(1, len(first) + len(second) + 1))
    assert [(e.name, e.id) for e in h.events] == [("FileReceived", BASE + 2), ("FileReceived", BASE + 2)]
    assert [t.id for t in h.tlm_named("FilesReceived")] == [BASE + 0, BASE + 0]
    assert (tmp_path / "a.txt").read_bytes() == b"alpha" * 50
    assert (tmp_path / "b.txt").read_bytes() == b"beta" * 10


def test_empty_file_start_then_end(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, StartPacket(0, 0, "src", "empty.dat"), EndPacket(1, 0))
    assert (tmp_path / "empty.dat").read_bytes() == b""
    h.assert_event("FileReceived", 0, "empty.dat")
    assert h.tlm_values("FilesReceived") == [1]
    h.assert_tlm_count("Warnings", 0)


def test_relative_path_resolves_under_root_and_absolute_path_inside_root_is_accepted(fprime_harness, tmp_path,
                                                                                       monkeypatch):
    """FS-ROOT-1: a relative destination lands under root, an absolute one inside root is accepted; the
    working directory plays no part."""
    root = tmp_path / "root"
    (root / "seq").mkdir(parents=True)
    elsewhere = tmp_path / "cwd"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)  # the working directory plays no part once the root is given
    h = make(fprime_harness, root)
    send(h, *file_packets(b"relative", "seq/run.seq"))
    send(h, *file_packets(b"absolute", str(root / "abs.bin")))
    assert (root / "seq" / "run.seq").read_bytes() == b"relative"
    assert (root / "abs.bin").read_bytes() == b"absolute"
    assert os.listdir(elsewhere) == []
    assert [c.args[0] for c in h.from_port("fileAnnounce")] == [str(root / "seq" / "run.seq"),
                                                                str(root / "abs.bin")]


@pytest.mark.parametrize("destination", ["../../traversal_rel.txt", "../outside.txt", "seq/../../outside.txt",
                                         "ABSOLUTE", "LINK/escaped.txt", "LINK/../../outside/x.txt"])
def test_destinations_outside_root_are_refused(fprime_harness, tmp_path, destination):
    """FS-ROOT-2 (issue #16 finding 6): ``..``, an absolute path outside root and symbolic-link escapes
    are refused: PathRefused with Os::File NO_PERMISSION (3), FileOpenError, START mode, nothing
    written outside root, and the next file inside root still lands."""
    root = tmp_path / "a" / "root"
    (root / "seq").mkdir(parents=True)
    outside = tmp_path / "outside"
    outside.mkdir()
    (root / "LINK").symlink_to(outside, target_is_directory=True)
    (root / "LINKFILE").symlink_to(outside / "target.txt")
    destination = destination.replace("ABSOLUTE", str(outside / "abs.txt"))
    before = sorted(p.name for p in tmp_path.rglob("*"))
    h = make(fprime_harness, root, overwrite=True)
    send(h, *file_packets(b"hostile", destination))
    assert h.events_named("PathRefused")[0][1] == 3
    assert h.events_named("FileOpenError")
    assert h.component.receive_mode == ReceiveMode.START
    assert sorted(p.name for p in tmp_path.rglob("*")) == before
    send(h, *file_packets(b"fine", "seq/ok.bin"))
    assert (root / "seq" / "ok.bin").read_bytes() == b"fine"


def test_in_place_writes_into_the_existing_file_a_reader_holds_open(fprime_harness, tmp_path):
    """FS-ROOT-5: with ``in_place`` (run --file-root, F´'s FileHandling suite) a file received whole is
    written into the existing destination, so a reader holding it open sees the new bytes, as with
    F´'s in-place write; without it the replace is atomic and the reader keeps the old file. A bad
    checksum leaves the destination untouched either way."""
    for in_place, seen in ((True, b"new content"), (False, b"")):
        folder = tmp_path / str(in_place)
        folder.mkdir()
        (folder / "out.txt").write_bytes(b"")
        h = make(fprime_harness, folder)
        h.component.in_place = in_place
        with open(folder / "out.txt", "rb") as reader:
            send(h, *file_packets(b"new content", "out.txt"))
            assert reader.read() == seen
        assert (folder / "out.txt").read_bytes() == b"new content"
        assert sorted(p.name for p in folder.iterdir()) == ["out.txt"]  # no temporary file left
        send(h, *file_packets(b"corrupt", "out.txt", checksum=1))
        assert (folder / "out.txt").read_bytes() == b"new content"


def test_a_link_at_the_destination_is_replaced_never_written_through(fprime_harness, tmp_path):
    """FS-ROOT-2b: a symbolic link inside root pointing outside is itself replaced (overwrite on); the
    file it points to outside root is never created or written."""
    outside = tmp_path / "outside"
    outside.mkdir()
    root = tmp_path / "root"
    root.mkdir()
    (root / "LINKFILE").symlink_to(outside / "target.txt")
    h = make(fprime_harness, root, overwrite=True)
    send(h, *file_packets(b"data", "LINKFILE"))
    assert not (outside / "target.txt").exists()
    assert not (root / "LINKFILE").is_symlink() and (root / "LINKFILE").read_bytes() == b"data"


def test_an_existing_file_is_replaced_only_when_overwrite_is_on(fprime_harness, tmp_path):
    """FS-ROOT-3: with the default overwrite=False an existing destination is refused (PathRefused with
    FILE_EXISTS, 6) and kept byte-for-byte; with overwrite=True it is replaced."""
    (tmp_path / "conf.ini").write_bytes(b"old")
    h = fprime_harness(FileUplink(base_id=BASE, root=tmp_path))
    send(h, *file_packets(b"new", "conf.ini"))
    assert h.events_named("PathRefused") == [("conf.ini", 6, "exists; overwrite is off")]
    assert (tmp_path / "conf.ini").read_bytes() == b"old"
    send(h, *file_packets(b"fresh", "fresh.ini"))  # a new file is fine
    assert (tmp_path / "fresh.ini").read_bytes() == b"fresh"
    h2 = make(fprime_harness, tmp_path, overwrite=True)
    send(h2, *file_packets(b"new", "conf.ini"))
    assert (tmp_path / "conf.ini").read_bytes() == b"new"


def test_the_runner_default_root_applies_only_without_an_explicit_root(tmp_path):
    """FS-ROOT-4: set_default_root (the run's folder) replaces the working-directory default but never a
    root given at construction."""
    run = tmp_path / "run"
    given = FileUplink(root=tmp_path / "given")
    default = FileUplink()
    given.set_default_root(run)
    default.set_default_root(run)
    assert given.root == str(tmp_path / "given") and default.root == str(run)


def test_default_root_is_the_working_directory_at_construction(fprime_harness, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    h = fprime_harness(FileUplink())
    assert h.component.name == "fileUplink" and h.component.root == str(tmp_path)
    (tmp_path / "later").mkdir()
    monkeypatch.chdir(tmp_path / "later")  # changing directory afterwards does not move the root
    send(h, *file_packets(b"x", "here.txt"))
    assert (tmp_path / "here.txt").read_bytes() == b"x"


def test_replacing_a_file_keeps_its_permissions(fprime_harness, tmp_path):
    target = tmp_path / "conf.ini"
    target.write_bytes(b"old contents that are longer than the new ones")
    target.chmod(0o640)
    h = make(fprime_harness, tmp_path)
    send(h, *file_packets(b"new", "conf.ini"))
    assert target.read_bytes() == b"new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_data_goes_to_a_temporary_file_until_end(fprime_harness, tmp_path):
    target = tmp_path / "table.bin"
    target.write_bytes(b"previous")
    h = make(fprime_harness, tmp_path)
    packets = file_packets(content(500), "table.bin", chunk=200)
    send(h, *packets[:-1])
    temp = h.component.temporary_path
    assert temp is not None and os.path.dirname(temp) == str(tmp_path) and os.path.exists(temp)
    assert target.read_bytes() == b"previous"  # untouched while the transfer runs
    send(h, packets[-1])
    assert target.read_bytes() == content(500) and not os.path.exists(temp)
    assert h.component.temporary_path is None


# --- failures that must leave the destination alone -------------------------------------------------

def test_bad_checksum_is_reported_and_leaves_existing_destination_untouched(fprime_harness, tmp_path):
    target = tmp_path / "app.bin"
    target.write_bytes(b"flight-proven version")
    h = make(fprime_harness, tmp_path)
    data = content(700)
    good = cfdp_checksum(data)
    send(h, *file_packets(data, "app.bin", checksum=good ^ 0x1))
    assert target.read_bytes() == b"flight-proven version"
    assert os.listdir(tmp_path) == ["app.bin"]
    h.assert_event("BadChecksum", 0, "app.bin", good, good ^ 0x1)
    h.assert_no_event("FileReceived")
    h.assert_tlm_count("FilesReceived", 0)
    assert h.tlm_values("FilesReceivedFailed") == [1]
    assert h.tlm_values("Warnings") == [1]
    h.assert_from_port_size("fileAnnounce", 0)
    text = [t.text for t in h.text_events]
    expected = (f"(fileUplink) BadChecksum: Bad checksum value during receipt of file app.bin: "
                f"computed 0x{good:x}, read 0x{good ^ 1:x}")
    assert text == [expected]
    assert h.component.receive_mode is ReceiveMode.START


def test_bad_checksum_for_a_new_file_creates_nothing(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, *file_packets(b"payload", "new.bin", checksum=0))
    assert os.listdir(tmp_path) == []
    assert h.tlm_values("FilesReceivedFailed") == [1]


def test_cancel_mid_transfer_discards_the_partial_file(fprime_harness, tmp_path):
    target = tmp_path / "seq.bin"
    target.write_bytes(b"keep me")
    h = make(fprime_harness, tmp_path)
    packets = file_packets(content(400), "seq.bin", chunk=100)
    send(h, *packets[:3], CancelPacket(3))
    h.assert_event("UplinkCanceled", 0)
    assert [e.name for e in h.events] == ["UplinkCanceled"]
    assert target.read_bytes() == b"keep me" and os.listdir(tmp_path) == ["seq.bin"]
    assert h.tlm_values("PacketsReceived") == [1, 2, 3, 4]
    h.assert_tlm_count("Warnings", 0)
    # The uplink is ready for the next file; a stray END after the cancel is a receive-mode warning.
    send(h, packets[-1])
    h.assert_event("InvalidReceiveMode", 0, 2, 0)
    send(h, *file_packets(b"second try", "seq.bin"))
    assert target.read_bytes() == b"second try"


def test_cancel_in_start_mode_is_logged(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, CancelPacket(0))
    h.assert_event("UplinkCanceled", 0)
    assert h.tlm_values("PacketsReceived") == [1]
    h.assert_tlm_count("Warnings", 0)


def test_new_start_mid_transfer_abandons_the_first_file(fprime_harness, tmp_path):
    (tmp_path / "first.bin").write_bytes(b"original")
    h = make(fprime_harness, tmp_path)
    first = file_packets(content(300), "first.bin")
    second = file_packets(b"the second file", "second.bin")
    send(h, *first[:2], *second)
    h.assert_event("InvalidReceiveMode", 0, 0, 1)  # START received in DATA mode
    assert (tmp_path / "first.bin").read_bytes() == b"original"
    assert (tmp_path / "second.bin").read_bytes() == b"the second file"
    assert sorted(os.listdir(tmp_path)) == ["first.bin", "second.bin"]
    h.assert_event("FileReceived", 0, "second.bin")
    assert h.tlm_values("Warnings") == [1]


def test_write_error_deletes_the_temporary_file_and_fails_the_file(fprime_harness, tmp_path, monkeypatch):
    target = tmp_path / "big.bin"
    target.write_bytes(b"old")
    h = make(fprime_harness, tmp_path)
    data = content(300)
    packets = file_packets(data, "big.bin", chunk=100)
    send(h, *packets[:2])
    temp = h.component.temporary_path

    def disk_full(fd, data, offset):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "pwrite", disk_full)
    send(h, packets[2])
    monkeypatch.undo()
    h.assert_event("FileWriteError", 0, "big.bin")
    assert not os.path.exists(temp) and os.listdir(tmp_path) == ["big.bin"]
    send(h, *packets[3:])  # the rest of the file is not written; END fails it (checksum differs)
    assert target.read_bytes() == b"old" and os.listdir(tmp_path) == ["big.bin"]
    h.assert_no_event("FileReceived")
    assert h.tlm_values("FilesReceivedFailed") == [1]
    h.assert_event_count("BadChecksum", 1)
    h.assert_event_count("FileWriteError", 1)
    assert h.tlm_values("Warnings") == [1, 2]  # FileWriteError, BadChecksum
    assert h.tlm_values("PacketsReceived") == list(range(1, len(packets) + 1))


def test_write_error_with_matching_checksum_still_fails_the_file(fprime_harness, tmp_path, monkeypatch):
    """A failed chunk of zeros leaves the CFDP checksum unchanged: the file is still refused."""
    h = make(fprime_harness, tmp_path)
    data = b"\x00" * 100 + b"tail"
    packets = file_packets(data, "zeros.bin", chunk=100)
    send(h, packets[0])
    monkeypatch.setattr(os, "pwrite", lambda fd, data, offset: (_ for _ in ()).throw(OSError(errno.EIO, "I/O")))
    send(h, packets[1])
    monkeypatch.undo()
    send(h, *packets[2:])
    assert os.listdir(tmp_path) == []
    h.assert_no_event("BadChecksum")
    h.assert_no_event("FileReceived")
    assert h.tlm_values("FilesReceivedFailed") == [1]


def test_failure_to_put_the_file_in_place_is_a_write_error(fprime_harness, tmp_path, monkeypatch):
    target = tmp_path / "t.bin"
    target.write_bytes(b"old")
    h = make(fprime_harness, tmp_path)

    def refuse(src, dst):
        raise OSError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(os, "replace", refuse)
    send(h, *file_packets(b"new", "t.bin"))
    monkeypatch.undo()
    h.assert_event("FileWriteError", 0, "t.bin")
    h.assert_no_event("FileReceived")
    assert target.read_bytes() == b"old" and os.listdir(tmp_path) == ["t.bin"]
    assert h.tlm_values("FilesReceivedFailed") == [1]


# --- receive modes and sequence indices ------------------------------------------------------------

def test_data_and_end_before_start_are_invalid_receive_mode(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, DataPacket(1, 0, b"orphan"), EndPacket(2, cfdp_checksum(b"orphan")))
    h.assert_event("InvalidReceiveMode", 0, 1, 0)  # DATA (1) in START mode (0)
    h.assert_event("InvalidReceiveMode", 1, 2, 0)  # END (2) in START mode
    assert h.tlm_values("Warnings") == [1, 2]
    assert h.tlm_values("PacketsReceived") == [1, 2]
    h.assert_tlm_count("FilesReceived", 0)
    assert os.listdir(tmp_path) == []


def test_invalid_receive_mode_is_throttled_but_counted_and_start_rearms_it(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, *[DataPacket(i, 0, b"x") for i in range(7)])
    h.assert_event_count("InvalidReceiveMode", 5)  # throttle 5
    assert h.tlm_values("Warnings") == list(range(1, 8))
    send(h, StartPacket(0, 1, "s", "one.bin"), StartPacket(0, 1, "s", "two.bin"))
    h.assert_event_count("InvalidReceiveMode", 6)  # the second START's warning gets through
    assert h.events[-1].args == (0, 1)


def test_out_of_order_packet_is_warned_and_still_written(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    data = b"0123456789" * 3
    send(h, StartPacket(0, 30, "s", "ooo.bin"), DataPacket(1, 0, data[:10]), DataPacket(3, 20, data[20:]),
         DataPacket(2, 10, data[10:20]), EndPacket(4, cfdp_checksum(data)))
    assert h.events_named("PacketOutOfOrder") == [(3, 1), (2, 3), (4, 2)]
    assert (tmp_path / "ooo.bin").read_bytes() == data  # offsets, not indices, place the bytes
    h.assert_event("FileReceived", 0, "ooo.bin")
    assert h.tlm_values("Warnings") == [1, 2, 3]


def test_duplicate_of_the_last_packet_is_skipped(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    data = b"abcdefgh" * 8
    send(h, StartPacket(0, 64, "s", "dup.bin"), DataPacket(1, 0, data[:32]), DataPacket(1, 0, data[:32]),
         DataPacket(2, 32, data[32:]), EndPacket(3, cfdp_checksum(data)))
    h.assert_event("PacketDuplicate", 0, 1)
    h.assert_no_event("PacketOutOfOrder")
    h.assert_no_event("BadChecksum")  # the repeat was not added to the checksum twice
    assert (tmp_path / "dup.bin").read_bytes() == data
    assert h.tlm_values("Warnings") == [1]
    assert h.tlm_values("PacketsReceived") == [1, 2, 3, 4, 5]


def test_repeat_of_an_earlier_packet_is_out_of_order_and_spoils_the_checksum(fprime_harness, tmp_path):
    """Only a repeat of the *last* packet is a duplicate (F´): an older one is written again."""
    (tmp_path / "rep.bin").write_bytes(b"before")
    h = make(fprime_harness, tmp_path)
    data = b"A" * 10 + b"B" * 10
    send(h, StartPacket(0, 20, "s", "rep.bin"), DataPacket(1, 0, data[:10]), DataPacket(2, 10, data[10:]),
         DataPacket(1, 0, data[:10]), EndPacket(3, cfdp_checksum(data)))
    assert h.events_named("PacketOutOfOrder") == [(1, 2), (3, 1)]
    h.assert_no_event("PacketDuplicate")
    h.assert_event_count("BadChecksum", 1)
    assert (tmp_path / "rep.bin").read_bytes() == b"before"


def test_first_data_packet_repeating_the_start_index_is_out_of_order_not_duplicate(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, StartPacket(0, 4, "s", "z.bin"), DataPacket(0, 0, b"abcd"), EndPacket(1, cfdp_checksum(b"abcd")))
    assert h.events_named("PacketOutOfOrder") == [(0, 0)]
    h.assert_no_event("PacketDuplicate")
    assert (tmp_path / "z.bin").read_bytes() == b"abcd"


def test_packet_out_of_bounds_is_not_written(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, StartPacket(0, 10, "s", "b.bin"), DataPacket(1, 0, b"01234567"), DataPacket(2, 8, b"89AB"),
         DataPacket(3, 0xFFFFFFFF, b"z"), EndPacket(4, cfdp_checksum(b"01234567")))
    assert h.events_named("PacketOutOfBounds") == [(2, "b.bin"), (3, "b.bin")]
    h.assert_no_event("PacketOutOfOrder")  # the refused packets still advanced the index
    assert (tmp_path / "b.bin").read_bytes() == b"01234567"
    h.assert_event("FileReceived", 0, "b.bin")
    assert h.tlm_values("Warnings") == [1, 2]


def test_destination_in_a_missing_directory_is_file_open_error(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    packets = file_packets(b"data", "no/such/dir/f.bin")
    send(h, *packets)
    h.assert_event("FileOpenError", 0, "no/such/dir/f.bin")
    assert h.component.receive_mode is ReceiveMode.START
    # The rest of the file finds the component in START mode, as in F´.
    assert h.events_named("InvalidReceiveMode") == [(1, 0), (2, 0)]
    assert h.tlm_values("Warnings") == [1, 2, 3]
    assert os.listdir(tmp_path) == []  # no directory was created


def test_destination_that_is_a_directory_or_empty_is_file_open_error(fprime_harness, tmp_path):
    (tmp_path / "adir").mkdir()
    h = make(fprime_harness, tmp_path)
    send(h, StartPacket(0, 1, "s", "adir"), StartPacket(0, 1, "s", ""))
    assert h.events_named("FileOpenError") == [("adir",), ("",)]
    assert os.listdir(tmp_path) == ["adir"] and os.listdir(tmp_path / "adir") == []


def test_long_file_names_are_cut_to_the_event_bound(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    name = "é" * 25 + ".bin"  # 54 bytes in UTF-8
    send(h, *file_packets(b"x", name))
    assert (tmp_path / name).read_bytes() == b"x"
    (logged,) = h.events_named("FileReceived")[0]
    assert logged == "é" * 20 and len(logged.encode()) == 40


# --- malformed input -------------------------------------------------------------------------------

@pytest.mark.parametrize("raw, status", [
    (b"", 3),                                                      # nothing at all
    (b"\x01\x00\x00", 3),                                          # shorter than a header
    (b"\x00\x00\x00\x00\x00\x00\x00", 3),                          # START without its size
    (b"\x07\x00\x00\x00\x01", 6),                                  # unknown packet type
    (b"\xff\x00\x00\x00\x01\x00", 6),                              # F´'s T_NONE
    (enc(DataPacket(1, 0, b"abcd"))[:-1], 5),                      # DATA shorter than it says
    (enc(DataPacket(1, 0, b"abcd")) + b"!", 5),                    # DATA longer than it says
    (enc(StartPacket(0, 4, "s", "d"))[:-1] + b"\xff", 4),         # destination not UTF-8
], ids=["empty", "short-header", "short-start", "type-7", "type-255", "data-short", "data-long", "utf8"])
def test_bytes_that_are_not_a_file_packet_are_decode_errors(fprime_harness, tmp_path, raw, status):
    h = make(fprime_harness, tmp_path)
    send(h, raw)
    h.assert_event("DecodeError", 0, status)
    h.assert_events_size(1)
    h.assert_tlm_size(0)  # neither a packet received nor a warning, as in F´


def test_something_other_than_bytes_is_an_invalid_packet(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    h.invoke("bufferSendIn", None)
    h.invoke("bufferSendIn", 12)
    h.dispatch_all()
    assert h.events_named("InvalidPacketReceived") == [(0xFF,), (0xFF,)]
    assert h.component.internal_errors == 0


SAFE_NAMES = ["f0.bin", "f1.bin", "sub/f2.bin", "missing/f3.bin", "sub", ""]

_packet = st.one_of(
    st.builds(StartPacket, st.integers(0, 3), st.integers(0, 64), st.just("src"), st.sampled_from(SAFE_NAMES)),
    st.builds(DataPacket, st.integers(0, 6), st.integers(0, 80), st.binary(max_size=24)),
    st.builds(EndPacket, st.integers(0, 6), st.integers(0, 0xFFFFFFFF)),
    st.builds(CancelPacket, st.integers(0, 6)),
).map(enc)


def _safe_raw(raw: bytes) -> bool:
    """Random bytes may decode as a START: only relative names without '..' stay inside the root."""
    packet = decode_file_packet(raw)
    if not isinstance(packet, StartPacket):
        return True
    d = packet.destination
    return not os.path.isabs(d) and ".." not in d and "\\" not in d and len(d) < 100


_buffer = st.one_of(_packet, _packet.map(lambda b: b[:len(b) // 2]), st.binary(max_size=40).filter(_safe_raw))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(buffers=st.lists(_buffer, max_size=12))
def test_fuzz_malformed_and_shuffled_packets_never_raise(tmp_path, buffers):
    root = pathlib.Path(tempfile.mkdtemp(dir=tmp_path))
    (root / "sub").mkdir()
    h = ComponentHarness(FileUplink(base_id=BASE, root=root))
    try:
        for raw in buffers:
            h.invoke("bufferSendIn", raw)
        h.dispatch_all()
        comp = h.component
        assert comp.internal_errors == 0 and comp.handler_faults == 0
        warnings = h.tlm_values("Warnings")
        assert warnings == list(range(1, len(warnings) + 1))
        send(h, CancelPacket(0))  # abandons whatever is in progress
        leftovers = [n for _, _, files in os.walk(root) for n in files if n.endswith(".part")]
        assert leftovers == []
    finally:
        h.close()


def test_unexpected_error_in_a_handler_is_contained(fprime_harness, tmp_path, monkeypatch, caplog):
    h = make(fprime_harness, tmp_path)
    packets = file_packets(b"0123456789", "c.bin", chunk=5)
    send(h, *packets[:2])
    temp = h.component.temporary_path

    def broken(sequence):
        raise RuntimeError("bug")

    monkeypatch.setattr(h.component, "_check_sequence", broken)
    send(h, packets[2])  # does not raise out of the port
    assert h.component.internal_errors == 1 and "bug" in caplog.text
    assert h.component.receive_mode is ReceiveMode.START and not os.path.exists(temp)
    assert os.listdir(tmp_path) == []


def test_discard_deletes_the_temporary_file(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    send(h, *file_packets(b"abc", "d.bin")[:2])
    assert len(os.listdir(tmp_path)) == 1 and h.component.last_sequence_index == 1
    h.component.discard()
    assert os.listdir(tmp_path) == [] and h.component.receive_mode is ReceiveMode.START


# --- ping, declarations ----------------------------------------------------------------------------

def test_ping_is_answered_with_the_same_key(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path)
    h.invoke("pingIn", 1234)
    h.dispatch_all()
    h.assert_from_port("pingOut", 0, 1234)


def test_unconnected_announce_and_ping_are_fine(fprime_harness, tmp_path):
    h = make(fprime_harness, tmp_path, unconnected=("fileAnnounce", "pingOut"))
    send(h, *file_packets(b"quiet", "q.bin"))
    h.invoke("pingIn", 1)
    h.dispatch_all()
    assert (tmp_path / "q.bin").read_bytes() == b"quiet"


def test_declarations_match_fprime():
    expected_events = {
        "BadChecksum": (0, Severity.WARNING_HI, None, [("fileName", "string", 40), ("computed", "U32", None),
                                                       ("read", "U32", None)]),
        "FileOpenError": (1, Severity.WARNING_HI, None, [("fileName", "string", 40)]),
        "FileReceived": (2, Severity.ACTIVITY_HI, None, [("fileName", "string", 40)]),
        "FileWriteError": (3, Severity.WARNING_HI, 5, [("fileName", "string", 40)]),
        "InvalidReceiveMode": (4, Severity.WARNING_HI, 5, [("packetType", "FwPacketDescriptorType", None),
                                                           ("mode", "U32", None)]),
        "PacketOutOfBounds": (5, Severity.WARNING_HI, 5, [("packetIndex", "U32", None),
                                                          ("fileName", "string", 40)]),
        "PacketOutOfOrder": (6, Severity.WARNING_HI, 20, [("packetIndex", "U32", None),
                                                          ("lastPacketIndex", "U32", None)]),
        "PacketDuplicate": (7, Severity.WARNING_HI, 20, [("packetIndex", "U32", None)]),
        "UplinkCanceled": (8, Severity.ACTIVITY_HI, None, []),
        "DecodeError": (9, Severity.WARNING_HI, None, [("status", "I32", None)]),
        "InvalidPacketReceived": (10, Severity.WARNING_HI, None, [("packetType", "FwPacketDescriptorType", None)]),
        "PathRefused": (0x40, Severity.WARNING_HI, None, [("fileName", "string", 40), ("status", "I32", None),
                                                          ("reason", "string", 40)]),  # not in F´
    }
    comp = FileUplink(root=".")
    for name, (local_id, severity, throttle, args) in expected_events.items():
        decl = comp.spec.event(name)
        assert (decl.local_id, decl.severity, decl.throttle) == (local_id, severity, throttle), name
        assert [(n, t.name, t.size if t.kind == "string" else None) for n, t in decl.args] == args, name
    packet_type = comp.spec.event("InvalidReceiveMode").args[0][1]
    assert packet_type.target.name == "U16"  # FwPacketDescriptorType
    assert sorted(e.name for e in comp.spec.own_events) == sorted(expected_events)
    assert {c.name: (c.local_id, c.type.name, c.update) for c in comp.spec.own_channels} == {
        "FilesReceived": (0, "U32", "always"), "PacketsReceived": (1, "U32", "always"),
        "Warnings": (2, "U32", "always"), "FilesReceivedFailed": (3, "U32", "always")}
    assert comp.spec.event("BadChecksum").format == ("Bad checksum value during receipt of file {}: computed 0x{x}, "
                                          "read 0x{x}")
    assert comp.spec.commands == []  # FileUplink has no commands


# --- against the ground system ---------------------------------------------------------------------

def test_file_encoded_by_the_gds_lands_intact(fprime_harness, tmp_path):
    pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency: pip install -e .[test]")
    from fprime_gds.common.data_types import file_data
    from fprime_gds.common.encoders.file_encoder import FileEncoder
    from fprime_gds.common.files.helpers import CFDPChecksum

    data = content(2500, seed=7)
    chunk = 256  # fprime-gds's default uplink chunk
    encoder = FileEncoder()
    checksum = CFDPChecksum()
    packets = [file_data.StartPacketData(0, len(data), "/ground/upload.bin", "uplinked.bin")]
    seq = 1
    for offset in range(0, len(data), chunk):
        piece = data[offset:offset + chunk]
        checksum.update(piece, offset)
        packets.append(file_data.DataPacketData(seq, offset, piece))
        seq += 1
    packets.append(file_data.EndPacketData(seq, checksum.value))

    h = make(fprime_harness, tmp_path)
    for packet in packets:
        raw = encoder.encode_api(packet)
        assert raw[8:10] == b"\x00\x03"  # GDS header (8 bytes), then the FW_PACKET_FILE descriptor
        h.invoke("bufferSendIn", raw[10:])
    h.dispatch_all()
    assert (tmp_path / "uplinked.bin").read_bytes() == data
    assert checksum.value == cfdp_checksum(data)
    h.assert_event("FileReceived", 0, "uplinked.bin")
    h.assert_tlm_count("Warnings", 0)
    assert h.tlm_values("PacketsReceived")[-1] == len(packets)


def test_events_and_channels_decode_with_the_gds_dictionary_loaders(tmp_path, monkeypatch):
    """A dictionary built from FileUplink's declarations loads in the GDS, and its EventDecoder and
    ChDecoder read what the component sends (the alias-typed InvalidReceiveMode argument too)."""
    pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency: pip install -e .[test]")
    import importlib.util
    import json
    import struct

    from fprime_gds.common.decoders.ch_decoder import ChDecoder
    from fprime_gds.common.decoders.event_decoder import EventDecoder
    from fprime_gds.common.models.dictionaries import Dictionaries

    from fprime_lite.model.time import TIME

    maker = pathlib.Path(__file__).parents[2] / "data" / "svc" / "make_svc_dictionary.py"
    spec = importlib.util.spec_from_file_location("_file_uplink_dictionary", maker)
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    monkeypatch.setattr(gen, "INSTANCES", [("FileHandling.fileUplink", FileUplink, BASE)])
    path = tmp_path / "dictionary.json"
    path.write_text(json.dumps(gen.build()))
    gds = Dictionaries.load_dictionaries_into_config(str(path))

    root = tmp_path / "root"
    root.mkdir()
    comp = FileUplink(base_id=BASE, root=root)
    h = ComponentHarness(comp)
    events, channels = [], []
    comp.output_port("logOut").connect_callable(
        0, lambda i, t, sev, args: events.append(struct.pack(">I", i) + TIME.serialize(t) + args), "gds")
    comp.output_port("tlmOut").connect_callable(
        0, lambda i, t, value: channels.append(struct.pack(">I", i) + TIME.serialize(t) + value), "gds")
    try:
        send(h, DataPacket(1, 0, b"x"), b"\x09", *file_packets(b"abc", "bad.bin", checksum=0x1234))
    finally:
        h.close()
    decoded = [EventDecoder(gds.event_id).decode_api(p)[0] for p in events]
    assert [e.get_template().get_full_name() for e in decoded] == [
        "FileHandling.fileUplink.InvalidReceiveMode", "FileHandling.fileUplink.DecodeError",
        "FileHandling.fileUplink.BadChecksum"]
    assert [[a.val for a in e.get_args()] for e in decoded] == [
        [1, 0], [3], ["bad.bin", cfdp_checksum(b"abc"), 0x1234]]
    assert decoded[2].get_str().split(" : ", 1)[1] == (
        f"Bad checksum value during receipt of file bad.bin: computed 0x{cfdp_checksum(b'abc'):x}, read 0x1234")
    values = {}
    for payload in channels:
        for c in ChDecoder(gds.channel_id).decode_api(payload):
            values.setdefault(c.get_template().get_full_name(), []).append(c.get_val_obj().val)
    assert values == {"FileHandling.fileUplink.PacketsReceived": [1, 2, 3, 4],
                      "FileHandling.fileUplink.Warnings": [1, 2],
                      "FileHandling.fileUplink.FilesReceivedFailed": [1]}
