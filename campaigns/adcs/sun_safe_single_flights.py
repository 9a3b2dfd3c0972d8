"""The single flights whose figures docs/studies/sun_safe.md's prose quotes, each part one table of the page.

* ``bias``: SUN_SAFE's gyro-bias observer (``control.sun_safe.SunRateBias``) on the wheels, plant-only
  (``detumble.sim.sun_safe_check.fly``, issue 27's 2 °/s tumble, the star tracker off), seeds 1–5 flown for
  :data:`BIAS_S` s: its estimate at the end against the gyro's true bias (deg/s, body frame B), and the error's part
  across the true Sun line (the part along it is not observable);
* ``lit``: the light sensors' lit threshold (a face lit above that fraction of the full Sun; the ADCS component's
  SUN_LIT_FRACTION, 2 % by default) at 5 % (the first version's) and 2 %, seed 1 on the wheels, the first
  :data:`LIT_S` s: the Sun vector's error against the truth at each sunlit reading (deg);
* ``coil_gains``: the coils' spinning Sun-safe with its damping and tip gains changed (SUN_SAFE_K_D_MAG for a
  transverse time constant ``I_t / k``, SUN_SAFE_K_P_MAG with it so the tip rate's gain ``K_P / K_D`` is unchanged;
  SUN_SAFE_K_P_MAG × 5 for a 5× faster tip), seed 2 on the coils over the first sunlit part (0–2809 s), the spin held
  at 3 °/s (SUN_HOLD_ANGLE 0, as when these were first tried): acquisition, and over the part's last
  :data:`TAIL_S` s the true error (deg) and the body rate across +Z (deg/s);
* ``tracker_limit``: seed N's 2 °/s and 1.9 °/s draws (``sun_safe_check.seed_settings``) against the star tracker's
  smear limit (``max_rate_deg_s`` 2 °/s, compared as ``|ω|² > limit²`` in rad²/s²): the excess at t = 0 (from the
  scenario's initial rate, no flight), and whether adcs_ref accepted the hand-back sequence's FORCE_MODE POINTING at
  1 s (a 1.5 s ``fprime-lite run`` each, ``campaigns/adcs/sun_safe_coil_runs.py``'s ``hand_back`` flights cut short);
* ``bounce``: tests/test_adcs_deployment.py ADCS-109's flight (seed 1's 2 °/s tumble, the coils, SUN_SPIN_RATE
  1.5 °/s, the tracker out 20–400 s) flown to :data:`BOUNCE_S` s: its modes, the true attitude error from
  POINTING's target at the hand-back (deg) and the true body rate |ω| (deg/s, ``truth.csv``) then and after it.

    python campaigns/adcs/sun_safe_single_flights.py [--json FILE] [--only PART ...]

``--only`` flies the named parts again and keeps the others as the ``--json`` file holds them.

The adcs_ref flights on the coils (``tracker_limit``, ``bounce``) pin the coils' hold as it was flown, field steering
on the raw magnetometer reading, the default before 2026-12-05 (MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0 sent at 00:00:00:
``sun_safe_coil_runs.FIELD_STEERING_HOLD``); ADCS-109's flight as the test flies it today uses the new defaults
(the on-board bias estimate from the tracker's fixes before the outage, the LQR below 50°). The plant-only flights
(``sun_safe_check.fly``) have no star tracker, so no bias estimate and no POINTING: the defaults' change does not
reach them.

11 plant-only flights (~22,000 simulated s), 11 short adcs_ref runs and one of an orbit: about a minute and a half
on this machine.
:func:`probe` (``tools/studies.py --check``) recomputes the t = 0 excesses and re-flies the ``lit`` and ``bounce``
parts (seconds) and compares them with the committed file to the float.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import statistics
import subprocess
import sys
import tempfile

from detumble.sim.scenario import load_scenario
from detumble.sim.sun_safe_check import POINTING_THRESHOLD_DEG, _percentile, fly, seed_settings

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
_CONTROLLER = "ReferenceDeployment.attitudeController"
BIAS_S = 900.0
BIAS_SEEDS = (1, 2, 3, 4, 5)
LIT_S = 600.0
LIT_SEED = 1
#: lit thresholds flown (fraction of the full Sun): the first version's, then the default
LIT_FRACTIONS = (0.05, 0.02)
COIL_SEED = 2
FIRST_PART_S = 2810.0  # s: the first sunlit part is 0–2809 s
TAIL_S = 1000.0
TRACKER_RATES = (2.0, 1.9)
TRACKER_SEEDS = (1, 2, 3, 4, 5)
TRACKER_LIMIT_DEG_S = 2.0
BOUNCE_S = 500.0
#: ADCS-109's sequence (tests/test_adcs_deployment.py ``_tracker_loss_flight`` at 1.5 °/s) with the coils' hold of
#: before 2026-12-05 pinned (the first two lines: sun_safe_coil_runs.FIELD_STEERING_HOLD)
BOUNCE_SEQUENCE = (f"R00:00:00 {_CONTROLLER}.MAG_BIAS_TIME_PRM_SET 0.0\n"
                   f"R00:00:00 {_CONTROLLER}.MAG_LQR_ANGLE_PRM_SET 0.0\n"
                   f"R00:00:00 {_CONTROLLER}.POINTING_ACTUATOR_PRM_SET MAGNETORQUERS\n"
                   f"R00:00:00 {_CONTROLLER}.SUN_SPIN_RATE_PRM_SET 1.5\n"
                   f"R00:00:00 {_CONTROLLER}.SET_TARGET_QUATERNION 0.9238795325112867 0 0.3826834323650898 0\n"
                   f"R00:00:01 {_CONTROLLER}.FORCE_MODE POINTING\n")
BOUNCE_SETTINGS = ("sensors.star_tracker.outage_s=[20,400]",)
ORBIT_S = 5580.0
ALBEDO = 0.3


def _coil_variants() -> dict:
    """key → (label, parameters): the transverse time constants from the scenario's inertia across +Z (kg·m²)."""
    from detumble.control.attitude_defaults import DEFAULTS

    inertia = load_scenario("adcs").spacecraft.inertia_kg_m2
    i_t = (inertia[0][0] + inertia[1][1]) / 2.0
    kd, kp = DEFAULTS["SUN_SAFE_K_D_MAG"], DEFAULTS["SUN_SAFE_K_P_MAG"]
    out = {"default": (f"the defaults (SUN_SAFE_K_D_MAG {kd:g} N·m·s: τ = {i_t / kd:.1f} s)", {})}
    for tau in (20.0, 60.0):
        k = i_t / tau
        out[f"tau_{tau:g}"] = (f"τ = {tau:g} s (SUN_SAFE_K_D_MAG {k:.3g}, SUN_SAFE_K_P_MAG {kp * k / kd:.3g})",
                               {"SUN_SAFE_K_D_MAG": k, "SUN_SAFE_K_P_MAG": kp * k / kd})
    out["tip_5"] = (f"tip 5× faster (SUN_SAFE_K_P_MAG {5 * kp:g})", {"SUN_SAFE_K_P_MAG": 5 * kp})
    return out


