"""The writer process of ``fprime-lite run`` (``--writer process``): the same outputs as inline, an
interrupted run keeps them, and a failure in the child fails the run with its reason."""

from __future__ import annotations

import errno
import json
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time

import pytest

from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.ground import writer_process
from fprime_lite.ground.downlink import GroundRecorder
from fprime_lite.ground.writer_process import OutputWriter, OutputWriterError, choose_writer
from fprime_lite.tools import runner
from fprime_lite.tools.cli import main
from fprime_lite.tools.runner import run_deployment

ROOT = pathlib.Path(__file__).resolve().parents[3]
PROVES = ROOT / "deployments" / "proves_ref" / "topology.yaml"
PACKETIZED = ROOT / "deployments" / "proves_ref" / "topology_packetized.yaml"
COURSEWORK = ROOT / "deployments" / "coursework" / "topology.yaml"
OUTPUTS = ["channels.csv", "channels_wide.csv", "dictionary.json", "events.log", "summary.json", "truth.csv"]

pytestmark = pytest.mark.skipif("fork" not in __import__("multiprocessing").get_all_start_methods(),
                                reason="the writer process is forked")


class _Spy(OutputWriter):
    """An OutputWriter that remembers itself (the test needs the child's pid and counters)."""

    made: list[OutputWriter] = []

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        _Spy.made.append(self)


@pytest.fixture
def spy(monkeypatch):
    _Spy.made = []
    monkeypatch.setattr(runner, "OutputWriter", _Spy)
    return _Spy.made


def _without_wall_clock(folder: pathlib.Path, name: str) -> str:
    """A file's text without what differs between two flights of the same tree: the rate groups'
    RgMaxTime (a wall-clock measure: its lines, its wide columns) and the summary's wall-clock keys."""
    text = (folder / name).read_text()
    if name == "channels.csv":
        return "".join(line for line in text.splitlines(keepends=True) if ".RgMaxTime," not in line)
    if name == "channels_wide.csv":
        rows = [line.split(",") for line in text.splitlines()]
        keep = [i for i, heading in enumerate(rows[0]) if "RgMaxTime" not in heading]
        return "\n".join(",".join(row[i] for i in keep) for row in rows)
    if name == "summary.json":
        summary = json.loads(text)
        for key in ("wall_seconds", "real_time_factor"):
            summary.pop(key)
        return json.dumps(summary, sort_keys=True)
    return text


@pytest.mark.parametrize("topology, seconds", [(PROVES, 60.0), (PACKETIZED, 30.0), (COURSEWORK, 5.0)],
                         ids=["proves_ref", "packetized", "coursework"])
def test_the_writer_process_writes_the_inline_bytes(tmp_path, spy, topology, seconds):
    """WRITER-001: a run whose telemetry files and truth rows a forked writer process formats writes every
    output as the inline run does, byte for byte but for the wall-clock measures (RgMaxTime and the
    summary's wall keys, which differ between any two flights); the child did the work (its own pid,
    every channel update counted there), and no temporary file is left."""
    outs = {}
    for writer in ("inline", "process"):
        outs[writer] = tmp_path / writer
        run_deployment(load_topology(topology), outs[writer], duration_s=seconds, plots=False, quiet=True,
                       allow_warnings=True, writer=writer)
        assert sorted(p.name for p in outs[writer].iterdir()) == OUTPUTS
    assert len(spy) == 1 and spy[0].pid != os.getpid() and spy[0].stats["channel_updates"] > 0
    for name in OUTPUTS:
        assert _without_wall_clock(outs["process"], name) == _without_wall_clock(outs["inline"], name), name
    lines = (outs["process"] / "channels.csv").read_text().count("\n") - 1
    assert spy[0].stats["channel_updates"] == lines


def _run_cli(out: pathlib.Path, *extra: str) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src") + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.cli", "run", str(PROVES), "--duration", "20000",
                             "--no-plots", "--no-progress", "--out", str(out), *extra], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)


def _wait_until_flying(out: pathlib.Path, timeout_s: float = 120.0) -> None:
    """Return a couple of seconds after the run wrote its dictionary (it does so as it starts)."""
    end = time.monotonic() + timeout_s
    while time.monotonic() < end and not (out / "dictionary.json").is_file():
        time.sleep(0.1)
    time.sleep(2.0)


