"""Tabulate the spin-stabilisation campaigns (campaigns/adcs/spin_minor_axis.yaml, spin_major_axis.yaml).

Run: ``python campaigns/adcs/report_spin_study.py runs/spin_minor runs/spin_major [--plot DIR]``.
Prints, per campaign, the settle-time statistics (null = not settled within the run = never), the
fraction of runs meeting issue 13's spin target and each of its parts, the spin-axis error per run and pooled
over all runs' SPIN_STABLE time (median and p95 with their histogram brackets, the exact fraction of time above
1, 5 and 15°: :mod:`detumble.analysis.pooled_stats`); ``--plot DIR`` draws the
settle-time CDFs and settle time against the initial rate (``spin_settle.png``).

A run meets the target when (all truth, from the AttitudeRunReport):
- the spin settled: momentum within 5° of +Z and the rate about +Z within 5 % of its target from
  ``spin_settled_s`` to the end of SPIN_STABLE, within the run's horizon (shorter than an orbit);
- it then stayed settled for at least ``MIN_DWELL_S`` (one revolution of the 1.5 °/s spin: every body
  orientation against the field), and
- the modes did not chatter: exactly SPIN_STABLE (commanded) then POINTING (AUTO's SPIN_STABLE_REACHED),
  i.e. two transitions.
"""

from __future__ import annotations

import argparse
import math
import pathlib

import numpy as np

from fprime_lite.tools.campaign import read_results
from fprime_lite.tools.campaign.report import percentile

from detumble.analysis.pooled_stats import SPIN_THRESHOLDS_DEG, pooled_lines, runs_from_columns, wilson_lower

ORBIT_S = 5578.0
MIN_DWELL_S = 240.0          # 360° / 1.5 °/s
EXPECTED_TRANSITIONS = 2     # SPIN_STABLE (FORCE_MODE), POINTING (SPIN_STABLE_REACHED)


def _fmt(x: float, digits: int = 0) -> str:
    return "never" if not math.isfinite(x) else f"{x:.{digits}f}"


def _pooled(ok_runs) -> list[str]:
    """The spin-axis error pooled over the ok runs' SPIN_STABLE time (lines of text)."""
    try:
        runs = runs_from_columns(ok_runs, "spin_axis_error_deg", SPIN_THRESHOLDS_DEG)
    except KeyError as exc:
        return [f"pooled spin-axis error: not available, {exc.args[0]} (campaign run before the pooling columns)"]
    return pooled_lines(runs, SPIN_THRESHOLDS_DEG, "spin-axis error (SPIN_STABLE after its first 10 %)")


def analyse(folder: str) -> dict:
    df = read_results(folder)
    ok = df["status"] == "ok"
    settle = np.where(df["spin_settled_s"].isna() | ~ok, np.inf, df["spin_settled_s"].to_numpy(dtype=float))
    dwell = df["spin_settled_dwell_s"].fillna(0.0).to_numpy(dtype=float)
    transitions = df["mode_transitions"].fillna(-1).to_numpy(dtype=float)
    settled = np.isfinite(settle) & (settle <= ORBIT_S)
    dwelt = dwell >= MIN_DWELL_S
    no_chatter = transitions <= EXPECTED_TRANSITIONS
    qualified = transitions == EXPECTED_TRANSITIONS
    meets = settled & dwelt & no_chatter & ok.to_numpy()
    n = len(df)
    return {
        "folder": folder, "n": n, "ok": int(ok.sum()), "df": df, "settle": settle,
        "p50": percentile(settle, 50), "p95": percentile(settle, 95), "max": float(np.max(settle)) if n else math.nan,
        "settled": int(settled.sum()), "dwelt": int((settled & dwelt).sum()), "no_chatter": int(no_chatter.sum()),
        "qualified": int(qualified.sum()), "meets": int(meets.sum()), "lower95": wilson_lower(int(meets.sum()), n),
        "axis_median": float(np.nanmedian(df["spin_axis_error_median_deg"])),
        "axis_p95_of_p95": percentile(df["spin_axis_error_p95_deg"].to_numpy(dtype=float), 95),
        "pooled": _pooled(df[ok]),
        "cpu_s": float(df["cpu_s"].sum()), "sim_s": float(df["sim_seconds"].sum()),
        "failures": df[~meets][["seed_index", "scenario.initial.rate.magnitude_deg_s", "spin_settled_s",
                                "spin_settled_dwell_s", "mode_transitions", "sim_seconds"]],
    }


