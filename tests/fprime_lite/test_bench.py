"""The benchmark code runs (its timings are never asserted)."""

from fprime_lite.bench import measure_port_call


def test_port_call_measurement_runs_through_a_connected_port():
    r = measure_port_call(number=2_000, repeat=2)
    assert r["plain_ns"] > 0 and r["port_ns"] > 0
    assert r["ratio"] == r["port_ns"] / r["plain_ns"]
