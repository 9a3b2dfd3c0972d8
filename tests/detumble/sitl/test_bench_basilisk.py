"""The Basilisk side-by-side bench piece: found as a plug-in, says how to install Basilisk when it is
missing, and (when Basilisk is installed) forms its ratios from the runs it reports. Timings are
never asserted."""

import argparse
import pathlib

import pytest

from detumble.sitl import bench_basilisk
from fprime_lite.tools.plugins import bench_pieces

REFERENCE = pathlib.Path(__file__).resolve().parents[3] / "deployments" / "proves_ref" / "topology.yaml"


def test_the_basilisk_piece_is_installed_as_a_bench_plug_in():
    """PLUG-004: fprime-lite bench finds the Basilisk comparison through its entry point."""
    assert bench_pieces()["basilisk"] is bench_basilisk.BASILISK_PIECE


def test_without_basilisk_the_piece_measures_nothing_and_says_how_to_install(monkeypatch):
    """PERF-BSK-001: Basilisk missing -> no child is started; the table row gives the pip command."""
    monkeypatch.setattr(bench_basilisk, "basilisk_installed", lambda: False)
    monkeypatch.setattr(bench_basilisk, "_child", lambda argv: pytest.fail("no run without Basilisk"))
    figures = bench_basilisk.BASILISK_PIECE.measure(argparse.Namespace(topology=str(REFERENCE), duration=None))
    assert figures == {"installed": False, "how_to_install": bench_basilisk.INSTALL_HINT}
    (row,) = bench_basilisk.BASILISK_PIECE.rows(figures)
    assert "pip install -e '.[bsk]'" in row[1]


@pytest.mark.slow
@pytest.mark.skipif(not bench_basilisk.basilisk_installed(),
                    reason="Basilisk is not installed (pip install -e '.[bsk]')")
def test_a_short_side_by_side_run_reports_every_kind_and_consistent_ratios():
    """PERF-BSK-002: 20 s simulated, one round: the four kinds ran for the asked time and the
    ratios are the quotients of the reported real-time factors."""
    d = bench_basilisk.measure(REFERENCE, duration_s=20.0, rounds=1)
    assert set(d["runs"]) == {"basilisk_20hz", "fprime_lite_plant_20hz", "basilisk_50hz", "fprime_lite_deployment_50hz"}
    assert all(len(v) == 1 and v[0]["sim_seconds"] == pytest.approx(20.0) for v in d["runs"].values())
    b = d["best_real_time_factor"]
    assert d["plant_20hz_over_basilisk"] == pytest.approx(b["fprime_lite_plant_20hz"] / b["basilisk_20hz"])
    assert d["deployment_50hz_over_basilisk"] == pytest.approx(b["fprime_lite_deployment_50hz"] / b["basilisk_50hz"])
    # 20 s is far from detumbled: neither side reports |w| < 1 deg/s yet
    assert d["case_a_time_below_1_deg_s"] == {"basilisk": None, "fprime_lite": None}
    assert len(bench_basilisk.BASILISK_PIECE.rows(d)) == 3
