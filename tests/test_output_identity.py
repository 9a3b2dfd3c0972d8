"""tools/output_identity.py: "outputs identical" as a command anyone can run between two revisions.

The script is checked the way it is used: a checkout against itself must come out identical, and a checkout
whose flight differs (a scenario's initial tumble changed by 1 °/s) must be reported, naming the file and
where it first differs; the wall-clock measurements that differ between any two runs are the only thing it
leaves out.
"""

import importlib.util
import json
import pathlib
import shutil
import sys

import pytest

ROOT = pathlib.Path(__file__).parents[1]
_spec = importlib.util.spec_from_file_location("output_identity", ROOT / "tools" / "output_identity.py")
assert _spec is not None and _spec.loader is not None
identity = importlib.util.module_from_spec(_spec)
sys.modules["output_identity"] = identity  # dataclasses look their module up there
_spec.loader.exec_module(identity)


def _copy_checkout(target: pathlib.Path) -> pathlib.Path:
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", ".venv", "runs")
    for part in ("src", "deployments", "campaigns"):
        shutil.copytree(ROOT / part, target / part, ignore=ignore)
    return target


@pytest.fixture(scope="module")
def perturbed(tmp_path_factory):
    """A copy of this checkout whose reference scenario starts at 29 °/s instead of 30 °/s."""
    tree = _copy_checkout(tmp_path_factory.mktemp("perturbed"))
    scenario = tree / "src" / "detumble" / "sim" / "scenarios" / "default.yaml"
    text = scenario.read_text()
    assert "magnitude_deg_s: 30.0" in text
    scenario.write_text(text.replace("magnitude_deg_s: 30.0", "magnitude_deg_s: 29.0", 1))
    return tree


def test_a_checkout_flies_identically_to_itself(capsys, tmp_path):
    status = identity.main([str(ROOT), str(ROOT), "--quick", "--cases", "proves_ref,sim_kopt,params_proves_ref",
                            "--keep", str(tmp_path)])
    out = capsys.readouterr().out
    assert status == 0, out
    assert "DIFFERS" not in out
    assert "proves_ref/truth.csv" in out and "sim_kopt/rate.csv" in out and "params_proves_ref/params.dat" in out
    assert "files identical" in out
    flown = json.loads((tmp_path / "base-out" / "sim_kopt" / "summary.json").read_text())
    assert flown["law"] == "kopt"  # the case flies the law it names, not the scenario's own


def test_every_case_flies_what_it_names(tmp_path):
    """Each plant-only case passes its law and its settings; each deployment case its settings and sequence."""
    for case in identity.CASES:
        argv = identity._command(case, tmp_path, tmp_path / case.name, quick=False)
        for setting in case.settings:
            assert f"--set={setting}" in argv, (case.name, setting)
        for arg in case.extra:
            assert arg in argv, (case.name, arg)
        if case.kind == "sim":
            assert "--law" in argv and argv[argv.index("--law") + 1] in case.name, case.name


def test_a_different_flight_is_reported_with_where_it_differs(perturbed, capsys):
    status = identity.main([str(ROOT), str(perturbed), "--quick", "--cases", "proves_ref,params_proves_ref"])
    out = capsys.readouterr().out
    assert status == 1, out
    truth = next(line for line in out.splitlines() if line.startswith("proves_ref/truth.csv"))
    assert "DIFFERS: line 2, wx_deg_s" in truth  # the first sample after the header: 30 against 29 °/s in all
    assert any(line.startswith("proves_ref/summary.json") and "DIFFERS: final_rate_deg_s" in line
               for line in out.splitlines())
    params = next(line for line in out.splitlines() if line.startswith("params_proves_ref/params.dat"))
    assert params.endswith("identical")  # the parameters did not change: only the flight did


def test_wall_clock_measurements_are_the_only_thing_left_out(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    summary = {"sim_seconds": 10.0, "wall_seconds": 0.2, "real_time_factor": 50.0, "final_rate_deg_s": 1.5}
    (a / "summary.json").write_text(json.dumps(summary))
    (b / "summary.json").write_text(json.dumps({**summary, "wall_seconds": 0.3, "real_time_factor": 33.3}))
    assert identity.compare_file(a / "summary.json", b / "summary.json") is None
    (b / "summary.json").write_text(json.dumps({**summary, "final_rate_deg_s": 1.5000000000000002}))
    assert identity.compare_file(a / "summary.json", b / "summary.json") == (
        "final_rate_deg_s: 1.5 against 1.5000000000000002")

    (b / "summary.json").write_text(json.dumps({**summary, "extra": {"annotation": "units: s"}}))
    assert identity.compare_file(a / "summary.json", b / "summary.json") == "key extra only in OTHER"
    (a / "summary.json").write_text(json.dumps({**summary, "extra": {}}))
    assert identity.compare_file(a / "summary.json", b / "summary.json", ignored_keys=frozenset({"annotation"})) is None

    head = "time,channel,value\n"
    (a / "channels.csv").write_text(head + "1.0,D.rateGroup50Hz.RgMaxTime,114 us\n1.0,D.ctrl.Mode,AUTO\n")
    (b / "channels.csv").write_text(head + "1.0,D.rateGroup50Hz.RgMaxTime,103 us\n1.0,D.ctrl.Mode,AUTO\n")
    assert identity.compare_file(a / "channels.csv", b / "channels.csv") is None
    (b / "channels.csv").write_text(head + "1.0,D.rateGroup50Hz.RgMaxTime,103 us\n1.0,D.ctrl.Mode,MANUAL\n")
    assert identity.compare_file(a / "channels.csv", b / "channels.csv") == "line 3, value: 'AUTO' against 'MANUAL'"


def test_a_side_that_is_not_a_checkout_is_a_clear_error(tmp_path, capsys):
    assert identity.main([str(tmp_path), str(ROOT), "--cases", "params_proves_ref"]) == 2
    assert "not a checkout of fprime-lite" in capsys.readouterr().err
    assert identity.main(["no-such-revision-xyz", str(ROOT), "--cases", "params_proves_ref"]) == 2
    assert "neither a folder nor a git revision" in capsys.readouterr().err
    assert identity.main(["--cases", "nope"]) == 2
    assert "unknown case(s) nope" in capsys.readouterr().err
