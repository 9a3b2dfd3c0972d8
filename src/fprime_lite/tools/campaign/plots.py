"""Campaign plots (PNG, headless Agg): a metric against one parameter with its spread; a heatmap over
two parameters; histogram and CDF for Monte Carlo.

Without a ``plots:`` section the campaign draws, for each metric: a line plot when the grid varies
one numeric key, a heatmap when it varies two, and a histogram + CDF otherwise.
"""

from __future__ import annotations

import pathlib
from typing import Callable

import numpy as np

__all__ = ["draw_plots", "auto_plots"]

AGGREGATES: dict[str, Callable[[np.ndarray], float]] = {
    "median": np.median, "mean": np.mean, "p95": lambda x: np.percentile(x, 95), "max": np.max, "min": np.min}


def _numeric_axes(df, campaign) -> list[str]:
    axes = []
    for k in campaign.grid_keys:
        col = df[k].dropna()
        if col.nunique() > 1 and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in col):
            axes.append(k)
    return axes


def auto_plots(df, campaign) -> list[dict]:
    axes = _numeric_axes(df, campaign)
    plots = []
    for m in campaign.metrics:
        if len(axes) == 1:
            plots.append({"type": "line", "x": axes[0], "metric": m})
        elif len(axes) == 2:
            plots.append({"type": "heatmap", "x": axes[0], "y": axes[1], "metric": m})
        elif not campaign.grid_keys or df["point"].nunique() == 1:
            plots += [{"type": "histogram", "metric": m}, {"type": "cdf", "metric": m}]
    return plots


def _log_if_geometric(ax, values, which: str) -> None:
    v = np.asarray(sorted(set(values)), dtype=float)
    if len(v) >= 3 and np.all(v > 0) and v[-1] / v[0] >= 20:
        (ax.set_xscale if which == "x" else ax.set_yscale)("log")


def _line(ax, df, x: str, metric: str) -> None:
    ok = df[df[metric].notna()]
    ax.scatter(ok[x], ok[metric], s=10, alpha=0.4, label="runs (seeds, other keys)")
    g = ok.groupby(x)[metric]
    xs = np.array(sorted(g.groups), dtype=float)
    if len(xs):
        med = g.median().reindex(xs).to_numpy()
        lo = g.quantile(0.05).reindex(xs).to_numpy()
        hi = g.quantile(0.95).reindex(xs).to_numpy()
        ax.fill_between(xs, lo, hi, alpha=0.2, label="5–95 %")
        ax.plot(xs, med, marker="o", label="median")
    _log_if_geometric(ax, df[x].dropna(), "x")
    nulls = df[metric].isna().sum()
    ax.set_xlabel(x)
    ax.set_ylabel(metric)
    ax.set_title(f"{metric} against {x}" + (f" ({nulls} null)" if nulls else ""))
    ax.legend(fontsize=8)


def _heatmap(fig, ax, df, x: str, y: str, metric: str, agg: str) -> None:
    fn = AGGREGATES[agg]
    xs = sorted(df[x].dropna().unique())
    ys = sorted(df[y].dropna().unique())
    grid = np.full((len(ys), len(xs)), np.nan)
    for (xv, yv), g in df.groupby([x, y]):
        vals = g[metric].to_numpy(dtype=float)
        vals = np.where(np.isnan(vals), np.inf, vals)  # a null (never reached) ranks as infinitely bad
        v = fn(vals)
        grid[ys.index(yv), xs.index(xv)] = v if np.isfinite(v) else np.nan
    im = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis")
    ax.set_xticks(range(len(xs)), [f"{v:.3g}" for v in xs], rotation=45)
    ax.set_yticks(range(len(ys)), [f"{v:.3g}" for v in ys])
    for i in range(len(ys)):
        for j in range(len(xs)):
            ax.text(j, i, "never" if np.isnan(grid[i, j]) else f"{grid[i, j]:.3g}", ha="center", va="center",
                    fontsize=7, color="w")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.set_title(f"{agg} of {metric}")
    fig.colorbar(im, ax=ax, label=metric)


def _distribution(ax, df, metric: str, cdf: bool) -> None:
    x = df[metric].dropna().to_numpy(dtype=float)
    nulls = df[metric].isna().sum()
    if cdf:
        xs = np.sort(x)
        ax.step(xs, np.arange(1, len(xs) + 1) / max(len(df), 1), where="post")
        ax.set_ylabel("fraction of runs")
        ax.set_ylim(0, 1)
    else:
        ax.hist(x, bins=min(30, max(5, len(x) // 3)))
        ax.set_ylabel("runs")
    ax.set_xlabel(metric)
    ax.set_title(f"{'CDF' if cdf else 'histogram'} of {metric} ({len(x)} runs" +
                 (f", {nulls} null" if nulls else "") + ")")


def draw_plots(df, campaign, folder: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for i, p in enumerate(campaign.plots or auto_plots(df, campaign)):
        fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
        kind, metric = p["type"], p["metric"]
        if kind == "line":
            _line(ax, df, p["x"], metric)
        elif kind == "heatmap":
            _heatmap(fig, ax, df, p["x"], p["y"], metric, p.get("agg", "median"))
        else:
            _distribution(ax, df, metric, cdf=kind == "cdf")
        name = "_".join(str(s).split(".")[-1] for s in (kind, p.get("x", ""), p.get("y", ""), metric) if s)
        path = folder / f"{i:02d}_{name}.png"
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written
