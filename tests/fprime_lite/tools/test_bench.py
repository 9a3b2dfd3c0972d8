"""The benchmark code runs (its timings are never asserted)."""

import pytest

from fprime_lite.tools.bench import measure_port_call


def test_port_call_measurement_runs_through_a_connected_port():
    r = measure_port_call(number=2_000, repeat=2)
    assert r["plain_ns"] > 0 and r["port_ns"] > 0
    # the ratio is formed from seconds, the check from nanoseconds: equal up to rounding
    assert r["ratio"] == pytest.approx(r["port_ns"] / r["plain_ns"], rel=1e-12)
