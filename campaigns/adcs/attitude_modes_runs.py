"""Seed 003's attitude modes on adcs_ref: the two flights behind docs/studies/attitude_modes.md's shipped-sequence
and wheel-orbit tables and their six figures, kept small enough to commit.

* ``shipped``: ``fprime-lite run deployments/adcs_ref/topology.yaml --duration 6000`` (the shipped start-up:
  DETUMBLE from 30 °/s → SPIN_STABLE → POINTING);
* ``orbit``: one orbit (5580 s) of POINTING on the wheels from a 0.5 °/s tumble, :data:`WHEELS_SEQ` (POINTING at
  5 s, a 90° target change at 1200 s).

Each flight keeps (``--json``): the figures its table quotes (from the run's ``summary.json`` and ``events.log``),
the coil dipole of its truth log binned as the run's own ``dipole.png`` bins it (300 bins: mean and range of the
exact interval means, A·m²), and, for the ``--check`` probe, the first :data:`PROBE_S` s of its ``attitude.csv`` at
full precision. The figures' traces go beside it, ``<flight>_trace.csv.gz``: ``attitude.csv`` thinned to about
6000 rows, every second 0.5 s sample (the shipped flight's are the rows its run's plotter drew; the orbit's plotter
drew all 11,160), with the columns the figures need (time s, mode, pointing and spin-axis error deg, wheel momenta
N·m·s), numbers to 6 significant digits.
:func:`draw` draws the page's figures from these files with the run's own plotter
(``detumble.reports.attitude_report.plot_attitude_csv``) and the dipole panel of ``detumble.reports.plots``.

    python campaigns/adcs/attitude_modes_runs.py [--json FILE] [--runs DIR]

``--runs DIR`` flies into DIR/<flight> (kept) or uses a finished flight found there. Two deployment runs (about
7 CPU-minutes on this machine unloaded).
"""

from __future__ import annotations

import argparse
import csv
import gzip
import io
import json
import math
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
_C = "ReferenceDeployment.attitudeController"
WHEELS_SEQ = (f"R00:00:00 {_C}.SET_TARGET_QUATERNION 0.9238795325112867 0 0.3826834323650898 0\n"
              f"R00:00:05 {_C}.FORCE_MODE POINTING\n"
              f"R00:20:00 {_C}.SET_TARGET_QUATERNION 0.6532814824381883 0.6532814824381882 "
              f"0.2705980500730985 -0.2705980500730985\n")
#: flight → (duration s, sequence text or None, --set lines)
FLIGHTS = {"shipped": (6000.0, None, ()), "orbit": (5580.0, WHEELS_SEQ, ("initial.rate.magnitude_deg_s=0.5",))}
#: s of each flight's attitude.csv kept at full precision for the probe
PROBE_S = 30.0
#: attitude.csv's columns the figures draw (the first ten are the file's own, as read_attitude_csv wants them)
TRACE_COLUMNS = ("t_s", "mode", "pointing_error_deg", "spin_axis_error_deg", "h0_nms", "h1_nms", "h2_nms", "h3_nms")
PROBE_COLUMNS = ("t_s", "mode", "pointing_error_deg", "spin_axis_error_deg", "spin_rate_deg_s", "rate_deg_s",
                 "h0_nms", "h1_nms", "h2_nms", "h3_nms")
_LIMIT_EVENTS = ("WheelLimitReached", "TorqueSaturated", "MomentumSaturated")


def fly(name: str, out: pathlib.Path, duration_s: float | None = None) -> None:
    """One ``fprime-lite run`` of adcs_ref into ``out``: flight ``name`` (its own duration unless given)."""
    duration, seq, sets = FLIGHTS[name]
    cmd = [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(TOPOLOGY), "--duration",
           f"{duration if duration_s is None else duration_s:g}", "--out", str(out), "--no-progress", "--no-plots",
           "--allow-warnings"]
    out.mkdir(parents=True, exist_ok=True)
    if seq is not None:
        (out.parent / f"{name}.seq").write_text(seq, encoding="utf-8")
        cmd += ["--seq", str(out.parent / f"{name}.seq")]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)


def _rows(run_dir: pathlib.Path) -> tuple[list[str], list[list[str]]]:
    with open(run_dir / "attitude.csv", encoding="utf-8", newline="") as f:
        reader = csv.reader(f)
        return next(reader), list(reader)


