"""Issue 27's magnetorquer hold: the candidates for a faster fall from the acquisition's 30° (plant only).

    python campaigns/adcs/magnetorquer_hold_candidates.py \
        --json docs/studies/magnetorquer_hold_after_acquisition/candidates.json
    python campaigns/adcs/magnetorquer_hold_candidates.py --part floquet --json /tmp/floquet.json   # a CPU-minute

``floquet`` (≈ 1 CPU-minute): the slowest mode's Floquet rate (1/s, negative decays) of the field-steering law
linearised about the adcs_ref target over one orbit (``detumble.analysis.magnetic_floquet``, inertia × 1.25 for the
coils' 80 % duty, ζ 1), (a) for the present gains (K_P_MAG 4e-6 N·m, K_D_MAG 4e-4 N·m·s, ρ 2) at 200 … 4000 samples
of the orbit, the law seeing the field through 0, 1, 1.5 and 2 × the scenario's LIS2MDL bias, in the tilted dipole and
IGRF-14: whether the maps the study pages quoted until 2026-12-04 (200 samples) are converged; (b) over ρ 2 … 5 and
two gain pairs at 16000 samples (:data:`RHO_SAMPLES`) in the tilted dipole (the campaign's field), without the bias
and with it: what a bias-free law can gain from a larger ρ.

``draws`` (≈ 6 CPU-minutes): the six draws of ``campaigns/adcs/pointing_magnetorquers_plant.yaml`` that miss the p95
with the longest tails (and four that pass, for the schedule) flown again plant-only (``detumble.sim.runner.run``,
law adcs, one orbit) with their committed seed and start, under: no magnetometer bias (ρ 2, the oracle of an on-board
bias estimate); no bias and ρ 3; ρ scheduled on the error (MAG_STEER_RHO_LARGE 4 from 20°, 2 below 12°) with the
bias; the same schedule without the bias; the controller's field from the on-board dipole model (MAG_BIAS_TIME 1 s,
2026-12-05); the hold scheduled on that model (MAG_LQR_ANGLE 180°, ``control.magnetic_lqr``, 2026-12-05), and it
and the present law in an IGRF-14 plant (the on-board model's error that of the dipole against the full field), and
the hold with an on-board IGRF-14 truncated to degree 6 in that plant; the margin screen's MAG_LQR_ANGLE 50° and 60°
on every draw that never acquired with the hold at every error (:data:`LQR_NEVER_ALL`, :data:`LQR_NEVER_IGRF14`).
``--part draws --case KEY`` flies one case into the file, keeping the others. Per run the summary's window
statistics and the tail (the time from the acquisition below 30° to the error staying below 15°).
``tools/studies.py --only magnetorquer_hold_candidates`` renders the blocks (:func:`markdown`).

``margin`` (≈ 15 CPU-minutes a candidate; not part of ``all``, its own file): a screen of candidate changes that
would give the 40° scheduled hold (MAG_LQR_ANGLE 40°, MAG_BIAS_TIME 1 s) margin under the p95 goal. Each candidate
of :data:`MARGIN_CANDIDATES` (module constants of ``control.three_mode`` patched for its flights only, and/or scenario
settings) flies each plant's near-misses (:data:`MARGIN_NEAR`) and five passing draws drawn with
:data:`MARGIN_SEED` (:func:`margin_draws`) from the committed 40° campaigns (tilted-dipole plant with the dipole on
board; IGRF-14 plant with IGRF-14 of degree 6 on board), each against its committed row; the baseline
("as_committed") flies two draws of each plant unchanged, which must give the committed rows.
``tools/studies.py --only magnetorquer_hold_margin`` renders its block (:func:`margin_markdown`).

    python campaigns/adcs/magnetorquer_hold_candidates.py --part margin \
        --json docs/studies/magnetorquer_hold_after_acquisition/margin.json [--case KEY]

Every draw pins the coils' hold of before 2026-12-05 where neither its scenario file nor its case sets it
(:data:`HOLD_BEFORE`, :func:`pinned`): MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0 (field steering on the raw reading) and
MAG_FIELD_MODEL_DEGREE 1 (the tilted dipole on board, which the cases that set MAG_BIAS_TIME or MAG_LQR_ANGLE alone
flew). Since 2026-12-05 the defaults are 1 s, 50° and 6 (the hold these candidates led to); the tables document the
candidates as they were flown.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "campaigns/adcs/scenarios/pointing_magnetorquers.yaml"
COMMITTED = ROOT / "docs/studies/magnetorquer_hold_after_acquisition/campaign/results.parquet"
TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
BIAS_G = (0.012, -0.008, 0.005)
FIELDS = {"dipole": ("field.model=dipole",), "igrf14": ("field.model=igrf14", "field.table_step_s=10")}
SAMPLES = ((200, 4), (400, 4), (1000, 2), (2000, 2), (4000, 1))  # (samples of the orbit, RK4 sub-steps)
BIAS_FACTORS = (0.0, 1.0, 1.5, 2.0)
RHO_GAINS = ((4e-6, 4e-4), (8e-6, 8e-4))
RHOS = (2.0, 2.5, 3.0, 3.5, 4.0, 5.0)
#: (b)'s samples of the orbit, one RK4 step each: magnetic_pointing_tables.py's FLOQUET_SAMPLES (2000 × 2 until the
#: maps were found unconverged below it, 2026-12-04)
RHO_SAMPLES = 16000
#: the committed campaign's draws (seed indices, = its rows) flown again: the six misses with the longest tails,
#: four passes
MISSES = (12, 72, 89, 76, 26, 8)
PASSES = (50, 87, 33, 0)
#: four of the draws that never acquired in the campaign of the hold scheduled on the field model at every error
#: (MAG_LQR_ANGLE 180°, campaign_field_model_lqr: they end spinning at ~1.5 °/s)
LQR_NEVER = (1, 7, 20, 40)
#: every draw that never acquired with the hold scheduled at every error (campaign_field_model_lqr: 17 of 100, dipole
#: plant; campaign_field_model_lqr_igrf14: 7 of its 30, IGRF-14 plant): the margin screen's MAG_LQR_ANGLE 50° flown
#: on them (2026-12-05), since a larger switch angle hands more of the tumble to the linear hold
LQR_NEVER_ALL = (3, 4, 7, 9, 17, 20, 40, 41, 44, 51, 56, 61, 68, 69, 75, 77, 78)
LQR_NEVER_IGRF14 = (3, 4, 7, 9, 14, 17, 20)
NO_BIAS = "sensors.magnetometer.bias_gauss=[0.0, 0.0, 0.0]"
SCHEDULE = ("control.adcs.MAG_STEER_RHO_LARGE=4.0", "control.adcs.MAG_STEER_RHO_FROM=12.0",
            "control.adcs.MAG_STEER_RHO_AT=20.0")
#: the controller's field from the on-board dipole model (the reading less a bias estimate low-passed at 1 s)
FIELD_MODEL = "control.adcs.MAG_BIAS_TIME=1.0"
#: (key, label, scenario settings, rows)
CASES = (("no_bias", "no magnetometer bias, ρ 2 (the oracle of a bias estimate)", (NO_BIAS,), MISSES),
         ("no_bias_rho3", "no magnetometer bias, ρ 3", (NO_BIAS, "control.adcs.MAG_STEER_RHO=3.0"), MISSES),
         ("schedule", "ρ 4 from 20°, 2 below 12° (the bias as flown)", SCHEDULE, MISSES + PASSES),
         ("no_bias_schedule", "no magnetometer bias, ρ 4 from 20°, 2 below 12°", (NO_BIAS, *SCHEDULE),
          MISSES + PASSES),
         ("field_model", "the field from the on-board model (MAG_BIAS_TIME 1 s), ρ 2", (FIELD_MODEL,),
          MISSES + PASSES),
         ("field_model_lqr", "the hold scheduled on the on-board field model (MAG_LQR_ANGLE 180°, MAG_BIAS_TIME 1 s)",
          (FIELD_MODEL, "control.adcs.MAG_LQR_ANGLE=180.0"), MISSES + PASSES),
         ("field_model_lqr_igrf14", "the same in an IGRF-14 plant (the on-board model still the tilted dipole)",
          (*FIELDS["igrf14"], FIELD_MODEL, "control.adcs.MAG_LQR_ANGLE=180.0"), MISSES + PASSES),
         ("field_model_lqr_reading_igrf14", "the hold scheduled on the on-board field model, the reading for its "
          "projection (MAG_LQR_ANGLE 180°, MAG_BIAS_TIME 0), in an IGRF-14 plant",
          (*FIELDS["igrf14"], "control.adcs.MAG_LQR_ANGLE=180.0"), MISSES + PASSES),
         ("igrf14", "the present law in an IGRF-14 plant", FIELDS["igrf14"], MISSES + PASSES),
         ("field_model_lqr_igrf14_degree6", "the hold scheduled on an on-board IGRF-14 of degree 6 "
          "(MAG_FIELD_MODEL_DEGREE 6, MAG_LQR_ANGLE 180°, MAG_BIAS_TIME 1 s) in an IGRF-14 plant",
          (*FIELDS["igrf14"], FIELD_MODEL, "control.adcs.MAG_LQR_ANGLE=180.0",
           "control.adcs.MAG_FIELD_MODEL_DEGREE=6.0"),
          MISSES + PASSES),
         ("field_model_lqr_below_40", "the hold scheduled on the on-board field model below 40°, field steering above "
          "(MAG_LQR_ANGLE 40°, MAG_BIAS_TIME 1 s)", (FIELD_MODEL, "control.adcs.MAG_LQR_ANGLE=40.0"),
          MISSES[:3] + LQR_NEVER),
         ("field_model_lqr_below_40_igrf14_degree6", "the hold scheduled on an on-board IGRF-14 of degree 6 below 40°, "
          "field steering above, in an IGRF-14 plant", (*FIELDS["igrf14"], FIELD_MODEL,
                                                        "control.adcs.MAG_LQR_ANGLE=40.0",
                                                        "control.adcs.MAG_FIELD_MODEL_DEGREE=6.0"),
          MISSES + PASSES + LQR_NEVER),
         *((f"field_model_lqr_below_{a}", f"the hold scheduled on the on-board field model below {a}°, field "
            f"steering above (MAG_LQR_ANGLE {a}°, MAG_BIAS_TIME 1 s; the margin screen)",
            (FIELD_MODEL, f"control.adcs.MAG_LQR_ANGLE={a}.0"), LQR_NEVER_ALL) for a in (50, 60)),
         *((f"field_model_lqr_below_{a}_igrf14_degree6", f"the hold scheduled on an on-board IGRF-14 of degree 6 "
            f"below {a}°, field steering above, in an IGRF-14 plant (the margin screen)",
            (*FIELDS["igrf14"], FIELD_MODEL, f"control.adcs.MAG_LQR_ANGLE={a}.0",
             "control.adcs.MAG_FIELD_MODEL_DEGREE=6.0"), LQR_NEVER_IGRF14) for a in (50, 60)))


def _rate(plant, period, b, bd, samples, substeps, k_p, k_d, rho, k) -> float | None:
    import numpy as np

    from detumble.analysis.magnetic_floquet import field_line_along_orbit, floquet_rate

    inertia = 1.25 * np.array(plant.scenario.spacecraft.inertia_kg_m2)
    _, bl, bdl = field_line_along_orbit(plant, TARGET, samples=samples, bias_t=[k * 1e-4 * c for c in BIAS_G])
    with np.errstate(all="ignore"):
        try:
            r = floquet_rate("field_steering", period, b, bd, inertia, k_p, k_d, substeps=substeps, rho=rho, zeta=1.0,
                             b_law=bl, bdot_law=bdl)
        except np.linalg.LinAlgError:  # grew past the floats within the orbit
            return None
    return r if math.isfinite(r) else None


def floquet() -> dict:
    from detumble.analysis.magnetic_floquet import field_line_along_orbit
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    out: dict = {"convergence": {}, "rho": []}
    plants = {f: Plant(load_scenario("adcs", settings=list(s))) for f, s in FIELDS.items()}
    for field, plant in plants.items():
        rows = []
        for samples, sub in SAMPLES:
            period, b, bd = field_line_along_orbit(plant, TARGET, samples=samples)
            rates = [_rate(plant, period, b, bd, samples, sub, 4e-6, 4e-4, 2.0, k) for k in BIAS_FACTORS]
            rows.append({"samples": samples, "substeps": sub, "rates": rates})
        out["convergence"][field] = rows
    plant = plants["dipole"]
    period, b, bd = field_line_along_orbit(plant, TARGET, samples=RHO_SAMPLES)
    out["rho_samples"] = RHO_SAMPLES
    out["r_mean"] = float(sum(math.sqrt(float(v @ v)) for v in bd[:-1]) / (len(bd) - 1))  # rad/s, orbit mean
    for k_p, k_d in RHO_GAINS:
        for rho in RHOS:
            out["rho"].append({"k_p": k_p, "k_d": k_d, "rho": rho,
                               "rates": [_rate(plant, period, b, bd, RHO_SAMPLES, 1, k_p, k_d, rho, k)
                                         for k in (0.0, 1.0)]})
    return out


#: the coils' hold as these candidates were flown (flight name → value): the defaults before 2026-12-05
HOLD_BEFORE = {"MAG_BIAS_TIME": 0.0, "MAG_LQR_ANGLE": 0.0, "MAG_FIELD_MODEL_DEGREE": 1.0}


def pinned(scenario: pathlib.Path) -> list[str]:
    """The settings pinning :data:`HOLD_BEFORE` for the parameters ``scenario``'s ``control.adcs`` does not set (a
    draw's own settings come after them and win)."""
    import yaml

    given = (yaml.safe_load(scenario.read_text(encoding="utf-8")).get("control") or {}).get("adcs") or {}
    return [f"control.adcs.{name}={value}" for name, value in HOLD_BEFORE.items() if name not in given]


