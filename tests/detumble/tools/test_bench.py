"""The detumble bench piece runs and its figures are consistent (its timings are never asserted)."""

import pathlib

import pytest

from fprime_lite.tools.plugins import bench_pieces

REFERENCE = pathlib.Path(__file__).resolve().parents[3] / "deployments" / "proves_ref" / "topology.yaml"


def test_deployment_measurement_interleaves_pieces_and_reports_consistent_figures():
    from detumble.tools.bench import measure_deployment

    d = measure_deployment(REFERENCE, duration_s=8.0, chunks=2)
    pieces = d["pieces_us_per_tick"]
    assert len(pieces["deployment"]) == len(pieces["plant_only"]) == 2
    assert d["deployment_us_per_tick"] == min(pieces["deployment"])
    assert d["tick_cost_ratio"] == pytest.approx(min(pieces["deployment"]) / min(pieces["plant_only"]))
    assert d["ticks_per_s"] * d["deployment_wall_s"] == pytest.approx(8.0 * 50 + 1, abs=1)
    assert d["sim_seconds"] == 8.0 and d["real_time_factor"] > 0
    assert d["tick_rate_group"] == "rateGroup50Hz" and d["tick_hz"] == 50.0 and d["plant_only_law"] == "bdot"
    cpu = d["pieces_cpu_us_per_tick"]
    assert len(cpu["deployment"]) == len(cpu["plant_only"]) == 2
    assert d["tick_cost_ratio_cpu"] == pytest.approx(min(cpu["deployment"]) / min(cpu["plant_only"]))
    assert d["fprime_part_cpu_us_per_tick"] == pytest.approx(min(cpu["deployment"]) - min(cpu["plant_only"]))
    assert d["fprime_part_us_per_tick"] == pytest.approx(min(pieces["deployment"]) - min(pieces["plant_only"]))


def test_the_other_reference_deployments_are_measured_against_their_own_plant_configuration():
    """BENCH-002: beside proves_ref the piece measures adcs_ref and coursework, each per tick of its
    fastest rate group (coursework: 100 Hz) against the plant-only runner on its own scenario."""
    import argparse

    from detumble.tools.bench import DEPLOYMENT_PIECE

    d = DEPLOYMENT_PIECE.measure(argparse.Namespace(topology=str(REFERENCE), duration=2.0))
    others = d["other_deployments"]
    assert set(others) == {"adcs_ref", "coursework"}
    adcs = others["adcs_ref"]
    assert (adcs["scenario"], adcs["tick_hz"], adcs["plant_only_law"]) == ("adcs", 50.0, "adcs")
    # the earlier counterpart, a bare B-dot, stays as a second row timed in the same pieces
    bdot = adcs["second_counterparts"]["bdot"]
    assert len(bdot["pieces_us_per_tick"]) == len(adcs["pieces_us_per_tick"]["plant_only"])
    assert bdot["tick_cost_ratio"] == pytest.approx(adcs["deployment_us_per_tick"] / bdot["plant_only_us_per_tick"])
    assert others["coursework"]["second_counterparts"] == {}
    course = others["coursework"]
    assert (course["scenario"], course["tick_hz"], course["plant_only_law"]) == ("surrey", 100.0, "wheels_pd")
    assert course["ticks_per_s"] * course["deployment_wall_s"] == pytest.approx(2.0 * 100 + 1, abs=1)
    labels = [row[0] for row in DEPLOYMENT_PIECE.rows(d)]
    assert any(label.startswith("coursework") for label in labels)
    assert any("per 100 Hz tick" in label for label in labels)
    assert sum("plant-only (adcs)" in label for label in labels) == 1
    assert sum("plant-only (bdot)" in label for label in labels) == 2  # proves_ref's, and adcs_ref's second row
    # BENCH-003 (issue 32): each deployment's F´ part of a tick in µs; only adcs_ref's has a goal
    fprime_rows = [row for row in DEPLOYMENT_PIECE.rows(d) if row[0].startswith("F´ part of a")]
    assert len(fprime_rows) == 3
    assert [row[2] for row in fprime_rows] == ["", "≤ 22 µs", ""]
    assert f"= {adcs['fprime_part_cpu_us_per_tick']:.1f} µs" in fprime_rows[1][1]


def test_the_piece_is_installed_as_a_bench_plug_in():
    """PLUG-003: fprime-lite bench finds the detumble piece through its entry point."""
    from detumble.tools.bench import DEPLOYMENT_PIECE

    assert bench_pieces()["deployment"] is DEPLOYMENT_PIECE
