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
(:func:`tumble_markdown`, :func:`hold_markdown`).
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
}


def sequence(lines: tuple[str, ...]) -> str:
    """The start-up sequence of a run: pointing_magnetorquers.seq with ``lines`` (parameter sets, later ones win)
    inserted before its FORCE_MODE."""
    out = []
    for line in SEQ.read_text(encoding="utf-8").splitlines():
        if "FORCE_MODE" in line:
            out += [f"R00:00:00 {C}.{x}" for x in lines]
        out.append(line)
    return "\n".join(out) + "\n"


def fly(name: str, runs_dir: pathlib.Path) -> dict:
    """Fly run ``name`` into ``runs_dir/name``; its figures (:func:`figures`)."""
    import shutil

    from fprime_lite.tools import run

    _, _, lines, sets = RUNS[name]
    out = runs_dir / name
    shutil.rmtree(out, ignore_errors=True)
    runs_dir.mkdir(parents=True, exist_ok=True)
    seq = runs_dir / f"{name}.seq"
    seq.write_text(sequence(lines), encoding="utf-8")
    run(TOPOLOGY, duration_s=DURATION_S, out=out, seq=seq, settings=list(sets))
    return figures(name, out)


def figures(name: str, out: pathlib.Path) -> dict:
    """The figures of run ``name`` from its folder ``out`` (degrees, seconds): median / p95 / max of the true
    error over the POINTING samples of ``attitude.csv`` after their first 10 % (the page's convention, numpy's
    linear percentile), and the run summary's own (``pointing_error_deg``: the samples after acquisition below
    its threshold, None when the error never stays below it)."""
    import csv

    import numpy as np

    start, _, lines, sets = RUNS[name]
    with open(out / "attitude.csv", newline="", encoding="utf-8") as f:
        errors = [float(r["pointing_error_deg"]) for r in csv.DictReader(f)
                  if r["mode"] == "POINTING" and r["pointing_error_deg"] not in ("", "nan")]
    tail = np.array(errors[len(errors) // 10:])
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    e = summary.get("pointing_error_deg") or {}
    out_figures = {"start": start, "seq_lines": list(lines), "settings": list(sets), "duration_s": DURATION_S,
                   "samples": len(tail), "median_deg": float(np.median(tail)),
                   "p95_deg": float(np.percentile(tail, 95)), "max_deg": float(tail.max()), "final_deg": errors[-1],
                   "acquisition_s": e.get("acquisition_s"), "steady_median_deg": e.get("median"),
                   "steady_p95_deg": e.get("p95")}
    if start == "corner":  # the on-board residual-dipole estimate (telemetry ResidualDipole, A·m², B) at the end
        with open(out / "channels_wide.csv", newline="", encoding="utf-8") as f:
            rows = [r for r in csv.DictReader(f) if r.get(f"{RESIDUAL}.0")]
        from detumble.sim.scenario import load_scenario

        out_figures["residual_estimate_am2"] = [float(rows[-1][f"{RESIDUAL}.{i}"]) for i in range(3)]
        out_figures["residual_plant_am2"] = list(load_scenario("adcs").spacecraft.residual_dipole_am2)
    return out_figures


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
    return 0


if __name__ == "__main__":
    sys.exit(main())