def fly_draw(row: int, settings: tuple[str, ...], scenario: pathlib.Path = SCENARIO,
             committed: pathlib.Path = COMMITTED) -> dict:
    """One draw of a committed campaign (``committed``: its results.parquet, whose row ``row`` gives the seed and the
    start) flown again from ``scenario`` with :func:`pinned` then ``settings``: the window's statistics (deg) and the
    acquisitions (s), beside that campaign's row."""
    import pandas as pd

    from detumble.analysis.pointing_windows import acquisition_time
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario
    from fprime_lite.tools.campaign.values import yaml_text

    frame = pd.read_parquet(committed)
    d = frame.set_index("seed_index").loc[row] if "seed_index" in frame else frame.iloc[row]
    q = [float(x) for x in d["scenario.initial.attitude.quaternion"]]
    w = [float(x) for x in d["scenario.initial.rate.omega_deg_s"]]
    sc = load_scenario(str(scenario), seed=int(d["seed"]),
                       settings=[f"initial.attitude.quaternion={yaml_text(q)}",
                                 f"initial.rate.omega_deg_s={yaml_text(w)}", *pinned(scenario), *settings])
    r = run(sc, law="adcs", duration_s=5580)
    j = r.adcs_header.index("pointing_error_deg")
    t_in = float(r.summary["pointing_intervals"][0]["t_s"])
    kept = [(row_[0], float(a[j])) for row_, a in zip(r.rows, r.adcs_rows, strict=True)
            if row_[0] >= t_in and a[j] not in ("", None) and math.isfinite(float(a[j]))]
    times, errors = [t for t, _ in kept], [e for _, e in kept]
    a30, a15 = acquisition_time(times, errors, 30.0), acquisition_time(times, errors, 15.0)
    pe = r.summary.get("pointing_error_deg") or {}
    return {"row": row, "seed": int(d["seed"]), "median": pe.get("median"), "p95": pe.get("p95"),
            "acquisition_s": a30, "acquisition_15deg_s": a15,
            "committed": {"median": float(d["pointing_median_deg"]), "p95": float(d["pointing_p95_deg"]),
                          "acquisition_s": float(d["pointing_acquisition_s"]),
                          "acquisition_15deg_s": float(d["pointing_acquisition_15deg_s"])}}


