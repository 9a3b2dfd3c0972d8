"""The framework's deployment run kind: parameters through a parameter file, read back from the
flight software; scenario values read back from the built spacecraft."""

from __future__ import annotations

import json
import pathlib

import pytest

from fprime_lite.tools.campaign import CampaignError, run_campaign
from tests.fprime_lite.tools.campaign.conftest import TOPOLOGY

FLIGHT = f"""\
campaign: flight-tiny
run:
  kind: deployment
  topology: {TOPOLOGY}
  duration_s: 3
grid:
  params.ReferenceDeployment.detumbleManager.GAIN: [2.5]
  params.ReferenceDeployment.detumbleManager.TORQUE_DURATION.useconds: [640000]
dispersions:
  scenario.initial.rate.magnitude_deg_s: {{dist: uniform, low: 40, high: 60}}
metrics: [initial_rate_deg_s, coil_energy_j, detumble_complete_s]
"""


def test_parameters_and_scenario_values_are_read_back(write_campaign, tmp_path):
    """CAMP-040: GAIN and a TORQUE_DURATION member reach the DetumbleManager through PrmDb (read back
    from the component), the dispersed rate is the spacecraft's initial rate, and a null summary
    value is recorded with its reason."""
    df = run_campaign(write_campaign(FLIGHT), workers=1, out=tmp_path / "o", plots=False, summary=False)
    (r,) = df.to_dict("records")
    assert r["status"] == "ok", r["error"]
    assert r["params.ReferenceDeployment.detumbleManager.GAIN"] == 2.5
    assert r["params.ReferenceDeployment.detumbleManager.TORQUE_DURATION.useconds"] == 640000
    assert 40 <= r["scenario.initial.rate.magnitude_deg_s"] <= 60
    assert r["scenario.initial.rate.magnitude_deg_s"] == pytest.approx(r["initial_rate_deg_s"], rel=1e-12)
    assert r["coil_energy_j"] > 0
    assert "null in the run summary" in json.loads(r["notes"])["detumble_complete_s"]


def test_a_misspelt_parameter_fails_before_the_campaign_starts(write_campaign, tmp_path):
    """CAMP-041: an unknown parameter or struct member is refused at its file:line with a hint."""
    path = write_campaign(FLIGHT.replace("detumbleManager.GAIN", "detumbleManager.GAIM"))
    with pytest.raises(CampaignError) as info:
        run_campaign(path, workers=1, out=tmp_path / "o", plots=False, summary=False)
    assert info.value.problems == [f"{path}:7: the topology has no parameter ReferenceDeployment.detumbleManager.GAIM"
                                   f" — did you mean params.ReferenceDeployment.detumbleManager.GAIN?"]
    path = write_campaign(FLIGHT.replace("TORQUE_DURATION.useconds", "TORQUE_DURATION.usecs"), "b.yaml")
    with pytest.raises(CampaignError, match=r"b.yaml:8: .*has no member 'usecs' \(members: seconds, useconds\)"):
        run_campaign(path, workers=1, out=tmp_path / "o", plots=False, summary=False)
    assert not pathlib.Path(tmp_path / "o").exists()


STOPPING = f"""\
campaign: flight-stop
run:
  kind: deployment
  topology: {TOPOLOGY}
  duration_s: 30
  stop_when: ["rate_deg_s > 0"]
grid:
  params.ReferenceDeployment.detumbleManager.GAIN: [2.5]
metrics: [sim_seconds]
"""


def test_stop_when_ends_each_run_early_and_a_bad_condition_fails_first(write_campaign, tmp_path):
    """CAMP-042: a run section's stop_when ends each run at the first whole-second check where it holds (the
    row's sim_seconds and stopped_by say so); a malformed condition stops the campaign before any run, naming
    stop_when."""
    df = run_campaign(write_campaign(STOPPING), workers=1, out=tmp_path / "o", plots=False, summary=False)
    (r,) = df.to_dict("records")
    assert r["status"] == "ok", r["error"]
    assert 1.0 <= r["sim_seconds"] < 1.1
    path = write_campaign(STOPPING.replace("rate_deg_s > 0", "rate_deg_s >> 0"), "b.yaml")
    with pytest.raises(CampaignError, match=r"stop_when: 'rate_deg_s >> 0' is not KEY OP VALUE"):
        run_campaign(path, workers=1, out=tmp_path / "p", plots=False, summary=False)