def probe_rows(run_dir: pathlib.Path) -> list[list]:
    """The first :data:`PROBE_S` s of the run's ``attitude.csv`` (:data:`PROBE_COLUMNS`, numbers as floats, NaN as
    None), as the JSON file keeps them."""
    header, rows = _rows(run_dir)
    idx = [header.index(c) for c in PROBE_COLUMNS]
    out = []
    for r in rows:
        if float(r[0]) > PROBE_S:
            break
        out.append([r[k] if c == "mode" else (None if not r[k] or math.isnan(float(r[k])) else float(r[k]))
                    for k, c in zip(idx, PROBE_COLUMNS, strict=True)])
    return out


def trace_text(run_dir: pathlib.Path) -> str:
    """The run's ``attitude.csv`` thinned to about 6000 rows (every second row of these flights' 2 Hz samples;
    :data:`TRACE_COLUMNS`, 6 significant digits) as CSV text."""
    header, rows = _rows(run_dir)
    idx = [header.index(c) for c in TRACE_COLUMNS]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(TRACE_COLUMNS)
    for r in rows[::max(1, round(len(rows) / 6000))]:
        writer.writerow([r[k] if c == "mode" or not r[k] else f"{float(r[k]):.6g}"
                         for k, c in zip(idx, TRACE_COLUMNS, strict=True)])
    return out.getvalue()