def draws(only: str | None = None, table: dict | None = None) -> dict:
    """Every case of :data:`CASES` flown, or (``only``, a case's key) that one flown into ``table``'s other cases."""
    kept = {c["key"]: c for c in (table or {}).get("cases", [])} if only else {}
    cases = []
    for key, label, sets, rows in CASES:
        if only and key != only:
            if key in kept:
                cases.append(kept[key])
            continue
        cases.append({"key": key, "label": label, "settings": list(sets), "runs": [fly_draw(r, sets) for r in rows]})
    return {"cases": cases}


#: the margin screen (2026-12-05): the 40° scheduled hold's two committed campaigns, (plant, scenario file, results)
HOLD_DIR = ROOT / "docs/studies/magnetorquer_hold_after_acquisition"
MARGIN_PLANTS = {
    "dipole": (ROOT / "campaigns/adcs/scenarios/pointing_magnetorquers_field_model_lqr_below_40.yaml",
               HOLD_DIR / "campaign_field_model_lqr_below_40/results.parquet"),
    "igrf14": (ROOT / "campaigns/adcs/scenarios/pointing_magnetorquers_field_model_lqr_below_40_igrf14.yaml",
               HOLD_DIR / "campaign_field_model_lqr_below_40_igrf14/results.parquet")}
