"""Issue 27's magnetorquer-only hold goal, plant-only campaign (docs/studies/magnetorquer_hold_after_acquisition.md).

Run: ``python campaigns/adcs/report_pointing_plant.py RUN_DIR [TWO_ORBIT_DIR]`` on the output folder of
``fprime-lite campaign campaigns/adcs/pointing_magnetorquers_plant.yaml --out RUN_DIR`` (prints the page's tables);
with the folder of ``pointing_magnetorquers_plant_2orbits.yaml`` (its first 20 draws flown for two orbits) also the
paired comparison of the two window lengths.

The window is the run summary's ``pointing_error_deg``: POINTING after its acquisition, i.e. from the time the true
error stays below 30° (``pointing_acquisition_s``, s after entering POINTING) to the end of the run. Per run the
campaign records that window's median, p95 and max (deg), its length and time above 15° (the pooling columns
``pointing_error_deg.window_s`` / ``.time_above_s.15``, s) and ``pointing_acquisition_15deg_s``: the same acquisition
rule at 15°. This computes, from those columns only:

* the spread over the runs of the per-run median / p95 / max (deg), of the acquisition time and of the window (s),
  the runs meeting the goals (median ≤ 5°, p95 ≤ 15°) with their 95 % Wilson lower bound, split by initial rate
  and by initial angle from the target;
* the error pooled over all the runs' windows (time-weighted, :mod:`detumble.analysis.pooled_stats`);
* why runs miss the p95: a run's p95 ≤ 15° exactly when at most 5 % of its window is above 15°; the **tail**
  ``pointing_acquisition_15deg_s − pointing_acquisition_s`` is the time, from the window's start, until the error
  stays below 15° — the part of the acquisition transient between 30° and 15° that the window holds. Its share of
  the time above 15° says whether the misses are that tail (share ≈ 1) or later excursions; its length against
  5 % of the window says how much tail a run can afford; ``ln 2 / tail`` is the tail's decay rate if it were one
  exponential from 30° to 15° (compare the slow along-field mode's Floquet rate, docs/studies/magnetic_pointing.md).
"""

from __future__ import annotations

import math
import pathlib
import sys

import numpy as np
import pandas as pd

from detumble.analysis.pooled_stats import (POINTING_THRESHOLDS_DEG, per_run_share, pooled_fraction_above,
                                            pooled_percentile, runs_from_columns)

TARGET_Q = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
MEDIAN_TARGET_DEG, P95_TARGET_DEG = 5.0, 15.0
P95_ALLOWANCE = 0.05  # share of the window a p95 lets lie above its bound
RATE_BANDS = ((0.0, 0.1), (0.1, 0.3), (0.3, 0.5))        # deg/s, the campaign draws 0–0.5
ANGLE_BANDS = ((0.0, 20.0), (20.0, 40.0), (40.0, 60.0))  # deg, the campaign draws 0–60
#: 1/s: the slow along-field mode's Floquet decay rate with the present defaults (K_P_MAG 4e-6, K_D_MAG 4e-4, ρ 2,
#: ζ 1) and the scenario's magnetometer bias, in the tilted dipole: docs/studies/magnetic_pointing.md, section 4's table
#: (16000 samples; the 200-sample map said 3.04e-3, not converged). MAGPT-081 checks it against the map.
FLOQUET_SLOW_RATE_PER_S = 2.614e-3

_PREFIX = "pointing_error_deg"


def offset_deg(q) -> float:
    """Angle between the initial attitude ``q`` (scalar first) and the target, deg."""
    dot = abs(sum(float(a) * b for a, b in zip(q, TARGET_Q, strict=True)))
    return 2.0 * math.degrees(math.acos(min(1.0, dot)))


