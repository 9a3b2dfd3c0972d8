"""FPP load + bind time of a reference deployment (issue 30's target: proves_ref in at most 2 s).

Run: ``python benchmarks/bench_fpp_load.py [--deployment proves_ref] [--repeat 5]``. Prints the
time of the first load in a fresh process (imports of the implementation modules included) and
the median of the repeats that follow (analysis of the FPP with the framework's definitions,
binding and checking every component): ``fprime_lite.deploy.fpp.loader.load_fpp``.
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import time

from fprime_lite.deploy.fpp.loader import load_fpp

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--deployment", default="proves_ref")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    folder = ROOT / "deployments" / args.deployment / "fpp"
    files = [folder / "components.fpp", folder / "topology.fpp"]
    start = time.perf_counter()
    model = load_fpp(files)
    first = time.perf_counter() - start
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        load_fpp(files)
        times.append(time.perf_counter() - start)
    print(f"{args.deployment}: {len(model.instances)} instances, {len(model.connections)} connections; "
          f"first load + bind {first:.2f} s (with imports), then median {statistics.median(times):.2f} s "
          f"over {args.repeat}")


if __name__ == "__main__":
    main()
