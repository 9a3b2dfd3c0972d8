"""The detumble application's campaign plug-ins: the ``plant`` run kind and the detumble metrics.

Reached by ``fprime-lite campaign`` through the ``fprime_lite.campaign_runs`` and
``fprime_lite.campaign_metrics`` entry points (pyproject.toml); the engine never imports detumble.

``plant`` run section::

    run: {kind: plant, scenario: case_a, law: kopt, gain: null, duration_s: 600}

Varied keys: ``law``, ``gain``, ``duration_s``, ``scenario`` and ``scenario.KEY.PATH`` (any
scenario value, as ``--set``). The run's seed is the scenario seed (sensor noise, random axes).
"""

from __future__ import annotations

import csv
import math
import pathlib

from fprime_lite.tools.campaign import Metric, MetricUnavailable, Prepared, RunKind, RunOutput, RunRequest
from fprime_lite.tools.campaign.errors import RunSetupError

__all__ = ["PLANT_RUN", "METRICS", "CoilEnergyMeter"]

DETUMBLED_DEG_S = 1.0
SETTLING_BAND = 0.02


# --- the plant run kind -------------------------------------------------------------------------

def _check_key(key: str) -> str | None:
    if key in ("law", "gain", "duration_s", "scenario") or (key.startswith("scenario.") and len(key) > 9):
        return None
    return "a plant run varies law, gain, duration_s, scenario or scenario.KEY.PATH"


def _prepare(req: RunRequest) -> Prepared:
    from detumble.sim.plant import Plant
    from detumble.sim.readback import read_setting
    from detumble.sim.runner import run
    from detumble.sim.scenario import LAWS, ScenarioError, load_scenario

    cfg, values = req.config, req.values
    name = str(cfg["scenario"])
    if (req.base_dir / name).is_file():
        name = str(req.base_dir / name)
    keys = [k for k in values if k.startswith("scenario.")]
    from fprime_lite.tools.campaign.values import yaml_text

    settings = [f"{k[9:]}={yaml_text(values[k])}" for k in keys]
    try:
        sc = load_scenario(name, seed=req.seed, settings=settings)
    except ScenarioError as exc:
        culprit = next((k for k in keys if f"'{k[9:]}=" in str(exc)), "scenario" if "scenario" in values else None)
        raise RunSetupError(str(exc), culprit) from None
    law = cfg.get("law") or sc.control.law
    if law not in LAWS:
        raise RunSetupError(f"unknown law {law!r}; laws: {', '.join(LAWS)}", "law")
    gain = cfg.get("gain")
    if gain is not None and not (isinstance(gain, (int, float)) and math.isfinite(gain) and gain > 0):
        raise RunSetupError(f"gain must be a positive number, got {gain!r}", "gain")
    duration = float(cfg.get("duration_s") or sc.duration_s)
    if not duration > 0:
        raise RunSetupError(f"duration_s must be positive, got {duration}", "duration_s")
    plant = Plant(sc)
    try:
        back = {k: read_setting(plant, k[9:]) for k in keys}
    except KeyError as exc:
        raise RunSetupError(str(exc.args[0]), next((k for k in keys if k[9:] in str(exc)), None)) from None
    result: dict = {}

    def execute() -> RunOutput:
        import numpy as np

        r = run(sc, law=law, gain=gain, duration_s=duration, plant=plant, should_stop=req.should_stop)
        result["summary"] = r.summary
        if req.write_files:  # files that 'keep' may retain: what `python -m detumble.sim` writes
            from detumble.sim.runner import write_outputs

            write_outputs(r, str(req.out_dir))
        rows = np.array(r.rows, dtype=float)
        trace = {"t_s": rows[:, 0], "rate_deg_s": rows[:, 4]}
        if r.adcs_header:  # the ADCS columns (wheel momenta, pointing error) the metrics may use
            for j, name in enumerate(r.adcs_header):
                if name.startswith("h") and name.endswith("_Nms") or name == "pointing_error_deg":
                    trace[name] = np.array([np.nan if row[j] in ("", None) else float(row[j])
                                            for row in r.adcs_rows or ()])
        return RunOutput(summary=r.summary, trace=trace, out_dir=req.out_dir if req.write_files else None,
                         stopped_early=r.summary["sim_seconds"] < duration - 1e-9)

    def readback(key: str):
        if key in back:
            return back[key]
        s = result.get("summary", {})
        if key == "law":
            return s.get("law")
        if key == "gain":
            return s.get("gain")
        if key == "duration_s":
            return s.get("sim_seconds")
        if key == "scenario":
            return sc.name
        raise KeyError(key)

    return Prepared(simulation=plant, readback=readback, execute=execute)


