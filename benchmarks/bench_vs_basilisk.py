"""fprime-lite against Basilisk, side by side in one sitting (issue #19).

    pip install -e '.[bsk]'          # Basilisk 2.12 from PyPI (pip name: bsk)
    python benchmarks/bench_vs_basilisk.py [--case proves_ref|adcs_ref|coursework|all]
                                           [--duration 5578] [--rounds 3] [--json FILE]

The measurement is :func:`basilisk.bench.measure_cases` (its module docstring lists
the kinds of run of each case); with ``--case all`` every kind of every case is flown in turn in
each round, all in child processes of this one. ``fprime-lite bench`` runs the proves_ref case as
its ``basilisk`` piece.
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys

from basilisk.bench import (CASES, GOALS, INSTALL_HINT, ORBIT_S, basilisk_installed, measure_cases,
                                          plausibility_text)


def _proves_ref(r: dict) -> None:
    b = r["best_real_time_factor"]
    print(f"  proves_ref 50 Hz  Basilisk case A {b['basilisk_50hz']:7.0f}   lean {b['basilisk_lean_50hz']:7.0f}   "
          f"fprime-lite run {b['fprime_lite_run_50hz']:7.0f}   ratio to the faster "
          f"{r['run_50hz_over_fastest_basilisk']:.2f} (median rounds {r['median_run_50hz_over_fastest_basilisk']:.2f}; "
          f"goal {GOALS['run_50hz_over_fastest_basilisk']})")
    print(f"  proves_ref 50 Hz  deployment without outputs {b['fprime_lite_deployment_50hz']:7.0f}   "
          f"ratio {r['deployment_50hz_over_basilisk']:.2f} / lean {r['deployment_50hz_over_basilisk_lean']:.2f} "
          "(context)")
    print(f"  proves_ref 20 Hz  Basilisk case A {b['basilisk_20hz']:7.0f}   fprime-lite plant-only "
          f"{b['fprime_lite_plant_20hz']:7.0f}   ratio {r['plant_20hz_over_basilisk']:.2f} "
          f"(median rounds {r['median_plant_20hz_over_basilisk']:.2f}; context)")
    runs = r["runs"]
    print(f"    case A |ω| < 1 °/s at: Basilisk {runs['basilisk_20hz'][0]['time_below_1_deg_s']} s, "
          f"Basilisk lean {runs['basilisk_lean_50hz'][0]['time_below_1_deg_s']} s, "
          f"fprime-lite {runs['fprime_lite_plant_20hz'][0]['time_below_1_deg_s']} s")


def _newer(case: str, r: dict) -> None:
    b = r["best_real_time_factor"]
    for name, ours, theirs in CASES[case][1]:
        print(f"  {case}  {theirs} {b[theirs]:7.0f}   {ours} {b[ours]:7.0f}   ratio {r[name]:.2f} "
              f"(median rounds {r['median_' + name]:.2f}; goal {GOALS.get(name, 'none: context')})")
    for kind, figures in r["plausibility"].items():
        print(f"    {kind}: {plausibility_text(figures)}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", choices=[*CASES, "all"], default="proves_ref")
    parser.add_argument("--duration", type=float, default=ORBIT_S, help="simulated seconds per run (one orbit)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--topology", default=None,
                        help="the deployment flown (one case only; default: the case's own)")
    parser.add_argument("--json", default="bench_vs_basilisk.json")
    args = parser.parse_args(argv)
    if not basilisk_installed():
        print(f"Basilisk is not installed: {INSTALL_HINT}", file=sys.stderr)
        return 2
    if not args.duration > 0 or args.rounds < 1:
        print("--duration must be positive and --rounds at least 1", file=sys.stderr)
        return 2
    cases = list(CASES) if args.case == "all" else [args.case]
    if args.topology is not None and len(cases) > 1:
        print("--topology applies to one case: give --case too", file=sys.stderr)
        return 2
    topologies = {cases[0]: args.topology} if args.topology is not None else None
    r = measure_cases(cases, args.duration, args.rounds, topologies,
                      progress=lambda s: print(s, file=sys.stderr, flush=True))
    pathlib.Path(args.json).write_text(json.dumps(r, indent=2) + "\n")
    print(f"{args.duration:.0f} s simulated per run, best of {args.rounds} rounds, real-time factors:")
    for case in cases:
        if case == "proves_ref":
            _proves_ref(r[case])
        else:
            _newer(case, r[case])
    print(f"figures written to {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
