"""The magnetorquer-only attitude-hold campaign's table (docs/studies/magnetic_pointing.md).

Run: ``python campaigns/adcs/report_hold_study.py RUN_DIR`` on the output folder of
``fprime-lite campaign campaigns/adcs/hold_magnetorquers.yaml --out RUN_DIR``.

Per run the campaign records the run summary's pointing-error median, p95 and max (deg, true error,
POINTING after its first 10 %). This prints their spread over the runs, the share of runs meeting
issue 13's targets (median ≤ 5°, p95 ≤ 15°) with a 95 % Wilson lower bound, the same targets on the
error pooled over all runs' POINTING time (median and p95 with their histogram brackets, the exact
fraction of time above 15°: pooled p95 ≤ 15° ⇔ at most 5 % of the time above; see
:mod:`detumble.analysis.pooled_stats`), and the runs that miss, with their start (angle from the
target, deg; initial rate, deg/s).
"""

from __future__ import annotations

import math
import pathlib
import sys

import numpy as np
import pandas as pd

from detumble.analysis.pooled_stats import (POINTING_THRESHOLDS_DEG, per_run_share, pooled_lines, runs_from_columns,
                                            target_lines)

TARGET_Q = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
MEDIAN_TARGET_DEG, P95_TARGET_DEG = 5.0, 15.0


def offset_deg(q) -> float:
    """Angle between the initial attitude ``q`` (scalar first) and the target, deg."""
    dot = abs(sum(a * b for a, b in zip(q, TARGET_Q, strict=True)))
    return 2.0 * math.degrees(math.acos(min(1.0, dot)))


def print_pooled(ok) -> None:
    """The pointing error pooled over the ok runs' POINTING time, and issue 13's targets on it."""
    try:
        runs = runs_from_columns(ok, "pointing_error_deg", POINTING_THRESHOLDS_DEG)
    except KeyError as exc:
        print(f"pooled pointing error: not available, {exc.args[0]} (campaign run before the pooling columns)")
        return
    print("\n".join(pooled_lines(runs, POINTING_THRESHOLDS_DEG, "pointing error (POINTING after its first 10 %)")))
    if runs:
        print("\n".join(target_lines(runs, ((0.5, MEDIAN_TARGET_DEG), (0.95, P95_TARGET_DEG)))))


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    df = pd.read_parquet(pathlib.Path(argv[0]) / "results.parquet")
    ok = df[df["status"] == "ok"]
    print(f"runs: {len(df)} ({len(ok)} ok, {len(df) - len(ok)} not)")
    for name in ("pointing_median_deg", "pointing_p95_deg", "pointing_max_deg"):
        v = ok[name].to_numpy(dtype=float)
        print(f"{name:22s} min {v.min():6.2f}  median {np.median(v):6.2f}  p95 {np.percentile(v, 95):6.2f}"
              f"  max {v.max():6.2f}")
    med_ok = ok["pointing_median_deg"] <= MEDIAN_TARGET_DEG
    p95_ok = ok["pointing_p95_deg"] <= P95_TARGET_DEG
    for label, hits in (("median <= 5 deg", med_ok), ("p95 <= 15 deg", p95_ok), ("both", med_ok & p95_ok)):
        share = per_run_share(hits)
        print(f"runs with {label:16s} {share.successes}/{share.n}  (95 % lower bound {100 * share.lower95:.1f} %)")
    print_pooled(ok)
    print("runs missing a target: offset deg, rate deg/s, median, p95, max")
    for _, row in ok[~(med_ok & p95_ok)].iterrows():
        print(f"  {offset_deg(row['scenario.initial.attitude.quaternion']):5.1f}"
              f"  {row['scenario.initial.rate.magnitude_deg_s']:.3f}"
              f"  {row['pointing_median_deg']:5.2f}  {row['pointing_p95_deg']:5.2f}  {row['pointing_max_deg']:5.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
