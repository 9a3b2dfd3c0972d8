"""Campaign metrics of pointing runs on an attitude-control deployment (``deployments/adcs_ref``).

Registered through the ``fprime_lite.campaign_metrics`` entry point ``detumble_pointing``. They read what
:class:`~detumble.reports.attitude_report.AttitudeRunReport` wrote: ``summary.json``'s ``slews`` and
``wheel_momentum_max_fraction``, ``attitude.csv`` (true pointing error every 0.5 s) and ``events.log``.

* ``slew_settle_s``: seconds from the first target change made while POINTING until the true error stays
  below 0.1° (the issue's slew target);
* ``pointing_steady_median_deg`` / ``pointing_steady_p95_deg``: statistics of the true error over the POINTING
  samples from ``STEADY_AFTER_S`` after the last target change (or after the first 10 % of POINTING when
  there was none) to the end: the steady-state hold;
* ``wheel_momentum_max_fraction``: largest ``|h_i| / h_max`` of the run;
* ``wheel_limit_events``: WheelLimitReached (the controller cut a request) plus the wheel drivers' saturation
  events in the run's event log (0: no limit was ever reached);
* the pooling columns of ``summary.json``'s ``pointing_error_deg`` and ``spin_axis_error_deg``
  (:mod:`detumble.analysis.pooled_stats`): ``PREFIX.window_s``, ``PREFIX.sample_interval_s`` (s),
  ``PREFIX.time_above_s.X`` (s above X deg) and ``PREFIX.histogram_s.I`` (s in histogram bin I, 0 … 126), one
  float column each, so that a campaign's results.parquet can pool its runs (list them all in ``metrics``:
  :func:`~detumble.analysis.pooled_stats.column_names` gives the names); ``pointing_steady.…``: the same
  fields of the steady-hold samples of ``pointing_steady_median_deg`` (each sample standing for
  ``pointing_error_deg.sample_interval_s``).
"""

from __future__ import annotations

import csv
import math
import pathlib

from fprime_lite.tools.campaign import Metric, MetricUnavailable, RunOutput

from detumble.analysis.pooled_stats import (N_BINS, POINTING_THRESHOLDS_DEG, SPIN_THRESHOLDS_DEG, dense_histogram,
                                            percentile, pooling_fields, threshold_key)

__all__ = ["METRICS", "POOLING_METRICS", "STEADY_AFTER_S", "percentile", "steady_errors"]

STEADY_AFTER_S = 60.0
_POINTING = ("POINTING", "3")  # the mode column of attitude.csv (by name; a number in older runs)
_LIMIT_EVENTS = ("WheelLimitReached", "TorqueSaturated", "MomentumSaturated")


def _out(output: RunOutput) -> pathlib.Path:
    return pathlib.Path(output.out_dir or ".")


def _slews(output: RunOutput) -> list:
    slews = output.summary.get("slews")
    if slews is None:
        raise MetricUnavailable("summary.json has no 'slews': the topology has no AttitudeRunReport")
    return slews


def _slew_settle(output: RunOutput, _probe) -> float:
    slews = _slews(output)
    if not slews:
        raise MetricUnavailable("no target change while POINTING (the sequence must change the target after "
                                "FORCE_MODE POINTING)")
    settle = slews[0]["settle_below_0p1_deg_s"]
    if settle is None:
        raise MetricUnavailable("the slew never settled below 0.1 deg within the run")
    return float(settle)


