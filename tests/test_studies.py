"""tools/studies.py: the studies' documented numbers cannot go stale.

STUDY-001: every generated block of docs/studies/ is what the committed campaign results give now (the
tables are rendered by the same code that wrote them, and compared with the docs).
STUDY-002: the committed campaign folders belong to their campaign files as they are now (hash, run ids),
and re-flying the cheap probe runs (seed 004's wheel law) gives the committed metrics to the float: a
change in the code that moves a documented number fails here.
STUDY-003/004: the check is able to fail — a doc block edited by hand, and a committed metric the code no
longer computes, are both reported.
"""

import dataclasses
import importlib.util
import json
import pathlib
import shutil
import sys

import pytest

ROOT = pathlib.Path(__file__).parents[1]
_spec = importlib.util.spec_from_file_location("studies_tool", ROOT / "tools" / "studies.py")
assert _spec is not None and _spec.loader is not None
studies = importlib.util.module_from_spec(_spec)
sys.modules["studies_tool"] = studies  # dataclasses look their module up there
_spec.loader.exec_module(studies)

COMMITTED = ("coursework_convergence", "spin_stabilisation_campaign", "coursework_grids",
             "coursework_replica_magnetorquer1", "gain_sweep", "flight_bdot_noise", "magnetic_pointing_hold",
             "magnetorquer_hold_after_acquisition", "performance_detumble", "robust_rates",
             "pointing_targets", "environment_torques", "sun_safe", "attitude_knowledge", "robust_rates_campaign",
             "environment_feed_forward", "environment_four_wheels", "pointing_gyroscopic", "magnetic_pointing",
             "magnetic_pointing_runs", "attitude_modes_magnetorquers", "attitude_modes_sensors",
             "magnetic_pointing_hold_worst", "magnetic_pointing_tumble", "robust_rates_tail",
             "robust_rates_window_campaign", "coursework_settling_ripple", "environment_closed_form",
             "attitude_knowledge_single_runs", "magnetic_pointing_hold_campaign", "magnetic_pointing_floquet_figure",
             "attitude_knowledge_orbit_runs", "attitude_modes_pointing", "attitude_modes_orbit",
             "magnetic_pointing_residual_ab", "flight_detumble_campaign",
             "magnetorquer_hold_candidates", "magnetorquer_hold_candidate_campaigns", "coursework_replica",
             "coursework_summary", "coursework_real_wheel", "attitude_knowledge_mekf",
             "attitude_knowledge_verdict", "magnetorquer_hold_lqr_bound", "magnetorquer_hold_margin")


@pytest.mark.parametrize("name", COMMITTED)
def test_documented_blocks_are_what_the_committed_results_give(name):
    """STUDY-001."""
    assert studies.check([name], fly_probes=False) == []


def test_a_comment_edit_of_a_campaign_file_is_not_staleness_but_a_value_edit_is(tmp_path, monkeypatch):
    """STUDY-007: the folder's manifest holds the campaign text it was made from; a campaign file that differs from it
    only in comments still owns the results, one whose values differ does not."""
    original = studies.CAMPAIGNS["flight_detumble_campaign"]
    text = (studies.ROOT / original.campaign_file).read_text(encoding="utf-8")
    monkeypatch.setattr(studies, "ROOT", tmp_path)
    (tmp_path / "campaigns").mkdir()
    moved = dataclasses.replace(original, campaign_file="campaigns/c.yaml")
    monkeypatch.setattr(studies, "STUDIES_DIR", original.path.parent)
    (tmp_path / "campaigns" / "c.yaml").write_text(text + "# a new comment\n", encoding="utf-8")
    assert not moved.campaign_file_changed()
    (tmp_path / "campaigns" / "c.yaml").write_text(text.replace("timeout_s: 900", "timeout_s: 901"), encoding="utf-8")
    assert moved.campaign_file_changed()


def test_committed_convergence_results_are_what_the_code_computes_now():
    """STUDY-002: the probe runs (the wheel law's rows at 0.02 and 0.01 s, 30 s each) fly again and match."""
    campaign = studies.CAMPAIGNS["coursework_convergence"]
    assert campaign.problems(fly_probes=True) == []


@pytest.mark.parametrize("key", ("coursework_wheels_pd_grid", "coursework_noise"))
def test_committed_seed004_sweeps_are_what_the_code_computes_now(key):
    """STUDY-005: the seed-004 sweeps' cheap probes (the wheel grid's report gains, the noise study's wheel runs of
    its first seed: 120 s plant runs) fly again and match their committed rows; the other folders (hours of CPU)
    are checked for belonging to their campaign files."""
    campaign = studies.CAMPAIGNS[key]
    if not (campaign.path / "results.parquet").exists():
        pytest.skip(f"docs/studies/{campaign.folder} not committed")
    assert campaign.problems(fly_probes=True) == []


def _check_with_a_hand_edit(tmp_path, monkeypatch, name: str, block: str, old: str, new: str) -> list[str]:
    """``--check``'s problems for study ``name`` when a copy of its doc has ``old`` -> ``new`` once in ``block``."""
    study = studies.STUDIES[name]
    text = study.doc.read_text(encoding="utf-8")
    body = studies.doc_blocks(text)[block]
    edited = body.replace(old, new, 1)
    assert edited != body
    copy = tmp_path / "doc.md"
    copy.write_text(text.replace(body, edited), encoding="utf-8")
    monkeypatch.setitem(studies.STUDIES, name, dataclasses.replace(study, doc=copy, campaigns=()))
    return studies.check([name], fly_probes=False)


def test_a_hand_edited_sweep_table_is_reported(tmp_path, monkeypatch):
    """STUDY-006: the wheel grid's table with one settling time changed by hand: --check reports that block."""
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "coursework_grids", "coursework_wheels_pd",
                                       "10.05", "10.04")
    assert len(problems) == 1 and "block 'coursework_wheels_pd'" in problems[0]


def test_the_bdot_noise_study_is_what_the_code_computes_now(tmp_path, monkeypatch):
    """STUDY-009: the B-dot noise campaign's probe (BDotDetumble with an ideal magnetometer, first seed: one
    deployment run of ≈ 570 simulated s) flies again and gives its committed row; the same probe against a
    copy whose committed time is nudged by 0.5 s is reported."""
    import pandas as pd

    campaign = studies.CAMPAIGNS["flight_bdot_noise"]
    assert campaign.problems(fly_probes=True) == []
    folder = tmp_path / "docs" / "studies" / "noise"
    shutil.copytree(campaign.path, folder)
    df = pd.read_parquet(folder / "results.parquet")
    probed = [i for i, row in df.iterrows() if row["seed_index"] == 0 and row["topology"].endswith("detumble.yaml")
              and row["scenario.sensors.magnetometer.noise_std_gauss"] == 0
              and row["scenario.sensors.magnetometer.resolution_gauss"] == 0]
    assert len(probed) == 1
    df.loc[probed[0], "detumble_complete_s"] += 0.5
    df.to_parquet(folder / "results.parquet")
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path / "docs" / "studies")
    problems = dataclasses.replace(campaign, folder="noise").problems(fly_probes=True)
    assert len(problems) == 1 and "detumble_complete_s" in problems[0] and "no longer computes" in problems[0]


@pytest.mark.parametrize("name, block, old, new", [
    ("magnetic_pointing_hold", "magnetic_pointing_hold", "16.27°", "16.26°"),
    ("flight_bdot_noise", "flight_bdot_noise", "**1,411 s**", "**1,399 s**"),
    ("robust_rates", "robust_rates_single_runs", "19.5 / 0.0067 / 0.0142", "19.0 / 0.0064 / 0.0145"),
    ("pointing_targets", "pointing_targets", "| 0.0106 | 0.0251 |", "| 0.0099 | 0.0269 |"),
    ("environment_torques", "environment_torques_field_auto", "| 333.9 | 851.2 |", "| 334 | 851 |"),
    ("sun_safe", "sun_safe_albedo_wheels", "| 0–2813 | 15 |", "| 0–2813 | 16 |"),
    ("robust_rates_campaign", "robust_rates_campaign", "| 0.0118 | 0.0154 | 0.0184 | 0.0237 |",
     "| 0.0118 | 0.0154 | 0.0184 | 0.0238 |"),
    ("environment_feed_forward", "environment_torques_feed_forward", "| 0.00749 |", "| 0.01980 |"),
    ("environment_four_wheels", "environment_torques_four_wheels", "| 0.0207 |", "| 0.0257 |"),
    ("pointing_gyroscopic", "pointing_targets_gyroscopic", "| 0.0090 | 0.0231 |", "| 0.0082 | 0.0226 |"),
    ("magnetic_pointing", "magnetic_pointing_floquet", "−2.24e-3", "−2.31e-3"),
    ("magnetic_pointing", "magnetic_pointing_corner_dipole", "2.39° / 12.4°", "2.39° / 12.5°"),
    ("magnetic_pointing_runs", "magnetic_pointing_tumble_runs", "118.8°", "119°"),
    ("attitude_modes_magnetorquers", "attitude_modes_magnetorquers", "99/100", "84/100"),
    ("attitude_modes_sensors", "attitude_modes_sensors", "| as in the scenario | 0.0059°",
     "| as in the scenario | 0.045°"),
    ("environment_closed_form", "environment_torques_nadir", "**7.1e-6°**", "**7e-6°**"),
    ("environment_closed_form", "environment_torques_floquet_bias", "**+9.2e-4**", "−2.39e-3"),
    ("environment_closed_form", "environment_torques_igrf_table", "**5.2 nT**", "**5.0 nT**"),
    ("attitude_knowledge_single_runs", "attitude_knowledge_design", "| 20.0 s | 0.0150° |", "| 26.5 s | 0.0155° |"),
    ("attitude_knowledge_single_runs", "attitude_knowledge_sensors", "| both ideal | 0.0002°",
     "| both ideal | 0.0013°"),
    ("magnetic_pointing", "magnetic_pointing_floor", "**0.00–1.45°**", "**0.18–0.93°**"),
    ("magnetic_pointing_runs", "magnetic_pointing_corner_runs", "(1.0, -0.5, 0.8)e-3", "(1.0, -0.5, 0.9)e-3"),
    ("magnetic_pointing_floquet_figure", "magnetic_pointing_floquet_maps", "eigenvalues 0.58, 0.63, 0.79",
     "eigenvalues 0.61, 0.62, 0.77"),
    ("sun_safe", "sun_safe_spin_down", "| 2361 | 354 |", "| 2361 | 355 |"),
    ("sun_safe", "sun_safe_spin_down_gate", "| 5.3° / 5.4° / 4.9° |", "| 5.3° / 5.4° / 5.0° |"),
    ("sun_safe", "sun_safe_spin_down_tip", "| 81.5 % / 56.8 % / 100.0 % |", "| 81.5 % / 58.6 % / 100.0 % |"),
    ("sun_safe", "sun_safe_spin_down_hold_rate", "| 288 / 439 / 396 |", "| 288 / 439 / 395 |"),
    ("sun_safe", "sun_safe_spin_down_spin_rate", "| 2361 / 2556 / never |", "| 2361 / 2556 / 2800 |"),
    ("attitude_modes_pointing", "attitude_modes_shipped", "| 5.3 % |", "| 5.4 % |"),
    ("attitude_modes_orbit", "attitude_modes_orbit", "**18.5 s**", "**19.0 s**"),
])
def test_a_hand_edited_figure_of_the_new_study_blocks_is_reported(tmp_path, monkeypatch, name, block, old, new):
    """STUDY-010: magnetic_pointing.md's hold table, flight_bdot_noise.md's, robust_rates.md's,
    pointing_targets.md's, environment_torques.md's, sun_safe.md's, magnetic_pointing.md's Floquet, worst-corner and
    tumble tables and attitude_modes.md's magnetorquer table with one figure changed by hand (for most, back to the
    figure the page quoted before it was generated): --check reports that block. STUDY-112: the same for sun_safe.md's
    spin-down tables and attitude_modes.md's shipped-sequence and orbit tables (the last seven cases)."""
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, name, block, old, new)
    assert len(problems) == 1 and f"block '{block}'" in problems[0]


