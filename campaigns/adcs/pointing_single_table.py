"""The two single-run tables of docs/studies/attitude_knowledge.md (the estimator and D-term rate design table, and
"What limits it now"), flown again on today's code: fifteen 400 s ``adcs_ref`` runs of
``campaigns/adcs/pointing_single.py``'s geometry (a few CPU-s each).

    python campaigns/adcs/pointing_single_table.py                                                   # printed
    python campaigns/adcs/pointing_single_table.py --json docs/studies/attitude_knowledge/single_runs.json  # kept

Each row is one run of :func:`pointing_single.fly` (noise seed 1; initial attitude 90° about (1, 1, 1)/√3 from the
target, a 0.05 °/s tumble, FORCE_MODE POINTING at 30 s, a target change to identity at 90 s) with the row's
controller parameters set at 0 s by the sequence and its scenario settings. Figures: the first slew's settling
below 0.1° (s, the run summary's) and the steady error's median / p95 / max (deg) from 60 s after the target change
to the end (``detumble.reports.pointing_metrics``, as the campaign's metrics). ``tools/studies.py --only
attitude_knowledge_single_runs`` renders the page's two tables from the JSON file (:func:`design_markdown`,
:func:`sensors_markdown`).
"""

from __future__ import annotations

import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
_INERTIA_10 = "INERTIA_XX_PRM_SET 10;INERTIA_YY_PRM_SET 10;INERTIA_ZZ_PRM_SET 10"
#: the design table: (estimator, D-term rate, the controller's parameters) per row; the default row in bold
DESIGN = (
    ("complementary", "gyro (before this work)", "ESTIMATOR_PRM_SET COMPLEMENTARY;RATE_SOURCE_PRM_SET GYRO"),
    ("MEKF", "gyro", "RATE_SOURCE_PRM_SET GYRO"),
    ("complementary", "observer, L 0.1 /s", "ESTIMATOR_PRM_SET COMPLEMENTARY"),
    ("MEKF", "observer, L 0.1 /s (default)", ""),
    ("MEKF", "observer, L 0.05 /s", "RATE_OBSERVER_GAIN_PRM_SET 0.05"),
    ("MEKF", "observer, L 0.2 /s", "RATE_OBSERVER_GAIN_PRM_SET 0.2"),
    ("MEKF", "observer, L 1 /s", "RATE_OBSERVER_GAIN_PRM_SET 1.0"),
    ("MEKF", "low-pass 5 rad/s (observer with no model: inertia 10 kg·m²)",
     f"{_INERTIA_10};RATE_OBSERVER_GAIN_PRM_SET 5.0"),
    ("MEKF", "low-pass 1 rad/s (same, L 1 /s)", f"{_INERTIA_10};RATE_OBSERVER_GAIN_PRM_SET 1.0"),
    ("MEKF, GYRO_BIAS_WALK 0", "observer 0.1", "GYRO_BIAS_WALK_PRM_SET 0.0"),
    ("MEKF, GYRO_BIAS_WALK 1e-3 °/s/√s", "observer 0.1", "GYRO_BIAS_WALK_PRM_SET 0.001"),
)
#: "What limits it now": the default design with one sensor made ideal at a time (scenario settings)
SENSORS = (
    ("as in the scenario", ()),
    ("ideal star tracker", ("sensors.star_tracker.ideal=true",)),
    ("ideal gyro (no noise, bias or quantisation)", ("sensors.gyro.ideal=true",)),
    ("both ideal", ("sensors.star_tracker.ideal=true", "sensors.gyro.ideal=true")),
)


def _single():
    from detumble.reports.study_table import sibling_script

    return sibling_script(HERE, "pointing_single")


def fly_row(params: str, settings: tuple[str, ...], out: pathlib.Path) -> dict:
    """One row's run into ``out``: its parameters, settings and figures."""
    return _single().fly(out, [p.strip() for p in params.split(";") if p.strip()], list(settings))


def results(runs_dir: pathlib.Path) -> dict:
    design = [dict(fly_row(params, (), runs_dir / f"design_{i}"), estimator=est, rate=rate)
              for i, (est, rate, params) in enumerate(DESIGN)]
    sensors = [dict(fly_row("", settings, runs_dir / f"sensors_{i}"), sensors=label)
               for i, (label, settings) in enumerate(SENSORS)]
    return {"script": "campaigns/adcs/pointing_single_table.py", "design": design, "sensors": sensors}


#: the row ``probe`` flies again: the default design
PROBE_ROW = next(i for i, row in enumerate(DESIGN) if "(default)" in row[1])


def probe(committed: dict) -> list[str]:
    """Fly the default design's row again (one 400 s run, a few CPU-s) and compare it with the committed row to the
    float: the differences found (empty: none)."""
    import json
    import tempfile

    est, rate, params = DESIGN[PROBE_ROW]
    with tempfile.TemporaryDirectory() as scratch:
        again = json.loads(json.dumps(dict(fly_row(params, (), pathlib.Path(scratch) / "run"), estimator=est,
                                           rate=rate)))
    row = committed["design"][PROBE_ROW]
    return [f"design row '{rate}': {key} = {again.get(key)} now, {row.get(key)} committed"
            for key in sorted(set(row) | set(again)) if row.get(key) != again.get(key)]


def _slew(r: dict) -> str:
    return "never" if r["slew_settle_s"] is None else f"{r['slew_settle_s']:.1f} s"


def design_markdown(table: dict) -> str:
    lines = ["| estimator | D-term rate | 90° slew settled < 0.1° | steady median | p95 | max |",
             "|---|---|---|---|---|---|"]
    for r in table["design"]:
        cells = [r["estimator"], r["rate"], _slew(r), f"{r['median_deg']:.4f}°", f"{r['p95_deg']:.4f}°"]
        if "(default)" in r["rate"]:
            cells = [f"**{c}**" for c in cells]
        lines.append("| " + " | ".join(cells) + f" | {r['max_deg']:.3f}° |")
    return "\n".join(lines) + "\n"


def sensors_markdown(table: dict) -> str:
    lines = ["| sensors | steady median | p95 |", "|---|---|---|"]
    lines += [f"| {r['sensors']} | {r['median_deg']:.4f}° | {r['p95_deg']:.4f}° |" for r in table["sensors"]]
    return "\n".join(lines) + "\n"


def markdown(table: dict) -> str:
    return design_markdown(table) + "\n" + sensors_markdown(table)


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import runs_table_script_main

    return runs_table_script_main(argv, __doc__.split("\n\n")[0], results, markdown,
                                  ROOT / "runs" / "pointing_single_table")


if __name__ == "__main__":
    sys.exit(main())