def fly_bias() -> dict:
    rows = []
    for seed in BIAS_SEEDS:
        r = fly(seed, duration_s=BIAS_S)
        est, true, s = r.bias_estimate_deg_s, r.bias_true_deg_s, r.sun_body_end
        err = [e - t for e, t in zip(est, true, strict=True)]
        along = sum(e * c for e, c in zip(err, s, strict=True))
        across = math.sqrt(max(0.0, sum(e * e for e in err) - along * along))
        rows.append({"seed": seed, "estimate_deg_s": list(est), "true_deg_s": list(true), "sun_B": list(s),
                     "error_across_sun_deg_s": across, "error_along_sun_deg_s": along})
    return {"duration_s": BIAS_S, "rows": rows}


def fly_lit() -> dict:
    rows = []
    for fraction in LIT_FRACTIONS:
        r = fly(LIT_SEED, duration_s=LIT_S, lit_fraction=fraction)
        v = r.vector_deg
        rows.append({"lit_fraction": fraction, "readings": len(v), "invalid": r.vector_invalid_sunlit,
                     "median_deg": statistics.median(v), "max_deg": max(v)})
    return {"seed": LIT_SEED, "duration_s": LIT_S, "rows": rows}


def fly_coil_gains(keys=None) -> dict:
    """The coil variants ``keys`` (default: all) on seed COIL_SEED (see the module's docstring)."""
    rows = []
    for key, (label, params) in _coil_variants().items():
        if keys is not None and key not in keys:
            continue
        r = fly(COIL_SEED, duration_s=FIRST_PART_S, actuator="MAGNETORQUERS",
                params={"SUN_HOLD_ANGLE": 0.0, **params})
        part = r.first_sunlit_part()
        assert part is not None
        keep = [i for i, t in enumerate(r.times) if part[1] - TAIL_S <= t < part[1]]
        err = [r.pointing_deg[i] for i in keep]
        trans = [r.transverse_deg_s[i] for i in keep]
        rows.append({"key": key, "label": label, "params": params, "acquisition_s": r.acquisition_s(),
                     "first_sunlit_part_s": list(part),
                     "tail_error_deg": {"median": statistics.median(err), "p95": _percentile(err, 95),
                                        "max": max(err)},
                     "tail_transverse_deg_s": {"median": statistics.median(trans), "max": max(trans)}})
        print(f"coil_gains {key}: flown", file=sys.stderr, flush=True)
    return {"seed": COIL_SEED, "duration_s": FIRST_PART_S, "tail_s": TAIL_S, "rows": rows}