def per_run(df: pd.DataFrame) -> pd.DataFrame:
    """One row per ok run: start (``rate_deg_s``, ``offset_deg``), the window's ``median``/``p95``/``max`` (deg),
    ``acquisition_s``, ``window_s``, ``above15_s``, ``share_above15`` (0…1), ``tail_s`` (s from the window's start
    until the error stays below 15°) and the goal flags."""
    ok = df[df["status"] == "ok"]
    out = pd.DataFrame({
        "run_id": ok["run_id"].to_numpy(),
        "seed_index": ok["seed_index"].to_numpy(),
        "seed": ok["seed"].to_numpy() if "seed" in ok else ok["seed_index"].to_numpy(),
        "rate_deg_s": [float(np.linalg.norm(np.asarray(w, dtype=float)))
                       for w in ok["scenario.initial.rate.omega_deg_s"]],
        "offset_deg": [offset_deg(q) for q in ok["scenario.initial.attitude.quaternion"]],
        "median": ok["pointing_median_deg"].to_numpy(dtype=float),
        "p95": ok["pointing_p95_deg"].to_numpy(dtype=float),
        "max": ok["pointing_max_deg"].to_numpy(dtype=float),
        "acquisition_s": ok["pointing_acquisition_s"].to_numpy(dtype=float),
        "acquisition15_s": ok["pointing_acquisition_15deg_s"].to_numpy(dtype=float),
        "window_s": ok[f"{_PREFIX}.window_s"].to_numpy(dtype=float),
        "above15_s": ok[f"{_PREFIX}.time_above_s.15"].to_numpy(dtype=float),
    })
    out["share_above15"] = out["above15_s"] / out["window_s"]
    out["tail_s"] = out["acquisition15_s"] - out["acquisition_s"]
    out["median_ok"] = out["median"] <= MEDIAN_TARGET_DEG
    out["p95_ok"] = out["p95"] <= P95_TARGET_DEG
    return out.sort_values("seed_index", kind="stable").reset_index(drop=True)


def spearman(x, y) -> float:
    """Spearman rank correlation of two equal-length sequences (average ranks for ties)."""
    rx = pd.Series(np.asarray(x, dtype=float)).rank().to_numpy()
    ry = pd.Series(np.asarray(y, dtype=float)).rank().to_numpy()
    return float(np.corrcoef(rx, ry)[0, 1])


def spread(values) -> tuple[float, float, float, float]:
    """(min, median, p95, max) of ``values`` (linear-interpolated percentiles)."""
    v = np.asarray(values, dtype=float)
    return float(v.min()), float(np.median(v)), float(np.percentile(v, 95)), float(v.max())


def slow_mode_tail_s(sigma_per_s: float, peak_deg: float = math.inf, high_deg: float = 30.0,
                     low_deg: float = 15.0) -> float:
    """s a critically damped slow pair takes to fall from ``high_deg`` to ``low_deg`` after its peak ``peak_deg``.

    With the double root ``−σ`` every solution is ``(a + b t) e^{−σt}``, which (a, b of one sign) is the curve
    ``P σt' e^{1−σt'}`` shifted in time, peak ``P`` at ``t' = 1/σ``. On its way down it is at ``x`` when
    ``u e^{1−u} = x/P`` (``u = σt' ≥ 1``). The fall from 30° to 15° lasts ``(u₁₅ − u₃₀)/σ``: ``ln 2/σ`` for
    ``P → ∞`` (the exponential limit) up to ``1.678/σ`` for a peak at 30°. Requires ``peak_deg ≥ high_deg``."""
    if not (sigma_per_s > 0.0 and peak_deg >= high_deg > low_deg > 0.0):
        raise ValueError("need sigma > 0 and peak >= high > low > 0 (deg)")
    if math.isinf(peak_deg):
        return math.log(high_deg / low_deg) / sigma_per_s

    def descending(y: float) -> float:  # u >= 1 with ln u + 1 - u = ln y, by bisection (monotone for u > 1)
        lo, hi = 1.0, 2.0
        while math.log(hi) + 1.0 - hi > math.log(y):
            hi *= 2.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if math.log(mid) + 1.0 - mid > math.log(y) else (lo, mid)
        return 0.5 * (lo + hi)

    return (descending(low_deg / peak_deg) - descending(high_deg / peak_deg)) / sigma_per_s


