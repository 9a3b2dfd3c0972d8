"""Plant-only runs: fly a scenario with a reference law (no F' framework involved).

``python -m detumble.sim SCENARIO --law none|kopt|bdot|bangbang|cross_product|beta_pd|wheels_pd|adcs
[--gain G] --out DIR [--duration S] [--seed N]`` writes ``DIR/summary.json`` and ``DIR/rate.csv`` (the body rate, then
the ADCS truth columns of :mod:`detumble.sim.truth`). :func:`main`
returns an exit code and reports bad input on stderr without a traceback, so a CLI
(``fprime-lite sim``) can call it directly.

Control timing: the law runs every ``control.period_s``. If ``control.sense_settle_s`` > 0 the
coils are switched off at the start of each period and the field is read that long afterwards
(the flight manager's COOLDOWN idea); otherwise it is read at the start of the period, with the
coils still on - and a magnetometer with coil coupling will then see them. A *ticked* law
(``adcs``, :mod:`detumble.sim.adcs_law`) keeps its own timing instead: the runner calls its
``tick`` every rate-group tick (``tick_s``, 20 ms) and it reads and drives the plant itself, as the
flight component does through its drivers.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time
from dataclasses import dataclass
from typing import Callable, cast

from detumble.errors import DetumbleError
from detumble.sim import frames, plant_kernel
from detumble.analysis.pointing_windows import pointing_summary
from detumble.analysis.pooled_stats import sorted_percentile
from detumble.control.quaternion import quat_angle, quat_error
from detumble.control.targets import LABELS
from detumble.sim.adcs_law import AdcsLaw, PlantIo
from detumble.sim.coursework_laws import REPORT_CROSS_PRODUCT_GAIN, BetaPdLaw, CrossProductLaw, WheelsPdLaw
from detumble.sim.laws import BangBangLaw, BdotLaw, KoptLaw, NoLaw, clip_to_limits, kopt_gain
from detumble.sim.plant import Plant
from detumble.control.attitude_defaults import DEFAULTS as ADCS_DEFAULTS
from detumble.control.units import TESLA_PER_GAUSS
from detumble.sim.scenario import LAWS, Scenario, ScenarioError, load_scenario
from detumble.sim.settling_metrics import COURSEWORK_LAWS, SettlingMetrics
from detumble.sim.truth import adcs_header, adcs_row

DEFAULT_BDOT_GAIN = 3.0  # A m^2 s / G, the flight DetumbleManager default


class LawError(DetumbleError, ValueError):
    """A law that cannot be made for this scenario (what is wrong and what to do instead)."""


@dataclass
class RunResult:
    summary: dict
    rows: list[tuple[float, float, float, float, float]]  # t s, wx wy wz |w| deg/s
    adcs_header: list[str] | None = None  # the ADCS truth columns (detumble.sim.truth) after those five
    adcs_rows: list[list] | None = None


#: The laws ``--gain`` sets (the others take their gains from the scenario's ``control.<law>`` block).
GAIN_LAWS = ("kopt", "bdot", "cross_product")


def make_law(name: str, plant: Plant, gain: float | None = None, saturation: str | None = None):
    """Instantiate a reference law for ``plant``. ``gain`` overrides the law's default;
    ``saturation`` (default: the scenario's ``control.saturation``) is ``scale`` or ``clip``."""
    law = _make_law(name, plant, gain)
    if (saturation or plant.scenario.control.saturation) == "clip":
        law.limit = clip_to_limits
    return law


def _make_law(name: str, plant: Plant, gain: float | None):
    m_max = plant.max_dipole_per_axis()
    if name == "none":
        return NoLaw()
    if name == "kopt":
        if gain is None:
            import numpy as np  # set-up only

            j_min = float(min(np.linalg.eigvalsh(np.array(plant.body.inertia))))
            gain = kopt_gain(plant.orbit.mean_motion, plant.orbit.inclination_rad, j_min)
        return KoptLaw(gain, m_max)
    if name == "bdot":
        return BdotLaw(DEFAULT_BDOT_GAIN if gain is None else gain, m_max)
    if name == "bangbang":
        return BangBangLaw(m_max)
    if name in ("cross_product", "beta_pd", "wheels_pd"):
        return _make_coursework_law(name, plant, gain, m_max)
    if name == "adcs":
        return make_adcs_law(plant)
    raise LawError(f"unknown law {name!r}; expected one of: {', '.join(LAWS)}")


def _make_coursework_law(name: str, plant: Plant, gain: float | None, m_max):
    cfg = plant.scenario.control
    n = plant.orbit.mean_motion
    if name == "cross_product":
        return CrossProductLaw(REPORT_CROSS_PRODUCT_GAIN if gain is None else gain, m_max)
    if gain is not None:
        raise LawError(f"--gain sets the single gain of {', '.join(GAIN_LAWS)}; set {name}'s gains with "
                       f"--set control.{name}.<gain>=VALUE")
    if name == "beta_pd":
        b = cfg.beta_pd
        return BetaPdLaw(b.k_s, b.k_d, n, m_max, switched=b.switched)
    w = cfg.wheels_pd
    if plant.wheel_count != 3 or any(abs(a[i] - (1.0 if i == k else 0.0)) > 1e-12
                                     for k, a in enumerate(plant.wheel_axes_B) for i in range(3)):
        raise LawError("wheels_pd needs three reaction wheels along body x, y and z "
                         "(spacecraft.reaction_wheels.axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]])")
    return WheelsPdLaw(w.k_p, w.k_d, plant.body.inertia, n, w.target_q_bo, m_max, limits=w.limits, error=w.error,
                       dump_gain=w.dump_gain)


#: s: the wheels campaign's steady window starts this long after the last target change (reports.pointing_metrics)
STEADY_AFTER_SLEW_S = 60.0


def _steady_after_slew(samples: list[tuple], slews) -> dict:
    """``steady_after_slew_median_deg`` / ``_p95_deg``: the POINTING errors from STEADY_AFTER_SLEW_S after the last
    slew to the end (the window of the deployment's ``pointing_steady_*`` campaign metrics); None without a slew or
    without samples in that window (the keys are always there, so that a campaign can name them as metrics)."""
    start = slews[-1]["t_s"] + STEADY_AFTER_SLEW_S if slews else math.inf
    kept = sorted(s[1] for s in samples if s[0] >= start and math.isfinite(s[1]))
    if not kept:
        return {"steady_after_slew_median_deg": None, "steady_after_slew_p95_deg": None}
    return {"steady_after_slew_median_deg": sorted_percentile(kept, 0.5),
            "steady_after_slew_p95_deg": sorted_percentile(kept, 0.95)}


def _turn_deg(q, previous) -> float:
    """The angle between two targets (0 without a previous one), deg."""
    return 0.0 if q is None or previous is None else math.degrees(quat_angle(quat_error(q, previous)))


def make_adcs_law(plant: Plant) -> AdcsLaw:
    """The three-mode controller of ``plant``'s scenario (``control.adcs``) on the plant's wheels (three or
    four; otherwise it points on the magnetorquers, as the component does without wheels)."""
    cfg = plant.scenario.control.adcs
    params = {name: getattr(cfg, name) for name in ADCS_DEFAULTS}
    n = plant.wheel_count
    axes = plant.wheel_axes_B if 3 <= n <= 4 else ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    try:
        return AdcsLaw(axes, 3 <= n <= 4, params, cfg.target_q_bn, bdot_provider=cfg.bdot_provider,
                       provider_gain=cfg.bdot_provider_gain, auto_start_s=cfg.auto_start_s,
                       force_mode=cfg.force_mode, force_at_s=cfg.force_at_s, target_changes=cfg.target_changes)
    except ValueError as exc:
        raise LawError(f"adcs: {exc}") from None


def _full_state_command(ctl, plant: Plant, b_B, t_read: float) -> None:
    """Read rate, attitude relative to O and wheel momenta as the law's sensors would, command."""
    gx, gy, gz, _ = plant.gyro_reading()
    if plant.star_tracker is not None:
        q0, q1, q2, q3, _valid, _ = plant.star_tracker_reading()
        q_BO = frames.q_BO((q0, q1, q2, q3), plant.q_ON)
    else:
        q_BO = plant.q_BO
    h = tuple(plant.wheel_reading(i)[1] for i in range(plant.wheel_count)) if plant.wheel_count else (0.0, 0.0, 0.0)
    m_B, torques = ctl.command(t_read, b_B, (gx, gy, gz), q_BO, h)
    plant.apply_dipole_B(m_B)
    if torques is not None:
        plant.set_wheel_torques(torques)


def run(scenario: Scenario, law: str | None = None, gain: float | None = None, duration_s: float | None = None,
        seed: int | None = None, *, plant: Plant | None = None, should_stop=None,
        implementation: str | None = None) -> RunResult:
    """Fly ``scenario`` with a law (default: the scenario's ``control.law``); return summary + samples.

    ``plant``: one already built from ``scenario`` (a campaign reads it back first);
    ``should_stop()``: polled once per recorded sample, ends the run early when true;
    ``implementation``: the plant's (``auto``, ``python``, ``compiled``; see :mod:`.plant_kernel`).
    """
    sc = scenario
    ctrl = sc.control
    law_name = law if law is not None else ctrl.law
    if law_name == "adcs" and gain is not None:
        raise LawError("--gain does not apply to adcs; set its flight parameters with "
                       "--set control.adcs.<PARAMETER>=VALUE (e.g. control.adcs.K_P=1.1e-3)")
    if law_name in ("none", "bangbang") and gain is not None:
        raise LawError(f"--gain does not apply to {law_name}, which has no gain; laws with one gain: "
                       f"{', '.join(GAIN_LAWS)}")
    if gain is None and law_name == ctrl.law:  # the scenario's gain is its own law's: another law keeps its default
        gain = ctrl.gain
    duration = sc.duration_s if duration_s is None else duration_s
    plant = Plant(sc, seed, implementation) if plant is None else plant
    ctl = make_law(law_name, plant, gain)
    dt = sc.dynamics_step_s
    n_steps = int(round(duration / dt))
    period = max(1, int(round(ctrl.period_s / dt)))
    settle = int(round(ctrl.sense_settle_s / dt))
    record_every = max(1, int(round(sc.record_interval_s / dt)))
    active = law_name != "none"
    full_state = getattr(ctl, "full_state", False)
    ticked = getattr(ctl, "ticked", False)
    if ticked:  # called every rate-group tick, as the flight component is
        tick_every = int(round(ctl.tick_s / dt))
        if tick_every < 1 or abs(tick_every * dt - ctl.tick_s) > 1e-9:
            raise LawError(f"{law_name} runs every {ctl.tick_s} s (the rate group's tick); dynamics_step_s "
                           f"{dt} s must divide it")
        io = PlantIo(plant)
        target_seen = None
        sample_every = max(1, int(round(0.5 / dt)))  # the attitude report's 0.5 s sampling
        pointing_deg: list[tuple] = []  # (t_s, true error deg, target key, label, on wheels, turn deg) in POINTING
        slew_prev = None  # the law's target at the last POINTING sample
    omega_final = (0.0, -plant.orbit.mean_motion, 0.0) if law_name in COURSEWORK_LAWS else (0.0, 0.0, 0.0)
    metrics = SettlingMetrics(plant, omega_final=omega_final, include_attitude=getattr(ctl, "wheel_law", False))
    threshold2 = math.radians(1.0) ** 2
    t_below: float | None = None
    rows: list[tuple[float, float, float, float, float]] = []
    deg = math.degrees
    zero = (0.0, 0.0, 0.0)

    adcs: list[list] = []

    def record() -> None:
        w = plant.omega_BN_B
        rows.append((plant.t, deg(w[0]), deg(w[1]), deg(w[2]), deg(math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]))))
        adcs.append(adcs_row(plant))

    record()
    wall0 = time.perf_counter()
    for k in range(n_steps):
        if ticked:
            if k % tick_every == 0:
                ctl.tick(io)
                if ctl.target is not target_seen:  # the truth log's pointing error follows the target
                    target_seen = ctl.target
                    plant.set_pointing_target(target_seen)
        elif active:
            phase = k % period
            if settle and phase == 0:
                plant.apply_dipole_B(zero)
            if phase == settle:
                bx, by, bz, t_read = plant.magnetometer_reading()
                b_B = (bx * TESLA_PER_GAUSS, by * TESLA_PER_GAUSS, bz * TESLA_PER_GAUSS)  # gauss -> T
                if full_state:
                    _full_state_command(ctl, plant, b_B, t_read)
                else:
                    plant.apply_dipole_B(ctl.update(b_B, t_read))
        plant.step(dt)
        if ticked and (k + 1) % sample_every == 0 and ctl.mode == "POINTING":  # as the attitude report samples
            three_mode = cast(AdcsLaw, ctl).law
            ref = three_mode.reference
            label = LABELS[ref.label] if ref is not None else ""
            pointing_deg.append((plant.t, cast(AdcsLaw, ctl).true_pointing_error_deg(plant.q_BN, plant.ephemeris),
                                 (three_mode.target_spec, label), label, three_mode.pointing_on_wheels,
                                 _turn_deg(three_mode.target, slew_prev)))
            slew_prev = three_mode.target
        if (k + 1) % period == 0:
            metrics.update(plant)
        if t_below is None:
            s = plant.state
            if s[4] * s[4] + s[5] * s[5] + s[6] * s[6] < threshold2:
                t_below = plant.t
        if (k + 1) % record_every == 0:
            record()
            if should_stop is not None and should_stop():
                break
    wall = time.perf_counter() - wall0
    if rows[-1][0] != plant.t:
        record()
    extra: dict = {}
    if ticked:
        extra = {"control_mode_transitions": [{"t_s": t, "mode": m, "reason": r} for t, m, r in ctl.transitions],
                 "final_mode": ctl.mode,
                 **pointing_summary(pointing_deg, sample_every * dt, slews=True),
                 "control_cycles": ctl.cycles}
        extra.update(_steady_after_slew(pointing_deg, extra.get("slews")))
    summary = {
        "scenario": sc.name,
        "source": sc.source,
        "law": law_name,
        "gain": getattr(ctl, "k", getattr(ctl, "gain", None)),
        "seed": plant.seed,
        "dynamics_step_s": dt,
        "control_period_s": ctrl.period_s,
        "steps": k + 1 if n_steps else 0,
        "sim_seconds": plant.t,
        "wall_seconds": wall,
        "real_time_factor": plant.t / wall if wall > 0 else None,  # the key fprime-lite run writes
        "plant_implementation": plant.implementation,  # compiled kernel or pure-Python reference (same floats)
        "initial_rate_deg_s": rows[0][4],
        "final_rate_deg_s": plant.rate_deg_s,
        "time_below_1_deg_s": t_below,
        **metrics.summary(),
        "orbit_period_s": 2.0 * math.pi / plant.orbit.mean_motion,
        **extra,
    }
    return RunResult(summary, rows, adcs_header(plant), adcs)


