"""The PNG plots of a detumble application run, drawn from the run's files alone.

A run draws them when it finishes; ``fprime-lite plot RUN_DIR`` draws them again from the folder (the
:data:`RUN_PLOTTER` plug-in, entry point group ``fprime_lite.plots``; :func:`plot_run_dir` picks each
deployment's plots by the files it wrote). Inputs: ``truth.csv`` (the simulated truth), ``summary.json``
(when detumbling started and completed) and ``channels_wide.csv`` (the deadband thresholds the flight
software reported); the coursework deployment's and ``fprime-lite sim``'s tables go to
:mod:`.history_plots`, ``attitude.csv`` to :func:`detumble.reports.attitude_report.plot_attitude_csv`.

The detumble deployments' plots (:func:`plot_truth`), each with its legend outside the data and the
DetumbleStarted / DetumbleCompleted times as vertical markers:

- ``rate.png`` — body-rate components (deg/s) and |ω| on a log axis with the deadband thresholds;
- ``drive_levels.png`` — a heat strip per coil (X+, X−, Y+, Y−, Z−): the mean drive level (−127…127)
  in each of up to 400 time bins, and below it the share of the time each coil was driven (60 bins),
  both from the exact interval means of ``truth.csv`` (``level_mean_*``, ``on_*``);
- ``state.png`` — the detumble strategy and the share of time in each manager state, when the
  DetumbleManager flew (``truth.csv`` has ``strategy``);
- ``field.png`` — the true geomagnetic field in the body frame (µT) and its magnitude;
- ``dipole.png`` — the coil dipole in the body frame (A·m²): the mean per bin of the exact interval
  means (``m_mean_x_Am2``…) and their range;
- ``attitude.png`` — the attitude quaternion (scalar first) and the pointing error, when the truth
  log has them (``q0``…``q3``, ``pointing_error_deg``);
- ``wheels.png`` — wheel momenta, when the truth log has them (``h0_Nms``…);
- ``power.png`` — :func:`detumble.reports.power_budget.plot_power`, with an electrical system.

A run folder written before the interval means (instantaneous ``level_*``, ``m_x_Am2`` only) is drawn
from those, and its drive-level title says they are aliased.
"""
from __future__ import annotations

import csv
import json
import math
import pathlib

from fprime_lite.tools.plugins import RunPlotter

from detumble.components.types import DetumbleState, DetumbleStrategy
from detumble.control.coil_layout import COIL_FACES, FACE_LABELS
from detumble.reports.figures import read_truth, save_figure
from detumble.reports.power_budget import plot_power

__all__ = ["plot_truth", "plot_run_dir", "RUN_PLOTTER"]

_HEAT_BINS = 400
_SHARE_BINS = 60
_LEVEL_COLUMNS = ("level_xp", "level_xm", "level_yp", "level_ym", "level_zm")  # runs before the interval means
_MEAN_LEVEL_COLUMNS = ("level_mean_xp", "level_mean_xm", "level_mean_yp", "level_mean_ym", "level_mean_zm")
_ON_COLUMNS = ("on_xp", "on_xm", "on_yp", "on_ym", "on_zm")
_THRESHOLDS = ("DEADBAND_UPPER_THRESHOLD", "DEADBAND_LOWER_THRESHOLD")
_THRESHOLD_CHANNELS = {"DEADBAND_UPPER_THRESHOLD": "DeadbandUpperThresholdParam",
                       "DEADBAND_LOWER_THRESHOLD": "DeadbandLowerThresholdParam"}
_LEGEND = {"loc": "upper left", "bbox_to_anchor": (1.01, 1.0), "borderaxespad": 0.0, "fontsize": 8}


def _mark(axes, marks: dict[str, float | None], scale: float, *, label: bool) -> None:
    """Vertical lines at DetumbleStarted / DetumbleCompleted on every axis (labelled on one)."""
    styles = {"detumble started": ("tab:gray", ":"), "detumble completed": ("tab:green", "--")}
    for name, t in marks.items():
        if t is None:
            continue
        colour, ls = styles.get(name, ("tab:gray", "-."))
        for i, ax in enumerate(axes):
            ax.axvline(t / scale, color=colour, ls=ls, lw=1.2,
                       label=f"{name} ({t:,.0f} s)" if label and i == 0 else None)


