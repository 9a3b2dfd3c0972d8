"""Plant-only check of SUN_SAFE: from a tumble with no star tracker, does the light-sensor Sun-safe mode turn the
chosen face to the Sun, and how good is the light sensors' Sun vector? (issue 27's targets; no framework)

:func:`fly` flies :class:`detumble.control.three_mode.ThreeModeLaw` (the AttitudeController's law) through
:class:`detumble.sim.adcs_law.AdcsLaw` on the ``adcs`` scenario's plant, with the six face light sensors
(:class:`detumble.sim.sun_sensors.SunSensorModel`, the stated noise) read at 1 Hz and turned into a Sun vector as
the ADCS component does, the star tracker switched off, and FORCE_MODE SUN_SAFE sent at the start (acting on the
second control cycle, 0.1 s). It samples, once a second: the true angle between SUN_SAFE_AXIS and the Sun, whether
the spacecraft is in eclipse, and the Sun vector estimate's error against the truth at its reading's instant.

``python -m detumble.sim.sun_safe_check [--seeds N] [--actuator ANY|MAGNETORQUERS] [--duration S] [--rate DEG_S]
[--albedo A] [--penumbra] [--param NAME=VALUE ...] [--spin-down] [--json FILE]``
prints a table of ``docs/studies/sun_safe.md`` (:func:`markdown`); ``--json`` also keeps its figures
(:func:`table`), from which ``tools/studies.py --only sun_safe`` renders the page's tables; ``--spin-down`` prints
the coils' automatic spin-down table instead (when the spin was lowered, the true error and body rate from then on;
:func:`spin_down_table`, kept with ``--json`` too, its seed 1 re-flown by :func:`spin_down_probe`);
``--from-run DIR`` reads a deployment's flight.
"""

from __future__ import annotations

import argparse
import math
import random
import statistics
from dataclasses import dataclass, field

from detumble.control.attitude_defaults import PARAMETERS
from detumble.control.sun_vector import SUN_LIT_FRACTION
from detumble.control.three_mode import checked_parameters
from detumble.sim.adcs_law import AdcsLaw, PlantIo
from detumble.sim.epoch import julian_date
from detumble.sim.orbit import R_EARTH_EQ
from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario
from detumble.sim.sun_sensors import SunSensorModel, SunSensorSpec

__all__ = ["SunSafeResult", "fly", "seed_settings", "main", "markdown", "pointing_from_run", "table",
           "vector_errors_from_run", "vector_errors_by_second", "spin_down_row", "spin_down_table",
           "spin_down_markdown", "spin_down_probe", "HAND_BACK_RATE_DEG_S", "POINTING_THRESHOLD_DEG",
           "VECTOR_THRESHOLD_DEG"]

#: The targets (issue 27): Sun-pointing error within this after acquisition, light-sensor vector within that.
POINTING_THRESHOLD_DEG = 10.0
VECTOR_THRESHOLD_DEG = 5.0

_AXES = {"PLUS_X": (1.0, 0.0, 0.0), "MINUS_X": (-1.0, 0.0, 0.0), "PLUS_Y": (0.0, 1.0, 0.0),
         "MINUS_Y": (0.0, -1.0, 0.0), "PLUS_Z": (0.0, 0.0, 1.0), "MINUS_Z": (0.0, 0.0, -1.0)}


def _angle_deg(a, b) -> float:
    d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    return math.degrees(math.acos(max(-1.0, min(1.0, d))))


