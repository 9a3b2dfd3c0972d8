"""End to end: the PROVES reference deployment detumbles the simulated 1U from 30 deg/s.

One run of the reference topology with the flight parameter file and start-up sequence, for long
enough to finish detumbling; every assertion is about what actually happened in that run.
"""

import csv
import json
import pathlib

import pytest

from detumble.components.types import DetumbleState
from fprime_lite.tools.runner import run_deployment
from fprime_lite.deploy.topology_loader import load_topology

ROOT = pathlib.Path(__file__).parents[1]
TOPOLOGY = ROOT / "deployments" / "proves_ref" / "topology.yaml"
DURATION_S = 3100.0  # a full detumble from 30 deg/s takes ~2990 s of simulated time


@pytest.fixture(scope="module")
def flown(tmp_path_factory):
    out = tmp_path_factory.mktemp("reference_run")
    loaded = load_topology(TOPOLOGY)
    manager = loaded.topology.instance("ReferenceDeployment.detumbleManager").component
    transitions = []

    def watch(_time_us):
        if not transitions or transitions[-1] != manager.state:
            transitions.append(manager.state)

    loaded.scheduler.add_time_listener(watch)
    summary = run_deployment(loaded, out, duration_s=DURATION_S, plots=True)
    return out, summary, transitions


def test_rate_falls_below_the_deadband_and_detumbling_completes(flown):
    _, summary, _ = flown
    assert summary["initial_rate_deg_s"] == pytest.approx(30.0, abs=1e-9)
    assert summary["final_rate_deg_s"] < 5.0  # DEADBAND_LOWER_THRESHOLD
    assert summary["detumble_started_s"] < 1.0
    assert 1000.0 < summary["detumble_complete_s"] < DURATION_S


def test_rate_decreases_over_the_run(flown):
    out, _, _ = flown
    with open(out / "truth.csv", newline="") as f:
        rates = [float(row["rate_deg_s"]) for row in csv.DictReader(f)]
    tenth = len(rates) // 10
    means = [sum(rates[i * tenth:(i + 1) * tenth]) / tenth for i in range(10)]
    assert all(b < a for a, b in zip(means, means[1:], strict=False)), means


def test_states_cycle_in_the_specified_order(flown):
    _, _, transitions = flown
    allowed = {
        DetumbleState.COOLDOWN: {DetumbleState.SENSING_ANGULAR_VELOCITY},
        DetumbleState.SENSING_ANGULAR_VELOCITY: {DetumbleState.SENSING_MAGNETIC_FIELD},
        DetumbleState.SENSING_MAGNETIC_FIELD: {DetumbleState.ACTUATING_BDOT},
        DetumbleState.ACTUATING_BDOT: {DetumbleState.COOLDOWN},
    }
    assert transitions[0] == DetumbleState.COOLDOWN
    for a, b in zip(transitions, transitions[1:], strict=False):
        assert b in allowed[a], f"{a.name} -> {b.name}"
    assert transitions[-1] == DetumbleState.SENSING_ANGULAR_VELOCITY  # detumbled: idle, sensing ω
    assert DetumbleState.ACTUATING_HYSTERESIS not in transitions  # 30 deg/s is far below BDOT_MAX_THRESHOLD
    assert transitions.count(DetumbleState.ACTUATING_BDOT) > 5000  # one B-dot cycle per ~0.5 s


def test_no_warning_hi_no_slips_no_faults(flown):
    _, summary, _ = flown
    assert "WARNING_HI" not in summary["events_by_severity"]
    assert "FATAL" not in summary["events_by_severity"]
    assert summary["cycle_slips"] == 0
    assert summary["member_faults"] == 0 and summary["handler_faults"] == 0
    assert summary["command_errors"] == 0
    assert summary["undecodable_packets"] == 0


def test_outputs_exist_and_parse(flown):
    out, summary, _ = flown
    on_disk = json.loads((out / "summary.json").read_text())
    for key in ("sim_seconds", "wall_seconds", "real_time_factor", "ticks", "initial_rate_deg_s",
                "final_rate_deg_s", "detumble_complete_s", "events_by_severity", "command_errors", "cycle_slips"):
        assert key in on_disk, key
    assert on_disk["sim_seconds"] == DURATION_S
    assert on_disk["ticks"] == int(DURATION_S * 1000) + 1  # every 1 kHz base tick was counted
    events = (out / "events.log").read_text().splitlines()
    assert any(" ReferenceDeployment.detumbleManager.DetumbleStarted ACTIVITY_LO " in e for e in events)
    completed = [e for e in events if ".DetumbleCompleted " in e]
    assert completed and completed[0].startswith("2025-06-01T00:49:")
    with open(out / "channels.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    states = {r["value"] for r in rows if r["channel"] == "ReferenceDeployment.detumbleManager.State"}
    assert states <= {s.name for s in DetumbleState} and states
    dictionary = json.loads((out / "dictionary.json").read_text())
    names = {c["name"] for c in dictionary["commands"]}
    assert {"CdhCore.cmdDisp.CMD_NO_OP", "ReferenceDeployment.detumbleManager.SET_MODE"} <= names
    for png in ("rate.png", "drive_levels.png", "state.png"):
        assert (out / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_power_budget_is_in_the_summary_and_plotted(flown):
    """SITL-PWR-002: the summary carries the coil energy of the detumble (from DetumbleStarted to
    DetumbleCompleted), bounded by the whole run's coil energy and by every coil at full drive for
    the whole detumble; the battery stays above the safe-mode threshold; power.png is drawn."""
    out, summary, _ = flown
    power = json.loads((out / "summary.json").read_text())["power"]
    duration = summary["detumble_complete_s"] - summary["detumble_started_s"]
    full_drive_w = 4 * 3.3 ** 2 / 13.0 + 3.3 ** 2 / 150.7
    assert power["detumble_complete"] is True
    assert 0.0 < power["coil_energy_detumble_j"] <= power["coil_energy_j"]
    assert power["coil_energy_detumble_j"] < full_drive_w * duration
    assert power["mean_coil_power_detumble_w"] == pytest.approx(power["coil_energy_detumble_j"] / duration)
    assert power["min_bus_voltage_v"] > 6.7
    assert 0.0 < power["eclipse_fraction"] < 1.0
    assert (out / "power.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with open(out / "truth.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert float(rows[-1]["coil_j"]) == pytest.approx(power["coil_energy_j"], rel=0.01)