#: what the page calls each plant (the on-board model in brackets)
MARGIN_PLANT_NAMES = {"dipole": "tilted dipole (dipole on board)", "igrf14": "IGRF-14 (degree 6 on board)"}
#: each plant's misses and near-misses (p95 above 13° as committed; seed indices), worst first
MARGIN_NEAR = {"dipole": (23, 86, 46, 13, 38, 8),
               "igrf14": (23, 50, 13, 81, 12, 70, 87, 3, 27, 19, 29, 62)}
#: passing draws drawn at random from each plant's other draws with p95 ≤ 15° (seeded: the same draws every time)
MARGIN_RANDOM = 5
#: s: an acquisition this much later than the committed run's is counted (the transient moved out of the window
#: rather than shortened: a later acquisition shortens the window the p95 is taken over)
MARGIN_LATER_S = 100.0
MARGIN_SEED = 20261205
#: the screen's candidates: (key, label, module constants of detumble.control.three_mode patched for the flight,
#: scenario settings on top of the plant's file, how many of each plant's draws: None all). "as_committed" changes
#: nothing and flies each plant's first two near-misses: it must give the committed campaigns' rows (the baseline).
MARGIN_CANDIDATES = (
    ("as_committed", "as committed (the baseline, flown again)", {}, (), 2),
    ("theta_20", "θ scale 20° (rate scale 0.03 rad/s, r 1, α 2e-3 /s)", {"MAG_LQR_THETA_SCALE": math.radians(20.0)},
     (), None),
    ("alpha_3e-3", "α 3e-3 /s (rate scale 0.03 rad/s, r 1, θ scale 30°)", {"MAG_LQR_ALPHA": 3.0e-3}, (), None),
    ("angle_50", "MAG_LQR_ANGLE 50° (the weights as committed)", {}, ("control.adcs.MAG_LQR_ANGLE=50.0",), None),
    ("angle_60", "MAG_LQR_ANGLE 60° (the weights as committed)", {}, ("control.adcs.MAG_LQR_ANGLE=60.0",), None))