def tracker_excess(seed: int, rate_deg_s: float) -> float:
    """|ω|² − limit² at t = 0 (rad²/s²) of seed ``seed``'s ``rate_deg_s`` draw, as the star tracker compares them."""
    sc = load_scenario("adcs", seed=seed, settings=seed_settings(seed, rate_deg_s))
    w = sc.omega_BN_B0
    return (w[0] ** 2 + w[1] ** 2 + w[2] ** 2) - math.radians(TRACKER_LIMIT_DEG_S) ** 2


def _run(out: pathlib.Path, duration_s: float, sequence: str, settings, seed: int | None = None) -> None:
    """One ``fprime-lite run`` of adcs_ref into ``out`` (``seed`` None: the topology's own)."""
    seq = out.parent / f"{out.name}.seq"
    seq.write_text(sequence)
    cmd = [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(TOPOLOGY), "--duration", f"{duration_s:g}",
           "--seq", str(seq), "--out", str(out), "--no-progress", "--no-plots", "--allow-warnings"]
    if seed is not None:
        cmd += ["--seed", str(seed)]
    for s in settings:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)


def _sibling(name: str):
    """The study script ``name`` of campaigns/adcs/ as a module."""
    from detumble.reports.study_table import sibling_script

    return sibling_script(pathlib.Path(__file__).resolve().parent, name)


def _transitions(run_dir: pathlib.Path) -> list[dict]:
    """The run's mode changes, as ``campaigns/adcs/sun_safe_coil_runs.py`` reads them from its events.log."""
    return _sibling("sun_safe_coil_runs")._transitions(run_dir)


def fly_tracker_limit() -> dict:
    coil_runs = _sibling("sun_safe_coil_runs")
    hand_back = coil_runs.with_params((ROOT / "campaigns" / "adcs" / "sun_safe_hand_back.seq").read_text(),
                                      coil_runs.FIELD_STEERING_HOLD)
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for rate in TRACKER_RATES:
            for seed in TRACKER_SEEDS:
                out = pathlib.Path(scratch) / f"r{rate:g}_s{seed}"
                _run(out, 1.5, hand_back, [*seed_settings(seed, rate), "sensors.star_tracker.outage_s=[20,3000]"],
                     seed)
                refused = "NoAttitudeKnowledge" in (out / "events.log").read_text()
                rows.append({"seed": seed, "rate_deg_s": rate, "excess_rad2_s2": tracker_excess(seed, rate),
                             "pointing_accepted": not refused,
                             "modes": [t["mode"] for t in _transitions(out)]})
    return {"limit_deg_s": TRACKER_LIMIT_DEG_S, "rows": rows}


