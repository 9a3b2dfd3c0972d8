"""The detumble campaign plug-ins: the plant run kind and the named metrics, checked against closed
forms."""

from __future__ import annotations

import json
import math
import pathlib

import numpy as np
import pytest

from detumble.sim.plant import Plant
from detumble.sim.readback import read_setting
from detumble.sim.scenario import load_scenario
from detumble.reports.campaign import METRICS, PLANT_RUN, CoilEnergyMeter
from fprime_lite.tools.campaign import MetricUnavailable, RunOutput, RunRequest
from fprime_lite.tools.campaign.kinds import metrics, run_kinds

BY_NAME = {m.name: m for m in METRICS}


def test_plug_ins_are_installed_through_entry_points():
    """CAMP-060: the engine finds the plant kind and the detumble metrics through their entry points."""
    assert run_kinds()["plant"] is PLANT_RUN
    assert set(BY_NAME) <= set(metrics())


def test_settling_time_of_an_exponential_decay():
    """CAMP-061: for |w| = w0·exp(-t/τ) (final ≈ 0) the 2 % settling time is τ·ln(50) within one
    sample (closed form)."""
    tau, dt = 100.0, 0.5
    t = np.arange(0, 2000 + dt, dt)
    r = 30.0 * np.exp(-t / tau)
    got = BY_NAME["settling_time_2pct_s"].compute(RunOutput({}, {"t_s": t, "rate_deg_s": r}), None)
    band = 0.02 * (r[0] - r[-1])  # the band is 2 % of the change actually made
    expected = -tau * math.log((band) / 30.0 + r[-1] / 30.0)
    assert abs(got - expected) <= dt
    assert abs(got - tau * math.log(50)) < 1.0
    with pytest.raises(MetricUnavailable, match="not settled"):
        BY_NAME["settling_time_2pct_s"].compute(RunOutput({}, {"t_s": t[:100], "rate_deg_s": 30 - t[:100]}), None)


def test_coil_energy_is_power_times_time():
    """CAMP-062: X+ held at level 127 for 10 s and Y− at −64 for 4 s spend (V²/R)·10 + ((64/127)V)²/R·4 J."""
    sc = load_scenario("default")
    plant = Plant(sc)
    meter = CoilEnergyMeter(plant)
    spec = plant.actuators.coils[0].spec
    plant.set_coil_level(0, 127)
    plant.set_coil_level(3, -64)
    for _ in range(200):  # 4 s at 0.02 s
        plant.step()
    plant.set_coil_level(3, 0)
    for _ in range(300):  # 6 s more
        plant.step()
    y = plant.actuators.coils[3].spec
    expected = spec.voltage_v ** 2 / spec.resistance_ohm * 10.0 + (64 / 127 * y.voltage_v) ** 2 / y.resistance_ohm * 4.0
    assert meter.total_j() == pytest.approx(expected, rel=1e-12)


def test_metrics_the_plant_cannot_give_are_null_with_a_reason():
    """CAMP-063: pointing error and wheel momentum are unavailable with a reason; so is coil energy
    for ideal rods; detumble time says the rate never fell below 1 deg/s."""
    out = RunOutput({"time_below_1_deg_s": None, "final_rate_deg_s": 4.5})
    for name, words in (("pointing_error_mean_deg", "no pointing target"), ("wheel_momentum_peak_nms", "wheel"),
                        ("detumble_time_s", "stayed above 1 deg/s")):
        with pytest.raises(MetricUnavailable, match=words):
            BY_NAME[name].compute(out, None)
    rods = CoilEnergyMeter(Plant(load_scenario("case_a")))
    with pytest.raises(MetricUnavailable, match="torque rods"):
        rods.total_j()


def test_plant_run_reads_its_values_back_from_the_plant(tmp_path):
    """CAMP-064: scenario values are read from the built plant (not echoed): a rate magnitude and
    axis come back as |w(0)| and w(0)/|w(0)|, the run honours its duration and seed."""
    axis = [1.0, 2.0, 2.0]
    req = RunRequest(config={"scenario": "default", "law": "bdot", "duration_s": 5.0},
                     values={"scenario.initial.rate.magnitude_deg_s": 12.5, "scenario.initial.rate.axis": axis,
                             "scenario.sensors.magnetometer.noise_std_gauss": 0.001},
                     seed=99, out_dir=tmp_path, base_dir=pathlib.Path("."))
    prepared = PLANT_RUN.prepare(req)
    out = prepared.execute()
    assert prepared.readback("scenario.initial.rate.magnitude_deg_s") == pytest.approx(12.5, rel=1e-12)
    assert prepared.readback("scenario.initial.rate.axis") == pytest.approx([1 / 3, 2 / 3, 2 / 3], rel=1e-12)
    assert prepared.readback("scenario.sensors.magnetometer.noise_std_gauss") == 0.001
    assert out.summary["sim_seconds"] == pytest.approx(5.0) and out.summary["seed"] == 99
    assert read_setting(prepared.simulation, "seed") == 99
    with pytest.raises(KeyError, match="initial state is read back as"):
        read_setting(prepared.simulation, "initial.rate.spin")
    json.dumps(out.summary)  # the summary is plain data


