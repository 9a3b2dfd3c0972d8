"""The fprime-lite command line: every verb, and clean errors for user mistakes."""

import json
import pathlib

import pytest

from fprime_lite.tools.cli import main

ROOT = pathlib.Path(__file__).parents[3]
TOPOLOGY = str(ROOT / "deployments" / "proves_ref" / "topology.yaml")


def test_check_reports_ok(capsys):
    assert main(["check", TOPOLOGY]) == 0
    assert "OK — deployment ReferenceDeployment: 65 instances" in capsys.readouterr().out


def test_dict_writes_a_dictionary_with_flight_names(tmp_path, capsys):
    out = tmp_path / "dict.json"
    assert main(["dict", TOPOLOGY, "-o", str(out)]) == 0
    d = json.loads(out.read_text())
    commands = {c["name"]: c["opcode"] for c in d["commands"]}
    assert commands["ReferenceDeployment.detumbleManager.SET_MODE"] == 0x1005A000
    assert commands["CdhCore.cmdDisp.CMD_NO_OP"] == 0x01000100
    assert d["metadata"]["deploymentName"] == "ReferenceDeployment.ReferenceDeployment"


def test_graph_prints_dot_and_mermaid(capsys):
    assert main(["graph", TOPOLOGY]) == 0
    dot = capsys.readouterr().out
    assert dot.startswith('digraph "ReferenceDeployment"')
    assert '"ReferenceDeployment.detumbleManager" -> "ReferenceDeployment.drv2605Face0Manager"' in dot
    assert main(["graph", TOPOLOGY, "--format", "mermaid"]) == 0
    assert capsys.readouterr().out.startswith("flowchart LR")


def test_params_writes_the_defaults_that_prmdb_reads(tmp_path):
    from fprime_lite.svc.prm_db import decode_param_file

    out = tmp_path / "p.dat"
    assert main(["params", TOPOLOGY, "-o", str(out)]) == 0
    records = dict(decode_param_file(out.read_bytes()).records)
    assert records[0x1005A000 + 39] == bytes.fromhex("4008000000000000")  # GAIN = 3.0 (F64)
    shipped = ROOT / "deployments" / "proves_ref" / "flight_params.dat"
    assert shipped.read_bytes() == out.read_bytes(), "the shipped flight parameter file is out of date"


def test_params_set_writes_chosen_values_checked_against_their_types(tmp_path, capsys):
    import struct

    from fprime_lite.svc.prm_db import decode_param_file

    out = tmp_path / "p.dat"
    assert main(["params", TOPOLOGY, "-o", str(out), "--set", "ReferenceDeployment.detumbleManager.GAIN=2.5",
                 "--set", "ReferenceDeployment.detumbleManager.COOLDOWN_DURATION={seconds: 1, useconds: 5}"]) == 0
    records = dict(decode_param_file(out.read_bytes()).records)
    assert records[0x1005A000 + 39] == struct.pack(">d", 2.5)
    assert records[0x1005A000 + 3] == struct.pack(">II", 1, 5)
    assert "1 set" not in capsys.readouterr().out  # two were set
    for setting, message in (("ReferenceDeployment.detumbleManager.GAINN=1", "did you mean "
                                                                             "ReferenceDeployment.detumbleManager.GAIN?"),
                             ("ReferenceDeployment.detumbleManager.GAIN=fast", "not a valid F64"),
                             ("GAIN", "expected Module.inst.PARAM=VALUE")):
        assert main(["params", TOPOLOGY, "-o", str(tmp_path / "q.dat"), "--set", setting]) == 2
        assert message in capsys.readouterr().err
    assert not (tmp_path / "q.dat").exists()


