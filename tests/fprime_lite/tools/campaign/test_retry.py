"""--retry-failed: failed and timed-out rows run again on resume, replacing their rows, seeds unchanged."""

from __future__ import annotations

import json

import pytest

from fprime_lite.tools.campaign.results import ResultStore
from fprime_lite.tools.cli import main

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

PROBE = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"


def test_retry_failed_reruns_only_failed_rows_with_their_seeds(write_campaign, tmp_path, capsys):
    """CAMP-092: a failed and a timed-out run stay so on a plain --resume; with
    --retry-failed they run again with the same run ids and seeds, their rows replaced (one row per
    run), while the ok rows are not run again (their wall times unchanged)."""
    from fprime_lite.tools.campaign import read_results

    path = write_campaign(f"""\
        campaign: retry
        run: {{kind: "{PROBE}", mode: fail_if_marker}}
        grid:
          x: [1.0, 2.0]
        seeds: 2
        metrics: [value]
        """)
    out = tmp_path / "out"
    assert main(["campaign", str(path), "--workers", "1", "--out", str(out), "--no-plots"]) == 0
    first = read_results(out)
    assert set(first["status"]) == {"ok"}
    store = ResultStore(out, ["x"], ["value"])
    rows = store.rows
    failed = [rows[0], rows[3]]
    for r, status in zip(failed, ("failed", "timeout"), strict=True):  # as a crashed / overlong run would be
        r.update(status=status, error="RuntimeError: boom", metrics={"value": None})
        store.add(r)  # recorded again: the last record of a run id counts
    store.close()
    (path.parent / "marker").write_text("")
    assert main(["campaign", str(path), "--workers", "1", "--out", str(out), "--resume", "--no-plots"]) == 1
    assert sorted(read_results(out)["status"]) == ["failed", "ok", "ok", "timeout"]  # plain resume: nothing to run
    assert main(["campaign", str(path), "--out", str(out), "--workers", "1", "--retry-failed", "--no-plots"]) == 1
    still = read_results(out)
    assert (still["status"] == "failed").sum() == 2 and "the marker file is there" in still["error"].dropna().iloc[0]
    (path.parent / "marker").unlink()
    assert main(["campaign", str(path), "--out", str(out), "--workers", "1", "--retry-failed", "--no-plots"]) == 0
    capsys.readouterr()
    final = read_results(out)
    assert len(final) == 4 and set(final["status"]) == {"ok"} and final["run_id"].is_unique
    keep = ["run_id", "point", "seed_index", "seed", "status", "x", "value"]
    pd.testing.assert_frame_equal(final[keep], first[keep])
    retried = {r["run_id"] for r in failed}
    untouched = final[~final["run_id"].isin(retried)]
    assert list(untouched["wall_s"]) == list(first[~first["run_id"].isin(retried)]["wall_s"])
    assert json.loads((out / "manifest.json").read_text())["retried"] == 2