def plot_truth(truth_csv: pathlib.Path, out_dir: pathlib.Path, *, thresholds: dict[str, float] | None = None,
               marks: dict[str, float | None] | None = None) -> list[pathlib.Path]:
    """Draw the run's plots from ``truth_csv`` into ``out_dir``; return the files written.

    ``thresholds``: the DetumbleManager's DEADBAND_UPPER/LOWER_THRESHOLD (deg/s) for the rate plot;
    ``marks``: ``{"detumble started": s, "detumble completed": s}`` since the start of the run.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir = pathlib.Path(out_dir)
    data = read_truth(truth_csv)
    t = data.get("t_s", [])
    if len(t) < 2:  # one sample (a run stopped at its start) draws no time history
        return []
    unit, scale = ("min", 60.0) if t[-1] > 1800 else ("s", 1.0)
    tt = [v / scale for v in t]
    xlabel = f"time since the start of the run ({unit})"
    marks = {k: v for k, v in (marks or {}).items() if v is not None}
    written = []

    def finish(fig, axes, name, title):
        _mark(axes, marks, scale, label=True)
        for ax in axes:
            handles, _ = ax.get_legend_handles_labels()
            if handles:
                ax.legend(**_LEGEND)
            ax.grid(alpha=0.3, which="both")
            ax.set_xlim(tt[0], tt[-1])
        axes[-1].set_xlabel(xlabel)
        fig.suptitle(title)
        written.append(save_figure(fig, out_dir / name))
        plt.close(fig)

    # rate.png
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(10, 6.5))
    for axis, colour, label in (("wx_deg_s", "tab:red", "ωx"), ("wy_deg_s", "tab:green", "ωy"),
                                ("wz_deg_s", "tab:blue", "ωz")):
        ax1.plot(tt, data[axis], lw=0.8, color=colour, label=label)
    ax1.set_ylabel("body rate (deg/s)")
    ax2.plot(tt, data["rate_deg_s"], color="black", lw=1.0, label="|ω|")
    for (name, value), style in zip((thresholds or {}).items(), ("--", ":"), strict=False):
        ax2.axhline(value, color="tab:orange", ls=style, lw=1.0, label=f"{name} {value:g} deg/s")
    ax2.set_ylabel("|ω| (deg/s)")
    ax2.set_yscale("log")
    finish(fig, [ax1, ax2], "rate.png", "Body rate (truth)")

    # drive_levels.png: a heat strip per coil, and the share of each bin each coil was on
    import numpy as np

    interval_means = all(c in data for c in _MEAN_LEVEL_COLUMNS + _ON_COLUMNS)
    if interval_means:  # exact means over each sample interval (a run since the columns were added)
        levels = np.array([data[c] for c in _MEAN_LEVEL_COLUMNS])[:, 1:]  # the first row closes no interval
        driven = np.array([data[c] for c in _ON_COLUMNS])[:, 1:]
    else:  # an older run's instantaneous levels: aliased by the sampling, as its title says
        levels = np.array([data[c] for c in _LEVEL_COLUMNS if c in data])
        driven = (levels != 0).astype(float)
    if levels.size:
        bins = min(_HEAT_BINS, levels.shape[1])
        edges = np.linspace(0, levels.shape[1], bins + 1).astype(int)
        mean = np.array([[row[a:b].mean() if b > a else np.nan for a, b in zip(edges[:-1], edges[1:], strict=True)]
                         for row in levels])
        on_edges = np.linspace(0, levels.shape[1], min(_SHARE_BINS, levels.shape[1]) + 1).astype(int)
        on = np.array([[row[a:b].mean() if b > a else np.nan
                        for a, b in zip(on_edges[:-1], on_edges[1:], strict=True)]
                       for row in driven])
        labels = [FACE_LABELS[f] for f in COIL_FACES][:len(levels)]
        fig = plt.figure(figsize=(10, 5.5))
        grid = fig.add_gridspec(2, 2, width_ratios=[40, 1], height_ratios=[3, 2], wspace=0.03, hspace=0.12)
        ax1 = fig.add_subplot(grid[0, 0])
        ax2 = fig.add_subplot(grid[1, 0], sharex=ax1)
        t_edges = [tt[min(i, len(tt) - 1)] for i in edges]  # interval i runs from tt[i] to tt[i + 1]
        mesh = ax1.pcolormesh(t_edges, np.arange(len(levels) + 1) - 0.5, mean, cmap="RdBu_r", vmin=-127,
                              vmax=127, shading="flat")
        ax1.set_yticks(range(len(labels)), labels)
        ax1.set_ylim(len(levels) - 0.5, -0.5)
        ax1.set_ylabel("coil")
        ax1.tick_params(labelbottom=False)
        bar = fig.colorbar(mesh, cax=fig.add_subplot(grid[0, 1]))
        bar.set_label("mean drive level")
        on_t = [tt[min(i, len(tt) - 1)] for i in on_edges]
        for row, label in zip(on, labels, strict=True):
            ax2.stairs(row * 100, on_t, lw=1.0, label=label, baseline=None)
        ax2.set_ylabel("time driven (%)")
        ax2.set_ylim(-3, 103)
        ax2.set_xlim(tt[0], tt[-1])
        _mark([ax1, ax2], marks, scale, label=False)
        ax2.legend(**_LEGEND)
        ax2.grid(alpha=0.3)
        ax2.set_xlabel(xlabel)
        n = levels.shape[1] / bins
        fig.suptitle(f"Magnetorquer drive levels (exact means over the sample intervals; {n:.0f} interval(s) per bin)"
                     if interval_means else
                     f"Magnetorquer drive levels (instantaneous truth samples, aliased; {n:.0f} sample(s) per bin)")
        written.append(save_figure(fig, out_dir / "drive_levels.png"))
        plt.close(fig)

    # state.png: the DetumbleManager's panel, when the run's manager flew (truth.csv has its columns)
    if "strategy" in data:
        _plot_state(plt, data, tt, finish)

    # field.png
    if "bx_uT" in data:
        fig, ax = plt.subplots(figsize=(10, 4))
        for axis, colour in (("bx_uT", "tab:red"), ("by_uT", "tab:green"), ("bz_uT", "tab:blue")):
            ax.plot(tt, data[axis], lw=0.8, color=colour, label=f"B{axis[1]} (body)")
        magnitude = [math.sqrt(x * x + y * y + z * z)
                     for x, y, z in zip(data["bx_uT"], data["by_uT"], data["bz_uT"], strict=True)]
        ax.plot(tt, magnitude, lw=1.0, color="black", label="|B|")
        ax.set_ylabel("geomagnetic field (µT)")
        finish(fig, [ax], "field.png", "Geomagnetic field in the body frame (truth)")

    # dipole.png: per axis, the binned mean and RMS (a bang-bang dipole sampled once a second is
    # otherwise a solid block of colour)
    if "m_mean_x_Am2" in data:  # exact interval means: their mean per bin, and the range of the interval means
        bins = max(1, min(300, (len(tt) - 1) // 4))
        edges = np.linspace(1, len(tt), bins + 1).astype(int)  # row 0 closes no interval
        centres = [0.5 * (tt[a - 1] + tt[b - 1]) for a, b in zip(edges[:-1], edges[1:], strict=True) if b > a]
        fig, axes = plt.subplots(3, 1, sharex=True, figsize=(10, 6.5))
        for ax, a, colour in zip(axes, ("x", "y", "z"), ("tab:red", "tab:green", "tab:blue"), strict=True):
            m = np.asarray(data[f"m_mean_{a}_Am2"], dtype=float)
            chunks = [m[i:j] for i, j in zip(edges[:-1], edges[1:], strict=True) if j > i]
            ax.fill_between(centres, [c.min() for c in chunks], [c.max() for c in chunks], color=colour, alpha=0.25,
                            lw=0, label=f"range of m{a}'s interval means")
            ax.plot(centres, [c.mean() for c in chunks], color=colour, lw=1.0, label=f"mean m{a}")
            ax.axhline(0.0, color="grey", lw=0.5)
            ax.set_ylabel(f"m{a} (A·m²)")
        n = (len(tt) - 1) / bins
        finish(fig, list(axes), "dipole.png",
               f"Magnetorquer dipole in the body frame (truth; exact means over the sample intervals, {n:.0f} per bin)")
    elif "m_x_Am2" in data:  # an older run: instantaneous samples
        bins = max(1, min(300, len(tt) // 4))
        edges = np.linspace(0, len(tt), bins + 1).astype(int)
        centres = [tt[(a + b - 1) // 2] for a, b in zip(edges[:-1], edges[1:], strict=True) if b > a]
        fig, axes = plt.subplots(3, 1, sharex=True, figsize=(10, 6.5))
        for ax, a, colour in zip(axes, ("x", "y", "z"), ("tab:red", "tab:green", "tab:blue"), strict=True):
            m = np.asarray(data[f"m_{a}_Am2"], dtype=float)
            chunks = [m[i:j] for i, j in zip(edges[:-1], edges[1:], strict=True) if j > i]
            mean = np.array([c.mean() for c in chunks])
            rms = np.array([math.sqrt(float((c * c).mean())) for c in chunks])
            ax.fill_between(centres, -rms, rms, color=colour, alpha=0.25, lw=0, label=f"±RMS m{a}")
            ax.plot(centres, mean, color=colour, lw=1.0, label=f"mean m{a}")
            ax.set_ylabel(f"m{a} (A·m²)")
        n = len(tt) / bins
        finish(fig, list(axes), "dipole.png",
               f"Magnetorquer dipole in the body frame (truth; mean and RMS of {n:.0f} sample(s) per bin)")

    # attitude.png
    if "q0" in data:
        error = data.get("pointing_error_deg")
        has_error = error is not None and any(not math.isnan(v) for v in error)
        fig, rows = plt.subplots(2 if has_error else 1, 1, sharex=True, figsize=(10, 6 if has_error else 4),
                                 squeeze=False)
        axes = [a[0] for a in rows]
        for q, colour in (("q0", "black"), ("q1", "tab:red"), ("q2", "tab:green"), ("q3", "tab:blue")):
            axes[0].plot(tt, data[q], lw=0.8, color=colour, label=q)
        axes[0].set_ylabel("q_BN (scalar first)")
        axes[0].set_ylim(-1.05, 1.05)
        if has_error:
            axes[1].plot(tt, error, lw=0.8, color="tab:purple", label="pointing error")
            axes[1].set_ylabel("pointing error (deg)")
        finish(fig, axes, "attitude.png", "Attitude (truth)")

    # wheels.png
    wheels = [c for c in data if c.startswith("h") and c.endswith("_Nms")]
    if wheels:
        fig, ax = plt.subplots(figsize=(10, 4))
        for c in wheels:
            ax.plot(tt, data[c], lw=0.8, label=f"wheel {c[1:-4]}")
        ax.set_ylabel("wheel momentum (N·m·s)")
        finish(fig, [ax], "wheels.png", "Reaction wheel momenta (truth)")
    return written



def _plot_state(plt, data: dict, tt: list, finish) -> None:
    """``state.png``: the detumble strategy, and the share of each interval in each manager state."""
    strategies = [s.name for s in DetumbleStrategy]
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(10, 5), gridspec_kw={"height_ratios": [1, 2]})
    ax1.step(tt, [strategies.index(s) if s in strategies else -1 for s in data.get("strategy", [])],
             where="post", color="tab:purple", lw=1.0, label="strategy")
    ax1.set_yticks(range(len(strategies)), strategies)
    states = [st.name for st in DetumbleState if f"frac_{st.name.lower()}" in data]
    if states:
        ax2.stackplot(tt, *(data[f"frac_{name.lower()}"] for name in states), labels=states, step="pre",
                      alpha=0.85)  # a row's shares are those of the interval that ends at it
    ax2.set_ylim(0, 1)
    ax2.set_ylabel("share of time")
    finish(fig, [ax1, ax2], "state.png", "Detumble strategy, and the share of each interval in each state")


def _thresholds_from_channels(run_dir: pathlib.Path) -> dict[str, float]:
    """The last reported deadband thresholds in ``channels_wide.csv`` (empty if absent)."""
    path = run_dir / "channels_wide.csv"
    if not path.exists():
        return {}
    wanted = {}
    last: dict[str, float] = {}
    with open(path, encoding="utf-8", newline="") as f:
        reader = csv.reader(f)
        header = next(reader, [])
        for i, column in enumerate(header):
            for param, channel in _THRESHOLD_CHANNELS.items():
                if column.split(" [")[0].endswith(f".{channel}"):
                    wanted[i] = param
        for row in reader:
            for i, param in wanted.items():
                if i < len(row) and row[i] != "":
                    last[param] = float(row[i])
    return {p: last[p] for p in _THRESHOLDS if p in last}


def plot_run_dir(run_dir: pathlib.Path, out_dir: pathlib.Path | None = None) -> list[pathlib.Path]:
    """Draw the plots of the finished run in ``run_dir`` (into ``out_dir``, default the run folder), each
    deployment's from its own files: the detumble deployments' ``truth.csv`` (with the coil columns),
    the coursework deployment's ``truth.csv`` and a plant-only run's ``rate.csv`` (seed 004's time
    histories, :mod:`.history_plots`), and the attitude report's ``attitude.csv``."""
    from detumble.reports.attitude_report import plot_attitude_csv
    from detumble.reports.history_plots import plot_time_histories

    run_dir = pathlib.Path(run_dir)
    summary: dict = {}
    summary_path = run_dir / "summary.json"
    if summary_path.exists():
        summary = json.loads(summary_path.read_text(encoding="utf-8"))
    marks = {"detumble started": summary.get("detumble_started_s"),
             "detumble completed": summary.get("detumble_complete_s")}
    out = pathlib.Path(out_dir or run_dir)
    written: list[pathlib.Path] = []
    truth = run_dir / "truth.csv"
    if truth.is_file():
        if is_detumble_truth(truth):
            manager_flew = "strategy" in _header(truth)  # else its thresholds are not this run's
            written += plot_truth(truth, out, thresholds=_thresholds_from_channels(run_dir) if manager_flew else {},
                                  marks=marks)
            written += plot_power(truth, out, marks["detumble started"], marks["detumble completed"])
        else:
            written += plot_time_histories(truth, out)
    rate = run_dir / "rate.csv"
    if rate.is_file():
        written += plot_time_histories(rate, out, title=f"law {summary['law']}" if summary.get("law") else "")
    attitude = run_dir / "attitude.csv"
    if attitude.is_file():
        written += plot_attitude_csv(attitude, out, summary.get("wheel_momentum_capacity_nms") or [])
    return written


def is_detumble_truth(truth_csv: pathlib.Path) -> bool:
    """True for a detumble report's ``truth.csv`` (it has the coil columns), False for the coursework's."""
    header = _header(truth_csv)
    return any(c in header for c in _MEAN_LEVEL_COLUMNS + _LEVEL_COLUMNS)


def _header(table: pathlib.Path) -> list[str]:
    with open(table, encoding="utf-8", newline="") as f:
        return next(csv.reader(f), [])


def _has_run_table(run_dir: pathlib.Path) -> bool:
    return any((pathlib.Path(run_dir) / name).is_file() for name in ("truth.csv", "rate.csv", "attitude.csv"))


#: ``fprime-lite plot RUN_DIR`` for the detumble application's runs (``fprime-lite run`` of its three
#: deployments, ``fprime-lite sim``).
RUN_PLOTTER = RunPlotter(name="detumble", applies=_has_run_table, plot=plot_run_dir)