def dipole_bins(run_dir: pathlib.Path) -> dict:
    """The truth log's coil dipole read and binned as ``detumble.reports.plots`` does for ``dipole.png``: bin centres
    (s) and per axis the mean, least and largest of the exact interval means in each bin (A·m², 6 significant
    digits)."""
    import numpy as np

    from detumble.reports.figures import read_truth

    truth = read_truth(run_dir / "truth.csv")  # thinned as the run's plotter thins it, the means kept exact
    data = np.array([truth[c] for c in ("t_s", "m_mean_x_Am2", "m_mean_y_Am2", "m_mean_z_Am2")], dtype=float).T
    t = data[:, 0]
    bins = max(1, min(300, (len(t) - 1) // 4))
    edges = np.linspace(1, len(t), bins + 1).astype(int)  # row 0 closes no interval
    pairs = [(a, b) for a, b in zip(edges[:-1], edges[1:], strict=True) if b > a]
    out: dict = {"span_s": [float(t[0]), float(t[-1])], "per_bin": (len(t) - 1) / bins,
                 "centre_s": [float(f"{0.5 * (t[a - 1] + t[b - 1]):.6g}") for a, b in pairs]}
    for k, axis in enumerate("xyz", start=1):
        chunks = [data[a:b, k] for a, b in pairs]
        out[axis] = {stat: [float(f"{float(getattr(c, stat)()):.6g}") for c in chunks]
                     for stat in ("mean", "min", "max")}
    return out


def figures(name: str, run_dir: pathlib.Path) -> dict:
    """Flight ``name``'s figures from its run folder (summary.json, events.log, attitude.csv, truth.csv)."""
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    wheels = Plant(load_scenario("adcs"), 0).wheels
    summary = json.loads((run_dir / "summary.json").read_text(encoding="utf-8"))
    events = (run_dir / "events.log").read_text(encoding="utf-8")
    slews = summary.get("slews") or []
    pointing = summary.get("pointing_error_deg") or {}
    return {"duration_s": FLIGHTS[name][0], "sequence": FLIGHTS[name][1], "settings": list(FLIGHTS[name][2]),
            "modes": [{"t_s": m["t_s"], "mode": m["mode"]} for m in summary.get("control_mode_transitions") or []],
            "spin_settled_s": summary.get("spin_settled_s"),
            "pointing_error_deg": {k: pointing.get(k) for k in ("median", "p95", "max", "samples", "window_s")},
            "wheel_momentum_max_fraction": summary.get("wheel_momentum_max_fraction"),
            "first_slew_settle_s": slews[0].get("settle_below_0p1_deg_s") if slews else None,
            "limit_events": sum(events.count(e) for e in _LIMIT_EVENTS),
            "wheel_capacity_nms": [] if wheels is None else [float(h) for h in wheels.h_max],
            "dipole": dipole_bins(run_dir), "probe": probe_rows(run_dir)}


def _fmt(value, digits: int = 0) -> str:
    return "—" if value is None else f"{value:,.{digits}f}"


def _flight(table: dict, name: str) -> dict:
    flight = table["flights"].get(name)
    duration, seq, sets = FLIGHTS[name]
    if flight is None or (flight["duration_s"], flight["sequence"], flight["settings"]) != (duration, seq, list(sets)):
        raise ValueError(f"flight {name!r} is missing or was flown otherwise: fly the script again")
    return flight


def shipped_markdown(table: dict) -> str:
    """The shipped sequence's table (attitude_modes.md, "The whole sequence in one run")."""
    f = _flight(table, "shipped")
    entry = {m["mode"]: m["t_s"] for m in f["modes"]}
    p = f["pointing_error_deg"]
    median, p95, worst = (_fmt(p.get(k), d) for k, d in (("median", 4), ("p95", 3), ("max", 3)))
    rows = ["| figure | value | target |", "|---|---|---|",
            "| mode transitions seen on the ground | " + ", ".join(f"{m['mode']} {m['t_s']:.1f} s" for m in f["modes"])
            + "; no other | all three, in order, no chatter |",
            f"| DETUMBLE: 30 °/s → below 1 °/s (for 5 s), SPIN_STABLE entered at | {_fmt(entry.get('SPIN_STABLE'))} s "
            "| — |",
            "| SPIN_STABLE: momentum within 5° of +Z and rate within 5 % of 1.5 °/s | "
            f"{_fmt(f['spin_settled_s'])} s after entry | ≤ 1 orbit (5578 s) |",
            f"| POINTING error, median / p95 / max | **{median}° / {p95}° / {worst}°** ({p.get('samples') or 0} "
            f"samples, {_fmt(p.get('window_s'))} s) | median ≤ 0.01°, p95 ≤ 0.05° |",
            f"| wheel momentum, largest \\|h_i\\|/h_max | {100 * (f['wheel_momentum_max_fraction'] or 0):.1f} % | "
            "< 50 % |"]
    return "\n".join(rows) + "\n"


def orbit_markdown(table: dict) -> str:
    """The wheel-pointing orbit's table (attitude_modes.md, "Pointing on the wheels for one orbit")."""
    f = _flight(table, "orbit")
    p = f["pointing_error_deg"]
    limits = f["limit_events"]
    rows = ["| figure | value | target |", "|---|---|---|",
            f"| 90° target change: settled below 0.1° (and stays) | **{_fmt(f['first_slew_settle_s'], 1)} s** | "
            "≤ 30 s |",
            "| error over the orbit (POINTING samples after the first 10 %; includes the 90° slew), median / p95 | "
            f"**{_fmt(p.get('median'), 4)}° / {_fmt(p.get('p95'), 3)}°** | median ≤ 0.01°, p95 ≤ 0.05° |",
            "| wheel momentum over the orbit, largest \\|h_i\\|/h_max | "
            f"**{100 * (f['wheel_momentum_max_fraction'] or 0):.1f} %** (magnetic dumping) | < 50 % |",
            "| wheel torque / momentum limits | " + ("never reached (no WheelLimitReached, TorqueSaturated or "
                                                   "MomentumSaturated event)" if limits == 0 else
                                                   f"{limits} limit event(s) in events.log") + " | never exceeded |"]
    return "\n".join(rows) + "\n"


def markdown(table: dict) -> str:
    return shipped_markdown(table) + "\n" + orbit_markdown(table)


def trace_path(json_path: pathlib.Path, name: str) -> pathlib.Path:
    """Flight ``name``'s trace file beside the JSON file."""
    return json_path.parent / f"{name}_trace.csv.gz"


def _draw_dipole(bins: dict, out: pathlib.Path) -> pathlib.Path:
    """``dipole.png`` as ``detumble.reports.plots`` draws it, from the committed bins."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from detumble.reports.figures import save_figure

    centres, span = bins["centre_s"], bins["span_s"]
    unit, scale = ("min", 60.0) if span[1] > 1800 else ("s", 1.0)
    tt = [c / scale for c in centres]
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(10, 6.5))
    for ax, a, colour in zip(axes, "xyz", ("tab:red", "tab:green", "tab:blue"), strict=True):
        ax.fill_between(tt, bins[a]["min"], bins[a]["max"], color=colour, alpha=0.25, lw=0,
                        label=f"range of m{a}'s interval means")
        ax.plot(tt, bins[a]["mean"], color=colour, lw=1.0, label=f"mean m{a}")
        ax.axhline(0.0, color="grey", lw=0.5)
        ax.set_ylabel(f"m{a} (A·m²)")
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=8)
        ax.grid(alpha=0.3, which="both")
        ax.set_xlim(span[0] / scale, span[1] / scale)
    axes[-1].set_xlabel(f"time since the start of the run ({unit})")
    fig.suptitle(f"Magnetorquer dipole in the body frame (truth; exact means over the sample intervals, "
                 f"{bins['per_bin']:.0f} per bin)")
    path = save_figure(fig, out / "dipole.png")
    plt.close(fig)
    return path


def draw(table: dict, json_path: pathlib.Path, name: str, out: pathlib.Path) -> list[pathlib.Path]:
    """Flight ``name``'s figures into ``out``: attitude_mode.png, pointing_error.png, wheel_momentum.png (the run's
    plotter on the committed trace) and dipole.png (from the committed bins)."""
    from detumble.reports.attitude_report import _COLUMNS, plot_attitude_csv

    flight = _flight(table, name)
    with gzip.open(trace_path(json_path, name), "rt", encoding="utf-8", newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    if tuple(header) != TRACE_COLUMNS:
        raise ValueError(f"{trace_path(json_path, name)}: columns {header}, not {TRACE_COLUMNS}")
    where = {c: k for k, c in enumerate(header)}
    capacity = flight["wheel_capacity_nms"]
    with tempfile.TemporaryDirectory() as scratch:
        csv_path = pathlib.Path(scratch) / "attitude.csv"
        with open(csv_path, "w", encoding="utf-8", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(_COLUMNS)
            for r in rows:  # the columns no figure of the page draws are left empty
                writer.writerow([r[where[c]] if c in where else "" for c in _COLUMNS])
        drawn = plot_attitude_csv(csv_path, out, capacity)
    keep = [p for p in drawn if p.name in ("attitude_mode.png", "pointing_error.png", "wheel_momentum.png")]
    return keep + [_draw_dipole(flight["dipole"], out)]


def probe_flight(committed: dict, name: str) -> list[str]:
    """Flight ``name``'s first :data:`PROBE_S` s flown again (a deployment run of seconds): its attitude.csv rows
    must be the committed probe's to the float (the differences found, empty: none)."""
    with tempfile.TemporaryDirectory() as scratch:
        run_dir = pathlib.Path(scratch) / name
        fly(name, run_dir, PROBE_S + 1.0)
        again = json.loads(json.dumps(probe_rows(run_dir)))
    old = committed["flights"][name]["probe"]
    if again == old:
        return []
    pairs = zip(again, old, strict=False)  # the first row that differs, or where the shorter ends
    first = next((i for i, (a, b) in enumerate(pairs) if a != b), min(len(again), len(old)))
    return [f"flight {name}'s attitude.csv row {first} of its first {PROBE_S:g} s differs "
            f"({again[first] if first < len(again) else 'none'} now, {old[first] if first < len(old) else 'none'} "
            "committed)"]


def shipped_probe(committed: dict) -> list[str]:
    return probe_flight(committed, "shipped")


def orbit_probe(committed: dict) -> list[str]:
    return probe_flight(committed, "orbit")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", type=pathlib.Path, metavar="FILE", help="keep the figures in FILE (JSON) and the "
                        "traces beside it")
    parser.add_argument("--runs", type=pathlib.Path, metavar="DIR", help="fly into DIR/<flight> and keep the runs, "
                        "or use a finished one found there")
    args = parser.parse_args(argv)
    flights = {}
    with tempfile.TemporaryDirectory() as scratch:
        base = args.runs or pathlib.Path(scratch)
        for name in FLIGHTS:
            run_dir = base / name
            if not (run_dir / "summary.json").exists():
                fly(name, run_dir)
            flights[name] = figures(name, run_dir)
            if args.json is not None:
                args.json.parent.mkdir(parents=True, exist_ok=True)
                with gzip.GzipFile(trace_path(args.json, name), "wb", mtime=0) as f:
                    f.write(trace_text(run_dir).encode("utf-8"))
    table = {"script": "campaigns/adcs/attitude_modes_runs.py", "flights": flights}
    print(markdown(table), end="")
    if args.json is not None:
        from detumble.sim.runner import write_atomic

        write_atomic(args.json, json.dumps(table, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