@dataclass
class SunSafeResult:
    """One flight's samples (1 Hz): time (s), true Sun-pointing error (deg), eclipse, true body rate |ω| and its part
    across the pointed axis |ω − (ω·â)â| (deg/s); the Sun vector's errors (deg) at its sunlit readings; the mode
    transitions ``(t s, mode, reason)``; the time the coils' SUN_SAFE lowered its spin to SUN_HOLD_SPIN_RATE (s;
    None: it did not); at the flight's end, SUN_SAFE's gyro-bias estimate (``control.sun_safe.SunRateBias``) and the
    gyro's true bias (deg/s, B), and the true Sun direction (unit, B: ``sun_body_end``)."""

    times: list = field(default_factory=list)
    pointing_deg: list = field(default_factory=list)
    eclipse: list = field(default_factory=list)
    vector_deg: list = field(default_factory=list)
    vector_invalid_sunlit: int = 0
    transitions: list = field(default_factory=list)
    rate_deg_s: list = field(default_factory=list)
    transverse_deg_s: list = field(default_factory=list)
    spin_lowered_s: float | None = None
    bias_estimate_deg_s: tuple | None = None
    bias_true_deg_s: tuple | None = None
    sun_body_end: tuple | None = None

    def sunlit_parts(self) -> list[tuple[float, float]]:
        """``(start, end)`` s of each sunlit stretch of the run, in order."""
        parts, start = [], None
        for t, e in zip(self.times, self.eclipse, strict=True):
            if not e and start is None:
                start = t
            elif e and start is not None:
                parts.append((start, t))
                start = None
        if start is not None:
            parts.append((start, self.times[-1]))
        return parts

    def first_sunlit_part(self) -> tuple[float, float] | None:
        """``(start, end)`` s of the first sunlit stretch of the run (None: never sunlit)."""
        parts = self.sunlit_parts()
        return parts[0] if parts else None

    def acquisition_s(self, threshold_deg: float = POINTING_THRESHOLD_DEG, part_index: int = 0) -> float | None:
        """Seconds from the start of sunlit part ``part_index`` (0: the first) until the error stays at or below
        ``threshold_deg`` for the rest of that part (None: it never does, or there is no such part)."""
        parts = self.sunlit_parts()
        if part_index >= len(parts):
            return None
        start, end = parts[part_index]
        last_above = None
        for t, err in zip(self.times, self.pointing_deg, strict=True):
            if start <= t < end and not err <= threshold_deg:
                last_above = t
        if last_above is None:
            return 0.0
        if last_above >= end - 1.0:
            return None
        return last_above + 1.0 - start

    def after_spin_down(self) -> tuple[list, list]:
        """``(pointing errors, body rates)`` (deg, deg/s) sampled in the first sunlit part from the spin-down to its
        end (both empty when the spin was not lowered in that part)."""
        part, t0 = self.first_sunlit_part(), self.spin_lowered_s
        if part is None or t0 is None or not t0 < part[1]:
            return [], []
        keep = [i for i, t in enumerate(self.times) if t0 <= t < part[1]]
        return [self.pointing_deg[i] for i in keep], [self.rate_deg_s[i] for i in keep]

    def steady_sunlit(self) -> list:
        """The pointing errors in the first sunlit part after its acquisition (empty: never acquired)."""
        acq = self.acquisition_s()
        part = self.first_sunlit_part()
        if acq is None or part is None:
            return []
        t0, end = part[0] + acq, part[1]
        return [err for t, err in zip(self.times, self.pointing_deg, strict=True) if t0 <= t < end]


#: The tumble of the deployment's hand-back flights (°/s; ``campaigns/adcs/sun_safe_hand_back.seq``): below the star
#: tracker's 2 °/s smear limit, so POINTING (forced at 1 s) has fixes on every seed. At exactly 2 °/s the first
#: sample sits on the limit and whether any fix comes before 1 s is decided by the last bit of |ω| and by the drawn
#: axis (torque-free motion moves |ω| up or down by ~1e-4 °/s per second): seed 5 got none and its POINTING was
#: refused (NoAttitudeKnowledge), seed 2 entered on its one fix at t = 0.
HAND_BACK_RATE_DEG_S = 1.9


