"""What a new user meets in the first hour (issue 17): broken inputs refused before flying, no
traceback for a mistake, unique run folders, re-plotting a run, loadable outputs, the Python API
and the skeletons."""

import json
import os
import pathlib
import subprocess
import sys
import tempfile

import pytest

from fprime_lite.tools.cli import main

ROOT = pathlib.Path(__file__).parents[3]
TOPOLOGY = str(ROOT / "deployments" / "proves_ref" / "topology.yaml")
PARAMS = ROOT / "deployments" / "proves_ref" / "flight_params.dat"


def one_line_error(capsys) -> str:
    err = capsys.readouterr().err
    assert "Traceback" not in err
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1, err
    return lines[0]


def _truncated_params(d):
    (d / "p.dat").write_bytes(PARAMS.read_bytes()[:30])
    return ["--params", str(d / "p.dat")]


def _garbage_sequence(d):
    (d / "g.bin").write_bytes(bytes(range(7, 107)))
    return ["--seq", str(d / "g.bin")]


def _unknown_command_sequence(d):
    (d / "u.seq").write_text("R00:00:01 Foo.bar.BAZ 1\n")
    return ["--seq", str(d / "u.seq")]


def _empty_sequence(d):
    (d / "e.seq").write_text("; nothing here yet\n\n")
    return ["--seq", str(d / "e.seq")]


@pytest.mark.parametrize("make, expected", [
    (_truncated_params, "parameter file .*p.dat: not a valid PrmDb file: PARAMETER_VALUE_SIZE"),
    (_garbage_sequence, "sequence .*g.bin: "),
    (_unknown_command_sequence, "u.seq:1: 'Foo.bar.BAZ' is not a command"),
    (_empty_sequence, "sequence .*e.seq: it holds no command .* write one command a line"),
])
def test_broken_parameter_file_or_sequence_is_refused_before_flying(tmp_path, capsys, make, expected):
    """FH-001: run refuses a truncated parameter file, a garbage sequence, a sequence naming an
    unknown command and one with no command at all (it was an IndexError in the sequencer's run handler
    once flying) with a one-line error and exit 2, before anything flies (no run folder)."""
    import re

    args = make(tmp_path)
    assert main(["run", TOPOLOGY, *args, "--duration", "1", "--out", str(tmp_path / "out")]) == 2
    assert re.search(expected, one_line_error(capsys))
    assert not (tmp_path / "out").exists()


def test_parameter_record_of_unknown_id_is_refused(tmp_path, capsys):
    """FH-001: a parameter file holding an id the deployment does not have is refused."""
    from fprime_lite.svc.prm_db import encode_param_file

    (tmp_path / "p.dat").write_bytes(encode_param_file([(0x7777, b"\x00")]))
    assert main(["run", TOPOLOGY, "--params", str(tmp_path / "p.dat"), "--duration", "1",
                 "--out", str(tmp_path / "out")]) == 2
    assert "record 0 has id 0x7777, which is no parameter" in one_line_error(capsys)


def test_run_fails_on_warning_hi_events_unless_allowed(tmp_path, capsys):
    """FH-001: a flight with WARNING_HI events exits 1 and the summary says why; --allow-warnings
    accepts them (exit 0, the summary still lists them)."""
    seq = tmp_path / "warn.seq"
    seq.write_text('R00:00:01 FileHandling.fileDownlink.SendFile "/nonexistent/x" "x"\n')
    common = [TOPOLOGY, "--seq", str(seq), "--duration", "3", "--no-plots"]
    assert main(["run", *common, "--out", str(tmp_path / "a")]) == 1
    assert ("3 WARNING_HI event(s): FileHandling.fileDownlink.FileOpenError, FileHandling.fileDownlink.PathRefused, "
            "ReferenceDeployment.cmdSeq.CS_CommandError (see events.log)") in capsys.readouterr().err  # issue 28
    summary = json.loads((tmp_path / "a" / "summary.json").read_text())
    assert summary["ok"] is False and any("WARNING_HI" in p for p in summary["problems"])
    assert main(["run", *common, "--out", str(tmp_path / "b"), "--allow-warnings"]) == 0
    summary = json.loads((tmp_path / "b" / "summary.json").read_text())
    assert summary["ok"] is True and summary["problems"]


