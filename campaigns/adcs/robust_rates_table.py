"""The single-run table of docs/studies/robust_rates.md: a ~90° slew on the wheels with the plant's inertia off the
controller's model (INERTIA_* stay at the adcs scenario's matrix), plant-only.

    python campaigns/adcs/robust_rates_table.py                                      # the table, printed
    python campaigns/adcs/robust_rates_table.py --json docs/studies/robust_rates/table.json   # and its figures kept

``tools/studies.py --only robust_rates`` renders the page's table from that JSON file (``markdown``).

Geometry (seed 1): from 90° about (1, 1, 1)/√3 and a 0.05 °/s tumble, FORCE_MODE POINTING at 30 s holding the
attitude of entry, the identity commanded at 60 s, 400 s. Rows: the plant's inertia exact, ×1.10, ×0.90 and skewed
(moments +10 / −10 / +5 %, the x–y product 1.7e-4 kg·m², 8 % of a moment); columns per rate source: the default
(observer, blended to the gyro during slews), the observer without the blend (RATE_BLEND_ANGLE = 180, the law before
issue 27: also no integral rate gate and no residual-dipole estimate) and the bias-corrected gyro (RATE_SOURCE = GYRO).
Figures: the slew's settle time below 0.1° (summary ``slews``), and median / p95 of the true error from 120 s to the
end (60 s after the slew began).
"""

from __future__ import annotations

import sys

from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario

NOMINAL = ((2.20e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.05e-3))
PLANTS = {
    "exact": NOMINAL,
    "x1.10": tuple(tuple(v * (1.1 if i == j else 1.0) for j, v in enumerate(r)) for i, r in enumerate(NOMINAL)),
    "x0.90": tuple(tuple(v * (0.9 if i == j else 1.0) for j, v in enumerate(r)) for i, r in enumerate(NOMINAL)),
    "skewed": ((2.42e-3, 1.7e-4, -1.5e-5), (1.7e-4, 1.935e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.1525e-3)),
}
#: How the page names each plant.
LABELS = {"exact": "exact", "x1.10": "×1.10", "x0.90": "×0.90",
          "skewed": "skewed (moments +10/−10/+5 %, x–y product 1.7e-4 kg·m²)"}
#: the D term's rate source per column; "before" is the issue's configuration: no blend, no integral rate gate and
#: no residual-dipole estimate in the observer
SOURCES = {"default (blend)": [], "observer, no blend (before)": ["control.adcs.RATE_BLEND_ANGLE=180",
                                                                 "control.adcs.INTEGRAL_RATE_GATE=0",
                                                                 "control.adcs.RATE_OBSERVER_DIPOLE_TIME=0"],
           "gyro": ["control.adcs.RATE_SOURCE=GYRO"]}
BASE = ["initial.rate.magnitude_deg_s=0.05",
        "initial.attitude.quaternion=[0.7071067811865476,0.4082482904638631,0.4082482904638631,0.4082482904638631]",
        "control.adcs.force_mode=POINTING", "control.adcs.force_at_s=30", "control.adcs.target_q_bn=null",
        "control.adcs.target_changes=[[60, 1.0, 0.0, 0.0, 0.0]]", "record_interval_s=0.5"]


def fly(inertia, extra: list[str]) -> tuple[float | None, float, float]:
    matrix = "[" + ", ".join("[" + ", ".join(format(x, ".7f") for x in row) + "]" for row in inertia) + "]"
    r = run(load_scenario("adcs", settings=BASE + [f"spacecraft.inertia_kg_m2={matrix}", *extra]), law="adcs",
            duration_s=400.0)
    assert r.adcs_header is not None and r.adcs_rows is not None
    k = r.adcs_header.index("pointing_error_deg")
    steady = sorted(float(a[k]) for row, a in zip(r.rows, r.adcs_rows, strict=True) if row[0] >= 120.0)
    p = lambda q: steady[int(round(q * (len(steady) - 1)))]  # noqa: E731 - nearest-rank quantile
    return r.summary["slews"][0]["settle_below_0p1_deg_s"], p(0.5), p(0.95)


def results() -> dict:
    """Every cell: ``{"plants": {plant: {source: {"settle_s", "median_deg", "p95_deg"}}}}`` (seconds, degrees)."""
    plants = {}
    for name, inertia in PLANTS.items():
        plants[name] = {}
        for source, extra in SOURCES.items():
            settle, med, p95 = fly(inertia, extra)
            plants[name][source] = {"settle_s": settle, "median_deg": med, "p95_deg": p95}
    return {"script": "campaigns/adcs/robust_rates_table.py", "duration_s": 400.0, "plants": plants}


def markdown(table: dict) -> str:
    """The page's table from :func:`results` (settle to 0.5 s as the summary gives it; errors to 1e-4 deg)."""
    lines = ["| plant inertia | " + " | ".join(f"{s}: settle s / median / p95 deg" for s in SOURCES) + " |",
             "|---|" + "---|" * len(SOURCES)]
    for name, cells in table["plants"].items():
        text = [f"{c['settle_s'] if c['settle_s'] is not None else 'never'} / {c['median_deg']:.4f} / "
                f"{c['p95_deg']:.4f}" for c in (cells[s] for s in SOURCES)]
        lines.append(f"| {LABELS[name]} | " + " | ".join(text) + " |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import table_script_main

    return table_script_main(argv, __doc__.split("\n\n")[0], lambda args: results(), markdown)


if __name__ == "__main__":
    sys.exit(main())
