"""FPP load + bind time of a reference deployment (issue 30's target: proves_ref in at most 2 s).

Run: ``python benchmarks/bench_fpp_load.py [--deployment proves_ref] [--repeat 5]``. Prints, for
this fresh process, the import of the loader (fprime-lite's framework), the first load (F´'s FPP
analysis, the imports of the implementation modules, binding and checking every component) and
their sum, the cold figure of the target; then the median of the repeats that follow (warm:
analysis + binding only): ``fprime_lite.deploy.fpp.loader.load_fpp``.
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import time

START = time.perf_counter()
from fprime_lite.deploy.fpp.loader import load_fpp  # noqa: E402 - its import is part of the cold time

IMPORTED = time.perf_counter() - START
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
          f"cold {IMPORTED + first:.2f} s (loader import {IMPORTED:.2f} s + first load + bind {first:.2f} s), "
          f"then warm median {statistics.median(times):.2f} s over {args.repeat}")


if __name__ == "__main__":
    main()