def margin_draws(p95_by_plant: dict[str, dict[int, float]], seed: int = MARGIN_SEED,
                 k: int = MARGIN_RANDOM) -> dict[str, list[int]]:
    """Each plant's screened draws (seed indices): its :data:`MARGIN_NEAR`, then ``k`` drawn with ``seed`` (one
    ``random.Random`` per plant, in :data:`MARGIN_NEAR`'s order of plants) from its other draws whose committed p95
    (deg; ``p95_by_plant[plant][index]``, ``None`` or NaN: never acquired) is at most 15°."""
    import random

    rng = random.Random(seed)
    out = {}
    for plant, near in MARGIN_NEAR.items():
        passing = sorted(i for i, p in p95_by_plant[plant].items()
                         if i not in near and p is not None and p == p and p <= 15.0)
        out[plant] = [*near, *rng.sample(passing, k)]
    return out


class _Patched:
    """``constants`` (name → value) set on ``module`` inside the ``with``, the old values put back after."""

    def __init__(self, module, constants: dict[str, float]):
        self.module, self.constants, self.old = module, constants, {}

    def __enter__(self):
        for name, value in self.constants.items():
            if not hasattr(self.module, name):
                raise AttributeError(f"{self.module.__name__} has no constant {name}")
            self.old[name] = getattr(self.module, name)
            setattr(self.module, name, value)
        return self

    def __exit__(self, *exc) -> None:
        for name, value in self.old.items():
            setattr(self.module, name, value)


def margin(only: str | None = None, table: dict | None = None) -> dict:
    """The screen: every candidate of :data:`MARGIN_CANDIDATES` (or ``only``, kept beside ``table``'s others) flown
    on each plant's :func:`margin_draws` from that plant's committed 40° campaign (seeds, starts and its row)."""
    import pandas as pd

    from detumble.control import three_mode

    p95 = {plant: {int(i): (None if pd.isna(v) else float(v)) for i, v in
                   pd.read_parquet(res).set_index("seed_index")["pointing_p95_deg"].items()}
           for plant, (_, res) in MARGIN_PLANTS.items()}
    chosen = margin_draws(p95)
    kept = {c["key"]: c for c in (table or {}).get("candidates", [])} if only else {}
    cases = []
    for key, label, constants, settings, first in MARGIN_CANDIDATES:
        if only and key != only:
            if key in kept:
                cases.append(kept[key])
            continue
        runs: dict[str, list[dict]] = {}
        with _Patched(three_mode, constants):
            for plant, rows in chosen.items():
                scenario, results = MARGIN_PLANTS[plant]
                runs[plant] = [fly_draw(r, settings, scenario, results) for r in rows[:first]]
                print(f"{key} {plant}: " + ", ".join(f"{r['row']} {_f(r['p95'], '.2f')}" for r in runs[plant]),
                      flush=True)
        cases.append({"key": key, "label": label, "constants": constants, "settings": list(settings), "runs": runs})
    return {"seed": MARGIN_SEED, "draws": chosen, "candidates": cases}


