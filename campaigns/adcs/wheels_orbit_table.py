"""The orbit and shipped-sequence table of docs/studies/attitude_knowledge.md ("One orbit, and the deployment as
shipped"): three ``adcs_ref`` runs, about a CPU-minute each.

    python campaigns/adcs/wheels_orbit_table.py                                                            # printed
    python campaigns/adcs/wheels_orbit_table.py --json docs/studies/attitude_knowledge/orbit_runs.json     # kept

``orbit``: pointing on the wheels for one orbit (5580 s) from a 0.5 °/s start, the start-up target set at 0 s and
POINTING forced at 5 s, a 90° target change at 1205 s (the sequence of attitude_modes.md's orbit run; noise seed 1).
``orbit_no_dumping``: the same with K_DUMP 0 (no magnetic momentum dumping). ``shipped``: the deployment with its own
start-up sequence for 6000 s (DETUMBLE → SPIN_STABLE → POINTING). Figures, from each run's ``attitude.csv`` (true
errors and the wheels' momenta every 0.5 s), ``summary.json`` and ``events.log``: the first slew's settling below
0.1°, the error over POINTING after its first 10 % of samples, the steady error from 60 s after the last target
change (``detumble.reports.pointing_metrics``), the wheels' largest |h_i|/h_max (the summary's), |h| after the slew
(mean and largest, N·m·s), the limit events; for the shipped run its mode transitions. Percentiles: numpy's linear.
``tools/studies.py --only attitude_knowledge_orbit_runs`` renders the page's table from the JSON file.
"""

from __future__ import annotations

import csv
import json
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
C = "ReferenceDeployment.attitudeController"
ORBIT_S, SHIPPED_S, SLEW_AT_S = 5580.0, 6000.0, 1205.0
ORBIT_SEQ = (f"R00:00:00 {C}.SET_TARGET_QUATERNION 0.9238795325112867 0 0.3826834323650898 0\n"
             f"R00:00:05 {C}.FORCE_MODE POINTING\n"
             f"R00:20:00 {C}.SET_TARGET_QUATERNION 0.6532814824381883 0.6532814824381882 "
             f"0.2705980500730985 -0.2705980500730985\n")
RUNS = {"orbit": (ORBIT_S, ORBIT_SEQ, ("initial.rate.magnitude_deg_s=0.5",)),
        "orbit_no_dumping": (ORBIT_S, f"R00:00:00 {C}.K_DUMP_PRM_SET 0.0\n" + ORBIT_SEQ,
                             ("initial.rate.magnitude_deg_s=0.5",)),
        "shipped": (SHIPPED_S, None, ())}
LIMIT_EVENTS = ("WheelLimitReached", "TorqueSaturated", "MomentumSaturated")


