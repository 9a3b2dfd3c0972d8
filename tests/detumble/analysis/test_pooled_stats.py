"""Pooling error statistics over runs (detumble.analysis.pooled_stats): angles deg, times s."""

import math
import random

import numpy as np
import pytest

from detumble.analysis import pooled_stats as ps
from detumble.reports.attitude_report import error_statistics

W = 0.5  # the attitude report's sample interval, s


def run(values, w=W, thresholds=ps.POINTING_THRESHOLDS_DEG):
    return ps.run_times(ps.pooling_fields(values, w, thresholds))


def exact_percentile(values, p):
    """The linear-interpolated percentile the run summary uses (numpy's default method)."""
    return float(np.percentile(np.asarray(values, dtype=float), 100.0 * p))


def test_bins_are_fixed_log_spaced_and_cover_0_to_180():
    assert ps.N_BINS == 127 and ps.bin_bounds(0) == (0.0, 1e-4) and ps.bin_bounds(126) == (ps.EDGES_DEG[125], 180.0)
    ratios = [b / a for a, b in zip(ps.EDGES_DEG[:-2], ps.EDGES_DEG[1:-1], strict=True)]
    assert all(r == pytest.approx(10 ** 0.05, rel=1e-12) for r in ratios)
    assert ps.bin_index(0.0) == 0 and ps.bin_index(9.99e-5) == 0 and ps.bin_index(1e-4) == 1
    assert ps.bin_index(0.01) == 41  # 1e-2 = 1e-4·10^(40/20) is the lower edge of bin 41
    assert ps.bin_index(180.0) == ps.bin_index(180.0000001) == 126
    with pytest.raises(ValueError, match=">= 0 deg"):
        ps.bin_index(-1e-9)
    with pytest.raises(ValueError, match=">= 0 deg"):
        ps.bin_index(float("nan"))


def test_closed_form_trace():
    """600 samples at 0.001°, 300 at 2°, 100 at 20°, 0.5 s each: 500 s, 150 + 50 s above 1°, 50 s above 15°."""
    values = [0.001] * 600 + [2.0] * 300 + [20.0] * 100
    random.Random(1).shuffle(values)
    f = ps.pooling_fields(values, W, ps.POINTING_THRESHOLDS_DEG)
    assert f["window_s"] == 500.0 and f["sample_interval_s"] == W
    assert f["time_above_s"] == {"0.01": 200.0, "0.05": 200.0, "0.1": 200.0, "1": 200.0, "5": 50.0, "15": 50.0}
    dense = ps.dense_histogram(f["histogram_s"])
    assert sum(dense) == 500.0 and dense[ps.bin_index(0.001)] == 300.0
    assert dense[ps.bin_index(2.0)] == 150.0 and dense[ps.bin_index(20.0)] == 50.0
    assert f["histogram_s"]["first_bin"] == ps.bin_index(0.001)
    assert len(f["histogram_s"]["time_s"]) == ps.bin_index(20.0) - ps.bin_index(0.001) + 1
    r = ps.run_times(f)
    assert ps.pooled_fraction_above([r], 15.0) == 0.1 and ps.pooled_fraction_above([r], 1.0) == 0.4
    median, p95 = ps.pooled_percentile([r], 0.5), ps.pooled_percentile([r], 0.95)
    assert median.lower_deg <= 0.001 <= median.upper_deg and median.upper_deg < 0.0012
    assert p95.lower_deg <= 20.0 <= p95.upper_deg and p95.lower_deg > 17.0
    # the run's own (sample-weighted) statistics are the same samples
    s = error_statistics(values, skip_fraction=0.0)
    assert s["median"] == 0.001 and s["p95"] == 20.0


def test_time_above_is_strictly_above():
    f = ps.pooling_fields([5.0, 5.0, 5.0000001, 15.0], W, (5.0, 15.0))
    assert f["time_above_s"] == {"5": 1.0, "15": 0.0}


