"""Issue 28's run-output items: a diverging plant stops cleanly, `--set` speaks for itself, every
deployment's run and `fprime-lite sim` draws its own plots and `fprime-lite plot` draws them again."""

import json
import pathlib

import pytest

from fprime_lite.tools.cli import main

ROOT = pathlib.Path(__file__).parents[3]
DEPLOYMENTS = ROOT / "deployments"
PROVES = str(DEPLOYMENTS / "proves_ref" / "topology.yaml")


def _err_lines(capsys) -> list[str]:
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return [line for line in err.splitlines() if line.strip()]


def test_a_diverging_plant_stops_the_run_with_one_line(tmp_path, capsys):
    """O28-001: a 1e6 deg/s tumble (349 rad per dynamics step) used to fly on NaN with a traceback per
    sensor read (258 and more) and a NaN final rate. Now the run stops where the plant diverged, says why
    in one line and in summary.json (strict JSON: no NaN), and exits 1."""
    out = tmp_path / "run"
    status = main(["run", PROVES, "--duration", "5", "--no-plots", "--no-progress", "--out", str(out),
                   "--set", "initial.rate.magnitude_deg_s=1e6"])
    lines = _err_lines(capsys)
    assert status == 1
    assert len(lines) == 1
    assert lines[0].startswith("fprime-lite run: stopped: the simulated spacecraft diverged at t = ")
    assert "lower the rate or the scenario's dynamics_step_s" in lines[0]
    summary = json.loads((out / "summary.json").read_text(), parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
    assert summary["stopped_by"] == "plant diverged" and summary["stop_reason"] in lines[0]
    assert summary["ok"] is False and summary["final_rate_deg_s"] is None
    assert summary["sim_seconds"] < 1.0 and summary["handler_faults"] == 0


@pytest.mark.parametrize("value, expected", [
    ("1e1", None),  # YAML 1.1 reads 1e1 (1e6 …) as text: the command line means a number
    ("nan", "--set 'initial.rate.magnitude_deg_s=nan': nan is not a finite number; scenario values must be finite"),
    ("inf", "--set 'initial.rate.magnitude_deg_s=inf': inf is not a finite number"),
    ("-5", "--set 'initial.rate.magnitude_deg_s=-5': initial.rate.magnitude_deg_s: must not be negative, got -5.0"),
])
def test_set_messages_name_the_setting_not_the_topology(tmp_path, capsys, value, expected):
    """O28-002: a --set mistake is reported as the --set's, without the "problem in the topology … check its
    args" wrapper or the scenario file's line; 1e6 is a number; nan and inf are refused as not finite (the
    hint about YAML exponents was wrong for them)."""
    status = main(["run", PROVES, "--duration", "1", "--no-plots", "--no-progress", "--out", str(tmp_path / "r"),
                   "--set", f"initial.rate.magnitude_deg_s={value}"])
    lines = _err_lines(capsys)
    if expected is None:
        assert status == 0 and lines == []
        assert json.loads((tmp_path / "r" / "summary.json").read_text())["initial_rate_deg_s"] == pytest.approx(10.0)
        return
    assert status == 2 and len(lines) == 1
    assert lines[0].startswith(f"fprime-lite run: {expected}"), lines[0]
    assert "topology" not in lines[0] and "check its args" not in lines[0] and "YAML" not in lines[0]


def test_set_in_a_plant_only_run_accepts_1e6(tmp_path, capsys):
    """O28-003: `fprime-lite sim` reads the same --set value the same way."""
    from detumble.sim.scenario import load_scenario

    assert load_scenario("default", settings=["initial.rate.magnitude_deg_s=1e2"]).omega_BN_B0 == pytest.approx(
        load_scenario("default", settings=["initial.rate.magnitude_deg_s=100.0"]).omega_BN_B0)
    assert main(["sim", "default", "--set", "sensors.magnetometer.noise_std_gauss=1e-3", "--duration", "1",
                 "--no-plots", "--out", str(tmp_path / "s")]) == 0


def _pngs(folder: pathlib.Path) -> set[str]:
    return {p.name for p in folder.glob("*.png")}


@pytest.mark.parametrize("deployment, duration, plots", [
    ("coursework", "12", {"rates.png", "beta.png", "wheel_momentum.png", "quaternion_orbit.png"}),
    ("adcs_ref", "6", {"rate.png", "drive_levels.png", "field.png", "dipole.png", "attitude.png", "wheels.png",
                       "power.png", "attitude_mode.png", "pointing_error.png", "wheel_momentum.png",
                       "dipole_commanded.png"}),
    pytest.param("proves_ref", "6", {"rate.png", "drive_levels.png", "state.png", "field.png", "dipole.png",
                                     "attitude.png", "power.png"},
                 marks=pytest.mark.slow),  # unchanged; test_reference_deployment draws them too
])
def test_each_deployment_draws_its_plots_and_plot_draws_them_all_again(tmp_path, capsys, deployment, duration,
                                                                        plots):
    """O28-004: the coursework run draws seed 004's time histories (it drew none, and `plot` failed with a
    matplotlib ValueError); adcs_ref draws no DetumbleManager panel (state.png: its manager does not fly)
    and `plot` draws all 11 of its plots (it drew 8); every plot a run drew is drawn again, the same."""
    out = tmp_path / "run"
    assert main(["run", str(DEPLOYMENTS / deployment / "topology.yaml"), "--duration", duration, "--no-progress",
                 "--out", str(out)]) == 0
    assert _pngs(out) == plots
    again = tmp_path / "again"
    again.mkdir()
    capsys.readouterr()
    assert main(["plot", str(out), "-o", str(again)]) == 0
    assert _err_lines(capsys) == []
    assert _pngs(again) == plots


def test_sim_runs_get_plots_and_plot_redraws_them(tmp_path, capsys):
    """O28-005: `fprime-lite sim` writes the time histories beside rate.csv (none before), `--no-plots`
    none, and `fprime-lite plot` draws them again from the folder."""
    out = tmp_path / "sim"
    assert main(["sim", "surrey", "--law", "wheels_pd", "--duration", "20", "--out", str(out)]) == 0
    plots = {"rates.png", "beta.png", "wheel_momentum.png", "quaternion_orbit.png"}
    assert _pngs(out) == plots
    assert main(["sim", "default", "--duration", "2", "--no-plots", "--out", str(tmp_path / "quiet")]) == 0
    assert _pngs(tmp_path / "quiet") == set()
    again = tmp_path / "again"
    again.mkdir()
    assert main(["plot", str(out), "-o", str(again)]) == 0
    assert _pngs(again) == plots


def test_two_skeleton_deployments_live_in_one_project(tmp_path):
    """O28-006: two `new deployment` skeletons in one folder each pass their tests in one `python -m pytest`
    (their test files were both test_deployment.py and test_counter.py: pytest refused the second)."""
    import subprocess
    import sys

    for name in ("Alpha", "Beta"):
        assert main(["new", "deployment", name, "--dir", str(tmp_path)]) == 0
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "4 passed" in done.stdout.splitlines()[-1]


def test_two_deployments_with_a_module_of_one_name_each_get_their_own(tmp_path):
    """O28-007: two topologies loaded in one process, each with its own `counter.py` beside it, each get
    their own module (the loader gave the second the first one's, from sys.modules)."""
    import inspect

    from fprime_lite.tools.api import load

    for name, step in (("Alpha", 1), ("Beta", 7)):
        assert main(["new", "deployment", name, "--dir", str(tmp_path)]) == 0
        folder = tmp_path / name
        module = folder / f"{name.lower()}_counter.py"
        module.rename(folder / "counter.py")
        counter_py = folder / "counter.py"
        counter_py.write_text(counter_py.read_text().replace("Param(U32, default=1)", f"Param(U32, default={step})"))
        topology = folder / "topology.yaml"
        topology.write_text(topology.read_text().replace(f"{name.lower()}_counter.Counter", "counter.Counter"))
    found = []
    for name in ("Alpha", "Beta"):
        counter = load(tmp_path / name / "topology.yaml").topology.instance(f"{name}.counter").component
        found.append((pathlib.Path(inspect.getfile(type(counter))).parent.name, counter.STEP.value))
    assert found == [("Alpha", 1), ("Beta", 7)]


def test_check_warns_about_a_topology_with_no_patterns(tmp_path, capsys):
    """O28-008: `check` on a topology with no `patterns:` (nothing reaches the ground) still passes but warns
    in one line what is missing and how to add it; a topology with patterns gets no warning."""
    import re

    assert main(["new", "deployment", "Plain", "--dir", str(tmp_path)]) == 0
    topology = tmp_path / "Plain" / "topology.yaml"
    capsys.readouterr()
    assert main(["check", str(topology)]) == 0
    assert capsys.readouterr().err == ""
    text = topology.read_text()
    topology.write_text(re.sub(r"patterns:\n(  .*\n)+", "", text))
    assert "patterns" not in topology.read_text()
    assert main(["check", str(topology)]) == 0
    lines = _err_lines(capsys)
    assert len(lines) == 1 and lines[0].startswith(f"{topology}: warning: no 'patterns:'")
    assert "patterns: {command: CdhCore.cmdDisp" in lines[0]


def test_a_year_long_run_is_refused_with_its_disk_estimate(tmp_path, capsys):
    """O28-009: `run --duration` of a year (the reference deployment writes about 130 GB of CSV in a year)
    is refused before it flies, with the estimate from a 60 s probe flight and what to do; nothing is
    created."""
    out = tmp_path / "year"
    assert main(["run", PROVES, "--duration", "31536000", "--no-progress", "--out", str(out)]) == 2
    lines = _err_lines(capsys)
    assert len(lines) == 1 and lines[0].startswith("fprime-lite run: --duration 3.1536e+07 s would write about ")
    gb = float(lines[0].split("would write about ")[1].split(" GB")[0].replace(",", ""))
    assert 80 < gb < 250  # about 4 kB per simulated second
    assert "shorten --duration" in lines[0] and "--force" in lines[0]
    assert not out.exists()


def test_the_disk_estimate_is_held_to_the_free_space(tmp_path, monkeypatch):
    """O28-010: an estimate that fits under 10 GB is still refused when the disk has less free space, and
    the message says how much is free; one that fits passes."""
    import shutil
    from collections import namedtuple

    from fprime_lite.tools import disk_estimate
    from fprime_lite.tools.errors import RunSetupError

    estimate = disk_estimate.OutputEstimate(fixed_bytes=1000, bytes_per_s=1000.0)
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(10**9, 0, 50_000_000))
    disk_estimate.check_disk(estimate, 40_000.0, tmp_path / "new" / "run")  # 40 MB of 45 MB usable
    with pytest.raises(RunSetupError, match=r"would write about 50.0 MB .*; 50.0 MB free there — shorten --duration "
                                            r"\(at most about 44,999 s here\)"):
        disk_estimate.check_disk(estimate, 50_000.0, tmp_path)


def test_the_python_api_run_is_held_to_the_disk_cap_too(tmp_path):
    """O28-011: `fprime_lite.tools.run(duration_s=a year)` is refused as `fprime-lite run` is, before it
    flies, with the estimate and the API's own remedies (duration_s, force=True); nothing is created.
    A non-finite duration is refused with a clear error, not a traceback deep in the scheduler."""
    from fprime_lite.tools import run
    from fprime_lite.tools.errors import RunSetupError

    out = tmp_path / "year"
    with pytest.raises(RunSetupError) as info:
        run(PROVES, duration_s=31_536_000.0, out=out)
    text = str(info.value)
    assert text.startswith("duration_s 3.1536e+07 s would write about ")
    gb = float(text.split("would write about ")[1].split(" GB")[0].replace(",", ""))
    assert 80 < gb < 250
    assert "pass force=True" in text and "--" not in text.replace(" — ", " ")
    assert not out.exists()
    for bad in (float("inf"), float("nan"), True):
        with pytest.raises(RunSetupError, match="duration_s must be a positive, finite number of seconds"):
            run(PROVES, duration_s=bad, out=tmp_path / "bad")