def _sci(x: float) -> str:
    """``x`` as the pages write it: 3 digits, a short exponent, a true minus (−3.04e-3)."""
    mantissa, exponent = f"{abs(x):.2e}".split("e")
    return f"{'−' if x < 0 else '+'}{mantissa}e{int(exponent)}"


def _e(x) -> str:
    if x is None:
        return "**grows past the floats**"
    return f"**{_sci(x)}**" if x > 0 else _sci(x)


def floquet_markdown(table: dict) -> str:
    f = table["floquet"]
    lines = ["| field | samples of the orbit (RK4 sub-steps) | "
             + " | ".join(f"{k:g} × bias" for k in BIAS_FACTORS) + " |", "|---|---|" + "---|" * len(BIAS_FACTORS)]
    for field, rows in f["convergence"].items():
        for r in rows:
            name = "tilted dipole" if field == "dipole" else "IGRF-14"
            cells = " | ".join(_e(x) for x in r["rates"])
            lines.append(f"| {name} | {r['samples']} ({r['substeps']}) | {cells} |")
    lines += ["", "Present gains (K_P_MAG 4e-6 N·m, K_D_MAG 4e-4 N·m·s, ρ 2, ζ 1), inertia × 1.25; slowest mode's rate "
              "in 1/s (bold: grows).", "",
              "| K_P_MAG (N·m), K_D_MAG (N·m·s) | ρ | no bias | the scenario's bias "
              f"| −ζρr̄ (the closed form at the orbit's mean r̄ = {_sci(f['r_mean'])[1:]} rad/s) |",
              "|---|---|---|---|---|"]
    for r in f["rho"]:
        lines.append(f"| {_sci(r['k_p'])[1:].replace('.00', '')}, {_sci(r['k_d'])[1:].replace('.00', '')} | "
                     f"{r['rho']:g} | {_e(r['rates'][0])} | {_e(r['rates'][1])} | {_sci(-r['rho'] * f['r_mean'])} |")
    lines += ["", f"Tilted dipole (the campaign's field), {f.get('rho_samples', 2000)} samples, ζ 1, inertia × 1.25."]
    return "\n".join(lines) + "\n"


def _tail(run: dict) -> float | None:
    a, b = run["acquisition_s"], run["acquisition_15deg_s"]
    return None if a is None or b is None else b - a


def _f(x, fmt: str) -> str:
    return "—" if x is None else format(x, fmt)


def draws_markdown(table: dict) -> str:
    lines = ["| case | draw (seed index) | p95 (deg), flown / as committed | median (deg), flown / as committed | "
             "acquisition < 30° (s), flown / as committed | "
             "tail (s), flown / as committed |", "|---|---|---|---|---|---|"]
    for case in table["draws"]["cases"]:
        for run in case["runs"]:
            c = case["label"]
            com = run["committed"]
            tail_c = com["acquisition_15deg_s"] - com["acquisition_s"]
            p95 = "never acquired" if run["p95"] is None else f"{run['p95']:.1f}"
            lines.append(f"| {c} | {run['row']} | {p95} / {com['p95']:.1f} | {_f(run['median'], '.2f')} / "
                         f"{com['median']:.2f} | "
                         f"{_f(run['acquisition_s'], '.0f')} / {com['acquisition_s']:.0f} | "
                         f"{_f(_tail(run), '.0f')} / {tail_c:.0f} |")
    lines.append("")
    for case in table["draws"]["cases"]:
        runs = case["runs"]
        miss = [r for r in runs if r["row"] in MISSES]
        met = sum(1 for r in miss if r["p95"] is not None and r["p95"] <= 15.0)
        never = sum(1 for r in runs if r["p95"] is None)
        extra = ""
        passes = [r for r in runs if r["row"] in PASSES]
        if passes:
            kept = sum(1 for r in passes if r["p95"] is not None and r["p95"] <= 15.0)
            extra = f"; of {len(passes)} that passed, {kept} still pass"
        others = [r for r in runs if r["row"] not in MISSES and r["row"] not in PASSES]
        if others:
            met_o = sum(1 for r in others if r["p95"] is not None and r["p95"] <= 15.0)
            extra += (f"; of the {len(others)} draws {', '.join(str(r['row']) for r in others)}, {met_o} meet "
                      "the p95")
        lines.append(f"- {case['label']}: p95 ≤ 15° in **{met} of {len(miss)}** misses{extra}; "
                     f"{never} of {len(runs)} never acquire (the error never stays below 30°)")
    return "\n".join(lines) + "\n"