def test_the_robust_rates_table_is_what_the_code_flies_now():
    """STUDY-011: robust_rates.md's table is rendered from a committed JSON file (12 flights, too long for the
    check); its first cell (the exact inertia, the default rate source: one 400 s plant-only flight) flies again
    and gives the committed figures to the float."""
    table = studies.SCRIPT_TABLES["robust_rates"]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))["plants"]["exact"]["default (blend)"]
    settle, median, p95 = script.fly(script.PLANTS["exact"], script.SOURCES["default (blend)"])
    assert {"settle_s": settle, "median_deg": median, "p95_deg": p95} == committed


def test_the_field_auto_table_is_what_the_code_flies_now():
    """STUDY-013: environment_torques.md's AUTO table is rendered from a committed JSON file (12 flights); its first
    flight (1.2 deg/s about the scenario's axis, dipole: one 3000 s plant-only flight) flies again and gives the
    committed record to the float."""
    table = studies.SCRIPT_TABLES["environment_torques"]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))["flights"][0]
    assert next(script.flights()) == committed


def test_the_robust_rates_campaign_is_what_the_code_flies_now():
    """STUDY-031: robust_rates.md's 100-run campaign table is rendered from its committed folder, which belongs to
    campaigns/adcs/robust_rates_plant.yaml; its first seed (one 330 s plant-only run) flies again and gives its
    committed row to the float."""
    assert studies.CAMPAIGNS["robust_rates_campaign"].problems(fly_probes=True) == []


def test_the_largest_moment_deviation_pairs_moments_by_their_axes():
    """STUDY-032: the campaign table's largest principal-moment deviation pairs each drawn moment with the nominal
    axis nearest its own, so a draw that reorders the moments (2.05e-3 × 1.08 > 2.15e-3 × 0.95) still reads 8 %."""
    import numpy as np

    nominal = [[2.20e-3, 2.0e-5, -1.5e-5], [2.0e-5, 2.15e-3, 1.0e-5], [-1.5e-5, 1.0e-5, 2.05e-3]]
    moments, axes = np.linalg.eigh(np.asarray(nominal))  # ascending: 2.05e-3's axis first
    scale = np.array([1.08, 0.95, 1.0])
    a = np.radians(15.0)
    k = np.array([1.0, 2.0, -1.0]) / np.sqrt(6.0)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    turn = np.eye(3) + np.sin(a) * kx + (1 - np.cos(a)) * kx @ kx
    v = turn @ axes
    drawn = v @ np.diag(moments * scale) @ v.T
    deviation = studies._largest_moment_deviation({"scenario.spacecraft.inertia_kg_m2": drawn.tolist()}, nominal)
    assert deviation == pytest.approx(0.08, rel=1e-9)


def test_the_published_convergence_figure_is_the_first_halving_under_the_rule():
    """STUDY-034: the convergence table's published figure (spec/control.md: < 0.5 % on halving) is the figure of the
    first halving from which every halving flown moves it by less, at that step; a halving under the rule followed by
    one over it publishes nothing (the listing form's 0.00125 s figure, +0.32 %, then +0.85 % at 0.000625 s)."""
    figures = [(0.01, 6000.0), (0.005, 6200.0), (0.0025, 6240.0), (0.00125, 6260.0), (0.000625, 6266.26)]
    assert studies._first_converged(figures) == (0.00125, 6260.0)
    assert studies._first_converged(figures[:3]) is None
    assert studies._first_converged([(0.01, 6612.0), (0.005, 6811.0), (0.0025, 6860.0), (0.00125, 6882.0),
                                     (0.000625, 6940.0)]) is None


def test_the_four_wheel_table_is_what_the_code_flies_now():
    """STUDY-033: environment_torques.md's four-wheel table is rendered from a committed JSON file; its first flight
    (K_DUMP default: one 1200 s plant-only flight) flies again and gives the committed record (the null-space
    momentum included) to the float."""
    table = studies.SCRIPT_TABLES["environment_four_wheels"]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))["flights"][0]
    assert json.loads(json.dumps(next(script.flights("four_wheels")))) == committed


def test_the_sun_safe_tables_are_what_the_code_flies_now():
    """STUDY-014: sun_safe.md's plant-only tables are rendered from committed JSON files (20 seed flights); the
    wheels table's seed 1 (one 5580 s plant-only flight) flies again and gives its committed row to the float."""
    from detumble.sim import sun_safe_check
    from detumble.sim.sun_sensors import SunSensorSpec

    table = next(t for t in studies.SUN_SAFE_TABLES if t.block == "sun_safe_wheels")
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["options"] == {"seeds": 5, "actuator": "ANY", "axis": "PLUS_Z", "duration": 5580.0, "rate": 2.0,
                                    "albedo": 0.0, "albedo_model": 0.0, "penumbra": False}
    again = sun_safe_check.table(1, rate_deg_s=2.0, duration_s=5580.0, actuator="ANY", axis="PLUS_Z",
                                 sensor_spec=SunSensorSpec(), albedo_model=0.0)
    assert json.loads(json.dumps(again["rows"][0])) == committed["rows"][0]


def test_the_deployment_albedo_table_is_what_the_deployment_flies_now(tmp_path):
    """STUDY-015: sun_safe.md's deployment albedo table is rendered from a committed JSON file (3 adcs_ref flights of
    5580 s); the albedo-0.3 flight's first 120 s (one deployment run of seconds) flies again and its corrected
    sunlit readings' errors are the committed probe's to 1e-9 deg."""
    table = next(t for t in studies.SUN_SAFE_TABLES if t.block == "sun_safe_albedo_deployment")
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["duration"] == 5580.0 and committed["rows"][0]["albedo"] == 0.3
    script = studies._load_script(table.script)
    script.fly(0.3, 120.0, tmp_path / "run")
    again = script.figures(tmp_path / "run")["corrected_errors"]
    probe = committed["probe"]
    assert len(probe) == script.PROBE_READINGS and len(again) >= len(probe)
    assert [round(e, 9) for e in again[:len(probe)]] == probe


@pytest.mark.parametrize("kind", ["command", "operator", "hand_back"])
def test_the_coil_tables_through_adcs_ref_are_what_the_deployment_flies_now(tmp_path, kind):
    """STUDY-060: sun_safe.md's coil tables through adcs_ref (by ground command at 2 °/s, the operator procedure and
    the automatic hand-back at 1.9 °/s) are rendered from committed JSON files of whole-orbit adcs_ref flights; seed
    1's first 120 s of each kind (one deployment run of seconds) flies again and its true Sun-pointing error, once a
    second, is the committed probe's to 1e-9 deg."""
    table = next(t for t in studies.SUN_SAFE_TABLES if t.block == f"sun_safe_coil_{kind}")
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    script = studies._load_script(table.script)
    seq, rate, extra, seeds = script.KINDS[kind]
    assert committed["duration"] == 5580.0 and committed["kind"] == kind and committed["sequence"] == seq
    assert committed["rate_deg_s"] == rate and committed["settings"] == list(extra)
    assert [r["seed"] for r in committed["rows"]] == list(range(1, seeds + 1))
    script.fly(kind, 1, 120.0, tmp_path / "run")
    again = script.figures(tmp_path / "run")["probe"]
    assert len(committed["probe"]) == script.PROBE_S and again == committed["probe"]


def test_the_spin_down_geometry_table_is_what_the_orbit_gives_now():
    """STUDY-061: sun_safe.md's field-geometry table (where along the orbit the field is across the Sun line) is the
    committed JSON, and that file is what one pass over the adcs scenario's orbit gives now (~1 s)."""
    from detumble.sim import spin_down_geometry as geo

    table = next(t for t in studies.SUN_SAFE_TABLES if t.block == "sun_safe_spin_down_geometry")
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    again = geo.table(geo.geometry("adcs"), [60.0, 70.0, 75.0, 80.0, 85.0], [520.0, 570.0, 1958.0, 2124.0, 2714.0],
                      "adcs")
    assert json.loads(json.dumps(again)) == committed


def test_the_albedo_mismatch_table_refuses_a_file_of_other_options(tmp_path, monkeypatch):
    """STUDY-016: the mismatch table's rows come from files made with their own albedo and model 0.3: a file made
    with another albedo in the sensors is refused, a missing one names its command."""
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path)
    (tmp_path / "sun_safe").mkdir()
    for _, results, _ in studies.SUN_SAFE_MISMATCH:
        shutil.copy(ROOT / "docs" / "studies" / results, tmp_path / results)
    assert "| 0.4 |" in studies.sun_safe_mismatch_block()["sun_safe_albedo_mismatch"]
    wrong = tmp_path / "sun_safe" / "albedo_model_truth_04.json"
    data = json.loads(wrong.read_text(encoding="utf-8"))
    wrong.write_text(json.dumps(dict(data, options=dict(data["options"], albedo=0.3))), encoding="utf-8")
    with pytest.raises(studies.StudyError, match="was not made by .*--albedo 0.4"):
        studies.sun_safe_mismatch_block()
    wrong.unlink()
    with pytest.raises(studies.StudyError, match="is not committed: make it with .*--albedo 0.4"):
        studies.sun_safe_mismatch_block()
def _mag_table(block: str):
    table = next(t for t in studies.MAG_POINTING_TABLES if t.block == block)
    return studies._load_script(table.script), json.loads(table.path.read_text(encoding="utf-8"))


def test_the_magnetic_pointing_floquet_table_is_what_the_code_computes_now():
    """STUDY-035: magnetic_pointing.md's gain table (Floquet rates) is rendered from a committed JSON file; its chosen
    row (K_P 4e-6, K_D 4e-4, ρ 2, ζ 1) is computed again in both fields and at the three biases (≈ 3 CPU-s) and
    gives the committed rates to the float."""
    script, committed = _mag_table("magnetic_pointing_floquet")
    row = next(r for r in committed["rows"] if r["note"] == "chosen")
    assert {f: script.floquet_row(f, row["k_p"], row["k_d"], row["rho"], row["zeta"]) for f in script.FIELDS} \
        == row["rates"]


def test_the_floquet_convergence_table_is_what_the_code_computes_now():
    """STUDY-150: magnetic_pointing.md's convergence table of the Floquet maps is rendered from a committed JSON file
    made with the maps' present sample count (FLOQUET_SAMPLES, so the block cannot vouch for a count it did not
    test); its row at that count in the tilted dipole is computed again (≈ 2 CPU-s) and gives the committed rates to
    the float, and the block says the rule is met there."""
    script, committed = _mag_table("magnetic_pointing_floquet_convergence")
    assert committed["chosen_samples"] == script.FLOQUET_SAMPLES
    row = next(r for r in committed["rows"] if r["samples"] == script.FLOQUET_SAMPLES and r["substeps"] == 1)
    kp, kd, rho, zeta = committed["gains"]
    assert script.floquet_row("dipole", kp, kd, rho, zeta, samples=script.FLOQUET_SAMPLES) == row["rates"]["dipole"]
    assert f"from {script.FLOQUET_SAMPLES} to {2 * script.FLOQUET_SAMPLES} samples: **met**" in \
        script.convergence_markdown(committed)