def analyse(df: pd.DataFrame) -> dict:
    """Every figure of the page's tables from a campaign's results table (see the module's docstring)."""
    runs = per_run(df)
    n_all = len(df)
    pooled = runs_from_columns(df[df["status"] == "ok"], _PREFIX, POINTING_THRESHOLDS_DEG)
    miss = runs[~runs["p95_ok"]]
    met = runs[runs["p95_ok"]]

    def band_rows(column: str, bands) -> list[dict]:
        rows = []
        for lo, hi in bands:
            last = hi == bands[-1][1]
            sel = runs[(runs[column] >= lo) & ((runs[column] <= hi) if last else (runs[column] < hi))]
            rows.append({"lo": lo, "hi": hi, "n": len(sel), "median_ok": int(sel["median_ok"].sum()),
                         "p95_ok": int(sel["p95_ok"].sum()),
                         "p95_median": float(np.median(sel["p95"])) if len(sel) else math.nan,
                         "p95_max": float(sel["p95"].max()) if len(sel) else math.nan,
                         "acq_median": float(np.median(sel["acquisition_s"])) if len(sel) else math.nan})
        return rows

    above = runs["above15_s"].to_numpy(dtype=float)
    tail = runs["tail_s"].to_numpy(dtype=float)
    allowance = P95_ALLOWANCE * runs["window_s"].to_numpy(dtype=float)
    band = (slow_mode_tail_s(FLOQUET_SLOW_RATE_PER_S), slow_mode_tail_s(FLOQUET_SLOW_RATE_PER_S, 30.0))
    share_rule = (runs["share_above15"] <= P95_ALLOWANCE) == runs["p95_ok"]
    return {
        "n": n_all, "ok": len(runs), "runs": runs,
        "median": spread(runs["median"]), "p95": spread(runs["p95"]), "max": spread(runs["max"]),
        "acquisition_s": spread(runs["acquisition_s"]), "window_s": spread(runs["window_s"]),
        "median_share": per_run_share(runs["median_ok"]), "p95_share": per_run_share(runs["p95_ok"]),
        "both_share": per_run_share(runs["median_ok"] & runs["p95_ok"]),
        "by_rate": band_rows("rate_deg_s", RATE_BANDS), "by_angle": band_rows("offset_deg", ANGLE_BANDS),
        "pooled_s": float(sum(r.window_s for r in pooled)),
        "pooled_p50": pooled_percentile(pooled, 0.5), "pooled_p95": pooled_percentile(pooled, 0.95),
        "pooled_above15": pooled_fraction_above(pooled, P95_TARGET_DEG),
        "pooled_above5": pooled_fraction_above(pooled, MEDIAN_TARGET_DEG),
        "rho_rate": spearman(runs["rate_deg_s"], runs["p95"]) if len(runs) > 2 else math.nan,
        "rho_angle": spearman(runs["offset_deg"], runs["p95"]) if len(runs) > 2 else math.nan,
        "rho_acq": spearman(runs["acquisition_s"], runs["p95"]) if len(runs) > 2 else math.nan,
        "share_rule_agrees": int(share_rule.sum()),
        "above_over_tail": float(above.sum() / tail.sum()) if tail.sum() > 0 else math.nan,
        "tail_end_max": float(((runs["tail_s"]) / runs["window_s"]).max()),
        "band_s": band,
        "miss": _group(miss, allowance[~runs["p95_ok"].to_numpy()], band),
        "met": _group(met, allowance[runs["p95_ok"].to_numpy()], band),
    }


def _group(sel: pd.DataFrame, allowance, band: tuple[float, float]) -> dict:
    """Medians (and ranges) of the cause columns over one group of runs."""
    if not len(sel):
        return {"n": 0}
    return {"n": len(sel),
            "share": (float(np.median(sel["share_above15"])), float(sel["share_above15"].min()),
                      float(sel["share_above15"].max())),
            "tail": (float(np.median(sel["tail_s"])), float(sel["tail_s"].min()), float(sel["tail_s"].max())),
            "allowance": float(np.median(allowance)),
            "above_over_tail": (float(sel["above15_s"].sum() / sel["tail_s"].sum()) if sel["tail_s"].sum() > 0
                                else math.nan),
            "tail_end": float((sel["tail_s"] / sel["window_s"]).max()),
            "long": int((sel["tail_s"] >= band[0]).sum()), "longer": int((sel["tail_s"] > band[1]).sum()),
            "tail_fits": int(np.sum(sel["tail_s"].to_numpy() <= allowance)),
            "rate": float(np.median(sel["rate_deg_s"])), "offset": float(np.median(sel["offset_deg"])),
            "acq": float(np.median(sel["acquisition_s"]))}


def _f(x: float, digits: int) -> str:
    return "—" if not math.isfinite(x) else f"{x:,.{digits}f}"


