"""The application's run outputs under recognisable temporary names (issue #16, finding 7): the
truth trace of a SITL run and the plant-only ``fprime-lite sim`` results are streamed or written
under names the framework's start-up clean-up recognises, and what a killed run left is removed."""

import os
from types import SimpleNamespace

from detumble.tools.cli import _sim
from detumble.drivers.spacecraft import make_spacecraft
from detumble.reports.detumble_report import DetumbleRunReport
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.model.time import SimulatedClock
from fprime_lite.osal.atomic import is_temporary_name


def test_the_truth_trace_streams_under_a_recognisable_name(tmp_path, killed_leftover, hidden):
    """TMP-20: while a run records truth.csv it is a recognisable temporary file; a killed run's
    leftover in the folder is removed when recording begins; finishing leaves truth.csv only."""
    old = killed_leftover(tmp_path, "truth.csv")
    scheduler = Scheduler(SimulatedClock())
    report = DetumbleRunReport(make_spacecraft(scheduler=scheduler))
    deployment = SimpleNamespace(topology=SimpleNamespace(instance=lambda name: SimpleNamespace(component=None)),
                                 scheduler=scheduler)
    report.begin(deployment, tmp_path)
    assert not old.exists()
    (streaming,) = hidden(tmp_path)
    assert is_temporary_name(streaming) and ".truth.csv." in streaming
    report.finish(tmp_path, plots=False)
    assert hidden(tmp_path) == [] and (tmp_path / "truth.csv").read_text().startswith("t_s,")


def test_fprime_lite_sim_writes_under_recognisable_names_and_cleans_its_folder(tmp_path, monkeypatch, killed_leftover,
                                                                                 hidden):
    """TMP-21: ``fprime-lite sim`` writes summary.json and rate.csv through recognisable temporary
    files and first removes what a killed run left in its output folder."""
    out = tmp_path / "sim"
    old = killed_leftover(out, "rate.csv")
    written = []
    replace = os.replace

    def spy(src, dst):
        written.append(os.path.basename(src))
        replace(src, dst)

    monkeypatch.setattr(os, "replace", spy)
    assert _sim(["default", "--duration", "2", "--out", str(out)]) == 0
    assert not old.exists()
    plots = {"rates.png", "beta.png", "quaternion_orbit.png"}  # fprime-lite sim draws them (issue 28)
    assert len(written) == 2 + len(plots) and all(is_temporary_name(n) for n in written)
    assert hidden(out) == [] and {p.name for p in out.iterdir()} == {"summary.json", "rate.csv"} | plots
