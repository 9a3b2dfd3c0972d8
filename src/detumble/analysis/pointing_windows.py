"""Pointing statistics with the acquisition reported apart from the steady hold (plain Python, no framework).

A POINTING run is cut into **intervals**: one starts at the first POINTING sample after entering the mode, at a
target change and when the active reference changes (a ground station rising or setting). In each interval the
**acquisition** is the time from its first sample to the first sample after which the true error stays below the
threshold for the rest of the interval (None: it never does, and the whole interval counts as acquisition). The
**steady** statistics pool the samples after each acquisition, and nothing else: no fixed fraction is dropped.

Thresholds (stated in every summary): :data:`ACQUISITION_THRESHOLD_WHEELS_DEG` on the wheels (20× the wheel goals'
p95, so it does not cap the steady statistics near their goals) and :data:`ACQUISITION_THRESHOLD_COILS_DEG` on the
magnetorquers (2× their p95 goal of 15°). By construction a steady sample is below its interval's threshold: the
steady maximum can never exceed it, which is why the thresholds sit well above the goals.
"""

from __future__ import annotations

from typing import Hashable, Sequence

from detumble.analysis.pooled_stats import POINTING_THRESHOLDS_DEG, error_statistics

__all__ = ["ACQUISITION_THRESHOLD_WHEELS_DEG", "ACQUISITION_THRESHOLD_COILS_DEG", "pointing_windows",
           "acquisition_time", "pointing_summary"]

#: deg: the acquisition threshold of an interval flown on the reaction wheels.
ACQUISITION_THRESHOLD_WHEELS_DEG = 1.0
#: deg: the acquisition threshold of an interval flown on the magnetorquers.
ACQUISITION_THRESHOLD_COILS_DEG = 30.0


def acquisition_time(times: Sequence[float], errors: Sequence[float], threshold_deg: float) -> float | None:
    """Seconds from ``times[0]`` to the first sample after which every error is below ``threshold_deg`` (None when
    the last sample is not)."""
    last_bad = None
    for i in range(len(errors) - 1, -1, -1):
        if not errors[i] < threshold_deg:
            last_bad = i
            break
    if last_bad is None:
        return 0.0
    if last_bad == len(errors) - 1:
        return None
    return times[last_bad + 1] - times[0]


def pointing_windows(samples: Sequence[tuple[float, float, Hashable, str, bool]], sample_interval_s: float) -> dict:
    """Acquisition and steady statistics of POINTING ``samples`` ``(t_s, error_deg, key, label, on_wheels)`` in time
    order (``key``: what was commanded and which reference was active; ``label``: the reference's name; a gap of
    more than 1.5 sample intervals means POINTING was left). Returns::

        {"steady": error_statistics of the steady samples (None: none) with "window": "steady",
         "acquisition_s": the first interval's, "acquisition_threshold_deg": its threshold,
         "intervals": [{"t_s", "target", "threshold_deg", "acquisition_s", "samples", "steady_samples"}],
         "by_target": {label: steady error_statistics}}
    """
    intervals: list[list] = []
    prev = None
    for s in samples:
        if prev is None or s[2] != prev[2] or s[0] - prev[0] > 1.5 * sample_interval_s:
            intervals.append([])
        intervals[-1].append(s)
        prev = s
    steady: list[float] = []
    by_label: dict[str, list[float]] = {}
    out_intervals = []
    for iv in intervals:
        times = [s[0] for s in iv]
        errors = [s[1] for s in iv]
        threshold = ACQUISITION_THRESHOLD_WHEELS_DEG if iv[0][4] else ACQUISITION_THRESHOLD_COILS_DEG
        acq = acquisition_time(times, errors, threshold)
        kept = [] if acq is None else [e for t, e in zip(times, errors, strict=True) if t - times[0] >= acq]
        steady += kept
        by_label.setdefault(iv[0][3], []).extend(kept)
        out_intervals.append({"t_s": times[0], "target": iv[0][3], "threshold_deg": threshold, "acquisition_s": acq,
                              "samples": len(iv), "steady_samples": len(kept)})

    def stats(values: list[float]) -> dict | None:
        return error_statistics(values, 0.0, sample_interval_s=sample_interval_s,
                                thresholds_deg=POINTING_THRESHOLDS_DEG)

    block = stats(steady)
    if block is not None:
        block["window"] = "steady"
    first = out_intervals[0] if out_intervals else None
    return {"steady": block,
            "acquisition_s": first["acquisition_s"] if first else None,
            "acquisition_threshold_deg": first["threshold_deg"] if first else None,
            "intervals": out_intervals,
            "by_target": {label: stats(v) for label, v in by_label.items()}}


def pointing_summary(samples: Sequence[tuple[float, float, Hashable, str, bool]], sample_interval_s: float) -> dict:
    """The summary.json keys of :func:`pointing_windows`: ``pointing_error_deg`` (the steady statistics with
    ``window``, ``acquisition_s`` and ``acquisition_threshold_deg`` of the first interval; None without a steady
    sample), ``pointing_intervals`` and ``pointing_error_by_target_deg``."""
    w = pointing_windows(samples, sample_interval_s)
    block = w["steady"]
    if block is not None:
        block["acquisition_s"] = w["acquisition_s"]
        block["acquisition_threshold_deg"] = w["acquisition_threshold_deg"]
    return {"pointing_error_deg": block, "pointing_intervals": w["intervals"],
            "pointing_error_by_target_deg": w["by_target"]}
