"""Why seed 004's β-PD settling time moves non-monotonically as the step is halved: its ripple, measured.

Flies ``fprime-lite sim surrey --law beta_pd`` (the project's plant, the dynamics step and the control period
both ``--step``), keeps the body rate every ``--record`` seconds, and reports per rate axis:

* ``settling_s``: the run's own 2 % settling time (``lsiminfo``'s: the last entry into the band, measured on
  line at every control period; the figure the convergence campaigns publish);
* ``peaks``: the ripple's peaks of ``|ω_i − ω_final,i|`` around that instant (rad/s, and as a fraction of the
  band), from :func:`detumble.analysis.settling.ripple_peaks` on the recorded trace;
* ``ripple_period_s``: the mean spacing of those peaks, beside ``rotation_period_s`` = 2π / |ω − ω_final| at the
  settling instant: the body turns at that rate through a field fixed in the orbit frame, so the bang-bang
  spin terms (±1 A·m² by the sign of B_x, B_z) switch, and ω ripples, once a turn;
* ``envelope_settling_s``: where the line through those peaks crosses the band
  (:func:`detumble.analysis.settling.envelope_settling_time`).

    nice -n 10 python campaigns/coursework/settling_ripple.py --step 0.00125 [--switched] > OUT.json

Prints one JSON line. A 9000 s run costs about 40 CPU-s at 0.0025 s and doubles with each halving.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time

import numpy as np

from detumble.analysis.settling import DEFAULT_BAND, envelope_settling_time, ripple_peaks, settling_time
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario

#: The peaks reported around the settling instant: this many before the first peak under the band, and it.
PEAKS_ABOVE = 3


def axis_report(t: np.ndarray, w: np.ndarray, w0: float, w_final: float, settling_online: float | None,
                rate_rel: np.ndarray) -> dict:
    """One axis's figures (times s, rates rad/s) from its trace ``w`` sampled at ``t``."""
    width = DEFAULT_BAND * abs(w_final - w0)
    peaks = ripple_peaks(t, w, w_final)
    above = [k for k, (_, h) in enumerate(peaks) if h > width]
    out: dict = {"band_rad_s": width, "settling_s": settling_online,
                 "settling_trace_s": settling_time(t, w, w_final, w0),
                 "envelope_settling_s": envelope_settling_time(t, w, w_final, w0)}
    if above and above[-1] + 1 < len(peaks):
        last = above[-1]
        around = peaks[max(0, last + 1 - PEAKS_ABOVE):last + 2]
        out["peaks"] = [{"t_s": p, "height_rad_s": h, "height_over_band": h / width} for p, h in around]
        out["ripple_period_s"] = (around[-1][0] - around[0][0]) / (len(around) - 1)
        if settling_online is not None:
            i = int(np.searchsorted(t, settling_online))
            out["rotation_period_s"] = 2.0 * math.pi / float(rate_rel[min(i, len(t) - 1)])
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--step", type=float, required=True, help="dynamics step = control period, s")
    ap.add_argument("--switched", action="store_true", help="eq. 23 or 24 (the default law); else the listing")
    ap.add_argument("--duration", type=float, default=9000.0, help="simulated s (default 9000)")
    ap.add_argument("--record", type=float, default=0.5, help="trace sampling, s (default 0.5)")
    args = ap.parse_args(argv)
    switched = "true" if args.switched else "false"
    scenario = load_scenario("surrey", settings=[f"dynamics_step_s={args.step!r}", f"control.period_s={args.step!r}",
                                                 f"control.beta_pd.switched={switched}",
                                                 f"record_interval_s={args.record!r}"])
    wall = time.perf_counter()
    result = run(scenario, law="beta_pd", duration_s=args.duration)
    wall = time.perf_counter() - wall
    rows = np.asarray(result.rows, dtype=float)
    t = rows[:, 0]
    w = np.radians(rows[:, 1:4])
    s = result.summary
    w_final = s["settling_omega_final_rad_s"]
    w0 = w[0]
    rate_rel = np.linalg.norm(w - np.asarray(w_final), axis=1)
    axes = {name: axis_report(t, w[:, i], float(w0[i]), float(w_final[i]), s["settling_time_2pct_axes_s"][i],
                              rate_rel)
            for i, name in enumerate("xyz")}
    envelopes = [a["envelope_settling_s"] for a in axes.values()]
    print(json.dumps({
        "law": "beta_pd", "switched": args.switched, "step_s": args.step, "duration_s": args.duration,
        "record_interval_s": args.record, "settling_s": s["settling_time_2pct_s"],
        "envelope_settling_s": None if None in envelopes else max(envelopes),
        "axes": axes, "plant_implementation": s["plant_implementation"], "wall_s": round(wall, 1),
        "command": "python campaigns/coursework/settling_ripple.py " + " ".join(sys.argv[1:] if argv is None
                                                                               else argv),
    }))
    return 0


if __name__ == "__main__":
    sys.exit(main())
