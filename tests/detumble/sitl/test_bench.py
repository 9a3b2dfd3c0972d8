"""The detumble bench piece runs and its figures are consistent (its timings are never asserted)."""

import pathlib

import pytest

from fprime_lite.tools.plugins import bench_pieces

REFERENCE = pathlib.Path(__file__).resolve().parents[3] / "deployments" / "proves_ref" / "topology.yaml"


def test_deployment_measurement_interleaves_pieces_and_reports_consistent_figures():
    from detumble.sitl.bench import measure_deployment

    d = measure_deployment(REFERENCE, duration_s=8.0, chunks=2)
    pieces = d["pieces_us_per_tick"]
    assert len(pieces["deployment"]) == len(pieces["plant_only"]) == 2
    assert d["deployment_us_per_tick"] == min(pieces["deployment"])
    assert d["tick_cost_ratio"] == pytest.approx(min(pieces["deployment"]) / min(pieces["plant_only"]))
    assert d["ticks_50hz_per_s"] * d["deployment_wall_s"] == pytest.approx(8.0 * 50 + 1, abs=1)
    assert d["sim_seconds"] == 8.0 and d["real_time_factor"] > 0


def test_the_piece_is_installed_as_a_bench_plug_in():
    """PLUG-003: fprime-lite bench finds the detumble piece through its entry point."""
    from detumble.sitl.bench import DEPLOYMENT_PIECE

    assert bench_pieces()["deployment"] is DEPLOYMENT_PIECE