def steady_errors(output: RunOutput) -> list[float]:
    """True pointing errors (deg) of the steady hold, as defined in the module docstring."""
    path = _out(output) / "attitude.csv"
    if not path.is_file():
        raise MetricUnavailable("the run wrote no attitude.csv (the topology has no AttitudeRunReport)")
    with open(path, newline="", encoding="utf-8") as fh:
        rows = [(float(r["t_s"]), float(r["pointing_error_deg"])) for r in csv.DictReader(fh)
                if r["mode"] in _POINTING]
    rows = [r for r in rows if math.isfinite(r[1])]
    slews = _slews(output)
    if slews:
        start = slews[-1]["t_s"] + STEADY_AFTER_S
        errors = [e for t, e in rows if t >= start]
    else:
        errors = [e for _, e in rows[len(rows) // 10:]]
    if not errors:
        raise MetricUnavailable(f"no POINTING samples {STEADY_AFTER_S:g} s after the last target change")
    return errors


def _wheel_fraction(output: RunOutput, _probe) -> float:
    value = output.summary.get("wheel_momentum_max_fraction")
    if value is None:
        raise MetricUnavailable("no reaction wheels (summary.json wheel_momentum_max_fraction is null or absent)")
    return float(value)


def _limit_events(output: RunOutput, _probe) -> float:
    path = _out(output) / "events.log"
    if not path.is_file():
        raise MetricUnavailable("the run wrote no events.log")
    with open(path, encoding="utf-8") as fh:
        return float(sum(1 for line in fh if any(f".{name} " in line for name in _LIMIT_EVENTS)))


def _pooling_block(output: RunOutput, prefix: str) -> dict:
    stats = output.summary.get(prefix)
    if not isinstance(stats, dict):
        raise MetricUnavailable(f"summary.json {prefix} is null or absent (no samples in that mode, or no "
                                "AttitudeRunReport)")
    if "window_s" not in stats:
        raise MetricUnavailable(f"summary.json {prefix} has no pooling fields (written before they existed)")
    return stats


def _pooling_metric(prefix: str, field: str, key, unit: str, description: str, block) -> Metric:
    """One float column of a statistics block's pooling fields: ``field`` (``key`` inside it, when given)."""
    def compute(output: RunOutput, _probe) -> float:
        stats = block(output, prefix)
        if field == "histogram_s":
            return dense_histogram(stats["histogram_s"])[key]
        value = stats[field] if key is None else stats[field].get(key)
        if value is None:
            raise MetricUnavailable(f"summary.json {prefix}.{field} has no {key!r}")
        return float(value)
    name = f"{prefix}.{field}" + ("" if key is None else f".{key}")
    return Metric(name, unit, description, compute)


def _pooling_metrics(prefix: str, thresholds: tuple[float, ...], what: str, block=_pooling_block
                     ) -> tuple[Metric, ...]:
    return (
        _pooling_metric(prefix, "window_s", None, "s", f"time the {what} statistics cover (samples × interval)",
                        block),
        _pooling_metric(prefix, "sample_interval_s", None, "s", f"time each {what} sample stands for", block),
        *(_pooling_metric(prefix, "time_above_s", threshold_key(x), "s", f"time with the {what} above {x:g} deg",
                          block) for x in thresholds),
        *(_pooling_metric(prefix, "histogram_s", i, "s", f"time with the {what} in histogram bin {i} "
                          "(detumble.analysis.pooled_stats)", block) for i in range(N_BINS)),
    )


_steady_cache: dict = {}  # the last run's: "key", "errors" and its pooling fields by sample interval


def _steady(output: RunOutput) -> dict:
    """:func:`steady_errors` of ``output``, read from attitude.csv once per run for all the metrics that use
    it (the key holds attitude.csv's path, size and mtime and the slews)."""
    path = _out(output) / "attitude.csv"
    st = path.stat() if path.is_file() else None
    key = (str(path.resolve()), st.st_size if st else None, st.st_mtime_ns if st else None,
           repr(output.summary.get("slews")))
    if _steady_cache.get("key") != key:
        errors = steady_errors(output)
        _steady_cache.clear()
        _steady_cache.update(key=key, errors=errors, pooled={})
    return _steady_cache


def _steady_block(output: RunOutput, _prefix: str) -> dict:
    """The pooling fields of :func:`steady_errors` (attitude.csv), each sample standing for the report's sample
    interval; computed once per run."""
    stats = output.summary.get("pointing_error_deg")
    if not isinstance(stats, dict) or "sample_interval_s" not in stats:
        raise MetricUnavailable("summary.json pointing_error_deg has no sample_interval_s (no POINTING, or "
                                "written before the pooling fields existed)")
    steady, interval = _steady(output), float(stats["sample_interval_s"])
    if interval not in steady["pooled"]:
        steady["pooled"][interval] = pooling_fields(steady["errors"], interval, POINTING_THRESHOLDS_DEG)
    return steady["pooled"][interval]


POOLING_METRICS = (_pooling_metrics("pointing_error_deg", POINTING_THRESHOLDS_DEG, "POINTING error")
                   + _pooling_metrics("spin_axis_error_deg", SPIN_THRESHOLDS_DEG, "SPIN_STABLE spin-axis error")
                   + _pooling_metrics("pointing_steady", POINTING_THRESHOLDS_DEG, "steady-hold pointing error",
                                      _steady_block))

METRICS = (
    Metric("slew_settle_s", "s", "first target change while POINTING until the true error stays below 0.1 deg",
           _slew_settle),
    Metric("pointing_steady_median_deg", "deg", f"median true pointing error from {STEADY_AFTER_S:g} s after the "
           "last target change", lambda output, _probe: percentile(_steady(output)["errors"], 0.5)),
    Metric("pointing_steady_p95_deg", "deg", f"95th percentile of the true pointing error from {STEADY_AFTER_S:g} s "
           "after the last target change", lambda output, _probe: percentile(_steady(output)["errors"], 0.95)),
    Metric("wheel_momentum_max_fraction", "1", "largest |h_i|/h_max of any wheel over the run", _wheel_fraction),
    Metric("wheel_limit_events", "1", "wheel torque/momentum limit events in the run's event log", _limit_events),
    *POOLING_METRICS,
)
