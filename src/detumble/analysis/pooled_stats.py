"""Pooling error statistics over many runs: fractions of time above thresholds, percentiles, shares of runs.

A run's percentiles cannot be combined into the percentile of all runs' time together. What can be combined
exactly is *time*: how long each run's statistics cover (``window_s``), how long the error was above a fixed
threshold (``time_above_s``) and how long it spent in each bin of a fixed histogram (``histogram_s``). The
run's attitude report writes these beside its median/p95/max (:func:`pooling_fields`); the functions here sum
them over runs.

Weighting. The report samples the truth at a fixed interval ``w`` (0.5 s) and each sample stands for ``w``
seconds, so a run's time above a threshold is ``w`` × the number of samples above it and ``window_s`` is ``w`` ×
the sample count: the same sample weighting as the run's own median and p95. Pooled over runs the weights are
the runs' time (a 2-hour run counts twice a 1-hour run), which is the percentile of all runs' samples put
together when every run samples at the same interval.

Histogram. Angles in degrees, fixed bins: bin 0 is ``[0, 1e-4)``; bins 1 … 126 are log-spaced, 20 per decade,
``[1e-4·10^((i-1)/20), 1e-4·10^(i/20))``, the last one cut at and closed on 180°. A pooled percentile from the
summed histograms is known to within its bracket: bins are 12.2 % wide (a factor 10^(1/20)); the bracket runs
from the bin of the sample ranked about one below ``p·n`` to that of the sample ranked at it, so with many
samples near the percentile it is one to three bins — see :func:`pooled_percentile`.

Thresholds. The pooled p-quantile of the time-weighted distribution is ≤ x exactly when the pooled fraction of
time above x is ≤ 1 - p (pooled p95 ≤ 15° ⇔ at most 5 % of the time above 15°): :func:`pooled_fraction_above`
is exact, with no bin error.

Campaign columns. The attitude-control campaign metrics (:mod:`detumble.reports.pointing_metrics`) give every field
one float column, named ``PREFIX.window_s``, ``PREFIX.sample_interval_s``, ``PREFIX.time_above_s.X`` (X as in
:func:`threshold_key`) and ``PREFIX.histogram_s.I`` (I = 0 … 126); :func:`runs_from_columns` reads them back.

Plain Python and math only (no framework import).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from typing import Any, Iterable, Mapping, Sequence

__all__ = ["BINS_PER_DECADE", "LOW_DEG", "HIGH_DEG", "EDGES_DEG", "N_BINS", "POINTING_THRESHOLDS_DEG",
           "SPIN_THRESHOLDS_DEG", "error_statistics", "percentile", "sorted_percentile", "RunTimes",
           "PooledPercentile", "Share", "bin_index", "bin_bounds", "threshold_key", "pooling_fields",
           "dense_histogram", "run_times", "pooled_window_s",
           "pooled_fraction_above", "pooled_percentile", "wilson_lower", "per_run_share", "column_names",
           "runs_from_columns", "pooled_lines", "target_lines"]

BINS_PER_DECADE = 20
LOW_DEG = 1e-4
HIGH_DEG = 180.0
#: The upper edges of bins 0 … N_BINS-1, deg: bin 0 is [0, EDGES_DEG[0]), bin i is [EDGES_DEG[i-1], EDGES_DEG[i]).
EDGES_DEG: tuple[float, ...] = tuple(
    [LOW_DEG * 10.0 ** (k / BINS_PER_DECADE)
     for k in range(math.ceil(BINS_PER_DECADE * math.log10(HIGH_DEG / LOW_DEG)))] + [HIGH_DEG])
N_BINS = len(EDGES_DEG)
#: time_above_s thresholds of the pointing error (issue 13's wheel and magnetorquer targets among them), deg.
POINTING_THRESHOLDS_DEG = (0.01, 0.05, 0.1, 1.0, 5.0, 15.0)
#: time_above_s thresholds of the spin-axis error (5°: the stable-spin band), deg.
SPIN_THRESHOLDS_DEG = (1.0, 5.0, 15.0)


def bin_index(value_deg: float) -> int:
    """The histogram bin of an angle (deg, ≥ 0); 180° and the rounding just above it go to the last bin."""
    if not value_deg >= 0.0:
        raise ValueError(f"an angle for the histogram must be a number >= 0 deg, got {value_deg!r}")
    return min(bisect.bisect_right(EDGES_DEG, value_deg), N_BINS - 1)


def bin_bounds(index: int) -> tuple[float, float]:
    """``(lower, upper)`` edges of bin ``index``, deg."""
    if not 0 <= index < N_BINS:
        raise IndexError(f"histogram bin {index} is outside 0 … {N_BINS - 1}")
    return (0.0 if index == 0 else EDGES_DEG[index - 1]), EDGES_DEG[index]


def threshold_key(threshold_deg: float) -> str:
    """The key of a threshold in ``time_above_s`` and in column names: ``15``, ``0.05``."""
    return f"{threshold_deg:g}"


def pooling_fields(values_deg: Sequence[float], sample_interval_s: float,
                   thresholds_deg: Sequence[float]) -> dict:
    """What a run's summary needs for pooling, each sample counting ``sample_interval_s`` seconds.

    Returns ``{"sample_interval_s", "window_s", "time_above_s": {key: s}, "histogram_s": {"first_bin",
    "time_s": [s, …]}}``: ``time_above_s`` is the time strictly above each threshold; ``histogram_s`` the
    time in bins ``first_bin`` … ``first_bin + len(time_s) - 1`` (every other bin holds no time).
    """
    if not sample_interval_s > 0:
        raise ValueError(f"sample_interval_s must be positive, got {sample_interval_s!r}")
    counts = [0] * N_BINS
    for v in values_deg:
        counts[bin_index(v)] += 1
    used = [i for i, c in enumerate(counts) if c]
    first, last = (used[0], used[-1]) if used else (0, -1)
    return {
        "sample_interval_s": sample_interval_s,
        "window_s": len(values_deg) * sample_interval_s,
        "time_above_s": {threshold_key(x): sum(1 for v in values_deg if v > x) * sample_interval_s
                         for x in thresholds_deg},
        "histogram_s": {"first_bin": first, "time_s": [c * sample_interval_s for c in counts[first:last + 1]]},
    }


def dense_histogram(histogram_s: Mapping[str, Any]) -> list[float]:
    """A summary's ``histogram_s`` as seconds in every bin 0 … N_BINS-1."""
    first, times = int(histogram_s["first_bin"]), list(histogram_s["time_s"])
    if first < 0 or first + len(times) > N_BINS:
        raise ValueError(f"histogram bins {first} … {first + len(times) - 1} are outside 0 … {N_BINS - 1}")
    return [0.0] * first + [float(t) for t in times] + [0.0] * (N_BINS - first - len(times))


