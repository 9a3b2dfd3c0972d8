"""The Basilisk side-by-side bench piece: found as a plug-in, says how to install Basilisk when it is
missing, and (when Basilisk is installed) forms its ratios from the runs it reports. Timings are
never asserted."""

import argparse
import pathlib

import pytest

from basilisk import bench as comparison
from detumble.tools import bench_basilisk as shim
from fprime_lite.tools.plugins import bench_pieces

REFERENCE = pathlib.Path(__file__).resolve().parents[2] / "deployments" / "proves_ref" / "topology.yaml"


def test_the_basilisk_piece_is_installed_as_a_bench_plug_in():
    """PLUG-004: fprime-lite bench finds the Basilisk comparison through its entry point."""
    assert bench_pieces()["basilisk"] is shim.BASILISK_PIECE


def test_without_basilisk_the_piece_measures_nothing_and_says_how_to_install(monkeypatch):
    """PERF-BSK-001: Basilisk missing -> no child is started; the table row gives the pip command."""
    monkeypatch.setattr(comparison, "basilisk_installed", lambda: False)
    monkeypatch.setattr(comparison, "_child", lambda argv: pytest.fail("no run without Basilisk"))
    figures = shim.BASILISK_PIECE.measure(argparse.Namespace(topology=str(REFERENCE), duration=None))
    assert figures == {"installed": False, "how_to_install": comparison.INSTALL_HINT}
    (row,) = shim.BASILISK_PIECE.rows(figures)
    assert "pip install -e '.[bsk]'" in row[1]



def test_outside_a_checkout_the_piece_says_where_the_comparison_is(monkeypatch, tmp_path):
    """PERF-BSK-006: the comparison is not installed with the package: without a checkout's
    benchmarks/basilisk/ beside src/ the piece runs nothing and its row names the script to run."""
    monkeypatch.setattr(shim, "BENCHMARKS", tmp_path / "benchmarks")
    monkeypatch.setattr(comparison, "_child", lambda argv: pytest.fail("nothing runs outside a checkout"))
    figures = shim.BASILISK_PIECE.measure(argparse.Namespace(topology=str(REFERENCE), duration=None))
    assert figures == {"installed": False, "how_to_run": shim.NOT_IN_A_CHECKOUT}
    (row,) = shim.BASILISK_PIECE.rows(figures)
    assert row[1].startswith("not measured:") and "python benchmarks/bench_vs_basilisk.py" in row[1]


def test_the_script_without_basilisk_exits_2_with_the_pip_command(monkeypatch, capsys):
    """PERF-BSK-007: python benchmarks/bench_vs_basilisk.py without Basilisk: exit 2, the pip command."""
    import bench_vs_basilisk

    monkeypatch.setattr(bench_vs_basilisk, "basilisk_installed", lambda: False)
    assert bench_vs_basilisk.main([]) == 2
    assert "pip install -e '.[bsk]'" in capsys.readouterr().err

@pytest.mark.slow
@pytest.mark.skipif(not comparison.basilisk_installed(),
                    reason="Basilisk is not installed (pip install -e '.[bsk]')")
def test_a_short_side_by_side_run_reports_every_kind_and_consistent_ratios():
    """PERF-BSK-002: 20 s simulated, one round: the six kinds ran for the asked time and the
    ratios are the quotients of the reported real-time factors (the run kind's against the faster
    Basilisk at 50 Hz)."""
    d = comparison.measure(REFERENCE, duration_s=20.0, rounds=1)
    assert set(d["runs"]) == {"basilisk_20hz", "fprime_lite_plant_20hz", "basilisk_50hz", "basilisk_lean_50hz",
                              "fprime_lite_deployment_50hz", "fprime_lite_run_50hz"}
    assert all(len(v) == 1 and v[0]["sim_seconds"] == pytest.approx(20.0) for v in d["runs"].values())
    b = d["best_real_time_factor"]
    assert d["plant_20hz_over_basilisk"] == pytest.approx(b["fprime_lite_plant_20hz"] / b["basilisk_20hz"])
    assert d["deployment_50hz_over_basilisk"] == pytest.approx(b["fprime_lite_deployment_50hz"] / b["basilisk_50hz"])
    assert d["run_50hz_over_fastest_basilisk"] == pytest.approx(
        b["fprime_lite_run_50hz"] / max(b["basilisk_50hz"], b["basilisk_lean_50hz"]))
    # 20 s is far from detumbled: no side reports |w| < 1 deg/s yet
    assert d["case_a_time_below_1_deg_s"] == {"basilisk": None, "basilisk_lean": None, "fprime_lite": None}
    assert len(shim.BASILISK_PIECE.rows(d)) == 5