@pytest.mark.parametrize("sig, status", [("SIGINT", 130), ("SIGTERM", 143)])
def test_an_interrupt_to_the_whole_group_keeps_the_outputs(tmp_path, sig, status):
    """WRITER-002 (issue 28 with the writer process): Ctrl-C reaches every process of the terminal's group,
    the writer process too; it ignores the signal and finishes when the flight ends its stream, so the run
    exits 128 + the signal's number with every output written up to the stop (the truth rows to the
    summary's sim_seconds, channels.csv and channels_wide.csv whole to the last line) and no temporary
    file left."""
    out = tmp_path / "run"
    with _run_cli(out, "--writer", "process") as proc:
        _wait_until_flying(out)
        os.killpg(proc.pid, getattr(signal, sig))  # as a terminal's Ctrl-C: the writer process gets it too
        try:
            stdout, stderr = proc.communicate(timeout=120)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            raise
    summary = json.loads((out / "summary.json").read_text())
    assert (proc.returncode, summary["stopped_by"]) == (status, "interrupted"), stdout + stderr
    assert f"interrupted by {sig}" in stderr and "Traceback" not in stderr
    assert 0 < summary["sim_seconds"] < 20000 and sorted(p.name for p in out.iterdir()) == OUTPUTS
    truth_last = (out / "truth.csv").read_text().splitlines()[-1]
    assert float(truth_last.split(",")[0]) == pytest.approx(summary["sim_seconds"], abs=1.0)
    channels = (out / "channels.csv").read_text()
    assert channels.endswith("\n")
    last_time = float(channels.splitlines()[-1].split(",")[0]) - 1748736000.0  # the scenario's epoch
    assert last_time == pytest.approx(summary["sim_seconds"], abs=1.5)  # telemetry downlinked each second
    wide = (out / "channels_wide.csv").read_text().splitlines()
    assert len({len(row.split(",")) for row in wide}) == 1
    assert float(wide[-1].split(",")[0]) == pytest.approx(summary["sim_seconds"], abs=1.5)


def test_a_killed_writer_process_fails_the_run(tmp_path, spy):
    """WRITER-003: the writer process killed during the flight: the flight stops, the run raises an
    OutputWriterError that says the writer ended and what it did not finish, and neither channels.csv nor
    truth.csv appears as if whole."""
    loaded = load_topology(PROVES)

    killed: list[int] = []

    def kill_at_20_s(time_us: int) -> None:
        if spy and not killed and time_us >= 20_000_000:
            killed.append(time_us)
            os.kill(spy[0].pid, signal.SIGKILL)

    loaded.scheduler.add_time_listener(kill_at_20_s)
    wall0 = time.monotonic()
    with pytest.raises(OutputWriterError, match="ended unexpectedly") as raised:
        run_deployment(loaded, tmp_path, duration_s=5000.0, plots=False, quiet=True, allow_warnings=True,
                       writer="process")
    assert "channels.csv" in str(raised.value)
    assert loaded.scheduler.now_us < 4000 * 1_000_000, "the flight went on after the writer died"
    assert time.monotonic() - wall0 < 60
    names = {p.name for p in tmp_path.iterdir()}
    assert "channels.csv" not in names and "truth.csv" not in names and "summary.json" not in names


def test_a_full_disk_in_the_writer_process_is_reported(tmp_path, monkeypatch, capsys):
    """WRITER-004: an OSError in the writer process (a full disk while writing channels.csv) comes back to
    the run: `fprime-lite run` exits 1 with the errno's text and the file's name, as for an inline write
    error, and writes no summary."""
    calls = [0]
    telemetry = GroundRecorder._telemetry

    def full_after_ten(self, packet):
        calls[0] += 1
        if calls[0] > 10:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(tmp_path / "run" / "channels.csv"))
        return telemetry(self, packet)

    monkeypatch.setattr(GroundRecorder, "_telemetry", full_after_ten)  # the forked child inherits it
    status = main(["run", str(PROVES), "--duration", "600", "--no-plots", "--no-progress", "--out",
                   str(tmp_path / "run"), "--writer", "process"])
    err = capsys.readouterr().err
    assert status == 1, err
    assert "in the output writer process: No space left on device" in err and "channels.csv" in err
    assert calls[0] == 0  # this process formatted nothing: the child did
    assert not (tmp_path / "run" / "summary.json").exists()


