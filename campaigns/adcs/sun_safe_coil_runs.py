"""SUN_SAFE on the magnetorquers through deployments/adcs_ref: the coil tables of docs/studies/sun_safe.md
("Magnetorquers through adcs_ref" and "Handing back with no operator"), each row one ``fprime-lite run`` of seed N.

Three kinds of flight, each from seed N's tumble and attitude (``detumble.sim.sun_safe_check.seed_settings``, the
draws the plant-only check flies) for ``--duration`` s (one orbit):

* ``command``: ``campaigns/adcs/sun_safe_magnetorquers.seq`` (POINTING_ACTUATOR MAGNETORQUERS, FORCE_MODE SUN_SAFE
  at 0 s), the star tracker off (``sensors.star_tracker.dropout_probability=1.0``), a 2 °/s tumble (issue 27's);
* ``operator``: ``campaigns/adcs/sun_safe_tracker_loss.seq`` (POINTING on the coils at 1 s, the ground's
  SUN_SPIN_RATE_PRM_SET 1.5 at 2900 s), the tracker out 20–3000 s, a 1.9 °/s tumble;
* ``hand_back``: ``campaigns/adcs/sun_safe_hand_back.seq`` (the same without the ground step: the automatic
  spin-down), the tracker out 20–3000 s, a 1.9 °/s tumble;
* ``hand_back_hold_1_9``: ``hand_back`` with the hold spin raised to 1.9 °/s (``SUN_HOLD_SPIN_RATE_PRM_SET 1.9``
  sent at 00:00:00, before the sequence's first command: :data:`PARAMS`), the candidate fix for the eclipse that
  the hold costs (sun_safe.md, "The hold costs the eclipse");
* ``hand_back_2_deg_s``: ``hand_back`` from seed N's draws at 2 °/s (issue 27's tumble), to show why the tracker-loss
  kinds fly 1.9 °/s (below).

Why 1.9 °/s for the two tracker-loss kinds: their premise is POINTING with a tracker fix before the FORCE_MODE
POINTING at 1 s, and at 2 °/s the tumble sits on the tracker's 2 °/s smear limit, where whether a fix comes is
decided by the last bit of |ω| and by the drawn axis (seed 5 gets none: ``sun_safe_check.HAND_BACK_RATE_DEG_S``).

    python campaigns/adcs/sun_safe_coil_runs.py KIND [--seeds N] [--duration S] [--json FILE]

Prints the kind's table (markdown); ``--json`` keeps its figures and, for the probe STUDY-060, the true Sun-pointing
error of seed 1's first :data:`PROBE_S` seconds (re-flown by tests/test_studies.py in seconds).

Every kind flies the coils' POINTING as the field-steering hold on the raw magnetometer reading, the default before
2026-12-05, pinned (:data:`FIELD_STEERING_HOLD`: MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0, sent at 00:00:00 before the
sequence's first command and before the kind's own :data:`PARAMS`): since 2026-12-05 the coils' default takes the
field through an on-board bias estimate made while the tracker gives an attitude (in every mode, SUN_SAFE too) and
holds with the LQR below 50°, which would change the tracker-loss kinds; the tables document Sun-safe as flown.
``command`` (no tracker at all: no estimate) is pinned too, for one configuration. The JSON's ``params`` keeps the
kind's own parameters only.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

from detumble.sim.sun_safe_check import (HAND_BACK_RATE_DEG_S, POINTING_THRESHOLD_DEG, _percentile, _slow_from,
                                         pointing_from_run, seed_settings, vector_errors_from_run)

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
_OUTAGE = "sensors.star_tracker.outage_s=[20,3000]"
#: kind → (sequence under campaigns/adcs/, tumble deg/s, extra --set lines, default seeds)
KINDS = {"command": ("sun_safe_magnetorquers.seq", 2.0, ("sensors.star_tracker.dropout_probability=1.0",), 3),
         "operator": ("sun_safe_tracker_loss.seq", HAND_BACK_RATE_DEG_S, (_OUTAGE,), 3),
         "hand_back": ("sun_safe_hand_back.seq", HAND_BACK_RATE_DEG_S, (_OUTAGE,), 5),
         "hand_back_hold_1_9": ("sun_safe_hand_back.seq", HAND_BACK_RATE_DEG_S, (_OUTAGE,), 5),
         "hand_back_2_deg_s": ("sun_safe_hand_back.seq", 2.0, (_OUTAGE,), 5)}
#: kind → AttitudeController parameters set by command at 00:00:00, before the sequence's first command
PARAMS = {"hand_back_hold_1_9": (("SUN_HOLD_SPIN_RATE", "1.9"),)}
#: every kind's coil hold, pinned (sent before PARAMS): field steering on the raw reading, the defaults before
#: 2026-12-05 (no on-board bias estimate, no model-scheduled LQR; MAG_FIELD_MODEL_DEGREE is then unused)
FIELD_STEERING_HOLD = (("MAG_BIAS_TIME", "0.0"), ("MAG_LQR_ANGLE", "0.0"))
_CONTROLLER = "ReferenceDeployment.attitudeController"
#: s of seed 1's flight whose pointing errors are kept for the probe
PROBE_S = 120


def with_params(sequence: str, params: tuple[tuple[str, str], ...]) -> str:
    """``sequence`` (a .seq file's text) with one ``R00:00:00 <controller>.NAME_PRM_SET VALUE`` line per parameter
    put before its first command: relative times, so the rest of the sequence keeps its times."""
    lines = sequence.splitlines()
    first = next((i for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith(";")), len(lines))
    sets = [f"R00:00:00 {_CONTROLLER}.{name}_PRM_SET {value}" for name, value in params]
    return "\n".join(lines[:first] + sets + lines[first:]) + "\n"


def fly(kind: str, seed: int, duration_s: float, out: pathlib.Path) -> None:
    """One ``fprime-lite run`` of adcs_ref into ``out``: ``kind``'s sequence with :data:`FIELD_STEERING_HOLD` and
    its :data:`PARAMS` sent first, its settings, seed ``seed``'s draws."""
    seq, rate, extra, _ = KINDS[kind]
    sets = [*seed_settings(seed, rate), *extra]
    seq_path = out.parent / f"{out.name}.seq"
    seq_path.write_text(with_params((ROOT / "campaigns" / "adcs" / seq).read_text(),
                                    (*FIELD_STEERING_HOLD, *PARAMS.get(kind, ()))))
    cmd = [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(TOPOLOGY), "--duration", f"{duration_s:g}",
           "--seq", str(seq_path), "--seed", str(seed), "--out", str(out),
           "--no-progress", "--no-plots", "--allow-warnings"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)


def _transitions(run_dir: pathlib.Path) -> list[dict]:
    """``[{"t_s", "mode", "reason"}]`` from the run's ControlModeChanged events (events.log), s from the epoch."""
    import datetime

    from detumble.sim.scenario import load_scenario

    epoch = load_scenario("adcs").epoch
    out = []
    for line in (run_dir / "events.log").read_text().splitlines():
        stamp, _, rest = line.partition(" ")
        if not rest.split(" ", 1)[0].endswith(".ControlModeChanged"):
            continue
        text = rest.rsplit("Attitude mode ", 1)[1]  # "OLD -> NEW (REASON)"
        new, reason = text.split(" -> ", 1)[1].split(" (", 1)
        when = datetime.datetime.fromisoformat(stamp.replace("Z", "+00:00"))
        out.append({"t_s": round((when - epoch).total_seconds(), 1), "mode": new, "reason": reason.rstrip(")")})
    return out


def spin_lowered_to(run_dir: pathlib.Path) -> float | None:
    """The spin (deg/s) the run's first SunSpinLowered event lowered SUN_SAFE's to (None: no such event): the
    SUN_HOLD_SPIN_RATE the controller flew, read from its own log."""
    for line in (run_dir / "events.log").read_text().splitlines():
        stamp, _, rest = line.partition(" ")
        if rest.split(" ", 1)[0].endswith(".SunSpinLowered"):
            return float(rest.split("lowering the SUN_SAFE spin to ", 1)[1].split(" ", 1)[0])
    return None


def _three(values: list[float]) -> dict | None:
    if not values:
        return None
    return {"median": statistics.median(values), "p95": _percentile(values, 95), "max": max(values)}


def figures(run_dir: pathlib.Path) -> dict:
    """One flight's row: mode changes, acquisition and reacquisition (s from the sunlit part's start; None: never),
    the steady error after acquisition (deg), the ADCS SunVector's error (deg), the spin-down's figures."""
    run = pointing_from_run(run_dir)
    parts = run.sunlit_parts()
    errs, invalid = vector_errors_from_run(run_dir)
    row = {"transitions": _transitions(run_dir), "first_sunlit_part_s": run.first_sunlit_part(),
           "acquisition_s": run.acquisition_s(), "steady_deg": _three(run.steady_sunlit()),
           "reacquisition_s": run.acquisition_s(part_index=1) if len(parts) > 1 else None, "sunlit_parts": len(parts),
           "vector_deg": _three(errs), "vector_invalid_sunlit": invalid, "spin_lowered_s": run.spin_lowered_s,
           "spin_lowered_to_deg_s": spin_lowered_to(run_dir), "after_spin_down": None}
    err, rate = run.after_spin_down()
    if err and run.spin_lowered_s is not None:
        row["after_spin_down"] = {"median": statistics.median(err), "max": max(err),
                                  "within": sum(e <= POINTING_THRESHOLD_DEG for e in err) / len(err),
                                  "slow_from": _slow_from(run.spin_lowered_s, rate)}
    row["probe"] = [round(e, 9) for t, e in zip(run.times, run.pointing_deg, strict=True) if t < PROBE_S]
    return row


def table(kind: str, seeds: int, duration_s: float) -> dict:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(1, seeds + 1):
            out = pathlib.Path(tmp) / f"{kind}_{seed}"
            fly(kind, seed, duration_s, out)
            rows.append(dict(figures(out), seed=seed))
    probe = rows[0].pop("probe")
    for r in rows:
        r.pop("probe", None)
    seq, rate, extra, _ = KINDS[kind]
    return {"kind": kind, "sequence": seq, "rate_deg_s": rate, "settings": list(extra),
            "params": [list(p) for p in PARAMS.get(kind, ())], "duration": duration_s, "rows": rows, "probe": probe}


def coil_probe(committed: dict) -> list[str]:
    """The probe of a kind's table (``tools/studies.py --check``): seed 1's first :data:`PROBE_S` s flown again (one
    adcs_ref run of seconds) with the file's kind, its true Sun-pointing error against the committed probe to 1e-9
    deg; and every committed SunSpinLowered at the kind's hold spin (:data:`PARAMS`; the controller's default,
    ``attitude_defaults.SUN_HOLD_SPIN_RATE``, when it sets none). The differences found (empty: none)."""
    from detumble.control import attitude_defaults

    kind = committed["kind"]
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "probe"
        fly(kind, 1, float(PROBE_S), out)
        again = figures(out)["probe"]
    if again != committed["probe"]:
        n = next((i for i, (a, b) in enumerate(zip(again, committed["probe"], strict=False)) if a != b),
                 min(len(again), len(committed["probe"])))
        problems.append(f"seed 1's pointing error at {n} s is {again[n] if n < len(again) else 'missing'} deg now, "
                        f"{committed['probe'][n] if n < len(committed['probe']) else 'missing'} committed")
    hold = float(dict(PARAMS.get(kind, ())).get("SUN_HOLD_SPIN_RATE", attitude_defaults.SUN_HOLD_SPIN_RATE))
    for r in committed["rows"]:
        to = r.get("spin_lowered_to_deg_s")
        if r["spin_lowered_s"] is not None and to != hold:
            problems.append(f"seed {r['seed']} lowered its spin to {to} °/s, not the kind's {hold:g}")
    return problems


def _s(v) -> str:
    return "never" if v is None else f"{v:.0f}"


def _three_s(st) -> str:
    return "—" if st is None else f"{st['median']:.2f} / {st['p95']:.2f} / {st['max']:.2f}"


def _entry(r: dict) -> str:
    sun = next((t for t in r["transitions"] if t["mode"] == "SUN_SAFE"), None)
    return "never" if sun is None else f"{sun['t_s']:.1f} s"


def _restored(r: dict) -> tuple[str, str]:
    """(the first POINTING (KNOWLEDGE_RESTORED), what followed it)"""
    tr = r["transitions"]
    i = next((k for k, t in enumerate(tr) if t["reason"] == "KNOWLEDGE_RESTORED"), None)
    if i is None:
        return "never", f"{tr[-1]['mode']} to the end" if tr else "—"
    rest = tr[i + 1:]
    then = ", ".join(f"{t['mode']} ({t['reason']}) {t['t_s']:.1f} s" for t in rest)
    return f"**{tr[i]['t_s']:.1f} s**", (then + " to the end") if rest else "POINTING to the end"


def markdown(data: dict) -> str:
    kind, rows = data["kind"], data["rows"]
    if data.get("params", []) != [list(p) for p in PARAMS.get(kind, ())]:
        raise ValueError(f"made with the parameters {data.get('params', [])}, not {kind}'s")
    if kind == "command":
        lines = ["| seed | modes | acquisition ≤ 10° in the first sunlit part (s) | after it: median / p95 / max (deg) "
                 "| after the eclipse: reacquisition (s) | ADCS SunVector median / p95 / max (deg) |",
                 "|---|---|---|---|---|---|"]
        for r in rows:
            modes = ", ".join(f"{t['mode']} ({t['reason']}) at {t['t_s']:.0f} s" for t in r["transitions"])
            re_s = "—" if r["sunlit_parts"] < 2 else _s(r["reacquisition_s"])
            lines.append(f"| {r['seed']} | {modes} | {_s(r['acquisition_s'])} | {_three_s(r['steady_deg'])} | "
                         f"{re_s} | {_three_s(r['vector_deg'])} |")
    elif kind == "operator":
        lines = ["| seed | SUN_SAFE (ATTITUDE_LOST) | acquisition ≤ 10° (s) | POINTING (KNOWLEDGE_RESTORED) | then |",
                 "|---|---|---|---|---|"]
        for r in rows:
            back, then = _restored(r)
            lines.append(f"| {r['seed']} | {_entry(r)} | {_s(r['acquisition_s'])} | {back} | {then} |")
    else:
        lines = ["| seed | SUN_SAFE (ATTITUDE_LOST) | acquisition ≤ 10° (s) | SunSpinLowered | from then to the "
                 "sunlit part's end: error median / max, within 10° | \\|ω\\| < 2 °/s from | "
                 "POINTING (KNOWLEDGE_RESTORED) | then |", "|---|---|---|---|---|---|---|---|"]
        for r in rows:
            back, then = _restored(r)
            low = "never" if r["spin_lowered_s"] is None else f"{r['spin_lowered_s']:.1f} s"
            if r.get("spin_lowered_to_deg_s") is not None:
                low += f" (to {r['spin_lowered_to_deg_s']:g} °/s)"
            a = r["after_spin_down"]
            after = "—" if a is None else f"{a['median']:.2f}° / {a['max']:.2f}°, {100 * a['within']:.0f} %"
            slow = "—" if a is None else (a["slow_from"] + (" s" if a["slow_from"] != "never" else ""))
            lines.append(f"| {r['seed']} | {_entry(r)} | {_s(r['acquisition_s'])} | {low} | {after} | {slow} | "
                         f"{back} | {then} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("kind", choices=tuple(KINDS))
    ap.add_argument("--seeds", type=int, help="fly seeds 1..N (default: 3, 5 for hand_back)")
    ap.add_argument("--duration", type=float, default=5580.0, help="s (default one orbit)")
    ap.add_argument("--json", metavar="FILE", help="also keep the figures in FILE")
    args = ap.parse_args(argv)
    seeds = args.seeds if args.seeds is not None else KINDS[args.kind][3]
    if seeds < 1:
        ap.error("--seeds must be at least 1")
    data = table(args.kind, seeds, args.duration)
    print(markdown(data), end="")
    if args.json:
        from detumble.sim.runner import write_atomic

        keep = pathlib.Path(args.json)
        keep.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(str(keep), json.dumps(data, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
