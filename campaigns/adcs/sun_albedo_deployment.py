"""The ADCS component's Sun vector on deployments/adcs_ref with the Earth's albedo on the light sensors, before and
after the on-board albedo correction (docs/studies/sun_safe.md, "On the deployment").

Each case flies adcs_ref's whole AUTO flight (``fprime-lite run``, its own seed) for ``--duration`` s with
``sensors.sun_sensors.albedo`` set to the case's Bond albedo and ``campaigns/adcs/sun_albedo_correction.seq``
(adcs_ref's start-up sequence plus ``SUN_ALBEDO_CORRECTION ENABLED``, SUN_ALBEDO_MODEL at its default 0.30), then
reads both ADCS channels against the truth (``detumble.sim.sun_safe_check.vector_errors_from_run``): SunVectorRaw
(the uncorrected vector) and SunVector (the published, corrected one). The correction does not act on the flight
(the AUTO flight never enters SUN_SAFE), so one flight gives both.

    python campaigns/adcs/sun_albedo_deployment.py [--duration S] [--json FILE]

Prints the table (markdown); ``--json`` keeps its figures and the first sunlit readings' errors of the 0.3 case
(the probe STUDY-015 re-flies).
"""

from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

from detumble.sim.sun_safe_check import VECTOR_THRESHOLD_DEG, _percentile, vector_errors_from_run

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
SEQUENCE = ROOT / "campaigns" / "adcs" / "sun_albedo_correction.seq"
#: (albedo in the sensors, what the row is called)
CASES = ((0.3, "0.3 (the model's)"), (0.4, "0.4 (model 0.3)"), (0.0, "0 (model 0.3)"))
#: sunlit readings of the 0.3 case kept for the probe
PROBE_READINGS = 60


def fly(albedo: float, duration_s: float, out: pathlib.Path) -> None:
    """One ``fprime-lite run`` of adcs_ref into ``out`` with the correction enabled and ``albedo`` in the sensors."""
    cmd = [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(TOPOLOGY), "--duration", f"{duration_s:g}",
           "--seq", str(SEQUENCE), "--set", f"sensors.sun_sensors.albedo={albedo:g}", "--out", str(out),
           "--no-progress", "--no-plots"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)


def _stats(errors: list[float], invalid: int) -> dict:
    """deg, and the share within VECTOR_THRESHOLD_DEG in %, as ``sun_safe_check --from-run`` prints them."""
    return {"readings": len(errors), "median": statistics.median(errors), "p95": _percentile(errors, 95),
            "max": max(errors), "within": 100.0 * sum(e <= VECTOR_THRESHOLD_DEG for e in errors) / len(errors),
            "invalid": invalid}


def figures(run_dir: pathlib.Path) -> dict:
    """The raw and the corrected vector's statistics over one run's sunlit readings."""
    raw = vector_errors_from_run(run_dir, channel="SunVectorRaw")
    corrected = vector_errors_from_run(run_dir, channel="SunVector")
    return {"raw": _stats(*raw), "corrected": _stats(*corrected), "corrected_errors": corrected[0]}


def table(duration_s: float) -> dict:
    rows, probe = [], None
    with tempfile.TemporaryDirectory() as tmp:
        for albedo, label in CASES:
            out = pathlib.Path(tmp) / f"albedo_{albedo:g}"
            fly(albedo, duration_s, out)
            f = figures(out)
            if probe is None:
                probe = [round(e, 9) for e in f["corrected_errors"][:PROBE_READINGS]]
            rows.append({"albedo": albedo, "label": label, "raw": f["raw"], "corrected": f["corrected"]})
    return {"duration": duration_s, "rows": rows, "probe": probe}


def markdown(data: dict) -> str:
    lines = ["| albedo in the sensors | SunVectorRaw: median / p95 / max (deg) | ≤ 5° | SunVector (corrected): "
             "median / p95 / max (deg) | ≤ 5° | sunlit readings |",
             "|---|---|---|---|---|---|"]
    for row in data["rows"]:
        r, c = row["raw"], row["corrected"]
        lines.append(f"| {row['label']} | {r['median']:.2f} / {r['p95']:.2f} / {r['max']:.2f} | {r['within']:.1f} % | "
                     f"{c['median']:.2f} / {c['p95']:.2f} / {c['max']:.2f} | {c['within']:.1f} % | {c['readings']} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--duration", type=float, default=5580.0, help="s (default one orbit)")
    ap.add_argument("--json", metavar="FILE", help="also keep the figures in FILE")
    args = ap.parse_args(argv)
    data = table(args.duration)
    if args.json:
        pathlib.Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(args.json).write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    print(markdown(data), end="")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