def test_a_clean_flight_is_ok():
    """FH-001: flight_problems names faults, slips and WARNING_HI/FATAL events, and nothing else."""
    from fprime_lite.tools.runner import flight_problems

    assert flight_problems({"handler_faults": 0, "cycle_slips": 0, "member_faults": 0,
                            "events_by_severity": {"WARNING_LO": 3, "ACTIVITY_HI": 9}}) == []
    assert flight_problems({"handler_faults": 2, "cycle_slips": 1, "events_by_severity": {"FATAL": 1}}) == [
        "2 handler fault(s)", "1 cycle slip(s)", "1 FATAL event(s) (see events.log)"]
    names = {"WARNING_HI": {"D.a.Lost": 1, "D.b.Fault": 4, "D.c.X": 1, "D.d.Y": 1}, "WARNING_LO": {"D.e.Z": 2}}
    assert flight_problems({"events_by_severity": {"WARNING_HI": 7, "WARNING_LO": 2}}, names) == [
        "7 WARNING_HI event(s): D.b.Fault ×4, D.a.Lost, D.c.X and 1 more (see events.log)"]


def _no_sequencer_topology(tmp_path) -> str:
    from fprime_lite.tools.skeleton import new_deployment

    new_deployment("Plain", tmp_path)
    return str(tmp_path / "Plain" / "topology.yaml")


@pytest.mark.parametrize("case", ["out is a file", "out unwritable", "dict -o folder", "scenario folder",
                                  "seq without sequencer", "params -o missing folder", "plot not a run"])
def test_user_mistakes_get_one_line_and_no_traceback(tmp_path, capsys, case):
    """FH-002: every OS error on outputs and every bad path is a one-line message with exit 2, and
    nothing is created that the user did not ask for."""
    (tmp_path / "file").write_text("x")
    (tmp_path / "folder").mkdir()
    out = ["--out", str(tmp_path / "run")]
    argv, expected = {
        "out is a file": (["run", TOPOLOGY, "--duration", "1", "--out", str(tmp_path / "file")], "is a file"),
        "out unwritable": (["run", TOPOLOGY, "--duration", "1", "--out", "/proc/fprime-lite-run"],
                           "cannot create the folder"),
        "dict -o folder": (["dict", TOPOLOGY, "-o", str(tmp_path / "folder")], "is a folder"),
        "scenario folder": (["run", TOPOLOGY, "--duration", "1", "--scenario", str(tmp_path / "folder"), *out],
                            "is a folder"),
        "seq without sequencer": (["run", _no_sequencer_topology(tmp_path), "--duration", "1", "--seq",
                                   str(ROOT / "deployments" / "proves_ref" / "startup.seq"), *out],
                                  "has no start-up sequencer"),
        "params -o missing folder": (["params", TOPOLOGY, "-o", str(tmp_path / "nope" / "p.dat")],
                                     "does not exist"),
        "plot not a run": (["plot", str(tmp_path / "folder")], "no run plotter recognises"),
    }[case]
    assert main(argv) == 2
    assert expected in one_line_error(capsys)
    assert not (tmp_path / "run").exists() and not (tmp_path / "nope").exists()


def test_six_quick_runs_get_six_folders(tmp_path, monkeypatch):
    """FH-003: default run folders are stamped to the millisecond with a suffix when the name is
    taken: six runs in a loop all succeed, in six different folders."""
    from fprime_lite.tools.api import claim_run_folder

    monkeypatch.chdir(tmp_path)
    claimed = {claim_run_folder() for _ in range(20)}  # faster than the clock's millisecond
    assert len(claimed) == 20
    for _ in range(6):
        assert main(["run", TOPOLOGY, "--duration", "1", "--no-plots", "--no-progress"]) == 0
    assert len(list((tmp_path / "runs").iterdir())) == 26


