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
    RATE_BLEND_GAIN while the error exceeds RATE_BLEND_ANGLE, and the default rate gate); without the blend
    (RATE_BLEND_ANGLE = 180°) and without the gate (INTEGRAL_RATE_GATE 0) the same slew takes more than 60 s (the
    issue's 67 s)."""
    big = ["spacecraft.inertia_kg_m2=[[0.00242, 0.00002, -0.000015], [0.00002, 0.002365, 0.00001], "
           "[-0.000015, 0.00001, 0.002255]]"]
    s = _slew(big)
    assert s["slews"][0]["angle_deg"] > 89.0 and s["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert s["pointing_error_deg"]["p95"] <= 0.05 and s["steady_after_slew_p95_deg"] <= 0.05
    # the configuration: no blend and no rate gate (both came later; the gate alone brings this to 42 s)
    old = _slew(big + ["control.adcs.RATE_BLEND_ANGLE=180", "control.adcs.INTEGRAL_RATE_GATE=0"])
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


def _tail_after_settle(settings: list[str], scenario: str | None = None) -> tuple[dict, float]:
    """The campaign's flight (campaigns/adcs/scenarios/robust_rates.yaml, 330 s, unless ``scenario`` names another) of
    ``settings``: its summary and the seconds the true error spent above 0.05° after the slew settled below 0.1°."""
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[3] / "campaigns" / "adcs" / "scenarios" / "robust_rates.yaml"
    r = run(load_scenario(scenario or str(path), seed=2102531420, settings=settings), law="adcs", duration_s=330.0)
    s = r.summary
    assert r.adcs_header is not None and r.adcs_rows is not None
    k = r.adcs_header.index("pointing_error_deg")
    settled = s["slews"][0]["t_s"] + s["slews"][0]["settle_below_0p1_deg_s"]
    above = sum(1 for row, a in zip(r.rows, r.adcs_rows, strict=True)
                if row[0] >= settled and a[k] not in ("", None) and float(a[k]) > 0.05)
    return s, above * 0.5


@pytest.mark.slow
def test_the_integral_window_removes_the_tail_after_a_slew():
    """ADCS-131 (slow): the robust-rates campaign's draw c85102070e557b0b, without the rate gate (INTEGRAL_RATE_GATE 0,
    the default before issue 27's gate). With the default INTEGRAL_WINDOW (1°) the
    integral fills during the slew's last degree and returns it as a tail at the slow root (ADCS-130): more than
    10 s above 0.05° after the settle and an honest-window p95 above 0.05°; with INTEGRAL_WINDOW 0.1° at most 2 s
    and p95 ≤ 0.05° (docs/studies/robust_rates.md). The settle stays below 30 s in both."""
    off = ["control.adcs.INTEGRAL_RATE_GATE=0"]  # the former default: no rate gate (ADCS-144 flies the gate)
    wide, wide_above = _tail_after_settle(_DRAW_C851 + off)
    narrow, narrow_above = _tail_after_settle(_DRAW_C851 + off + ["control.adcs.INTEGRAL_WINDOW=0.1"])
    for s in (wide, narrow):
        assert s["slews"][0]["angle_deg"] > 80.0 and s["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert wide_above > 10.0 and wide["pointing_error_deg"]["p95"] > 0.05
    assert narrow_above <= 2.0 and narrow["pointing_error_deg"]["p95"] <= 0.05


@pytest.mark.slow
def test_the_rate_gate_removes_the_tail_after_a_slew():
    """ADCS-144 (slow): the draw of ADCS-131 with INTEGRAL_RATE_GATE 0.05 °/s (the default; set here explicitly) and
    the default 1° window: at most 2 s
    above 0.05° after the settle (24 s without the gate) and an honest-window p95 ≤ 0.05°, the settle below 30 s."""
    gated, above = _tail_after_settle(_DRAW_C851 + ["control.adcs.INTEGRAL_RATE_GATE=0.05"])
    assert gated["slews"][0]["angle_deg"] > 80.0 and gated["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert above <= 2.0 and gated["pointing_error_deg"]["p95"] <= 0.05


@pytest.mark.slow
def test_the_default_flies_the_rate_gate(tmp_path):
    """ADCS-160 (slow): the controller's defaults fly the rate gate (INTEGRAL_RATE_GATE 0.05 °/s, issue 27): the draw of
    ADCS-131 with no controller parameter set leaves at most 2 s above 0.05° after the settle and an honest-window p95
    ≤ 0.05° (without the gate, ADCS-131: more than 10 s and p95 above 0.05°), the settle below 30 s."""
    import pathlib

    # the campaign's scenario without its pin of the former default (INTEGRAL_RATE_GATE 0): the controller's own
    scenarios = pathlib.Path(__file__).resolve().parents[3] / "campaigns" / "adcs" / "scenarios"
    text = (scenarios / "robust_rates.yaml").read_text(encoding="utf-8")
    pin = [line for line in text.splitlines(keepends=True) if line.strip().startswith("INTEGRAL_RATE_GATE:")]
    assert len(pin) == 1
    (tmp_path / "robust_rates_default.yaml").write_text(text.replace(pin[0], ""), encoding="utf-8")
    flown, above = _tail_after_settle(_DRAW_C851, scenario=str(tmp_path / "robust_rates_default.yaml"))
    assert flown["slews"][0]["angle_deg"] > 80.0 and flown["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert above <= 2.0 and flown["pointing_error_deg"]["p95"] <= 0.05


def _hold_under_a_constant_torque(torque_nm: float, settings: list[str]) -> float:
    """The robust-rates scenario from rest, the plant's inertia = the controller's model, no residual dipole, and a
    constant body torque ``torque_nm`` (N·m, about body x) the controller does not model, applied by the plant; the
    hold of the attitude of entry (POINTING from 30 s, no target change): the median true error from 230 s to 330 s
    (deg)."""
    import pathlib
    import statistics

    from detumble.sim.plant import Plant

    path = pathlib.Path(__file__).resolve().parents[3] / "campaigns" / "adcs" / "scenarios" / "robust_rates.yaml"
    sc = load_scenario(str(path), seed=1, settings=["spacecraft.residual_dipole_am2=[0, 0, 0]",
                                                   "control.adcs.target_changes=[]",
                                                   "initial.rate.omega_deg_s=[0, 0, 0]", "record_interval_s=0.5",
                                                   *settings])
    plant = Plant(sc, 1)
    assert plant._surfaces is None  # the scenario has no drag or solar pressure: the extra torque is the only one
    plant._surfaces = True  # the plant adds _surface_torque's value to the dynamics: here the constant torque
    plant._surface_torque = lambda t, state: (torque_nm, 0.0, 0.0)
    r = run(sc, law="adcs", duration_s=330.0, plant=plant)
    assert r.adcs_header is not None and r.adcs_rows is not None
    k = r.adcs_header.index("pointing_error_deg")
    return statistics.median(float(a[k]) for row, a in zip(r.rows, r.adcs_rows, strict=True)
                             if row[0] >= 230.0 and a[k] not in ("", None))


@pytest.mark.slow
def test_the_rate_gate_keeps_the_integrals_reach_in_the_law():
    """ADCS-142 (slow): the flight law (plant-only) holding under an unmodelled constant torque. 3e-7 N·m: without
    the integral the error sits near 0.1° (the observer's factor 10.1 pushes it out, above RATE_BLEND_ANGLE the blend's
    1 + K_D/(2I) = 1.45 lets it back); with the 0.05 °/s gate, which reads the gyro, it is removed (median < 0.01°);
    a gate reading the observer's rate (lag d/(I L) = 0.078 °/s) would not be; the 0.1° window removes it too (at
    the blend's switching). 1e-6 N·m: the blend's factor alone
    holds 1.45 d/(K_P/2) = 0.15° > 0.1°, so a 0.1° window never integrates it (median > 0.14°); the gate's 1° window
    does (median below half of that; docs/studies/robust_rates.md, "The rate gate")."""
    gate = ["control.adcs.INTEGRAL_RATE_GATE=0.05"]
    assert _hold_under_a_constant_torque(3e-7, ["control.adcs.K_I=0"]) > 0.08
    assert _hold_under_a_constant_torque(3e-7, gate) < 0.01
    # the blend's switching at 0.1° lets a 0.1° window reach this torque too (the page's limit 9.5e-8 N·m ignored it)
    narrow = ["control.adcs.INTEGRAL_WINDOW=0.1", "control.adcs.INTEGRAL_RATE_GATE=0"]  # the window alone, no gate
    assert _hold_under_a_constant_torque(3e-7, narrow) < 0.01
    window = _hold_under_a_constant_torque(1e-6, narrow)
    assert window > 0.14
    assert _hold_under_a_constant_torque(1e-6, gate) < 0.5 * window


#: The robust-rates campaign's draw 3 (seed 2322129229, run 7eed08c37a3f4a0a): the worst of the three the default
#: misses (honest-window p95 0.064°, docs/studies/robust_rates.md).
_DRAW_3 = ["initial.attitude.quaternion=[0.7071067811865476, -0.40550546833391066, 0.2064106019636068, "
           "-0.5412577745846403]",
           "initial.rate.omega_deg_s=[-0.025637938949145227, -0.02883012103709754, 0.02117682366105961]",
           "orbit.arg_latitude_deg=295.6647128023345",
           "spacecraft.inertia_kg_m2=[[0.002316624487247223, 3.753763483293934e-05, -2.154862752188413e-08], "
           "[3.753763483293934e-05, 0.0022228712568566934, -1.723630104895505e-06], "
           "[-2.154862752188413e-08, -1.723630104895505e-06, 0.0022176435272181013]]"]


def _entry_hold(settings: list[str], scenario: str | None = None) -> tuple[dict, float]:
    """Draw 3 flown as the gate campaign flies it (campaigns/adcs/scenarios/robust_rates_gate.yaml, 330 s; it pins
    RATE_OBSERVER_DIPOLE_TIME 0, or ``scenario`` instead) with ``settings`` added: its summary and the seconds the true
    error spent above 0.05° in the hold of the attitude of entry (30–60 s, sampled each second)."""
    import pathlib

    path = scenario or str(pathlib.Path(__file__).resolve().parents[3] / "campaigns" / "adcs" / "scenarios"
                           / "robust_rates_gate.yaml")
    r = run(load_scenario(path, seed=2322129229, settings=_DRAW_3 + settings), law="adcs", duration_s=330.0)
    assert r.adcs_header is not None and r.adcs_rows is not None
    k = r.adcs_header.index("pointing_error_deg")
    above = sum(1 for row, a in zip(r.rows, r.adcs_rows, strict=True)
                if 30.0 < row[0] < 60.0 and a[k] not in ("", None) and float(a[k]) > 0.05)
    return r.summary, float(above)


@pytest.mark.slow
def test_the_observers_residual_dipole_removes_the_entry_hump():
    """ROB-030 (slow): the robust-rates draw the default misses worst (draw 3: honest-window p95 0.064°, 12 s above
    0.05° in the hold of the attitude of entry, from the plant's residual dipole through the observer's d/(I L)).
    With RATE_OBSERVER_DIPOLE_TIME 20 s the observer has learned the dipole in the 30 s before POINTING: at most 7 s
    above 0.05° in that hold and the p95 ≤ 0.05°; without it (0, the gate scenario's pin: the default before issue
    27's) more than 10 s and p95 above 0.05°. The slew settles below 0.1° within 30 s in both."""
    off, off_above = _entry_hold([])
    on, on_above = _entry_hold(["control.adcs.RATE_OBSERVER_DIPOLE_TIME=20"])
    for s in (off, on):
        assert s["slews"][0]["angle_deg"] > 80.0 and s["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert off_above > 10.0 and off["pointing_error_deg"]["p95"] > 0.05
    assert on_above <= 7.0 and on["pointing_error_deg"]["p95"] <= 0.05


@pytest.mark.slow
def test_the_default_flies_the_residual_dipole_estimate(tmp_path):
    """ROB-040 (slow): the controller's defaults fly the rate observer's residual-dipole estimate
    (RATE_OBSERVER_DIPOLE_TIME 20 s since issue 27): ROB-030's draw 3 in the gate scenario without its pin of the
    former default (0) and no controller parameter set leaves at most 7 s above 0.05° in the hold of the attitude of
    entry and an honest-window p95 ≤ 0.05° (with the pin, ROB-030: more than 10 s and p95 above 0.05°), the slew's
    settle below 30 s."""
    import pathlib

    scenarios = pathlib.Path(__file__).resolve().parents[3] / "campaigns" / "adcs" / "scenarios"
    text = (scenarios / "robust_rates_gate.yaml").read_text(encoding="utf-8")
    pin = [line for line in text.splitlines(keepends=True) if line.strip().startswith("RATE_OBSERVER_DIPOLE_TIME:")]
    assert len(pin) == 1
    (tmp_path / "robust_rates_default.yaml").write_text(text.replace(pin[0], ""), encoding="utf-8")
    flown, above = _entry_hold([], scenario=str(tmp_path / "robust_rates_default.yaml"))
    assert flown["slews"][0]["angle_deg"] > 80.0 and flown["slews"][0]["settle_below_0p1_deg_s"] < 30.0
    assert above <= 7.0 and flown["pointing_error_deg"]["p95"] <= 0.05


def test_the_dipole_fit_reads_the_gyro_as_measured_so_any_estimator_serves(monkeypatch):
    """ADCS-181: the residual-dipole fit reads the gyro's reading, bias and all (a constant bias has no slope), not
    the estimator's bias-corrected rate, whose correction moves while it converges. With ESTIMATOR COMPLEMENTARY,
    whose bias is still converging in the 30 s of calm before POINTING (adcs scenario, 90° from the target, POINTING
    at 30 s, the identity at 60 s), the estimate at POINTING's entry is within 3e-4 A·m² of the plant's residual dipole
    on each axis (reading the corrected rate it was (−4.0, −5.3, 7.1)e-3 against (1.0, −0.5, 0.8)e-3) and the steady
    p95 from 120 s is ≤ 0.05° (0.067° then; docs/studies/robust_rates.md, limit (3))."""
    from detumble.control.rate_observer import RateObserver

    fit, update = RateObserver.learn_dipole, RateObserver.update
    cycles, seen = [0], []

    def counted(self, *args, **kwargs):
        cycles[0] += 1
        return update(self, *args, **kwargs)

    def learned(self, *args):
        seen.append((cycles[0], fit(self, *args)))
        return self.dipole

    monkeypatch.setattr(RateObserver, "update", counted)
    monkeypatch.setattr(RateObserver, "learn_dipole", learned)
    sc = load_scenario("adcs", settings=[
        "initial.rate.magnitude_deg_s=0.05",
        "initial.attitude.quaternion=[0.7071067811865476,0.4082482904638631,0.4082482904638631,0.4082482904638631]",
        "control.adcs.force_mode=POINTING", "control.adcs.force_at_s=30", "control.adcs.target_q_bn=null",
        "control.adcs.target_changes=[[60, 1.0, 0.0, 0.0, 0.0]]", "record_interval_s=0.5",
        "control.adcs.ESTIMATOR=COMPLEMENTARY", "control.adcs.RATE_OBSERVER_DIPOLE_TIME=20"])
    r = run(sc, law="adcs", duration_s=400.0)
    cycle_s = r.rows[-1][0] / cycles[0]
    at_entry = [m for n, m in seen if n * cycle_s <= 30.0]
    assert at_entry and any(x != 0.0 for x in at_entry[-1])
    plant = sc.spacecraft.residual_dipole_am2
    assert all(abs(at_entry[-1][i] - plant[i]) < 3e-4 for i in range(3)), (at_entry[-1], plant)
    assert r.adcs_header is not None and r.adcs_rows is not None
    k = r.adcs_header.index("pointing_error_deg")
    steady = sorted(float(a[k]) for row, a in zip(r.rows, r.adcs_rows, strict=True) if row[0] >= 120.0)
    assert steady[int(round(0.95 * (len(steady) - 1)))] <= 0.05