def test_wheel_and_settling_metrics_come_from_the_run(tmp_path):
    """CAMP-065: on `surrey` with the wheel law, wheel_momentum_peak_nms is the largest |h| of the
    run's truth (within the wheels' 0.1 N·m·s), and settling_time_2pct_s is the run summary's own
    (seed 004's per-axis bands), not a figure recomputed from |ω|."""
    req = RunRequest(config={"scenario": "surrey", "law": "wheels_pd", "duration_s": 30.0}, values={}, seed=1,
                     out_dir=tmp_path, base_dir=pathlib.Path("."))
    out = PLANT_RUN.prepare(req).execute()
    peak = BY_NAME["wheel_momentum_peak_nms"].compute(out, None)
    assert 1e-3 < peak <= 0.1 + 1e-12
    assert BY_NAME["settling_time_2pct_s"].compute(out, None) == out.summary["settling_time_2pct_s"]


def test_a_key_set_for_every_wheel_reads_back_once():
    """CAMP-066: reaction_wheels.momentum_noise_std_nms, set for all wheels at once, is read back
    from the built plant's wheels (one value when they agree)."""
    from detumble.sim.readback import read_setting

    plant = Plant(load_scenario("surrey", settings=["spacecraft.reaction_wheels.momentum_noise_std_nms=1.0e-05"]))
    assert read_setting(plant, "spacecraft.reaction_wheels.momentum_noise_std_nms") == 1e-05


def test_pointing_statistics_come_from_the_run_summary():
    """CAMP-067: pointing_median_deg, pointing_p95_deg and pointing_max_deg are the run summary's POINTING
    statistics (AttitudeRunReport: after the first 10 % of POINTING); without them, null with a reason."""
    stats = {"median": 3.8, "p95": 10.4, "max": 13.4, "samples": 100}
    out = RunOutput({"pointing_error_deg": stats})
    for name, key in (("pointing_median_deg", "median"), ("pointing_p95_deg", "p95"), ("pointing_max_deg", "max")):
        assert BY_NAME[name].compute(out, None) == stats[key]
        for summary in ({}, {"pointing_error_deg": None}):
            with pytest.raises(MetricUnavailable, match="no POINTING statistics"):
                BY_NAME[name].compute(RunOutput(summary), None)
def test_spin_metrics_come_from_the_attitude_report_s_summary():
    """CAMP-068: mode_transitions counts the ground's ControlModeChanged transitions; spin_axis_error_*_deg are the
    AttitudeRunReport's SPIN_STABLE statistics; each is null with its reason when the run has no attitude report
    or no SPIN_STABLE samples."""
    summary = {"control_mode_transitions": [{"t_s": 0.0, "mode": "SPIN_STABLE"}, {"t_s": 480.5, "mode": "POINTING"}],
               "spin_axis_error_deg": {"median": 1.2, "p95": 3.4, "max": 7.5, "samples": 900}}
    out = RunOutput(summary)
    assert BY_NAME["mode_transitions"].compute(out, None) == 2.0
    assert [BY_NAME[f"spin_axis_error_{s}_deg"].compute(out, None) for s in ("median", "p95", "max")] == [1.2, 3.4, 7.5]
    for name, words in (("mode_transitions", "no attitude report"), ("spin_axis_error_p95_deg", "no attitude report")):
        with pytest.raises(MetricUnavailable, match=words):
            BY_NAME[name].compute(RunOutput({"final_rate_deg_s": 1.0}), None)
    with pytest.raises(MetricUnavailable, match="no SPIN_STABLE samples"):
        BY_NAME["spin_axis_error_max_deg"].compute(RunOutput({"spin_axis_error_deg": None}), None)


def test_per_channel_settling_metrics_read_the_run_summary():
    """CAMP-070: settling_time_2pct_x/y/z_s and _attitude_s are the run summary's channels; a channel
    not settled, or a summary without them (not a seed-004 law), is a null with its reason."""
    out = RunOutput({"settling_time_2pct_axes_s": [6339.92, 73.73, None], "settling_time_2pct_attitude_s": 7.95})
    assert BY_NAME["settling_time_2pct_x_s"].compute(out, None) == 6339.92
    assert BY_NAME["settling_time_2pct_y_s"].compute(out, None) == 73.73
    assert BY_NAME["settling_time_2pct_attitude_s"].compute(out, None) == 7.95
    with pytest.raises(MetricUnavailable, match="not settled"):
        BY_NAME["settling_time_2pct_z_s"].compute(out, None)
    for name in ("settling_time_2pct_x_s", "settling_time_2pct_attitude_s"):
        with pytest.raises(MetricUnavailable, match="only seed 004's laws"):
            BY_NAME[name].compute(RunOutput({"final_rate_deg_s": 1.0}), None)
