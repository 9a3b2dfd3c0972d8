"""Plant-only command: outputs, exit codes, error messages without tracebacks."""

import csv
import json
import os

from detumble.sim.runner import main, write_atomic


def test_main_writes_summary_and_rate_csv(tmp_path, capsys):
    out = tmp_path / "run"
    code = main(["case_a", "--law", "kopt", "--out", str(out), "--duration", "60"])
    assert code == 0
    summary = json.loads((out / "summary.json").read_text())
    for key in ("sim_seconds", "wall_seconds", "final_rate_deg_s", "time_below_1_deg_s"):
        assert key in summary
    assert summary["sim_seconds"] == 60.0 and summary["time_below_1_deg_s"] is None
    assert summary["law"] == "kopt" and summary["scenario"] == "case_a"
    rows = list(csv.reader((out / "rate.csv").open()))
    assert rows[0][:5] == ["time_s", "omega_x_deg_s", "omega_y_deg_s", "omega_z_deg_s", "rate_deg_s"]
    assert len(rows) == 62 and float(rows[1][4]) == 30.0 and float(rows[-1][0]) == 60.0
    assert float(rows[-1][4]) < 30.0
    assert sorted(os.listdir(out)) == ["rate.csv", "summary.json"]  # no temp files left
    assert "case_a: law kopt" in capsys.readouterr().out


def test_scenario_option_seed_and_bdot_gain(tmp_path):
    out = tmp_path / "r"
    assert main(["--scenario", "default", "--law", "bdot", "--gain", "2.0", "--seed", "4",
                 "--duration", "2", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert (s["law"], s["gain"], s["seed"]) == ("bdot", 2.0, 4)


def test_missing_file_and_bad_scenario_are_clear_errors(tmp_path, capsys):
    assert main(["no_such_scenario.yaml", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: no_such_scenario.yaml: no such scenario file") and "Traceback" not in err
    bad = tmp_path / "bad.yaml"
    bad.write_text("orbit:\n  altitude_km: -3\n")
    assert main([str(bad), "--out", str(tmp_path / "y")]) == 2
    err = capsys.readouterr().err
    assert f"error: {bad}:2: orbit.altitude_km: -3.0 km is inside the Earth" in err and "Traceback" not in err
    assert not (tmp_path / "y").exists()
    assert main(["case_a", "--out", str(tmp_path / "z"), "--duration", "-1"]) == 2
    assert "--duration must be a positive number of seconds" in capsys.readouterr().err
    assert main(["case_a", "--law", "magic", "--out", str(tmp_path / "z")]) == 2
    assert "invalid choice: 'magic'" in capsys.readouterr().err


def test_write_atomic_replaces_whole_file(tmp_path):
    target = tmp_path / "f.txt"
    target.write_text("old")
    write_atomic(str(target), "new content\n")
    assert target.read_text() == "new content\n"
    assert os.listdir(tmp_path) == ["f.txt"]


def test_set_overrides_a_scenario_value_and_names_a_bad_key(tmp_path, capsys):
    out = tmp_path / "r"
    assert main(["default", "--set", "initial.rate.magnitude_deg_s=7", "--duration", "1", "--out", str(out)]) == 0
    assert abs(json.loads((out / "summary.json").read_text())["initial_rate_deg_s"] - 7.0) < 1e-9
    assert main(["default", "--set", "initial.rat=1", "--out", str(tmp_path / "x")]) == 2
    assert "has no key 'rat' at initial" in capsys.readouterr().err


def test_an_output_folder_that_cannot_be_written_is_refused_before_flying(tmp_path, capsys, monkeypatch):
    import detumble.sim.runner as runner

    flown = []
    monkeypatch.setattr(runner, "run", lambda *a, **k: flown.append(a))
    a_file = tmp_path / "a_file"
    a_file.write_text("keep me\n")
    assert main(["case_a", "--out", str(a_file), "--duration", "1"]) == 2
    assert f"error: --out {a_file}: is a file, not a folder" in capsys.readouterr().err
    assert main(["case_a", "--out", str(a_file / "sub"), "--duration", "1"]) == 2
    err = capsys.readouterr().err
    assert f"error: --out {a_file / 'sub'}: cannot create the folder" in err and "Traceback" not in err
    assert a_file.read_text() == "keep me\n" and flown == []


def test_a_run_refused_after_its_folder_was_made_leaves_no_empty_folder(tmp_path, capsys):
    out = tmp_path / "new"
    assert main(["case_a", "--law", "wheels_pd", "--out", str(out), "--duration", "1"]) == 2
    assert "error: wheels_pd needs three reaction wheels" in capsys.readouterr().err  # case_a has none
    assert not out.exists()


def test_each_law_takes_its_own_default_gain_not_the_scenario_s(tmp_path, capsys):
    """SIM-GAIN-001 (issue 28): the scenario's control.gain belongs to its control.law (default.yaml: bdot,
    3.0 A·m²·s/G). `--law kopt` on it flies kopt's own k = 2n(1 + sin i)J_min (it flew k = 3.0); `--law
    beta_pd` flies (it failed on a --gain nobody gave); the scenario's own law still takes its gain; and a
    --gain for a law that has none is refused."""
    from detumble.sim.laws import kopt_gain
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario
    import numpy as np

    plant = Plant(load_scenario("default"))
    j_min = float(min(np.linalg.eigvalsh(np.array(plant.body.inertia))))
    k_star = kopt_gain(plant.orbit.mean_motion, plant.orbit.inclination_rad, j_min)
    assert main(["default", "--law", "kopt", "--duration", "2", "--out", str(tmp_path / "k")]) == 0
    assert json.loads((tmp_path / "k" / "summary.json").read_text())["gain"] == k_star != 3.0
    assert main(["default", "--law", "beta_pd", "--duration", "2", "--out", str(tmp_path / "b")]) == 0
    assert main(["default", "--duration", "2", "--out", str(tmp_path / "own")]) == 0  # bdot, the scenario's law
    assert json.loads((tmp_path / "own" / "summary.json").read_text())["gain"] == 3.0
    capsys.readouterr()
    assert main(["default", "--law", "none", "--gain", "2", "--duration", "2", "--out", str(tmp_path / "n")]) == 2
    err = capsys.readouterr().err
    assert "--gain does not apply to none, which has no gain; laws with one gain: kopt, bdot, cross_product" in err
    assert not (tmp_path / "n").exists()


def test_the_rate_column_is_the_deployment_truth_s_expression():
    """SIM-RATE-001 (issue 27): the plant-only rate is |ω| computed as the deployment's truth and Plant.rate_deg_s
    compute it (``w * w``, not ``w ** 2``: libm pow and a product differ in the last bit for about one input in
    a thousand, which made ADCS-078 differ by one ulp in one of 401 rates once the field changed). 0.09105 °/s on
    the adcs axis is such an input: ``** 2`` gives 0.09105000000000002, the product 0.09105."""
    import math

    from detumble.sim.plant import Plant
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    scenario = load_scenario("adcs", settings=["initial.rate.magnitude_deg_s=0.09105"])
    w = Plant(scenario).omega_BN_B
    assert math.degrees(math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)) != Plant(scenario).rate_deg_s  # the case
    assert run(scenario, law="bdot", duration_s=0.02).rows[0][4] == Plant(scenario).rate_deg_s