def _p95_cell(run: dict) -> str:
    return "never acquired" if run["p95"] is None else f"{run['p95']:.2f}"


def margin_markdown(table: dict) -> str:
    """The margin screen's table (p95 in deg per draw: the committed campaign's, then each candidate's) and, per
    candidate and plant, the counts: p95 ≤ 15° and ≤ 14° (a degree of margin) among the near-misses and among the
    random passes, the largest p95, the median change against the committed rows, the median tail (s); then how
    closely the baseline ("as_committed") flown again gave the committed rows."""
    import statistics

    cases = [c for c in table["candidates"] if c["key"] != "as_committed"]
    base = next((c for c in table["candidates"] if c["key"] == "as_committed"), None)
    if not cases:
        raise ValueError("no candidate flown")
    lines = ["| plant | draw (seed index) | p95 (deg) as committed | " + " | ".join(c["label"] for c in cases) + " |",
             "|---|---|---|" + "---|" * len(cases)]
    for plant, rows in table["draws"].items():
        for row in rows:
            runs = [next(r for r in c["runs"][plant] if r["row"] == row) for c in cases]
            kind = "" if row in MARGIN_NEAR[plant] else " (random pass)"
            lines.append(f"| {MARGIN_PLANT_NAMES[plant]} | {row}{kind} | {runs[0]['committed']['p95']:.2f} | "
                         + " | ".join(_p95_cell(r) for r in runs) + " |")
    lines.append("")
    for c in cases:
        for plant, runs in c["runs"].items():
            near = [r for r in runs if r["row"] in MARGIN_NEAR[plant]]
            others = [r for r in runs if r["row"] not in MARGIN_NEAR[plant]]

            def count(rs, limit):
                return sum(1 for r in rs if r["p95"] is not None and r["p95"] <= limit)

            flown = [r for r in runs if r["p95"] is not None]
            worst = "—" if not flown else f"{max(r['p95'] for r in flown):.2f}°"
            change = [r["p95"] - r["committed"]["p95"] for r in flown]
            tails = [t for t in (_tail(r) for r in flown) if t is not None]
            later = sum(1 for r in flown if r["acquisition_s"] > r["committed"]["acquisition_s"] + MARGIN_LATER_S)
            acquired = [r["acquisition_s"] for r in flown]
            lines.append(
                f"- {c['label']}, {MARGIN_PLANT_NAMES[plant]}: near-misses p95 ≤ 15° in **{count(near, 15.0)} of "
                f"{len(near)}**, ≤ 14° in {count(near, 14.0)}; random passes ≤ 15° in {count(others, 15.0)} of "
                f"{len(others)}; largest p95 {worst}; p95 change against the committed rows "
                f"{_f(statistics.median(change) if change else None, '+.2f')}° at the median; tail above 15° "
                f"{_f(statistics.median(tails) if tails else None, '.0f')} s at the median; acquisition below 30° "
                f"{statistics.median(r['committed']['acquisition_s'] for r in runs):.0f} → "
                f"{_f(statistics.median(acquired) if acquired else None, '.0f')} s at the median, over "
                f"{MARGIN_LATER_S:.0f} s later in **{later}**; the runs' median error "
                f"{statistics.median(r['committed']['median'] for r in runs):.2f} → "
                f"{_f(statistics.median(r['median'] for r in flown) if flown else None, '.2f')}° at the median; "
                f"{len(runs) - len(flown)} of {len(runs)} never acquire")
    lines.append("")
    if base is not None:
        flown = [r for runs in base["runs"].values() for r in runs]
        diffs = [abs(r["p95"] - r["committed"]["p95"]) for r in flown if r["p95"] is not None]
        named = ", ".join(f"{MARGIN_PLANT_NAMES[p]} {', '.join(str(r['row']) for r in rs)}"
                          for p, rs in base["runs"].items())
        lines.append(f"The baseline flown again by this script ({named}): {len(diffs)} of {len(flown)} acquire"
                     + (f", their p95 within {max(diffs):.1e}° of the committed campaigns' rows. " if diffs
                        else ". "))
    lines[-1] += (f"Draws: each plant's near-misses, then {MARGIN_RANDOM} passes drawn with seed {table['seed']} "
                  "(`margin_draws`).")
    return "\n".join(lines) + "\n"


