"""Pointing campaign metrics on a hand-made run folder (attitude.csv, events.log) and summary."""

import pytest

from detumble.reports.pointing_metrics import METRICS, STEADY_AFTER_S
from fprime_lite.tools.campaign import MetricUnavailable, RunOutput

BY_NAME = {m.name: m for m in METRICS}
HEADER = "t_s,mode,pointing_error_deg\n"


def run_folder(tmp_path, rows, events=""):
    (tmp_path / "attitude.csv").write_text(HEADER + "".join(f"{t},{m},{e}\n" for t, m, e in rows))
    (tmp_path / "events.log").write_text(events)
    return tmp_path


def value(name, summary, out_dir):
    return BY_NAME[name].compute(RunOutput(summary=summary, out_dir=out_dir), None)


def test_steady_statistics_start_after_the_last_target_change(tmp_path):
    """PM-001: a slew at 10 s; the samples before 10 + 60 s (large errors) are left out, and the median / p95 are
    of the samples after (0.001 … 0.100° in 0.001° steps: median 0.0505°, p95 0.09505° by linear interpolation);
    samples outside POINTING are left out too."""
    rows = [(t * 0.5, "POINTING", 5.0) for t in range(0, 2 * int(10 + STEADY_AFTER_S))]
    rows += [(10 + STEADY_AFTER_S + i * 0.5, "POINTING", (i + 1) * 0.001) for i in range(100)]
    rows += [(500.0, "SPIN_STABLE", 9.0)]
    out = run_folder(tmp_path, rows)
    summary = {"slews": [{"t_s": 10.0, "angle_deg": 90.0, "settle_below_0p1_deg_s": 21.5}],
               "wheel_momentum_max_fraction": 0.07}
    assert value("pointing_steady_median_deg", summary, out) == pytest.approx(0.0505)
    assert value("pointing_steady_p95_deg", summary, out) == pytest.approx(0.09505)
    assert value("slew_settle_s", summary, out) == 21.5
    assert value("wheel_momentum_max_fraction", summary, out) == 0.07


def test_unsettled_or_missing_slews_are_reported_not_invented(tmp_path):
    """PM-002: no slew while POINTING, or one that never settled, is MetricUnavailable with the reason."""
    out = run_folder(tmp_path, [(0.0, "POINTING", 1.0)])
    with pytest.raises(MetricUnavailable, match="no target change"):
        value("slew_settle_s", {"slews": []}, out)
    with pytest.raises(MetricUnavailable, match="never settled"):
        value("slew_settle_s", {"slews": [{"t_s": 0.0, "angle_deg": 90, "settle_below_0p1_deg_s": None}]}, out)
    with pytest.raises(MetricUnavailable, match="AttitudeRunReport"):
        value("slew_settle_s", {}, out)


def test_limit_events_are_counted(tmp_path):
    """PM-003: WheelLimitReached and the drivers' saturation events are counted; other lines are not."""
    events = ("t ReferenceDeployment.attitudeController.WheelLimitReached WARNING_LO cut\n"
              "t ReferenceDeployment.reactionWheel0.TorqueSaturated WARNING_LO clip\n"
              "t ReferenceDeployment.starTracker.NoSolution WARNING_LO none\n")
    out = run_folder(tmp_path, [(0.0, "POINTING", 1.0)], events)
    assert value("wheel_limit_events", {}, out) == 2.0