def fly_bounce() -> dict:
    import csv

    with tempfile.TemporaryDirectory() as scratch:
        out = pathlib.Path(scratch) / "bounce"
        _run(out, BOUNCE_S, BOUNCE_SEQUENCE, [*seed_settings(1, 2.0), *BOUNCE_SETTINGS])
        modes = _transitions(out)
        with open(out / "truth.csv", newline="") as f:
            rows = [(float(r["t_s"]), float(r["rate_deg_s"]), r["pointing_error_deg"])
                    for r in csv.DictReader(f)]
    rates = [(t, w) for t, w, _ in rows]
    back = [m["t_s"] for m in modes if m["mode"] == "POINTING" and m["reason"] == "KNOWLEDGE_RESTORED"]
    t_back = back[0] if back else None
    after = [(t, w) for t, w in rates if t_back is not None and t >= t_back]
    peak = max(after, key=lambda tw: tw[1]) if after else None
    error = next((float(e) for t, _, e in rows if t_back is not None and t >= t_back and e), None)
    return {"duration_s": BOUNCE_S, "modes": modes, "hand_back_s": t_back,
            "rate_at_hand_back_deg_s": after[0][1] if after else None, "error_at_hand_back_deg": error,
            "rate_at_end_deg_s": rates[-1][1], "end_s": rates[-1][0],
            "peak_after_deg_s": None if peak is None else peak[1], "peak_after_s": None if peak is None else peak[0]}


def _spans(seconds: list[int]) -> list[list[int]]:
    """Consecutive runs of whole seconds, ``[[first, last], ...]``."""
    spans: list[list[int]] = []
    for k in seconds:
        if spans and k == spans[-1][1] + 1:
            spans[-1][1] = k
        else:
            spans.append([k, k])
    return spans


def fly_albedo_flight() -> dict:
    """adcs_ref's AUTO flight with albedo 0.3 in the sensors and the correction on (the albedo-deployment table's
    first row, ``campaigns/adcs/sun_albedo_deployment.py``): where the corrected vector is beyond 5°, the sunlit
    seconds it was not corrected, and the AlbedoCorrectionUnavailable events."""
    import csv

    from detumble.sim.sun_safe_check import VECTOR_THRESHOLD_DEG, vector_errors_by_second

    deployment = _sibling("sun_albedo_deployment")
    with tempfile.TemporaryDirectory() as scratch:
        out = pathlib.Path(scratch) / "albedo"
        deployment.fly(ALBEDO, ORBIT_S, out)
        timed, invalid = vector_errors_by_second(out)
        corrected, t0 = {}, None
        with open(out / "channels.csv", newline="") as f:
            for row in csv.DictReader(f):
                if row["channel"].endswith(".adcs.AlbedoCorrected"):
                    stamp = float(row["time"])
                    t0 = stamp if t0 is None else t0
                    corrected[int(round(stamp - t0))] = row["value"] == "1"
        events = (out / "events.log").read_text().splitlines()
    beyond = [(k, e) for k, e in timed if e > VECTOR_THRESHOLD_DEG]
    return {"albedo": ALBEDO, "duration_s": ORBIT_S, "readings": len(timed), "invalid": invalid,
            "beyond": len(beyond), "beyond_max_deg": max((e for _, e in beyond), default=None),
            "beyond_from_s": min((k for k, _ in beyond), default=None),
            "beyond_to_s": max((k for k, _ in beyond), default=None),
            "uncorrected_spans_s": _spans([k for k, _ in timed if not corrected.get(k, False)]),
            "unavailable_events": sum(".adcs.AlbedoCorrectionUnavailable " in ln for ln in events)}