def markdown(table: dict) -> str:
    return floquet_markdown(table) + "\n" + draws_markdown(table)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", required=True, help="write the figures here")
    ap.add_argument("--part", choices=("all", "floquet", "draws", "margin"), default="all",
                    help="margin: the 40° hold's margin screen, into its own file (not part of all)")
    ap.add_argument("--case", choices=[key for key, *_ in (*CASES, *MARGIN_CANDIDATES)],
                    help="with --part draws or margin: fly only this case, keeping the file's others")
    args = ap.parse_args(argv)
    path = pathlib.Path(args.json)
    if args.part == "margin":
        old = json.loads(path.read_text(encoding="utf-8")) if args.case and path.exists() else None
        screen = margin(args.case, old)
        if args.case and path.exists():  # keep candidates written meanwhile by another process, in the screen's order
            have = {c["key"]: c for c in json.loads(path.read_text(encoding="utf-8"))["candidates"]}
            have.update({c["key"]: c for c in screen["candidates"]})
            screen["candidates"] = [have[k] for k, *_ in MARGIN_CANDIDATES if k in have]
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(screen, indent=1) + "\n", encoding="utf-8")
        if any(c["key"] != "as_committed" for c in screen["candidates"]):
            print(margin_markdown(screen))
        return 0
    if args.part in ("all", "floquet"):
        fl = floquet()
    if args.part in ("all", "draws"):
        old = json.loads(path.read_text(encoding="utf-8")).get("draws") if args.case and path.exists() else None
        dr = draws(args.case, old)
    # read what is there only now (another part may have been written meanwhile), then replace this part
    table = json.loads(path.read_text(encoding="utf-8")) if path.exists() and args.part != "all" else {}
    if args.part in ("all", "floquet"):
        table["floquet"] = fl
    if args.part in ("all", "draws"):
        if args.case and table.get("draws"):  # keep cases flown meanwhile by another process
            mine = {c["key"]: c for c in dr["cases"]}
            have = {c["key"]: c for c in table["draws"]["cases"]}
            dr = {"cases": [mine.get(k) or have.get(k) for k, _, _, _ in CASES if k in mine or k in have]}
        table["draws"] = dr
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(table, indent=1) + "\n", encoding="utf-8")
    if "floquet" in table and "draws" in table:
        print(markdown(table))
    return 0


if __name__ == "__main__":
    sys.exit(main())


def campaign_markdown(base, new, label: str) -> str:
    """A candidate's campaign (``new``, results of the first N draws) against the committed campaign's same draws
    (``base``, paired on the seed index): per run p95, acquisition and tail, then the counts."""
    import pandas as pd

    def tail(df):
        return df["pointing_acquisition_15deg_s"] - df["pointing_acquisition_s"]

    b = base.assign(tail=tail(base)).set_index("seed_index")
    n = new.assign(tail=tail(new)).set_index("seed_index")
    wrong = [int(i) for i in n.index if i not in b.index or int(b.loc[i, "seed"]) != int(n.loc[i, "seed"])]
    if wrong:
        raise ValueError(f"seed indices {wrong}: not the committed campaign's draws (another seed): nothing to pair")
    lines = ["| draw (seed index) | p95 (deg): as committed → " + label + " | median (deg) | acquisition < 30° (s) | "
             "tail above 15° (s) |", "|---|---|---|---|---|"]

    def cell(x, fmt):
        return "—" if x is None or pd.isna(x) else format(float(x), fmt)

    met_b = met_n = never = med_n = 0
    for i in sorted(n.index):
        rb, rn = b.loc[i], n.loc[i]
        acquired = rn["status"] == "ok" and not pd.isna(rn["pointing_p95_deg"])
        never += 0 if acquired else 1
        met_b += int(rb["pointing_p95_deg"] <= 15.0)
        met_n += int(acquired and rn["pointing_p95_deg"] <= 15.0)
        med_n += int(acquired and rn["pointing_median_deg"] <= 5.0)
        p95_n = cell(rn["pointing_p95_deg"], ".1f") if acquired else "never acquired"
        lines.append(f"| {i} | {rb['pointing_p95_deg']:.1f} → {p95_n} | {cell(rb['pointing_median_deg'], '.2f')} → "
                     f"{cell(rn['pointing_median_deg'], '.2f')} | {cell(rb['pointing_acquisition_s'], '.0f')} → "
                     f"{cell(rn['pointing_acquisition_s'], '.0f')} | {cell(rb['tail'], '.0f')} → "
                     f"{cell(rn['tail'], '.0f')} |")
    lines += ["", f"{len(n)} draws: p95 ≤ 15° in **{met_b}/{len(n)}** as committed, **{met_n}/{len(n)}** with "
              f"{label}; median ≤ 5° in {med_n}/{len(n)}; never acquired (the error never stays below 30° to the "
              f"orbit's end): {never}."]
    return "\n".join(lines) + "\n"
