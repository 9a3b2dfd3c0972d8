"""The Dask client a campaign submits to: an embedded LocalCluster, or an existing cluster.

The same engine code serves both; only the :class:`distributed.Client` differs.

- Embedded (default): ``LocalCluster`` on 127.0.0.1, ``workers`` worker *processes* (default: one
  per core), each with one thread — the simulator is pure Python, so threads would only share the GIL.
  The scheduler's HTTP endpoint (health, metrics; the dashboard only if bokeh is installed)
  listens on a free port of 127.0.0.1 too.
- External: ``Client("tcp://HOST:PORT")`` to a scheduler started with ``dask scheduler`` (workers
  joined with ``dask worker tcp://HOST:PORT --nthreads 1``) or by dask-jobqueue on SLURM/PBS.
"""

from __future__ import annotations

import contextlib
import logging
import os

from fprime_lite.tools.campaign.errors import CampaignError

__all__ = ["dask_client"]


@contextlib.contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None, connect_timeout_s: float = 20.0):
    """Yield ``(client, info)``; ``info`` describes the cluster for the manifest."""
    from distributed import Client, LocalCluster

    logging.getLogger("distributed").setLevel(logging.ERROR)  # its INFO chatter would bury the progress bar
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=connect_timeout_s)
        except (OSError, TimeoutError) as exc:
            raise CampaignError([f"--scheduler {scheduler}: cannot reach the scheduler ({exc}) — start one with "
                                 f"'dask scheduler' and join workers with 'dask worker {scheduler} --nthreads 1'"]) \
                from None
        try:
            n = len(client.scheduler_info().get("workers", {}))
            yield client, {"type": "external", "scheduler": scheduler, "workers": n}
        finally:
            client.close()
        return
    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1",
                           dashboard_address="127.0.0.1:0", silence_logs=logging.ERROR)
    client = Client(cluster)
    try:
        yield client, {"type": "local", "scheduler": cluster.scheduler_address, "workers": n,
                       "threads_per_worker": 1}
    finally:
        client.close()
        cluster.close()