def test_cases_are_interleaved_round_by_round_and_ratios_are_quotients(monkeypatch):
    """PERF-BSK-003: measure_cases flies every kind of every case once per round, in the same order
    each round, and forms each ratio from the fastest (and the median) rounds of its two kinds."""
    calls = []
    factor = {"basilisk_adcs_c_50hz": 1000.0, "basilisk_adcs_python_50hz": 500.0, "fprime_lite_adcs_ref_50hz": 100.0,
              "fprime_lite_adcs_plant_50hz": 400.0, "basilisk_coursework_100hz": 80.0,
              "fprime_lite_coursework_100hz": 60.0}

    def fake_child(argv):
        text = " ".join(argv)
        if "basilisk.adcs" in text:
            kind = "basilisk_adcs_c_50hz" if argv[-1] == "c" else "basilisk_adcs_python_50hz"
        elif "plant_only_settings" in text:
            kind = "fprime_lite_adcs_plant_50hz"
        elif "basilisk.coursework" in text:
            kind = "basilisk_coursework_100hz"
        else:
            kind = "fprime_lite_adcs_ref_50hz" if "adcs_ref" in text else "fprime_lite_coursework_100hz"
        calls.append(kind)
        scale = 1.0 + 0.1 * calls.count(kind)  # a later round of a kind is faster
        return {"sim_seconds": 10.0, "real_time_factor": factor[kind] * scale, "slew1_settle_s": 1.0}

    monkeypatch.setattr(comparison, "_child", fake_child)
    monkeypatch.setattr(comparison, "_warm_bytecode", lambda: None)
    d = comparison.measure_cases(["adcs_ref", "coursework"], duration_s=10.0, rounds=2)
    one_round = ["basilisk_adcs_c_50hz", "basilisk_adcs_python_50hz", "fprime_lite_adcs_ref_50hz",
                 "fprime_lite_adcs_plant_50hz", "basilisk_coursework_100hz", "fprime_lite_coursework_100hz"]
    assert calls == one_round * 2
    a, c = d["adcs_ref"], d["coursework"]
    assert a["adcs_ref_over_basilisk_c"] == pytest.approx((100.0 * 1.2) / (1000.0 * 1.2))
    assert a["median_adcs_ref_over_basilisk_python"] == pytest.approx((100.0 * 1.15) / (500.0 * 1.15))
    assert a["adcs_laws_alone_over_basilisk_c"] == pytest.approx(400.0 / 1000.0)
    assert a["adcs_ref_tick_over_plant_only_tick"] == pytest.approx(400.0 / 100.0)
    assert c["coursework_over_basilisk"] == pytest.approx(60.0 / 80.0)
    assert set(a["plausibility"]) == {"basilisk_adcs_c_50hz", "basilisk_adcs_python_50hz", "fprime_lite_adcs_ref_50hz",
                                      "fprime_lite_adcs_plant_50hz"}
    assert a["plausibility"]["fprime_lite_adcs_ref_50hz"] == {"slew1_settle_s": 1.0}
    rows = shim.BASILISK_PIECE.rows(a)  # four ratios, four plausibility lines
    assert len(rows) == 8 and "0.10" in rows[0][1] and "slew1_settle_s 1" in rows[7][1]
    # issue 32's goal: the same laws in Python, ≥ 1.0; the C laws and the laws alone are context
    assert [r[2] for r in rows[:4]] == ["context", "≥ 1.0", "context", "context"]


