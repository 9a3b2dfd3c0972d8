"""When AUTO reaches POINTING in the tilted dipole and in IGRF-14 (docs/studies/environment_torques.md, "IGRF").

    nice -n 10 python campaigns/adcs/field_auto_study.py

Six tumbling starts, each flown plant-only (`--law adcs`, the controller adcs_ref flies) for 3000 s in both fields
(IGRF-14 on adcs_ref's 10 s table); one JSON line per flight: the times of entering SPIN_STABLE and POINTING and
the POINTING median error. A few minutes per flight.
"""

from __future__ import annotations

import json

from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario

STARTS = (("1.2", "[0.36353657, 0.86429949, 0.34760259]"), ("1.2", "[1, 0, 0]"), ("1.2", "[0, 0.6, 0.8]"),
          ("3.0", "[0.36353657, 0.86429949, 0.34760259]"), ("3.0", "[0.577, -0.577, 0.577]"), ("0.8", "[0, 0, 1]"))
FIELDS = {"dipole": ["field.model=dipole"], "igrf14": ["field.model=igrf14", "field.table_step_s=10"]}


def main() -> None:
    for rate, axis in STARTS:
        for field, settings in FIELDS.items():
            start = [f"initial.rate.magnitude_deg_s={rate}", f"initial.rate.axis={axis}"]
            result = run(load_scenario("adcs", settings=start + settings), law="adcs", duration_s=3000.0)
            modes = {t["mode"]: t["t_s"] for t in result.summary["control_mode_transitions"]}
            print(json.dumps({"rate_deg_s": float(rate), "axis": axis, "field": field,
                              "spin_stable_s": modes.get("SPIN_STABLE"), "pointing_s": modes.get("POINTING"),
                              "pointing_median_deg": result.summary.get("pointing_error_deg", {}).get("median")}),
                  flush=True)


if __name__ == "__main__":
    main()