def write_atomic(path: str, text: str) -> None:
    """Write ``text`` to ``path`` atomically: temp file in the same folder, fsync, os.replace.

    The temporary file is named as ``fprime_lite.osal.atomic`` names its own
    (``.fprime-lite-tmp.<pid>.<name>.<random>.part``; this layer does not import the framework),
    so the start-up clean-up of ``fprime-lite sim`` and ``run`` recognises what a kill left."""
    folder = os.path.dirname(os.path.abspath(path))
    name = os.path.basename(path)[:64]
    fd, tmp = tempfile.mkstemp(prefix=f".fprime-lite-tmp.{os.getpid()}.{name}.", suffix=".part", dir=folder)
    try:
        os.chmod(tmp, _new_file_mode(path))  # mkstemp makes 0600; a result file gets the usual mode
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _new_file_mode(path: str) -> int:
    """An existing file's permissions, else ``0o666 & ~umask`` (what ``open()`` would give)."""
    try:
        return os.stat(path).st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def write_outputs(result: RunResult, out_dir: str) -> None:
    os.makedirs(out_dir, exist_ok=True)
    write_atomic(os.path.join(out_dir, "summary.json"), json.dumps(result.summary, indent=2) + "\n")
    extra = result.adcs_header or []
    lines = [",".join(["time_s", "omega_x_deg_s", "omega_y_deg_s", "omega_z_deg_s", "rate_deg_s", *extra])]
    adcs = result.adcs_rows or [[] for _ in result.rows]
    lines += [",".join([f"{t:.3f}", f"{x:.9g}", f"{y:.9g}", f"{z:.9g}", f"{w:.9g}", *map(_cell, more)])
              for (t, x, y, z, w), more in zip(result.rows, adcs, strict=True)]
    write_atomic(os.path.join(out_dir, "rate.csv"), "\n".join(lines) + "\n")