def test_the_magnetic_pointing_plant_tables_are_what_the_code_flies_now():
    """STUDY-036: magnetic_pointing.md's plant checks are rendered from committed JSON files (≈ 400 one-orbit plant
    flights); the worst corner's chosen row, draw 1, in both fields, and seed 003's PD in the dipole (four plant
    flights, a few CPU-s) fly again and give the committed figures to the float."""
    script, corner = _mag_table("magnetic_pointing_corner_dipole")
    _, corner_igrf = _mag_table("magnetic_pointing_corner_igrf14")
    for table in (corner, corner_igrf):
        row = table["rows"][6]
        assert row["params"] == [4e-6, 4e-4, 2.0, 1.0, 30.0, 0.8, 0.8]  # the chosen gains, the 30 s settle
        assert list(script.corner_run(table["field"], tuple(row["params"]), 1)) == row["runs"][0]
    _, checks = _mag_table("magnetic_pointing_checks")
    from detumble.sim.magnetic_pointing_check import fly

    again = fly("seed_pd", 2.0e-6, 4.0e-4, seed=1, dt_s=0.1, settings=script.FIELDS["dipole"]).stats()
    assert list(again) == checks["seed_pd"]["dipole"]


@pytest.mark.slow
def test_the_magnetic_pointing_hold_run_is_what_the_deployment_flies_now(tmp_path):
    """STUDY-037 (`slow`: one orbit of adcs_ref, about a CPU-minute): the attitude-hold run of the committed
    magnetic_pointing/deployment.json (present defaults, at rest on the target) flies again and gives its committed
    figures to the float."""
    script, committed = _mag_table("magnetic_pointing_hold_runs")
    assert script.fly("hold", tmp_path) == committed["runs"]["hold"]


@pytest.mark.slow
def test_the_wheel_orbit_run_is_what_the_deployment_flies_now(tmp_path):
    """STUDY-045 (`slow`: one orbit of adcs_ref, about a CPU-minute): attitude_knowledge.md's orbit table is rendered
    from a committed JSON file (three runs of an orbit or more); its orbit run (one 5580 s deployment run) flies again
    and gives its committed figures to the float."""
    table = studies.SCRIPT_TABLES["attitude_knowledge_orbit_runs"]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))["runs"]["orbit"]
    assert json.loads(json.dumps(script.fly("orbit", tmp_path))) == committed


@pytest.mark.slow
def test_the_magnetic_pointing_corner_run_is_what_the_deployment_flies_now(tmp_path):
    """STUDY-046 (`slow`: one orbit of adcs_ref, about a CPU-minute): magnetic_pointing.md's worst-corner run with the
    on-board residual-dipole estimate (test ADCS-064's start, committed in magnetic_pointing/deployment.json) flies
    again and gives its committed figures, the estimate included, to the float."""
    script, committed = _mag_table("magnetic_pointing_corner_runs")
    assert json.loads(json.dumps(script.fly("corner", tmp_path))) == committed["runs"]["corner"]


def test_the_wheels_sensor_table_is_what_the_deployment_flies_now(tmp_path):
    """STUDY-038: attitude_modes.md's sensor table is rendered from a committed JSON file (four 300 s adcs_ref runs);
    its first row (the scenario's sensors: one 300 s deployment run, a few CPU-s) flies again and gives the committed
    figures to the float."""
    table = studies.SCRIPT_TABLES["attitude_modes_sensors"]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))["rows"]["as in the scenario"]
    assert script.fly("as in the scenario", tmp_path) == committed


def _nudged_script_table(tmp_path, monkeypatch, table, nudge) -> None:
    """Point ``studies`` at a copy of ``table``'s committed JSON file changed by ``nudge(data)`` (in place)."""
    data = json.loads(table.path.read_text(encoding="utf-8"))
    nudge(data)
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path)
    (tmp_path / table.results).parent.mkdir(parents=True, exist_ok=True)
    (tmp_path / table.results).write_text(json.dumps(data), encoding="utf-8")


def test_the_closed_form_figures_are_what_the_code_computes_now(tmp_path, monkeypatch):
    """STUDY-040: environment_torques.md's closed-form blocks (nadir torques, drag and solar pressure, the coil law's
    Floquet margin to the magnetometer bias, the IGRF table's accuracy) are rendered from a committed JSON file; its
    --check probe computes every figure again (about 8 CPU-s) and finds the committed ones to the float; a copy
    whose Floquet rate at 1.75 × the bias is nudged by 1e-12 /s is reported, through --check."""
    assert studies.check(["environment_closed_form"], fly_probes=True) == []
    table = studies.ENV_CLOSED_FORM_TABLES[0]

    def nudge(data):
        data["floquet_bias"]["rates"]["igrf14"][4] += 1e-12

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "floquet_bias" in problems[0] and "no longer computes" in problems[0]


def test_the_single_run_design_table_is_what_the_deployment_flies_now(tmp_path, monkeypatch):
    """STUDY-041: attitude_knowledge.md's two single-run tables are rendered from a committed JSON file (fifteen 400 s
    adcs_ref runs, re-flown in IGRF-14); the probe flies the default design's row again (one 400 s deployment run, a
    few CPU-s) and finds its committed figures to the float; a copy whose steady median is nudged is reported."""
    table = studies.KNOWLEDGE_SINGLE_TABLES[0]
    assert table.run_probe() == []
    script = studies._load_script(table.script)

    def nudge(data):
        data["design"][script.PROBE_ROW]["median_deg"] += 1e-9

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "median_deg" in problems[0]


def test_the_gravity_gradient_floor_is_what_the_code_computes_now(tmp_path, monkeypatch):
    """STUDY-042: magnetic_pointing.md's gravity-gradient floor is rendered from a committed JSON file; its probe (run
    by --check with the magnetic_pointing study) computes the closed form again in both fields and finds the committed
    figures to the float; a copy holding the tilted dipole's figures under IGRF-14 (what the page quoted before the
    field changed) is reported."""
    table = next(t for t in studies.MAG_POINTING_TABLES if t.block == "magnetic_pointing_floor")
    assert table.run_probe() == []

    def nudge(data):
        data["closed_form"]["igrf14"] = data["closed_form"]["dipole"]

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "IGRF-14" in problems[0]


def test_the_floquet_figure_is_drawn_from_maps_the_code_computes_now(tmp_path, monkeypatch):
    """STUDY-044: magnetic_pointing.md's Floquet figure and the figures quoted from it come from committed maps
    (campaigns/adcs/magnetic_pointing_figures.py --json, the scenario's field); the probe computes the field line and
    the old gains' rate again and finds them to the float; maps of the tilted dipole (the field of the figure's first
    version) are reported; regenerating draws the figure from the committed maps (quick: into a scratch folder)."""
    table = studies.FLOQUET_MAPS
    assert table.run_probe() == []
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["field_model"] == "igrf14"
    ctx = studies.Context(quick=True, out=tmp_path / "quick")
    studies.regenerate_floquet_figure(ctx)
    assert (tmp_path / "quick" / "docs" / "img" / "magnetic_pointing" / "floquet.png").stat().st_size > 10_000
    script = table.code()
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    dipole = Plant(load_scenario("adcs", settings=["field.model=dipole"]))
    _, period, b, bd = script.field_line(dipole)
    inertia = dipole.scenario.spacecraft.inertia_kg_m2

    def nudge(data):
        data["old_gains_rate"] = float(script.floquet_rate("seed_pd", period, b, bd, inertia, *script.OLD_GAINS))

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "old_gains_rate" in problems[0]


def test_the_hold_campaign_folder_belongs_to_its_campaign_file():
    """STUDY-043: the hold campaign flown again with today's code (docs/studies/magnetic_pointing_hold/campaign/,
    complete or stopped) belongs to campaigns/adcs/hold_magnetorquers.yaml as it is now (hash, run ids, the resolved
    scenario and field model: IGRF-14); its block says how many of the 100 runs were flown."""
    campaign = studies.CAMPAIGNS["magnetic_pointing_hold_campaign"]
    if not (campaign.path / "results.parquet").exists():
        pytest.skip("docs/studies/magnetic_pointing_hold/campaign not committed")
    assert campaign.problems(fly_probes=False) == []
    manifest = json.loads((campaign.path / "manifest.json").read_text(encoding="utf-8"))
    assert [v["field_model"] for v in manifest["resolved"].values()] == ["igrf14"]
    block = studies.magnetic_hold_campaign_blocks()["magnetic_pointing_hold_campaign"]
    flown = len(campaign.results())
    assert (f"of {flown} runs ok" in block) and (flown == 100 or f"stopped after {flown} of 100 runs" in block)


def test_a_script_table_of_a_quick_run_is_refused(tmp_path, monkeypatch):
    """STUDY-012: a JSON file written by a script's --quick (300 s flights) cannot stand for the page's table."""
    table = studies.SCRIPT_TABLES["robust_rates"]
    data = json.loads(table.path.read_text(encoding="utf-8"))
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path)
    (tmp_path / "robust_rates").mkdir()
    (tmp_path / table.results).write_text(json.dumps(dict(data, quick=True)), encoding="utf-8")
    with pytest.raises(studies.StudyError, match="--quick"):
        table.blocks()
    (tmp_path / table.results).unlink()
    with pytest.raises(studies.StudyError, match="is not committed: make it with `python campaigns/adcs/robust"):
        table.blocks()


def test_spin_campaign_folders_belong_to_their_campaign_files():
    """STUDY-002 (no probe: a spin run is a deployment run of minutes)."""
    for key in ("spin_minor_axis", "spin_major_axis"):
        assert studies.CAMPAIGNS[key].problems(fly_probes=False) == []


def test_a_folder_flown_under_another_default_field_model_is_stale(tmp_path, monkeypatch):
    """STUDY-017: a committed spin folder whose manifest records what adcs_ref's default scenario resolved to with the
    tilted dipole (as before merge cb777e1, the campaign file and run ids unchanged) is stale now that the scenario
    flies IGRF-14, with a message naming the change and the re-fly command; the same manifest recording today's
    resolution is not stale; one recording nothing is not stale either, but reported as unknown."""
    import re
    import tempfile

    from detumble.sim import scenario as scenario_module
    from fprime_lite.tools.campaign.manifest import resolved_configuration
    from fprime_lite.tools.campaign.plan import plan_runs

    original = studies.CAMPAIGNS["spin_minor_axis"]
    folder = tmp_path / "docs" / "studies" / "spin"
    folder.mkdir(parents=True)
    shutil.copy(original.path / "results.parquet", folder)
    manifest = json.loads((original.path / "manifest.json").read_text(encoding="utf-8"))
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path / "docs" / "studies")
    moved = dataclasses.replace(original, folder="spin")
    with tempfile.TemporaryDirectory() as scratch:
        tasks = plan_runs(moved.campaign(), pathlib.Path(scratch))
    real = scenario_module.resolve_scenario

    def dipole(name):
        label, text = real(name)
        return label, re.sub(r"\n  model: igrf14[^\n]*\n  table_step_s:[^\n]*\n", "\n  model: dipole\n", text)

    with monkeypatch.context() as m:
        m.setattr(scenario_module, "resolve_scenario", dipole)
        then = resolved_configuration(tasks)
    now = resolved_configuration(tasks)
    assert [v["field_model"] for v in then.values()] == ["dipole"] and [v["field_model"] for v in now.values()] == [
        "igrf14"]

    def problems_with(resolved):
        recorded = {k: v for k, v in manifest.items() if k not in ("resolved", "resolution_confirmed")}
        if resolved is not None:
            recorded["resolved"] = resolved
        (folder / "manifest.json").write_text(json.dumps(recorded), encoding="utf-8")
        return moved.problems(fly_probes=False)

    stale = problems_with(then)
    assert len(stale) == 1, stale
    assert "field model dipole → igrf14" in stale[0] and "sections changed: field" in stale[0]
    assert ("`nice -n 10 fprime-lite campaign campaigns/adcs/spin_minor_axis.yaml --workers 1 --out docs/studies/spin`"
            in stale[0])
    assert problems_with(now) == [] and moved.resolution_unknown() is None
    assert problems_with(None) == [] and "records no resolved configuration" in moved.resolution_unknown()


