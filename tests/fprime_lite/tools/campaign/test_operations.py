"""Running campaigns (issue 31): a plain script, an empty scheduler, first-run wall time, a ready
Client, TLS, several runs per task, the journal's fsync and the heartbeat."""

from __future__ import annotations

import contextlib
import json
import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from fprime_lite.tools.campaign import CampaignError, run_campaign
from tests.fprime_lite.tools.campaign.conftest import BIN, REPO, _free_port, _stop

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

PROBE = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"
SRC = str(pathlib.Path(__import__("fprime_lite").__file__).resolve().parents[1])  # the code under test
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [SRC, str(REPO), os.environ.get("PYTHONPATH")])))


def _probe_campaign(write_campaign, mode="ok", seeds=2, name="c.yaml", extra=""):
    return write_campaign(f"""\
        campaign: probe_{mode}
        run: {{kind: "{PROBE}", mode: {mode}}}
        grid:
          x: [1.0, 2.0]
        seeds: {seeds}
        metrics: [value]
        {extra}
        """, name)


def test_the_python_api_works_from_a_plain_script(write_campaign, tmp_path):
    """CAMP-122: the documented Python example, as a plain script with no `if __name__ == "__main__":`
    guard, runs its campaign (before: 'Nanny failed to start' — spawned workers re-ran the script)."""
    path = _probe_campaign(write_campaign)
    script = tmp_path / "plain.py"
    script.write_text(textwrap.dedent(f"""\
        from fprime_lite.tools.campaign import run_campaign
        df = run_campaign({str(path)!r}, workers=1, out={str(tmp_path / 'o')!r}, plots=False, summary=False)
        print("rows", len(df), sorted(set(df.status)))
        """))
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, env=ENV,
                       timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    assert "rows 4 ['ok']" in r.stdout


@pytest.fixture
def lone_scheduler(tmp_path):
    """A `dask scheduler` with no worker."""
    port = _free_port()
    log = open(tmp_path / "sched.log", "w")
    proc = subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                             "--dashboard-address", "127.0.0.1:0"], stdout=log, stderr=subprocess.STDOUT,
                            start_new_session=True, cwd=tmp_path)
    try:
        from distributed import Client

        deadline = time.monotonic() + 90
        while time.monotonic() < deadline:
            try:
                Client(f"tcp://127.0.0.1:{port}", timeout=5).close()
                break
            except OSError:
                time.sleep(0.5)
        yield f"tcp://127.0.0.1:{port}"
    finally:
        _stop([proc])
        log.close()


def test_a_scheduler_without_workers_is_reported_not_waited_on_forever(lone_scheduler, write_campaign, tmp_path,
                                                                       capsys):
    """CAMP-123: a scheduler with no worker: the campaign says it is waiting, then stops with a message
    naming the scheduler and how to join workers (before: a silent hang)."""
    from fprime_lite.tools.cli import main

    path = _probe_campaign(write_campaign)
    t0 = time.monotonic()
    assert main(["campaign", str(path), "--scheduler", lone_scheduler, "--out", str(tmp_path / "o"),
                 "--wait-for-workers", "3", "--no-plots"]) == 2
    assert time.monotonic() - t0 < 60
    err = capsys.readouterr().err
    assert f"the scheduler {lone_scheduler} has no workers; waiting up to 3 s" in err
    assert f"--scheduler {lone_scheduler} has no workers after 3 s — join some with 'dask worker" in err
    manifest = json.loads((tmp_path / "o" / "manifest.json").read_text())
    # an error is a failure, with its message; "interrupted" is for SIGINT/SIGTERM only (before: interrupted)
    assert (manifest["status"], manifest["history"][-1]["status"]) == ("failed", "failed")
    assert "interrupted" not in manifest
    assert f"--scheduler {lone_scheduler} has no workers after 3 s" in manifest["error"]
    assert manifest["history"][-1]["error"] == manifest["error"]


@pytest.mark.parametrize("raised, status, recorded", [
    (RuntimeError("the cluster fell over"), "failed", {"error": "RuntimeError: the cluster fell over"}),
    (KeyboardInterrupt(), "interrupted", {"interrupted": {"signal": "SIGINT", "done": 0, "planned": 4}}),
])
def test_a_session_ended_by_an_error_is_failed_and_only_ctrl_c_is_interrupted(write_campaign, tmp_path, monkeypatch,
                                                                               raised, status, recorded):
    """CAMP-123: the cluster raising while the session runs leaves the manifest "failed" with the error's message
    (before: "interrupted", the default of any session that did not complete); a Ctrl-C that reaches the campaign
    as KeyboardInterrupt (run_campaign without interruptible=True) is still "interrupted", by SIGINT."""
    from fprime_lite.tools.campaign import cluster

    @contextlib.contextmanager
    def broken_cluster(*args, **kwargs):
        raise raised
        yield  # pragma: no cover - a generator for contextmanager

    monkeypatch.setattr(cluster, "dask_client", broken_cluster)
    with pytest.raises(type(raised)):
        run_campaign(_probe_campaign(write_campaign), workers=1, out=tmp_path / "o", plots=False, summary=False)
    manifest = json.loads((tmp_path / "o" / "manifest.json").read_text())
    assert manifest["status"] == manifest["history"][-1]["status"] == status
    assert {k: manifest.get(k) for k in recorded} == recorded
    assert not ({"error", "interrupted"} - set(recorded)) & set(manifest)  # the other one is absent