def seed_settings(seed: int, rate_deg_s: float = 2.0) -> list[str]:
    """The scenario settings of seed ``seed``'s flight: a ``rate_deg_s`` tumble about an axis and an attitude drawn
    from the seed (the ``--set`` lines of a deployment flight, the same draws :func:`fly` flies)."""
    rng = random.Random(seed)
    w_axis = [rng.gauss(0.0, 1.0) for _ in range(3)]
    q = [rng.gauss(0.0, 1.0) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    q = [c / n for c in q]
    return [f"initial.rate.magnitude_deg_s={rate_deg_s}", "initial.rate.axis=[{},{},{}]".format(*w_axis),
            "initial.attitude.quaternion=[{},{},{},{}]".format(*q)]


def fly(seed: int = 1, *, rate_deg_s: float = 2.0, duration_s: float = 5580.0, actuator: str = "ANY",
        axis: str = "PLUS_Z", scenario: str = "adcs", settings: tuple[str, ...] = (),
        params: dict | None = None, sensor_spec: SunSensorSpec | None = None,
        albedo_model: float = 0.0, lit_fraction: float = SUN_LIT_FRACTION) -> SunSafeResult:
    """Fly SUN_SAFE from a ``rate_deg_s`` tumble about an axis drawn from ``seed`` (the attitude drawn too), the
    star tracker off, POINTING_ACTUATOR = ``actuator``, SUN_SAFE_AXIS = ``axis``; the light sensors as
    ``sensor_spec`` (default: the stated noise, no albedo, cylindrical shadow), a face taken as lit above
    ``lit_fraction`` of the full Sun (the ADCS component's SUN_LIT_FRACTION); with ``albedo_model`` > 0 the Sun
    vector has that Bond albedo taken out (``control.albedo``; the law flies on it too)."""
    if axis not in _AXES:
        raise ValueError(f"axis must be one of {', '.join(_AXES)}, got {axis!r}")
    sc = load_scenario(scenario, seed=seed, settings=seed_settings(seed, rate_deg_s) + list(settings))
    plant = Plant(sc, seed)
    sensors = SunSensorModel(julian_date(sc.epoch), R_EARTH_EQ, sensor_spec or SunSensorSpec(), seed=seed)
    io = PlantIo(plant, sensors, albedo_model=albedo_model, lit_fraction=lit_fraction)
    io.has_tracker = False
    law = AdcsLaw(params={"POINTING_ACTUATOR": actuator, "SUN_SAFE_AXIS": axis, **(params or {})},
                  force_mode="SUN_SAFE")
    a = _AXES[axis]
    dt = sc.dynamics_step_s
    tick_every = int(round(law.tick_s / dt))
    sample_every = int(round(1.0 / dt))
    out = SunSafeResult()
    for k in range(int(round(duration_s / dt))):
        if k % sample_every == 0:
            t = plant.t
            reading = io.sun_vector()  # the 1 Hz reading of this second (the law sees the same one)
            assert reading is not None
            s_true = sensors.true_sun_B(t, plant.q_BN)
            out.times.append(t)
            out.eclipse.append(sensors.eclipse)
            out.pointing_deg.append(_angle_deg(a, s_true))
            w = plant.omega_BN_B
            out.rate_deg_s.append(math.degrees(math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])))
            w_a = w[0] * a[0] + w[1] * a[1] + w[2] * a[2]
            out.transverse_deg_s.append(math.degrees(math.sqrt(sum((w[i] - w_a * a[i]) ** 2 for i in range(3)))))
            if out.spin_lowered_s is None and law.law.sun_hold.lowered:
                out.spin_lowered_s = t
            if not sensors.eclipse:
                if reading[1]:
                    out.vector_deg.append(_angle_deg(reading[0], s_true))
                else:
                    out.vector_invalid_sunlit += 1
        if k % tick_every == 0:
            law.tick(io)
        plant.step(dt)
    out.transitions = list(law.transitions)
    out.bias_estimate_deg_s = tuple(math.degrees(b) for b in law.law.sun_bias.bias)
    out.bias_true_deg_s = tuple(sc.gyro.bias_dps)
    out.sun_body_end = tuple(sensors.true_sun_B(plant.t, plant.q_BN))
    return out


def vector_errors_from_run(run_dir, scenario: str = "adcs", channel: str = "SunVector") -> tuple[list, int]:
    """:func:`vector_errors_by_second` without the seconds: ``([error deg at each valid sunlit reading], invalid
    sunlit readings)``."""
    timed, invalid = vector_errors_by_second(run_dir, scenario, channel)
    return [e for _, e in timed], invalid


