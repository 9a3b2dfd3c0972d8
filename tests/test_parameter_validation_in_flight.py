"""Issue #16 finding 1 in the reference deployment: one bad parameter value no longer silences
attitude control. Rates in deg/s; 30 s simulated runs of the default scenario (30 deg/s initial)."""

from __future__ import annotations

import json
import pathlib
import struct

from fprime_lite.svc.prm_db import decode_param_file, encode_param_file
from fprime_lite.tools.cli import main

ROOT = pathlib.Path(__file__).parents[1]
TOPOLOGY = str(ROOT / "topology.yaml")
DIAMETER = "ReferenceDeployment.detumbleManager.Z_MINUS_DIAMETER"


def _run(tmp_path, *extra):
    out = tmp_path / "run"
    # the refusals are WARNING events, which fail a run unless --allow-warnings; the summary lists them
    assert main(["run", TOPOLOGY, "--duration", "30", "--out", str(out), "--no-progress", "--no-plots",
                 "--allow-warnings", *extra]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["problems"], "the run's warnings are listed in the summary"
    return summary, (out / "events.log").read_text()


def test_prm_set_of_a_huge_diameter_is_refused_and_detumbling_goes_on(tmp_path, capsys):
    """PRM-016-11: a sequence sending Z_MINUS_DIAMETER_PRM_SET 1e308 gets VALIDATION_ERROR (the
    sequencer logs error 2), the manager logs ParamSetRefused, no handler faults, and B-dot keeps
    working: |w| falls by more than 0.3 deg/s in 30 s (before: OK, 1 fault per cycle, no torque)."""
    seq = tmp_path / "bad.seq"
    seq.write_text("R00:00:00 ReferenceDeployment.detumbleManager.SET_MODE AUTO\n"
                   f"R00:00:01 {DIAMETER}_PRM_SET 1e308\n")
    summary, events = _run(tmp_path, "--seq", str(seq))
    assert f"{DIAMETER.rsplit('.', 1)[0]}.ParamSetRefused WARNING_LO Z_MINUS_DIAMETER PRM_SET refused" in events
    assert "completed with error 2" in events  # VALIDATION_ERROR
    assert summary["handler_faults"] == 0
    assert summary["initial_rate_deg_s"] - summary["final_rate_deg_s"] > 0.3


def test_a_parameter_file_with_a_huge_diameter_loads_the_default(tmp_path, capsys):
    """PRM-016-12: a parameter file holding 1e308 m for Z_MINUS_DIAMETER: the manager loads the
    default, logs ParamDefaulted (WARNING_HI) and detumbles as with the default."""
    out = tmp_path / "p.dat"
    assert main(["params", TOPOLOGY, "-o", str(out)]) == 0
    dictionary = tmp_path / "d.json"
    assert main(["dict", TOPOLOGY, "-o", str(dictionary)]) == 0
    ids = {p["name"]: p["id"] for p in json.loads(dictionary.read_text())["parameters"]}
    records = [(pid, struct.pack(">d", 1e308) if pid == ids[DIAMETER] else data)
               for pid, data in decode_param_file(out.read_bytes()).records]
    out.write_bytes(encode_param_file(records))
    summary, events = _run(tmp_path, "--params", str(out))
    assert ("detumbleManager.ParamDefaulted WARNING_HI Z_MINUS_DIAMETER parameter file value refused "
            "(1e+308 is above the maximum 1.0); default loaded") in events
    assert summary["handler_faults"] == 0
    assert summary["initial_rate_deg_s"] - summary["final_rate_deg_s"] > 0.3


def test_fprime_lite_params_refuses_a_value_the_component_would_refuse(tmp_path, capsys):
    """PRM-016-13: `fprime-lite params --set` of an out-of-range value is a user error (exit 2)
    naming the bound, not a file the deployment would silently replace."""
    assert main(["params", TOPOLOGY, "-o", str(tmp_path / "p.dat"), "--set", f"{DIAMETER}=1.0e+308"]) == 2
    assert "1e+308 is above the maximum 1.0" in capsys.readouterr().err
    assert not (tmp_path / "p.dat").exists()

