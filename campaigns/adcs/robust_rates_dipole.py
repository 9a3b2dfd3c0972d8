"""The residual dipole in the rate observer (docs/studies/robust_rates.md, "The residual dipole in the observer"):
the figures the page gives beside its campaign, flown plant-only.

    python campaigns/adcs/robust_rates_dipole.py draws      # the default's three misses, T 0/10/20/40 s
    python campaigns/adcs/robust_rates_dipole.py targets    # pointing_targets.md's nadir and station pass, 0 and 20 s

``draws``: the robust-rates campaign's draws 3, 0 and 77 (the three the default gate misses) flown as the gate
campaign flies them (``robust_rates_tail.fly`` with INTEGRAL_RATE_GATE 0.05 °/s) with the estimate's time constant
at 0 (off), 10, 20 and 40 s: honest-window p95 (deg), seconds above 0.05° in the hold of the attitude of entry and
after the slew's settle. ``targets``: pointing_targets.md's default cases (adcs scenario, seed 1, from rest, FORCE_MODE
POINTING at 1 s: nadir over one orbit, the ground-station pass over 1900 s) with the estimate off and at 20 s:
acquisition (s) and steady median / p95 / max (deg) per active reference.
"""

from __future__ import annotations

import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
DRAWS = (3, 0, 77)
TIMES_S = (0.0, 10.0, 20.0, 40.0)


def draws() -> None:
    import pandas as pd

    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from robust_rates_tail import CAMPAIGN, fly

    df = pd.read_parquet(CAMPAIGN).set_index("seed_index")
    for i in DRAWS:
        for t in TIMES_S:
            r = fly(json.loads(df.loc[i, "requested"]), int(df.loc[i, "seed"]),
                    ["control.adcs.INTEGRAL_RATE_GATE=0.05", f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"])
            print(f"draw {i:3d}  T {t:4.0f} s  p95 {r['p95_deg']:.4f}°  entry above 0.05° {r['entry_above_s']:4.1f} s  "
                  f"after the settle {r['after_settle_above_s']:4.1f} s  settle {r['settle_s']:.1f} s", flush=True)


def targets() -> None:
    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from targets_study import CASES

    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    for case in ("nadir", "ground station"):
        target, duration = CASES[case]
        for t in (0.0, 20.0):
            settings = ["initial.rate.magnitude_deg_s=0", "control.adcs.force_mode=POINTING",
                        "control.adcs.force_at_s=1", f"control.adcs.target_changes=[[0.5, {target}]]",
                        f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"]
            s = run(load_scenario("adcs", settings=settings), law="adcs", duration_s=duration).summary
            for label, st in s["pointing_error_by_target_deg"].items():
                acq = [i["acquisition_s"] for i in s["pointing_intervals"] if i["target"] == label]
                figures = "none" if st is None else f"{st['median']:.4f} / {st['p95']:.4f} / {st['max']:.3f}"
                print(f"{case:15s} T {t:4.0f} s  {label:17s} acquisitions {acq}  median / p95 / max {figures}",
                      flush=True)


if __name__ == "__main__":
    {"draws": draws, "targets": targets}[sys.argv[1] if len(sys.argv) > 1 else "draws"]()