def vector_errors_by_second(run_dir, scenario: str = "adcs", channel: str = "SunVector") -> tuple[list, int]:
    """The ADCS component's Sun vector in a ``fprime-lite run`` of ``deployments/adcs_ref`` against the truth:
    ``([(s from the run's start, error deg) at each valid sunlit reading], invalid sunlit readings)``. Reads
    ``channels.csv`` (``channel``: SunVector, the published one, or SunVectorRaw, the one before the albedo
    correction; SunVectorValid; 1 Hz) and ``truth.csv`` (``q_BN`` and the power model's eclipse flag at 1 s); the
    Sun from ``sim.sun`` at the scenario's epoch; a reading within 1 s of an eclipse boundary is left out (the flag
    is the power model's over 100 ms steps)."""
    import csv
    import json
    import pathlib

    from detumble.sim.sun import sun_direction_N
    from detumble.sim.vec import rotate_n_to_b

    run = pathlib.Path(run_dir)
    jd0 = julian_date(load_scenario(scenario).epoch)
    truth = {}
    with open(run / "truth.csv", newline="") as f:
        for row in csv.DictReader(f):
            t = float(row["t_s"])
            if t == int(t):
                truth[int(t)] = ((float(row["q0"]), float(row["q1"]), float(row["q2"]), float(row["q3"])),
                                 row["eclipse"] == "1")
    vectors, valid = {}, {}
    t0 = None
    with open(run / "channels.csv", newline="") as f:
        for row in csv.DictReader(f):
            name = row["channel"]
            if not name.endswith(".adcs." + channel) and not name.endswith(".adcs.SunVectorValid"):
                continue
            stamp = float(row["time"])
            t0 = stamp if t0 is None else t0
            k = int(round(stamp - t0))
            if name.endswith(channel):
                vectors[k] = json.loads(row["value"])
            else:
                valid[k] = row["value"] == "1"
    errors, invalid = [], 0
    for k, v in sorted(vectors.items()):
        near = [truth.get(k + d) for d in (-1, 0, 1)]
        here = near[1]
        if here is None or any(n is None or n[1] for n in near):
            continue
        q = here[0]
        s_B = rotate_n_to_b(q, sun_direction_N(jd0 + k / 86400.0)[0])
        if valid.get(k):
            errors.append((k, _angle_deg(v, s_B)))
        else:
            invalid += 1
    return errors, invalid


def pointing_from_run(run_dir, axis: str = "PLUS_Z", scenario: str = "adcs") -> SunSafeResult:
    """The true angle between ``axis`` and the Sun, once a second, over a ``fprime-lite run`` of
    ``deployments/adcs_ref`` (``truth.csv``: ``q_BN`` and the power model's eclipse flag), as a
    :class:`SunSafeResult` (no Sun-vector samples) so its acquisition and steady statistics read the same."""
    import csv
    import pathlib

    from detumble.sim.sun import sun_direction_N
    from detumble.sim.vec import rotate_n_to_b

    if axis not in _AXES:
        raise ValueError(f"axis must be one of {', '.join(_AXES)}, got {axis!r}")
    a = _AXES[axis]
    jd0 = julian_date(load_scenario(scenario).epoch)
    out = SunSafeResult()
    with open(pathlib.Path(run_dir) / "truth.csv", newline="") as f:
        for row in csv.DictReader(f):
            t = float(row["t_s"])
            if t != int(t):
                continue
            q = (float(row["q0"]), float(row["q1"]), float(row["q2"]), float(row["q3"]))
            out.times.append(t)
            out.eclipse.append(row["eclipse"] == "1")
            out.pointing_deg.append(_angle_deg(a, rotate_n_to_b(q, sun_direction_N(jd0 + t / 86400.0)[0])))
            out.rate_deg_s.append(float(row["rate_deg_s"]))
    out.spin_lowered_s = _spin_lowered_from_events(pathlib.Path(run_dir) / "events.log", load_scenario(scenario).epoch)
    return out


def _spin_lowered_from_events(path, epoch) -> float | None:
    """Seconds from ``epoch`` (a UTC datetime) of the first SunSpinLowered in a run's ``events.log`` (None: none,
    or no log)."""
    import datetime

    if not path.is_file():
        return None
    for line in path.read_text().splitlines():
        stamp, _, rest = line.partition(" ")
        if rest.split(" ", 1)[0].endswith(".SunSpinLowered"):
            when = datetime.datetime.fromisoformat(stamp.replace("Z", "+00:00"))
            return (when - epoch).total_seconds()
    return None


