"""The three-mode law pointing at moving targets plant-only (``fprime-lite sim --law adcs``, issue 27): a
ground-station pass tracked on the wheels, and nadir (LVLH) over one orbit against the issue's goals."""

import pytest

from detumble.sim.runner import run
from detumble.sim.scenario import ScenarioError, load_scenario

#: A station 3° east of the ground track at 250 s: in view (10° mask) from ~80 s to ~475 s, peak elevation ~80°.
STATION = "12.588265107202169, 122.40357949484263, 0.0"


def _fly(target: str, duration_s: float) -> dict:
    settings = ["initial.rate.magnitude_deg_s=0", "control.adcs.force_mode=POINTING", "control.adcs.force_at_s=1",
                f"control.adcs.target_changes=[[0.5, {target}]]"]
    return run(load_scenario("adcs", settings=settings), law="adcs", duration_s=duration_s).summary


def test_a_ground_station_pass_is_tracked_in_view_within_the_goal():
    """ADCS-092: from rest, a station target: nadir fallback first, the station acquired when it rises (below 0.1°
    within 30 s) and tracked at steady p95 ≤ 0.05° (the issue's goal) while in view, nadir again when it sets; the
    intervals and the per-reference statistics say which reference each sample measured."""
    s = _fly(f"GROUND_STATION, {STATION}, PLUS_Z, PLUS_X", 520.0)
    labels = [i["target"] for i in s["pointing_intervals"]]
    assert labels == ["STATION_FALLBACK", "GROUND_STATION", "STATION_FALLBACK"]
    rise = s["pointing_intervals"][1]
    assert 60.0 < rise["t_s"] < 100.0 and rise["acquisition_s"] is not None and rise["acquisition_s"] < 30.0
    in_view = s["pointing_error_by_target_deg"]["GROUND_STATION"]
    assert in_view["p95"] <= 0.05 and in_view["samples"] > 600
    assert s["pointing_error_deg"]["window"] == "steady" and s["pointing_error_deg"]["acquisition_threshold_deg"] == 0.1


def test_a_malformed_moving_target_is_refused_at_the_scenario_key():
    """ADCS-093: control.adcs.target_changes refuses a parallel axis pair and a station off the Earth by name."""
    with pytest.raises(ScenarioError, match="parallel"):
        load_scenario("adcs", settings=["control.adcs.target_changes=[[1, NADIR, PLUS_Z, MINUS_Z]]"])
    with pytest.raises(ScenarioError, match="latitude"):
        load_scenario("adcs", settings=["control.adcs.target_changes=[[1, GROUND_STATION, 95, 0, 0, PLUS_Z, PLUS_X]]"])


@pytest.mark.slow
def test_nadir_pointing_over_one_orbit_meets_the_goal():
    """ADCS-094 (slow): nadir (LVLH) on the wheels with the star tracker over one orbit from rest: acquisition below
    0.1° within 40 s, then steady median ≤ 0.01° and p95 ≤ 0.03° (the issue's goals)."""
    s = _fly("NADIR, PLUS_Z, PLUS_X", 5580.0)
    p = s["pointing_error_deg"]
    assert p["acquisition_s"] < 40.0
    assert p["median"] <= 0.01 and p["p95"] <= 0.03


def _slew(settings: list[str]) -> dict:
    """A ~90° slew (the issue's): from 90° about (1, 1, 1)/√3, POINTING at 30 s holding the attitude of entry, the
    identity commanded at 60 s, to 330 s."""
    base = ["initial.rate.magnitude_deg_s=0.05",
            "initial.attitude.quaternion=[0.7071067811865476,0.4082482904638631,0.4082482904638631,"
            "0.4082482904638631]",
            "control.adcs.force_mode=POINTING", "control.adcs.force_at_s=30", "control.adcs.target_q_bn=null",
            "control.adcs.target_changes=[[60, 1.0, 0.0, 0.0, 0.0]]"]
    return run(load_scenario("adcs", settings=base + settings), law="adcs", duration_s=330.0).summary


@pytest.mark.slow
def test_a_slew_with_the_inertia_model_10_percent_off_settles_within_30_s():
    """ADCS-095 (slow): the plant's inertia ×1.10 of the controller's model: the 90° slew is below 0.1° within 30 s
    and the steady p95 ≤ 0.05° (the issue's goals) with the default rate source (the observer pulled at
    RATE_BLEND_GAIN while the error exceeds RATE_BLEND_ANGLE); without the blend (RATE_BLEND_ANGLE = 180°) the same
    slew takes more than 60 s (the issue's 67 s)."""
    big = ["spacecraft.inertia_kg_m2=[[0.00242, 0.00002, -0.000015], [0.00002, 0.002365, 0.00001], "
           "[-0.000015, 0.00001, 0.002255]]"]
    s = _slew(big)
    assert s["slews"][0]["angle_deg"] > 89.0 and s["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert s["pointing_error_deg"]["p95"] <= 0.05 and s["steady_after_slew_p95_deg"] <= 0.05
    old = _slew(big + ["control.adcs.RATE_BLEND_ANGLE=180"])
    assert old["slews"][0]["settle_below_0p1_deg_s"] > 60.0