def test_pooling_two_runs_of_different_lengths_is_time_weighted():
    """A 50 s run at 1° and a 450 s run at 10°: the pooled median is 10° and 90 % of the time is above 5°,
    not the mean of the medians (5.5°) nor the mean of the fractions (50 %)."""
    short, long_ = run([1.0] * 100), run([10.0] * 900)
    assert ps.pooled_window_s([short, long_]) == 500.0
    assert ps.pooled_fraction_above([short, long_], 5.0) == pytest.approx(0.9, abs=1e-15)
    median = ps.pooled_percentile([short, long_], 0.5)
    assert median.lower_deg <= 10.0 <= median.upper_deg and median.lower_deg > 5.5
    assert median.estimate_deg == pytest.approx(10.0, rel=0.13)
    p05 = ps.pooled_percentile([short, long_], 0.05)  # 5 % of 500 s = 25 s, inside the short run's 50 s at 1°
    assert p05.lower_deg <= 1.0 <= p05.upper_deg and p05.upper_deg < 1.2


@pytest.mark.parametrize("seed", range(6))
def test_bracket_holds_the_exact_percentile_of_the_concatenated_traces(seed):
    """Runs of different lengths, errors spread over decades with ties and values on bin edges: for every p the
    bracket from the summed histograms holds numpy's percentile of all samples put together, and is no wider
    than the bins of the samples ranked two below and one above p·n."""
    rng = random.Random(seed)
    traces = []
    for _ in range(rng.randint(2, 7)):
        n = rng.randint(1, 400)
        scale = 10 ** rng.uniform(-3.5, 1.5)
        t = [min(180.0, scale * rng.lognormvariate(0.0, 1.0)) for _ in range(n)]
        t += [rng.choice(ps.EDGES_DEG)] * rng.randint(0, 20) + [t[0]] * rng.randint(0, 30)
        traces.append(t)
    runs = [run(t) for t in traces]
    everything = [v for t in traces for v in t]
    ranked, n = sorted(everything), len(everything)
    for p in [0.0, 0.001, 0.01, 0.05, 0.25, 0.5, 0.75, 0.9, 0.95, 0.99, 0.999, 1.0] + [rng.random() for _ in range(40)]:
        q = ps.pooled_percentile(runs, p)
        exact = exact_percentile(everything, p)
        assert q.lower_deg <= exact <= q.upper_deg, (p, exact, q)
        assert q.lower_deg <= q.estimate_deg <= q.upper_deg
        assert q.lower_deg >= ps.bin_bounds(ps.bin_index(ranked[max(0, math.floor(p * n) - 2)]))[0], (p, q)
        assert q.upper_deg <= ps.bin_bounds(ps.bin_index(ranked[min(n - 1, math.ceil(p * n) + 1)]))[1], (p, q)


def test_bracket_holds_the_percentile_when_its_neighbours_straddle_a_bin_edge():
    """Two samples either side of an edge, p between them: the interpolated percentile is inside the upper bin
    of the pair and the time-weighted quantile in the lower one; the bracket spans both."""
    edge = ps.EDGES_DEG[60]
    values = [edge * 0.99, edge * 1.01]
    r = run(values)
    for p in (0.3, 0.5, 0.7):
        q = ps.pooled_percentile([r], p)
        assert q.lower_deg <= exact_percentile(values, p) <= q.upper_deg
        assert q.lower_deg <= edge * 0.99 and q.upper_deg >= edge * 1.01


def test_fraction_above_decides_the_pooled_p95_target():
    """Pooled p95 ≤ 15° exactly when at most 5 % of the time is above 15° (the time-weighted quantile, the
    estimate's bin; the bracket is wider by the sample-rank margin)."""
    at_limit = run([1.0] * 95 + [30.0] * 5)
    over = run([1.0] * 94 + [30.0] * 6)
    assert ps.pooled_fraction_above([at_limit], 15.0) == 0.05
    assert ps.pooled_percentile([at_limit], 0.95).estimate_deg < 15.0
    assert ps.pooled_fraction_above([over], 15.0) == 0.06
    assert ps.pooled_percentile([over], 0.95).estimate_deg > 15.0