def test_a_hand_edited_number_in_a_block_is_reported(tmp_path, monkeypatch):
    """STUDY-003: change one digit of the convergence table in a copy of the doc: --check reports it."""
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "coursework_convergence", "coursework_convergence",
                                       "**", "**9")
    assert len(problems) == 1 and "block 'coursework_convergence'" in problems[0]


def test_a_committed_metric_the_code_no_longer_computes_is_reported(tmp_path, monkeypatch):
    """STUDY-004: a committed wheel-law settling time nudged by 0.001 s: the re-flown probe disagrees."""
    import pandas as pd

    original = studies.CAMPAIGNS["coursework_convergence"]
    folder = tmp_path / "docs" / "studies" / "cc"
    shutil.copytree(original.path, folder)
    df = pd.read_parquet(folder / "results.parquet")
    row = df.index[(df["law"] == "wheels_pd") & (df["scenario.dynamics_step_s"] == 0.01)
                   & (df["scenario.control.wheels_pd.error"] == "shortest_path")
                   & df["scenario.control.wheels_pd.k_d"].isna()][0]
    df.loc[row, "settling_time_2pct_s"] += 0.001
    df.to_parquet(folder / "results.parquet")
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path / "docs" / "studies")
    nudged = dataclasses.replace(original, folder="cc",
                                 probe=lambda t: t["run_id"] == df.loc[row, "run_id"])
    problems = nudged.problems(fly_probes=True)
    assert len(problems) == 1 and "settling_time_2pct_s" in problems[0] and "no longer computes" in problems[0]


def test_the_replica_table_refuses_a_figure_read_off_solver_steps(tmp_path, monkeypatch):
    """STUDY-008: magnetorquer1's replica figures are of the dense output; a committed run made with --sample 0
    (read off the accepted steps, the artefact issue 28 names) is refused, not tabulated."""
    folder = tmp_path / "coursework_replica"
    shutil.copytree(studies._MT1_DIR, folder)
    path = folder / "magnetorquer1_ode45.json"
    run = json.loads(path.read_text(encoding="utf-8"))
    path.write_text(json.dumps({**run, "sample_s": 0.0}), encoding="utf-8")
    monkeypatch.setattr(studies, "_MT1_DIR", folder)
    with pytest.raises(studies.StudyError, match="read off the solver's steps"):
        studies.magnetorquer1_blocks()


def test_the_beta_pd_settling_time_is_the_falling_edge_of_its_last_ripple_peak():
    """STUDY-054: in every committed settling_ripple run (docs/studies/coursework_settling_ripple/) the β-PD's 2 %
    settling time is the convergence campaigns' figure for that form at that step (the same flight), its slow axis's
    lies on the falling edge of its last ripple peak above the band (after it, before the next peak, which is under
    the band), and the envelope figure is where the line through those two peaks crosses the band."""
    pytest.importorskip("pandas")
    df = studies._convergence_results()
    beta = df[df["law"] == "beta_pd"]
    files = sorted(studies._RIPPLE_DIR.glob("*.json"))
    assert files
    for path in files:
        out = json.loads(path.read_text(encoding="utf-8"))
        assert path.name.startswith("switched_" if out["switched"] else "listing_")
        a = out["axes"][studies._slow_axis(out)]
        assert a["settling_s"] == out["settling_s"]
        (ta, ha), (tb, hb) = [(p["t_s"], p["height_over_band"]) for p in a["peaks"][-2:]]
        assert ha > 1.0 >= hb, path.name
        assert ta < a["settling_s"] < tb, path.name
        assert a["envelope_settling_s"] == pytest.approx(ta + (ha - 1.0) / (ha - hb) * (tb - ta), abs=1e-6)
        rows = beta[(beta["scenario.control.beta_pd.switched"].astype(bool) == out["switched"])
                    & (beta["scenario.dynamics_step_s"] == out["step_s"])]
        assert len(rows) >= 1 and all(v == pytest.approx(out["settling_s"], abs=1e-9)
                                      for v in rows["settling_time_2pct_s"]), path.name


def test_a_missing_block_marker_is_a_clear_error():
    """Rewriting a block the document does not have says which and how to add it."""
    with pytest.raises(studies.StudyError, match="no block nowhere"):
        studies.replace_blocks("text\n", {"nowhere": "x"}, "doc.md")


def test_unknown_study_names_a_close_one(capsys):
    assert studies.main(["--only", "coursework_convergenc", "--check"]) == 2
    assert "did you mean coursework_convergence" in capsys.readouterr().err


def test_the_robust_rates_tail_table_is_what_the_code_flies_now():
    """STUDY-070: robust_rates.md's tail table is rendered from a committed JSON file (400 flights); the first draw's
    default variant (one 330 s plant-only flight) flies again and gives the committed figures to the float."""
    pd = pytest.importorskip("pandas")

    table = studies.SCRIPT_TABLES["robust_rates_tail"]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))["runs"][0]
    row = pd.read_parquet(script.CAMPAIGN).set_index("seed_index").loc[committed["seed_index"]]
    flown = script.fly(json.loads(row["requested"]), int(row["seed"]), script.VARIANTS[script.DEFAULT])
    assert flown == committed["variants"][script.DEFAULT]


def test_the_window_campaign_comparison_is_checked_and_needs_the_same_draws(tmp_path, monkeypatch):
    """STUDY-071: robust_rates.md's INTEGRAL_WINDOW 0.1° campaign block: its run-by-run comparison with the default
    campaign edited by hand is reported by --check; a default campaign with another run's seed is refused (the
    comparison pairs the same draws)."""
    pytest.importorskip("pandas")
    block = studies.doc_blocks(studies._ROBUST_DOC.read_text(encoding="utf-8"))["robust_rates_window_campaign"]
    count = block.split("p95 ≤ 0.05° in ")[1].split(" of ")[0]  # "45 → 97"
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "robust_rates_window_campaign",
                                       "robust_rates_window_campaign", count, count.replace("→", "->"))
    assert len(problems) == 1 and "block 'robust_rates_window_campaign'" in problems[0]
    _campaigns_with_a_foreign_seed(tmp_path, monkeypatch, "robust_rates_campaign", ("robust_rates_window_campaign",))
    with pytest.raises(studies.StudyError, match="draws"):
        studies.robust_rates_window_campaign_blocks()


def _campaigns_with_a_foreign_seed(tmp_path, monkeypatch, foreign: str, copies: tuple[str, ...]) -> None:
    """STUDIES_DIR moved to a copy holding committed campaign ``foreign`` with its first run's seed changed and the
    campaigns ``copies`` as committed."""
    base = studies.CAMPAIGNS[foreign]
    df = base.results().copy()
    df.loc[df.index[0], "seed"] = int(df["seed"].max()) + 1
    folder = tmp_path / "docs" / "studies" / base.folder
    folder.mkdir(parents=True)
    df.to_parquet(folder / "results.parquet")
    for key in copies:
        shutil.copytree(studies.CAMPAIGNS[key].path, tmp_path / "docs" / "studies" / studies.CAMPAIGNS[key].folder)
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path / "docs" / "studies")



def test_the_rate_gate_campaign_block_is_checked_and_pairs_the_same_draws(tmp_path, monkeypatch):
    """STUDY-120: robust_rates.md's INTEGRAL_RATE_GATE campaign block: its run-by-run comparison with the 0.1° window's
    campaign edited by hand is reported by --check; a window campaign with another run's seed is refused (the
    comparison pairs the same draws)."""
    pytest.importorskip("pandas")
    block = studies.doc_blocks(studies._ROBUST_DOC.read_text(encoding="utf-8"))["robust_rates_gate_campaign"]
    count = block.split("p95 ≤ 0.05° in ")[2].split(" of ")[0]  # against the window's: "97 → 97"
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "robust_rates_gate_campaign",
                                       "robust_rates_gate_campaign", f"in {count} of",
                                       f"in {count.split(' → ')[0]} → 98 of")
    assert len(problems) == 1 and "block 'robust_rates_gate_campaign'" in problems[0]
    _campaigns_with_a_foreign_seed(tmp_path, monkeypatch, "robust_rates_window_campaign",
                                   ("robust_rates_campaign", "robust_rates_gate_campaign"))
    with pytest.raises(studies.StudyError, match="draws of robust_rates/campaign_window"):
        studies.robust_rates_gate_campaign_blocks()



def test_the_residual_dipole_campaign_block_is_checked_and_pairs_the_same_draws(tmp_path, monkeypatch):
    """STUDY-170: robust_rates.md's RATE_OBSERVER_DIPOLE_TIME campaign block: its run-by-run comparison with the gate
    campaign edited by hand (the count of runs meeting 0.05°) is reported by --check; a gate campaign with another
    run's seed is refused (the comparison pairs the same draws)."""
    pytest.importorskip("pandas")
    block = studies.doc_blocks(studies._ROBUST_DOC.read_text(encoding="utf-8"))["robust_rates_dipole_campaign"]
    count = block.split("≤ 0.05° in ")[1].split(" of ")[0]  # the honest-window p95: "97 → 100"
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "robust_rates_dipole_campaign",
                                       "robust_rates_dipole_campaign", f"in {count} of",
                                       f"in {count.split(' → ')[0]} → 99 of")
    assert len(problems) == 1 and "block 'robust_rates_dipole_campaign'" in problems[0]
    _campaigns_with_a_foreign_seed(tmp_path, monkeypatch, "robust_rates_gate_campaign",
                                   ("robust_rates_dipole_campaign",))
    with pytest.raises(studies.StudyError, match="draws of robust_rates/campaign_gate"):
        studies.robust_rates_dipole_campaign_blocks()

def _copied_campaign(tmp_path, monkeypatch, key: str):
    """A copy of a committed campaign folder under tmp_path (STUDIES_DIR pointed there): the campaign, its
    manifest's path and the manifest as read."""
    original = studies.CAMPAIGNS[key]
    shutil.copytree(original.path, tmp_path / original.folder)
    monkeypatch.setattr(studies, "STUDIES_DIR", tmp_path)
    campaign = dataclasses.replace(original)
    manifest_path = campaign.path / "manifest.json"
    return campaign, manifest_path, json.loads(manifest_path.read_text(encoding="utf-8"))


