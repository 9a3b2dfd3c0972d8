"""Tabulate the PROVES flight detumble study (campaigns/proves_flight_detumble.yaml).

Run: ``python campaigns/report_flight_study.py runs/flight-study``. Prints, per configuration, the
detumble times of each draw (null = not detumbled within the run, counted as never), their
median and 95th percentile; then the best configuration against the flight defaults and the
``fprime-lite params`` command that writes it as an uplinkable parameter file.
"""

from __future__ import annotations

import json
import math
import sys

import numpy as np

from fprime_lite.tools.campaign import read_results
from fprime_lite.tools.campaign.report import percentile

P = "params.ReferenceDeployment."
KEYS = {"GAIN": P + "detumbleManager.GAIN", "Gain": P + "bdotDetumble.Gain",
        "TORQUE_us": P + "detumbleManager.TORQUE_DURATION.useconds",
        "COOLDOWN_us": P + "detumbleManager.COOLDOWN_DURATION.useconds"}
METRIC = "detumble_complete_s"


def _fmt(x: float) -> str:
    return "never" if not math.isfinite(x) else f"{x:.0f}"


def main(folder: str) -> int:
    df = read_results(folder)
    rows = []
    for point, g in df.groupby("point"):
        asked = json.loads(g.iloc[0]["requested"])
        provider = "BDotDetumble" if "bdot_detumble" in asked.get("topology", "") else "flight 5-point"
        times = np.where(g[METRIC].isna(), np.inf, g[METRIC].to_numpy(dtype=float))
        rows.append({"point": point, "provider": provider, **{k: asked.get(v) for k, v in KEYS.items()},
                     "times": times, "rates": g["scenario.initial.rate.magnitude_deg_s"].to_numpy(dtype=float),
                     "left": [f"{f:.1f}" for f, c in zip(g["final_rate_deg_s"], g[METRIC]) if np.isnan(c)],
                     "median": percentile(times, 50), "p95": percentile(times, 95),
                     "energy": float(np.nanmedian(g["coil_energy_j"])), "status": sorted(set(g["status"]))})
    rates = rows[0]["rates"]
    print(f"draws: initial rates {', '.join(f'{r:.1f}' for r in rates)} deg/s (same for every configuration)")
    print("| provider | GAIN / Gain | TORQUE_DURATION | COOLDOWN_DURATION | detumble complete at, per draw (s) "
          "| median | p95 | not detumbled: \\|ω\\| at the end (deg/s) | coil energy, median (J) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in sorted(rows, key=lambda r: (r["p95"], r["median"])):
        gain = r["GAIN"] if r["GAIN"] is not None else r["Gain"]
        print(f"| {r['provider']} | {gain:g} | {r['TORQUE_us'] / 1000:g} ms | {r['COOLDOWN_us'] / 1000:g} ms | "
              f"{', '.join(_fmt(t) for t in r['times'])} | {_fmt(r['median'])} | {_fmt(r['p95'])} | "
              f"{', '.join(r['left']) or '—'} | {r['energy']:.0f} |")
    default = next(r for r in rows if r["provider"] == "flight 5-point" and r["GAIN"] == 3.0
                   and r["TORQUE_us"] == 320000 and r["COOLDOWN_us"] == 20000)
    key = lambda r: (r["p95"], r["median"])  # noqa: E731 - ties on p95 ("never") go to the median
    print(f"\nflight defaults: p95 {_fmt(default['p95'])} s, median {_fmt(default['median'])} s")
    for label, pool in (("best overall", rows), ("best on the flight topology (a parameter uplink, no new software)",
                                                  [r for r in rows if r["provider"] == "flight 5-point"])):
        best = min(pool, key=key)
        print(f"{label}: point {best['point']} ({best['provider']}): p95 {_fmt(best['p95'])} s, "
              f"median {_fmt(best['median'])} s")
        topo = "topology_bdot_detumble.yaml" if best["provider"] == "BDotDetumble" else "topology.yaml"
        sets = []
        if best["GAIN"] is not None:
            sets.append(f"ReferenceDeployment.detumbleManager.GAIN={best['GAIN']}")
        if best["Gain"] is not None:
            sets.append(f"ReferenceDeployment.bdotDetumble.Gain={best['Gain']}")
        for name, us in (("TORQUE_DURATION", best["TORQUE_us"]), ("COOLDOWN_DURATION", best["COOLDOWN_us"])):
            sets.append(f"'ReferenceDeployment.detumbleManager.{name}={{seconds: 0, useconds: {us}}}'")
        print(f"  fprime-lite params deployments/proves_ref/{topo} -o proves_detumble_best.dat \\\n      "
              + " \\\n      ".join(f"--set {s}" for s in sets))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "runs/flight-study"))