def test_the_run_ratio_is_taken_against_the_faster_basilisk_of_each_round(monkeypatch):
    """PERF-BSK-008: proves_ref's goal ratio (issue 32) divides ``fprime-lite run``'s real-time
    factor by the faster of the two Basilisk 50 Hz configurations, whichever it is, and the
    lean configuration is flown as ``case_a --lean``."""
    factor = {"basilisk_20hz": 300.0, "fprime_lite_plant_20hz": 3000.0, "basilisk_50hz": 250.0,
              "basilisk_lean_50hz": 400.0, "fprime_lite_deployment_50hz": 700.0, "fprime_lite_run_50hz": 500.0}
    argvs = {}

    def fake_child(argv):
        text = " ".join(argv)
        if "basilisk.case_a" in text:
            kind = ("basilisk_lean_50hz" if "--lean" in argv else
                    "basilisk_20hz" if "0.05" in argv else "basilisk_50hz")
        elif "run_deployment" in text:
            kind = "fprime_lite_run_50hz"
        elif "load_scenario" in text:
            kind = "fprime_lite_plant_20hz"
        else:
            kind = "fprime_lite_deployment_50hz"
        argvs[kind] = argv
        return {"sim_seconds": 10.0, "real_time_factor": factor[kind], "time_below_1_deg_s": None}

    monkeypatch.setattr(comparison, "_child", fake_child)
    monkeypatch.setattr(comparison, "_warm_bytecode", lambda: None)
    d = comparison.measure(REFERENCE, duration_s=10.0, rounds=1)
    assert set(argvs) == set(factor)
    assert d["run_50hz_over_fastest_basilisk"] == pytest.approx(500.0 / 400.0)
    factor["basilisk_50hz"] = 450.0  # now the first-written configuration is the faster one
    d = comparison.measure(REFERENCE, duration_s=10.0, rounds=1)
    assert d["run_50hz_over_fastest_basilisk"] == pytest.approx(500.0 / 450.0)
    rows = shim.BASILISK_PIECE.rows(d)
    assert rows[0][2] == "≥ 2.0" and "500 / 450 = 1.11" in rows[0][1]


def test_the_bench_piece_picks_the_case_of_the_deployment_it_is_given():
    """PERF-BSK-005: adcs_ref's and coursework's own topologies fly their cases; any other
    deployment is compared with Basilisk's case A (proves_ref)."""
    deployments = REFERENCE.parents[1]
    assert comparison.case_of(deployments / "adcs_ref" / "topology.yaml") == "adcs_ref"
    assert comparison.case_of(deployments / "coursework" / "topology.yaml") == "coursework"
    assert comparison.case_of(REFERENCE) == "proves_ref"
    assert comparison.case_of("some/other/topology.yaml") == "proves_ref"


def test_an_unknown_case_is_refused_with_the_choices():
    """PERF-BSK-004: a case name that does not exist names the ones that do."""
    with pytest.raises(ValueError, match="proves_ref, adcs_ref, coursework"):
        comparison.measure_cases(["adcs"], duration_s=1.0, rounds=1)


def test_children_run_with_a_bytecode_cache_of_their_own(monkeypatch):
    """PERF-BSK-010: the children import this package and keep compiled bytecode, as a user's install
    does, even where the parent's environment forbids writing it (the build machines'
    PYTHONDONTWRITEBYTECODE: every child compiled ~140 modules, 0.3-0.45 s of CPU a run)."""
    monkeypatch.setenv("PYTHONDONTWRITEBYTECODE", "1")
    monkeypatch.delenv("PYTHONPYCACHEPREFIX", raising=False)
    env = comparison._child_env()
    assert "PYTHONDONTWRITEBYTECODE" not in env
    assert env["PYTHONPYCACHEPREFIX"] == str(comparison._BYTECODE_CACHE)
    assert str(comparison.BENCHMARKS) in env["PYTHONPATH"].split(":")
