"""The run report of the coursework deployment: truth log and seed 004's settling figures.

A topology resource (role ``report``) beside the spacecraft. It samples the truth at the control
period (``metrics_interval_s``, default the coursework's 0.01 s) and feeds the same on-line
settling trackers the plant-only runner uses (:class:`detumble.sim.settling_metrics.SettlingMetrics`),
so ``summary.json`` carries the same ``settling_time_2pct_s``, ``settling_time_2pct_axes_s`` and
``time_below_threshold_s`` as ``fprime-lite sim``; every ``truth_interval_s`` a row goes to
``truth.csv`` (ω in deg/s and the ADCS columns of :mod:`detumble.sim.truth`). When the run ends it
draws seed 004's time histories from ``truth.csv`` (:mod:`detumble.reports.history_plots`).
"""
from __future__ import annotations

from typing import Any
import math
import pathlib

from fprime_lite.deploy.resources import topology_resource
from fprime_lite.ground.writer_process import open_row_stream
from fprime_lite.model.time import US_PER_S

from detumble.sim.settling_metrics import SettlingMetrics
from detumble.sim.truth import adcs_header, adcs_row
from detumble.reports.csv_rows import FastCsvWriter
from detumble.drivers.spacecraft import SimulatedSpacecraft, TruthSample

__all__ = ["CourseworkRunReport"]


def _finite(x: float) -> float | None:
    """``x``, or None when the plant diverged (summary.json is strict JSON)."""
    return x if math.isfinite(x) else None



@topology_resource(role="report")
class CourseworkRunReport:
    """Args: the spacecraft (``$spacecraft``), whether the wheel law flies (its attitude channel
    counts in the overall settling time), the truth-log and metric intervals (simulated s)."""

    def __init__(self, spacecraft: SimulatedSpacecraft, *, wheel_law: bool = False, truth_interval_s: float = 1.0,
                 metrics_interval_s: float = 0.01):
        for name, value in (("truth_interval_s", truth_interval_s), ("metrics_interval_s", metrics_interval_s)):
            if not value > 0:
                raise ValueError(f"{name} must be positive, got {value}")
        self.spacecraft = spacecraft
        self.wheel_law = wheel_law
        self.metrics_us = max(1, round(metrics_interval_s * US_PER_S))
        self.rows_every = max(1, round(truth_interval_s / metrics_interval_s))
        self.initial_rate_deg_s = spacecraft.truth().rate_deg_s
        self.metrics: SettlingMetrics | None = None
        self._count = 0
        self._path: pathlib.Path | None = None
        self._writer: Any = None  # truth.csv's row stream (open_row_stream), begin() to finish()

    def begin(self, deployment, out_dir: pathlib.Path) -> None:
        plant = self.spacecraft.plant
        self.start_us = deployment.scheduler.now_us
        self.metrics = SettlingMetrics(plant, omega_final=(0.0, -plant.orbit.mean_motion, 0.0),
                                       include_attitude=self.wheel_law)
        self._path = pathlib.Path(out_dir) / "truth.csv"
        # streamed under a temporary name, by the run's writer process when it has one
        self._writer = open_row_stream(deployment, self._path, FastCsvWriter)
        self._writer.writerow(["t_s", "wx_deg_s", "wy_deg_s", "wz_deg_s", "rate_deg_s",
                               *adcs_header(plant, with_field=True)])
        self.spacecraft.set_trace(self._sample, self.metrics_us)

    def _sample(self, s: TruthSample) -> None:
        assert self.metrics is not None and self._writer is not None
        self.metrics.update(self.spacecraft.plant, s.q_BO)  # s: the plant's state now (its q_BO taken once)
        if self._count % self.rows_every == 0:
            w = s.omega_BN_B
            t = s.t_s - self.start_us / US_PER_S
            self._writer.writerow([f"{t:.6f}", math.degrees(w[0]), math.degrees(w[1]), math.degrees(w[2]),
                                   s.rate_deg_s, *adcs_row(self.spacecraft.plant, with_field=True, sample=s)])
        self._count += 1

    def on_event(self, event) -> None:
        pass

    #: What :meth:`progress` may publish (``--stop-when`` / a campaign's ``stop_when`` keys are checked against it).
    progress_keys = ("rate_deg_s", "state")

    def progress(self) -> dict:
        return {"rate_deg_s": self.spacecraft.truth().rate_deg_s, "state": ""}

    def summary(self) -> dict:
        out = {"initial_rate_deg_s": self.initial_rate_deg_s,
               "final_rate_deg_s": _finite(self.spacecraft.truth().rate_deg_s),
               "scenario": self.spacecraft.scenario.name, "physics_steps": self.spacecraft.steps_taken}
        if self.metrics is not None:
            out.update(self.metrics.summary())
        return out

    def finish(self, out_dir: pathlib.Path, *, plots: bool = True) -> list[pathlib.Path]:
        self.spacecraft.set_trace(None)
        if self._writer is None or self._path is None:
            return []
        self._writer.close()  # truth.csv renamed into place (before the plots read it)
        self._writer = None
        written = [self._path]
        if plots:
            from detumble.reports.history_plots import plot_time_histories

            written += plot_time_histories(self._path, pathlib.Path(out_dir))
        return written
