"""fprime-lite against Basilisk, side by side in one sitting (issue #19).

    pip install -e '.[bsk]'          # Basilisk 2.12 from PyPI (pip name: bsk)
    python benchmarks/bench_vs_basilisk.py [--duration 5578] [--rounds 3] [--json FILE]

The measurement is :func:`detumble.sitl.bench_basilisk.measure` (its docstring lists the four
interleaved kinds of run); ``fprime-lite bench`` runs the same as its ``basilisk`` piece.
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys

from detumble.sitl.bench_basilisk import INSTALL_HINT, ORBIT_S, basilisk_installed, measure

REFERENCE = pathlib.Path(__file__).resolve().parents[1] / "deployments" / "proves_ref" / "topology.yaml"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=ORBIT_S, help="simulated seconds per run (one orbit)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--topology", default=str(REFERENCE), help="the deployment flown at 50 Hz")
    parser.add_argument("--json", default="bench_vs_basilisk.json")
    args = parser.parse_args(argv)
    if not basilisk_installed():
        print(f"Basilisk is not installed: {INSTALL_HINT}", file=sys.stderr)
        return 2
    r = measure(args.topology, args.duration, args.rounds, progress=lambda s: print(s, file=sys.stderr, flush=True))
    pathlib.Path(args.json).write_text(json.dumps(r, indent=2) + "\n")
    b = r["best_real_time_factor"]
    print(f"{r['sim_seconds']:.0f} s simulated, best of {r['rounds']} rounds, real-time factors:")
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