def test_a_workers_first_run_does_not_pay_for_its_imports(write_campaign, tmp_path):
    """CAMP-124: a kind whose build imports a module that takes 1.5 s: the workers build one run before the
    campaign's clock starts, so no run reports the import in its wall_s (before: the first run on each
    worker did) — with and without timeout_s (a run process warms itself the same way)."""
    for extra, out in (("", "o"), ("timeout_s: 60", "t")):
        path = _probe_campaign(write_campaign, mode="slow_import", name=f"{out}.yaml", extra=extra)
        df = run_campaign(path, workers=2, out=tmp_path / out, plots=False, summary=False)
        assert set(df["status"]) == {"ok"}
        assert df["wall_s"].max() < 1.0, df[["worker", "wall_s"]]


def test_a_ready_client_is_used_and_left_open(write_campaign, tmp_path):
    """CAMP-125: run_campaign(..., client=c) submits to that Client (dask-jobqueue, Kubernetes, Coiled…),
    records it as the cluster and leaves it open; giving workers= as well is refused."""
    from distributed import Client, LocalCluster

    path = _probe_campaign(write_campaign)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        df = run_campaign(path, client=client, out=tmp_path / "o", plots=False, summary=False)
        assert len(df) == 4 and set(df["status"]) == {"ok"}
        assert client.status == "running" and client.submit(sum, [1, 2]).result() == 3
        manifest = json.loads((tmp_path / "o" / "manifest.json").read_text())
        assert manifest["cluster"]["type"] == "client" and manifest["cluster"]["workers"] == 1
        with pytest.raises(CampaignError, match="not --workers and client="):
            run_campaign(path, client=client, workers=1, out=tmp_path / "p", plots=False, summary=False)


def _tls_files(folder: pathlib.Path) -> dict:
    """A CA and a certificate it signs for 127.0.0.1 (openssl), as Dask's TLS wants them."""
    def ssl(*args):
        subprocess.run(["openssl", *args], check=True, capture_output=True, cwd=folder, timeout=60)
    ssl("req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", "ca.key", "-out", "ca.pem", "-days", "2",
        "-subj", "/CN=campaign-test-ca")
    ssl("req", "-newkey", "rsa:2048", "-nodes", "-keyout", "node.key", "-out", "node.csr", "-subj", "/CN=127.0.0.1")
    (folder / "ext.cnf").write_text("subjectAltName=IP:127.0.0.1\n")
    ssl("x509", "-req", "-in", "node.csr", "-CA", "ca.pem", "-CAkey", "ca.key", "-CAcreateserial", "-out",
        "node.pem", "-days", "2", "-extfile", "ext.cnf")
    return {"ca": folder / "ca.pem", "cert": folder / "node.pem", "key": folder / "node.key"}


@pytest.mark.skipif(not any((pathlib.Path(p) / "openssl").exists() for p in os.environ.get("PATH", "").split(":")),
                    reason="openssl makes the test certificates")