@pytest.fixture(scope="module")
def finished_run(tmp_path_factory):
    """A 120 s run of the reference deployment with its plots."""
    out = tmp_path_factory.mktemp("run") / "r"
    assert main(["run", TOPOLOGY, "--duration", "120", "--out", str(out), "--no-progress"]) == 0
    return out


def test_plot_redraws_a_finished_run_from_its_files(finished_run, tmp_path, capsys):
    """FH-007: fprime-lite plot RUN_DIR draws the run's plots again from its folder alone, the same
    set the run drew (rate, per-coil drive levels, state, field)."""
    drawn_by_run = sorted(p.name for p in finished_run.glob("*.png"))
    assert {"rate.png", "drive_levels.png", "state.png", "field.png"} <= set(drawn_by_run)
    assert main(["plot", str(finished_run), "-o", str(tmp_path)]) == 0
    assert sorted(p.name for p in tmp_path.glob("*.png")) == drawn_by_run
    assert all(p.stat().st_size > 10_000 for p in tmp_path.glob("*.png"))


def test_drive_level_plot_has_one_row_per_coil_and_legends_sit_outside(finished_run, tmp_path, monkeypatch):
    """FH-007: the drive-level plot is a heat strip with one labelled row per coil (not five step
    lines drawn over each other); every legend is outside its axes; the completion marker is drawn
    when the summary has a completion time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from detumble.reports import plots

    figures = []
    monkeypatch.setattr(plots, "save_figure", lambda fig, path: figures.append((path.name, fig)) or path)
    monkeypatch.setattr(plt, "close", lambda fig=None: None)
    plots.plot_truth(finished_run / "truth.csv", tmp_path, thresholds={"DEADBAND_UPPER_THRESHOLD": 8.0},
                     marks={"detumble completed": 60.0})
    figs = dict(figures)
    heat = figs["drive_levels.png"].axes[0]
    assert [t.get_text() for t in heat.get_yticklabels()] == ["X+", "X−", "Y+", "Y−", "Z−"]
    assert heat.collections and not heat.lines[:-2]  # a mesh, plus the marker lines only
    for name, fig in figs.items():
        fig.canvas.draw()
        for ax in fig.axes:
            legend = ax.get_legend()
            if legend is not None:
                assert legend.get_window_extent().x0 >= ax.get_window_extent().x1, name
    rate_labels = [line.get_label() for line in figs["rate.png"].axes[0].lines]
    assert "detumble completed (60 s)" in rate_labels


def test_channels_wide_loads_in_one_pandas_line_with_units(finished_run):
    """FH-011: channels.csv stays as received; channels_wide.csv has one column per channel scalar
    with units in the heading, loads with one read_csv, and agrees with channels.csv."""
    import pandas as pd

    wide = pd.read_csv(finished_run / "channels_wide.csv", index_col="t_s")
    rate = "ReferenceDeployment.detumbleManager.AngularVelocityMagnitude [deg/s]"
    assert rate in wide.columns
    assert "ReferenceDeployment.imuManager.MagneticField.x [G]" in wide.columns
    assert wide.index.is_monotonic_increasing and wide.index[-1] == pytest.approx(120.0)
    long = pd.read_csv(finished_run / "channels.csv", dtype={"value": str})
    assert list(long.columns) == ["time", "channel", "value"]
    received = long[long.channel == rate.split(" [")[0]].value.astype(float)
    assert wide[rate].dropna().iloc[-1] == pytest.approx(received.iloc[-1], abs=5e-4)  # text has 3 decimals


def test_events_of_one_instant_have_distinct_times_in_events_log(finished_run):
    """FH-006: no two events of a run share a stamp (each stamped when emitted)."""
    stamps = [line.split(" ", 1)[0] for line in (finished_run / "events.log").read_text().splitlines()]
    assert len(stamps) > 5 and len(set(stamps)) == len(stamps) and stamps == sorted(stamps)


def test_progress_state_is_the_share_of_time_since_the_last_refresh():
    """FH-008: the progress bar's state is the share of simulated time since the previous refresh
    spent in each manager state, equal to the exact fractions the truth log records (to 1e-3)."""
    import csv

    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.tools.api import load

    loaded = load(TOPOLOGY)
    report = loaded.resources["report"]
    deployment = Deployment(loaded)
    with tempfile.TemporaryDirectory() as out:
        report.begin(deployment, pathlib.Path(out))
        deployment.start()
        deployment.run_for(100)
        report.state_shares()  # the first 100 s
        deployment.run_for(200)
        shares = report.state_shares()
        deployment.run_for(20)
        text = report.progress()["state"]
        report.finish(pathlib.Path(out), plots=False)
        rows = list(csv.DictReader(open(pathlib.Path(out) / "truth.csv")))
    window = [r for r in rows if 100.0 < float(r["t_s"]) <= 300.0]
    exact = sum(float(r["frac_actuating_bdot"]) for r in window) / len(window)
    assert shares["ACTUATING_BDOT"] == pytest.approx(exact, abs=1e-3)
    assert 0.5 < shares["ACTUATING_BDOT"] < 0.9 and sum(shares.values()) == pytest.approx(1.0)
    assert "ACTUATING_BDOT" in text and "%" in text


def test_python_api_returns_a_result_with_dataframes_quietly(tmp_path, capsys):
    """FH-012: fprime_lite.tools.run flies quietly and returns the summary and DataFrames;
    open_run gives the same for a finished folder; a mistake raises one clear error."""
    from fprime_lite.model.errors import FprimeLiteError
    from fprime_lite.tools import open_run, run

    result = run(TOPOLOGY, duration_s=20, out=tmp_path / "r")
    assert capsys.readouterr().out == ""
    assert result.ok and result.problems == []
    assert result.summary["sim_seconds"] == pytest.approx(20.0)
    assert {"time", "name", "severity", "text"} <= set(result.events.columns)
    assert (result.events.name == "ReferenceDeployment.detumbleManager.DetumbleStarted").sum() == 1
    assert "ReferenceDeployment.detumbleManager.State" in result.telemetry.columns
    assert result.truth["rate_deg_s"].iloc[0] == pytest.approx(30.0, rel=1e-6)
    again = open_run(tmp_path / "r")
    assert again.summary == result.summary and len(again.channels) == len(result.channels)
    with pytest.raises(FprimeLiteError, match="no such file"):
        run(TOPOLOGY, duration_s=1, seq=tmp_path / "missing.seq", out=tmp_path / "x")
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize("kind", ["component", "deployment"])
def test_new_skeleton_passes_its_own_test(tmp_path, kind):
    """FH-010: fprime-lite new component|deployment NAME writes a skeleton (component with one
    command, event, channel and parameter; its harness test; a topology with a rate group; a docs
    stub) whose own tests pass right away."""
    assert main(["new", kind, "MyHeater", "--dir", str(tmp_path)]) == 0
    folder = tmp_path if kind == "component" else tmp_path / "MyHeater"
    names = sorted(p.name for p in folder.iterdir())
    expected = ["my_heater.md", "my_heater.py", "test_my_heater.py"] if kind == "component" else \
        ["README.md", "my_heater_counter.md", "my_heater_counter.py", "test_my_heater_counter.py",
         "test_my_heater_deployment.py", "topology.yaml"]
    assert names == expected
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"], cwd=folder,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert ("1 passed" if kind == "component" else "2 passed") in done.stdout.splitlines()[-1]
    assert main(["new", kind, "MyHeater", "--dir", str(tmp_path)]) == 2  # never overwrites


def test_small_ones(tmp_path, capsys):
    """FH-009: sim --help names fprime-lite sim; sim writes umask-respecting modes and says
    real_time_factor like run; GAIN=1e400 is out of range for F64, not 'not a number'."""
    assert main(["sim", "--help"]) == 0
    assert capsys.readouterr().out.startswith("usage: fprime-lite sim")
    old = os.umask(0o022)
    try:
        assert main(["sim", "case_a", "--law", "kopt", "--duration", "20", "--out", str(tmp_path / "s")]) == 0
    finally:
        os.umask(old)
    for name in ("summary.json", "rate.csv"):
        assert (tmp_path / "s" / name).stat().st_mode & 0o777 == 0o644
    summary = json.loads((tmp_path / "s" / "summary.json").read_text())
    assert "real_time_factor" in summary and "realtime_factor" not in summary
    capsys.readouterr()
    assert main(["params", TOPOLOGY, "-o", str(tmp_path / "p.dat"), "--set",
                 "ReferenceDeployment.detumbleManager.GAIN=1e400"]) == 2
    assert "1e400 is out of range for F64" in one_line_error(capsys)
    assert main(["params", TOPOLOGY, "-o", str(tmp_path / "p.dat"), "--set",
                 "ReferenceDeployment.detumbleManager.GAIN=1e2"]) == 0


def test_attitude_dipole_and_wheel_plots_appear_with_their_truth_columns(tmp_path):
    """FH-007: the attitude, dipole and wheel plots are drawn when truth.csv has their columns
    (q0…q3 and pointing_error_deg, m_/mcmd_*_Am2, h<i>_Nms) and only then."""
    import csv
    import math

    from detumble.reports.plots import plot_truth

    base = ["t_s", "wx_deg_s", "wy_deg_s", "wz_deg_s", "rate_deg_s", "bx_uT", "by_uT", "bz_uT",
            "level_xp", "level_xm", "level_yp", "level_ym", "level_zm", "strategy"]
    extra = ["q0", "q1", "q2", "q3", "pointing_error_deg", "m_x_Am2", "m_y_Am2", "m_z_Am2",
             "mcmd_x_Am2", "mcmd_y_Am2", "mcmd_z_Am2", "h0_Nms"]

    def write(path, columns):
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(columns)
            for i in range(50):
                a = i / 50 * math.pi
                row = {"t_s": i, "strategy": "BDOT", "q0": math.cos(a / 2), "q1": math.sin(a / 2),
                       "pointing_error_deg": "" if i < 5 else 90 - i, "level_xp": 127 if i % 2 else -127}
                w.writerow([row.get(c, 0.1) for c in columns])

    write(tmp_path / "plain.csv", base)
    (tmp_path / "a").mkdir()
    names = {p.name for p in plot_truth(tmp_path / "plain.csv", tmp_path / "a")}
    assert names == {"rate.png", "drive_levels.png", "state.png", "field.png"}
    write(tmp_path / "adcs.csv", base + extra)
    (tmp_path / "b").mkdir()
    names = {p.name for p in plot_truth(tmp_path / "adcs.csv", tmp_path / "b")}
    assert names >= {"attitude.png", "dipole.png", "wheels.png"}


@pytest.mark.parametrize("sig, status", [("SIGINT", 130), ("SIGTERM", 143)])
def test_an_interrupted_run_keeps_what_flew(tmp_path, sig, status):
    """FH-012 (issue 28): Ctrl-C or SIGTERM on a plain `run` ends the flight where it is and writes every
    output up to that instant — events, channels, truth, a summary saying stopped_by "interrupted" and the
    signal — with no temporary file left for the next run to delete, and exits 128 + the signal's number
    (130, 143), as a shell reports a job a signal ended."""
    import signal
    import time

    out = tmp_path / "run"
    proc = subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.cli", "run", TOPOLOGY, "--duration", "20000",
                             "--no-plots", "--no-progress", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while not (out / "dictionary.json").is_file() and time.monotonic() < deadline:  # written as it starts
            time.sleep(0.1)
        time.sleep(1.5)  # some seconds of flight
        proc.send_signal(getattr(signal, sig))
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == status, stdout + stderr
    assert f"interrupted by {sig}" in stderr and "Traceback" not in stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["stopped_by"] == "interrupted" and summary["signal"] == sig
    assert 0 < summary["sim_seconds"] < 20000
    assert sorted(p.name for p in out.iterdir()) == ["channels.csv", "channels_wide.csv", "dictionary.json",
                                                     "events.log", "summary.json", "truth.csv"]
    last = (out / "truth.csv").read_text().splitlines()[-1]
    assert float(last.split(",")[0]) == pytest.approx(summary["sim_seconds"], abs=1.0)  # sampled each second
