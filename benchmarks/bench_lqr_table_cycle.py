"""The largest per-tick CPU of the attitude controller with the magnetorquer hold's gain table under way (issue 27).

Flies the below-40° scheduled hold's scenario (MAG_LQR_ANGLE 40°,
``campaigns/adcs/scenarios/pointing_magnetorquers_field_model_lqr_below_40.yaml``, or its ``_igrf14`` twin with
IGRF-14 of degree 6 on board) plant-only (``detumble.sim.runner``, ``--law adcs``) from 45° off the target at
0.2 °/s, with every ``ThreeModeLaw.tick`` timed on the thread's CPU clock (``time.thread_time_ns``). Prints the
ticks' max, p99 and p99.9 (µs), the count above 2 ms, and the same max over the ticks in which the interpreter ran
no full (generation-2) garbage collection: such a collection (~10 ms here) comes in any long flight, the table's
or not, and is reported apart. Run it on a tree before and after a change of the table's build (PYTHONPATH picks
the tree):

    PYTHONPATH=src python benchmarks/bench_lqr_table_cycle.py --duration 600 [--igrf14]

CPU figures are comparable only within one sitting (a shared machine).
"""

from __future__ import annotations

import argparse
import gc
import json
import tempfile
import time

from detumble.control import three_mode
from detumble.sim import runner

SCENARIO = "campaigns/adcs/scenarios/pointing_magnetorquers_field_model_lqr_below_40.yaml"


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--duration", type=float, default=600.0, help="simulated seconds (default 600)")
    ap.add_argument("--igrf14", action="store_true", help="the IGRF-14 case (IGRF-14 of degree 6 on board)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--rate", type=float, default=0.2, help="initial rate, deg/s (default 0.2)")
    ap.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = ap.parse_args(argv)
    samples: list[int] = []
    full: list[bool] = []
    collections = [0]
    tick = three_mode.ThreeModeLaw.tick
    clock = time.thread_time_ns

    def on_gc(phase: str, info: dict) -> None:
        if phase == "start" and info["generation"] == 2:
            collections[0] += 1

    def timed(self) -> None:
        n0 = collections[0]
        t0 = clock()
        tick(self)
        samples.append(clock() - t0)
        full.append(collections[0] != n0)

    three_mode.ThreeModeLaw.tick = timed  # type: ignore[method-assign]
    gc.callbacks.append(on_gc)
    try:
        with tempfile.TemporaryDirectory() as out:
            scenario = SCENARIO.replace(".yaml", "_igrf14.yaml") if args.igrf14 else SCENARIO
            runner.main([scenario, "--law", "adcs", "--duration", str(args.duration), "--seed", str(args.seed),
                         "--out", out, "--no-plots", "--set", f"initial.rate.magnitude_deg_s={args.rate}",
                         "--set", "initial.attitude.quaternion=[1,0,0,0]"])
    finally:
        three_mode.ThreeModeLaw.tick = tick  # type: ignore[method-assign]
        gc.callbacks.remove(on_gc)
    s = sorted(samples)
    n = len(s)
    figures = {"ticks": n, "max_us": s[-1] / 1e3, "p99_us": s[int(0.99 * (n - 1))] / 1e3,
               "p999_us": s[int(0.999 * (n - 1))] / 1e3, "above_2ms": sum(1 for x in s if x > 2_000_000),
               "full_collections": collections[0],
               "max_no_full_collection_us": max(x for x, f in zip(samples, full, strict=True) if not f) / 1e3}
    print(json.dumps(figures) if args.json else
          "ticks {ticks}  max {max_us:.0f} us  p99 {p99_us:.0f} us  p99.9 {p999_us:.0f} us  above 2 ms {above_2ms}  "
          "full collections {full_collections}  max without one {max_no_full_collection_us:.0f} us".format(**figures))
    return figures


if __name__ == "__main__":
    main()
