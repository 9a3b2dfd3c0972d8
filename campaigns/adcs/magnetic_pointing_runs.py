"""The single deployment runs of docs/studies/magnetic_pointing.md (and attitude_modes.md's magnetorquer table):
``adcs_ref`` with the coils alone in POINTING, one orbit (5580 s) each, noise seed 1.

    python campaigns/adcs/magnetic_pointing_runs.py                      # every run, its table printed
    python campaigns/adcs/magnetic_pointing_runs.py --json docs/studies/magnetic_pointing/deployment.json
    python campaigns/adcs/magnetic_pointing_runs.py --only tumble hold --json FILE   # some runs (merged into FILE)

Each run is ``fprime-lite run deployments/adcs_ref/topology.yaml --duration 5580 --seq SEQ --set ...`` with SEQ
``campaigns/adcs/pointing_magnetorquers.seq`` plus the run's parameter lines before its FORCE_MODE (≈ 20 CPU-s a run
on this machine, 2026-12-04). Starts: *tumble* 0.5 °/s about the scenario's axis from the identity, 45° from the
target; *hold* at rest on the target; *corner* the hold campaign's worst corner as test ADCS-064 flies it (20° off
at 0.05 °/s), with the on-board residual-dipole estimate at the end (:func:`corner_markdown`). Rows: the present
defaults (in the scenario's field, IGRF-14 since 2026-12-04, and in the tilted dipole), seed 003's PD with its old
gains, and the first pass's parameters (K_P_MAG 1e-6, K_D_MAG 1e-4, ζ 0.7, the complementary filter, no residual
feed-forward, MAG_SETTLE_TIME 120 s or 0) in the tilted dipole they were chosen in: today's code with those
parameters, not the build of 2026-12-01. Figures (:func:`figures`): the true error over POINTING after its first
10 % from ``attitude.csv`` (the page's convention), and the run summary's own window (after acquisition).
``tools/studies.py --only magnetic_pointing_runs`` renders the pages' tables from the JSON file
(:func:`tumble_markdown`, :func:`hold_markdown`), and the error-vs-time figure from the error series each run keeps
(one POINTING sample every SERIES_STEP_S; :func:`draw_errors`, :func:`error_runs_markdown`).

*residual_ab* (its own JSON file, ``--only ab_present_on ab_present_off ab_previous_on ab_previous_off --json
docs/studies/magnetic_pointing/residual_ab.json``): a deliberate A/B of the residual-dipole compensation, the same
start (20° off at 0.05 °/s, the run that first flew the on-board estimate) and noise seed with MAG_RESIDUAL_MODE
ESTIMATE (the default) or OFF, with the present and the previous defaults, in IGRF-14 (:func:`residual_ab_markdown`).
The probes (``--check``) fly the first PROBE_S of one run again and compare its error series to the float
(:func:`probe`, :func:`ab_probe`).

Every run is the field-steering hold on the raw magnetometer reading, the default before 2026-12-05, pinned by
``pointing_magnetorquers.seq`` itself (MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0, its first lines, so a row's own lines still
win): since 2026-12-05 the coils' default hold with the star tracker is the LQR scheduled on the on-board IGRF-14
below MAG_LQR_ANGLE 50° through a 1 s bias estimate (docs/studies/magnetorquer_hold_after_acquisition.md), and these
rows document the field steering as it was flown. "Present defaults" in the rows' labels means the field steering's
present gains (K_P_MAG 4e-6, K_D_MAG 4e-4, ζ 1, MAG_SETTLE_TIME 30 s) with that pin.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
SEQ = ROOT / "campaigns" / "adcs" / "pointing_magnetorquers.seq"
DURATION_S = 5580.0
C = "ReferenceDeployment.attitudeController"
HOLD_Q = "[0.9238795325112867,0,0.3826834323650898,0]"
TUMBLE = ("initial.rate.magnitude_deg_s=0.5",)
HOLD = ("initial.rate.magnitude_deg_s=0.0", f"initial.attitude.quaternion={HOLD_Q}")
DIPOLE = ("field.model=dipole",)
#: the hold campaign's worst corner as test ADCS-064 flies it: 20° off the target, 0.05 °/s
CORNER = ("initial.rate.magnitude_deg_s=0.05",
          "initial.rate.axis=[0.6639284297189,0.7349611899967293,0.13795321456779147]",
          "initial.attitude.quaternion=[0.873197000649162,0.11579247954753936,0.46534263362703093,0.08703638932423131]")
RESIDUAL = "ReferenceDeployment.attitudeController.ResidualDipole"
#: the first pass's parameters (2026-12-01), before the second pass of section 4
FIRST = ("K_P_MAG_PRM_SET 1.0e-6", "K_D_MAG_PRM_SET 1.0e-4", "MAG_STEER_ZETA_PRM_SET 0.7",
         "MAG_RESIDUAL_MODE_PRM_SET OFF", "ESTIMATOR_PRM_SET COMPLEMENTARY", "MAG_SETTLE_TIME_PRM_SET 120.0")
NO_WAIT = ("MAG_SETTLE_TIME_PRM_SET 0.0",)
SEED_PD = ("MAG_POINTING_LAW_PRM_SET SEED_PD", "K_P_MAG_PRM_SET 2.0e-6", "K_D_MAG_PRM_SET 4.0e-4")
#: the start of the residual-dipole A/B: 20° off the target (about (0.6, −0.48, 0.64)) at 0.05 °/s about
#: (0.2, 0.9, −0.3), the run that first flew the on-board estimate (2026-12-02, by accident with the previous gains)
AB_START = ("initial.rate.magnitude_deg_s=0.05", "initial.rate.axis=[0.2,0.9,-0.3]",
            "initial.attitude.quaternion=[0.9417408211801008,0.13878745794087152,0.29986321248437037,"
            "0.06280382981867638]")
#: the previous defaults of section 4 (before the second pass): gains, ζ and the settle wait; MEKF as today
PREVIOUS = ("K_P_MAG_PRM_SET 1.0e-6", "K_D_MAG_PRM_SET 1.0e-4", "MAG_STEER_ZETA_PRM_SET 0.7",
            "MAG_SETTLE_TIME_PRM_SET 120.0")
COMP_OFF = ("MAG_RESIDUAL_MODE_PRM_SET OFF",)
#: the coils' per-axis dipole capacity (A·m², B; magnetic_pointing.md section 1)
COIL_CAPACITY_AM2 = (0.116, 0.116, 0.0087)

#: name: (start, the label the page gives, parameter lines, scenario settings), in the order flown
RUNS: dict[str, tuple[str, str, tuple[str, ...], tuple[str, ...]]] = {
    "tumble": ("tumble", "**FIELD_STEERING, present defaults** (IGRF-14)", (), TUMBLE),
    "tumble_dipole": ("tumble", "FIELD_STEERING, present defaults, in the tilted dipole", (), TUMBLE + DIPOLE),
    "hold": ("hold", "**FIELD_STEERING, present defaults** (IGRF-14)", (), HOLD),
    "hold_dipole": ("hold", "FIELD_STEERING, present defaults, in the tilted dipole", (), HOLD + DIPOLE),
    "tumble_seed_pd": ("tumble", "SEED_PD, K_P_MAG 2e-6, K_D_MAG 4e-4 (seed 003's law; first pass otherwise, "
                       "no settle wait; dipole)", FIRST + NO_WAIT + SEED_PD, TUMBLE + DIPOLE),
    "tumble_first": ("tumble", "FIELD_STEERING, first pass (MAG_SETTLE_TIME 120 s; dipole)", FIRST, TUMBLE + DIPOLE),
    "tumble_first_no_wait": ("tumble", "FIELD_STEERING, first pass, no settle wait (dipole)", FIRST + NO_WAIT,
                             TUMBLE + DIPOLE),
    "hold_first": ("hold", "FIELD_STEERING, first pass (MAG_SETTLE_TIME 120 s; dipole)", FIRST, HOLD + DIPOLE),
    "hold_first_no_wait": ("hold", "FIELD_STEERING, first pass, no settle wait (dipole)", FIRST + NO_WAIT,
                           HOLD + DIPOLE),
    "tumble_first_kd4e-5": ("tumble", "FIELD_STEERING, first pass, K_D_MAG 4e-5, no settle wait (dipole)",
                            FIRST + NO_WAIT + ("K_D_MAG_PRM_SET 4.0e-5",), TUMBLE + DIPOLE),
    "corner": ("corner", "**FIELD_STEERING, present defaults** (IGRF-14), 20° off at 0.05 °/s (test ADCS-064's start)",
               (), CORNER),
    # the residual-dipole A/B: the same start and noise seed, the on-board estimate fed forward (the default,
    # MAG_RESIDUAL_MODE ESTIMATE) or not (OFF), with the present and with the previous gains; IGRF-14
    "ab_present_on": ("residual_ab", "present defaults, **compensation on** (ESTIMATE)", (), AB_START),
    "ab_present_off": ("residual_ab", "present defaults, compensation off", COMP_OFF, AB_START),
    "ab_previous_on": ("residual_ab", "previous defaults (K_P 1e-6, K_D 1e-4, ζ 0.7, 120 s), **compensation on**",
                       PREVIOUS, AB_START),
    "ab_previous_off": ("residual_ab", "previous defaults, compensation off", PREVIOUS + COMP_OFF, AB_START),
}
#: the runs of the residual-dipole A/B (their own JSON file: ``--only`` these)
AB_RUNS = tuple(n for n, (s, *_) in RUNS.items() if s == "residual_ab")
#: the error-vs-time figure's runs (:func:`draw_errors`), with their legends
FIGURE_RUNS = {"tumble_seed_pd": "SEED_PD, K_P 2e-6, K_D 4e-4 (seed 003's law, dipole)",
               "tumble_first_kd4e-5": "first pass, K_D 4e-5, no settle wait (dipole)",
               "tumble_first_no_wait": "first pass, no settle wait (dipole)",
               "tumble_first": "first pass, 120 s settle wait (dipole)",
               "tumble": "present defaults (IGRF-14)",
               "hold_first_no_wait": "hold at rest: first pass, no settle wait (dipole)",
               "hold_first": "hold at rest: first pass (dipole)",
               "hold": "hold at rest: present defaults (IGRF-14)"}
#: the error series keeps one POINTING sample every SERIES_STEP_S (s); the probe re-flies PROBE_S of a run
SERIES_STEP_S = 10.0
PROBE_S = 300.0


def sequence(lines: tuple[str, ...]) -> str:
    """The start-up sequence of a run: pointing_magnetorquers.seq with ``lines`` (parameter sets, later ones win)
    inserted before its FORCE_MODE."""
    out = []
    for line in SEQ.read_text(encoding="utf-8").splitlines():
        if "FORCE_MODE" in line:
            out += [f"R00:00:00 {C}.{x}" for x in lines]
        out.append(line)
    return "\n".join(out) + "\n"


def fly(name: str, runs_dir: pathlib.Path, duration_s: float = DURATION_S) -> dict:
    """Fly run ``name`` (``duration_s`` simulated seconds) into ``runs_dir/name``; its figures (:func:`figures`)."""
    import shutil

    from fprime_lite.tools import run

    _, _, lines, sets = RUNS[name]
    out = runs_dir / name
    shutil.rmtree(out, ignore_errors=True)
    runs_dir.mkdir(parents=True, exist_ok=True)
    seq = runs_dir / f"{name}.seq"
    seq.write_text(sequence(lines), encoding="utf-8")
    run(TOPOLOGY, duration_s=duration_s, out=out, seq=seq, settings=list(sets))
    return figures(name, out)


def figures(name: str, out: pathlib.Path) -> dict:
    """The figures of run ``name`` from its folder ``out`` (degrees, seconds): median / p95 / max of the true
    error over the POINTING samples of ``attitude.csv`` after their first 10 % (the page's convention, numpy's
    linear percentile), and the run summary's own (``pointing_error_deg``: the samples after acquisition below
    its threshold, None when the error never stays below it)."""
    import csv

    import numpy as np

    start, _, lines, sets = RUNS[name]
    times, errors = pointing_errors(out)
    tail = np.array(errors[len(errors) // 10:])
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    e = summary.get("pointing_error_deg") or {}
    out_figures = {"start": start, "seq_lines": list(lines), "settings": list(sets), "duration_s": DURATION_S,
                   "samples": len(tail), "median_deg": float(np.median(tail)),
                   "p95_deg": float(np.percentile(tail, 95)), "max_deg": float(tail.max()), "final_deg": errors[-1],
                   "acquisition_s": e.get("acquisition_s"), "steady_median_deg": e.get("median"),
                   "steady_p95_deg": e.get("p95"), "series": series(times, errors)}
    if start in ("corner", "residual_ab"):  # the residual-dipole estimate (telemetry ResidualDipole, A·m², B)
        with open(out / "channels_wide.csv", newline="", encoding="utf-8") as f:
            rows = [r for r in csv.DictReader(f) if r.get(f"{RESIDUAL}.0")]
        from detumble.sim.scenario import load_scenario

        out_figures["residual_estimate_am2"] = [float(rows[-1][f"{RESIDUAL}.{i}"]) for i in range(3)] if rows \
            else None
        # when the feed-forward first differs from zero (s; None: never, e.g. with MAG_RESIDUAL_MODE OFF)
        out_figures["residual_ready_s"] = next((float(r["t_s"]) for r in rows
                                                if any(float(r[f"{RESIDUAL}.{i}"]) != 0.0 for i in range(3))), None)
        out_figures["residual_plant_am2"] = list(load_scenario("adcs").spacecraft.residual_dipole_am2)
    if start == "residual_ab":  # the gyro-bias estimate at 30 s and 60 s (°/s, B) and the largest dipole commanded
        with open(out / "channels_wide.csv", newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        bias, dipole = f"{C}.GyroBiasEstimate", f"{C}.CommandedDipole"
        out_figures["gyro_bias_estimate_deg_s"] = {
            f"{t:.0f}": [float(r[f"{bias}.{i}"]) for i in range(3)]
            for t in (30.0, 60.0) for r in rows if float(r["t_s"]) == t and r.get(f"{bias}.0")}
        out_figures["gyro_bias_plant_deg_s"] = list(load_scenario("adcs").gyro.bias_dps)
        commanded = [[abs(float(r[f"{dipole}.{i}"])) for i in range(3)] for r in rows if r.get(f"{dipole}.0")]
        out_figures["commanded_dipole_max_am2"] = [max(m[i] for m in commanded) for i in range(3)]
        # the share of the 1 s telemetry samples with some coil commanded at 99 % of its capacity or more
        out_figures["coil_limit_share"] = sum(
            any(m[i] >= 0.99 * COIL_CAPACITY_AM2[i] for i in range(3)) for m in commanded) / len(commanded)
    return out_figures


def pointing_errors(out: pathlib.Path) -> tuple[list[float], list[float]]:
    """The POINTING samples of a run's ``attitude.csv``: times (s) and the true pointing error (degrees)."""
    import csv

    times, errors = [], []
    with open(out / "attitude.csv", newline="", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            if r["mode"] == "POINTING" and r["pointing_error_deg"] not in ("", "nan"):
                times.append(float(r["t_s"]))
                errors.append(float(r["pointing_error_deg"]))
    return times, errors


def series(times: list[float], errors: list[float], step_s: float = SERIES_STEP_S) -> dict:
    """The error series kept for the figure: the first POINTING sample, then the first one at least ``step_s``
    after the last kept (times in s to 0.1 s, errors in degrees to 1e-3°)."""
    t_kept, e_kept = [], []
    for t, e in zip(times, errors, strict=True):
        if not t_kept or t >= t_kept[-1] + step_s - 1e-9:
            t_kept.append(round(t, 1))
            e_kept.append(round(e, 3))
    return {"step_s": step_s, "t_s": t_kept, "error_deg": e_kept}


def _cell(x, digits: int = 2) -> str:
    if x is None:
        return "—"
    return f"{x:.{digits}f}°" if x < 100 else f"{x:.1f}°"


def markdown(table: dict, start: str) -> str:
    """The table of the runs that start as ``start`` (``tumble`` or ``hold``); a run not in ``table`` is shown as
    not flown."""
    lines = ["| law and parameters | median | p95 | max | final | below 30° from (s) | after that: median / p95 |",
             "|---|---|---|---|---|---|---|"]
    for name, (s, label, _, _) in RUNS.items():
        if s != start:
            continue
        r = table["runs"].get(name)
        if r is None:
            lines.append(f"| {label} | not flown | | | | | |")
        else:
            acq = "never" if r["acquisition_s"] is None else f"{r['acquisition_s']:.0f}"
            steady = "—" if r["steady_median_deg"] is None else \
                f"{_cell(r['steady_median_deg'])} / {_cell(r['steady_p95_deg'])}"
            lines.append(f"| {label} | {_cell(r['median_deg'])} | {_cell(r['p95_deg'])} | {_cell(r['max_deg'])} | "
                         f"{_cell(r['final_deg'])} | {acq} | {steady} |")
    done = sum(1 for n, (s, *_) in RUNS.items() if s == start and n in table["runs"])
    planned = sum(1 for s, *_ in RUNS.values() if s == start)
    if done < planned:
        lines += ["", f"{done} of the {planned} runs of this table flown (`--only NAME ...` flies the others)."]
    return "\n".join(lines) + "\n"


def tumble_markdown(table: dict) -> str:
    """The from-a-tumble table (tools/studies.py renders it)."""
    return markdown(table, "tumble")


def hold_markdown(table: dict) -> str:
    """The attitude-hold table (tools/studies.py renders it)."""
    return markdown(table, "hold")


def corner_markdown(table: dict) -> str:
    """The worst-corner run with the on-board residual-dipole estimate (tools/studies.py renders it)."""
    import math

    lines = [markdown(table, "corner").rstrip("\n")]
    r = table["runs"].get("corner")
    if r is not None:
        est, plant = r["residual_estimate_am2"], r["residual_plant_am2"]
        worst = max(abs(a - b) for a, b in zip(est, plant, strict=True))
        norm = math.sqrt(sum(b * b for b in plant))
        lines += ["", f"On-board residual-dipole estimate at the end (telemetry `ResidualDipole`): "
                  f"({', '.join(f'{1e3 * x:.3f}' for x in est)})e-3 A·m², the plant's "
                  f"({', '.join(f'{1e3 * x:.1f}' for x in plant)})e-3: **{worst:.1e} A·m²** at most per axis "
                  f"({100 * worst / norm:.1f} % of \\|m\\|)."]
    return "\n".join(lines) + "\n"


def residual_ab_markdown(table: dict) -> str:
    """The residual-dipole A/B: the same start and noise seed with the on-board estimate fed forward or not
    (tools/studies.py renders it)."""
    import math

    lines = [markdown(table, "residual_ab").rstrip("\n")]
    pairs = (("present", "ab_present_on", "ab_present_off"), ("previous", "ab_previous_on", "ab_previous_off"))
    for gains, on, off in pairs:
        a, b = table["runs"].get(off), table["runs"].get(on)
        if a is None or b is None:
            continue
        lines.append(f"{'' if gains == 'previous' else chr(10)}- {gains} defaults, compensation off → on: median "
                     f"{_cell(a['median_deg'])} → **{_cell(b['median_deg'])}**, p95 {_cell(a['p95_deg'])} → "
                     f"{_cell(b['p95_deg'])}, final {_cell(a['final_deg'])} → {_cell(b['final_deg'])}")
    est = [(n, table["runs"][n]["residual_estimate_am2"]) for n in ("ab_present_on", "ab_previous_on")
           if n in table["runs"] and table["runs"][n].get("residual_estimate_am2")]
    for n, e in est:
        plant = table["runs"][n]["residual_plant_am2"]
        worst = max(abs(x - y) for x, y in zip(e, plant, strict=True))
        norm = math.sqrt(sum(x * x for x in plant))
        ready = table["runs"][n].get("residual_ready_s")
        lines.append(f"- {RUNS[n][1].split(' ')[0]} defaults' on-board estimate (telemetry `ResidualDipole`): "
                     f"fed forward from {'—' if ready is None else f'{ready:.0f}'} s; at the end "
                     f"({', '.join(f'{1e3 * x:.3f}' for x in e)})e-3 A·m², **{worst:.1e} A·m²** at most per axis "
                     f"({100 * worst / norm:.1f} % of \\|m\\|) from the plant's "
                     f"({', '.join(f'{1e3 * x:.1f}' for x in plant)})e-3")
    r = table["runs"].get("ab_present_on", {})
    if r.get("gyro_bias_estimate_deg_s"):
        plant = r["gyro_bias_plant_deg_s"]
        worst = max(abs(x - y) for e in r["gyro_bias_estimate_deg_s"].values() for x, y in zip(e, plant, strict=True))
        at = "; ".join(f"({', '.join(f'{x:.4f}' for x in e)}) °/s at {t} s"
                       for t, e in r["gyro_bias_estimate_deg_s"].items())
        lines.append(f"- present defaults' gyro-bias estimate (MEKF, telemetry `GyroBiasEstimate`): {at}; at most "
                     f"**{worst:.4f} °/s** from the LSM6DSO's ({', '.join(f'{x:g}' for x in plant)}) °/s")
    for n in ("ab_previous_on", "ab_present_on"):
        r = table["runs"].get(n, {})
        if r.get("commanded_dipole_max_am2"):
            peak = ", ".join(f"{x:.4f}" for x in r["commanded_dipole_max_am2"])
            lines.append(f"- {RUNS[n][1].split(' ')[0]} defaults, compensation on: commanded dipole (telemetry "
                         f"`CommandedDipole`, 1 s samples) at most ({peak}) "
                         f"A·m² (x, y, z; capacity {', '.join(f'{x:g}' for x in COIL_CAPACITY_AM2)}); some coil at "
                         f"≥ 99 % of its capacity in **{100 * r['coil_limit_share']:.1f} %** of the samples")
    return "\n".join(lines) + "\n"


def _first_index(times: list[float], t: float) -> int:
    return next((i for i, x in enumerate(times) if x >= t), len(times))


def error_runs_markdown(table: dict) -> str:
    """The figures the page quotes from the error-vs-time figure (:func:`draw_errors`), from the kept series
    (one sample every SERIES_STEP_S: the extremes are those of the kept samples)."""
    lines = []
    r = table["runs"].get("tumble_first_no_wait", {}).get("series")
    if r:
        t, e = r["t_s"], r["error_deg"]
        i = max(range(_first_index(t, 405.0)), key=e.__getitem__)
        lines.append(f"- first pass, no settle wait, from the tumble: largest error in POINTING's first 400 s "
                     f"**{e[i]:.0f}°** at {t[i]:.0f} s (the statistics start after the first 10 % of POINTING, "
                     f"≈ {t[0] + 0.1 * (t[-1] - t[0]):.0f} s)")
    r = table["runs"].get("tumble_first_kd4e-5", {}).get("series")
    if r:
        t, e = r["t_s"], r["error_deg"]
        i = min(range(len(e)), key=e.__getitem__)
        j = max(range(i, len(e)), key=e.__getitem__)
        lines.append(f"- first pass with K_D_MAG 4e-5, no settle wait: smallest error **{e[i]:.1f}°** at {t[i]:.0f} s, "
                     f"then thrown off again: {e[j]:.0f}° at {t[j]:.0f} s")
    r = table["runs"].get("tumble_seed_pd", {}).get("series")
    if r:
        e = r["error_deg"]
        lines.append(f"- seed 003's PD: error {min(e):.0f}–{max(e):.0f}° over POINTING (never below 30°)"
                     if min(e) >= 30.0 else f"- seed 003's PD: smallest error {min(e):.1f}° over POINTING")
    late = []
    for name in ("tumble", "hold"):
        r = table["runs"].get(name, {}).get("series")
        if r:
            t, e = r["t_s"], r["error_deg"]
            i = max(range(_first_index(t, 1000.0), len(e)), key=e.__getitem__)
            late.append(f"{'from the tumble' if name == 'tumble' else 'at rest'} {e[i]:.1f}° at {t[i]:.0f} s")
    if late:
        lines.append(f"- present defaults (IGRF-14), largest error after the first 1000 s: {', '.join(late)}")
    missing = [n for n in FIGURE_RUNS if not table["runs"].get(n, {}).get("series")]
    if missing:
        lines.append(f"- not in the figure (no error series kept: `--only {' '.join(missing)}` flies them): "
                     f"{', '.join(missing)}")
    return "\n".join(lines) + "\n"


def draw_errors(table: dict, out: pathlib.Path) -> pathlib.Path:
    """The true pointing error against time of FIGURE_RUNS, from their kept series, into
    ``out/pointing_error_runs.png``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(10, 5.4))
    for name, label in FIGURE_RUNS.items():
        r = table["runs"].get(name, {}).get("series")
        if r:
            ax.plot(r["t_s"], r["error_deg"], lw=1.1 if name in ("tumble", "hold") else 0.9, label=label,
                    ls="-" if RUNS[name][0] == "tumble" else "--")
    ax.axhline(5.0, color="k", ls="--", lw=0.6)
    ax.axhline(15.0, color="k", ls=":", lw=0.6)
    ax.set_yscale("log")
    ax.set_ylim(0.05, 200)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("pointing error (deg, truth)")
    ax.set_title("adcs_ref, magnetorquers only, POINTING forced at 5 s: 0.5 deg/s start 45 deg off (solid) "
                 "or at rest on the target (dashed)", fontsize=9)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3)
    fig.tight_layout()
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "pointing_error_runs.png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    return out / "pointing_error_runs.png"


def probe_run(committed: dict, name: str) -> list[str]:
    """Fly the first PROBE_S of run ``name`` again and compare its error series with the committed one's first
    samples, to the float (a few CPU-s)."""
    import tempfile

    kept = committed["runs"].get(name, {}).get("series")
    if not kept:
        return [f"run {name} has no committed error series"]
    with tempfile.TemporaryDirectory() as scratch:
        fly(name, pathlib.Path(scratch), duration_s=PROBE_S)
        again = series(*pointing_errors(pathlib.Path(scratch) / name), step_s=kept["step_s"])
    n = _first_index(kept["t_s"], PROBE_S - kept["step_s"])
    now = list(zip(again["t_s"], again["error_deg"], strict=True))[:n]
    then = list(zip(kept["t_s"], kept["error_deg"], strict=True))[:n]
    if now != then:
        i = next((k for k, (a, b) in enumerate(zip(now, then, strict=False)) if a != b), min(len(now), len(then)))
        shown = now[i] if i < len(now) else None
        return [f"run {name}'s first {PROBE_S:.0f} s: (t, error) {shown} now, "
                f"{then[i] if i < len(then) else None} committed"]
    return []


def probe(committed: dict) -> list[str]:
    """The deployment runs' probe: the present defaults' tumble, its first PROBE_S flown again."""
    return probe_run(committed, "tumble")


def ab_probe(committed: dict) -> list[str]:
    """The A/B's probe: the compensated present-defaults run, its first PROBE_S flown again."""
    return probe_run(committed, "ab_present_on")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", type=pathlib.Path, metavar="FILE", help="also keep the figures in FILE (merged)")
    ap.add_argument("--only", nargs="+", choices=list(RUNS), help="these runs only")
    ap.add_argument("--from-runs", action="store_true",
                    help="do not fly: read the figures of the runs already in --runs (those that finished)")
    ap.add_argument("--runs", type=pathlib.Path, default=ROOT / "runs" / "magnetic_pointing",
                    help="where the runs' folders go (default runs/magnetic_pointing)")
    args = ap.parse_args(argv)
    table = {"script": "campaigns/adcs/magnetic_pointing_runs.py", "runs": {}}
    if args.json is not None and args.json.exists():
        table = json.loads(args.json.read_text(encoding="utf-8"))
    for name in args.only or list(RUNS):
        if args.from_runs:
            if not (args.runs / name / "summary.json").exists():
                continue
            table["runs"][name] = figures(name, args.runs / name)
        else:
            table["runs"][name] = fly(name, args.runs)
        print(f"{name}: {table['runs'][name]}", flush=True)
        if args.json is not None:
            from fprime_lite.osal.atomic import atomic_write_json

            table["runs"] = {n: table["runs"][n] for n in RUNS if n in table["runs"]}
            atomic_write_json(args.json, table)
    for start in ("tumble", "hold"):
        print(markdown(table, start))
    print(corner_markdown(table))
    if any(n in table["runs"] for n in AB_RUNS):
        print(residual_ab_markdown(table))
    return 0


if __name__ == "__main__":
    sys.exit(main())