def test_a_changed_resolution_is_confirmed_only_by_flights_that_agree(tmp_path, monkeypatch):
    """STUDY-080: a committed campaign whose resolved configuration changed is stale; `--confirm-resolution`
    re-flies its probe run with today's configuration and, when the metrics agree to the float, records the
    new configuration in the manifest (then it is no longer stale, and the original `resolved` is kept); when
    a committed metric disagrees, nothing is recorded and it stays stale."""
    pytest.importorskip("pandas")
    import pandas as pd

    campaign, manifest_path, manifest = _copied_campaign(tmp_path, monkeypatch, "robust_rates_campaign")
    manifest.pop("resolution_confirmed", None)  # as flown: one resolution, today's or not
    from fprime_lite.tools.campaign.manifest import resolved_configuration
    from fprime_lite.tools.campaign.plan import plan_runs

    today = resolved_configuration(plan_runs(campaign.campaign(), tmp_path / "plan"))
    key = next(iter(manifest["resolved"]))
    manifest["resolved"][key] = dict(manifest["resolved"][key], sha256="0" * 64,
                                     sections=dict(manifest["resolved"][key]["sections"], control="0" * 16))
    manifest_path.write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    assert any("scenario sections changed: control" in p for p in campaign.problems(fly_probes=False))

    # a committed metric the flight no longer gives: not confirmed, the manifest untouched
    df = pd.read_parquet(campaign.path / "results.parquet")
    good = df.copy()
    probe_row = df.index[df["seed_index"] == 0][0]
    df.loc[probe_row, "slew_settle_s"] = float(df.loc[probe_row, "slew_settle_s"]) + 0.5
    df.to_parquet(campaign.path / "results.parquet")
    before = manifest_path.read_bytes()
    problems = campaign.confirm_resolution()
    assert len(problems) == 1 and "slew_settle_s" in problems[0]
    assert manifest_path.read_bytes() == before

    # the committed rows as flown: confirmed and recorded; the original resolution stays as it was
    good.to_parquet(campaign.path / "results.parquet")
    assert campaign.confirm_resolution() == []
    after = json.loads(manifest_path.read_text(encoding="utf-8"))
    (entry,) = after["resolution_confirmed"]
    assert entry["resolved"] == today and entry["runs"] == [df.loc[probe_row, "run_id"]]
    assert after["resolved"][key]["sha256"] == "0" * 64
    assert campaign.problems(fly_probes=False) == []


def _sun_table(block: str):
    return next(t for t in studies.SUN_SAFE_TABLES if t.block == block)


def test_the_spin_down_table_is_what_the_code_flies_now():
    """STUDY-110: sun_safe.md's plant-only spin-down table is rendered from a committed JSON file (5 one-orbit seed
    flights); `--check`'s probe flies seed 1 again to the end of its first sunlit part (one 2810 s plant-only flight)
    and its figures there are the committed row's to the float; with one committed figure nudged by 1e-9° the same
    flight is reported, naming the figure."""
    from detumble.sim import sun_safe_check

    table = _sun_table("sun_safe_spin_down")
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["options"]["spin_down"] and committed["options"]["seeds"] == 5
    assert [r["seed"] for r in committed["rows"]] == [1, 2, 3, 4, 5]
    row = sun_safe_check.spin_down_probe_row(committed)
    assert sun_safe_check.spin_down_compare(row, committed) == []
    tampered = json.loads(json.dumps(committed))
    tampered["rows"][0]["after_deg"]["max"] += 1e-9
    found = sun_safe_check.spin_down_compare(row, tampered)
    assert len(found) == 1 and "after_deg" in found[0]


def test_the_spin_down_variants_fly_the_spin_down_table_at_the_defaults():
    """STUDY-111: the spin-down variants' file (51 plant-only flights, four tables of sun_safe.md) holds every variant
    as its script defines it, and its default variant's seeds 1–3 are the plant-only spin-down table's rows to the
    float (two scripts, one flight); a variant flown with other parameters is refused by name, not rendered."""
    variants = _sun_table("sun_safe_spin_down_gate")
    script = studies._load_script(variants.script)
    table = json.loads(variants.path.read_text(encoding="utf-8"))
    assert set(table["variants"]) == set(script.VARIANTS)
    for key, (_, params, duration) in script.VARIANTS.items():
        assert table["variants"][key]["params"] == params and table["variants"][key]["duration_s"] == duration
    spin_down = json.loads(_sun_table("sun_safe_spin_down").path.read_text(encoding="utf-8"))
    assert table["variants"]["default"]["rows"] == spin_down["rows"][:3]
    moved = json.loads(json.dumps(table))
    moved["variants"]["gate_70"]["params"]["SUN_HOLD_FIELD_ANGLE"] = 65.0
    with pytest.raises(ValueError, match="gate_70"):
        script.gate_markdown(moved)


def test_the_attitude_mode_flights_are_what_the_deployment_flies_now(tmp_path):
    """STUDY-113: attitude_modes.md's shipped-sequence and wheel-orbit tables and figures are rendered from a
    committed JSON file and traces (two adcs_ref flights of 6000 and 5580 s); `--check`'s probe flies the shipped
    flight's first 30 s again (one deployment run of seconds) and its attitude.csv rows are the committed ones to the
    float; with one committed pointing error nudged by 1e-12° it reports that row. The figures are drawn from the
    committed files alone (the four of the shipped flight)."""
    table = studies.ATTITUDE_RUNS_TABLES[0]
    script = studies._load_script(table.script)
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["flights"]["shipped"]["duration_s"] == 6000.0
    assert committed["flights"]["orbit"]["settings"] == ["initial.rate.magnitude_deg_s=0.5"]
    probe = committed["flights"]["shipped"]["probe"]
    assert probe[-1][0] == script.PROBE_S and len(probe) == 2 * script.PROBE_S + 1
    assert script.shipped_probe(committed) == []
    tampered = json.loads(json.dumps(committed))
    tampered["flights"]["shipped"]["probe"][20][2] += 1e-12
    found = script.shipped_probe(tampered)
    assert len(found) == 1 and "row 20" in found[0]
    drawn = script.draw(committed, table.path, "shipped", tmp_path)
    assert sorted(p.name for p in drawn) == ["attitude_mode.png", "dipole.png", "pointing_error.png",
                                             "wheel_momentum.png"]


def test_the_residual_dipole_ab_is_what_the_deployment_flies_now(tmp_path, monkeypatch):
    """STUDY-100: magnetic_pointing.md's residual-dipole A/B (four one-orbit adcs_ref runs, the compensation on and
    off from the same start and noise seed) is rendered from a committed JSON file; its probe flies the first 300 s
    of the compensated present-defaults run again (a few CPU-s) and finds the committed error series to the float;
    a copy with one sample of that series nudged is reported by the probe."""
    table = studies.SCRIPT_TABLES["magnetic_pointing_residual_ab"]
    assert table.run_probe() == []
    script = table.code()

    def nudge(data):
        data["runs"]["ab_present_on"]["series"]["error_deg"][3] += 1e-3

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "ab_present_on" in problems[0] and f"{script.PROBE_S:.0f} s" in problems[0]


def test_a_tampered_residual_ab_figure_is_reported_by_check(tmp_path, monkeypatch):
    """STUDY-101: --check compares the A/B block with what the committed JSON gives: a committed median changed in a
    copy of the JSON (the page left as it is) is reported as a stale block."""
    assert studies.check(["magnetic_pointing_residual_ab"], fly_probes=False) == []
    table = studies.SCRIPT_TABLES["magnetic_pointing_residual_ab"]

    def nudge(data):
        data["runs"]["ab_previous_off"]["median_deg"] += 0.01

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = studies.check(["magnetic_pointing_residual_ab"], fly_probes=False)
    assert len(problems) == 1 and "magnetic_pointing_residual_ab" in problems[0] and "not what" in problems[0]


