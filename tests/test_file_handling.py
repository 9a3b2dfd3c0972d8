"""File handling in the reference deployment: a sequence downlinks a file into the run's downlink/."""

import json
import os
import pathlib

from fprime_lite.tools.cli import main

TOPOLOGY = str(pathlib.Path(__file__).parents[1] / "topology.yaml")


def test_a_sequence_downlinks_a_file_into_the_run_outputs(tmp_path, capsys):
    """FS-ROOT-10: the file services' default root is the run's folder: a file written there before
    the flight (the dictionary) is downlinked by a sequence; a file outside it is refused."""
    outside = tmp_path / "telemetry_dump.bin"
    outside.write_bytes(os.urandom(100))
    seq = tmp_path / "downlink.seq"
    seq.write_text("; enable detumbling, then send a file to the ground\n"
                   "R00:00:00 ReferenceDeployment.detumbleManager.SET_MODE AUTO\n"
                   'R00:00:01 FileHandling.fileDownlink.SendFile "dictionary.json" "dump.bin"\n'
                   f'R00:00:01 FileHandling.fileDownlink.SendFile "{outside}" "stolen.bin"\n')
    out = tmp_path / "run"
    # ~300 KB at 10 packets of 499 bytes a second: about 60 s of flight; 120 s leaves room to grow
    assert main(["run", TOPOLOGY, "--duration", "120", "--seq", str(seq), "--out", str(out),
                 "--no-progress", "--no-plots", "--allow-warnings"]) == 0  # the refused SendFile warns
    data = (out / "dictionary.json").read_bytes()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["files_downlinked"] == [{"destination": "dump.bin", "path": str(out / "downlink" / "dump.bin"),
                                            "bytes": len(data), "status": "complete"}]
    assert (out / "downlink" / "dump.bin").read_bytes() == data
    events = (out / "events.log").read_text()
    assert "FileHandling.fileDownlink.SendStarted" in events and "FileHandling.fileDownlink.FileSent" in events
    warnings = [line.split()[1] for line in events.splitlines() if "WARNING" in line]
    assert warnings[:2] == ["FileHandling.fileDownlink.PathRefused", "FileHandling.fileDownlink.FileOpenError"]
    assert not (out / "downlink" / "stolen.bin").exists()
