"""Temporary files of the ground side and of run folders (issue #16: "temporary files of atomic
writes are cleaned at start-up, and named so they can be"): the recorders stream under names the
start-up clean-up recognises, clean what killed processes left where they start, and never touch
what a live writer — of another process or of this one — is still writing."""


from fprime_lite.deploy.topology import Topology
from fprime_lite.ground.downlink import GroundRecorder
from fprime_lite.ground.files import FileReceiver
from fprime_lite.osal.atomic import clean_temporary_files, is_temporary_name, open_temporary
from fprime_lite.tools.api import claim_run_folder
from fprime_lite.wire.file_packet import DataPacket, StartPacket, encode_file_packet


def test_the_ground_recorder_streams_under_recognisable_names_and_cleans_at_start(tmp_path, killed_leftover,
                                                                                 hidden):
    """TMP-10: while a GroundRecorder records, its events.log / channels.csv / channels_wide.csv are
    temporary files the start-up clean-up recognises; a killed recorder's leftover in the folder is
    removed when the next one starts; closing leaves only the final files."""
    old = killed_leftover(tmp_path, "events.log")
    recorder = GroundRecorder(Topology("Demo"), tmp_path)
    assert not old.exists()
    streaming = hidden(tmp_path)
    assert len(streaming) == 3 and all(is_temporary_name(n) for n in streaming)
    assert {n.split(".")[3] for n in streaming} == {"events", "channels", "channels_wide"}
    recorder.close()
    assert hidden(tmp_path) == []
    assert {p.name for p in tmp_path.iterdir()} >= {"events.log", "channels.csv", "channels_wide.csv"}


def test_a_file_being_reassembled_is_recognisable_and_a_killed_ones_is_cleaned(tmp_path, killed_leftover,
                                                                               hidden):
    """TMP-11: a downlinked file being reassembled sits under a recognisable temporary name; the
    half-received file of a killed receiver is removed when a FileReceiver starts on the folder."""
    folder = tmp_path / "downlink"
    old = killed_leftover(folder, "logs_today.bin")
    receiver = FileReceiver(folder)
    assert not old.exists()
    receiver.receive(encode_file_packet(StartPacket(0, 10, "/flight/a.bin", "logs/today.bin")))
    receiver.receive(encode_file_packet(DataPacket(1, 0, b"01234")))
    (partial,) = hidden(folder)
    assert is_temporary_name(partial) and ".logs_today.bin." in partial


def test_clean_up_spares_what_this_process_is_writing(tmp_path, killed_leftover):
    """TMP-12: a temporary file this process is still streaming into is not removed by a clean-up
    of its folder (another component starting there), though it carries this process's pid; a
    dead process's is."""
    old = killed_leftover(tmp_path, "truth.csv")
    handle, tmp = open_temporary(tmp_path / "events.log", "w", encoding="utf-8")
    try:
        handle.write("still writing\n")
        assert clean_temporary_files(tmp_path) == [str(old)]
        assert tmp.exists() and is_temporary_name(tmp.name)
    finally:
        handle.close()


def test_claiming_a_run_folder_cleans_what_killed_runs_left(tmp_path, killed_leftover):
    """TMP-13: claiming a new folder under runs/ removes the temporary files killed runs left in
    their folders (events.log, truth.csv, a downlinked file …) and nothing else."""
    runs = tmp_path / "runs"
    dead = [killed_leftover(runs / "20261201-101010.000", "events.log"),
            killed_leftover(runs / "20261201-101010.000" / "downlink", "img.bin"),
            killed_leftover(runs / "20261201-111111.000", "truth.csv")]
    keep = runs / "20261201-101010.000" / "summary.json"
    keep.write_text("{}")
    folder = claim_run_folder(runs_dir=runs)
    assert folder.parent == runs and folder.is_dir()
    assert [p for p in dead if p.exists()] == [] and keep.exists()