def rate_bands(r: dict, edges=(0.5, 1.0, 1.5, 2.0)) -> list[tuple[float, float, np.ndarray]]:
    """``(low, high, settle times)`` of the runs whose initial rate (deg/s) is in each band (the last
    band closed); bands without runs are left out."""
    rate = r["df"]["scenario.initial.rate.magnitude_deg_s"].to_numpy(dtype=float)
    out = []
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        sel = (rate >= lo) & ((rate < hi) if hi < edges[-1] else (rate <= hi))
        if sel.any():
            out.append((lo, hi, r["settle"][sel]))
    return out


def paired(first: dict, second: dict) -> dict | None:
    """Runs of two common-random-numbers campaigns paired by seed index: in how many pairs the second
    settled sooner, and the median of (first − second) settle time, s (None: no pair settled in both)."""
    a = dict(zip(first["df"]["seed_index"], first["settle"], strict=True))
    b = dict(zip(second["df"]["seed_index"], second["settle"], strict=True))
    common = [k for k in a if k in b and np.isfinite(a[k]) and np.isfinite(b[k])]
    if not common:
        return None
    gains = np.array([a[k] - b[k] for k in common])
    return {"pairs": len(common), "sooner": int((gains > 0).sum()), "median_gain_s": float(np.median(gains))}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folders", nargs="+", help="campaign output folders (results.parquet)")
    ap.add_argument("--plot", metavar="DIR", help="write spin_settle.png there")
    args = ap.parse_args(argv)
    results = [analyse(f) for f in args.folders]
    print("| campaign | runs (ok) | settle time p50 / p95 / max (s) | settled ≤ 1 orbit | and stayed ≥ 240 s "
          "| no chatter (≤ 2 transitions) | AUTO declared the spin stable | **meets the target** | 95 % lower bound "
          "| spin-axis error, median of run medians (deg) | CPU (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        n = r["n"]
        print(f"| {pathlib.Path(r['folder']).name} | {n} ({r['ok']}) | {_fmt(r['p50'])} / {_fmt(r['p95'])} / "
              f"{_fmt(r['max'])} | {r['settled']}/{n} | {r['dwelt']}/{n} | {r['no_chatter']}/{n} | "
              f"{r['qualified']}/{n} | **{r['meets']}/{n} = {100 * r['meets'] / n:.1f} %** | "
              f"{100 * r['lower95']:.1f} % | {r['axis_median']:.2f} | {r['cpu_s']:.0f} |")
    for r in results:
        print(f"\n{pathlib.Path(r['folder']).name}: spin-axis error, per run: median of run medians "
              f"{r['axis_median']:.2f} deg, p95 of run p95s {r['axis_p95_of_p95']:.2f} deg")
        print("\n".join(r["pooled"]))
    for r in results:
        if len(r["failures"]):
            print(f"\n{pathlib.Path(r['folder']).name}: runs not meeting the target")
            print(r["failures"].to_string(index=False))
        for lo, hi, s in rate_bands(r):
            print(f"{pathlib.Path(r['folder']).name}: initial rate {lo}-{hi} deg/s: {len(s)} runs, "
                  f"settle p50 {_fmt(percentile(s, 50))} s, max {_fmt(float(np.max(s)))} s")
    if len(results) == 2 and (p := paired(*results)) is not None:
        print(f"paired: the second campaign settles sooner in {p['sooner']} of {p['pairs']} pairs "
              f"(median {p['median_gain_s']:.1f} s sooner)")
    if args.plot:
        _plot(results, pathlib.Path(args.plot))
    return 0


def _plot(results, out_dir: pathlib.Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir.mkdir(parents=True, exist_ok=True)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    for r, colour in zip(results, ("tab:blue", "tab:orange", "tab:green"), strict=False):
        label = pathlib.Path(r["folder"]).name
        s = np.sort(r["settle"])
        finite = np.isfinite(s)
        a.step(s[finite], np.arange(1, finite.sum() + 1) / len(s), where="post", color=colour, label=label)
        b.plot(r["df"]["scenario.initial.rate.magnitude_deg_s"], r["settle"], ".", color=colour, ms=4, label=label)
    a.axhline(0.95, color="grey", ls=":", lw=1)
    a.set_xlabel("spin settle time (s from SPIN_STABLE entry; 1 orbit = 5578 s)")
    a.set_ylabel("fraction of runs settled")
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
    b.set_xlabel("initial |ω| (deg/s, random axis)")
    b.set_ylabel("spin settle time (s)")
    b.grid(alpha=0.3)
    b.legend(fontsize=8)
    fig.suptitle("adcs_ref spin stabilisation: momentum within 5° of +Z and rate within 5 % of 1.5 °/s")
    fig.tight_layout()
    from fprime_lite.osal.atomic import atomic_write_bytes
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    atomic_write_bytes(out_dir / "spin_settle.png", buf.getvalue())


if __name__ == "__main__":
    raise SystemExit(main())
