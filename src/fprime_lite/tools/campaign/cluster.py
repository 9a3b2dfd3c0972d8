"""The Dask client a campaign submits to: an embedded cluster, an existing one, or a ready ``Client``.

The same engine code serves all three; only the :class:`distributed.Client` differs.

- Embedded (default): a scheduler in this process on 127.0.0.1 and ``workers`` worker processes
  (default: one per core), each with one thread — the simulator is pure Python, so threads would
  only share the GIL. The workers are started as plain subprocesses (``python -m dask spec``), not
  with ``multiprocessing``: a spawned child re-runs the calling script, so a script calling
  ``run_campaign`` without an ``if __name__ == "__main__":`` guard would start clusters from its
  workers; a subprocess runs only Dask. They get this process's ``sys.path`` (``PYTHONPATH``), so
  a run kind importable here is importable there.
- External: ``Client("tcp://HOST:PORT")`` (or ``tls://``, with ``security``: a
  :class:`distributed.Security`, or the ``distributed.comm.tls`` settings of a Dask config file)
  to a scheduler started with ``dask scheduler`` / ``dask worker``, dask-jobqueue, Kubernetes…
  A scheduler without workers is waited for ``wait_for_workers_s``, saying so, then refused.
- A ready ``Client`` (``run_campaign(..., client=c)``): used as it is, and left open.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import os
import sys

from fprime_lite.tools.campaign.errors import CampaignError

__all__ = ["dask_client", "security_from", "worker_info"]

GUARD = "fprime_lite.tools.campaign.orphan_guard"
#: Seconds an embedded cluster's workers get to start (interpreter start and imports, on a loaded machine).
LOCAL_START_TIMEOUT_S = 180.0


def security_from(tls_ca_file=None, tls_cert=None, tls_key=None, dask_config=None):
    """A :class:`distributed.Security` from TLS files and/or a Dask config file (YAML with
    ``distributed: comm: tls: …``); None when neither is given."""
    if not any((tls_ca_file, tls_cert, tls_key, dask_config)):
        return None
    import dask.config
    from distributed import Security

    loaded: dict = {}
    if dask_config is not None:
        import yaml

        try:
            with open(dask_config, encoding="utf-8") as fh:
                loaded = yaml.safe_load(fh) or {}
        except (OSError, yaml.YAMLError) as exc:
            raise CampaignError([f"--dask-config {dask_config}: cannot be read ({exc})"]) from None
        if not isinstance(loaded, dict):
            raise CampaignError([f"--dask-config {dask_config}: a Dask config file is a YAML mapping"])
    files = {"tls_ca_file": tls_ca_file, "tls_client_cert": tls_cert, "tls_client_key": tls_key}
    for flag, path in zip(("--tls-ca-file", "--tls-cert", "--tls-key"), files.values(), strict=True):
        if path is not None and not os.path.isfile(path):
            raise CampaignError([f"{flag} {path}: no such file"])
    given = {k: v for k, v in files.items() if v is not None}
    if given and len(given) != 3:
        raise CampaignError(["TLS needs all three of --tls-ca-file, --tls-cert and --tls-key"])
    # the file's settings are read into this Security object only: the process's Dask config (and so
    # the embedded clusters of later campaigns in this process) is left as it was
    def dotted(tree: dict, prefix: str = "") -> dict:
        flat: dict = {}
        for k, v in tree.items():
            flat.update(dotted(v, f"{prefix}{k}.") if isinstance(v, dict) else {f"{prefix}{k}": v})
        return flat
    with dask.config.set(dotted(loaded)):
        return Security(require_encryption=True, **given) if given else Security()


def worker_info() -> dict:
    """Where a worker runs: host, CPU and package versions (for the manifest)."""
    from fprime_lite.tools.campaign.manifest import machine, package_versions

    return {**machine(), "versions": package_versions()}


def _subprocess_worker_class():
    from distributed.deploy.subprocess import SubprocessWorker

    class _Worker(SubprocessWorker):
        """A worker (a Nanny and its process) started as ``python -m dask spec`` with our sys.path."""

        async def _start(self) -> None:
            opts = dict(self.worker_kwargs, name=self.name)
            cmd = [sys.executable, "-m", "dask", "spec", self.scheduler, "--spec",
                   json.dumps({"cls": self.worker_class, "opts": opts})]
            env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p),
                       DASK_LOGGING__DISTRIBUTED="error")
            self.process = await asyncio.create_subprocess_exec(*cmd, env=env, stdin=asyncio.subprocess.DEVNULL)

    return _Worker


def _wait_for_workers(client, n: int, timeout_s: float, where: str) -> None:
    try:
        client.wait_for_workers(n, timeout=timeout_s)
    except (TimeoutError, asyncio.TimeoutError, OSError) as exc:
        raise CampaignError([f"{where}: {exc}"]) from None


@contextlib.contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None, connect_timeout_s: float = 20.0, *,
                security=None, client=None, wait_for_workers_s: float = 60.0):
    """Yield ``(client, info)``; ``info`` describes the cluster for the manifest."""
    from distributed import Client, Scheduler, SpecCluster

    logging.getLogger("distributed").setLevel(logging.ERROR)  # its INFO chatter would bury the progress bar
    if client is not None:
        n = len(client.scheduler_info().get("workers", {}))
        if n == 0:
            print(f"campaign: the given client's scheduler has no workers yet; waiting up to "
                  f"{wait_for_workers_s:g} s", file=sys.stderr, flush=True)
            _wait_for_workers(client, 1, wait_for_workers_s, "the given client's scheduler has no workers")
        yield client, {"type": "client", "scheduler": client.scheduler.address,
                       "workers": len(client.scheduler_info().get("workers", {}))}
        return
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=connect_timeout_s, security=security)
        except (OSError, TimeoutError) as exc:
            raise CampaignError([f"--scheduler {scheduler}: cannot reach the scheduler ({exc}) — start one with "
                                 f"'dask scheduler' and join workers with 'dask worker {scheduler} --nthreads 1'"
                                 + ("; a tls:// scheduler needs --tls-ca-file/--tls-cert/--tls-key or a "
                                    "--dask-config with distributed.comm.tls" if scheduler.startswith("tls")
                                    and security is None else "")]) from None
        try:
            n = len(client.scheduler_info().get("workers", {}))
            if n == 0:
                print(f"campaign: the scheduler {scheduler} has no workers; waiting up to {wait_for_workers_s:g} s "
                      f"for one (join with 'dask worker {scheduler} --nthreads 1')", file=sys.stderr, flush=True)
                _wait_for_workers(client, 1, wait_for_workers_s,
                                  f"--scheduler {scheduler} has no workers after {wait_for_workers_s:g} s — join "
                                  f"some with 'dask worker {scheduler} --nthreads 1' (or dask-jobqueue), or wait "
                                  f"longer with --wait-for-workers SECONDS")
                n = len(client.scheduler_info().get("workers", {}))
            yield client, {"type": "external", "scheduler": scheduler, "workers": n}
        finally:
            client.close()
        return
    n = workers or os.cpu_count() or 1
    worker_spec = {"cls": _subprocess_worker_class(),
                   "options": {"worker_class": "distributed.Nanny",
                               "worker_kwargs": {"host": "127.0.0.1", "nthreads": 1, "dashboard": False,
                                                 "silence_logs": logging.ERROR,
                                                 # a killed campaign takes its worker processes with it
                                                 "preload": [GUARD], "preload_nanny": [GUARD]}}}
    cluster = SpecCluster(
        scheduler={"cls": Scheduler, "options": {"host": "127.0.0.1", "dashboard_address": "127.0.0.1:0"}},
        workers={f"local-{i}": worker_spec for i in range(n)}, worker=worker_spec,
        silence_logs=logging.ERROR, name="campaign")
    try:
        client = Client(cluster)
        try:
            _wait_for_workers(client, n, LOCAL_START_TIMEOUT_S,
                              f"the embedded cluster's {n} worker process(es) did not start within "
                              f"{LOCAL_START_TIMEOUT_S:g} s (is 'python -m dask spec' runnable here?)")
            yield client, {"type": "local", "scheduler": cluster.scheduler_address, "workers": n,
                           "threads_per_worker": 1}
        finally:
            client.close()
    finally:
        cluster.close()
