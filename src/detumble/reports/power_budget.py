"""The power budget of a run: what the electrical system did, for ``summary.json`` and ``power.png``.

:class:`PowerBudget` is fed by the run report at every truth-trace sample (1 s by default) and
keeps the cumulative coil energy against time, so the energy the coils drew *during the detumble*
(between the downlinked DetumbleStarted and DetumbleCompleted events) is read off at those times
(linear interpolation between samples; within one sample interval of coil power).
"""

from __future__ import annotations

import bisect
import math
import pathlib

from detumble.reports.figures import read_truth, save_figure

__all__ = ["PowerBudget", "plot_power", "POWER_COLUMNS", "POWER_FORMATS"]

#: Columns the run report appends to ``truth.csv`` (``nan`` without an electrical system): the state at
#: the sample (``load_w``/``coil_w``: the electrical system's last 100 ms step), then the exact mean
#: load and coil power over the interval since the previous sample (the coils switch within it).
POWER_COLUMNS = ("soc", "bus_v", "solar_w", "load_w", "coil_w", "coil_j", "eclipse", "load_w_mean", "coil_w_mean")
#: How ``truth.csv`` writes each of :data:`POWER_COLUMNS` (format specs: :meth:`PowerBudget.sample` gives numbers)
POWER_FORMATS = (".6f", ".4f", ".4f", ".4f", ".4f", ".3f", None, ".4f", ".4f")


class PowerBudget:
    """Samples and summarises the spacecraft's :class:`~detumble.sim.power.ElectricalSystem`."""

    def __init__(self, spacecraft):
        self.spacecraft = spacecraft
        eps = spacecraft.power
        self.initial_soc = eps.battery.soc if eps is not None else None
        self.min_bus_v = math.inf
        self.times: list[float] = []
        self.coil_j: list[float] = []
        self._eclipse_samples = 0
        self._energy: tuple[float, float] | None = None  # (coil J, load J) at the previous sample
        self._energy_t_s = 0.0

    def sample(self, t_s: float) -> tuple:
        """One row of the power columns at run time ``t_s``: numbers, written with :data:`POWER_FORMATS`
        (the texts ``"nan"`` without an electrical system; the means ``""`` at the first sample)."""
        eps = self.spacecraft.power
        if eps is None:
            return ("nan",) * len(POWER_COLUMNS)
        self.times.append(t_s)
        self.coil_j.append(eps.coil_j)
        self.min_bus_v = min(self.min_bus_v, eps.bus_v)
        self._eclipse_samples += eps.eclipse
        coil_j, load_j = energy = self.spacecraft.energy_j()
        before, dt = self._energy, t_s - self._energy_t_s
        means = ("", "") if before is None or dt <= 0.0 else \
            ((load_j - before[1]) / dt, (coil_j - before[0]) / dt)  # none at the first sample
        self._energy, self._energy_t_s = energy, t_s
        return (eps.battery.soc, eps.bus_v, eps.solar_w, eps.load_w, eps.coil_w, eps.coil_j, int(eps.eclipse), *means)

    def coil_energy_at(self, t_s: float) -> float:
        """Cumulative coil energy (J) at run time ``t_s`` (interpolated between samples)."""
        ts = self.times
        k = bisect.bisect_left(ts, t_s)
        if k <= 0:
            return self.coil_j[0]
        if k >= len(ts):
            return self.coil_j[-1]
        t0, t1 = ts[k - 1], ts[k]
        return self.coil_j[k - 1] + (self.coil_j[k] - self.coil_j[k - 1]) * (t_s - t0) / (t1 - t0)

    def summary(self, detumble_started_s, detumble_complete_s) -> dict | None:
        eps = self.spacecraft.power
        if eps is None or not self.times:
            return None
        out = {
            "coil_energy_j": eps.coil_j,
            "load_energy_j": eps.load_j,
            "solar_energy_j": eps.solar_j,
            "battery_soc_initial": self.initial_soc,
            "battery_soc_final": eps.battery.soc,
            "min_bus_voltage_v": self.min_bus_v,
            "eclipse_fraction": self._eclipse_samples / len(self.times),
        }
        if detumble_started_s is not None:
            end = detumble_complete_s if detumble_complete_s is not None else self.times[-1]
            energy = self.coil_energy_at(end) - self.coil_energy_at(detumble_started_s)
            out["coil_energy_detumble_j"] = energy
            out["coil_energy_detumble_wh"] = energy / 3600.0
            out["detumble_complete"] = detumble_complete_s is not None
            if end > detumble_started_s:
                out["mean_coil_power_detumble_w"] = energy / (end - detumble_started_s)
        return out


def plot_power(truth_csv: pathlib.Path, out_dir: pathlib.Path, started_s=None, complete_s=None) -> list[pathlib.Path]:
    """``power.png``: battery state of charge and bus voltage; solar, load and coil power; eclipses."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = read_truth(truth_csv)
    t = data["t_s"]
    if len(t) < 2 or "soc" not in data or all(math.isnan(v) for v in data["soc"]):
        return []
    unit, scale = ("min", 60.0) if t[-1] > 3 * 3600 / 10 else ("s", 1.0)
    tt = [v / scale for v in t]
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(9, 6.5))
    ax1.plot(tt, [100 * v for v in data["soc"]], color="tab:green", lw=1.0, label="state of charge (%)")
    ax1.set_ylabel("state of charge (%)")
    ax1b = ax1.twinx()
    ax1b.plot(tt, data["bus_v"], color="tab:blue", lw=0.8, label="bus voltage (V)")
    ax1b.set_ylabel("bus voltage (V)")
    ax1.grid(alpha=0.3)
    ax1.legend(loc="upper left", fontsize=8)
    ax1b.legend(loc="upper right", fontsize=8)
    ax2.plot(tt, data["solar_w"], color="tab:orange", lw=0.8, label="solar array (W)")
    if "coil_w_mean" in data:  # exact means over each sample interval (the coils switch within it)
        ax2.plot(tt, data["load_w_mean"], color="black", lw=0.8, label="total load, interval mean (W)")
        ax2.plot(tt, data["coil_w_mean"], color="tab:red", lw=0.8, label="coils, interval mean (W)")
    else:  # an older run: the electrical system's 100 ms step before each sample
        ax2.plot(tt, data["load_w"], color="black", lw=0.8, label="total load (W)")
        ax2.plot(tt, data["coil_w"], color="tab:red", lw=0.8, label="coils (W)")
    for axis in (ax1, ax2):
        ecl = data["eclipse"]
        start = None
        for i, e in enumerate(ecl + [0.0]):
            if e and start is None:
                start = i
            elif not e and start is not None:
                axis.axvspan(tt[start], tt[min(i, len(tt) - 1)], color="grey", alpha=0.15, lw=0)
                start = None
        for mark, style in ((started_s, "--"), (complete_s, ":")):
            if mark is not None:
                axis.axvline(mark / scale, color="tab:purple", ls=style, lw=1.0)
    ax2.set_ylabel("power (W)")
    ax2.set_xlabel(f"time ({unit}); grey: eclipse; purple: detumble start / complete")
    ax2.grid(alpha=0.3)
    ax2.legend(loc="upper right", fontsize=8)
    fig.suptitle("Power budget")
    fig.tight_layout()
    written = [save_figure(fig, out_dir / "power.png")]
    plt.close(fig)
    return written