def _percentile(values, p: float) -> float:
    if not values:
        return math.nan
    s = sorted(values)
    return s[min(len(s) - 1, int(math.ceil(p / 100.0 * len(s))) - 1)]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m detumble.sim.sun_safe_check", description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=5, help="fly seeds 1..N (tumble axis, attitude, sensor noise)")
    ap.add_argument("--actuator", default="ANY", choices=("ANY", "WHEELS", "MAGNETORQUERS"))
    ap.add_argument("--axis", default="PLUS_Z", choices=tuple(_AXES))
    ap.add_argument("--duration", type=float, default=5580.0, help="s (default one orbit)")
    ap.add_argument("--rate", type=float, default=2.0, help="initial tumble, deg/s")
    ap.add_argument("--albedo", type=float, default=0.0, help="Earth's Bond albedo on the light sensors (0.30: "
                    "the Earth's mean; default 0, none)")
    ap.add_argument("--albedo-model", type=float, default=0.0, metavar="A",
                    help="take the Earth's albedo out of the Sun vector with this Bond albedo (control.albedo: TRIAD "
                    "on the Sun vector and the magnetometer); default 0, no correction")
    ap.add_argument("--penumbra", action="store_true", help="the conical shadow (penumbra) instead of the cylinder")
    ap.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                    help="an attitude-controller parameter by its flight name (e.g. SUN_HOLD_ANGLE=0: no spin-down); "
                    "repeatable")
    ap.add_argument("--spin-down", action="store_true", help="instead: the coils' automatic spin-down (SUN_HOLD_*): "
                    "acquisition, when the spin was lowered, and the pointing and body rate from then to the end of "
                    "the first sunlit part (sets --actuator MAGNETORQUERS)")
    ap.add_argument("--json", metavar="FILE", help="also keep the table's figures in FILE (JSON)")
    ap.add_argument("--from-run", metavar="DIR", help="instead: a fprime-lite run of adcs_ref against its truth: "
                    "--axis to the Sun (acquisition, steady statistics) and the ADCS Sun vector")
    ap.add_argument("--vector-channel", default="SunVector", choices=("SunVector", "SunVectorRaw"),
                    help="with --from-run: the ADCS channel read (SunVectorRaw: before the albedo correction)")
    args = ap.parse_args(argv)
    try:
        spec = SunSensorSpec(albedo=args.albedo, penumbra=args.penumbra)
    except ValueError as exc:
        ap.error(str(exc))
    if not (math.isfinite(args.albedo_model) and 0.0 <= args.albedo_model < 1.0):
        ap.error(f"--albedo-model must be a Bond albedo in [0, 1) (the Earth's mean: 0.30), got {args.albedo_model}")
    if args.from_run:
        import pathlib

        missing = [n for n in ("truth.csv", "channels.csv") if not (pathlib.Path(args.from_run) / n).is_file()]
        if missing:
            ap.error(f"--from-run {args.from_run}: no {' or '.join(missing)} there; give the output folder of a "
                     "finished `fprime-lite run deployments/adcs_ref/topology.yaml --out DIR`")
        errs, invalid = vector_errors_from_run(args.from_run, channel=args.vector_channel)
        if not errs:
            print(f"{args.from_run}: no sunlit ADCS SunVector readings found")
            return 1
        import json

        summary = pathlib.Path(args.from_run) / "summary.json"
        if summary.exists():
            modes = json.loads(summary.read_text()).get("control_mode_transitions") or []
            print("modes: " + (", ".join(f"{m['mode']} at {m['t_s']:.1f} s" for m in modes) or "none"))
        run = pointing_from_run(args.from_run, args.axis)
        part, acq, steady = run.first_sunlit_part(), run.acquisition_s(), run.steady_sunlit()
        parts = run.sunlit_parts()
        re_acq = run.acquisition_s(part_index=1) if len(parts) > 1 else None
        print(f"{args.axis} to the true Sun: first sunlit part {part[0]:.0f}–{part[1]:.0f} s, acquisition ≤ "
              f"{POINTING_THRESHOLD_DEG:g}° " + ("never" if acq is None else f"{acq:.0f} s") +
              (f", after it median {statistics.median(steady):.2f}, p95 {_percentile(steady, 95):.2f}, max "
               f"{max(steady):.2f} deg" if steady else "") +
              ("" if len(parts) < 2 else ", after the eclipse: reacquisition " +
               ("never" if re_acq is None else f"{re_acq:.0f} s")) if part else f"{args.axis}: never sunlit")
        if run.spin_lowered_s is not None:
            err, rate = run.after_spin_down()
            print(f"spin lowered (SunSpinLowered) at {run.spin_lowered_s:.1f} s" + (
                f"; from then to the first sunlit part's end: error median {statistics.median(err):.2f}, max "
                f"{max(err):.2f} deg, {100 * sum(e <= POINTING_THRESHOLD_DEG for e in err) / len(err):.1f} % within "
                f"{POINTING_THRESHOLD_DEG:g}°, |ω| below 2 °/s from {_slow_from(run.spin_lowered_s, rate)} s"
                if err else ""))
        within = sum(e <= VECTOR_THRESHOLD_DEG for e in errs) / len(errs)
        print(f"ADCS {args.vector_channel} vs truth, sunlit: {len(errs)} readings, median "
              f"{statistics.median(errs):.2f}, p95 {_percentile(errs, 95):.2f}, max {max(errs):.2f} deg; "
              f"{100 * within:.1f} % within {VECTOR_THRESHOLD_DEG:g} deg; {invalid} invalid")
        return 0
    params: dict[str, object] = {}
    for item in args.param:
        name, eq, value = item.partition("=")
        if not eq:
            ap.error(f"--param {item!r}: give NAME=VALUE, e.g. --param SUN_HOLD_ANGLE=0")
        try:
            number = float(value)
        except ValueError:
            params[name] = value  # an enumerated parameter by its member name
            continue
        row = PARAMETERS.get(name)
        if row is not None:
            units, low, high, finite = row
            if (finite and not math.isfinite(number)) or (low is not None and not number >= low) or (
                    high is not None and not number <= high):
                ap.error(f"--param {name}={value}: outside its range {low}…{high} {units}")
        params[name] = number
    try:
        checked_parameters(params)
    except ValueError as exc:
        ap.error(f"--param: {exc}")
    args.params = params
    if args.spin_down:
        return _spin_down_table(args, spec)
    figures = table(args.seeds, rate_deg_s=args.rate, duration_s=args.duration, actuator=args.actuator,
                    axis=args.axis, sensor_spec=spec, albedo_model=args.albedo_model, params=args.params)
    if args.json is not None:
        _write_json(args, figures)
    print(markdown(figures), end="")
    return 0


