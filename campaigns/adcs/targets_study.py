"""The moving-target figures of docs/studies/pointing_targets.md, plant-only (``fprime-lite sim --law adcs``'s law).

    python campaigns/adcs/targets_study.py [--quick]                                    # the table, printed
    python campaigns/adcs/targets_study.py --json docs/studies/pointing_targets/table.json   # and its figures kept

``tools/studies.py --only pointing_targets`` renders the page's table from that JSON file (``markdown``).

Cases (adcs scenario, seed 1, from rest, FORCE_MODE POINTING at 1 s, the target commanded at 0.5 s):
nadir (LVLH, +Z nadir, +X along track) over one orbit; a ground-station pass (a station 3° east of the ground track
at 1500 s, peak elevation ~87°, 10° mask) over 1900 s; the Sun (+Z to the Sun, +X toward the orbit normal) over
one orbit. Each is flown with the reference fed forward (the default), with the reference rate in the D term but
no feed-forward torque, and with neither (the PD as for an inertial target; ablations replace
``ThreeModeLaw._reference_feed_forward``). Prints one markdown row per case and variant: acquisition of the first
interval, steady median / p95 / max per active reference (``detumble.analysis.pointing_windows``).
"""

from __future__ import annotations

import sys

from detumble.control import three_mode
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario

STATION = "51.08237071939756, -152.0921352524934, 0.0"
CASES = {"nadir": ("NADIR, PLUS_Z, PLUS_X", 5580.0), "ground station": (f"GROUND_STATION, {STATION}, PLUS_Z, PLUS_X",
                                                                         1900.0),
         "sun": ("SUN, PLUS_Z, PLUS_X", 5580.0)}
_ORIGINAL = three_mode.ThreeModeLaw._reference_feed_forward


def _rate_only(self, ref, q_err, rate):
    relative, _ = _ORIGINAL(self, ref, q_err, rate)
    return relative, (0.0, 0.0, 0.0)


def _neither(self, ref, q_err, rate):
    return rate, (0.0, 0.0, 0.0)


VARIANTS = {"feed-forward (default)": _ORIGINAL, "rate only": _rate_only, "neither": _neither}


def results(quick: bool = False) -> dict:
    """Every case and variant: its first interval's acquisition (s), and per active reference the acquisitions
    of its intervals (s) and its steady statistics (``median``/``p95``/``max`` deg, ``samples``; None: none)."""
    rows = []
    try:
        for case, (target, duration) in CASES.items():
            for variant, method in VARIANTS.items():
                three_mode.ThreeModeLaw._reference_feed_forward = method  # type: ignore[method-assign]
                settings = ["initial.rate.magnitude_deg_s=0", "control.adcs.force_mode=POINTING",
                            "control.adcs.force_at_s=1", f"control.adcs.target_changes=[[0.5, {target}]]"]
                s = run(load_scenario("adcs", settings=settings), law="adcs",
                        duration_s=min(duration, 300.0) if quick else duration).summary
                acq = s["pointing_error_deg"]["acquisition_s"] if s["pointing_error_deg"] else None
                for label, st in s["pointing_error_by_target_deg"].items():
                    ivs = [i["acquisition_s"] for i in s["pointing_intervals"] if i["target"] == label]
                    rows.append({"case": case, "variant": variant, "reference": label, "acquisition_s": acq,
                                 "interval_acquisitions_s": ivs,
                                 "steady": None if st is None else {k: st[k] for k in ("median", "p95", "max",
                                                                                        "samples")}})
    finally:
        three_mode.ThreeModeLaw._reference_feed_forward = _ORIGINAL  # type: ignore[method-assign]
    return {"script": "campaigns/adcs/targets_study.py", "quick": quick, "rows": rows}


def markdown(table: dict) -> str:
    """The page's table from :func:`results`."""
    lines = ["| case | variant | reference | acquisition s (first interval) | steady median deg | p95 deg | max deg |"
             " steady samples |", "|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        head = f"| {r['case']} | {r['variant']} | {r['reference']} | {r['acquisition_s']}"
        st = r["steady"]
        if st is None:
            lines.append(f"{head} | — | — | — | 0 |")
            continue
        lines.append(f"{head} (this reference: {r['interval_acquisitions_s']}) | {st['median']:.4f} | "
                     f"{st['p95']:.4f} | {st['max']:.3f} | {st['samples']} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import table_script_main

    def quick(parser) -> None:
        parser.add_argument("--quick", action="store_true", help="300 s per run (a smoke test, not the page's figures)")

    return table_script_main(argv, __doc__.split("\n\n")[0], lambda args: results(args.quick), markdown, quick)


if __name__ == "__main__":
    sys.exit(main())
