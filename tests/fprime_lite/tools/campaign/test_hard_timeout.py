"""Hard timeouts: a run that never polls its deadline is killed, recorded as timeout, and the campaign goes on."""

from __future__ import annotations

import json
import math
import os
import time

import pytest

from tests.fprime_lite.tools.campaign.conftest import TINY_PLANT, comparable

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

PROBE = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"


def _gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


def test_a_busy_loop_that_never_polls_is_killed_and_the_next_run_flies(write_campaign, tmp_path):
    """CAMP-090: with timeout_s 2 a run stuck in a loop that never checks its deadline is recorded
    'timeout' (killed after timeout_s + the 2 s grace, its process gone), and the next run on the
    same single worker is ok in a fresh run process; a run whose process exits is 'failed' with its
    exit status."""
    from fprime_lite.tools.campaign import run_campaign
    from fprime_lite.tools.campaign.isolation import grace_s

    path = write_campaign(f"""\
        campaign: stuck
        run: {{kind: "{PROBE}"}}
        grid:
          mode: [stuck, exit, ok]
        metrics: [value]
        timeout_s: 2
        """)
    t0 = time.perf_counter()
    df = run_campaign(path, workers=1, out=tmp_path / "o", plots=False, summary=False)
    assert time.perf_counter() - t0 < 120  # not left to loop for ever (generous for a loaded machine)
    stuck, died, ok = df.to_dict("records")
    assert stuck["status"] == "timeout" and "killed after" in stuck["error"]
    assert "never checked its deadline" in stuck["error"]
    assert stuck["wall_s"] >= 2 + grace_s(2) and math.isnan(stuck["value"])
    assert json.loads(stuck["notes"]) == {"*": "killed at its hard timeout"}
    assert json.loads(stuck["requested"]) == {"mode": "stuck"}
    (pid_file,) = tmp_path.glob("stuck-*.pid")
    assert _gone(int(pid_file.read_text()))
    assert died["status"] == "failed" and "ended (exit status 3) without a result" in died["error"]
    assert ok["status"] == "ok" and ok["value"] == 2.0 and ok["cpu_s"] >= 0


def test_isolated_runs_give_the_same_table_as_runs_in_the_worker(write_campaign, tmp_path):
    """CAMP-091: the same plant campaign with timeout_s (runs in the run process) and without (runs in
    the worker) gives bit-identical tables; the timeout does not change the run ids."""
    from fprime_lite.tools.campaign import run_campaign

    plain = write_campaign(TINY_PLANT)
    timed = write_campaign(TINY_PLANT + "timeout_s: 600\n", "t.yaml")
    a = run_campaign(plain, workers=1, out=tmp_path / "a", plots=False, summary=False)
    b = run_campaign(timed, workers=2, out=tmp_path / "b", plots=False, summary=False)
    assert set(b["status"]) == {"ok"}
    pd.testing.assert_frame_equal(comparable(a), comparable(b), check_exact=True)