def test_auto_picks_the_process_only_where_it_helps(monkeypatch):
    """WRITER-005: ``--writer auto`` is a process with two cores, a single thread and an unpaced run; inline
    on one core, with another thread running (a fork copies none) or paced to the wall clock; an unknown
    mode is refused."""
    monkeypatch.setattr(writer_process.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    if threading.active_count() == 1:
        assert choose_writer("auto") == "process"
    assert choose_writer("auto", realtime=True) == "inline"
    assert choose_writer("inline") == "inline" and choose_writer("process") == "process"
    release = threading.Event()
    other = threading.Thread(target=release.wait)
    other.start()
    try:
        assert choose_writer("auto") == "inline"
    finally:
        release.set()
        other.join()
    monkeypatch.setattr(writer_process.os, "sched_getaffinity", lambda pid: {0}, raising=False)
    assert choose_writer("auto") == "inline"
    with pytest.raises(ValueError, match="writer must be one of"):
        choose_writer("thread")


def test_the_writer_process_writes_the_dictionary(tmp_path, monkeypatch):
    """WRITER-010: with a writer process the flight's process does not build ``dictionary.json`` (the child
    does, from its copy of the topology, as the flight starts); the file is the inline run's, byte for byte."""
    built_here: list[str] = []
    write = runner.write_dictionary

    def spy(topology, path, **kwargs):
        built_here.append(str(path))
        return write(topology, path, **kwargs)

    monkeypatch.setattr(runner, "write_dictionary", spy)  # the runner's name: the child does not use it
    outs = {}
    for writer in ("inline", "process"):
        outs[writer] = tmp_path / writer
        run_deployment(load_topology(PROVES), outs[writer], duration_s=2.0, plots=False, quiet=True,
                       allow_warnings=True, writer=writer)
    assert built_here == [str(outs["inline"] / "dictionary.json")]
    assert (outs["process"] / "dictionary.json").read_bytes() == (outs["inline"] / "dictionary.json").read_bytes()


def test_a_dictionary_error_in_the_writer_process_is_reported(tmp_path, monkeypatch):
    """WRITER-011: the child failing to write ``dictionary.json`` (a full disk) fails the run with the errno,
    the file's name and the child's text, as an inline write error would; no dictionary is left in place."""
    def full(topology, path, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    monkeypatch.setattr(writer_process, "write_dictionary", full)  # the forked child inherits it
    with pytest.raises(OutputWriterError) as caught:
        run_deployment(load_topology(PROVES), tmp_path / "run", duration_s=5.0, plots=False, quiet=True,
                       allow_warnings=True, writer="process")
    assert caught.value.errno == errno.ENOSPC and caught.value.filename.endswith("dictionary.json")
    assert "in the output writer process: No space left on device" in str(caught.value)
    assert not (tmp_path / "run" / "dictionary.json").exists()


def test_the_flight_hands_the_truth_rows_over_unformatted(tmp_path, monkeypatch):
    """WRITER-012: with a writer process the flight's process hands each truth row's numbers over as numbers
    (the time, the coil means, the state shares and the power columns, which ``truth.csv`` writes with a
    fixed number of decimals): the writer process formats them; the file is the inline run's."""
    handed: list = []
    writerow = writer_process._RemoteRows.writerow

    def spy(self, row):
        handed.append(row)
        return writerow(self, row)

    monkeypatch.setattr(writer_process._RemoteRows, "writerow", spy)
    outs = {}
    for writer in ("inline", "process"):
        outs[writer] = tmp_path / writer
        run_deployment(load_topology(PROVES), outs[writer], duration_s=5.0, plots=False, quiet=True,
                       allow_warnings=True, writer=writer)
    header, rows = handed[0], handed[2:]  # the first sample closes no interval (empty means)
    assert len(rows) == 5 and all(isinstance(name, str) for name in header)  # t = 1 … 5 s
    formatted = [i for i, name in enumerate(header) if name == "t_s" or name.startswith(("level_mean_", "frac_"))
                 or name in ("soc", "bus_v", "coil_w_mean")]
    assert len(formatted) > 10
    assert all(type(row[i]) is float for row in rows for i in formatted), [row[i] for row in rows for i in formatted]
    assert (outs["process"] / "truth.csv").read_bytes() == (outs["inline"] / "truth.csv").read_bytes()
