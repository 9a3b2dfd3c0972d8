"""The detumble deployments' run report, a topology *resource* (see ``docs/topology.md``).

:class:`DetumbleRunReport` watches a run: it streams the truth trace to ``truth.csv``, follows the
downlinked DetumbleStarted / DetumbleCompleted events, reports progress, adds the detumble figures
to ``summary.json`` and draws the plots. The spacecraft it watches is the ``simulation`` resource,
:func:`detumble.drivers.spacecraft.make_spacecraft`.
"""

from __future__ import annotations

from typing import Any

import math
import pathlib

from fprime_lite.deploy.resources import topology_resource
from fprime_lite.model.time import US_PER_S
from fprime_lite.ground.writer_process import open_row_stream
from fprime_lite.osal.atomic import clean_temporary_files

from detumble.control.coil_layout import COIL_FACES
from detumble.sim.truth import adcs_header, adcs_row
from detumble.reports.csv_rows import formatted_csv_writer
from detumble.reports.power_budget import POWER_COLUMNS as _POWER_COLUMNS, POWER_FORMATS, PowerBudget, plot_power
from detumble.drivers.spacecraft import SimulatedSpacecraft, TruthSample
from detumble.components.types import DetumbleState

__all__ = ["DetumbleRunReport", "MEAN_DIPOLE_COLUMNS"]

#: ``truth.csv``'s column suffix of each coil face (``level_mean_xp``, ``on_zm`` …)
_FACE_SUFFIX = {0: "xp", 1: "xm", 2: "yp", 3: "ym", 5: "zm"}
#: the achieved coil dipole's mean over each sample interval, A·m² in B
MEAN_DIPOLE_COLUMNS = _MEAN_DIPOLE_COLUMNS = ("m_mean_x_Am2", "m_mean_y_Am2", "m_mean_z_Am2")
_STATES = tuple(DetumbleState)



