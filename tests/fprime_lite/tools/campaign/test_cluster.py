"""An external Dask cluster (a real ``dask scheduler`` and two ``dask worker`` processes on
127.0.0.1), and a campaign killed mid-way then resumed."""

from __future__ import annotations

import contextlib
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

import pytest

from fprime_lite.tools.campaign import read_results, run_campaign
from tests.fprime_lite.tools.campaign.conftest import BIN, TINY_PLANT, _free_port, _stop, comparable

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

START_TIMEOUT_S = 90


@pytest.fixture
def external_cluster(tmp_path):
    """A scheduler and two single-threaded workers on free loopback ports; always torn down."""
    from distributed import Client

    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "dask.log", "w")
    repo = str(pathlib.Path(__file__).resolve().parents[4])  # the probe run kind is imported from tests/
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [repo, os.environ.get("PYTHONPATH")])))
    common = dict(stdout=log, stderr=subprocess.STDOUT, start_new_session=True, cwd=tmp_path, env=env)
    procs = [subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--dashboard-address", "127.0.0.1:0"], **common)]
    try:
        for i in range(2):
            procs.append(subprocess.Popen([str(BIN / "dask"), "worker", address, "--nthreads", "1", "--nworkers", "1",
                                           "--host", "127.0.0.1", "--name", f"ext-{i}", "--no-dashboard"], **common))
        deadline = time.monotonic() + START_TIMEOUT_S
        client = None
        while time.monotonic() < deadline:
            try:
                client = client or Client(address, timeout=5)
                if len(client.scheduler_info()["workers"]) == 2:
                    break
            except OSError:
                pass
            time.sleep(0.5)
        else:
            pytest.fail(f"the external Dask cluster did not come up in {START_TIMEOUT_S} s: "
                        f"{(tmp_path / 'dask.log').read_text()[-2000:]}")
        client.close()
        yield address
    finally:
        _stop(procs)
        log.close()


def test_a_campaign_runs_on_an_external_scheduler(external_cluster, write_campaign, tmp_path):
    """CAMP-050: `fprime-lite campaign --scheduler tcp://127.0.0.1:PORT` runs every run on the two
    external workers, with a table bit-identical to an embedded LocalCluster's."""
    from fprime_lite.tools.cli import main

    path = write_campaign(TINY_PLANT)
    assert main(["campaign", str(path), "--scheduler", external_cluster, "--out", str(tmp_path / "ext"),
                 "--no-plots"]) == 0
    ext = read_results(tmp_path / "ext")
    assert set(ext["worker"]) <= {"ext-0", "ext-1"} and set(ext["status"]) == {"ok"} and len(ext) == 4
    manifest = json.loads((tmp_path / "ext" / "manifest.json").read_text())
    assert manifest["cluster"] == {"type": "external", "scheduler": external_cluster, "workers": 2}
    local = run_campaign(path, workers=2, out=tmp_path / "local", plots=False, summary=False)
    pd.testing.assert_frame_equal(comparable(ext), comparable(local), check_exact=True)


def test_hard_timeouts_and_kept_best_runs_on_external_workers(external_cluster, write_campaign, tmp_path):
    """CAMP-052: on two `dask worker` processes a run that busy-loops without polling is killed and
    recorded 'timeout', the other runs are ok, and the folders left are exactly the 2 best runs'."""
    path = write_campaign("""\
        campaign: ext_stuck
        run: {kind: "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"}
        grid:
          mode: [stuck, ok]
        dispersions:
          x: {dist: uniform, low: 0, high: 10}
        seeds: 3
        metrics: [value]
        timeout_s: 2
        keep: {best: 2, by: value}
        """)
    out = tmp_path / "ext"
    df = run_campaign(path, scheduler=external_cluster, out=out, plots=False, summary=False)
    assert list(df["status"]) == ["timeout"] * 3 + ["ok"] * 3 and set(df["worker"]) <= {"ext-0", "ext-1"}
    assert df["error"][:3].str.contains("never checked its deadline").all()
    best = set(df[df["status"] == "ok"].sort_values("value")["run_id"][:2])
    assert {p.name for p in (out / "runs").iterdir()} == best


# killable mid-way: each run ~1.3 s on a quiet machine, longer than the 0.5 s batch window of the results parts
# (at 400 s a quiet machine finished all 8 runs inside the first part, so nothing was left to kill)
RESUMABLE = TINY_PLANT.replace("duration_s: 20", "duration_s: 4000").replace("seeds: 2", "seeds: 4")


def test_a_killed_campaign_resumes_to_the_same_table(write_campaign, tmp_path):
    """CAMP-051: SIGKILL of `fprime-lite campaign` mid-way leaves a readable results file with the
    runs finished so far; `--resume` runs only the others and the final table equals an
    uninterrupted campaign's."""
    path = write_campaign(RESUMABLE)
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "fprime_lite.tools.cli", "campaign", str(path), "--workers", "1",
           "--out", str(out), "--no-plots"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and proc.poll() is None:
            if (out / "results.parts").is_dir() and len(read_results(out)) >= 2:
                break
            time.sleep(0.05)
        assert proc.poll() is None, "the campaign ended before it could be killed"
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)  # its LocalCluster worker processes too
    partial = read_results(out)  # from the parts: results.parquet is written when a session ends
    finished = len(partial)
    assert 2 <= finished < 8 and partial["run_id"].is_unique and set(partial["status"]) == {"ok"}
    df = run_campaign(path, workers=2, out=out, resume=True, plots=False, summary=False)
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["resumed_with"] == finished and manifest["status"] == "complete"
    whole = run_campaign(path, workers=2, out=tmp_path / "whole", plots=False, summary=False)
    assert len(df) == 8
    pd.testing.assert_frame_equal(comparable(df), comparable(whole), check_exact=True)
