"""File handling in the reference deployment: a sequence downlinks a file into the run's downlink/."""

import json
import os
import pathlib

from fprime_lite.tools.cli import main

TOPOLOGY = str(pathlib.Path(__file__).parents[1] / "topology.yaml")


def test_a_sequence_downlinks_a_file_into_the_run_outputs(tmp_path, capsys):
    source = tmp_path / "telemetry_dump.bin"
    data = os.urandom(12_345)  # 25 DATA packets: several 1 Hz ticks of the downlink budget
    source.write_bytes(data)
    seq = tmp_path / "downlink.seq"
    seq.write_text("; enable detumbling, then send a file to the ground\n"
                   "R00:00:00 ReferenceDeployment.detumbleManager.SET_MODE AUTO\n"
                   f'R00:00:01 FileHandling.fileDownlink.SendFile "{source}" "dump.bin"\n')
    out = tmp_path / "run"
    assert main(["run", TOPOLOGY, "--duration", "10", "--seq", str(seq), "--out", str(out),
                 "--no-progress", "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["files_downlinked"] == [{"destination": "dump.bin", "path": str(out / "downlink" / "dump.bin"),
                                            "bytes": len(data), "status": "complete"}]
    assert (out / "downlink" / "dump.bin").read_bytes() == data
    events = (out / "events.log").read_text()
    assert "FileHandling.fileDownlink.SendStarted" in events and "FileHandling.fileDownlink.FileSent" in events
    assert "WARNING" not in events
