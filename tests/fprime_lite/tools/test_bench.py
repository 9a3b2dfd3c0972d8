"""The benchmark code runs (its timings are never asserted)."""

import pytest

from fprime_lite.tools.bench import measure_port_call


def test_port_call_measurement_runs_through_a_connected_port():
    r = measure_port_call(number=2_000, repeat=2)
    assert r["plain_ns"] > 0 and r["port_ns"] > 0
    # the ratio is formed from seconds, the check from nanoseconds: equal up to rounding
    assert r["ratio"] == pytest.approx(r["port_ns"] / r["plain_ns"], rel=1e-12)


def test_deployment_measurement_interleaves_pieces_and_reports_consistent_figures():
    from fprime_lite.tools.bench import measure_deployment

    d = measure_deployment(duration_s=8.0, chunks=2)
    pieces = d["pieces_us_per_tick"]
    assert len(pieces["deployment"]) == len(pieces["plant_only"]) == 2
    assert d["deployment_us_per_tick"] == min(pieces["deployment"])
    assert d["tick_cost_ratio"] == pytest.approx(min(pieces["deployment"]) / min(pieces["plant_only"]))
    assert d["ticks_50hz_per_s"] * d["deployment_wall_s"] == pytest.approx(8.0 * 50 + 1, abs=1)
    assert d["sim_seconds"] == 8.0 and d["real_time_factor"] > 0