def _fingerprint(config: dict, base_dir: pathlib.Path) -> dict:
    """The scenario a plant run of ``config`` loads, resolved as :func:`_prepare` resolves it."""
    from detumble.sim.scenario import scenario_fingerprint

    name = str(config["scenario"])
    if (base_dir / name).is_file():
        name = str(base_dir / name)
    return {f"scenario {config['scenario']}": scenario_fingerprint(name)}


PLANT_RUN = RunKind(name="plant", fields=frozenset({"scenario", "law", "gain", "duration_s"}),
                    required=frozenset({"scenario"}), check_key=_check_key, prepare=_prepare,
                    description="a plant-only scenario flown with a reference law (no flight software)",
                    fingerprint=_fingerprint)


# --- metrics --------------------------------------------------------------------------------------

def _trace(output: RunOutput):
    """(t_s, rate_deg_s) of the run: the plant run's samples, or a deployment's truth.csv."""
    import numpy as np

    if output.trace is not None:
        return output.trace["t_s"], output.trace["rate_deg_s"]
    path = pathlib.Path(output.out_dir or ".") / "truth.csv"
    if not path.is_file():
        raise MetricUnavailable("the run wrote no truth trace (truth.csv): the topology has no detumble report")
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        it, ir = header.index("t_s"), header.index("rate_deg_s")
        rows = [(float(r[it]), float(r[ir])) for r in reader]
    a = np.array(rows, dtype=float)
    return a[:, 0], a[:, 1]


def _columns(output: RunOutput, wanted) -> dict:
    """The trace columns whose names ``wanted(name)`` accepts: the plant run's, or truth.csv's."""
    import numpy as np

    if output.trace is not None:
        return {k: v for k, v in output.trace.items() if wanted(k)}
    path = pathlib.Path(output.out_dir or ".") / "truth.csv"
    if not path.is_file():
        return {}
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        keep = [(i, name) for i, name in enumerate(header) if wanted(name)]
        values: dict = {name: [] for _, name in keep}
        for row in reader:
            for i, name in keep:
                values[name].append(float(row[i]) if row[i] not in ("", "None") else np.nan)
    return {k: np.array(v, dtype=float) for k, v in values.items()}


def _is_wheel_momentum(name: str) -> bool:
    return name.startswith("h") and name.endswith("_Nms") and name[1:-4].isdigit()


def _wheel_momentum_peak(output: RunOutput, _probe) -> float:
    import numpy as np

    cols = _columns(output, _is_wheel_momentum)
    if not cols:
        raise MetricUnavailable("the spacecraft has no reaction wheels (no h<i>_Nms columns in the truth)")
    return float(max(np.nanmax(np.abs(v)) for v in cols.values()))


def _pointing(output: RunOutput, reduce) -> float:
    import numpy as np

    col = _columns(output, lambda n: n == "pointing_error_deg").get("pointing_error_deg")
    if col is None or not np.isfinite(col).any():
        raise MetricUnavailable("no pointing target during the run (no pointing error in the truth)")
    return float(reduce(col[np.isfinite(col)]))


def _detumble_time(output: RunOutput, _probe) -> float:
    t = output.summary.get("time_below_1_deg_s")
    if t is None:
        final = output.summary.get("final_rate_deg_s")
        raise MetricUnavailable(f"|w| stayed above {DETUMBLED_DEG_S:g} deg/s for the whole run"
                                + (f" (final {final:.3g} deg/s)" if isinstance(final, float) else ""))
    return float(t)


def _settling_time(output: RunOutput, _probe) -> float:
    from detumble.analysis.settling import settling_time

    if "settling_time_2pct_s" in output.summary:  # the run measured it against its controllers' goal
        value = output.summary["settling_time_2pct_s"]
        if value is None:
            raise MetricUnavailable("not settled within the run (summary.json settling_time_2pct_s is null)")
        return float(value)
    t, r = _trace(output)
    if len(t) < 3:
        raise MetricUnavailable("the trace has fewer than 3 samples")
    settled = settling_time(t, r, y_final=None, y_init=float(r[0]), band=SETTLING_BAND)
    if settled is None or settled > t[0] + 0.95 * (t[-1] - t[0]):
        raise MetricUnavailable("still moving in the last 5 % of the run: not settled within 2 % of its "
                                "final rate before the run ended (run longer)")
    return float(settled)