def _stats(values: list[float]) -> dict | None:
    """median / p95 / max of ``values`` (deg), None for none."""
    if not values:
        return None
    return {"median": statistics.median(values), "p95": _percentile(values, 95), "max": max(values)}


def table(seeds: int, **fly_args) -> dict:
    """Seeds 1..``seeds`` flown by :func:`fly` (``fly_args``): per seed the first sunlit part (s), the acquisition
    and reacquisition (s from the part's start; None: never; reacquisition absent with one sunlit part), the steady
    pointing error and the Sun vector's error (deg, :func:`_stats`), the share of sunlit readings within
    VECTOR_THRESHOLD_DEG and the invalid sunlit readings; and the pooled Sun vector statistics."""
    rows, pooled = [], []
    for seed in range(1, seeds + 1):
        r = fly(seed, **fly_args)
        parts = r.sunlit_parts()
        vec = r.vector_deg
        pooled += vec
        rows.append({"seed": seed, "first_sunlit_part_s": r.first_sunlit_part(), "acquisition_s": r.acquisition_s(),
                     "steady_deg": _stats(r.steady_sunlit()),
                     "reacquisition_s": r.acquisition_s(part_index=1) if len(parts) > 1 else None,
                     "sunlit_parts": len(parts), "vector_deg": _stats(vec),
                     "vector_within": sum(v <= VECTOR_THRESHOLD_DEG for v in vec) / len(vec) if vec else None,
                     "vector_invalid_sunlit": r.vector_invalid_sunlit})
    return {"rows": rows, "pooled_vector_deg": _stats(pooled), "pooled_readings": len(pooled),
            "fly": {k: v for k, v in fly_args.items() if k != "sensor_spec" and not (k == "params" and not v)}}


def markdown(figures: dict) -> str:
    """The table :func:`table` measured, as the page prints it."""
    def three(st) -> str:
        return "—" if st is None else f"{st['median']:.2f} / {st['p95']:.2f} / {st['max']:.2f}"

    lines = ["| seed | first sunlit part (s) | acquisition ≤ 10° (s) | after it: median / p95 / max (deg) | "
             "after the eclipse: reacquisition (s) | Sun vector median / p95 / max (deg) | sunlit readings ≤ 5° | "
             "invalid sunlit readings |", "|---|---|---|---|---|---|---|---|"]
    for r in figures["rows"]:
        part = r["first_sunlit_part_s"]
        part_s = "none" if part is None else f"{part[0]:.0f}–{part[1]:.0f}"
        acq_s = "never" if r["acquisition_s"] is None else f"{r['acquisition_s']:.0f}"
        re_s = "—" if r["sunlit_parts"] < 2 else (
            "never" if r["reacquisition_s"] is None else f"{r['reacquisition_s']:.0f}")
        within = "—" if r["vector_within"] is None else f"{100 * r['vector_within']:.1f} %"
        lines.append(f"| {r['seed']} | {part_s} | {acq_s} | {three(r['steady_deg'])} | {re_s} | "
                     f"{three(r['vector_deg'])} | {within} | {r['vector_invalid_sunlit']} |")
    pooled = figures["pooled_vector_deg"]
    if pooled is not None:
        lines += ["", f"all seeds: Sun vector p95 {pooled['p95']:.2f} deg, max {pooled['max']:.2f} deg over "
                  f"{figures['pooled_readings']} sunlit readings"]
    return "\n".join(lines) + "\n"


