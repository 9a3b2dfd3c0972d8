"""Seed 004's time histories, drawn from a run's table: the coursework deployment's ``truth.csv`` and a
plant-only run's ``rate.csv`` (``fprime-lite sim``).

The plots the coursework report shows for its three controllers (seed 004, figures 2–11):

- ``rates.png`` — the body rate ω_BN in the body frame (deg/s) per axis, and |ω| with the body rate
  relative to the orbit frame ω_BO (the wheel law's and the magnetic laws' end state: ω_BO → 0, so
  ω_BN → (0, −n, 0));
- ``beta.png`` — β = acos(B_y/|B|), the angle between body +Y and the true geomagnetic field (deg;
  the ``magnetorquer2`` law's input, seed 004 eq. 20), when the table has the field;
- ``wheel_momentum.png`` — each reaction wheel's momentum (mN·m·s), when the spacecraft has wheels and
  the law moved them;
- ``quaternion_orbit.png`` — q_BO, the attitude relative to the orbit frame (scalar first).

Both tables name their columns after :mod:`detumble.sim.truth` (``qo0`` …, ``b_x_uT`` …, ``h0_Nms`` …);
``rate.csv`` names time and rate ``time_s`` and ``omega_x_deg_s`` … and is read as ``t_s``/``wx_deg_s``.
"""
from __future__ import annotations

import math
import pathlib

from detumble.reports.figures import read_truth, save_figure

__all__ = ["plot_time_histories", "read_history"]

_LEGEND = {"loc": "upper left", "bbox_to_anchor": (1.01, 1.0), "borderaxespad": 0.0, "fontsize": 8}
_RENAME = {"time_s": "t_s", "omega_x_deg_s": "wx_deg_s", "omega_y_deg_s": "wy_deg_s", "omega_z_deg_s": "wz_deg_s"}
_AXES = (("x", "tab:red"), ("y", "tab:green"), ("z", "tab:blue"))


def read_history(path: pathlib.Path) -> dict[str, list]:
    """The table's columns (floats, decimated as :func:`read_truth` does), ``rate.csv``'s renamed."""
    data = read_truth(path)
    return {_RENAME.get(name, name): values for name, values in data.items()}


def plot_time_histories(table: pathlib.Path, out_dir: pathlib.Path, *, title: str = "") -> list[pathlib.Path]:
    """Draw the time histories of ``table`` (a ``truth.csv`` or ``rate.csv``) into ``out_dir``; return
    the files written. ``title`` goes before each plot's own title (e.g. the law's name)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = read_history(pathlib.Path(table))
    t = data.get("t_s", [])
    if len(t) < 2 or "wx_deg_s" not in data:
        return []
    out_dir = pathlib.Path(out_dir)
    unit, scale = ("h", 3600.0) if t[-1] > 3 * 3600 else ("min", 60.0) if t[-1] > 1800 else ("s", 1.0)
    tt = [v / scale for v in t]
    prefix = f"{title}: " if title else ""
    written = []

    def finish(fig, axes, name, heading):
        for ax in axes:
            if ax.get_legend_handles_labels()[0]:
                ax.legend(**_LEGEND)
            ax.grid(alpha=0.3, which="both")
            ax.set_xlim(tt[0], tt[-1])
        axes[-1].set_xlabel(f"time since the start of the run ({unit})")
        fig.suptitle(prefix + heading)
        written.append(save_figure(fig, out_dir / name))
        plt.close(fig)

    has_orbit_rate = "wo_x_deg_s" in data
    fig, rows = plt.subplots(3 if has_orbit_rate else 2, 1, sharex=True, figsize=(10, 8 if has_orbit_rate else 6),
                             squeeze=False)
    axes = [r[0] for r in rows]
    for a, colour in _AXES:
        axes[0].plot(tt, data[f"w{a}_deg_s"], lw=0.8, color=colour, label=f"ω{a}")
    axes[0].set_ylabel("ω_BN, body frame (deg/s)")
    rate = [v for v in data["rate_deg_s"]]
    axes[1].plot(tt, rate, lw=1.0, color="black", label="|ω_BN|")
    if any(v > 0 for v in rate):
        axes[1].set_yscale("log")
    axes[1].set_ylabel("|ω| (deg/s)")
    if has_orbit_rate:
        for a, colour in _AXES:
            axes[2].plot(tt, data[f"wo_{a}_deg_s"], lw=0.8, color=colour, label=f"ω_BO {a}")
        axes[2].set_ylabel("ω_BO, body frame (deg/s)")
    finish(fig, axes, "rates.png", "Body rates (truth)")

    if all(f"b_{a}_uT" in data for a, _ in _AXES):
        beta = []
        for bx, by, bz in zip(data["b_x_uT"], data["b_y_uT"], data["b_z_uT"], strict=True):
            norm = math.sqrt(bx * bx + by * by + bz * bz)
            beta.append(math.degrees(math.acos(max(-1.0, min(1.0, by / norm)))) if norm > 0 else math.nan)
        fig, ax = plt.subplots(figsize=(10, 3.8))
        ax.plot(tt, beta, lw=0.8, color="tab:purple", label="β = acos(B_y/|B|)")
        ax.set_ylabel("β (deg)")
        ax.set_ylim(-5, 185)
        finish(fig, [ax], "beta.png", "Angle β between body +Y and the geomagnetic field (truth)")

    wheels = sorted((c for c in data if c.startswith("h") and c.endswith("_Nms") and c[1:-4].isdigit()),
                    key=lambda c: int(c[1:-4]))
    if any(v != 0.0 for c in wheels for v in data[c]):  # wheels a law leaves idle draw no flat plot
        fig, ax = plt.subplots(figsize=(10, 4))
        for c, (_, colour) in zip(wheels, _AXES * 4, strict=False):
            ax.plot(tt, [1e3 * v for v in data[c]], lw=0.8, color=colour, label=f"wheel {c[1:-4]}")
        ax.set_ylabel("wheel momentum (mN·m·s)")
        finish(fig, [ax], "wheel_momentum.png", "Reaction wheel momenta (truth)")

    if all(f"qo{i}" in data for i in range(4)):
        fig, ax = plt.subplots(figsize=(10, 4))
        for i, colour in enumerate(("black", "tab:red", "tab:green", "tab:blue")):
            ax.plot(tt, data[f"qo{i}"], lw=0.8, color=colour, label=f"q{i}" + (" (scalar)" if i == 0 else ""))
        ax.set_ylabel("q_BO (scalar first)")
        ax.set_ylim(-1.05, 1.05)
        finish(fig, [ax], "quaternion_orbit.png", "Attitude relative to the orbit frame (truth)")
    return written
