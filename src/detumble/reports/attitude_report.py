"""AttitudeRunReport: the attitude controller's figures of one run (a topology resource).

It sits beside :class:`~detumble.reports.detumble_report.DetumbleRunReport` (which owns the truth trace
and ``truth.csv``): this report samples the truth on a scheduler time listener of its own, follows
the downlinked ``ControlModeChanged`` events, and adds to ``summary.json``:

* ``control_mode_transitions``: ``[{"t_s", "mode"}]`` as the ground received them;
* ``pointing_error_deg``: ``{"median", "p95", "max", "samples"}`` of the true angle between the
  body attitude and the target's reference at the sample's time (a moving target's from the plant's own
  ephemeris), over the **steady** POINTING samples — those after each acquisition
  (:mod:`detumble.analysis.pointing_windows`: ``acquisition_s`` of the first interval and its
  ``acquisition_threshold_deg`` are in the block, ``window`` says "steady") — and beside them what pooling runs
  needs (:mod:`detumble.analysis.pooled_stats`): ``sample_interval_s``, ``window_s`` (samples × interval),
  ``time_above_s`` at 0.01, 0.05, 0.1, 1, 5, 15° and ``histogram_s``;
* ``pointing_intervals``: each POINTING interval (entry, target change, a station rising or setting) with its
  active reference, threshold and ``acquisition_s``; ``pointing_error_by_target_deg``: the steady statistics
  per active reference (INERTIAL, NADIR, GROUND_STATION, STATION_FALLBACK, SUN);
* ``spin_axis_error_deg``: the same statistics of the angle between the total angular momentum
  (body + wheels) and body +Z over the SPIN_STABLE samples (after their first 10 %; ``time_above_s`` at
  1, 5, 15°);
* ``spin_settled_s``: seconds from entering SPIN_STABLE until the momentum stays within 5° of +Z
  and the rate about +Z within 5 % of its target (the issue's spin target) for the rest of that first
  SPIN_STABLE interval, or None; ``spin_settled_dwell_s``: how long it then stayed settled (to the
  interval's last sample: the mode's end or the run's), or None;
* ``slews``: for each target change while POINTING, its angle and the time until the true error
  stays below 0.1°;
* ``wheel_momentum_max_fraction``: the largest ``|h_i| / h_max`` seen, and the same over the last
  orbit-long window (``wheel_momentum_max_fraction_last_orbit``).

``progress()`` (the progress bar's figures, and what ``--stop-when`` conditions test) gives ``mode``,
``pointing_error_deg`` and ``spin_settled_for_s``: how long the spin has been inside that band without a
break in the present SPIN_STABLE interval (0 outside it).

Plots (:func:`plot_attitude_csv`, from ``attitude.csv`` alone, so ``fprime-lite plot`` draws them again):
``attitude_mode.png`` (mode vs time), ``pointing_error.png``, ``wheel_momentum.png``,
``dipole_commanded.png``; the samples go to ``attitude.csv``, the achieved dipole as its exact mean over
each sample interval (``mx_mean_Am2``…), its ``target`` column the active reference, as
``pointing_error_by_target_deg`` names it. Time ``t_s`` is seconds since the run started.
"""

from __future__ import annotations

import csv
from typing import Any
import math
import os
import pathlib

from fprime_lite.deploy.resources import topology_resource
from fprime_lite.model.time import US_PER_S

from detumble.analysis.pointing_windows import pointing_summary
from detumble.analysis.pooled_stats import SPIN_THRESHOLDS_DEG, error_statistics
from detumble.components.attitude_types import ControlMode
from detumble.control.quaternion import quat_angle, quat_error
from detumble.control.targets import LABELS, true_reference_q
from detumble.drivers.spacecraft import SimulatedSpacecraft
from detumble.reports.csv_rows import FastCsvWriter
from detumble.reports.figures import save_figure

__all__ = ["AttitudeRunReport", "error_statistics", "settle_time", "plot_attitude_csv", "read_attitude_csv"]