def test_params_list_prints_every_parameter_with_its_units(tmp_path, capsys):
    """UNITS-005: `params --list` prints one row a parameter (name, id, type, value, units) in id order,
    --set values included, and writes no file unless -o is given; -o with --list writes the same
    file as -o alone; neither is a usage error."""
    assert main(["params", TOPOLOGY, "--list", "--set", "ReferenceDeployment.detumbleManager.GAIN=2.5"]) == 0
    out = capsys.readouterr().out
    rows = {line.split()[0]: line.split() for line in out.splitlines()[1:]}
    assert out.splitlines()[0].split() == ["parameter", "id", "type", "value", "units"]
    assert rows["ReferenceDeployment.detumbleManager.GAIN"] == ["ReferenceDeployment.detumbleManager.GAIN",
                                                              "0x1005A027", "F64", "2.5", "A·m²·s/G"]
    assert rows["ReferenceDeployment.detumbleManager.X_PLUS_RESISTANCE"][-1] == "Ω"
    assert rows["ReferenceDeployment.detumbleManager.HYSTERESIS_AXIS"][-2:] == ["X_AXIS", "—"]
    assert rows["ReferenceDeployment.modeManager.SafeModeEntryVoltage"][-1] == "V"
    assert len(rows) == 81 and not list(tmp_path.iterdir())
    listed, alone = tmp_path / "listed.dat", tmp_path / "alone.dat"
    assert main(["params", TOPOLOGY, "--list", "-o", str(listed)]) == 0
    assert main(["params", TOPOLOGY, "-o", str(alone)]) == 0
    assert listed.read_bytes() == alone.read_bytes()
    capsys.readouterr()
    assert main(["params", TOPOLOGY]) == 2
    assert "give -o FILE (write the parameter file), --list (print the parameters) or both" in capsys.readouterr().err