@dataclass(frozen=True)
class RunTimes:
    """One run's pooling data: seconds covered, sample interval, time above each threshold key, time per bin."""

    window_s: float
    sample_interval_s: float
    time_above_s: Mapping[str, float]
    histogram_s: Sequence[float]  # dense, N_BINS entries


def run_times(fields: Mapping[str, Any]) -> RunTimes:
    """A :class:`RunTimes` from the fields :func:`pooling_fields` wrote (a summary's statistics block)."""
    return RunTimes(float(fields["window_s"]), float(fields["sample_interval_s"]),
                    {k: float(v) for k, v in fields["time_above_s"].items()}, dense_histogram(fields["histogram_s"]))


def pooled_window_s(runs: Iterable[RunTimes]) -> float:
    """Total time the runs' statistics cover, s."""
    return math.fsum(r.window_s for r in runs)


def pooled_fraction_above(runs: Sequence[RunTimes], threshold_deg: float) -> float:
    """Fraction (0…1) of all the runs' time with the error above ``threshold_deg``: exact, time-weighted.

    The threshold must be one each run recorded (``time_above_s``); NaN when the runs cover no time.
    """
    key = threshold_key(threshold_deg)
    missing = [i for i, r in enumerate(runs) if key not in r.time_above_s]
    if missing:
        raise KeyError(f"runs {missing[:5]} have no time_above_s at {key} deg (they have "
                       f"{', '.join(sorted(runs[missing[0]].time_above_s, key=float))})")
    total = pooled_window_s(runs)
    if total == 0:
        return float("nan")
    return math.fsum(r.time_above_s[key] for r in runs) / total