class OutputFolderError(DetumbleError):
    """The ``--out`` folder cannot take a run's outputs (the message says why and what to do)."""


def _output_folder(out_dir: str) -> str | None:
    """Make sure ``out_dir`` is a folder the run can write in; returns it when this call created
    it (None when it was already there). Raises :class:`OutputFolderError` otherwise."""
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        raise OutputFolderError("is a file, not a folder — give a new or empty folder")
    existed = os.path.isdir(out_dir)
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as exc:
        raise OutputFolderError(f"cannot create the folder ({exc.strerror}) — choose a folder you can write") from None
    if not os.access(out_dir, os.W_OK | os.X_OK):
        raise OutputFolderError("cannot write in this folder (permission denied) — choose a folder you can write")
    return None if existed else out_dir


def _cell(v) -> str:
    return v if isinstance(v, str) else f"{v:.12g}"


def build_parser(prog: str = "python -m detumble.sim") -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=prog,
                                description="Plant-only detumble run of a scenario (no flight software).")
    p.add_argument("scenario", nargs="?", help="packaged scenario name (e.g. case_a, default) or a YAML file")
    p.add_argument("--scenario", dest="scenario_opt", metavar="NAME|FILE", help="same as the positional argument")
    p.add_argument("--law", choices=LAWS, default=None, help="control law (default: the scenario's control.law)")
    p.add_argument("--gain", type=float, default=None,
                   help="kopt: k in kg m^2/s (default 2n(1+sin i)J_min); bdot: A m^2 s/G (default 3.0); "
                        "cross_product: k (default the report's); the scenario's control.gain applies only "
                        "to the scenario's own control.law")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder for summary.json and rate.csv")
    p.add_argument("--duration", type=float, default=None, metavar="S", help="simulated seconds (default: scenario)")
    p.add_argument("--seed", type=int, default=None, help="noise / random-rate seed (default: scenario)")
    p.add_argument("--plant", choices=plant_kernel.IMPLEMENTATIONS, default=None,
                   help="plant implementation: compiled kernel, pure-Python reference, or auto (default: "
                        "$FPRIME_LITE_PLANT, else auto); both give the same floats")
    p.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE",
                   help="override one scenario value, e.g. sensors.magnetometer.noise_std_gauss=0 (repeatable)")
    p.add_argument("--no-plots", action="store_true", help="write no plots (fprime-lite sim draws them by default)")
    return p


