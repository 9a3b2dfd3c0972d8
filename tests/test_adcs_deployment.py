"""End to end: deployments/adcs_ref flies its three modes on the simulated 1U (wheels + star tracker).

Each test is one run of the topology with its start-up sequence (or a variant of it), and asserts what
happened: the modes the ground saw, in order, and the true pointing error from the truth samples.
"""

import csv
import json
import pathlib

import pytest

from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.tools.runner import run_deployment

ROOT = pathlib.Path(__file__).parents[1]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
CTRL = "ReferenceDeployment.attitudeController"


def fly(out, duration_s, *, settings=(), sequence=None):
    overrides = {"spacecraft": {"settings": list(settings)}} if settings else None
    loaded = load_topology(TOPOLOGY, overrides)
    summary = run_deployment(loaded, out, duration_s=duration_s, sequence=sequence, plots=False)
    with open(out / "attitude.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return summary, rows


@pytest.fixture(scope="module")
def short_flight(tmp_path_factory):
    """A 1.5 °/s spin about +Z with DETUMBLE_EXIT_RATE raised to 2 °/s: DETUMBLE → SPIN_STABLE in 5 s,
    POINTING after the 60 s stable-spin dwell, a 90° target change at 200 s, 400 s in all."""
    out = tmp_path_factory.mktemp("adcs_short")
    seq = out / "short.seq"
    seq.write_text(f"R00:00:00 {CTRL}.DETUMBLE_EXIT_RATE_PRM_SET 2.0\n"
                   f"R00:00:00 {CTRL}.SET_TARGET_QUATERNION 0.9238795325112867 0 0.3826834323650898 0\n"
                   f"R00:00:00 {CTRL}.SET_AUTO\n"
                   f"R00:03:20 {CTRL}.SET_TARGET_QUATERNION 0.6532814824381883 0.6532814824381882 "
                   f"0.2705980500730985 -0.2705980500730985\n")
    summary, rows = fly(out, 400.0, settings=("initial.rate.magnitude_deg_s=1.5", "initial.rate.axis=[0,0,1]"),
                        sequence=seq)
    return summary, rows


def test_short_flight_modes_in_order_and_target_held(short_flight):
    """ADCS-040: the ground sees DETUMBLE, SPIN_STABLE, POINTING in that order and nothing else; the 90° target
    change settles below 0.1° within 30 s; over the last 100 s the true error stays below 0.05°; no wheel
    exceeds half its momentum capacity."""
    summary, rows = short_flight
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["DETUMBLE", "SPIN_STABLE", "POINTING"]
    assert summary["handler_faults"] == 0 and summary["command_errors"] == 0
    (slew,) = summary["slews"]
    assert slew["angle_deg"] == pytest.approx(90.0, abs=0.5)
    assert slew["settle_below_0p1_deg_s"] is not None and slew["settle_below_0p1_deg_s"] <= 30.0
    tail = [float(r["pointing_error_deg"]) for r in rows if float(r["t_s"]) >= 300.0]
    assert tail and max(tail) < 0.05
    assert summary["wheel_momentum_max_fraction"] < 0.5


@pytest.fixture(scope="module")
def full_flight(tmp_path_factory):
    """The deployment as shipped, flown by the plain command `fprime-lite run deployments/adcs_ref/topology.yaml`
    (30 °/s tumble; start-up sequence: target, then SET_AUTO; the topology's run.duration_s, 6000 s)."""
    from fprime_lite.tools.cli import main

    out = tmp_path_factory.mktemp("adcs_full") / "run"
    assert main(["run", str(TOPOLOGY), "--out", str(out), "--no-progress", "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sim_seconds"] == 6000.0  # the topology's default, no --duration given
    with open(out / "attitude.csv", newline="") as f:
        return summary, list(csv.DictReader(f))


def test_the_topology_s_default_run_covers_the_whole_auto_sequence():
    """ADCS-043: the plain `fprime-lite run` of adcs_ref lasts the topology's run.duration_s, long enough for the
    measured sequence from a 30 °/s tumble (POINTING entered at 3420 s, docs/studies/attitude_modes.md) plus the
    2580 s of held target the study's pointing figures are taken over; the 600 s framework default would end in
    DETUMBLE."""
    from fprime_lite.tools.runner import DEFAULT_DURATION_S, run_duration

    loaded = load_topology(TOPOLOGY)
    assert run_duration(loaded, None) == loaded.config.run.duration_s == 6000.0
    assert run_duration(loaded, None) >= 3420.0 + 2580.0 > DEFAULT_DURATION_S
    assert run_duration(loaded, 400.0) == 400.0


def test_stop_when_ends_a_settled_spin(tmp_path):
    """ADCS-044: SPIN_STABLE forced on a body spinning at the 1.5 °/s target about +Z (the uncorrected gyro bias
    first tips the momentum ~7° off, then it settles back); --stop-when 'spin_settled_for_s >= 20' (the attitude
    report's progress value) ends the run at the first whole-second check after 20 s in the band, and the
    summary says why and how long the spin was settled."""
    seq = tmp_path / "spin.seq"
    seq.write_text(f"R00:00:00 {CTRL}.FORCE_MODE SPIN_STABLE\n")
    loaded = load_topology(TOPOLOGY, {"spacecraft": {"settings": ["initial.rate.magnitude_deg_s=1.5",
                                                                  "initial.rate.axis=[0,0,1]"]}})
    summary = run_deployment(loaded, tmp_path / "out", duration_s=200.0, sequence=seq, plots=False, quiet=True,
                             stop_when=["spin_settled_for_s >= 20"])
    assert summary["sim_seconds"] < 200.0
    assert summary["stopped_by"] == "stop_when spin_settled_for_s >= 20"
    settled, dwell = summary["spin_settled_s"], summary["spin_settled_dwell_s"]
    assert settled is not None and 20.0 <= dwell <= 21.0  # sampled every 0.5 s, checked every 1 s
    assert 0.0 <= summary["sim_seconds"] - (settled + 20.0) <= 1.0
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["SPIN_STABLE"]


@pytest.mark.slow
def test_full_flight_from_a_30_deg_s_tumble(full_flight):
    """ADCS-041: DETUMBLE → SPIN_STABLE → POINTING with no other transition; the spin settles (5°, 5 %) within
    one orbit of entering SPIN_STABLE; over POINTING after its first 10 % the true error's p95 is ≤ 0.05° (the
    issue's target), and so is the final error (the median of the last minute); no wheel passes half its
    capacity."""
    summary, rows = full_flight
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["DETUMBLE", "SPIN_STABLE", "POINTING"]
    assert summary["spin_settled_s"] is not None and summary["spin_settled_s"] <= 5578.0
    stats = summary["pointing_error_deg"]
    assert stats["p95"] <= 0.05, stats
    last = sorted(float(r["pointing_error_deg"]) for r in rows if float(r["t_s"]) >= 5940.0)
    assert last and last[len(last) // 2] <= 0.05
    assert summary["wheel_momentum_max_fraction"] < 0.5
    print(json.dumps({k: summary[k] for k in ("control_mode_transitions", "pointing_error_deg",
                                              "spin_axis_error_deg", "spin_settled_s")}))


@pytest.mark.slow
def test_full_flight_pointing_median_target(full_flight):
    """ADCS-045: the issue's median target, median true pointing error ≤ 0.01° over POINTING after its first
    10 % (MEKF attitude, the model-aided rate observer in the D term: 0.0082° measured; the complementary filter
    with the raw gyro gave 0.0165°, docs/studies/attitude_knowledge.md)."""
    summary, _ = full_flight
    assert summary["pointing_error_deg"]["median"] <= 0.01


@pytest.mark.slow
def test_magnetorquer_only_attitude_hold_meets_the_target(tmp_path):
    """ADCS-042: POINTING_ACTUATOR = MAGNETORQUERS, forced at 5 s with the spacecraft at rest on its target, one
    orbit (docs/studies/magnetic_pointing.md): the run summary's pointing error (after the first 10 % of POINTING)
    has a median ≤ 5° and a p95 ≤ 15° (issue 13's target; measured 0.87° / 2.06° with the present defaults, 3.2° /
    4.8° with the previous ones), the wheels never turn."""
    seq = ROOT / "campaigns" / "adcs" / "pointing_magnetorquers.seq"
    summary, rows = fly(tmp_path, 5580.0, settings=("initial.rate.magnitude_deg_s=0.0",
                                                    "initial.attitude.quaternion=[0.9238795325112867,0,0.3826834323650898,0]"),
                        sequence=seq)
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["POINTING"]
    stats = summary["pointing_error_deg"]
    assert stats["median"] <= 5.0
    assert stats["p95"] <= 15.0
    assert all(float(r["h0_nms"]) == 0.0 and float(r["h1_nms"]) == 0.0 and float(r["h2_nms"]) == 0.0 for r in rows)


@pytest.mark.slow
def test_magnetorquer_hold_from_the_worst_corner_meets_the_target(tmp_path):
    """ADCS-064: the hold campaign's worst corner on the deployment — 20° from the target about a random axis at
    0.05 °/s (the draw of campaigns/adcs/hold_magnetorquers_worst.yaml's first run), POINTING_ACTUATOR =
    MAGNETORQUERS forced at 5 s, one orbit, defaults (K_P_MAG 4e-6, K_D_MAG 4e-4, ζ 1, MAG_SETTLE_TIME 30 s,
    MAG_RESIDUAL_MODE ESTIMATE): the run summary's median ≤ 5° and p95 ≤ 15° (issue 13's target; the previous
    defaults missed p95 in 16 of 100 hold runs, mostly at these rates), and the on-board residual-dipole estimate
    (telemetry ResidualDipole) ends within 1e-4 A·m² per axis of the plant's (1.0, −0.5, 0.8)e-3 A·m² (measured:
    median 1.00°, p95 4.43°, estimate within 8e-6 A·m²)."""
    seq = ROOT / "campaigns" / "adcs" / "pointing_magnetorquers.seq"
    summary, _ = fly(tmp_path, 5580.0, sequence=seq, settings=(
        "initial.rate.magnitude_deg_s=0.05",
        "initial.rate.axis=[0.6639284297189,0.7349611899967293,0.13795321456779147]",
        "initial.attitude.quaternion=[0.873197000649162,0.11579247954753936,0.46534263362703093,0.08703638932423131]"))
    stats = summary["pointing_error_deg"]
    assert stats["median"] <= 5.0
    assert stats["p95"] <= 15.0
    with open(tmp_path / "channels_wide.csv", newline="") as f:
        last = None
        for row in csv.DictReader(f):
            if row.get(f"{CTRL}.ResidualDipole.0"):
                last = row
    assert last is not None
    estimate = [float(last[f"{CTRL}.ResidualDipole.{i}"]) for i in range(3)]
    assert all(abs(e - m) <= 1.0e-4 for e, m in zip(estimate, (1.0e-3, -5.0e-4, 8.0e-4), strict=True))


@pytest.mark.slow
def test_sun_safe_by_ground_command_on_the_deployment(tmp_path):
    """ADCS-104: adcs_ref from a 2 °/s tumble: the ground's FORCE_MODE SUN_SAFE (the sequence) is obeyed
    (SunSafeEntered, mode SUN_SAFE), the ADCS component's SunVector reaches the ground, and after 90 s +Z is within
    10° of the true Sun and the last SunVector within 5° of it (the wheels; the target of docs/studies/sun_safe.md)."""
    import math

    seq = tmp_path / "sun.seq"
    seq.write_text(f"R00:00:00 {CTRL}.FORCE_MODE SUN_SAFE\n")
    loaded = load_topology(TOPOLOGY, {"spacecraft": {"settings": ["initial.rate.magnitude_deg_s=2.0",
                                                                  "initial.rate.axis=[0.6,-0.48,0.64]"]}})
    summary = run_deployment(loaded, tmp_path / "out", duration_s=90.0, sequence=seq, plots=False, quiet=True)
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["SUN_SAFE"]
    events = (tmp_path / "out" / "events.log").read_text()
    assert "attitudeController.SunSafeEntered" in events and "adcs.SunVectorAcquired" in events
    craft = loaded.resources["spacecraft"]
    t, q = craft.plant.t, craft.plant.q_BN
    sun = craft.sun_sensors.true_sun_B(t, q)
    assert math.degrees(math.acos(max(-1.0, min(1.0, sun[2])))) <= 10.0
    adcs = next(c for c in loaded.topology.components() if c.name.endswith(".adcs") or c.name == "adcs")
    last = adcs.sunVectorGet().value
    assert last.valid
    assert math.degrees(math.acos(max(-1.0, min(1.0, last.x * sun[0] + last.y * sun[1] + last.z * sun[2])))) <= 5.0
    # every sunlit SunVector the ground saw, against the truth log (the study's --from-run measure)
    from detumble.sim.sun_safe_check import vector_errors_from_run
    errors, invalid = vector_errors_from_run(tmp_path / "out")
    assert len(errors) >= 85 and max(errors) <= 5.0 and invalid == 0


# seed 1 of detumble.sim.sun_safe_check.fly: a 2 °/s tumble about a drawn axis from a drawn attitude
SUN_SAFE_SEED_1 = ("initial.rate.magnitude_deg_s=2.0",
                   "initial.rate.axis=[1.2881847531554629,1.449445608699771,0.06633580893826191]",
                   "initial.attitude.quaternion=[-0.455033429261049,-0.6500287103088415,0.0186493637479742,"
                   "-0.6083251229901242]")


def test_coil_sun_safe_by_ground_command_on_the_deployment(tmp_path):
    """ADCS-108: adcs_ref from a 2 °/s tumble with no star tracker (every sample dropped), the ground's
    POINTING_ACTUATOR_PRM_SET MAGNETORQUERS and FORCE_MODE SUN_SAFE (campaigns/adcs/sun_safe_magnetorquers.seq):
    SUN_SAFE (COMMAND) is the only mode, the wheels never turn, and +Z comes within 10° of the true Sun in under
    350 s and stays there to 450 s (measured 218 s; the whole orbit: docs/studies/sun_safe.md)."""
    from detumble.sim.sun_safe_check import pointing_from_run

    seq = ROOT / "campaigns" / "adcs" / "sun_safe_magnetorquers.seq"
    summary, rows = fly(tmp_path, 450.0, sequence=seq,
                        settings=SUN_SAFE_SEED_1 + ("sensors.star_tracker.dropout_probability=1.0",))
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["SUN_SAFE"]
    assert "SunSafeEntered WARNING_HI Entering SUN_SAFE (COMMAND)" in (tmp_path / "events.log").read_text()
    assert all(float(r["h0_nms"]) == 0.0 and float(r["h1_nms"]) == 0.0 and float(r["h2_nms"]) == 0.0 for r in rows)
    run = pointing_from_run(tmp_path)
    acq = run.acquisition_s()
    assert acq is not None and acq <= 350.0
    assert run.steady_sunlit() and max(run.steady_sunlit()) <= 10.0


def _tracker_loss_flight(out, spin_rate_deg_s):
    """campaigns/adcs/sun_safe_tracker_loss.seq shortened: SUN_SPIN_RATE set at the start, the tracker back at 400 s."""
    out.mkdir()
    seq = out / "loss.seq"
    seq.write_text(f"R00:00:00 {CTRL}.POINTING_ACTUATOR_PRM_SET MAGNETORQUERS\n"
                   f"R00:00:00 {CTRL}.SUN_SPIN_RATE_PRM_SET {spin_rate_deg_s}\n"
                   f"R00:00:00 {CTRL}.SET_TARGET_QUATERNION 0.9238795325112867 0 0.3826834323650898 0\n"
                   f"R00:00:01 {CTRL}.FORCE_MODE POINTING\n")
    summary, _ = fly(out, 430.0, sequence=seq, settings=SUN_SAFE_SEED_1 + ("sensors.star_tracker.outage_s=[20,400]",))
    return [(round(t["t_s"], 1), t["mode"]) for t in summary["control_mode_transitions"]]


def test_coil_sun_safe_on_star_tracker_loss_and_back_on_knowledge(tmp_path):
    """ADCS-109: adcs_ref in POINTING on the coils from a 2 °/s tumble (sun_safe_tracker_loss.seq, shortened);
    the tracker gives nothing from 20 s to 400 s (sensors.star_tracker.outage_s): SUN_SAFE at 20 s +
    ATTITUDE_TIMEOUT (ATTITUDE_LOST), and with SUN_SPIN_RATE 1.5 °/s back to POINTING (KNOWLEDGE_RESTORED) within
    SUN_SAFE_EXIT_DWELL + 1 s of the tracker's return. At the default 3 °/s the spin is above the tracker's 2 °/s
    rate limit: no fix comes and SUN_SAFE is not left (docs/studies/sun_safe.md)."""
    modes = _tracker_loss_flight(tmp_path / "slow_spin", 1.5)
    assert [m for _, m in modes][:3] == ["POINTING", "SUN_SAFE", "POINTING"]
    assert 19.8 + 90.0 <= modes[1][0] <= 20.0 + 91.0  # the last fix: 19.8 s (5 Hz)
    assert 400.0 + 10.0 <= modes[2][0] <= 400.0 + 11.0
    events = (tmp_path / "slow_spin" / "events.log").read_text()
    assert "Entering SUN_SAFE (ATTITUDE_LOST)" in events
    assert "Leaving SUN_SAFE for POINTING (KNOWLEDGE_RESTORED)" in events
    modes = _tracker_loss_flight(tmp_path / "default_spin", 3.0)
    assert [m for _, m in modes] == ["POINTING", "SUN_SAFE"]


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5])
def test_the_hand_back_flights_enter_pointing_on_every_seed(tmp_path, seed):
    """ADCS-111: the premise of the hand-back table of docs/studies/sun_safe.md (POINTING, then the tracker lost): from
    seed N's HAND_BACK_RATE_DEG_S tumble (below the tracker's 2 °/s smear limit), with the run's seed N, the
    sequence's FORCE_MODE POINTING at 1 s is accepted on every seed 1–5. At 2 °/s seed 5's was refused
    (NoAttitudeKnowledge, CS_CommandError): |ω| sat on the limit and rose, so no fix came before 1 s."""
    from detumble.sim.sun_safe_check import HAND_BACK_RATE_DEG_S, seed_settings

    settings = seed_settings(seed, HAND_BACK_RATE_DEG_S) + ["sensors.star_tracker.outage_s=[20,3000]"]
    loaded = load_topology(TOPOLOGY, {"spacecraft": {"settings": settings, "seed": seed}})
    summary = run_deployment(loaded, tmp_path, duration_s=1.5, plots=False,
                             sequence=ROOT / "campaigns" / "adcs" / "sun_safe_hand_back.seq")
    assert [(t["mode"], round(t["t_s"], 1)) for t in summary["control_mode_transitions"]] == [("POINTING", 1.0)]
    assert "NoAttitudeKnowledge" not in (tmp_path / "events.log").read_text()


@pytest.mark.slow
def test_coil_sun_safe_hands_back_to_pointing_with_no_operator(tmp_path):
    """ADCS-110: campaigns/adcs/sun_safe_hand_back.seq (no ground step after 1 s), seed 1's 2 °/s tumble, the tracker
    out from 20 s to 3000 s: SUN_SAFE (ATTITUDE_LOST) after ATTITUDE_TIMEOUT, SunSpinLowered once +Z has held the Sun
    (measured 1986 s: acquisition 1676 s + SUN_HOLD_DWELL), +Z within 10° of the true Sun from then to the end of
    the sunlit part (2809 s; max 4.7° measured), the body rate below the tracker's 2 °/s when it returns, and POINTING
    (KNOWLEDGE_RESTORED) within SUN_SAFE_EXIT_DWELL + 1 s of it; if POINTING's slew loses the tracker again (seed 1:
    SUN_SAFE at 3127.5 s) the re-entry keeps the lowered spin and the flight ends in POINTING (3160 s). ~3200 s of
    flight (docs/studies/sun_safe.md)."""
    from detumble.sim.sun_safe_check import pointing_from_run

    seq = ROOT / "campaigns" / "adcs" / "sun_safe_hand_back.seq"
    commands = [line for line in seq.read_text().splitlines() if line.strip() and not line.startswith(";")]
    assert len(commands) == 3 and not any("SUN_SPIN_RATE" in c or "SUN_HOLD" in c for c in commands)
    summary, _ = fly(tmp_path, 3200.0, sequence=seq,
                     settings=SUN_SAFE_SEED_1 + ("sensors.star_tracker.outage_s=[20,3000]",))
    modes = [(round(t["t_s"], 1), t["mode"]) for t in summary["control_mode_transitions"]]
    assert [m for _, m in modes][:3] == ["POINTING", "SUN_SAFE", "POINTING"]
    assert 3000.0 + 10.0 <= modes[2][0] <= 3000.0 + 11.0
    assert modes[-1][1] == "POINTING"  # a bounce back to SUN_SAFE (if any) hands back again
    events = (tmp_path / "events.log").read_text()
    assert "Entering SUN_SAFE (ATTITUDE_LOST)" in events and "SunSpinLowered" in events
    assert "Leaving SUN_SAFE for POINTING (KNOWLEDGE_RESTORED)" in events
    run = pointing_from_run(tmp_path)
    assert run.spin_lowered_s is not None and run.spin_lowered_s < 2700.0
    err, rate = run.after_spin_down()
    assert len(err) >= 100 and max(err) <= 10.0
    at_return = [w for t, w in zip(run.times, run.rate_deg_s, strict=True) if 2990.0 <= t <= 3010.0]
    assert at_return and max(at_return) < 2.0


def test_sun_safe_flies_on_the_albedo_corrected_sun_vector(tmp_path):
    """ADCS-112: adcs_ref with the Earth's albedo (0.3) on the light sensors, SUN_ALBEDO_CORRECTION ENABLED and
    FORCE_MODE SUN_SAFE from a 2 °/s tumble, 200 s: every sunlit reading the ADCS component published (SunVector)
    is within 5° of the truth (median below 2°) while its uncorrected SunVectorRaw is off by more than 5° at the
    median; AlbedoCorrected 1 at every reading after the sequence's PRM_SET; the controller's SunVectorEstimate is
    the corrected vector (its last value within 2° of the last SunVector); no AlbedoCorrectionUnavailable."""
    import math
    import statistics

    from detumble.sim.sun_safe_check import vector_errors_from_run

    adcs = "ReferenceDeployment.adcs"
    seq = tmp_path / "sun.seq"
    seq.write_text(f"R00:00:00 {adcs}.SUN_ALBEDO_CORRECTION_PRM_SET ENABLED\nR00:00:00 {CTRL}.FORCE_MODE SUN_SAFE\n")
    out = tmp_path / "out"
    loaded = load_topology(TOPOLOGY, {"spacecraft": {"settings": ["initial.rate.magnitude_deg_s=2.0",
                                                                  "initial.rate.axis=[0.6,-0.48,0.64]",
                                                                  "sensors.sun_sensors.albedo=0.3"]}})
    summary = run_deployment(loaded, out, duration_s=200.0, sequence=seq, plots=False, quiet=True)
    assert [t["mode"] for t in summary["control_mode_transitions"]] == ["SUN_SAFE"]
    corrected, invalid = vector_errors_from_run(out)
    raw, _ = vector_errors_from_run(out, channel="SunVectorRaw")
    assert len(corrected) >= 190 and invalid == 0
    assert max(corrected) <= 5.0 and statistics.median(corrected) < 2.0
    assert statistics.median(raw) > 5.0
    last = {}
    with open(out / "channels.csv", newline="") as f:
        for row in csv.DictReader(f):
            last.setdefault(row["channel"], []).append(row["value"])
    assert set(last[f"{adcs}.AlbedoCorrected"][1:]) == {"1"}  # the 1 Hz group's first run is before the PRM_SET
    estimate, published = (json.loads(last[name][-1]) for name in (f"{CTRL}.SunVectorEstimate", f"{adcs}.SunVector"))
    dot = sum(a * b for a, b in zip(estimate, published, strict=True))
    assert math.degrees(math.acos(max(-1.0, min(1.0, dot)))) < 2.0
    assert "AlbedoCorrectionUnavailable" not in (out / "events.log").read_text()