@dataclass(frozen=True)
class PooledPercentile:
    """A percentile of all the runs' time: ``estimate_deg`` (log-interpolated inside its bin) and the bracket
    ``[lower_deg, upper_deg]`` that certainly holds it."""

    p: float
    estimate_deg: float
    lower_deg: float
    upper_deg: float


def pooled_percentile(runs: Sequence[RunTimes], p: float) -> PooledPercentile:
    """The ``p`` quantile (0…1) of the error over all the runs' time, from their summed histograms.

    The time-weighted quantile ``inf{x : time(error ≤ x) ≥ p·T}`` lies in the bin where the cumulative time
    first reaches ``p·T``. The bracket runs from the first bin whose cumulative time exceeds ``p·T - w`` to
    the first that reaches ``p·T + (1 - p)·w`` (``w``, the largest sample interval), so it also holds the
    linear-interpolated percentile of the concatenated samples (what
    :func:`error_statistics` computes for one run) when the runs share one
    interval: that percentile lies between the samples ranked ``floor((n-1)p)`` and ``ceil((n-1)p)``, which
    are in those bins or between them.
    """
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"p is a fraction 0…1, got {p!r}")
    if not runs:
        raise ValueError("no runs to pool")
    total = pooled_window_s(runs)
    if not total > 0:
        raise ValueError("the runs cover no time (window_s sums to 0)")
    w = max(r.sample_interval_s for r in runs)
    summed = [math.fsum(r.histogram_s[i] for r in runs) for i in range(N_BINS)]
    cum, acc = [], 0.0
    for t in summed:
        acc += t
        cum.append(acc)
    used = [i for i, t in enumerate(summed) if t > 0]
    slack = 1e-9 * total

    def first_reaching(level: float, strictly: bool) -> int:
        for i in used:
            if cum[i] > level if strictly else cum[i] >= level:
                return i
        return used[-1]

    centre = first_reaching(p * total - slack, False)
    lo_bin = first_reaching(p * total - w - slack, True)
    hi_bin = first_reaching(p * total + (1.0 - p) * w + slack, False)
    lower, upper = bin_bounds(lo_bin)[0], bin_bounds(hi_bin)[1]
    a, b = bin_bounds(centre)
    below = cum[centre] - summed[centre]
    frac = min(1.0, max(0.0, (p * total - below) / summed[centre]))
    estimate = min(b, max(a, a + (b - a) * frac if a == 0.0 else a * (b / a) ** frac))  # rounding stays in
    return PooledPercentile(p, estimate, lower, upper)