def main(argv: list[str] | None = None, prog: str = "python -m detumble.sim",
         clean_out: Callable[[str], object] | None = None, draw_plots: Callable[[str], object] | None = None) -> int:
    """Entry point. Returns 0 on success, 2 on bad input (message on stderr). ``clean_out(folder)``,
    if given, is called on the output folder before anything is written there (``fprime-lite sim``
    passes the framework's start-up clean-up of temporary files); ``draw_plots(folder)``, if given,
    after the outputs are written, unless ``--no-plots`` (``fprime-lite sim`` passes the application's
    run plotter: this layer draws nothing)."""
    parser = build_parser(prog)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse has already printed its message
        return int(exc.code or 0)
    name = args.scenario_opt or args.scenario
    if not name:
        print("error: give a scenario name or file (e.g. case_a)", file=sys.stderr)
        return 2
    if args.duration is not None and not (math.isfinite(args.duration) and args.duration > 0):
        print(f"error: --duration must be a positive number of seconds, got {args.duration}", file=sys.stderr)
        return 2
    if args.gain is not None and not (math.isfinite(args.gain) and args.gain > 0):
        print(f"error: --gain must be positive, got {args.gain}", file=sys.stderr)
        return 2
    created = None
    try:
        sc = load_scenario(name, seed=args.seed, settings=args.set)
        created = _output_folder(args.out)  # before flying: a long run must not end unable to write
        result = run(sc, law=args.law, gain=args.gain, duration_s=args.duration, implementation=args.plant)
        if clean_out is not None:
            clean_out(args.out)
        write_outputs(result, args.out)
        if draw_plots is not None and not args.no_plots:
            draw_plots(args.out)
    except OutputFolderError as exc:
        print(f"error: --out {args.out}: {exc}", file=sys.stderr)
        return 2
    except (ScenarioError, LawError, plant_kernel.KernelUnavailableError) as exc:
        if created is not None and not os.listdir(created):
            os.rmdir(created)  # the folder this call made, still empty: leave nothing behind
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except (ImportError, OSError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:  # a bad FPRIME_LITE_PLANT
        if plant_kernel.ENV_VAR not in str(exc):
            raise
        print(f"error: {exc}", file=sys.stderr)
        return 2
    s = result.summary
    below = s["time_below_1_deg_s"]
    print(f"{s['scenario']}: law {s['law']}, {s['sim_seconds']:.0f} s simulated in {s['wall_seconds']:.1f} s "
          f"({s['real_time_factor']:.0f}x real time, {s['plant_implementation']} plant); "
          f"final rate {s['final_rate_deg_s']:.3f} deg/s; "
          f"|w| < 1 deg/s at {'never' if below is None else f'{below:.1f} s'}; wrote {args.out}")
    return 0


__all__ = ["RunResult", "LawError", "run", "make_law", "make_adcs_law", "main", "write_atomic", "write_outputs"]
