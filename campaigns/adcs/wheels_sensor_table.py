"""The sensor table of docs/studies/attitude_modes.md ("What limits the steady error"): pointing on the wheels with
each of the star tracker and the gyro made noiseless, four 300 s ``adcs_ref`` runs (a few CPU-s each).

    python campaigns/adcs/wheels_sensor_table.py                                              # the table, printed
    python campaigns/adcs/wheels_sensor_table.py --json docs/studies/attitude_modes/sensors.json   # and kept

Each run: ``fprime-lite run deployments/adcs_ref/topology.yaml --duration 300 --seq SEQ --set
initial.rate.axis=[0,0,1] --set initial.rate.magnitude_deg_s=1.5`` plus the row's sensor settings, SEQ setting
DETUMBLE_EXIT_RATE 2 and the start-up target (45° about N's y axis) at 0 s and forcing POINTING at 5 s (noise seed
1). An ideal sensor here is one without noise (``sensors.star_tracker.noise_*_arcsec=0``,
``sensors.gyro.noise_density_dps_rthz=0``); the gyro keeps its bias, which the filter estimates. Figures: median and
p95 (numpy's linear percentile) of the true pointing error in ``attitude.csv`` over the POINTING samples from 200 s.
``tools/studies.py --only attitude_modes_sensors`` renders the page's table from the JSON file (:func:`markdown`).
"""

from __future__ import annotations

import csv
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
DURATION_S, FROM_S = 300.0, 200.0
C = "ReferenceDeployment.attitudeController"
SEQ = (f"R00:00:00 {C}.DETUMBLE_EXIT_RATE_PRM_SET 2.0\n"
       f"R00:00:00 {C}.SET_TARGET_QUATERNION 0.9238795325112867 0 0.3826834323650898 0\n"
       f"R00:00:05 {C}.FORCE_MODE POINTING\n")
BASE = ("initial.rate.axis=[0,0,1]", "initial.rate.magnitude_deg_s=1.5")
IDEAL_TRACKER = ("sensors.star_tracker.noise_cross_boresight_arcsec=0",
                 "sensors.star_tracker.noise_about_boresight_arcsec=0")
IDEAL_GYRO = ("sensors.gyro.noise_density_dps_rthz=0",)
ROWS = {"as in the scenario": (), "ideal star tracker": IDEAL_TRACKER, "ideal gyro": IDEAL_GYRO,
        "ideal gyro and star tracker": IDEAL_GYRO + IDEAL_TRACKER}


def fly(label: str, runs_dir: pathlib.Path) -> dict:
    """Fly the row ``label`` into ``runs_dir``; its median and p95 (deg) from 200 s."""
    import shutil

    import numpy as np

    from fprime_lite.tools import run

    out = runs_dir / label.replace(" ", "_")
    shutil.rmtree(out, ignore_errors=True)
    runs_dir.mkdir(parents=True, exist_ok=True)
    seq = runs_dir / "sensors.seq"
    seq.write_text(SEQ, encoding="utf-8")
    settings = [*BASE, *ROWS[label]]
    run(TOPOLOGY, duration_s=DURATION_S, out=out, seq=seq, settings=settings)
    with open(out / "attitude.csv", newline="", encoding="utf-8") as f:
        errors = np.array([float(r["pointing_error_deg"]) for r in csv.DictReader(f)
                           if r["mode"] == "POINTING" and float(r["t_s"]) >= FROM_S
                           and r["pointing_error_deg"] not in ("", "nan")])
    return {"settings": settings, "samples": len(errors), "median_deg": float(np.median(errors)),
            "p95_deg": float(np.percentile(errors, 95))}


def results(runs_dir: pathlib.Path) -> dict:
    return {"script": "campaigns/adcs/wheels_sensor_table.py", "duration_s": DURATION_S, "from_s": FROM_S,
            "rows": {label: fly(label, runs_dir) for label in ROWS}}


def markdown(table: dict) -> str:
    lines = ["| sensors | median | p95 |", "|---|---|---|"]
    for label, r in table["rows"].items():
        lines.append(f"| {label} | {r['median_deg']:.4f}° | {r['p95_deg']:.4f}° |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import runs_table_script_main

    return runs_table_script_main(argv, __doc__.split("\n\n")[0], results, markdown, ROOT / "runs" / "wheels_sensors")


if __name__ == "__main__":
    sys.exit(main())