@topology_resource(role="report")
class DetumbleRunReport:
    """Follows one run of a detumble deployment and writes its detumble-specific outputs.

    Args:
        spacecraft: the simulated spacecraft (``$spacecraft``).
        manager: the qualified name of the DetumbleManager instance, or None for a deployment whose
            manager does not fly (``adcs_ref``): ``truth.csv`` then has no ``frac_*``/``strategy``
            columns and no ``state.png`` is drawn.
        truth_interval_s: how often the truth trace is sampled (simulated seconds).
    """

    def __init__(self, spacecraft: SimulatedSpacecraft, *, manager: str | None = "ReferenceDeployment.detumbleManager",
                 truth_interval_s: float = 1.0):
        if not truth_interval_s > 0:
            raise ValueError(f"truth_interval_s must be positive, got {truth_interval_s}")
        self.spacecraft = spacecraft
        self.manager_name = manager
        self.truth_interval_us = max(1, round(truth_interval_s * US_PER_S))
        self.manager: Any = None  # the flight manager instance, found by name at begin()
        self.start_us = 0
        self.initial_rate_deg_s = spacecraft.truth().rate_deg_s
        self.last: TruthSample | None = None
        self.detumble_started_s: float | None = None
        self.detumble_complete_s: float | None = None
        self.time_below_1_deg_s: float | None = None
        self.samples = 0
        self._writer: Any = None  # truth.csv's row stream (open_row_stream), begin() to finish()
        self._path: pathlib.Path | None = None
        self.power = PowerBudget(spacecraft)

    # --- run hooks (called by ``fprime-lite run``) ------------------------------------------------

    def begin(self, deployment, out_dir: pathlib.Path) -> None:
        self.manager = None if self.manager_name is None else deployment.topology.instance(self.manager_name).component
        states = tuple(DetumbleState) if self.manager is not None else ()
        self.start_us = deployment.scheduler.now_us
        self._path = pathlib.Path(out_dir) / "truth.csv"
        clean_temporary_files(self._path.parent)  # what a killed run left (a live run's are kept)
        adcs = adcs_header(self.spacecraft.plant, with_field=False)
        # the numbers written with a fixed number of decimals go over as numbers: the row's writer (the
        # run's writer process when it has one) formats them
        formats = (".6f", *(None,) * 7, *(".3f",) * len(COIL_FACES), *(".4f",) * len(COIL_FACES),
                   *(".4f",) * len(states), *([None] if states else []), *(None,) * (len(adcs) + 3), *POWER_FORMATS)
        # streamed under a temporary name, by the run's writer process when it has one
        self._writer = open_row_stream(deployment, self._path, formatted_csv_writer(formats))
        self._writer.writerow(["t_s", "wx_deg_s", "wy_deg_s", "wz_deg_s", "rate_deg_s", "bx_uT", "by_uT",
                               "bz_uT", *(f"level_mean_{_FACE_SUFFIX[f]}" for f in COIL_FACES),
                               *(f"on_{_FACE_SUFFIX[f]}" for f in COIL_FACES),
                               *(f"frac_{st.name.lower()}" for st in states), *(["strategy"] if states else []),
                               *adcs, *_MEAN_DIPOLE_COLUMNS, *_POWER_COLUMNS])
        plant = self.spacecraft.plant
        self._drive_before = plant.drive_integrals.totals(plant.t_ns)
        self._state_us = {s: 0 for s in DetumbleState}
        self._progress_us = {s: 0 for s in DetumbleState}
        self._state_since = self._last_us = deployment.scheduler.now_us
        self._state: DetumbleState | None = None  # the manager's state at the last event
        if self.manager is not None:
            deployment.scheduler.add_time_listener(self._on_time)
        self.spacecraft.set_trace(self._sample, self.truth_interval_us)

    def _on_time(self, time_us: int) -> None:
        """The time since the last event was spent in the state the manager is in now (exact
        fractions); credited when the state changes or the shares are read (:meth:`_settle`), so an
        event that finds the state unchanged only moves the end of the span."""
        state = self.manager.state
        if state is not self._state:
            self._settle()
            self._state = state
        self._last_us = time_us

    def take_state_us(self) -> dict[DetumbleState, int]:
        """Microseconds spent in each state since the previous call (up to the last event); resets the count."""
        self._settle()
        state_us = self._state_us
        self._state_us = dict.fromkeys(_STATES, 0)
        return state_us

    def _settle(self) -> None:
        """Credit the span not yet credited (up to the last event) to its state."""
        state = self._state
        if state is not None:
            self._state_us[state] += self._last_us - self._state_since
            self._progress_us[state] += self._last_us - self._state_since
        self._state_since = self._last_us

    def _sample(self, s: TruthSample) -> None:
        writer = self._writer
        assert writer is not None  # begin() made it
        self.last = s
        self.samples += 1
        t = s.t_s - self.start_us / US_PER_S
        if self.time_below_1_deg_s is None and s.rate_deg_s < 1.0:
            self.time_below_1_deg_s = t
        w = s.omega_BN_B
        plant = self.spacecraft.plant
        drive = plant.drive_integrals
        now = drive.totals(plant.t_ns)
        if now.t_ns > self._drive_before.t_ns:  # the means over the interval since the previous sample
            means = drive.interval_means(self._drive_before, now)
            level, on = means.level, means.on
            switched: list = [level.get(f, 0.0) for f in COIL_FACES] + [on.get(f, 0.0) for f in COIL_FACES]
            dipole: list = list(means.m_B)
        else:  # the first sample closes no interval
            switched, dipole = [""] * (2 * len(COIL_FACES)), [""] * 3
        self._drive_before = now
        manager_columns: list = []
        if self.manager is not None:
            strategy = getattr(self.manager, "strategy", None)
            state_us = self.take_state_us()
            total = sum(state_us.values())
            manager_columns = [state_us[st] / total if total else 0.0 for st in _STATES]
            manager_columns.append(strategy.name if strategy is not None else "")
        writer.writerow([t, math.degrees(w[0]), math.degrees(w[1]), math.degrees(w[2]),
                               s.rate_deg_s, s.b_B[0] * 1e6, s.b_B[1] * 1e6, s.b_B[2] * 1e6, *switched,
                               *manager_columns,
                               *adcs_row(plant, with_field=False, sample=s), *dipole, *self.power.sample(t)])

    def on_event(self, event) -> None:
        """A downlinked event (``fprime_lite.ground.downlink.DecodedEvent``)."""
        t = event.time.total_us / US_PER_S - (self.spacecraft.clock.epoch_us + self.start_us) / US_PER_S
        if event.name.endswith(".DetumbleStarted") and self.detumble_started_s is None:
            self.detumble_started_s = t
        elif event.name.endswith(".DetumbleCompleted") and self.detumble_started_s is not None \
                and self.detumble_complete_s is None:
            self.detumble_complete_s = t

    #: What :meth:`progress` may publish (``--stop-when`` / a campaign's ``stop_when`` keys are checked against it).
    progress_keys = ("rate_deg_s", "state")

    def progress(self) -> dict:
        """The body rate now, and how the time since the previous call was shared among the
        manager's states (the states taking 5 % or more, largest first: ``ACTUATING_BDOT 68%``)."""
        truth = self.spacecraft.truth()
        return {"rate_deg_s": truth.rate_deg_s, "state": self._state_shares()}

    def state_shares(self) -> dict[str, float]:
        """Share of the simulated time since the previous call spent in each state (sums to 1);
        resets the count."""
        shares = getattr(self, "_progress_us", None)
        if not shares:
            return {}
        if self.manager is not None:
            self._settle()
        total = sum(shares.values())
        out = {st.name: us / total for st, us in shares.items()} if total else {}
        self._progress_us = dict.fromkeys(_STATES, 0)
        return out

    def _state_shares(self) -> str:
        shares = self.state_shares()
        if not shares:
            return self.manager.state.name if self.manager is not None else ""
        ranked = sorted(((v, k) for k, v in shares.items() if v >= 0.05), reverse=True)
        return " ".join(f"{name} {share:.0%}" for share, name in ranked)

    def summary(self) -> dict:
        final = self.spacecraft.truth()
        power = self.power.summary(self.detumble_started_s, self.detumble_complete_s)
        return {
            "initial_rate_deg_s": self.initial_rate_deg_s,
            "final_rate_deg_s": final.rate_deg_s if math.isfinite(final.rate_deg_s) else None,  # None: diverged
            "detumble_started_s": self.detumble_started_s,
            "detumble_complete_s": self.detumble_complete_s,
            "time_below_1_deg_s": self.time_below_1_deg_s,
            "scenario": self.spacecraft.scenario.name,
            "physics_steps": self.spacecraft.steps_taken,
            **({"power": power} if power else {}),
            "flight_software_resets": self.spacecraft.resets,
        }

    def finish(self, out_dir: pathlib.Path, *, plots: bool = True) -> list[pathlib.Path]:
        """Close the truth log; draw the plots; return the files written."""
        self.spacecraft.set_trace(None)
        if self._writer is not None:  # begin() opened it
            self._writer.close()  # truth.csv renamed into place (before the plots read it)
            self._writer = None
        written = [self._path] if self._path is not None else []
        if plots and self._path is not None:
            from detumble.reports.plots import plot_truth

            thresholds: dict[str, float] = {name: getattr(self.manager, name).value for name in
                          ("DEADBAND_UPPER_THRESHOLD", "DEADBAND_LOWER_THRESHOLD")} if self.manager else {}
            written += plot_truth(self._path, pathlib.Path(out_dir), thresholds=thresholds,
                                  marks={"detumble started": self.detumble_started_s,
                                         "detumble completed": self.detumble_complete_s})
            if self.spacecraft.power is not None:
                written += plot_power(self._path, pathlib.Path(out_dir), self.detumble_started_s,
                                      self.detumble_complete_s)
        return written
