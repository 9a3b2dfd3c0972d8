"""When AUTO reaches POINTING in the tilted dipole and in IGRF-14 (docs/studies/environment_torques.md, "IGRF").

    nice -n 10 python campaigns/adcs/field_auto_study.py                 # one JSON line per flight, as it flies
    nice -n 10 python campaigns/adcs/field_auto_study.py --json docs/studies/environment_torques/field_auto.json

Six tumbling starts, each flown plant-only (`--law adcs`, the controller adcs_ref flies) for 3000 s in both fields
(IGRF-14 on adcs_ref's 10 s table); one JSON line per flight: the times of entering SPIN_STABLE and POINTING and
the POINTING median error. A few minutes per flight. With ``--json FILE`` the flights are also kept in FILE, from
which ``tools/studies.py --only environment_torques`` renders the page's table (``markdown``).
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys

from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario

#: (rate deg/s, axis in the body frame, how the page names the start)
STARTS = (("1.2", "[0.36353657, 0.86429949, 0.34760259]", "1.2 °/s about the scenario's axis"),
          ("1.2", "[1, 0, 0]", "1.2 °/s about x"), ("1.2", "[0, 0.6, 0.8]", "1.2 °/s about (0, 0.6, 0.8)"),
          ("3.0", "[0.36353657, 0.86429949, 0.34760259]", "3.0 °/s about the scenario's axis"),
          ("3.0", "[0.577, -0.577, 0.577]", "3.0 °/s about (0.577, −0.577, 0.577)"),
          ("0.8", "[0, 0, 1]", "0.8 °/s about z"))
FIELDS = {"dipole": ["field.model=dipole"], "igrf14": ["field.model=igrf14", "field.table_step_s=10"]}


def flights():
    """Each flight's record (times in s from the start, median in deg), as it lands."""
    for rate, axis, label in STARTS:
        for field, settings in FIELDS.items():
            start = [f"initial.rate.magnitude_deg_s={rate}", f"initial.rate.axis={axis}"]
            result = run(load_scenario("adcs", settings=start + settings), law="adcs", duration_s=3000.0)
            modes = {t["mode"]: t["t_s"] for t in result.summary["control_mode_transitions"]}
            yield {"rate_deg_s": float(rate), "axis": axis, "start": label, "field": field,
                   "spin_stable_s": modes.get("SPIN_STABLE"), "pointing_s": modes.get("POINTING"),
                   "pointing_median_deg": (result.summary.get("pointing_error_deg") or {}).get("median")}


def markdown(table: dict) -> str:
    """The page's table (time of entering POINTING per start and field) and what it says, from ``--json``'s file."""
    by = {(f["start"], f["field"]): f for f in table["flights"]}

    def when(f) -> str:
        return "never" if f["pointing_s"] is None else f"{f['pointing_s']:g}"

    lines = ["| start | dipole | IGRF-14 |", "|---|---|---|"]
    later = earlier = 0
    for _, _, label in STARTS:
        dipole, igrf = by[(label, "dipole")], by[(label, "igrf14")]
        lines.append(f"| {label} | {when(dipole)} | {when(igrf)} |")
        if dipole["pointing_s"] is not None and igrf["pointing_s"] is not None:
            later += igrf["pointing_s"] > dipole["pointing_s"]
            earlier += igrf["pointing_s"] < dipole["pointing_s"]
    medians = [f["pointing_median_deg"] for f in table["flights"] if f["pointing_median_deg"] is not None]
    lines += ["", f"IGRF-14 is the later of the two in {later} starts and the earlier in {earlier}; the POINTING "
              f"median is {min(medians):.4f}–{max(medians):.4f}° in {len(medians)} of {len(table['flights'])} "
              f"flights."]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", type=pathlib.Path, metavar="FILE", help="also keep the flights in FILE (JSON)")
    args = parser.parse_args(argv)
    kept = []
    for flight in flights():
        print(json.dumps(flight), flush=True)
        kept.append(flight)
    if args.json is not None:
        from fprime_lite.osal.atomic import atomic_write_text

        args.json.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(args.json, json.dumps({"script": "campaigns/adcs/field_auto_study.py", "duration_s": 3000.0,
                                                 "flights": kept}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
