"""The single-run tables of docs/studies/environment_torques.md and the gyroscopic feed-forward of
docs/studies/pointing_targets.md, flown plant-only (``fprime-lite sim --law adcs``'s law, the adcs scenario, seed 1).

    nice -n 10 python campaigns/adcs/wheel_runs_study.py --part PART                 # one JSON line per flight
    nice -n 10 python campaigns/adcs/wheel_runs_study.py --part PART --json FILE     # and the flights kept in FILE

Parts (``tools/studies.py`` renders each one's table from its JSON file with :func:`markdown`):

``feed_forward`` (environment_torques.md; 5 flights of 1200 s): a nadir hold (+Z nadir, +X along track commanded at
0.5 s, POINTING forced at 1 s, from rest) with ``WHEEL_FEED_FORWARD`` REFERENCE or REFERENCE_GYROSCOPIC_GRAVITY and
K_I 0 or the default 5.5e-5 N·m/s; a fifth flight with the defaults and the drag and solar-pressure torques on
(centre-of-pressure offset (0.005, −0.005, 0.01) m in B).

``four_wheels`` (environment_torques.md; 2 flights of 1200 s): four wheels in a 35.26° pyramid about +Z, their
momenta starting at (1.5, −1.0, 0.5, 1.0) mN·m·s, holding the attitude of entry from rest (POINTING forced at 1 s)
with K_DUMP the default 2e-3 1/s and 0; the null-space momentum |P h| (N·m·s) at the end beside the closed form
|P h(0)| e^(−K_DUMP t).

``gyroscopic`` (pointing_targets.md; 2 flights of 1900 s): the ground-station pass of
``campaigns/adcs/targets_study.py`` with ``WHEEL_FEED_FORWARD`` REFERENCE (the default) and REFERENCE_GYROSCOPIC.

Figures per flight: the summary's ``pointing_error_deg`` (the steady samples after each 0.1° acquisition: median,
p95, max in deg; acquisition s) and, for the pass, ``pointing_error_by_target_deg`` with the acquisitions (s) of
each interval of that reference (``pointing_intervals``).
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys

from detumble.control.wheel_allocation import WheelAllocator
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario

_FROM_REST = ["initial.rate.magnitude_deg_s=0", "control.adcs.force_mode=POINTING", "control.adcs.force_at_s=1"]
_NADIR = _FROM_REST + ["control.adcs.target_changes=[[0.5, NADIR, PLUS_Z, PLUS_X]]"]
_SURFACES = ["spacecraft.surfaces.drag=true", "spacecraft.surfaces.solar_pressure=true",
             "spacecraft.surfaces.cp_offset_m=[0.005, -0.005, 0.01]"]
_S = 0.816496580927726
_C = 0.5773502691896258
#: the four wheels' spin axes (B, unit vectors): a pyramid of 35.26° half-angle from the xy plane about +Z
PYRAMID = ((_S, 0.0, _C), (0.0, _S, _C), (-_S, 0.0, _C), (0.0, -_S, _C))
H0_NMS = (1.5e-3, -1.0e-3, 5.0e-4, 1.0e-3)
_STATION = "51.08237071939756, -152.0921352524934, 0.0"  # campaigns/adcs/targets_study.py's STATION

#: part -> (duration s, [(label, settings)])
PARTS = {
    "feed_forward": (1200.0, [
        (f"{ff}|{ki}|{surfaces}", _NADIR + [f"control.adcs.K_I={ki}", f"control.adcs.WHEEL_FEED_FORWARD={ff}"]
         + (_SURFACES if surfaces == "on" else []))
        for ff, ki, surfaces in (("REFERENCE", "0", "off"), ("REFERENCE_GYROSCOPIC_GRAVITY", "0", "off"),
                                 ("REFERENCE", "5.5e-5", "off"), ("REFERENCE_GYROSCOPIC_GRAVITY", "5.5e-5", "off"),
                                 ("REFERENCE", "5.5e-5", "on"))]),
    "four_wheels": (1200.0, [
        (k_dump, _FROM_REST + [f"spacecraft.reaction_wheels.axes={json.dumps([list(a) for a in PYRAMID])}",
                               f"spacecraft.reaction_wheels.initial_momentum_nms={json.dumps(list(H0_NMS))}"]
         + ([] if k_dump == "default" else [f"control.adcs.K_DUMP={k_dump}"]))
        for k_dump in ("default", "0")]),
    "gyroscopic": (1900.0, [
        (ff, _FROM_REST + [f"control.adcs.target_changes=[[0.5, GROUND_STATION, {_STATION}, PLUS_Z, PLUS_X]]",
                           f"control.adcs.WHEEL_FEED_FORWARD={ff}"])
        for ff in ("REFERENCE", "REFERENCE_GYROSCOPIC")]),
}


def null_space_momentum(momenta) -> float:
    """|P h| (N·m·s) of the pyramid's wheel momenta ``momenta`` (N·m·s): P the null-space projector of its axes."""
    p = WheelAllocator(PYRAMID, 1.0, 1.0).null_projector
    assert p is not None
    ph = [sum(p[i][j] * momenta[j] for j in range(len(momenta))) for i in range(len(momenta))]
    return math.sqrt(sum(x * x for x in ph))


