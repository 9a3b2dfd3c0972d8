"""The benchmark code runs (its timings are never asserted)."""

import pytest

from fprime_lite.tools.bench import measure_port_call


def test_port_call_measurement_runs_through_a_connected_port():
    r = measure_port_call(number=2_000, repeat=2)
    assert r["plain_ns"] > 0 and r["port_ns"] > 0
    # the ratio is formed from seconds, the check from nanoseconds: equal up to rounding
    assert r["ratio"] == pytest.approx(r["port_ns"] / r["plain_ns"], rel=1e-12)


def test_a_piece_s_rows_are_printed_as_written(capsys):
    """BENCH-002: a bench piece's text reaches the table verbatim; rich markup in it (the Basilisk piece's
    "pip install -e '.[bsk]'") is not taken for a style tag and dropped."""
    from fprime_lite.tools.bench import _print
    from fprime_lite.tools.plugins import BenchPiece

    piece = BenchPiece("demo", measure=lambda options: {}, rows=lambda f: [("demo", "pip install -e '.[bsk]'", "[b]")])
    _print({"port_call": {"port_ns": 2.0, "plain_ns": 1.0, "ratio": 2.0}, "peak_rss_mb": 10.0, "demo": {}},
           {"demo": piece})
    out = capsys.readouterr().out
    assert "pip install -e '.[bsk]'" in out and "[b]" in out
