"""Tabulate the PROVES flight detumble study (campaigns/proves_flight_detumble.yaml, and part 2,
campaigns/proves_flight_detumble_p95.yaml).

Run: ``python campaigns/report_flight_study.py runs/flight-study [--bootstrap 2000]``. Prints, per
configuration, the detumble times (null = not detumbled within the run, counted as never): each
draw's when there are at most five draws, and always the median, the 95th percentile with a
bootstrap 95 % interval, the worst draw and the median coil energy; then the best configuration
against the flight defaults — the difference of their p95 with a paired bootstrap interval (every
configuration flew the same draws) — and the ``fprime-lite params`` command that writes it as an
uplinkable parameter file.

Only draws that every configuration completed with status ``ok`` are used (a campaign stopped
early, or a run that failed, would otherwise compare configurations on different draws).
"""

from __future__ import annotations

import argparse
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
RATE = "scenario.initial.rate.magnitude_deg_s"


def _fmt(x: float) -> str:
    return "never" if not math.isfinite(x) else f"{x:.0f}"


def _interval(lo: float, hi: float) -> str:
    return f"[{_fmt(lo)}, {_fmt(hi)}]"


def _difference(a: float, b: float) -> float:
    """a - b where inf stands for never: never - never is undecided (nan)."""
    if math.isinf(a) and math.isinf(b):
        return math.nan
    return a - b


def _p95s(times: np.ndarray, resamples: np.ndarray) -> np.ndarray:
    return np.array([percentile(times[idx], 95) for idx in resamples])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", nargs="?", default="runs/flight-study")
    ap.add_argument("--bootstrap", type=int, default=2000, metavar="B", help="bootstrap resamples (default 2000)")
    args = ap.parse_args(argv)
    df = read_results(args.folder)
    points = df["point"].nunique()
    per_seed = df[df["status"] == "ok"].groupby("seed_index")["point"].nunique()
    draws = sorted(per_seed[per_seed == points].index)
    dropped = sorted(set(df["seed_index"]) - set(draws))
    df = df[df["seed_index"].isin(draws)]
    rng = np.random.default_rng(20261201)
    resamples = rng.integers(0, len(draws), size=(args.bootstrap, len(draws)))
    rows = []
    for point, g in df.groupby("point"):
        g = g.sort_values("seed_index")
        asked = json.loads(g.iloc[0]["requested"])
        provider = "BDotDetumble" if "bdot_detumble" in asked.get("topology", "") else "flight 5-point"
        times = np.where(g[METRIC].isna(), np.inf, g[METRIC].to_numpy(dtype=float))
        boot = _p95s(times, resamples)
        rows.append({"point": point, "provider": provider, **{k: asked.get(v) for k, v in KEYS.items()},
                     "times": times, "rates": g[RATE].to_numpy(dtype=float), "boot": boot,
                     "left": [f"{f:.1f}" for f, c in zip(g["final_rate_deg_s"], g[METRIC], strict=True) if np.isnan(c)],
                     "median": percentile(times, 50), "p95": percentile(times, 95),
                     "p95_ci": (percentile(boot, 2.5), percentile(boot, 97.5)),
                     "energy": float(np.nanmedian(g["coil_energy_j"]))})
    rates = rows[0]["rates"]
    cpu = df["cpu_s"].sum() if "cpu_s" in df else math.nan
    print(f"{len(draws)} draws per configuration, {len(df)} runs, {cpu / 60:.1f} CPU-minutes in the runs"
          + (f" (seed indices {dropped} left out: not complete for every configuration)" if dropped else ""))
    print(f"initial rates {rates.min():.1f}-{rates.max():.1f} deg/s"
          + (f": {', '.join(f'{r:.1f}' for r in rates)} (same for every configuration)" if len(rates) <= 5 else
             f", median {np.median(rates):.1f} (same draws for every configuration)"))
    per_draw = len(draws) <= 5
    print("| provider | GAIN / Gain | TORQUE_DURATION | COOLDOWN_DURATION | "
          + ("detumble complete at, per draw (s) | " if per_draw else "not detumbled | ")
          + "median (s) | p95 (s) | p95 95 % bootstrap interval (s) | worst draw (s) | coil energy, median (J) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in sorted(rows, key=lambda r: (r["p95"], r["median"])):
        gain = r["GAIN"] if r["GAIN"] is not None else r["Gain"]
        never = int(np.isinf(r["times"]).sum())
        middle = ', '.join(_fmt(t) for t in r["times"]) if per_draw else \
            f"{never} of {len(r['times'])}" + (f" (|ω| left: {', '.join(r['left'])} deg/s)" if never else "")
        print(f"| {r['provider']} | {gain:g} | {r['TORQUE_us'] / 1000:g} ms | {r['COOLDOWN_us'] / 1000:g} ms | "
              f"{middle} | {_fmt(r['median'])} | {_fmt(r['p95'])} | {_interval(*r['p95_ci'])} | "
              f"{_fmt(r['times'].max())} | {r['energy']:.0f} |")
    default = next(r for r in rows if r["provider"] == "flight 5-point" and r["GAIN"] == 3.0
                   and r["TORQUE_us"] == 320000 and r["COOLDOWN_us"] == 20000)
    key = lambda r: (r["p95"], r["median"])  # noqa: E731 - ties on p95 ("never") go to the median
    print(f"\nflight defaults: p95 {_fmt(default['p95'])} s {_interval(*default['p95_ci'])}, "
          f"median {_fmt(default['median'])} s")
    for label, pool in (("best overall", rows), ("best on the flight topology (a parameter uplink, no new software)",
                                                  [r for r in rows if r["provider"] == "flight 5-point"])):
        best = min(pool, key=key)
        diff = np.array([_difference(b, d) for b, d in zip(best["boot"], default["boot"], strict=True)])
        diff = diff[~np.isnan(diff)]
        gain = _difference(best["p95"], default["p95"])
        share = float(np.mean(diff < 0)) if len(diff) else math.nan
        against = "undecided (both never)" if math.isnan(gain) else \
            "never detumbled" if math.isinf(gain) else f"{gain:+.0f} s ({100 * gain / default['p95']:+.0f} %)"
        print(f"{label}: point {best['point']} ({best['provider']}): p95 {_fmt(best['p95'])} s "
              f"{_interval(*best['p95_ci'])}, median {_fmt(best['median'])} s; p95 against the defaults "
              f"{against}, paired bootstrap 95 % interval [{percentile(diff, 2.5):+.0f}, "
              f"{percentile(diff, 97.5):+.0f}] s, faster in {100 * share:.0f} % of the resamples where one is decided")
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
    sys.exit(main())
