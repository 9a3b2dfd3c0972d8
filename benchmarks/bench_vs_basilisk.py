"""fprime-lite against Basilisk, side by side in one sitting (issue #19).

    pip install -e '.[bsk]'          # Basilisk 2.12 from PyPI (pip name: bsk)
    python benchmarks/bench_vs_basilisk.py [--duration 5578] [--rounds 3] [--json FILE]

Four runs, each in a fresh child process of this one, interleaved round by round so that every
kind sees the same load on a shared machine:

1. Basilisk, case A, dynamics and its Python B-dot at 20 Hz (0.05 s): ``basilisk_case_a.py``;
2. fprime-lite plant-only, case A, 20 Hz (``fprime-lite sim case_a --law kopt``);
3. Basilisk, case A at 50 Hz (0.02 s);
4. the whole fprime-lite reference deployment at 50 Hz (``fprime-lite run``: every F´ component,
   rate group, channel and event).

Each child times only its run proper (set-up excluded) and reports the real-time factor; the
figures are the fastest round of each kind and the ratios are formed from them (the median
round's ratios are printed beside them). Both case-A runs also report the time at which
|ω| < 1 °/s, as a check that the two simulate the same thing (Basilisk: 2817 s).
"""
from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
REFERENCE = ROOT / "deployments" / "proves_ref" / "topology.yaml"

_PLANT = """
import json, sys, time
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario
scenario = load_scenario("case_a")
s = run(scenario, law="kopt", duration_s={duration}).summary
print(json.dumps({{"sim_seconds": s["sim_seconds"], "wall_s": s["wall_seconds"],
                  "real_time_factor": s["sim_seconds"] / s["wall_seconds"],
                  "time_below_1_deg_s": s["time_below_1_deg_s"], "final_rate_deg_s": s["final_rate_deg_s"]}}))
"""

_DEPLOYMENT = """
import json, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
loaded = load_topology({topology!r})
deployment = Deployment(loaded)
deployment.start()
t0 = time.perf_counter()
deployment.run_for({duration})
wall = time.perf_counter() - t0
rate = loaded.resources["spacecraft"].truth().rate_deg_s
print(json.dumps({{"sim_seconds": {duration}, "wall_s": wall, "real_time_factor": {duration} / wall,
                  "final_rate_deg_s": rate}}))
"""


def _child(argv: list[str]) -> dict:
    done = subprocess.run(argv, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(argv[:3])}…: failed\n{done.stderr[-2000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure(duration_s: float, rounds: int) -> dict:
    kinds = {
        "basilisk_20hz": [sys.executable, str(HERE / "basilisk_case_a.py"), "--duration", str(duration_s),
                          "--step", "0.05"],
        "fprime_lite_plant_20hz": [sys.executable, "-c", _PLANT.format(duration=duration_s)],
        "basilisk_50hz": [sys.executable, str(HERE / "basilisk_case_a.py"), "--duration", str(duration_s),
                          "--step", "0.02"],
        "fprime_lite_deployment_50hz": [sys.executable, "-c",
                                        _DEPLOYMENT.format(topology=str(REFERENCE), duration=duration_s)],
    }
    runs: dict[str, list[dict]] = {k: [] for k in kinds}
    for r in range(rounds):
        for kind, argv in kinds.items():
            runs[kind].append(_child(argv))
            print(f"round {r + 1}/{rounds} {kind}: {runs[kind][-1]['real_time_factor']:.0f}× real time",
                  file=sys.stderr, flush=True)
    best = {k: max(x["real_time_factor"] for x in v) for k, v in runs.items()}
    median = {k: statistics.median(x["real_time_factor"] for x in v) for k, v in runs.items()}
    return {
        "sim_seconds": duration_s,
        "rounds": rounds,
        "runs": runs,
        "best_real_time_factor": best,
        "median_real_time_factor": median,
        "plant_20hz_over_basilisk": best["fprime_lite_plant_20hz"] / best["basilisk_20hz"],
        "deployment_50hz_over_basilisk": best["fprime_lite_deployment_50hz"] / best["basilisk_50hz"],
        "median_plant_20hz_over_basilisk": median["fprime_lite_plant_20hz"] / median["basilisk_20hz"],
        "median_deployment_50hz_over_basilisk": median["fprime_lite_deployment_50hz"] / median["basilisk_50hz"],
        "case_a_time_below_1_deg_s": {"basilisk": runs["basilisk_20hz"][0]["time_below_1_deg_s"],
                                      "fprime_lite": runs["fprime_lite_plant_20hz"][0]["time_below_1_deg_s"]},
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=5578.0, help="simulated seconds per run (one orbit)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json", default="bench_vs_basilisk.json")
    args = parser.parse_args(argv)
    try:
        import Basilisk  # noqa: F401
    except ImportError:
        print("Basilisk is not installed: pip install -e '.[bsk]'", file=sys.stderr)
        return 2
    r = measure(args.duration, args.rounds)
    pathlib.Path(args.json).write_text(json.dumps(r, indent=2) + "\n")
    b = r["best_real_time_factor"]
    print(f"one orbit ({r['sim_seconds']:.0f} s), best of {r['rounds']} rounds, real-time factors:")
    print(f"  20 Hz  Basilisk {b['basilisk_20hz']:7.0f}   fprime-lite plant-only {b['fprime_lite_plant_20hz']:7.0f}"
          f"   ratio {r['plant_20hz_over_basilisk']:.2f} (median rounds {r['median_plant_20hz_over_basilisk']:.2f})")
    print(f"  50 Hz  Basilisk {b['basilisk_50hz']:7.0f}   "
          f"fprime-lite deployment {b['fprime_lite_deployment_50hz']:7.0f}"
          f"   ratio {r['deployment_50hz_over_basilisk']:.2f} (median rounds "
          f"{r['median_deployment_50hz_over_basilisk']:.2f})")
    t = r["case_a_time_below_1_deg_s"]
    print(f"  case A |ω| < 1 °/s at: Basilisk {t['basilisk']} s, fprime-lite {t['fprime_lite']} s")
    print(f"figures written to {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