def test_per_run_share_and_wilson_bound():
    """k = n: the Wilson lower bound is n / (n + z²); 0 of n gives 0; no runs give NaN."""
    share = ps.per_run_share([True] * 100)
    assert (share.successes, share.n, share.fraction) == (100, 100, 1.0)
    assert share.lower95 == pytest.approx(100 / (100 + 1.96 ** 2), rel=1e-12)
    assert ps.per_run_share([False] * 10).lower95 == pytest.approx(0.0, abs=1e-15)
    assert 0.75 < ps.per_run_share([True] * 84 + [False] * 16).lower95 < 0.84
    assert math.isnan(ps.per_run_share([]).lower95)


def test_columns_round_trip_and_skip_runs_without_data():
    a, b = [0.2, 3.0, 40.0], [0.02] * 7
    fa, fb = (ps.pooling_fields(v, W, ps.POINTING_THRESHOLDS_DEG) for v in (a, b))
    names = ps.column_names("pointing_error_deg", ps.POINTING_THRESHOLDS_DEG)
    assert len(names) == 2 + 6 + 127 and "pointing_error_deg.time_above_s.15" in names
    columns = {n: [] for n in names}
    for f in (fa, None, fb):
        dense = ps.dense_histogram(f["histogram_s"]) if f else None
        for n in names:
            field = n.split(".", 2)[1]
            if f is None:
                columns[n].append(float("nan"))
            elif field == "histogram_s":
                columns[n].append(dense[int(n.rsplit(".", 1)[1])])
            elif field == "time_above_s":
                columns[n].append(f["time_above_s"][n.split(".", 2)[2]])
            else:
                columns[n].append(f[field])
    runs = ps.runs_from_columns(columns, "pointing_error_deg", ps.POINTING_THRESHOLDS_DEG)
    assert runs == [ps.run_times(fa), ps.run_times(fb)]
    del columns["pointing_error_deg.histogram_s.7"]
    with pytest.raises(KeyError, match="histogram_s.7"):
        ps.runs_from_columns(columns, "pointing_error_deg", ps.POINTING_THRESHOLDS_DEG)


def test_errors_are_clear():
    r = run([1.0, 2.0])
    with pytest.raises(KeyError, match="no time_above_s at 7 deg"):
        ps.pooled_fraction_above([r], 7.0)
    with pytest.raises(ValueError, match="fraction 0…1"):
        ps.pooled_percentile([r], 95)
    with pytest.raises(ValueError, match="no runs"):
        ps.pooled_percentile([], 0.5)
    with pytest.raises(ValueError, match="cover no time"):
        ps.pooled_percentile([run([])], 0.5)
    with pytest.raises(ValueError, match="sample_interval_s must be positive"):
        ps.pooling_fields([1.0], 0.0, ())
    with pytest.raises(ValueError, match="outside 0"):
        ps.dense_histogram({"first_bin": 126, "time_s": [1.0, 1.0]})
    assert math.isnan(ps.pooled_fraction_above([run([])], 1.0))


def test_summary_statistics_are_unchanged_and_gain_the_pooling_fields():
    """error_statistics keeps median/p95/max/samples as before and adds the fields over the same kept samples."""
    values = [100.0] * 10 + [float(v) for v in range(1, 91)]
    plain = error_statistics(values)
    full = error_statistics(values, sample_interval_s=W, thresholds_deg=(15.0,))
    assert {k: full[k] for k in plain} == plain
    assert full["window_s"] == 90 * W and full["time_above_s"] == {"15": 75 * W}  # 16 … 90, not the dropped 100s
    assert sum(ps.dense_histogram(full["histogram_s"])) == full["window_s"]
