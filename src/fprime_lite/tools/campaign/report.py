"""What a campaign shows on the terminal: the progress bar and the summary tables."""

from __future__ import annotations

import contextlib
import math
import time

import numpy as np

__all__ = ["progress_bar", "print_summary", "point_table", "percentile"]


@contextlib.contextmanager
def progress_bar(total: int, already: int, enabled: bool, console=None, log_every_s: float = 60.0,
                 running=lambda: 0):
    """A rich progress bar: done/total, failed, runs per hour and ETA. Yields ``update(row)``.

    Disabled (no terminal), it prints a plain line to stderr every ``log_every_s`` instead — a
    heartbeat, printed even when no run has finished since the last one (``running()``: how many
    runs are in flight), so a log shows the campaign is alive.
    """
    import sys
    import threading

    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, \
        TimeRemainingColumn

    t0 = time.perf_counter()
    state = {"done": 0, "failed": 0, "last_row": t0}
    lock = threading.Lock()

    def line() -> str:
        now = time.perf_counter()
        wall = now - t0
        done = state["done"]
        rate = done / wall * 3600 if wall > 0 else 0.0
        left = f"ETA {(total - already - done) * wall / done / 60:.1f} min" if done else "ETA —"
        return (f"campaign: {already + done}/{total} done, {state['failed']} failed, {running()} running, "
                f"{rate:,.0f} runs/h, last result {now - state['last_row']:.0f} s ago, {left}")

    stop = threading.Event()

    def heartbeat() -> None:
        while not stop.wait(log_every_s):
            with lock:
                print(line(), file=sys.stderr, flush=True)

    with Progress(TextColumn("[bold]campaign"), BarColumn(), MofNCompleteColumn(),
                  TextColumn("failed {task.fields[failed]}"), TextColumn("{task.fields[rate]}"),
                  TimeElapsedColumn(), TextColumn("ETA"), TimeRemainingColumn(), console=console,
                  disable=not enabled, transient=False) as bar:
        task = bar.add_task("runs", total=total, completed=already, failed=0, rate="")
        beat = None
        if not enabled:
            beat = threading.Thread(target=heartbeat, name="campaign-heartbeat", daemon=True)
            beat.start()

        def update(row: dict) -> None:
            with lock:
                state["done"] += 1
                if row["status"] != "ok":
                    state["failed"] += 1
                now = time.perf_counter()
                state["last_row"] = now
            if enabled:
                wall = now - t0
                bar.update(task, advance=1, failed=state["failed"], rate=f"{state['done'] / wall * 3600:,.0f} runs/h")
        try:
            yield update
        finally:
            stop.set()
            if beat is not None:
                beat.join(timeout=5)


def _stats(x: np.ndarray) -> list[str]:
    if not len(x):
        return ["—"] * 6
    q = np.percentile(x, [5, 50, 95])
    return [f"{x.mean():.4g}", f"{q[0]:.4g}", f"{q[1]:.4g}", f"{q[2]:.4g}", f"{x.min():.4g}", f"{x.max():.4g}"]


def point_table(df, campaign, metric: str):
    """Per grid point: the grid values and the metric's median, 95th percentile and count.

    A run whose metric is null (e.g. never detumbled) counts as +inf: it ranks the point last, as
    it should for a "fastest at the 95th percentile" question.
    """
    import pandas as pd

    import json

    keys = campaign.grid_keys
    rows = []
    for point, g in df.groupby("point", sort=True):
        x = g[metric].to_numpy(dtype=float)
        filled = np.where(np.isnan(x), np.inf, x)
        asked = json.loads(g.iloc[0]["requested"])
        rows.append({"point": point, **{k: asked.get(k) for k in keys}, "runs": len(g),
                     "null": int(np.isnan(x).sum()), "median": percentile(filled, 50),
                     "p95": percentile(filled, 95), "max": float(filled.max())})
    return pd.DataFrame(rows)


def percentile(x: np.ndarray, q: float) -> float:
    """numpy's default (linear) percentile, where +inf stands for "never": inf only when the
    interpolation actually reaches an inf sample (numpy would give nan for inf·0)."""
    s = np.sort(np.asarray(x, dtype=float))
    if not len(s):
        return math.nan
    h = (len(s) - 1) * q / 100.0
    lo, hi = int(math.floor(h)), int(math.ceil(h))
    frac = h - lo
    if frac == 0.0 or s[lo] == s[hi]:
        return float(s[lo])
    return float(s[lo] + (s[hi] - s[lo]) * frac)


def print_summary(df, campaign, console=None, wall_s: float | None = None) -> None:
    from rich.console import Console
    from rich.table import Table

    console = console or Console()
    counts = df["status"].value_counts().to_dict() if len(df) else {}
    head = ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) or "no runs"
    speed = f"; {len(df) / wall_s * 3600:,.0f} runs/h" if wall_s else ""
    table = Table(title=f"Campaign {campaign.name} — {len(df)} runs: {head}{speed}")
    for col in ("metric", "n", "null", "mean", "p5", "p50", "p95", "min", "max"):
        table.add_column(col, justify="left" if col == "metric" else "right")
    ok = df[df["status"] == "ok"] if len(df) else df
    grouped = {m for members in campaign.metric_groups.values() for m in members}
    for m in campaign.metrics:
        if m in grouped:
            continue
        x = ok[m].to_numpy(dtype=float) if len(ok) else np.array([])
        finite = x[~np.isnan(x)]
        table.add_row(m, str(len(finite)), str(int(np.isnan(x).sum())), *_stats(finite))
    console.print(table)
    for group, members in campaign.metric_groups.items():
        console.print(f"{group}: {len(members)} columns in results.parquet (not tabulated here)")
    failures = df[df["status"] != "ok"] if len(df) else df
    for _, r in failures.head(5).iterrows():
        console.print(f"[red]{r['status']}[/red] run {r['run_id']} (point {r['point']}, seed {r['seed_index']}): "
                      f"{r['error']}")
    if len(failures) > 5:
        console.print(f"… and {len(failures) - 5} more (column 'error' of results.parquet)")
    n_points = df["point"].nunique() if len(df) else 0
    if campaign.metrics and n_points > 1 and campaign.grid_keys:
        metric = campaign.metrics[0]
        best = point_table(df, campaign, metric).sort_values(["p95", "median"]).head(5)
        t = Table(title=f"Best grid points by the 95th percentile of {metric} (null counted as never)")
        for col in best.columns:
            t.add_column(str(col), justify="right")
        for _, r in best.iterrows():
            t.add_row(*[f"{v:.4g}" if isinstance(v, float) else str(v) for v in r.tolist()])
        console.print(t)