PARTS = {"bias": fly_bias, "lit": fly_lit, "coil_gains": fly_coil_gains, "tracker_limit": fly_tracker_limit,
         "bounce": fly_bounce, "albedo_flight": fly_albedo_flight}


def _part(table: dict, key: str) -> dict:
    part = table.get("parts", {}).get(key)
    if part is None:
        raise ValueError(f"part {key!r} is missing: fly the script again")
    return part


def _vec(v) -> str:
    return "(" + ", ".join(f"{x:.3f}" for x in v) + ")"


def bias_markdown(table: dict) -> str:
    part = _part(table, "bias")
    lines = [f"| seed | estimate after {part['duration_s']:.0f} s (°/s, B) | true bias (°/s, B) | error across the "
             "Sun line (°/s) | along it (°/s, not observable) |", "|---|---|---|---|---|"]
    for r in part["rows"]:
        lines.append(f"| {r['seed']} | {_vec(r['estimate_deg_s'])} | {_vec(r['true_deg_s'])} | "
                     f"{r['error_across_sun_deg_s']:.4f} | {r['error_along_sun_deg_s']:+.3f} |")
    return "\n".join(lines) + "\n"


def lit_markdown(table: dict) -> str:
    part = _part(table, "lit")
    lines = [f"| lit threshold (of the full Sun) | seed {part['seed']}, first {part['duration_s']:.0f} s: Sun vector "
             "median / max error (deg) | sunlit readings (invalid) |", "|---|---|---|"]
    for r in part["rows"]:
        name = f"{100 * r['lit_fraction']:g} %" + (" (the default)" if r["lit_fraction"] == 0.02 else
                                                    " (the first version)" if r["lit_fraction"] == 0.05 else "")
        lines.append(f"| {name} | {r['median_deg']:.2f} / {r['max_deg']:.2f} | {r['readings']} ({r['invalid']}) |")
    return "\n".join(lines) + "\n"


def coil_gains_markdown(table: dict) -> str:
    part = _part(table, "coil_gains")
    lines = [f"| seed {part['seed']}, the spin held at 3 °/s | acquisition ≤ {POINTING_THRESHOLD_DEG:g}° (s) | last "
             f"{part['tail_s']:.0f} s of the first sunlit part: error median / p95 / max (deg) | rate across +Z "
             "median / max (°/s) |", "|---|---|---|---|"]
    for r in part["rows"]:
        acq = "never" if r["acquisition_s"] is None else f"{r['acquisition_s']:.0f}"
        e, w = r["tail_error_deg"], r["tail_transverse_deg_s"]
        lines.append(f"| {r['label']} | {acq} | {e['median']:.1f} / {e['p95']:.1f} / {e['max']:.1f} | "
                     f"{w['median']:.2f} / {w['max']:.2f} |")
    return "\n".join(lines) + "\n"


