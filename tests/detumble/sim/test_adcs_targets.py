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


#: The robust-rates campaign's draw c85102070e557b0b (docs/studies/robust_rates/campaign/, its ``requested`` values):
#: the plant's inertia, the start, the orbit position (the noise seed below); its honest-window p95 was the campaign's
#: second largest (0.071°).
_DRAW_C851 = ["spacecraft.inertia_kg_m2=[[0.002070388808621008, -1.3996533902924319e-05, -1.3969949326111605e-05], "
              "[-1.3996533902924319e-05, 0.0021631743402672973, 2.7846512074982627e-05], "
              "[-1.3969949326111605e-05, 2.7846512074982627e-05, 0.002046366877352651]]",
              "initial.attitude.quaternion=[0.7071067811865477, -0.5458824077798762, -0.21019707976156277, "
              "0.3972777171402345]",
              "initial.rate.omega_deg_s=[0.0005109310891091469, -0.0052443468567744305, -0.0027512393867292727]",
              "orbit.arg_latitude_deg=114.25499619977569", "record_interval_s=0.5"]


def _tail_after_settle(settings: list[str]) -> tuple[dict, float]:
    """The campaign's flight (campaigns/adcs/scenarios/robust_rates.yaml, 330 s) of ``settings``: its summary and the
    seconds the true error spent above 0.05° after the slew settled below 0.1°."""
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[3] / "campaigns" / "adcs" / "scenarios" / "robust_rates.yaml"
    r = run(load_scenario(str(path), seed=2102531420, settings=settings), law="adcs", duration_s=330.0)
    s = r.summary
    assert r.adcs_header is not None and r.adcs_rows is not None
    k = r.adcs_header.index("pointing_error_deg")
    settled = s["slews"][0]["t_s"] + s["slews"][0]["settle_below_0p1_deg_s"]
    above = sum(1 for row, a in zip(r.rows, r.adcs_rows, strict=True)
                if row[0] >= settled and a[k] not in ("", None) and float(a[k]) > 0.05)
    return s, above * 0.5


@pytest.mark.slow
def test_the_integral_window_removes_the_tail_after_a_slew():
    """ADCS-131 (slow): the robust-rates campaign's draw c85102070e557b0b. With the default INTEGRAL_WINDOW (1°) the
    integral fills during the slew's last degree and returns it as a tail at the slow root (ADCS-130): more than
    10 s above 0.05° after the settle and an honest-window p95 above 0.05°; with INTEGRAL_WINDOW 0.1° at most 2 s
    and p95 ≤ 0.05° (docs/studies/robust_rates.md). The settle stays below 30 s in both."""
    wide, wide_above = _tail_after_settle(_DRAW_C851)
    narrow, narrow_above = _tail_after_settle(_DRAW_C851 + ["control.adcs.INTEGRAL_WINDOW=0.1"])
    for s in (wide, narrow):
        assert s["slews"][0]["angle_deg"] > 80.0 and s["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert wide_above > 10.0 and wide["pointing_error_deg"]["p95"] > 0.05
    assert narrow_above <= 2.0 and narrow["pointing_error_deg"]["p95"] <= 0.05
