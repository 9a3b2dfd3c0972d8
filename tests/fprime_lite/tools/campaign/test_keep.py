"""keep: {best/worst: N, by: METRIC}: which run folders stay, as runs arrive, on Dask workers and on resume."""

from __future__ import annotations

import math

import pytest

from fprime_lite.tools.campaign import CampaignError, load_campaign
from fprime_lite.tools.campaign.keep import KeepPolicy, kept_ids

PROBE = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"


def _row(run_id, value, point=0, seed_index=0, status="ok"):
    return {"run_id": run_id, "point": point, "seed_index": seed_index, "status": status,
            "metrics": {"m": value}}


def test_ranking_is_by_metric_with_nulls_last_and_ties_by_point():
    """CAMP-100: best 2 (min) are the two smallest; max reverses; a null ranks after every number
    (first of the worst); ties go to the lower point; failed runs are ranked only through failed: true."""
    rows = [_row("a", 3.0, 0), _row("b", 1.0, 1), _row("c", None, 2), _row("d", 1.0, 3),
            _row("e", 0.5, 4, status="failed"), _row("f", math.nan, 5)]
    assert kept_ids(rows, KeepPolicy("ranked", best=2, by="m")) == {"b", "d"}
    assert kept_ids(rows, KeepPolicy("ranked", best=1, by="m", order="max")) == {"a"}
    assert kept_ids(rows, KeepPolicy("ranked", worst=2, by="m")) == {"c", "f"}
    assert kept_ids(rows, KeepPolicy("ranked", best=1, worst=1, by="m", failed=True)) == {"b", "f", "e"}
    assert kept_ids(rows[::-1], KeepPolicy("ranked", best=3, by="m")) == {"b", "d", "a"}  # arrival order is irrelevant


def test_bad_keep_is_refused_at_its_lines(write_campaign):
    """CAMP-101: an unknown keep field, a metric not in 'metrics', a zero count and a bad order are
    reported at their own file:line; a ranking without best/worst and a bad string are refused too."""
    path = write_campaign(f"""\
        campaign: k
        run: {{kind: "{PROBE}"}}
        metrics: [value]
        keep:
          best: 0
          by: valeu
          order: smallest
          top: 3
        """)
    with pytest.raises(CampaignError) as info:
        load_campaign(path)
    text = "\n".join(info.value.problems)
    assert f"{path}:5: 'keep: best' is how many runs to keep, a whole number >= 1, got 0" in text
    assert f"{path}:6: 'keep: by' 'valeu' is not in 'metrics' — did you mean 'value'?" in text
    assert f"{path}:7: 'keep: order' is min" in text
    assert f"{path}:8: unknown key 'top' in 'keep'" in text
    assert len(info.value.problems) == 4
    for keep, message in (("{by: value}", "needs 'best: N', 'worst: N', 'every: N' or 'failed: true'"),
                          ("best", "is one of none, failed, all")):
        bad = write_campaign(f'campaign: k\nrun: {{kind: "{PROBE}"}}\nmetrics: [value]\nkeep: {keep}\n', "b.yaml")
        with pytest.raises(CampaignError, match=message):
            load_campaign(bad)


CAMPAIGN = f"""\
campaign: keep_best
run: {{kind: "{PROBE}"}}
dispersions:
  x: {{dist: uniform, low: 0, high: 100}}
seeds: SEEDS
metrics: [value]
keep: {{best: 3, worst: 1, by: value, order: min}}
"""


def test_best_runs_keep_their_folders_on_two_workers_and_after_resume(write_campaign, tmp_path):
    """CAMP-102: on a LocalCluster of 2 (workers write the folders) exactly the 3 best and the worst
    run keep DIR/runs/RUN_ID; after raising seeds and --resume the set is the best of all rows
    (the earlier best displaced ones deleted) and a stray folder left by a kill is removed."""
    pd = pytest.importorskip("pandas")
    pytest.importorskip("distributed")
    from fprime_lite.tools.campaign import run_campaign

    def expected(df):
        order = df.sort_values(["value", "point", "seed_index"])
        return set(order["run_id"][:3]) | {order["run_id"].iloc[-1]}

    path = write_campaign(CAMPAIGN.replace("SEEDS", "6"))
    out = tmp_path / "out"
    df = run_campaign(path, workers=2, out=out, plots=False, summary=False)
    assert len(df) == 6 and set(df["status"]) == {"ok"} and df["worker"].nunique() == 2
    folders = {p.name for p in (out / "runs").iterdir()}
    assert folders == expected(df)
    assert all((out / "runs" / r / "out.txt").read_text().startswith("x=") for r in folders)
    (out / "runs" / "0123456789abcdef").mkdir()  # a run that finished without its row reaching the journal
    path.write_text(CAMPAIGN.replace("SEEDS", "14"))
    df2 = run_campaign(path, workers=2, out=out, resume=True, plots=False, summary=False)
    assert len(df2) == 14
    pd.testing.assert_frame_equal(df2[df2["seed_index"] < 6].drop(columns=["wall_s", "cpu_s", "worker"]),
                                  df.drop(columns=["wall_s", "cpu_s", "worker"]))
    assert {p.name for p in (out / "runs").iterdir()} == expected(df2)
    assert expected(df2) != expected(df)  # the new draws displaced some of the first best


def test_the_pruner_keeps_the_same_set_as_a_full_ranking_whatever_the_order(tmp_path):
    """CAMP-103: fed 300 random rows one by one (ties, nulls, failures, a failed run retried ok), the
    pruner's kept set equals kept_ids of all rows so far after every row, and only kept folders remain."""
    import random

    from fprime_lite.tools.campaign.keep import ArtifactPruner

    rnd = random.Random(4)
    policy = KeepPolicy("ranked", best=4, worst=3, by="m", order="max", failed=True)
    pruner = ArtifactPruner(tmp_path, policy)
    pruner.start([])
    rows: dict[str, dict] = {}
    for i in range(300):
        retry = i % 50 == 49 and any(r["status"] == "failed" for r in rows.values())
        run_id = next(k for k, r in rows.items() if r["status"] == "failed") if retry else f"r{i:03d}"
        value = rnd.choice([None, float(rnd.randint(0, 20))])
        row = _row(run_id, value, point=rnd.randint(0, 5), seed_index=i,
                   status="ok" if retry or rnd.random() > 0.1 else "failed")
        (tmp_path / run_id).mkdir(exist_ok=True)
        rows[run_id] = row
        pruner.update(row)
        assert pruner.kept == kept_ids(rows.values(), policy)
    assert {p.name for p in tmp_path.iterdir()} == kept_ids(rows.values(), policy)