def tracker_limit_markdown(table: dict) -> str:
    part = _part(table, "tracker_limit")
    rates = sorted({r["rate_deg_s"] for r in part["rows"]}, reverse=True)
    lines = ["| seed | " + " | ".join(f"{rate:g} °/s: \\|ω\\|² − ({part['limit_deg_s']:g} °/s)² at t = 0 (rad²/s²); "
                                       "POINTING at 1 s" for rate in rates) + " |", "|---" * (1 + len(rates)) + "|"]
    for seed in sorted({r["seed"] for r in part["rows"]}):
        cells = []
        for rate in rates:
            r = next(x for x in part["rows"] if x["seed"] == seed and x["rate_deg_s"] == rate)
            cells.append(f"{r['excess_rad2_s2']:.2g}; " + ("accepted" if r["pointing_accepted"] else
                                                           "**refused** (NoAttitudeKnowledge)"))
        lines.append(f"| {seed} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def bounce_markdown(table: dict) -> str:
    part = _part(table, "bounce")
    modes = ", ".join(f"{m['mode']} ({m['reason']}) {m['t_s']:.1f} s" for m in part["modes"])
    if part["hand_back_s"] is None:
        return f"ADCS-109's flight to {part['duration_s']:.0f} s: {modes}; no hand-back to POINTING\n"
    return (f"ADCS-109's flight to {part['duration_s']:.0f} s: {modes}; at the hand-back the true attitude error from "
            f"POINTING's target {part['error_at_hand_back_deg']:.0f}° and true \\|ω\\| "
            f"{part['rate_at_hand_back_deg_s']:.2f} °/s, largest after it {part['peak_after_deg_s']:.2f} °/s at "
            f"{part['peak_after_s']:.0f} s, {part['rate_at_end_deg_s']:.2f} °/s at {part['end_s']:.0f} s\n")


def albedo_flight_markdown(table: dict) -> str:
    part = _part(table, "albedo_flight")
    spans = ", ".join(f"{a}–{b} s ({b - a + 1} s)" for a, b in part["uncorrected_spans_s"]) or "none"
    where = ("none" if not part["beyond"] else f"{part['beyond']}, max {part['beyond_max_deg']:.1f}°, all at "
             f"{part['beyond_from_s']}–{part['beyond_to_s']} s")
    return (f"adcs_ref's AUTO flight, {part['duration_s']:.0f} s, albedo {part['albedo']:g} in the sensors, the "
            f"correction on: {part['readings']} sunlit SunVector readings ({part['invalid']} invalid); beyond 5°: "
            f"{where}; sunlit readings not corrected (AlbedoCorrected 0): {spans}; AlbedoCorrectionUnavailable "
            f"events: {part['unavailable_events']}\n")


def markdown(table: dict) -> str:
    return "\n".join(f(table) for f in (bias_markdown, lit_markdown, coil_gains_markdown, tracker_limit_markdown,
                                        bounce_markdown, albedo_flight_markdown))


def differences(now, then, where: str = "") -> list[str]:
    """Where ``now`` and ``then`` (JSON values) differ, to the float: ``"where: now, then committed"`` each."""
    if isinstance(now, dict) and isinstance(then, dict) and set(now) == set(then):
        return [d for k in now for d in differences(now[k], then[k], f"{where}.{k}" if where else k)]
    if isinstance(now, list) and isinstance(then, list) and len(now) == len(then):
        return [d for i, (a, b) in enumerate(zip(now, then, strict=True)) for d in differences(a, b, f"{where}[{i}]")]
    return [] if now == then else [f"{where}: {now!r} now, {then!r} committed"]


def probe(committed: dict) -> list[str]:
    """The t = 0 excesses recomputed, the ``lit`` and ``bounce`` parts flown again (seconds), against the committed
    file to the float: the differences found (empty: none)."""
    found = []
    for r in _part(committed, "tracker_limit")["rows"]:
        now = tracker_excess(r["seed"], r["rate_deg_s"])
        if now != r["excess_rad2_s2"]:
            found.append(f"seed {r['seed']} at {r['rate_deg_s']:g} °/s: excess {now!r} now, "
                         f"{r['excess_rad2_s2']!r} committed")
    for key in ("lit", "bounce"):
        found += differences(json.loads(json.dumps(PARTS[key]())), _part(committed, key), key)
    return found


def _results(args: argparse.Namespace) -> dict:
    """The parts flown (``--only``: those, the others kept as the ``--json`` file holds them)."""
    kept: dict = {}
    if args.only:
        if args.json is None or not args.json.exists():
            raise SystemExit("--only needs --json FILE, an existing file whose other parts are kept")
        kept = json.loads(args.json.read_text(encoding="utf-8"))["parts"]
    parts = {k: (f() if not args.only or k in args.only else kept[k]) for k, f in PARTS.items()}
    return {"script": "campaigns/adcs/sun_safe_single_flights.py", "parts": parts}


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import table_script_main

    def only(parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--only", nargs="+", choices=sorted(PARTS), metavar="PART",
                            help="fly these parts only, keeping the others as --json's FILE holds them")

    return table_script_main(argv, __doc__.split("\n\n")[0], _results, markdown, only)


if __name__ == "__main__":
    sys.exit(main())