def figures(out: pathlib.Path) -> dict:
    """The table's figures of the finished run in ``out``."""
    import numpy as np

    from fprime_lite.tools.campaign import RunOutput

    from detumble.reports.pointing_metrics import steady_errors

    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    with open(out / "attitude.csv", newline="", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if r["mode"] == "POINTING"]
    errors = [float(r["pointing_error_deg"]) for r in rows]
    errors = [e for e in errors if math.isfinite(e)]
    after = errors[len(errors) // 10:]
    steady = steady_errors(RunOutput(summary=summary, out_dir=out))
    slews = summary.get("slews") or []
    end = slews[0]["t_s"] + (slews[0]["settle_below_0p1_deg_s"] or 0.0) if slews else None
    h = [math.sqrt(sum(float(r[f"h{i}_nms"]) ** 2 for i in range(4))) for r in rows
         if end is not None and float(r["t_s"]) >= end]
    events = (out / "events.log").read_text(encoding="utf-8")
    return {"slew_settle_s": slews[0]["settle_below_0p1_deg_s"] if slews else None,
            "pointing_samples": len(after), "pointing_median_deg": float(np.median(after)),
            "pointing_p95_deg": float(np.percentile(after, 95)), "pointing_max_deg": float(max(after)),
            "steady_samples": len(steady), "steady_median_deg": float(np.median(steady)),
            "steady_p95_deg": float(np.percentile(steady, 95)), "steady_max_deg": float(max(steady)),
            "wheel_momentum_max_fraction": summary["wheel_momentum_max_fraction"],
            "h_after_slew_mean_nms": float(np.mean(h)) if h else None, "h_after_slew_max_nms": max(h) if h else None,
            "limit_events": sum(events.count(name) for name in LIMIT_EVENTS),
            "transitions": [[m["mode"], m["t_s"]] for m in summary.get("control_mode_transitions") or []]}


def fly(name: str, runs_dir: pathlib.Path) -> dict:
    """Fly the run ``name`` of :data:`RUNS` into ``runs_dir/name``; its figures."""
    import shutil

    from fprime_lite.tools import run

    duration, seq_text, settings = RUNS[name]
    out = runs_dir / name
    shutil.rmtree(out, ignore_errors=True)
    runs_dir.mkdir(parents=True, exist_ok=True)
    seq = None
    if seq_text is not None:
        seq = runs_dir / f"{name}.seq"
        seq.write_text(seq_text, encoding="utf-8")
    run(TOPOLOGY, duration_s=duration, out=out, seq=seq, settings=list(settings))
    return dict(figures(out), duration_s=duration, settings=list(settings))


def results(runs_dir: pathlib.Path) -> dict:
    return {"script": "campaigns/adcs/wheels_orbit_table.py", "runs": {name: fly(name, runs_dir) for name in RUNS}}


def markdown(table: dict) -> str:
    o, n, s = (table["runs"][k] for k in ("orbit", "orbit_no_dumping", "shipped"))

    def pct(x: float) -> str:
        return f"{100 * x:.1f} %"

    def cap(x: float) -> str:
        return f"{x:.1e}"

    lines = ["| run | figure | value | target |", "|---|---|---|---|",
             f"| pointing on the wheels, one orbit ({o['duration_s']:g} s, 0.5 °/s start, FORCE_MODE POINTING at 5 s, "
             f"90° target change at {SLEW_AT_S:g} s) | 90° slew settled < 0.1° | **{o['slew_settle_s']:.1f} s** | "
             "≤ 30 s |",
             f"| | error over POINTING after its first 10 % (includes the slew), median / p95 | "
             f"**{o['pointing_median_deg']:.4f}° / {o['pointing_p95_deg']:.4f}°** | 0.01° / 0.05° |",
             f"| | error from 60 s after the slew to the end ({o['steady_samples']} samples), median / p95 / max | "
             f"{o['steady_median_deg']:.4f}° / {o['steady_p95_deg']:.4f}° / {o['steady_max_deg']:.3f}° | |",
             f"| | wheel momentum, largest \\|h_i\\|/h_max over the orbit (K_DUMP 2e-3 /s) | "
             f"**{pct(o['wheel_momentum_max_fraction'])}** | < 50 % |",
             f"| | wheel limit events ({', '.join(LIMIT_EVENTS)}) | **{o['limit_events']}** | never |",
             f"| | the same orbit with K_DUMP = 0 (no dumping) | peak {pct(n['wheel_momentum_max_fraction'])}; after "
             f"the slew \\|h\\| averages {cap(n['h_after_slew_mean_nms'])} and reaches "
             f"{cap(n['h_after_slew_max_nms'])} N·m·s, against {cap(o['h_after_slew_mean_nms'])} / "
             f"{cap(o['h_after_slew_max_nms'])} with dumping | |",
             f"| `deployments/adcs_ref` as shipped, {s['duration_s']:g} s | transitions | "
             + ", ".join(f"{m} {t:.1f} s" for m, t in s["transitions"]) + " | in order, no chatter |",
             f"| | POINTING error after its first 10 % ({s['pointing_samples']} samples), median / p95 / max | "
             f"**{s['pointing_median_deg']:.4f}° / {s['pointing_p95_deg']:.4f}° / {s['pointing_max_deg']:.3f}°** | "
             "0.01° / 0.05° |",
             f"| | wheel momentum | {pct(s['wheel_momentum_max_fraction'])} | < 50 % |"]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import runs_table_script_main

    return runs_table_script_main(argv, __doc__.split("\n\n")[0], results, markdown, ROOT / "runs" / "wheels_orbit")


if __name__ == "__main__":
    sys.exit(main())