def _steady(stats: dict | None) -> dict | None:
    return None if stats is None else {k: stats.get(k) for k in ("acquisition_s", "median", "p95", "max", "samples")}


def flight(part: str, label: str, settings: list[str], duration_s: float) -> dict:
    """One flight's record: its label, the steady statistics (deg, s) and what its part reads besides."""
    result = run(load_scenario("adcs", settings=settings), law="adcs", duration_s=duration_s)
    s = result.summary
    record = {"part": part, "label": label, "pointing": _steady(s.get("pointing_error_deg"))}
    if part == "four_wheels":
        cols = {name: i for i, name in enumerate(result.adcs_header)}
        last = result.adcs_rows[-1]
        momenta = [last[cols[f"h{i}_Nms"]] for i in range(len(PYRAMID))]
        record.update(t_s=result.rows[-1][0], wheel_momenta_nms=momenta, null_space_nms=null_space_momentum(momenta))
    if part == "gyroscopic":
        intervals = s.get("pointing_intervals") or []
        record["by_target"] = {}
        for label, stats in (s.get("pointing_error_by_target_deg") or {}).items():
            st = _steady(stats)
            if st is not None:
                st["acquisition_s"] = [i["acquisition_s"] for i in intervals if i["target"] == label]
            record["by_target"][label] = st
    return record


def flights(part: str):
    """The part's flights' records, as they land."""
    duration, cases = PARTS[part]
    for label, settings in cases:
        yield flight(part, label, settings, duration)


def _row(p: dict | None, digits: int = 5) -> str:
    if p is None:
        return "never | — | — | —"
    return f"{p['acquisition_s']:.1f} | {p['median']:.{digits}f} | {p['p95']:.{digits}f} | {p['max']:.4f}"


def markdown(table: dict) -> str:
    """The part's table from ``--json``'s file."""
    part, rows = table["part"], table["flights"]
    if part == "feed_forward":
        lines = ["| WHEEL_FEED_FORWARD | K_I (N·m/s) | drag and solar pressure | acquisition s | steady median deg | "
                 "p95 deg | max deg |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            ff, ki, surfaces = r["label"].split("|")
            ff = "REFERENCE (default)" if ff == "REFERENCE" else ff
            ki = "0 (pure PD)" if ki == "0" else f"{ki} (default)"
            surfaces = "off (default)" if surfaces == "off" else "on, offset (0.005, −0.005, 0.01) m"
            lines.append(f"| {ff} | {ki} | {surfaces} | {_row(r['pointing'])} |")
        return "\n".join(lines) + "\n"
    if part == "four_wheels":
        h0 = null_space_momentum(H0_NMS)
        lines = ["| K_DUMP (1/s) | null-space momentum at the end (N·m·s) | closed form \\|P h(0)\\| e^(−K_DUMP t) | "
                 "acquisition s | steady median deg | p95 deg | max deg |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            default = r["label"] == "default"
            k = 2e-3 if default else 0.0
            name = "2e-3 (default)" if default else "0 (dumping and null-space management off)"
            lines.append(f"| {name} | {r['null_space_nms']:.2e} | {h0 * math.exp(-k * r['t_s']):.2e} | "
                         f"{_row(r['pointing'], 4)} |")
        return "\n".join(lines) + "\n"
    lines = ["| WHEEL_FEED_FORWARD | reference | acquisitions s | steady median deg | p95 deg | max deg | "
             "steady samples |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        name = "REFERENCE (default)" if r["label"] == "REFERENCE" else r["label"]
        for ref, st in r["by_target"].items():
            if st is None:
                lines.append(f"| {name} | {ref} | — | — | — | — | 0 |")
                continue
            acquisitions = ", ".join(f"{a:.1f}" for a in st["acquisition_s"])
            lines.append(f"| {name} | {ref} | {acquisitions} | {st['median']:.4f} | {st['p95']:.4f} | "
                         f"{st['max']:.3f} | {st['samples']} |")
    return "\n".join(lines) + "\n"


def _keep(path: pathlib.Path, table: dict) -> None:
    """Write ``table`` to ``path`` (JSON), atomically, making its folder."""
    from fprime_lite.osal.atomic import atomic_write_text

    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_text(path, json.dumps(table, indent=1) + "\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--part", choices=sorted(PARTS), required=True)
    parser.add_argument("--json", type=pathlib.Path, metavar="FILE", help="also keep the flights in FILE (JSON)")
    args = parser.parse_args(argv)
    kept = []
    for record in flights(args.part):
        print(json.dumps(record), flush=True)
        kept.append(record)
    table = {"script": "campaigns/adcs/wheel_runs_study.py", "part": args.part,
             "duration_s": PARTS[args.part][0], "flights": kept}
    print(markdown(table), end="")
    if args.json is not None:
        _keep(args.json, table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