def _slow_from(t0: float, rate: list, limit: float = 2.0) -> str:
    """When the 1 Hz body rates ``rate`` (deg/s, from ``t0`` s) go below ``limit`` for good: "t s" or "never"."""
    last_fast = max((i for i, w in enumerate(rate) if not w < limit), default=None)
    return "never" if last_fast == len(rate) - 1 else f"{t0 + (0 if last_fast is None else last_fast + 1):.0f}"


def spin_down_row(seed: int, r: SunSafeResult, limit_deg_s: float = 2.0) -> dict:
    """One coil flight's spin-down figures: the first sunlit part (s), the acquisition (s from its start; None:
    never), when the spin was lowered (s; None: never), the true pointing error from then to the part's end (deg,
    median / p95 / max; None: not lowered in the part) and its share within POINTING_THRESHOLD_DEG, when the true body
    rate went below ``limit_deg_s`` (deg/s; the star tracker's smear limit) for good in that stretch (s; None: never,
    or not lowered), and the reacquisition after the eclipse (s from the second sunlit part's start; None: never;
    absent with one sunlit part)."""
    parts = r.sunlit_parts()
    err, rate = r.after_spin_down()
    slow = _slow_from(r.spin_lowered_s, rate, limit_deg_s) if err and r.spin_lowered_s is not None else None
    return {"seed": seed, "first_sunlit_part_s": r.first_sunlit_part(), "acquisition_s": r.acquisition_s(),
            "spin_lowered_s": r.spin_lowered_s, "after_deg": _stats(err),
            "within": sum(e <= POINTING_THRESHOLD_DEG for e in err) / len(err) if err else None,
            "slow_from_s": None if slow in (None, "never") else float(slow), "slow_never": slow == "never",
            "sunlit_parts": len(parts),
            "reacquisition_s": r.acquisition_s(part_index=1) if len(parts) > 1 else None}


def spin_down_table(seeds, **fly_args) -> dict:
    """Seeds ``seeds`` (an iterable of ints) flown on the coils by :func:`fly` (``fly_args``; the actuator is set to
    MAGNETORQUERS), one :func:`spin_down_row` each, and the controller parameters the flights used."""
    from detumble.control.attitude_defaults import DEFAULTS

    fly_args = {**fly_args, "actuator": "MAGNETORQUERS"}
    rows = [spin_down_row(seed, fly(seed, **fly_args)) for seed in seeds]
    params = fly_args.get("params") or {}
    names = ("SUN_SPIN_RATE", "SUN_HOLD_ANGLE", "SUN_HOLD_DWELL", "SUN_HOLD_SPIN_RATE", "SUN_HOLD_RAMP",
             "SUN_HOLD_FIELD_ANGLE", "SUN_HOLD_TIP_ANGLE")
    return {"rows": rows, "values": {n: params.get(n, DEFAULTS[n]) for n in names},
            "fly": {k: v for k, v in fly_args.items() if k != "sensor_spec" and not (k == "params" and not v)}}


#: The first-sunlit-part figures of a :func:`spin_down_row` (what a flight to PROBE_DURATION_S gives as a whole orbit
#: does) and that flight's duration (s): the first sunlit part is 0–2809 s
PROBE_FIELDS = ("first_sunlit_part_s", "acquisition_s", "spin_lowered_s", "after_deg", "within", "slow_from_s",
                "slow_never")
PROBE_DURATION_S = 2810.0


def spin_down_probe_row(committed: dict) -> dict:
    """Seed 1 of a ``--spin-down`` JSON file flown again to the end of its first sunlit part (one 2810 s plant-only
    flight, seconds) with the file's options: its :func:`spin_down_row` as the JSON file keeps it."""
    import json

    opts = committed["options"]
    spec = SunSensorSpec(albedo=opts["albedo"], penumbra=opts["penumbra"])
    again = spin_down_table([1], rate_deg_s=opts["rate"], duration_s=PROBE_DURATION_S, axis=opts["axis"],
                            sensor_spec=spec, albedo_model=opts["albedo_model"], params=opts.get("params") or {})
    return json.loads(json.dumps(again["rows"][0]))  # tuples as lists


