"""benchmarks/bench_outputs.py (issue 32): what a run's outputs cost, by the child's own timing, its CPU and
the whole process's wall time, like for like; bench_vs_basilisk's kinds beside them. Timings are never
asserted: the shares are checked on given rounds, and each kind's child is flown once, briefly."""

from __future__ import annotations

import pathlib

import pytest

import bench_outputs

REFERENCE = str(pathlib.Path(__file__).resolve().parents[2] / "deployments" / "proves_ref" / "topology.yaml")


def test_the_shares_come_from_each_kinds_fastest_round_by_each_measure():
    """BENCH-020: each kind's best is its fastest round in each measure on its own (wall, CPU, whole
    process; bench_vs_basilisk's kinds have no CPU figure); the outputs' share is 1 − deployment / run in
    each measure, with the writer process too, and by bench_vs_basilisk's kinds."""
    rounds = {
        "deployment": [(6.0, 5.9, 6.6), (6.2, 5.8, 6.4)],
        "run": [(7.5, 6.9, 8.0), (7.0, 7.2, 8.2)],
        "run_process": [(6.6, 6.3, 7.4), (6.9, 6.2, 7.0)],
        "vs_basilisk_deployment": [(5.5, None, 6.5), (5.6, None, 6.6)],
        "vs_basilisk_run": [(6.4, None, 6.6), (6.3, None, 6.5)],
    }
    flown: list[str] = []

    def fly(kind, topology, duration_s):
        wall, cpu, process = rounds[kind][sum(k == kind for k in flown)]
        flown.append(kind)
        return {"wall_s": wall, "cpu_s": cpu, "process_wall_s": process}

    result = bench_outputs.measure("t.yaml", 10.0, 2, tuple(rounds), fly=fly)
    assert flown == list(rounds) * 2  # alternating rounds
    assert result["best"]["deployment"] == {"wall_s": 6.0, "cpu_s": 5.8, "process_wall_s": 6.4}
    assert result["best"]["vs_basilisk_run"] == {"wall_s": 6.3, "cpu_s": None, "process_wall_s": 6.5}
    assert result["outputs_share_wall"] == pytest.approx(1 - 6.0 / 7.0)
    assert result["outputs_share_cpu"] == pytest.approx(1 - 5.8 / 6.9)
    assert result["outputs_share_process_wall"] == pytest.approx(1 - 6.4 / 8.0)
    assert result["outputs_share_wall_writer_process"] == pytest.approx(1 - 6.0 / 6.6)
    assert result["outputs_share_process_wall_writer_process"] == pytest.approx(1 - 6.4 / 7.0)
    assert result["outputs_share_vs_basilisk"] == pytest.approx(1 - 5.5 / 6.3)


@pytest.mark.parametrize("kind", ["deployment", "run", "run_process", "vs_basilisk_deployment", "vs_basilisk_run"])
def test_each_kind_flies_and_is_timed_from_outside_too(kind):
    """BENCH-021: each kind's child flies (two simulated seconds of proves_ref) and reports its own wall time,
    which the whole process's, timed from outside, contains; the CPU figure where the child measures it."""
    figures = bench_outputs.fly(kind, REFERENCE, 2.0)
    assert 0.0 < figures["wall_s"] < figures["process_wall_s"]
    assert (figures["cpu_s"] is None) == kind.startswith("vs_basilisk")


def test_a_base_revision_is_flown_in_the_same_rounds_first():
    """BENCH-022: with ``base_src`` each round flies every kind with the base's sources, then with this
    checkout's ``src``; each side's figures are formed from its own rounds only."""
    flown: list[tuple[str, str | None]] = []

    def fly(kind, topology, duration_s, src=None):
        flown.append((kind, src))
        wall = {"deployment": 6.0, "run": 7.0}[kind] + (0.5 if src == "/base/src" else 0.0) + 0.1 * len(flown)
        return {"wall_s": wall, "cpu_s": wall, "process_wall_s": wall + 0.2}

    result = bench_outputs.measure("t.yaml", 10.0, 2, ("deployment", "run"), fly=fly, base_src="/base/src")
    here = str(bench_outputs.REPO / "src")
    one_round = [("deployment", "/base/src"), ("run", "/base/src"), ("deployment", here), ("run", here)]
    assert flown == one_round * 2
    assert result["base"]["src"] == "/base/src" and result["src"] == here
    assert result["base"]["best"]["deployment"]["wall_s"] == pytest.approx(6.6)
    assert result["best"]["deployment"]["wall_s"] == pytest.approx(6.3)
    assert result["best"]["run"]["wall_s"] == pytest.approx(7.4)
    assert result["median"]["run"]["wall_s"] == pytest.approx((7.4 + 7.8) / 2)
    assert result["outputs_share_wall"] == pytest.approx(1 - 6.3 / 7.4)
    assert result["base"]["outputs_share_wall"] == pytest.approx(1 - 6.6 / 7.7)