def test_the_error_figure_is_drawn_from_series_the_deployment_flies_now(tmp_path, monkeypatch):
    """STUDY-102: the error-vs-time figure of the single deployment runs and the figures quoted from it come from the
    error series kept in docs/studies/magnetic_pointing/deployment.json; the runs' probe flies the first 300 s of the
    present defaults' tumble again and finds its series to the float; regenerating draws the figure (quick: into a
    scratch folder); a copy whose no-settle-wait series is changed inside its first 400 s is reported by --check (the
    block quoting it), and one whose tumble series is nudged by the probe."""
    table = next(t for t in studies.MAG_POINTING_TABLES if t.block == "magnetic_pointing_error_figure")
    assert table.run_probe() == []
    ctx = studies.Context(quick=True, out=tmp_path / "quick")
    studies.regenerate_magnetic_pointing_runs(ctx)
    assert (tmp_path / "quick" / "docs" / "img" / "magnetic_pointing" / "pointing_error_runs.png").stat().st_size \
        > 10_000

    def raise_peak(data):
        e = data["runs"]["tumble_first_no_wait"]["series"]["error_deg"]
        e[10] = max(e[:40]) + 5.0

    _nudged_script_table(tmp_path / "a", monkeypatch, table, raise_peak)
    problems = studies.check(["magnetic_pointing_runs"], fly_probes=False)
    assert len(problems) == 1 and "magnetic_pointing_error_figure" in problems[0]

    def nudge(data):
        data["runs"]["tumble"]["series"]["error_deg"][5] += 1e-3

    _nudged_script_table(tmp_path / "b", monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "tumble" in problems[0]


def test_a_folder_recording_no_resolution_is_confirmed_only_by_flights_that_agree(tmp_path, monkeypatch):
    """STUDY-090: a committed campaign folder whose manifest records no resolved configuration (UNKNOWN) is
    confirmed by `--confirm-resolution`: it re-flies the probe run, the last run and one run of every other run
    section (flight_bdot_noise: two topologies), and only when every metric agrees to the float appends a
    `resolution_confirmed` entry saying the folder had none before (then it is no longer UNKNOWN nor stale); when a
    committed metric of the run chosen for the other section disagrees, nothing is written and it stays UNKNOWN."""
    pytest.importorskip("pandas")
    import pandas as pd
    from fprime_lite.tools.campaign.manifest import resolved_configuration
    from fprime_lite.tools.campaign.plan import plan_runs

    original = studies.CAMPAIGNS["flight_bdot_noise"]
    campaign, manifest_path, manifest = _copied_campaign(tmp_path, monkeypatch, "flight_bdot_noise")
    for key in ("resolved", "resolution_confirmed"):  # as made before manifests recorded a resolution
        manifest.pop(key, None)
    manifest_path.write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    assert campaign.resolution_unknown() is not None

    tasks = plan_runs(campaign.campaign(), tmp_path / "plan")
    today = resolved_configuration(tasks)
    assert len(today) == 2  # the two topologies: each must be flown
    df = pd.read_parquet(campaign.path / "results.parquet")
    chosen = campaign.confirmation_tasks(df, tasks, unknown=True)
    probe_ids = [t["run_id"] for t in tasks if original.probe(t)]
    assert [t["run_id"] for t in campaign.confirmation_tasks(df, tasks)] == probe_ids
    ids = [t["run_id"] for t in chosen]
    assert set(probe_ids) <= set(ids) and tasks[-1]["run_id"] in ids and len(ids) == len(set(ids))
    assert set().union(*(resolved_configuration([t]) for t in chosen)) == set(today)
    other = next(t for t in chosen if t["config"]["topology"] != tasks[-1]["config"]["topology"]
                 and t["run_id"] not in probe_ids)

    # a committed metric the other section's run no longer gives: not confirmed, the manifest untouched
    good = df.copy()
    row = df.index[df["run_id"] == other["run_id"]][0]
    df.loc[row, "detumble_complete_s"] = float(df.loc[row, "detumble_complete_s"]) + 0.5
    df.to_parquet(campaign.path / "results.parquet")
    before = manifest_path.read_bytes()
    problems = campaign.confirm_resolution()
    assert len(problems) == 1 and other["run_id"] in problems[0] and "detumble_complete_s" in problems[0], problems
    assert manifest_path.read_bytes() == before and campaign.resolution_unknown() is not None

    # the committed rows as flown: confirmed, recorded as having had no resolution before
    good.to_parquet(campaign.path / "results.parquet")
    assert campaign.confirm_resolution() == []
    after = json.loads(manifest_path.read_text(encoding="utf-8"))
    (entry,) = after["resolution_confirmed"]
    assert entry["resolved"] == today and entry["runs"] == ids
    assert entry["how"].startswith("the manifest recorded no resolved configuration before")
    assert "resolved" not in after and campaign.resolution_unknown() is None
    assert campaign.problems(fly_probes=False) == []


def _hold_rows(pd, rows):
    """A campaign frame of (seed_index, seed, status, p95, median, acquisition, acquisition at 15°) rows."""
    return pd.DataFrame(rows, columns=["seed_index", "seed", "status", "pointing_p95_deg", "pointing_median_deg",
                                       "pointing_acquisition_s", "pointing_acquisition_15deg_s"])


def test_a_hold_candidate_campaign_is_paired_with_the_same_draws_and_counts_the_runs_that_never_acquire():
    """STUDY-130: magnetorquer_hold_after_acquisition.md's candidate campaigns: each draw is paired with the committed
    campaign's draw of the same seed index, the counts of p95 ≤ 15° before and after are the runs' own, a run whose
    error never stays below 30° (no p95) counts as never acquired and not as a pass, and a candidate run whose seed
    is not the committed draw's is refused (there is nothing to pair)."""
    pd = pytest.importorskip("pandas")
    script = studies._load_script(studies.HOLD_CANDIDATE_TABLES[0].script)
    nan = float("nan")
    base = _hold_rows(pd, [(0, 11, "ok", 16.0, 1.0, 500.0, 900.0), (1, 12, "ok", 9.0, 1.0, 300.0, 350.0),
                           (2, 13, "ok", 14.0, 1.1, 200.0, 400.0), (3, 14, "ok", 20.0, 1.2, 600.0, 1200.0)])
    new = _hold_rows(pd, [(0, 11, "ok", 8.0, 1.0, 700.0, 760.0), (1, 12, "ok", nan, nan, nan, nan),
                          (2, 13, "ok", 15.5, 1.1, 200.0, 500.0)])
    text = script.campaign_markdown(base, new, "X")
    assert "p95 ≤ 15° in **2/3** as committed, **1/3** with X" in text
    assert "median ≤ 5° in 2/3" in text and "to the orbit's end): 1." in text
    assert "| 1 | 9.0 → never acquired |" in text and "| 0 | 16.0 → 8.0 |" in text
    assert "| 400 → 60 |" in text  # draw 0's tail: 900 − 500 as committed, 760 − 700 flown
    new.loc[0, "seed"] = 99
    with pytest.raises(ValueError, match="not the committed campaign's draws"):
        script.campaign_markdown(base, new, "X")


def test_the_hold_candidates_draw_table_counts_the_misses_met_and_the_runs_never_acquired():
    """STUDY-131: the re-flown draws' table: per case the misses meeting p95 ≤ 15° (a run without a p95 is not one),
    the passes kept, and the runs that never acquire; the tail is the flown run's acquisition at 15° minus at 30°."""
    script = studies._load_script(studies.HOLD_CANDIDATE_TABLES[0].script)
    miss, passed = script.MISSES, script.PASSES

    def run(row, p95, a30, a15):
        return {"row": row, "seed": 1, "median": None if p95 is None else 1.0, "p95": p95, "acquisition_s": a30,
                "acquisition_15deg_s": a15,
                "committed": {"median": 1.0, "p95": 18.0, "acquisition_s": 500.0, "acquisition_15deg_s": 1100.0}}

    table = {"draws": {"cases": [{"key": "k", "label": "L", "settings": [], "runs": [
        run(miss[0], 10.0, 400.0, 455.0), run(miss[1], 15.2, 400.0, 800.0), run(miss[2], None, None, None),
        run(passed[0], 7.0, 100.0, 150.0), run(passed[1], None, None, None)]}]}}
    text = script.draws_markdown(table)
    assert "- L: p95 ≤ 15° in **1 of 3** misses; of 2 that passed, 1 still pass; 2 of 5 never acquire" in text
    assert f"| L | {miss[0]} | 10.0 / 18.0 | 1.00 / 1.00 | 400 / 500 | 55 / 600 |" in text
    assert f"| L | {miss[2]} | never acquired / 18.0 |" in text


def test_the_hold_candidates_draw_table_counts_draws_beyond_the_misses_and_passes():
    """STUDY-220: a case flown on draws that are neither the six misses nor the four passes (the all-angle scheduled
    hold's spin-ups, re-flown at 40°) names them and counts those meeting the p95; a case without passes says
    nothing of passes kept."""
    script = studies._load_script(studies.HOLD_CANDIDATE_TABLES[0].script)
    miss = script.MISSES
    others = [r for r in range(100) if r not in miss and r not in script.PASSES][:3]

    def run(row, p95):
        return {"row": row, "seed": 1, "median": None if p95 is None else 1.0, "p95": p95, "acquisition_s": 100.0,
                "acquisition_15deg_s": 150.0,
                "committed": {"median": 1.0, "p95": 18.0, "acquisition_s": 500.0, "acquisition_15deg_s": 1100.0}}

    table = {"draws": {"cases": [{"key": "k", "label": "L", "settings": [], "runs": [
        run(miss[0], 10.0), run(others[0], 14.0), run(others[1], 15.5), run(others[2], None)]}]}}
    text = script.draws_markdown(table)
    assert (f"- L: p95 ≤ 15° in **1 of 1** misses; of the 3 draws {others[0]}, {others[1]}, {others[2]}, 1 meet the "
            "p95; 1 of 4 never acquire") in text
    assert "that passed" not in text



def _margin_script():
    return studies._load_script("campaigns/adcs/magnetorquer_hold_candidates.py")


def test_the_hold_margin_screen_draws_the_near_misses_then_seeded_passes_only():
    """STUDY-221: the margin screen's draws are each plant's near-misses, then MARGIN_RANDOM draws whose committed
    p95 is at most 15° (never a miss, a near-miss or a run that never acquired), the same for the same seed and
    others for another seed."""
    script = _margin_script()
    p95 = {plant: {i: (20.0 if i % 3 == 0 else None if i % 7 == 0 else float("nan") if i % 11 == 0
                       else 15.0 if i == 40 else 5.0) for i in range(100)}
           for plant in script.MARGIN_NEAR}
    chosen = script.margin_draws(p95, seed=3)
    assert chosen == script.margin_draws(p95, seed=3)
    others = [d for d in range(6)
              if script.margin_draws(p95, seed=4 + d) != chosen]
    assert others  # another seed, other draws (six tries)
    for plant, near in script.MARGIN_NEAR.items():
        rows = chosen[plant]
        assert rows[:len(near)] == list(near) and len(rows) == len(near) + script.MARGIN_RANDOM
        extra = rows[len(near):]
        assert len(set(extra)) == len(extra) and not set(extra) & set(near)
        assert all(p95[plant][i] is not None and p95[plant][i] <= 15.0 for i in extra)
    everyone = script.margin_draws({plant: {i: 1.0 for i in [*near, 40, 41, 42, 43, 44]}
                                    for plant, near in script.MARGIN_NEAR.items()}, seed=3)
    assert all(sorted(v[-5:]) == [40, 41, 42, 43, 44] for v in everyone.values())  # a p95 of exactly 15° is a pass


def test_the_committed_hold_margin_screen_flew_the_draws_its_seed_gives():
    """STUDY-222: the committed margin.json's draws are those margin_draws gives on the two committed 40° campaigns
    with the stated seed, and every candidate was flown on exactly those draws of each plant."""
    pd = pytest.importorskip("pandas")
    script = _margin_script()
    table = json.loads((studies.STUDIES_DIR / "magnetorquer_hold_after_acquisition/margin.json").read_text())
    p95 = {plant: {int(i): (None if pd.isna(v) else float(v))
                   for i, v in pd.read_parquet(res).set_index("seed_index")["pointing_p95_deg"].items()}
           for plant, (_, res) in script.MARGIN_PLANTS.items()}
    assert table["seed"] == script.MARGIN_SEED
    assert table["draws"] == script.margin_draws(p95, seed=table["seed"])
    first = {key: n for key, *_, n in script.MARGIN_CANDIDATES}
    for case in table["candidates"]:
        assert {p: [r["row"] for r in runs] for p, runs in case["runs"].items()} == {
            p: rows[:first[case["key"]]] for p, rows in table["draws"].items()}
        for plant, runs in case["runs"].items():
            assert all(r["committed"]["p95"] == pytest.approx(p95[plant][r["row"]], abs=1e-12) for r in runs)


def test_the_hold_margin_table_counts_near_misses_passes_and_runs_never_acquired():
    """STUDY-223: the margin block: per candidate and plant the near-misses at p95 ≤ 15° and ≤ 14°, the random
    passes kept, the largest p95, the median change against the committed rows, the median tail (15° acquisition
    minus 30°) and the runs that never acquire; each draw a row with the committed p95 then each candidate's."""
    script = _margin_script()
    near = script.MARGIN_NEAR["dipole"]

    def run(row, p95, committed=15.1):
        return {"row": row, "seed": 1, "median": 1.0, "p95": p95, "acquisition_s": None if p95 is None else 300.0,
                "acquisition_15deg_s": None if p95 is None else 420.0,
                "committed": {"median": 1.0, "p95": committed, "acquisition_s": 300.0,
                              "acquisition_15deg_s": 600.0}}

    rows = [near[0], near[1], near[2], 90]
    table = {"seed": 5, "draws": {"dipole": rows}, "candidates": [
        {"key": "as_committed", "label": "A", "runs": {"dipole": [run(near[0], 15.1), run(near[1], 15.098)]}},
        {"key": "x", "label": "X", "runs": {"dipole": [run(near[0], 13.5), run(near[1], 14.5),
                                                      run(near[2], None), run(90, 16.0)]}}]}
    x = table["candidates"][1]["runs"]["dipole"]
    x[0]["acquisition_s"], x[0]["acquisition_15deg_s"] = 401.0, 521.0  # 101 s later: counted
    x[1]["acquisition_s"], x[1]["acquisition_15deg_s"] = 400.0, 520.0  # 100 s later: not
    x[0]["median"], x[1]["median"], x[3]["median"] = 1.2, 1.4, 0.9
    text = script.margin_markdown(table)
    assert ("- X, tilted dipole (dipole on board): near-misses p95 ≤ 15° in **2 of 3**, ≤ 14° in 1; random passes "
            "≤ 15° in 0 of 1; largest p95 16.00°; p95 change against the committed rows -0.60° at the median") in text
    assert ("tail above 15° 120 s at the median; acquisition below 30° 300 → 400 s at the median, over 100 s later "
            "in **1**; the runs' median error 1.00 → 1.20° at the median; 1 of 4 never acquire") in text
    assert f"| tilted dipole (dipole on board) | {near[2]} | 15.10 | never acquired |" in text
    assert "| tilted dipole (dipole on board) | 90 (random pass) | 15.10 | 16.00 |" in text
    assert (f"The baseline flown again by this script (tilted dipole (dipole on board) {near[0]}, {near[1]}): 2 of 2 "
            "acquire, their p95 within 2.0e-03° of the committed campaigns' rows.") in text
    assert "| A |" not in text and "- A," not in text  # the baseline is a check, not a column


def test_the_hold_margin_screen_patches_the_law_constants_only_inside_the_flight():
    """STUDY-224: a candidate's module constants are set on control.three_mode inside the screen's `with` and put
    back after it (also when the flight raises); a constant the module lacks is refused, not silently added."""
    from detumble.control import three_mode

    script = _margin_script()
    before = three_mode.MAG_LQR_ALPHA
    with script._Patched(three_mode, {"MAG_LQR_ALPHA": 9.0}):
        assert three_mode.MAG_LQR_ALPHA == 9.0
    assert three_mode.MAG_LQR_ALPHA == before
    with pytest.raises(RuntimeError), script._Patched(three_mode, {"MAG_LQR_ALPHA": 9.0}):
        raise RuntimeError
    assert three_mode.MAG_LQR_ALPHA == before
    with pytest.raises(AttributeError), script._Patched(three_mode, {"MAG_LQR_ALPHAS": 9.0}):
        pass
    assert not hasattr(three_mode, "MAG_LQR_ALPHAS")
    for _, _, constants, _, _ in script.MARGIN_CANDIDATES:
        assert all(hasattr(three_mode, name) for name in constants)


def test_the_hold_margin_block_edited_by_hand_is_reported(tmp_path, monkeypatch):
    """STUDY-225: the margin screen's block with one p95 changed by hand is reported by --check, naming the block."""
    study = studies.STUDIES["magnetorquer_hold_margin"]
    body = studies.doc_blocks(study.doc.read_text(encoding="utf-8"))["magnetorquer_hold_margin"]
    cell = body.split("\n")[2].split(" | ")[2]  # the first draw's committed p95
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "magnetorquer_hold_margin", "magnetorquer_hold_margin",
                                       f"| {cell} |", f"| {float(cell) + 0.01:.2f} |")
    assert len(problems) == 1 and "block 'magnetorquer_hold_margin'" in problems[0]