ORBIT_S = 5578.0
#: The issue's stable spin: total momentum within this angle of body +Z …
SPIN_AXIS_BAND_DEG = 5.0
#: … and the body rate about +Z within this fraction of SPIN_RATE_TARGET.
SPIN_RATE_BAND = 0.05
_COLUMNS = ("t_s", "mode", "pointing_error_deg", "spin_axis_error_deg", "spin_rate_deg_s", "rate_deg_s",
            "h0_nms", "h1_nms", "h2_nms", "h3_nms", "mx_cmd_Am2", "my_cmd_Am2", "mz_cmd_Am2",
            "mx_mean_Am2", "my_mean_Am2", "mz_mean_Am2", "target")


def settle_time(times: list[float], ok: list[bool], start: float) -> float | None:
    """Seconds from ``start`` to the first sample after which ``ok`` holds to the end (None if never)."""
    last_bad = None
    for t, good in zip(times, ok, strict=True):
        if t >= start and not good:
            last_bad = t
    after = [t for t in times if t >= start and (last_bad is None or t > last_bad)]
    if not after:
        return None
    return after[0] - start


@topology_resource
class AttitudeRunReport:
    """Follows one run of an attitude-control deployment.

    Args:
        spacecraft: the simulated spacecraft (``$spacecraft``).
        controller: the qualified name of the AttitudeController instance.
        sample_interval_s: how often the truth is sampled, simulated seconds.
    """

    def __init__(self, spacecraft: SimulatedSpacecraft, *,
                 controller: str = "ReferenceDeployment.attitudeController", sample_interval_s: float = 0.5):
        if not sample_interval_s > 0:
            raise ValueError(f"sample_interval_s must be positive, got {sample_interval_s}")
        self.spacecraft = spacecraft
        self.controller_name = controller
        self.interval_us = max(1, round(sample_interval_s * US_PER_S))
        self.controller: Any = None  # the AttitudeController instance, found by name at begin()
        self.start_us = 0
        self._next_us = 0
        self.rows: list[tuple] = []
        self.transitions: list[dict] = []
        self._target_changes: list[tuple[float, float]] = []  # (t_s, angle deg) while POINTING
        self._last_target = None  # the controller's reference attitude at the last sample
        self._last_key: tuple | None = None  # (target commanded, active reference label) at the last sample
        self._logged_target: tuple | None = None  # the true reference last handed to the spacecraft's truth log
        self._row_meta: list[tuple] = []  # per row: (target key, POINTING on the wheels)
        self._spin_since: float | None = None  # start of the present in-band SPIN_STABLE streak, s

    # --- run hooks -------------------------------------------------------------------------------

    def begin(self, deployment, out_dir: pathlib.Path) -> None:
        self.controller = deployment.topology.instance(self.controller_name).component
        self.start_us = deployment.scheduler.now_us
        self._next_us = self.start_us + self.interval_us
        deployment.scheduler.add_time_listener(self._on_time)
        plant = self.spacecraft.plant
        self._drive_before = plant.drive_integrals.totals(plant.t_ns)
        self._sample(self.start_us)

    def _on_time(self, time_us: int) -> None:
        while time_us >= self._next_us:
            self._sample(self._next_us)
            self._next_us += self.interval_us

    def _sample(self, time_us: int) -> None:
        c = self.controller
        p = self.spacecraft.plant
        t = (time_us - self.start_us) / US_PER_S
        mode = c.mode
        q = p.q_BN
        law = c.law
        ref = law.reference
        label = ref.label if ref is not None else None
        key = (law.target_spec, label)  # a new target, or a station rising or setting: a target change
        target = c.target
        if key != self._last_key:
            if self._last_target is not None and target is not None and mode == ControlMode.POINTING:
                self._target_changes.append((t, math.degrees(quat_angle(quat_error(target, self._last_target)))))
            self._last_key = key
        self._last_target = target
        # the true reference now, from the plant's own ephemeris (the controller's is a cycle old)
        target = true_reference_q(law.target_spec, p.ephemeris, target)
        if target != self._logged_target:
            self._logged_target = target
            self.spacecraft.set_pointing_target(target)
        err = math.degrees(quat_angle(quat_error(target, q))) if target is not None else float("nan")
        h = p.angular_momentum_B()
        if p.wheel_count:
            hw = p.wheel_momentum_B
            h = (h[0] + hw[0], h[1] + hw[1], h[2] + hw[2])
        hn = math.sqrt(h[0] ** 2 + h[1] ** 2 + h[2] ** 2)
        spin_err = math.degrees(math.atan2(math.hypot(h[0], h[1]), h[2])) if hn > 0 else float("nan")
        w = p.omega_BN_B
        momenta = list(p.wheel_momenta)[:4]
        momenta += [0.0] * (4 - len(momenta))
        self._row_meta.append((key, law.pointing_on_wheels if mode == ControlMode.POINTING else False))
        drive = p.drive_integrals
        now = drive.totals(p.t_ns)
        # the achieved dipole's exact mean since the previous sample: the coils switch within each
        # 20 ms cycle, so the dipole at the sample instant is aliased (always off at a cycle's end)
        m_mean = drive.interval_means(self._drive_before, now).m_B if now.t_ns > self._drive_before.t_ns \
            else (math.nan, math.nan, math.nan)
        self._drive_before = now
        self.rows.append((t, int(mode), err, spin_err, math.degrees(w[2]), p.rate_deg_s, *momenta,
                          *c.dipole, *m_mean, LABELS[label] if label is not None else ""))
        if mode == ControlMode.SPIN_STABLE and self._in_band(spin_err, math.degrees(w[2])):
            if self._spin_since is None:
                self._spin_since = t
        else:
            self._spin_since = None

    def _in_band(self, axis_err_deg: float, rate_z_deg_s: float) -> bool:
        target = self.controller.SPIN_RATE_TARGET.value
        return axis_err_deg <= SPIN_AXIS_BAND_DEG and abs(rate_z_deg_s - target) <= SPIN_RATE_BAND * abs(target)

    def on_event(self, event) -> None:
        """A downlinked event: ControlModeChanged(from, to, reason) becomes a transition."""
        if event.name.endswith(".ControlModeChanged"):
            t = event.time.total_us / US_PER_S - (self.spacecraft.clock.epoch_us + self.start_us) / US_PER_S
            to_mode = event.args[1]
            name = to_mode.name if hasattr(to_mode, "name") else str(to_mode)
            self.transitions.append({"t_s": round(t, 6), "mode": name})

    #: What :meth:`progress` may publish (``--stop-when`` / a campaign's ``stop_when`` keys are checked against it).
    progress_keys = ("mode", "pointing_error_deg", "spin_settled_for_s")

    def progress(self) -> dict:
        c = self.controller
        if c is None:
            return {}
        out = {"mode": c.mode.name}
        if self.rows and math.isfinite(self.rows[-1][2]):
            out["pointing_error_deg"] = self.rows[-1][2]
        if self.rows:
            out["spin_settled_for_s"] = self.rows[-1][0] - self._spin_since if self._spin_since is not None else 0.0
        return out

    # --- figures ---------------------------------------------------------------------------------

    def _column(self, k: int, mode: ControlMode) -> list[float]:
        return [r[k] for r in self.rows if r[1] == mode and math.isfinite(r[k])]

    def pointing_samples(self) -> list[tuple]:
        """``(t_s, true error deg, target key, reference label, on wheels)`` of the POINTING samples (the input of
        :func:`detumble.analysis.pointing_windows.pointing_windows`)."""
        return [(r[0], r[2], m[0], r[-1], m[1]) for r, m in zip(self.rows, self._row_meta, strict=True)
                if r[1] == ControlMode.POINTING and math.isfinite(r[2])]

    def spin_settled_s(self) -> float | None:
        """Seconds from the first entry into SPIN_STABLE until momentum within 5° of +Z and the rate within
        5 % of SPIN_RATE_TARGET hold for the rest of that SPIN_STABLE interval."""
        return self._spin_settling()[0]

    def _spin_settling(self) -> tuple[float | None, float | None]:
        """``(settled_s, dwell_s)`` of the first SPIN_STABLE interval (None, None when it never settled)."""
        first = next((i for i, r in enumerate(self.rows) if r[1] == ControlMode.SPIN_STABLE), None)
        if first is None:
            return None, None
        start = self.rows[first][0]
        interval = []
        for r in self.rows[first:]:
            if r[1] != ControlMode.SPIN_STABLE:
                break
            interval.append(r)
        ok = [self._in_band(r[3], r[4]) for r in interval]
        settled = settle_time([r[0] for r in interval], ok, start)
        if settled is None:
            return None, None
        return settled, interval[-1][0] - (start + settled)

    def slews(self) -> list[dict]:
        out = []
        for i, (t0, angle) in enumerate(self._target_changes):
            t_end = self._target_changes[i + 1][0] if i + 1 < len(self._target_changes) else float("inf")
            sel = [(r[0], r[2] < 0.1) for r in self.rows if t0 <= r[0] < t_end and r[1] == ControlMode.POINTING]
            settle = settle_time([s[0] for s in sel], [s[1] for s in sel], t0) if sel else None
            out.append({"t_s": t0, "angle_deg": angle, "settle_below_0p1_deg_s": settle})
        return out

    def wheel_fraction(self, last_s: float | None = None) -> float | None:
        p = self.spacecraft.plant
        n = p.wheel_count
        if not n:
            return None
        limits = [self.spacecraft.wheel_limits(i)[1] for i in range(n)]
        t_end = self.rows[-1][0] if self.rows else 0.0
        rows = self.rows if last_s is None else [r for r in self.rows if r[0] >= t_end - last_s]
        return max((abs(r[6 + i]) / limits[i] for r in rows for i in range(n)), default=0.0)

    def summary(self) -> dict:
        settled, dwell = self._spin_settling()
        dt = self.interval_us / US_PER_S  # every sample stands for one interval of time
        return {
            "control_mode_transitions": self.transitions,
            **pointing_summary(self.pointing_samples(), dt),
            "spin_axis_error_deg": error_statistics(self._column(3, ControlMode.SPIN_STABLE), sample_interval_s=dt,
                                                    thresholds_deg=SPIN_THRESHOLDS_DEG),
            "spin_settled_s": settled,
            "spin_settled_dwell_s": dwell,
            "slews": self.slews(),
            "wheel_momentum_max_fraction": self.wheel_fraction(),
            "wheel_momentum_max_fraction_last_orbit": self.wheel_fraction(ORBIT_S),
            "wheel_momentum_capacity_nms": [self.spacecraft.wheel_limits(i)[1]
                                            for i in range(self.spacecraft.plant.wheel_count)],
            "final_mode": self.controller.mode.name if self.controller is not None else None,
        }

    def finish(self, out_dir: pathlib.Path, *, plots: bool = True) -> list[pathlib.Path]:
        out_dir = pathlib.Path(out_dir)
        path = out_dir / "attitude.csv"
        tmp = path.with_name(".attitude.csv.part")
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            w = FastCsvWriter(f)  # the bytes csv.writer writes
            w.writerow(_COLUMNS)
            for r in self.rows:
                w.writerow([ControlMode(r[1]).name if i == 1 else r[i] for i in range(len(r))])
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
        written = [path]
        if plots and self.rows:
            n = self.spacecraft.plant.wheel_count
            written += plot_attitude_csv(path, out_dir, [self.spacecraft.wheel_limits(i)[1] for i in range(n)])
        return written


