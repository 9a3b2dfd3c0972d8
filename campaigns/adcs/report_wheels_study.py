"""The pointing-on-wheels campaign's steady-hold table (campaigns/adcs/pointing_wheels.yaml).

Run: ``python campaigns/adcs/report_wheels_study.py RUN_DIR`` on the output folder of
``fprime-lite campaign campaigns/adcs/pointing_wheels.yaml --out RUN_DIR``.

Per run the campaign records the steady hold's true pointing error median and p95 (deg, POINTING from 60 s after
the last target change, :mod:`detumble.reports.pointing_metrics`). This prints their spread over the runs, the share
of runs meeting issue 13's wheel targets (median ≤ 0.01°, p95 ≤ 0.05°) with a 95 % Wilson lower bound, and the
same targets on the error pooled over all runs' steady-hold time (median and p95 with their histogram brackets,
the exact fraction of time above 0.01° and 0.05°: :mod:`detumble.analysis.pooled_stats`).
"""

from __future__ import annotations

import argparse
import pathlib

import numpy as np
import pandas as pd

from detumble.analysis.pooled_stats import (POINTING_THRESHOLDS_DEG, per_run_share, pooled_lines, runs_from_columns,
                                            target_lines)

MEDIAN_TARGET_DEG, P95_TARGET_DEG = 0.01, 0.05


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", help="the campaign output folder (results.parquet)")
    df = pd.read_parquet(pathlib.Path(ap.parse_args(argv).folder) / "results.parquet")
    ok = df[df["status"] == "ok"]
    counts = df["status"].value_counts().to_dict()
    print(f"runs: {len(df)} ({', '.join(f'{v} {k}' for k, v in sorted(counts.items()))})")
    for name in ("pointing_steady_median_deg", "pointing_steady_p95_deg"):
        v = ok[name].to_numpy(dtype=float)
        v = v[np.isfinite(v)]
        if len(v):
            print(f"{name:27s} min {v.min():.5f}  median {np.median(v):.5f}  p95 {np.percentile(v, 95):.5f}"
                  f"  max {v.max():.5f}")
    med_ok = ok["pointing_steady_median_deg"] <= MEDIAN_TARGET_DEG
    p95_ok = ok["pointing_steady_p95_deg"] <= P95_TARGET_DEG
    for label, hits in (("median <= 0.01 deg", med_ok), ("p95 <= 0.05 deg", p95_ok), ("both", med_ok & p95_ok)):
        share = per_run_share(hits)
        print(f"runs with {label:18s} {share.successes}/{share.n}  (95 % lower bound {100 * share.lower95:.1f} %)")
    try:
        runs = runs_from_columns(ok, "pointing_steady", POINTING_THRESHOLDS_DEG)
    except KeyError as exc:
        print(f"pooled steady-hold error: not available, {exc.args[0]} (campaign run before the pooling columns)")
        return 0
    print("\n".join(pooled_lines(runs, POINTING_THRESHOLDS_DEG, "steady-hold pointing error")))
    if runs:
        print("\n".join(target_lines(runs, ((0.5, MEDIAN_TARGET_DEG), (0.95, P95_TARGET_DEG)))))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