def test_the_hold_spin_hand_back_block_edited_by_hand_is_reported(tmp_path, monkeypatch):
    """STUDY-160: sun_safe.md's hand-back flights with the hold spin at 1.9 °/s (five one-orbit adcs_ref flights,
    committed JSON) are a generated block: one hand-back time changed by hand in it is reported by --check, naming
    the block."""
    block = "sun_safe_coil_hand_back_hold_1_9"
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "sun_safe", block, "**3010.0 s**", "**3011.0 s**")
    assert len(problems) == 1 and f"block '{block}'" in problems[0]


def test_the_hold_spin_hand_back_probe_catches_a_tampered_file(tmp_path, monkeypatch):
    """STUDY-161: the 1.9 °/s hold-spin hand-back table's --check probe flies seed 1's first 120 s again (one adcs_ref
    run of seconds) and finds the committed pointing errors to 1e-9 deg, and every committed SunSpinLowered at 1.9
    °/s; a copy with one committed error nudged by 1e-9 deg, or one spin lowered to 1.5 °/s, is reported; a file
    made without the kind's parameter (the plain hand-back's) is refused, not rendered."""
    table = _sun_table("sun_safe_coil_hand_back_hold_1_9")
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["params"] == [["SUN_HOLD_SPIN_RATE", "1.9"]] and committed["kind"] == "hand_back_hold_1_9"
    assert table.run_probe() == []
    plain = json.loads(_sun_table("sun_safe_coil_hand_back").path.read_text(encoding="utf-8"))

    def nudge(data):
        data["probe"][60] += 1e-9
        data["rows"][2]["spin_lowered_to_deg_s"] = 1.5

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 2 and "at 60 s" in problems[0] and "seed 3 lowered its spin to 1.5" in problems[1]
    assert all("no longer computes" in p for p in problems)
    (tmp_path / table.results).write_text(json.dumps(dict(plain, kind="hand_back_hold_1_9")), encoding="utf-8")
    with pytest.raises(studies.StudyError, match="parameters"):
        table.blocks()


def test_the_two_deg_s_hand_back_block_is_checked_and_probed(tmp_path, monkeypatch):
    """STUDY-162: sun_safe.md's hand-back flights from the 2 °/s draws (five one-orbit adcs_ref flights, committed
    JSON): one acquisition changed by hand in the block is reported by --check; the probe flies seed 1's first 120 s
    again and finds the committed errors to 1e-9 deg and every SunSpinLowered at the default 1.5 °/s; a copy with
    one committed error nudged by 1e-9 deg is reported."""
    block = "sun_safe_coil_hand_back_2_deg_s"
    table = _sun_table(block)
    committed = json.loads(table.path.read_text(encoding="utf-8"))
    assert committed["rate_deg_s"] == 2.0 and committed["params"] == [] and len(committed["rows"]) == 5
    assert table.run_probe() == []
    row = committed["rows"][0]["acquisition_s"]
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "sun_safe", block, f"| {row:.0f} |",
                                       f"| {row + 1:.0f} |")
    assert len(problems) == 1 and f"block '{block}'" in problems[0]

    def nudge(data):
        data["probe"][119] -= 1e-9

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "at 119 s" in problems[0]


@pytest.mark.parametrize("block, old, new", [
    ("sun_safe_single_bias", "| 0.0013 |", "| 0.0014 |"),
    ("sun_safe_single_lit", "| 2.98 / 4.33 |", "| 2.78 / 4.42 |"),
    ("sun_safe_single_coil_gains", "| 654 |", "| 655 |"),
    ("sun_safe_single_tracker_limit", "| 5 | 2.2e-19;", "| 5 | 2e-19;"),
    ("sun_safe_single_bounce", "1.29 °/s", "1.30 °/s"),
    ("sun_safe_single_albedo_flight", "2456–2807 s (352 s)", "2456–2808 s (353 s)"),
    ("sun_safe_albedo_mismatch", "| 15 / 1319 / 14 |", "| 15 / 1320 / 14 |"),
    ("sun_safe_spin_down_geometry", "23–41 µT over the first", "23–40 µT over the first"),
])
def test_a_hand_edited_single_flight_block_is_reported(tmp_path, monkeypatch, block, old, new):
    """STUDY-180: sun_safe.md's single-flight blocks (the figures its prose quoted by hand until 2026-12-04: the
    bias observer, the lit threshold, the coils' gains, the tracker's rate limit at t = 0, ADCS-109's flight, the
    albedo deployment flight second by second), the albedo-mismatch table's acquisition column and the field
    geometry's line after its tables (the gate's windows after the first sunlit part, the field's range) are rendered
    from committed JSON: one figure changed by hand in each (for three, back to the figure the page quoted before) is
    reported by --check, naming the block."""
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "sun_safe", block, old, new)
    assert len(problems) == 1 and f"block '{block}'" in problems[0]


def test_the_single_flights_probe_catches_a_tampered_file(tmp_path, monkeypatch):
    """STUDY-181: the single flights' --check probe recomputes the tracker table's t = 0 excesses and re-flies the
    lit-threshold part (two 600 s plant-only flights) and ADCS-109's flight (one 500 s adcs_ref run): the committed
    file passes; a copy with the 5 % row's median, the hand-back rate and seed 5's excess each nudged is reported,
    one problem each, naming the figure."""
    table = _sun_table("sun_safe_single_bias")
    assert table.run_probe() == []

    def nudge(data):
        data["parts"]["lit"]["rows"][0]["median_deg"] += 1e-9
        data["parts"]["bounce"]["rate_at_hand_back_deg_s"] += 1e-9
        data["parts"]["tracker_limit"]["rows"][4]["excess_rad2_s2"] *= 2.0

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 3 and all("no longer computes" in p for p in problems)
    assert "seed 5 at 2 °/s" in problems[0] and "lit.rows[0].median_deg" in problems[1]
    assert "bounce.rate_at_hand_back_deg_s" in problems[2]


def test_the_single_flights_are_what_the_code_flies_now():
    """STUDY-182: the single flights' parts not in the probe fly again to the float: seed 1's bias-observer estimate
    after 900 s (plant-only, wheels) and the coils' τ = 20 s row (seed 2, the first sunlit part: its acquisition,
    error and rate across +Z); a file with a part missing is refused by name, not rendered."""
    table = _sun_table("sun_safe_single_bias")
    script = table.code()
    committed = json.loads(table.path.read_text(encoding="utf-8"))["parts"]
    bias = committed["bias"]["rows"][0]
    r = script.fly(1, duration_s=script.BIAS_S)
    assert [list(r.bias_estimate_deg_s), list(r.bias_true_deg_s), list(r.sun_body_end)] == [
        bias["estimate_deg_s"], bias["true_deg_s"], bias["sun_B"]]
    row = next(x for x in committed["coil_gains"]["rows"] if x["key"] == "tau_20")
    again = script.fly_coil_gains(keys=("tau_20",))["rows"][0]
    assert script.differences(json.loads(json.dumps(again)), row) == []
    with pytest.raises(ValueError, match="'lit'"):
        script.lit_markdown({"parts": {"bias": committed["bias"]}})


def test_the_tumble_campaigns_misses_by_initial_rate_are_generated(tmp_path, monkeypatch):
    """STUDY-183: magnetic_pointing.md's dispersed-tumble block gives which runs miss p95 ≤ 15° by initial rate (the
    figures its prose quoted by hand until 2026-12-04), from the committed campaign: the bins' counts add up to the
    runs and their misses to the block's; one count changed by hand is reported by --check."""
    pytest.importorskip("pandas")
    body = studies.magnetic_tumble_blocks()["magnetic_pointing_tumble"]
    line = next(ln for ln in body.splitlines() if ln.startswith("- runs with p95 ≤ 15° by initial rate:"))
    pairs = [cell.split(" at ")[0].split("/") for cell in line.split(": ", 1)[1].split(", ")]
    met, runs = sum(int(a) for a, _ in pairs), sum(int(b) for _, b in pairs)
    assert runs == 100 and f"p95 ≤ 15°: **{met} / {runs}**" in body
    assert f"- the {runs - met} p95 misses:" in body
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "magnetic_pointing_tumble", "magnetic_pointing_tumble",
                                       "23/23 at", "22/23 at")
    assert len(problems) == 1 and "block 'magnetic_pointing_tumble'" in problems[0]


@pytest.mark.parametrize(("block", "old", "new"), (
    ("coursework_summary", "6,285 s", "6,284 s"),
    ("coursework_summary", "**6,962 s**", "**6,961 s**"),
    ("coursework_beta_pattern", "| 73.7 |", "| 73.8 |"),
    ("coursework_beta_pattern", "z before x, y ≈ 60 s", "x before z, y ≈ 60 s"),
))
def test_the_coursework_summary_tables_are_generated(tmp_path, monkeypatch, block, old, new):
    """STUDY-190: coursework_reproduction.md's side-by-side table and the β-PD's per-axis pattern (typed by hand until
    2026-12-04) are rendered from the committed replica runs and the convergence campaigns: a figure or a pattern
    changed by hand in either is reported by --check, naming the block."""
    pytest.importorskip("pandas")
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "coursework_summary", block, old, new)
    assert len(problems) == 1 and f"block '{block}'" in problems[0]


def test_the_replica_table_is_rendered_from_committed_runs(tmp_path, monkeypatch):
    """STUDY-191: the report's-model table (β-PD and wheels under RK45) is rendered from the committed JSON lines of
    report_replica.py, no longer by running SciPy: --check reports a hand edit; a missing file is refused with the
    command that makes it."""
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "coursework_replica", "coursework_replica",
                                       "**6,099**", "**6,094**")
    assert len(problems) == 1 and "block 'coursework_replica'" in problems[0]
    folder = tmp_path / "coursework_replica"
    shutil.copytree(studies._MT1_DIR, folder)
    (folder / "wheels_tight.json").unlink()
    monkeypatch.setattr(studies, "_MT1_DIR", folder)
    with pytest.raises(studies.StudyError, match="wheels_pd --t-max 30 --rtol 1e-8 --atol 1e-10 > "):
        studies.replica_blocks()


def test_the_real_wheel_table_is_generated_and_flies_again(tmp_path, monkeypatch):
    """STUDY-192: coursework_reproduction.md's real-1U-wheel table (typed by hand until 2026-12-04) is rendered from
    the committed JSON of campaigns/coursework/real_wheel.py and the convergence campaigns: a hand edit is reported by
    --check; the orbit flown again (~15 CPU-s) gives the committed file's figures to the float."""
    pytest.importorskip("pandas")
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "coursework_real_wheel", "coursework_real_wheel",
                                       "| 9.93 s |", "| 9.94 s |")
    assert len(problems) == 1 and "block 'coursework_real_wheel'" in problems[0]
    committed = json.loads((studies.STUDIES_DIR / studies.REAL_WHEEL).read_text(encoding="utf-8"))
    again = json.loads(json.dumps(studies._load_script(studies._REAL_WHEEL_SCRIPT).fly()))
    assert again == committed