def test_a_tls_scheduler_with_security_files(write_campaign, tmp_path):
    """CAMP-126: a `dask scheduler` and worker that require TLS: `--scheduler tls://…` with --tls-ca-file,
    --tls-cert and --tls-key runs the campaign; the same through a --dask-config file; without them the
    message says what to give; the config file does not change the process's Dask config."""
    from fprime_lite.tools.cli import main

    tls = _tls_files(tmp_path)
    port = _free_port()
    address = f"tls://127.0.0.1:{port}"
    flags = ["--tls-ca-file", str(tls["ca"]), "--tls-cert", str(tls["cert"]), "--tls-key", str(tls["key"])]
    log = open(tmp_path / "dask.log", "w")
    common = dict(stdout=log, stderr=subprocess.STDOUT, start_new_session=True, cwd=tmp_path, env=ENV)
    procs = [subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--protocol", "tls", "--dashboard-address", "127.0.0.1:0", *flags], **common)]
    try:
        procs.append(subprocess.Popen([str(BIN / "dask"), "worker", address, "--nthreads", "1", "--host", "127.0.0.1",
                                       "--no-dashboard", *flags], **common))
        path = _probe_campaign(write_campaign)
        assert main(["campaign", str(path), "--scheduler", address, *flags, "--out", str(tmp_path / "o"),
                     "--no-plots", "--wait-for-workers", "120"]) == 0
        assert len(pd.read_parquet(tmp_path / "o" / "results.parquet")) == 4
        config = tmp_path / "dask.yaml"
        config.write_text(json.dumps({"distributed": {"comm": {"require-encryption": True, "tls": {
            "ca-file": str(tls["ca"]), "client": {"cert": str(tls["cert"]), "key": str(tls["key"])}}}}}))
        assert main(["campaign", str(path), "--scheduler", address, "--dask-config", str(config), "--out",
                     str(tmp_path / "c"), "--no-plots"]) == 0
        import dask.config

        assert not dask.config.get("distributed.comm.require-encryption")  # the file's settings stayed local
    finally:
        _stop(procs)
        log.close()


def test_short_runs_travel_several_per_task():
    """CAMP-127: once runs are known to take 1 ms, a task carries many of them (TARGET_TASK_S of work), but
    never more than leaves every worker a share; before the first result, one run per task."""
    from fprime_lite.tools.campaign.engine import TARGET_TASK_S, _Submitter

    class FakeClient:
        def nthreads(self):
            return {"a": 1, "b": 1}

    s = _Submitter(FakeClient(), None, [{"run_id": str(i)} for i in range(10_000)])
    s.window()
    assert s.batch_size() == 1
    s.observe([{"wall_s": 0.001}] * 10)
    assert s.batch_size() == int(TARGET_TASK_S / s.mean_wall) and 490 < s.batch_size() <= 500
    s.queue = s.queue.__class__(list(s.queue)[:40])
    assert s.batch_size() == 10  # 40 left, 2 threads: a quarter each
    s.observe([{"wall_s": 5.0}] * 10)
    assert s.batch_size() == 1


def _row(i: int) -> dict:
    return {"run_id": f"r{i:04d}", "point": i, "seed_index": 0, "seed": 1, "status": "ok", "values": {"x": float(i)},
            "metrics": {"m": 2.0 * i}}


def test_rows_are_written_in_batches_as_parts_never_rewritten(tmp_path):
    """CAMP-128: 250 rows in quick succession with batches of 100 make two parts (not 250 writes, and
    no rewrite of what is written: the first part's bytes never change); close writes the rest, compacts
    the parts into one, and writes results.parquet with all 250 rows."""
    from fprime_lite.tools.campaign.results import ResultStore, read_results

    store = ResultStore(tmp_path, ["x"], ["m"], flush_s=3600, batch_rows=100)
    parts = tmp_path / "results.parts"
    first = None
    for i in range(250):
        store.add(_row(i))
        names = sorted(p.name for p in parts.iterdir()) if parts.is_dir() else []
        assert len(names) == (i + 1) // 100
        if names:
            first = first or (parts / names[0]).read_bytes()
            assert (parts / names[0]).read_bytes() == first
    assert len(read_results(tmp_path)) == 200  # a reader meanwhile: every flushed row
    df = store.close()
    assert len(list(parts.iterdir())) == 1 and len(df) == 250 and list(df["m"]) == [2.0 * i for i in range(250)]
    assert read_results(tmp_path).equals(df)


def test_a_lone_row_is_flushed_without_waiting_for_another(tmp_path):
    """CAMP-128: a row that no other row follows (a long run next) is in a part within flush_s."""
    from fprime_lite.tools.campaign.results import ResultStore, read_results

    store = ResultStore(tmp_path, ["x"], ["m"], flush_s=0.2)
    store.add(_row(1))
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and not list(tmp_path.glob("results.parts/part-*.parquet")):
        time.sleep(0.05)
    assert list(read_results(tmp_path)["run_id"]) == ["r0001"]
    store.close()


def test_a_heartbeat_line_comes_when_no_run_finishes(capsys):
    """CAMP-129: without a terminal, a line every log_every_s says the campaign is alive — how many runs
    are in flight and how long since the last result — even when no run has finished."""
    from fprime_lite.tools.campaign.report import progress_bar

    with progress_bar(5, 0, False, log_every_s=0.2, running=lambda: 2) as update:
        time.sleep(0.7)
        update({"status": "ok"})
    err = capsys.readouterr().err
    assert "campaign: 0/5 done, 0 failed, 2 running, 0 runs/h, last result" in err
    assert err.count("campaign: ") >= 2


def test_a_campaign_killed_while_waiting_leaves_no_worker_behind(write_campaign, tmp_path):
    """CAMP-130: SIGTERM to `fprime-lite campaign` during its runs ends it and its embedded cluster's
    worker processes (subprocesses now, not multiprocessing children)."""
    path = _probe_campaign(write_campaign, mode="slow_import", seeds=40)
    proc = subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.cli", "campaign", str(path), "--workers", "1",
                             "--out", str(tmp_path / "o"), "--no-plots"], env=ENV, cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and not (tmp_path / "o" / "results.parts").exists():
            time.sleep(0.2)
        children = subprocess.run(["pgrep", "-g", str(proc.pid)], capture_output=True, text=True).stdout.split()
        assert len(children) >= 2  # the campaign and its worker's processes
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=60)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            left = subprocess.run(["pgrep", "-g", str(proc.pid)], capture_output=True, text=True).stdout.split()
            if not left:
                break
            time.sleep(0.5)
        assert left == []
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