def read_attitude_csv(path: pathlib.Path, max_rows: int = 6000) -> list[tuple]:
    """The rows of ``attitude.csv`` as the report keeps them (the mode as its value), every k-th row
    so at most about ``max_rows`` remain."""
    with open(path, encoding="utf-8", newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        # the mode by name, the target label as written (runs before issue 27 have none), numbers
        text = {k for k, name in enumerate(header) if name == "target"}
        rows = [tuple(ControlMode[v].value if k == 1 else v if k in text else float(v) if v else math.nan
                      for k, v in enumerate(r)) for r in reader]
    if tuple(header[:10]) != _COLUMNS[:10]:
        raise ValueError(f"{path}: not an attitude.csv (columns {header[:10]})")
    return rows[::max(1, len(rows) // max_rows)]


def plot_attitude_csv(path: pathlib.Path, out_dir: pathlib.Path, wheel_capacity_nms: list[float]) -> list[pathlib.Path]:
    """Draw the attitude report's plots from its ``attitude.csv`` (a run's, or ``fprime-lite plot``'s):
    ``attitude_mode.png``, ``pointing_error.png``, ``wheel_momentum.png`` (one line per wheel of
    ``wheel_capacity_nms``, N·m·s, with 50 % of the first wheel's capacity dashed) and
    ``dipole_commanded.png``. Returns the files written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = read_attitude_csv(path)
    if len(rows) < 2:
        return []
    t = [r[0] for r in rows]
    unit, scale = ("min", 60.0) if t[-1] > 1800 else ("s", 1.0)
    tt = [v / scale for v in t]
    written = []

    fig, ax = plt.subplots(figsize=(9, 3))
    ax.step(tt, [r[1] for r in rows], where="post", color="tab:purple")
    ax.set_yticks([m.value for m in ControlMode], [m.name for m in ControlMode])
    ax.set_xlabel(f"time ({unit})")
    ax.set_title("Attitude control mode")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    written.append(save_figure(fig, out_dir / "attitude_mode.png"))
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 4))
    pe = [(a, r[2]) for a, r in zip(tt, rows, strict=True) if r[1] == ControlMode.POINTING and r[2] > 0]
    if pe:
        ax.semilogy([p[0] for p in pe], [p[1] for p in pe], ".", ms=1.5, label="pointing error (POINTING)")
    se = [(a, r[3]) for a, r in zip(tt, rows, strict=True) if r[1] == ControlMode.SPIN_STABLE and r[3] > 0]
    if se:
        ax.semilogy([p[0] for p in se], [p[1] for p in se], ".", ms=1.5, label="momentum to +Z (SPIN_STABLE)")
    ax.axhline(0.1, color="tab:red", ls=":", lw=1, label="0.1°")
    ax.set_ylabel("angle (deg)")
    ax.set_xlabel(f"time ({unit})")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    ax.set_title("True pointing error and spin-axis error")
    fig.tight_layout()
    written.append(save_figure(fig, out_dir / "pointing_error.png"))
    plt.close(fig)

    if wheel_capacity_nms:
        fig, ax = plt.subplots(figsize=(9, 4))
        for i in range(len(wheel_capacity_nms)):
            ax.plot(tt, [r[6 + i] * 1e3 for r in rows], lw=0.8, label=f"wheel {i}")
        for s in (1, -1):
            ax.axhline(s * 0.5 * wheel_capacity_nms[0] * 1e3, color="grey", ls="--", lw=0.8)
        ax.set_ylabel("wheel momentum (mN·m·s)")
        ax.set_xlabel(f"time ({unit}); dashed: 50 % of capacity")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        written.append(save_figure(fig, out_dir / "wheel_momentum.png"))
        plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 4))
    for k, name in enumerate("xyz"):
        ax.plot(tt, [r[10 + k] for r in rows], lw=0.7, label=f"m_{name} commanded")
    ax.set_ylabel("dipole (A·m²)")
    ax.set_xlabel(f"time ({unit})")
    ax.legend(fontsize=8, ncol=3)
    ax.grid(alpha=0.3)
    ax.set_title("Commanded dipole (coils on 80 % of each control cycle; dipole.png: what they gave)")
    fig.tight_layout()
    written.append(save_figure(fig, out_dir / "dipole_commanded.png"))
    plt.close(fig)
    return written