def _settling_channel(index: int | None):
    """The run summary's seed-004 settling time of one channel: body-rate axis ``index`` (0, 1, 2 =
    x, y, z) or, for ``None``, the attitude's real part (the wheel law's)."""
    def compute(output: RunOutput, _probe) -> float:
        if index is None:
            key = "settling_time_2pct_attitude_s"
            value = output.summary.get(key)
            present = key in output.summary
        else:
            key = "settling_time_2pct_axes_s"
            axes = output.summary.get(key)
            present = isinstance(axes, list) and len(axes) == 3
            value = axes[index] if isinstance(axes, list) and present else None
        if not present:
            raise MetricUnavailable(f"summary.json has no {key} (only seed 004's laws measure it)")
        if value is None:
            raise MetricUnavailable(f"not settled within the run (summary.json {key} is null)")
        return float(value)
    return compute


def _pointing_statistic(key: str):
    """The run summary's POINTING error statistic ``key`` (median, p95, max; the steady samples after each
    interval's acquisition, detumble.analysis.pointing_windows)."""
    def compute(output: RunOutput, _probe) -> float:
        stats = output.summary.get("pointing_error_deg")
        if not isinstance(stats, dict) or stats.get(key) is None:
            raise MetricUnavailable("no POINTING statistics in the run summary (the controller never pointed, or "
                                    "the deployment has no attitude run report)")
        return float(stats[key])
    return compute


def _pointing_acquisition(output: RunOutput, _probe) -> float:
    """s from entering POINTING until the true error stays below the acquisition threshold (30° on the coils,
    0.1° on the wheels): the run summary's ``pointing_error_deg.acquisition_s``."""
    stats = output.summary.get("pointing_error_deg")
    if not isinstance(stats, dict) or stats.get("acquisition_s") is None:
        raise MetricUnavailable("no acquisition in the run summary (the controller never pointed, the error never "
                                "stayed below the acquisition threshold, or the deployment has no attitude report)")
    return float(stats["acquisition_s"])


def _acquisition_below(threshold_deg: float):
    """s from entering POINTING until the true error stays below ``threshold_deg`` (deg) to the end of the first
    POINTING interval: the summary's acquisition rule (detumble.analysis.pointing_windows) at another angle, on
    the run's recorded true error (the plant run's trace or a deployment's truth.csv)."""
    def compute(output: RunOutput, _probe) -> float:
        from detumble.analysis.pointing_windows import acquisition_time

        intervals = output.summary.get("pointing_intervals")
        if not intervals:
            raise MetricUnavailable("no POINTING interval in the run summary (pointing_intervals)")
        t0 = float(intervals[0]["t_s"])
        t1 = float(intervals[1]["t_s"]) if len(intervals) > 1 else math.inf
        cols = _columns(output, lambda n: n in ("t_s", "pointing_error_deg"))
        if "pointing_error_deg" not in cols or "t_s" not in cols:
            raise MetricUnavailable("no true pointing error in the run's trace")
        kept = [(float(t), float(e)) for t, e in zip(cols["t_s"], cols["pointing_error_deg"], strict=True)
                if t0 <= t < t1 and math.isfinite(e)]
        if not kept:
            raise MetricUnavailable("no pointing error recorded in the first POINTING interval")
        acq = acquisition_time([t for t, _ in kept], [e for _, e in kept], threshold_deg)
        if acq is None:
            raise MetricUnavailable(f"the error was still above {threshold_deg:g} deg at the interval's end")
        return acq + (kept[0][0] - t0)
    return compute


def _final_rate(output: RunOutput, _probe) -> float:
    return float(output.summary["final_rate_deg_s"])


def _mode_transitions(output: RunOutput, _probe) -> float:
    transitions = output.summary.get("control_mode_transitions")
    if transitions is None:
        raise MetricUnavailable("the run has no attitude report (no control_mode_transitions in summary.json)")
    return float(len(transitions))


def _spin_axis_error(statistic: str):
    def compute(output: RunOutput, _probe) -> float:
        if "spin_axis_error_deg" not in output.summary:
            raise MetricUnavailable("the run has no attitude report (no spin_axis_error_deg in summary.json)")
        stats = output.summary["spin_axis_error_deg"]
        if stats is None:
            raise MetricUnavailable("no SPIN_STABLE samples in the run (summary.json spin_axis_error_deg is null)")
        return float(stats[statistic])
    return compute