def wilson_lower(successes: int, n: int, z: float = 1.96) -> float:
    """Lower end of the Wilson score interval (95 % for z = 1.96) of a binomial fraction."""
    if n == 0:
        return float("nan")
    p = successes / n
    centre = p + z * z / (2 * n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (centre - half) / (1 + z * z / n)


@dataclass(frozen=True)
class Share:
    """``successes`` of ``n`` runs, their fraction and its 95 % Wilson lower bound."""

    successes: int
    n: int
    fraction: float
    lower95: float


def per_run_share(hits: Iterable[bool]) -> Share:
    """The share of runs for which ``hits`` is true, with its 95 % Wilson lower bound."""
    flags = [bool(h) for h in hits]
    k, n = sum(flags), len(flags)
    return Share(k, n, k / n if n else float("nan"), wilson_lower(k, n))


def column_names(prefix: str, thresholds_deg: Sequence[float]) -> list[str]:
    """The campaign columns of one statistics block (``prefix``: ``pointing_error_deg``, …)."""
    return ([f"{prefix}.window_s", f"{prefix}.sample_interval_s"]
            + [f"{prefix}.time_above_s.{threshold_key(x)}" for x in thresholds_deg]
            + [f"{prefix}.histogram_s.{i}" for i in range(N_BINS)])


def runs_from_columns(columns: Mapping[str, Sequence[float]], prefix: str,
                      thresholds_deg: Sequence[float]) -> list[RunTimes]:
    """The runs of a results table (a DataFrame or ``{column: values}``) that have pooling data.

    A run whose ``PREFIX.window_s`` is null/NaN (no samples in that mode, or not ok) is left out. Raises
    ``KeyError`` naming the missing columns when the table does not have them all.
    """
    names = column_names(prefix, thresholds_deg)
    missing = [c for c in names if c not in columns]
    if missing:
        raise KeyError(f"the results have no {', '.join(missing[:3])}{' …' if len(missing) > 3 else ''} "
                       f"({len(missing)} of the {len(names)} pooling columns of {prefix} missing)")
    cols = {c: [float(v) for v in columns[c]] for c in names}
    runs = []
    for j, window in enumerate(cols[f"{prefix}.window_s"]):
        if not math.isfinite(window):
            continue
        runs.append(RunTimes(window, cols[f"{prefix}.sample_interval_s"][j],
                             {threshold_key(x): cols[f"{prefix}.time_above_s.{threshold_key(x)}"][j]
                              for x in thresholds_deg},
                             [cols[f"{prefix}.histogram_s.{i}"][j] for i in range(N_BINS)]))
    return runs


def pooled_lines(runs: Sequence[RunTimes], thresholds_deg: Sequence[float], what: str) -> list[str]:
    """Text lines of the pooled figures of ``runs``: total time, median and p95 with their brackets, the
    fraction of time above each threshold (deg)."""
    if not runs:
        return [f"pooled {what}: no run has pooling data"]
    total = pooled_window_s(runs)
    lines = [f"pooled {what} over {len(runs)} runs, {total:.0f} s (time-weighted; percentile brackets: histogram "
             f"bins, 10^(1/{BINS_PER_DECADE}) wide)"]
    for p in (0.5, 0.95):
        q = pooled_percentile(runs, p)
        lines.append(f"  pooled p{100 * p:g} {q.estimate_deg:.4g} deg  (within [{q.lower_deg:.4g}, "
                     f"{q.upper_deg:.4g}] deg)")
    for x in thresholds_deg:
        lines.append(f"  time above {x:g} deg: {100 * pooled_fraction_above(runs, x):.2f} %  (exact)")
    return lines


def target_lines(runs: Sequence[RunTimes], targets: Sequence[tuple[float, float]]) -> list[str]:
    """Pooled verdicts on percentile targets ``[(p, x_deg), …]`` (p95 ≤ 15°: ``(0.95, 15.0)``), each exact from
    the fraction of time above x (the pooled p-quantile is ≤ x ⇔ that fraction is ≤ 1 - p); x must be one of
    the runs' thresholds."""
    lines = []
    for p, x in targets:
        above = pooled_fraction_above(runs, x)
        verdict = "met" if above <= 1.0 - p else "missed"
        lines.append(f"pooled p{100 * p:g} <= {x:g} deg (time above {x:g} deg <= {100 * (1 - p):g} %): {verdict} "
                     f"({100 * above:.2f} % of the time above)")
    return lines


def sorted_percentile(s: Sequence[float], p: float) -> float:
    """The ``p`` quantile (0…1) of the sorted samples ``s`` by linear interpolation between order statistics
    (numpy's default method)."""
    k = (len(s) - 1) * p
    lo = math.floor(k)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


def percentile(values: Iterable[float], p: float) -> float:
    """The ``p`` quantile (0…1) of ``values`` by linear interpolation (:func:`sorted_percentile`)."""
    return sorted_percentile(sorted(values), p)


def error_statistics(values: list[float], skip_fraction: float = 0.1, *, sample_interval_s: float | None = None,
                     thresholds_deg: tuple[float, ...] = ()) -> dict | None:
    """``{"median", "p95", "max", "samples"}`` of ``values`` (deg) after dropping their first ``skip_fraction``.

    Sample-weighted (linear-interpolated percentiles over the kept samples). With ``sample_interval_s`` (s, the
    time each sample stands for) the pooling fields of :func:`detumble.analysis.pooled_stats.pooling_fields`
    over the same samples are added: ``sample_interval_s``, ``window_s``, ``time_above_s`` at ``thresholds_deg``
    and ``histogram_s``. None when no sample is kept.
    """
    kept = values[int(len(values) * skip_fraction):]
    if not kept:
        return None
    s = sorted(kept)
    stats = {"median": sorted_percentile(s, 0.5), "p95": sorted_percentile(s, 0.95), "max": s[-1], "samples": len(s)}
    if sample_interval_s is not None:
        stats.update(pooling_fields(kept, sample_interval_s, thresholds_deg))
    return stats