def test_short_run_writes_every_output(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", TOPOLOGY, "--duration", "5", "--out", str(out), "--no-progress", "--seed", "3"]) == 0
    for name in ("summary.json", "events.log", "channels.csv", "dictionary.json", "truth.csv", "rate.png",
                 "drive_levels.png", "state.png"):
        assert (out / name).is_file(), name
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sim_seconds"] == 5.0 and summary["ticks"] == 5001
    assert "Run summary" in capsys.readouterr().out


@pytest.mark.parametrize("argv, message", [
    (["check", "nope.yaml"], "nope.yaml: no such topology file"),
    (["run", "nope.yaml", "--no-progress"], "nope.yaml: no such topology file"),
    (["run", TOPOLOGY, "--scenario", "no_such_scenario", "--no-progress"],
     "with the simulation options {'scenario': 'no_such_scenario'}: no_such_scenario: no such scenario file"),
    (["run", TOPOLOGY, "--duration", "-1"], "--duration must be a positive, finite number of seconds, got -1.0"),
    (["run", TOPOLOGY, "--duration", "inf"], "--duration must be a positive, finite number of seconds, got inf"),
    (["run", TOPOLOGY, "--duration", "nan"], "--duration must be a positive, finite number of seconds, got nan"),
    (["run", TOPOLOGY, "--stop-when", "rate_deg_s"], "--stop-when 'rate_deg_s' is not KEY OP VALUE"),
    (["run", TOPOLOGY, "--params", "missing.dat"], "--params missing.dat: no such file"),
    (["run", TOPOLOGY, "--set", "sensors.gyro"], "--set 'sensors.gyro': expected KEY.PATH=VALUE"),
    (["run", TOPOLOGY, "--scenario", "case_a", "--set", "orbit.altitud=1"], "case_a.yaml has no key 'altitud'"),
])
def test_user_mistakes_are_one_line_errors_without_traceback(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err
    assert "Traceback" not in err


def test_set_changes_the_topology_s_scenario_and_a_bad_key_is_one_problem(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", TOPOLOGY, "--duration", "1", "--out", str(out), "--no-progress", "--no-plots",
                 "--set", "initial.rate.magnitude_deg_s=12"]) == 0
    assert json.loads((out / "summary.json").read_text())["initial_rate_deg_s"] == pytest.approx(12.0)
    capsys.readouterr()
    assert main(["run", TOPOLOGY, "--no-progress", "--set", "sensors.magnetometr.noise_std_gauss=0"]) == 2
    err = capsys.readouterr().err
    # the --set's own mistake, in one line: not "1 problem in the topology … check its args" (issue 28)
    assert err.strip() == ("fprime-lite run: --set 'sensors.magnetometr.noise_std_gauss=0': default.yaml has no "
                           "key 'magnetometr' at sensors (keys there: magnetometer, gyro, accelerometer); "
                           "keys that can be added there: star_tracker, sun_sensors")


def test_bad_yaml_is_reported_with_its_line(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("deployment: X\nmodules: [\n")
    assert main(["check", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "bad.yaml:3: invalid YAML" in err and "Traceback" not in err


def test_run_refuses_a_non_empty_output_folder(tmp_path, capsys):
    (tmp_path / "x").write_text("keep me")
    assert main(["run", TOPOLOGY, "--out", str(tmp_path), "--no-progress"]) == 2
    assert "exists and is not empty" in capsys.readouterr().err
    assert (tmp_path / "x").read_text() == "keep me"


def test_help_everywhere(capsys):
    for verb in ("run", "dict", "check", "graph", "params"):
        with pytest.raises(SystemExit) as exit_:
            main([verb, "--help"])
        assert exit_.value.code == 0
    assert "--duration" in capsys.readouterr().out


def test_sim_verb_flies_a_scenario_plant_only(tmp_path, capsys):
    out = tmp_path / "sim"
    assert main(["sim", "case_a", "--law", "kopt", "--duration", "60", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sim_seconds"] == 60.0 and summary["final_rate_deg_s"] < 30.0
    assert (out / "rate.csv").read_text().startswith("time_s,omega_x_deg_s,")
    assert main(["sim", "no_such_scenario", "--out", str(out)]) == 2
    assert "not a packaged scenario" in capsys.readouterr().err


def _variant(tmp_path, run_section: str) -> str:
    path = tmp_path / "variant.yaml"
    path.write_text(f"extends: {TOPOLOGY}\n{run_section}", encoding="utf-8")
    return str(path)


def test_the_topology_s_run_duration_is_the_default_and_duration_overrides_it(tmp_path):
    """RUN-050: without --duration, `run` flies the topology's run.duration_s; --duration still overrides it."""
    topology = _variant(tmp_path, "run:\n  duration_s: 3.5\n")
    assert main(["run", topology, "--out", str(tmp_path / "a"), "--no-progress", "--no-plots"]) == 0
    summary = json.loads((tmp_path / "a" / "summary.json").read_text())
    assert summary["sim_seconds"] == 3.5 and summary["stopped_by"] is None
    assert main(["run", topology, "--duration", "2", "--out", str(tmp_path / "b"), "--no-progress", "--no-plots"]) == 0
    assert json.loads((tmp_path / "b" / "summary.json").read_text())["sim_seconds"] == 2.0


def test_a_topology_without_a_run_section_runs_600_s():
    """RUN-050: with neither --duration nor run.duration_s the run lasts 600 simulated seconds."""
    from fprime_lite.tools.api import load
    from fprime_lite.tools.runner import DEFAULT_DURATION_S, run_duration

    loaded = load(TOPOLOGY)
    assert loaded.config.run.duration_s is None
    assert run_duration(loaded, None) == DEFAULT_DURATION_S == 600.0
    assert run_duration(loaded, 12.0) == 12.0


@pytest.mark.parametrize("section, message", [
    ("run:\n  duration_s: -5\n", "variant.yaml:3: 'run.duration_s' must be a positive number of simulated seconds"),
    ("run:\n  duration_s: soon\n", "variant.yaml:3: 'run.duration_s' must be a positive number"),
    ("run:\n  duraton_s: 60\n", "variant.yaml:3: unknown key 'duraton_s' in 'run' — did you mean 'duration_s'?"),
    ("run: 60\n", "variant.yaml:2: 'run' must be a mapping"),
])
def test_a_bad_run_section_is_a_file_line_error(tmp_path, capsys, section, message):
    """RUN-051: run.duration_s is checked like every topology key: file:line, what is wrong, what to write."""
    assert main(["check", _variant(tmp_path, section)]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_stop_when_ends_the_run_at_the_first_check_where_it_holds(tmp_path):
    """RUN-062: --stop-when 'rate_deg_s > 0' (the detumble report's progress value; the tumble is 30 deg/s) ends
    the run at the first whole-second check; a key no report publishes never stops it."""
    out = tmp_path / "a"
    assert main(["run", TOPOLOGY, "--duration", "20", "--stop-when", "rate_deg_s > 0", "--out", str(out),
                 "--no-progress", "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert 1.0 <= summary["sim_seconds"] < 1.1
    assert summary["stopped_by"] == "stop_when rate_deg_s > 0"
    out = tmp_path / "b"
    assert main(["run", TOPOLOGY, "--duration", "3", "--stop-when", "no_such_value > 0", "--out", str(out),
                 "--no-progress", "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sim_seconds"] == 3.0 and summary["stopped_by"] is None


@pytest.mark.parametrize("argv, hint", [
    (["run", "--duraton", "5"], "unrecognized arguments: --duraton — did you mean --duration?"),
    (["graph", "--qqqq"], None),  # nothing close enough among graph's options: no guess
    (["run", "--seed=3", "--no-progrss", "--truth-intervl=2"],
     "did you mean --no-progress for --no-progrss, --truth-interval for --truth-intervl?"),
    (["check", "--patterns"], "did you mean"),  # an option of another verb (graph) is not guessed for check
])
def test_a_misspelt_option_gets_a_did_you_mean(argv, hint, capsys):
    """CLI-020 (issue 28): an option the verb does not have is refused (exit 2) with the closest option of
    that verb, when one is close."""
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert f"fprime-lite {argv[0]}: error: unrecognized arguments" in err
    if argv[0] == "check":
        assert hint not in err
    elif hint is None:
        assert "did you mean" not in err
    else:
        assert hint in err


@pytest.mark.parametrize("verb", ["params", "dict"])
def test_an_output_never_replaces_a_file_of_another_kind_unless_forced(verb, tmp_path, capsys):
    """CLI-021 (issue 28): `params -o topology.yaml` or `dict -o thermostat.py` (a slip of the keyboard) is
    refused, exit 2, and the file is left as it was; the verb's own kind of file is replaced as before;
    --force replaces anything."""
    mine = tmp_path / "thermostat.py"
    mine.write_text("print('my own code')\n")
    assert main([verb, TOPOLOGY, "-o", str(mine)]) == 2
    assert "the file exists and is not" in capsys.readouterr().err
    assert mine.read_text() == "print('my own code')\n"
    own = tmp_path / ("p.dat" if verb == "params" else "d.json")
    assert main([verb, TOPOLOGY, "-o", str(own)]) == 0
    first = own.read_bytes()
    assert main([verb, TOPOLOGY, "-o", str(own)]) == 0  # its own output is replaced without asking
    assert own.read_bytes() == first
    assert main([verb, TOPOLOGY, "-o", str(mine), "--force"]) == 0
    assert mine.read_bytes() == first


def test_dash_writes_to_standard_output(capsysbinary, tmp_path):
    """CLI-022 (issue 28): `-o -` writes the parameter file or the dictionary to standard output, byte for
    byte what -o FILE writes; nothing else is printed there."""
    from fprime_lite.svc.prm_db import decode_param_file

    assert main(["params", TOPOLOGY, "-o", str(tmp_path / "p.dat")]) == 0
    capsysbinary.readouterr()
    assert main(["params", TOPOLOGY, "-o", "-"]) == 0
    out = capsysbinary.readouterr().out
    assert out == (tmp_path / "p.dat").read_bytes() and decode_param_file(out).records
    assert main(["dict", TOPOLOGY, "-o", str(tmp_path / "d.json")]) == 0
    capsysbinary.readouterr()
    assert main(["dict", TOPOLOGY, "-o", "-"]) == 0
    assert capsysbinary.readouterr().out == (tmp_path / "d.json").read_bytes()
    assert main(["params", TOPOLOGY, "-o", "-", "--list"]) == 2