class CoilEnergyMeter:
    """Integrates the coils' electrical energy: each face's steady-state power
    ``(level/127·V)²/R`` times the time it is held (the L/R lag is neglected), in J."""

    def __init__(self, simulation):
        from detumble.sim.coils import MAX_LEVEL, CoilSet

        plant = _find_plant(simulation)
        self.unavailable = None
        if plant is None:
            self.unavailable = "the run has no simulated plant to meter"
            return
        acts = plant.actuators
        if not isinstance(acts, CoilSet):
            self.unavailable = "ideal torque rods have no electrical model (actuators: rods)"
            return
        self.plant = plant
        self.coils = acts.coils
        self.energy_j = 0.0
        self.since_ns = {face: plant.t_ns for face in self.coils}
        self._max = MAX_LEVEL
        original = acts.set_level
        coils = self.coils

        def set_level(face: int, level: int) -> None:
            coil = coils.get(face)
            before = coil.level if coil is not None else 0
            original(face, level)
            if coil is not None and coil.level != before:
                self._account(face, before)
        setattr(acts, "set_level", set_level)  # CoilSet.apply_dipole_B and the drivers both come through here

    def _power_w(self, face: int, level: int) -> float:
        spec = self.coils[face].spec
        if spec.resistance_ohm == 0.0:
            return 0.0
        v = level / self._max * spec.voltage_v
        return v * v / spec.resistance_ohm

    def _account(self, face: int, level: int) -> None:
        now = self.plant.t_ns
        self.energy_j += self._power_w(face, level) * (now - self.since_ns[face]) * 1e-9
        self.since_ns[face] = now

    def total_j(self) -> float:
        if self.unavailable:
            raise MetricUnavailable(self.unavailable)
        for face, coil in self.coils.items():
            self._account(face, coil.level)
        return self.energy_j


def _find_plant(simulation):
    if hasattr(simulation, "actuators") and hasattr(simulation, "t_ns"):
        return simulation
    for resource in getattr(simulation, "resources", {}).values():
        plant = getattr(resource, "plant", None)
        if plant is not None and hasattr(plant, "actuators"):
            return plant
    return None


METRICS = (
    Metric("detumble_time_s", "s", f"first time |w| < {DETUMBLED_DEG_S:g} deg/s (truth)", _detumble_time),
    Metric("settling_time_2pct_s", "s", "the run summary's seed-004 settling time when it has one (each axis "
           "within 2 % of its step around the controllers' goal); else the time after which |w| stays within 2 % "
           "of its initial-to-final change around its final value", _settling_time),
    *(Metric(f"settling_time_2pct_{axis}_s", "s", f"the run summary's seed-004 settling time of body rate "
             f"axis {axis} alone (summary.json settling_time_2pct_axes_s)", _settling_channel(i))
      for i, axis in enumerate("xyz")),
    Metric("settling_time_2pct_attitude_s", "s", "the run summary's seed-004 settling time of the attitude's real "
           "part (wheels_pd only; summary.json settling_time_2pct_attitude_s)", _settling_channel(None)),
    Metric("final_rate_deg_s", "deg/s", "|w| at the end of the run (truth)", _final_rate),
    Metric("pointing_error_mean_deg", "deg", "mean pointing error while a target is set (truth)",
           lambda output, _probe: _pointing(output, lambda v: v.mean())),
    Metric("pointing_error_max_deg", "deg", "largest pointing error while a target is set (truth)",
           lambda output, _probe: _pointing(output, lambda v: v.max())),
    Metric("pointing_median_deg", "deg", "median steady pointing error in POINTING, after each acquisition "
           "(run summary)",
           _pointing_statistic("median")),
    Metric("pointing_p95_deg", "deg", "95th percentile of the steady pointing error in POINTING, after each "
           "acquisition (run summary)", _pointing_statistic("p95")),
    Metric("pointing_max_deg", "deg", "largest steady pointing error in POINTING, after each acquisition "
           "(run summary)",
           _pointing_statistic("max")),
    Metric("pointing_acquisition_s", "s", "time from entering POINTING until the true error stays below the "
           "acquisition threshold (30 deg on the coils, 0.1 deg on the wheels; run summary)", _pointing_acquisition),
    Metric("pointing_acquisition_15deg_s", "s", "time from entering POINTING until the true error stays below "
           "15 deg (the coils' p95 goal) to the end of the first POINTING interval (true error trace)",
           _acquisition_below(15.0)),
    Metric("mode_transitions", "", "number of attitude-control mode changes the ground saw "
           "(summary.json control_mode_transitions)", _mode_transitions),
    *(Metric(f"spin_axis_error_{stat}_deg", "deg", f"{stat} angle between the total angular momentum and body "
             f"+Z over SPIN_STABLE after its first 10 % (summary.json spin_axis_error_deg)", _spin_axis_error(stat))
      for stat in ("median", "p95", "max")),
    Metric("wheel_momentum_peak_nms", "N m s", "largest |h| of any reaction wheel (truth)", _wheel_momentum_peak),
    Metric("coil_energy_j", "J", "electrical energy spent in the coils (steady-state I²R)",
           lambda output, meter: meter.total_j(), instrument=CoilEnergyMeter),
)
