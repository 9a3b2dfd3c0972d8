"""A Dask preload for the embedded cluster's processes: end this process when its parent is gone.

The embedded cluster's workers are subprocesses (``python -m dask spec``, then the Nanny's worker
process). If the campaign process is killed (SIGTERM, SIGKILL) nothing closes them; this module,
preloaded into both the Nanny and the worker (``preload`` / ``preload_nanny``), watches the parent
process id once a second and exits when it changes (the process was re-parented: its parent died).
"""

from __future__ import annotations

import os
import threading
import time

__all__ = ["dask_setup", "watch_parent"]

_started = False


def watch_parent(period_s: float = 1.0) -> None:
    """Start (once per process) a daemon thread that ends the process when its parent dies."""
    global _started
    if _started:
        return
    _started = True
    parent = os.getppid()

    def watch() -> None:
        while True:
            time.sleep(period_s)
            if os.getppid() != parent:
                os._exit(1)
    threading.Thread(target=watch, name="campaign-orphan-guard", daemon=True).start()


def dask_setup(_worker_or_nanny) -> None:
    """Dask's preload hook."""
    watch_parent()