def test_the_listing_beta_pd_grid_is_generated(tmp_path, monkeypatch):
    """STUDY-193: the β-PD grid in the listing's form (typed by hand from uncommitted runs of 2026-12-02 until
    2026-12-04) is rendered from its committed campaign (campaigns/coursework/beta_pd_grid_listing.yaml): a settling
    time changed by hand is reported by --check, naming its block, and the block says which form it is."""
    pytest.importorskip("pandas")
    body = studies.grid_blocks()["coursework_beta_pd_listing"]
    assert "`switched: false`" in body and "coursework_beta_pd_grid_listing/" in body
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "coursework_grids", "coursework_beta_pd_listing",
                                       "8,943", "8,944")
    assert len(problems) == 1 and "block 'coursework_beta_pd_listing'" in problems[0]


def test_the_mekf_evidence_table_is_generated_and_flies_again(tmp_path, monkeypatch):
    """STUDY-194: attitude_knowledge.md's MEKF evidence table (typed by hand from the unit tests' flights until
    2026-12-04) is rendered from the committed JSON of campaigns/adcs/mekf_evidence.py, which flies
    tests/detumble/control/test_mekf.py's own harness: a hand edit is reported by --check; its probe flies everything
    again (a few CPU-s) and passes on the committed file, and reports a copy with one NEES nudged, by name."""
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "attitude_knowledge_mekf", "attitude_knowledge_mekf",
                                       "**MEKF 8.0 /", "**MEKF 7.9 /")
    assert len(problems) == 1 and "block 'attitude_knowledge_mekf'" in problems[0]
    table = studies.SCRIPT_TABLES["attitude_knowledge_mekf"]
    assert table.run_probe() == []

    def nudge(data):
        data["nees"][1]["nees_attitude"] += 1e-9

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 1 and "nees[1].nees_attitude" in problems[0] and "no longer computes" in problems[0]


@pytest.mark.parametrize(("old", "new"), (("100 / 100 runs, 18.5–20.0 s", "100 / 100 runs, 18.5–20.5 s"),
                                          ("peak 7.3 %", "peak 7.2 %")))
def test_the_pointing_verdict_is_generated(tmp_path, monkeypatch, old, new):
    """STUDY-195: attitude_knowledge.md's verdict on issue 13's targets (typed by hand until 2026-12-04) is rendered
    from the committed 100-run campaign and orbit_runs.json: a figure changed by hand is reported by --check."""
    pytest.importorskip("pandas")
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, "attitude_knowledge_verdict",
                                       "attitude_knowledge_verdict", old, new)
    assert len(problems) == 1 and "block 'attitude_knowledge_verdict'" in problems[0]


def test_the_hold_lqr_bound_block_edited_by_hand_is_reported(tmp_path, monkeypatch):
    """STUDY-200: magnetorquer_hold_after_acquisition.md's periodic-LQR bound (committed JSON of
    campaigns/adcs/magnetic_lqr_bound.py) is a generated block: its verdict's fastest rate changed by hand is reported
    by --check, naming the block."""
    block = "magnetorquer_hold_lqr_bound"
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, block, block, "within the capacity: **−",
                                       "within the capacity: **−9")
    assert len(problems) == 1 and f"block '{block}'" in problems[0]


def test_the_hold_lqr_bound_probe_catches_a_tampered_file(tmp_path, monkeypatch):
    """STUDY-201: the LQR bound's --check probe solves one weight again (rate scale 0.01 rad/s, r 1e4, α 4e-3; a few
    CPU-s) and finds the committed row to 1e-6; a copy whose slowest rate is nudged by 1e-5 relative, or one of whose
    falls is moved by 1 s, is reported with both figures."""
    table = studies.SCRIPT_TABLES["magnetorquer_hold_lqr_bound"]
    assert table.run_probe() == []

    def nudge(data):
        row = next(r for r in data["rows"] if (r["w_scale"], r["r"], r["alpha"]) == (0.01, 1e4, 4e-3))
        row["rate"] *= 1.0 + 1e-5
        row["fall_field_s"][3] += 1.0

    _nudged_script_table(tmp_path, monkeypatch, table, nudge)
    problems = table.run_probe()
    assert len(problems) == 2 and ": rate of (0.01, 10000.0, 0.004)" in problems[0]
    assert ": fall_field_s of" in problems[1] and all("no longer computes" in p for p in problems)


def _weight_record(start: float, theta: float = 30.0, peak: float = 70.2) -> dict:
    return {"start_s": start, "theta_scale_deg": theta, "rate_scale_rad_s": 0.03, "r": 1.0, "alpha_per_s": 0.002,
            "peak_deg": peak, "fall_median_s": 258.4, "fall_max_s": 391.0, "fall_field_line_s": 220.6}


def test_the_weight_screen_renders_each_set_at_its_starts_and_refuses_a_set_missing_a_start():
    """STUDY-226: the linear-model weight screen's table has a row per weight set in the order flown, each figure at
    the starts in time order joined by " / " (rounded to the unit); a file in which one set lacks one start is
    refused with the set named, not rendered with a gap."""
    script = studies._load_script("campaigns/adcs/magnetorquer_hold_lqr_weights.py")
    records = [_weight_record(2000.0, peak=63.4), _weight_record(0.0), _weight_record(4000.0, peak=80.0),
               _weight_record(0.0, theta=20.0), _weight_record(2000.0, theta=20.0), _weight_record(4000.0, theta=20.0)]
    lines = script.markdown({"records": records}).splitlines()
    assert lines[2] == "| 30 | 0.03 | 1 | 0.002 | 70 / 63 / 80 | 258 / 258 / 258 | 391 / 391 / 391 | 221 / 221 / 221 |"
    assert lines[3].startswith("| 20 | 0.03 | 1 | 0.002 | 70 / 70 / 70 |") and len(lines) == 4
    with pytest.raises(ValueError, match="20/0.03/1/0.002 was not flown at every start"):
        script.markdown({"records": records[:-1]})


def test_the_weight_screen_block_edited_by_hand_is_reported(tmp_path, monkeypatch):
    """STUDY-227: the weight screen's block (rendered from lqr_weights.json) with one peak changed by hand is reported
    by --check, naming the block."""
    name = "magnetorquer_hold_lqr_weights_screen"
    body = studies.doc_blocks(studies.STUDIES[name].doc.read_text(encoding="utf-8"))[name]
    cell = body.split("\n")[2].split(" | ")[4]  # the kept set's peaks, "a / b / c"
    edited = " / ".join([str(int(cell.split(" / ")[0]) + 1), *cell.split(" / ")[1:]])
    problems = _check_with_a_hand_edit(tmp_path, monkeypatch, name, name, f"| {cell} |", f"| {edited} |")
    assert len(problems) == 1 and f"block '{name}'" in problems[0]


def test_the_hold_candidates_pin_the_coils_hold_they_were_flown_with(monkeypatch):
    """STUDY-228: the coil-hold candidates' draws (magnetorquer_hold_candidates.fly_draw) pin the coils' hold of before
    2026-12-05 (MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0, MAG_FIELD_MODEL_DEGREE 1) for each parameter their scenario file
    does not set: the degree on the base scenario (which pins the other two itself), none on the two 40° plants that
    set all three; a case's own setting comes after the pin and wins (the scenario fly_draw hands the runner, captured
    instead of flown): MAG_BIAS_TIME 1 s alone flies the dipole on board, not the new default's degree 6."""
    from detumble.sim import runner

    script = studies._load_script("campaigns/adcs/magnetorquer_hold_candidates.py")
    dipole, igrf14 = (script.MARGIN_PLANTS[p] for p in ("dipole", "igrf14"))
    assert script.pinned(script.SCENARIO) == ["control.adcs.MAG_FIELD_MODEL_DEGREE=1.0"]
    assert script.pinned(dipole[0]) == script.pinned(igrf14[0]) == []

    class FlownError(Exception):
        pass

    def flown(sc, **_):
        raise FlownError(sc.control.adcs)

    monkeypatch.setattr(runner, "run", flown)
    degree6 = (script.FIELD_MODEL, "control.adcs.MAG_FIELD_MODEL_DEGREE=6.0")
    for args, hold in ((((script.FIELD_MODEL,),), (1.0, 0.0, 1.0)), ((degree6,), (1.0, 0.0, 6.0)),
                       (((), *dipole), (1.0, 40.0, 1.0)), (((), *igrf14), (1.0, 40.0, 6.0))):
        with pytest.raises(FlownError) as got:
            script.fly_draw(23, *args)
        adcs = got.value.args[0]
        assert (adcs.MAG_BIAS_TIME, adcs.MAG_LQR_ANGLE, adcs.MAG_FIELD_MODEL_DEGREE) == hold


def test_the_coil_deployment_scripts_send_the_pinned_hold_first(tmp_path, monkeypatch):
    """STUDY-229: the adcs_ref coil flights of magnetic_pointing.md and sun_safe.md send MAG_BIAS_TIME 0 and
    MAG_LQR_ANGLE 0 (field steering on the raw reading, the default before 2026-12-05) at 00:00:00 before the
    sequence's first coil command: magnetic_pointing_runs' sequence (pointing_magnetorquers.seq's first lines; the
    row's own lines come later and win), every kind of sun_safe_coil_runs (its parameters after the pin), and the
    single flights' tracker-limit and ADCS-109 flights (the sequences handed to the run, captured instead of flown)."""
    pin = [f"R00:00:00 ReferenceDeployment.attitudeController.{x}"
           for x in ("MAG_BIAS_TIME_PRM_SET 0.0", "MAG_LQR_ANGLE_PRM_SET 0.0")]

    def commands(text: str) -> list[str]:
        return [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith(";")]

    runs = studies._load_script("campaigns/adcs/magnetic_pointing_runs.py")
    seq = commands(runs.sequence(("K_P_MAG_PRM_SET 1.0e-6",)))
    forced = next(i for i, ln in enumerate(seq) if "FORCE_MODE" in ln)
    assert seq[:2] == pin and seq[forced - 1].endswith("K_P_MAG_PRM_SET 1.0e-6")
    coil = studies._load_script("campaigns/adcs/sun_safe_coil_runs.py")
    sent = []

    def captured(cmd, **_):
        sent.append(commands(pathlib.Path(cmd[cmd.index("--seq") + 1]).read_text()))

    monkeypatch.setattr(coil.subprocess, "run", captured)
    for kind in coil.KINDS:
        coil.fly(kind, 1, 1.0, tmp_path / kind)
        own = [f"R00:00:00 ReferenceDeployment.attitudeController.{n}_PRM_SET {v}"
               for n, v in coil.PARAMS.get(kind, ())]
        assert sent[-1][:2 + len(own)] == pin + own, kind
        assert any("POINTING_ACTUATOR_PRM_SET MAGNETORQUERS" in ln for ln in sent[-1][2:]), kind
    single = studies._load_script("campaigns/adcs/sun_safe_single_flights.py")

    def run_captured(out, duration, sequence, *args, **kwargs):
        out.mkdir(parents=True)
        (out / "events.log").write_text("")
        sent.append(commands(sequence))

    monkeypatch.setattr(single, "_run", run_captured)
    monkeypatch.setattr(single, "_transitions", lambda run_dir: [])
    n = len(sent)
    single.fly_tracker_limit()
    assert len(sent) == n + len(single.TRACKER_RATES) * len(single.TRACKER_SEEDS)
    assert all(s[:2] == pin for s in sent[n:])
    assert commands(single.BOUNCE_SEQUENCE)[:2] == pin
