"""Campaign plots (PNG, headless Agg): a metric against one parameter with its spread; a heatmap over
two parameters; histogram and CDF for Monte Carlo.

Without a ``plots:`` section the campaign draws, for each metric: a line plot when the grid varies
one numeric key, a heatmap when it varies two, and a histogram + CDF otherwise.
"""

from __future__ import annotations

import pathlib
from typing import Callable

import numpy as np

__all__ = ["draw_plots", "auto_plots", "aggregate", "AGGREGATE_NAMES"]

AGGREGATES: dict[str, Callable[[np.ndarray], float]] = {
    "median": np.median, "mean": np.mean, "max": np.max, "min": np.min}
AGGREGATE_NAMES = ("median", "mean", "p95", "max", "min")


def aggregate(name) -> Callable[[np.ndarray], float] | None:
    """The heatmap aggregate called ``name``: median, mean, max, min or ``pNN`` (the NN-th
    percentile, 0–100, where a null counts as never); None for anything else."""
    if not isinstance(name, str):
        return None
    if name in AGGREGATES:
        return AGGREGATES[name]
    if name.startswith("p"):
        try:
            q = float(name[1:])
        except ValueError:
            return None
        if 0 <= q <= 100:
            from fprime_lite.tools.campaign.report import percentile

            return lambda x: percentile(x, q)
    return None


def _numeric_axes(df, campaign) -> list[str]:
    axes = []
    for k in campaign.grid_keys:
        col = df[k].dropna()
        # a list-valued key (a vector setting) is not an axis, and cannot be hashed for nunique: test it first
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in col) and col.nunique() > 1:
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


def _label(v) -> str:
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def _line(ax, df, x: str, metric: str, others: list[str], percentiles=(5, 95)) -> None:
    """The metric against ``x``: the runs as points; per grid point (one line for each combination
    of the ``others`` grid keys) the median and the ``percentiles`` band over its seeds."""
    lo_q, hi_q = percentiles
    ok = df[df[metric].notna()]
    ax.scatter(ok[x], ok[metric], s=10, alpha=0.35, color="0.4", label="runs")
    others = [k for k in others if k != x and k in df.columns and df[k].map(repr).nunique() > 1]
    groups = ok.groupby(ok[others].map(repr).apply(tuple, axis=1) if others else np.zeros(len(ok)), sort=True) \
        if len(ok) else []
    for i, (_, g) in enumerate(groups):
        by_x = g.groupby(x)[metric]
        xs = np.array(sorted(by_x.groups), dtype=float)
        if not len(xs):
            continue
        med = by_x.median().reindex(xs).to_numpy()
        lo = by_x.quantile(lo_q / 100).reindex(xs).to_numpy()
        hi = by_x.quantile(hi_q / 100).reindex(xs).to_numpy()
        label = ", ".join(f"{k.split('.')[-1]}={_label(g.iloc[0][k])}" for k in others) if others else "median"
        color = f"C{i % 10}"
        ax.fill_between(xs, lo, hi, alpha=0.15, color=color)
        ax.plot(xs, med, marker="o", color=color, label=label + (" (median)" if others else ""))
    ax.plot([], [], color="0.5", alpha=0.3, linewidth=6, label=f"{lo_q:g}–{hi_q:g} % over seeds")
    _log_if_geometric(ax, df[x].dropna(), "x")
    nulls = df[metric].isna().sum()
    ax.set_xlabel(x)
    ax.set_ylabel(metric)
    ax.set_title(f"{metric} against {x}" + (f" ({nulls} null)" if nulls else ""))
    ax.legend(fontsize=7)


def _cell(v: float) -> str:
    """A heatmap cell's value: three significant digits, but whole numbers from 1,000 up (2,989 s, not
    2.99e+03)."""
    return f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.3g}"


def _heatmap(fig, ax, df, x: str, y: str, metric: str, agg: str) -> None:
    """``agg`` of the metric per (x, y) cell; a null counts as never (it ranks last), a cell whose
    aggregate is never is drawn hatched and labelled "never"; with no value at all, no colour bar."""
    from matplotlib.patches import Rectangle

    fn = aggregate(agg) or AGGREGATES["median"]
    xs = sorted(df[x].dropna().unique())
    ys = sorted(df[y].dropna().unique())
    grid = np.full((len(ys), len(xs)), np.nan)
    has_runs = np.zeros_like(grid, dtype=bool)
    for (xv, yv), g in df.groupby([x, y]):
        vals = g[metric].to_numpy(dtype=float)
        vals = np.where(np.isnan(vals), np.inf, vals)  # a null (never reached) ranks as infinitely bad
        v = fn(vals)
        i, j = ys.index(yv), xs.index(xv)
        has_runs[i, j] = True
        grid[i, j] = v if np.isfinite(v) else np.nan
    finite = np.isfinite(grid)
    im = ax.imshow(np.ma.masked_invalid(grid), origin="lower", aspect="auto", cmap="viridis")
    cmap = im.get_cmap()
    for i in range(len(ys)):
        for j in range(len(xs)):
            if finite[i, j]:
                r, gr, b, _ = cmap(im.norm(grid[i, j]))
                dark = 0.299 * r + 0.587 * gr + 0.114 * b < 0.5
                ax.text(j, i, _cell(grid[i, j]), ha="center", va="center", fontsize=7, color="w" if dark else "k")
            elif has_runs[i, j]:
                ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="0.85", edgecolor="0.45", hatch="//",
                                       linewidth=0.5))
                ax.text(j, i, "never", ha="center", va="center", fontsize=7, color="k", fontweight="bold",
                        bbox={"facecolor": "w", "edgecolor": "none", "pad": 1.5})  # not crossed by the hatching
    ax.set_xlim(-0.5, len(xs) - 0.5)
    ax.set_ylim(-0.5, len(ys) - 0.5)
    ax.set_xticks(range(len(xs)), [f"{v:.3g}" for v in xs], rotation=45)
    ax.set_yticks(range(len(ys)), [f"{v:.3g}" for v in ys])
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    if finite.any():
        fig.colorbar(im, ax=ax, label=metric)
        ax.set_title(f"{agg} of {metric}" + (" (hatched: never)" if (has_runs & ~finite).any() else ""))
    else:
        ax.set_title(f"{agg} of {metric}: no value in any cell (every run null)")


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
            _line(ax, df, p["x"], metric, campaign.grid_keys, tuple(p.get("percentiles", (5, 95))))
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