def spin_down_compare(row: dict, committed: dict) -> list[str]:
    """Each first-sunlit-part figure (:data:`PROBE_FIELDS`) of ``row`` against seed 1's committed row, to the float:
    the differences found (empty: none)."""
    old = committed["rows"][0]
    return [f"seed 1's {name} is {row[name]} now, {old[name]} committed" for name in PROBE_FIELDS
            if row[name] != old[name]]


def spin_down_probe(committed: dict) -> list[str]:
    """The ``--spin-down`` table's probe (``tools/studies.py --check``): :func:`spin_down_probe_row` against the
    committed seed 1 (:func:`spin_down_compare`)."""
    return spin_down_compare(spin_down_probe_row(committed), committed)


def _slow_text(row: dict) -> str:
    """"t" (s), "never", or "—" (the spin not lowered in the first sunlit part) of a :func:`spin_down_row`."""
    if row["slow_from_s"] is not None:
        return f"{row['slow_from_s']:.0f}"
    return "never" if row["slow_never"] else "—"


def spin_down_markdown(figures: dict) -> str:
    """The ``--spin-down`` table (:func:`spin_down_table`'s figures) as the page prints it."""
    v = figures["values"]
    lines = [f"SUN_HOLD_ANGLE {v['SUN_HOLD_ANGLE']:g}°, SUN_HOLD_DWELL {v['SUN_HOLD_DWELL']:g} s, SUN_HOLD_SPIN_RATE "
             f"{v['SUN_HOLD_SPIN_RATE']:g} °/s (from SUN_SPIN_RATE {v['SUN_SPIN_RATE']:g}), SUN_HOLD_RAMP "
             f"{v['SUN_HOLD_RAMP']:g} °/s², SUN_HOLD_FIELD_ANGLE {v['SUN_HOLD_FIELD_ANGLE']:g}°", "",
             "| seed | first sunlit part (s) | acquisition ≤ 10° (s) | spin lowered at (s) | from then to the "
             "part's end: error median / p95 / max (deg) | within 10° | \\|ω\\| < 2 °/s from (s) | after the "
             "eclipse: reacquisition (s) |", "|---|---|---|---|---|---|---|---|"]
    for r in figures["rows"]:
        part, acq, st = r["first_sunlit_part_s"], r["acquisition_s"], r["after_deg"]
        part_s = "none" if part is None else f"{part[0]:.0f}–{part[1]:.0f}"
        low = "never" if r["spin_lowered_s"] is None else f"{r['spin_lowered_s']:.0f}"
        three = "—" if st is None else f"{st['median']:.2f} / {st['p95']:.2f} / {st['max']:.2f}"
        within = "—" if r["within"] is None else f"{100 * r['within']:.1f} %"
        re_s = "—" if r["sunlit_parts"] < 2 else (
            "never" if r["reacquisition_s"] is None else f"{r['reacquisition_s']:.0f}")
        lines.append(f"| {r['seed']} | {part_s} | {'never' if acq is None else f'{acq:.0f}'} | {low} | {three} | "
                     f"{within} | {_slow_text(r)} | {re_s} |")
    return "\n".join(lines) + "\n"


def _spin_down_table(args, spec) -> int:
    """The ``--spin-down`` table: each seed on the coils, the spin lowered by SUN_HOLD_* (defaults, or ``--param``);
    with ``--json`` its figures (:func:`spin_down_table`) kept in that file."""
    figures = spin_down_table(range(1, args.seeds + 1), rate_deg_s=args.rate, duration_s=args.duration,
                              axis=args.axis, sensor_spec=spec, albedo_model=args.albedo_model, params=args.params)
    if args.json is not None:
        _write_json(args, figures)
    print(spin_down_markdown(figures), end="")
    return 0


def _write_json(args, figures: dict) -> None:
    """Keep ``figures`` in ``args.json`` with the command's options (and its ``--param`` values, if any)."""
    import json
    import pathlib

    from detumble.sim.runner import write_atomic

    dropped = ("json", "from_run", "vector_channel", "param", "params", "spin_down")
    options = {k: v for k, v in vars(args).items() if k not in dropped}
    if args.params:
        options["params"] = args.params
    if args.spin_down:
        options["spin_down"] = True
    pathlib.Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    write_atomic(args.json, json.dumps(dict(figures, options=options), indent=1) + "\n")


if __name__ == "__main__":
    raise SystemExit(main())