def markdown(a: dict) -> str:
    """The page's tables (markdown) from :func:`analyse`."""
    n = a["ok"]
    lb = lambda s: f"{s.successes}/{s.n} (95 % lower bound {100 * s.lower95:.1f} %)"  # noqa: E731
    lines = [f"{a['n']} runs, {n} `ok`. Per-run figures of the window after acquisition, then their spread over "
             "the runs:", "",
             "| per run | min | median | p95 | max | goal: runs meeting it |", "|---|---|---|---|---|---|"]
    for key, label, digits, goal in (("median", "median (deg)", 2, f"≤ 5°: **{lb(a['median_share'])}**"),
                                     ("p95", "p95 (deg)", 2, f"≤ 15°: **{lb(a['p95_share'])}**"),
                                     ("max", "max (deg)", 2, "—"),
                                     ("acquisition_s", "acquisition, to < 30° for good (s)", 0, "reported"),
                                     ("window_s", "window after acquisition (s)", 0, "—")):
        lines.append(f"| {label} | " + " | ".join(_f(v, digits) for v in a[key]) + f" | {goal} |")
    lines += ["", f"Both goals in the same run: **{lb(a['both_share'])}**.", "",
              "| initial rate (°/s) | runs | median ≤ 5° | p95 ≤ 15° | run p95: median / max (deg) | "
              "acquisition median (s) |", "|---|---|---|---|---|---|"]
    for r in a["by_rate"]:
        lines.append(f"| {r['lo']:g}–{r['hi']:g} | {r['n']} | {r['median_ok']} | {r['p95_ok']} | "
                     f"{_f(r['p95_median'], 1)} / {_f(r['p95_max'], 1)} | {_f(r['acq_median'], 0)} |")
    lines += ["", "| initial angle from the target (°) | runs | median ≤ 5° | p95 ≤ 15° | run p95: median / max "
              "(deg) | acquisition median (s) |", "|---|---|---|---|---|---|"]
    for r in a["by_angle"]:
        lines.append(f"| {r['lo']:g}–{r['hi']:g} | {r['n']} | {r['median_ok']} | {r['p95_ok']} | "
                     f"{_f(r['p95_median'], 1)} / {_f(r['p95_max'], 1)} | {_f(r['acq_median'], 0)} |")
    p50, p95, band = a["pooled_p50"], a["pooled_p95"], a["band_s"]
    rest = "" if a["share_rule_agrees"] == n else ", the rest within a sample"
    lines += ["", f"Pooled over all {n} windows ({a['pooled_s']:,.0f} s, time-weighted): p50 "
              f"**{p50.estimate_deg:.2f}°** (bracket {p50.lower_deg:.2f}–{p50.upper_deg:.2f}°), p95 "
              f"**{p95.estimate_deg:.1f}°** (bracket {p95.lower_deg:.1f}–{p95.upper_deg:.1f}°); time above 5°: "
              f"{100 * a['pooled_above5']:.2f} %, above 15°: "
              f"**{100 * a['pooled_above15']:.2f} %** (exact; the pooled p95 ≤ 15° ⇔ ≤ 5 %).",
              "", f"Spearman rank correlation of the run p95 with the initial rate {a['rho_rate']:+.2f}, with the "
              f"initial angle {a['rho_angle']:+.2f}, with the acquisition time {a['rho_acq']:+.2f}.",
              "", "Why runs miss p95 ≤ 15° (a run's p95 ≤ 15° ⇔ at most 5 % of its window above 15°: the two agree "
              f"in {a['share_rule_agrees']}/{n} runs{rest}). The tail: from the window's start "
              "(the error below 30° for good) until the error stays below 15°; every second above 15° in the window "
              f"lies in it. Closed form for the slow along-field pair (critically damped, rate σ = "
              f"{FLOQUET_SLOW_RATE_PER_S:.2e} /s, Floquet): its fall from 30° to 15° lasts {band[0]:.0f}–"
              f"{band[1]:.0f} s (ln 2/σ for a peak ≫ 30°, 1.678/σ for a peak at 30°).", "",
              "| runs | count | above 15°, share of the window: median (range) | tail (s): median (range) | above 15° "
              "/ tail time | tail ends by (share of the window) | 5 % of the window (s), median | tails ≤ 5 % of "
              f"the window | tails ≥ {band[0]:.0f} s | tails > {band[1]:.0f} s | initial rate (°/s) / angle (°), "
              "median | acquisition (s), median |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for key, label in (("met", "p95 ≤ 15°"), ("miss", "p95 > 15°")):
        g = a[key]
        if not g["n"]:
            lines.append(f"| {label} | 0 | | | | | | | | | | |")
            continue
        share, tail = g["share"], g["tail"]
        lines.append(f"| {label} | {g['n']} | {100 * share[0]:.1f} % ({100 * share[1]:.1f}–{100 * share[2]:.1f} %) "
                     f"| {tail[0]:.0f} ({tail[1]:.0f}–{tail[2]:.0f}) | {100 * g['above_over_tail']:.0f} % | "
                     f"{100 * g['tail_end']:.1f} % | {g['allowance']:.0f} | {g['tail_fits']}/{g['n']} | "
                     f"{g['long']}/{g['n']} | {g['longer']}/{g['n']} | {g['rate']:.2f} / {g['offset']:.0f} | "
                     f"{g['acq']:.0f} |")
    return "\n".join(lines) + "\n"


def paired(one: pd.DataFrame, two: pd.DataFrame) -> dict:
    """The same draws flown for one orbit (``one``) and for two (``two``), paired by seed: the runs meeting p95 ≤
    15° in each, the share of the window above 15° (median of the runs) in each, and in how many pairs the
    acquisition, the tail and the time above 15° are the same (the second orbit added no time above 15°)."""
    m = per_run(one).merge(per_run(two), on="seed", suffixes=("_1", "_2"))
    same = lambda c: int((m[f"{c}_1"] == m[f"{c}_2"]).sum())  # noqa: E731
    return {"pairs": len(m), "p95_ok_1": int(m["p95_ok_1"].sum()), "p95_ok_2": int(m["p95_ok_2"].sum()),
            "median_ok_2": int(m["median_ok_2"].sum()),
            "share_1": float(np.median(m["share_above15_1"])), "share_2": float(np.median(m["share_above15_2"])),
            "p95_1": float(np.median(m["p95_1"])), "p95_2": float(np.median(m["p95_2"])),
            "same_acquisition": same("acquisition_s"), "same_tail": same("tail_s"), "same_above": same("above15_s"),
            "window_2": float(np.median(m["window_s_2"])),
            "still_missing": [(float(r["tail_s_2"]), P95_ALLOWANCE * float(r["window_s_2"]))
                              for _, r in m[~m["p95_ok_2"]].iterrows()]}


def paired_markdown(p: dict) -> str:
    """The one-orbit / two-orbit comparison (markdown) from :func:`paired`."""
    n = p["pairs"]
    return ("| the same draws, window after acquisition to the end of | runs | p95 ≤ 15° | run p95, median (deg) | "
            "above 15°, share of the window: median |\n|---|---|---|---|---|\n"
            f"| one orbit (5580 s) | {n} | {p['p95_ok_1']}/{n} | {p['p95_1']:.1f} | {100 * p['share_1']:.1f} % |\n"
            f"| two orbits (11160 s) | {n} | **{p['p95_ok_2']}/{n}** | {p['p95_2']:.1f} | {100 * p['share_2']:.1f} % |"
            f"\n\nIn {p['same_acquisition']}/{n} pairs the acquisition is the same, in {p['same_tail']}/{n} the tail, "
            f"in {p['same_above']}/{n} the time above 15° (the second orbit added none); median ≤ 5° in "
            f"{p['median_ok_2']}/{n} two-orbit runs."
            + ("" if not p["still_missing"] else
               f" The {len(p['still_missing'])} that still miss have tails of "
               + ", ".join(f"{t:.0f} s" for t, _ in p["still_missing"]) + " against 5 % of their two-orbit window ("
               + ", ".join(f"{w:.0f} s" for _, w in p["still_missing"]) + ").") + "\n")


def main(argv: list[str]) -> int:
    if len(argv) not in (1, 2):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    from fprime_lite.tools.campaign import read_results

    frames = []
    for folder in map(pathlib.Path, argv):
        try:
            frames.append(read_results(folder))
        except (FileNotFoundError, OSError) as exc:
            print(f"report_pointing_plant: no campaign results in {folder} ({exc}): give the --out folder of "
                  "`fprime-lite campaign campaigns/adcs/pointing_magnetorquers_plant.yaml` (and, second, of "
                  "pointing_magnetorquers_plant_2orbits.yaml)", file=sys.stderr)
            return 2
    try:
        print(markdown(analyse(frames[0])), end="")
        if len(frames) == 2:
            print("\n" + paired_markdown(paired(*frames)), end="")
    except KeyError as exc:
        print(f"report_pointing_plant: the results have no {exc.args[0]} column: the campaign was run before its "
              "file listed pointing_acquisition_s, pointing_acquisition_15deg_s and pointing_error_deg.*; run it "
              "again", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
