"""FPP load + bind time of a reference deployment (issue 30's target: proves_ref in at most 2 s).

Run: ``python benchmarks/bench_fpp_load.py [--deployment proves_ref] [--repeat 5] [--processes 5]``.
Prints, for this fresh process, the import of the loader (fprime-lite's framework), the first load
(F´'s FPP analysis, the imports of the implementation modules, binding and checking every
component) and their sum, the cold figure of the target; then the median of the repeats that
follow (warm: analysis + binding only): ``fprime_lite.deploy.fpp.loader.load_fpp``.

With ``--processes N`` it first writes the bytecode caches of ``src/`` (``compileall``, as an
installed package has them: with ``PYTHONDONTWRITEBYTECODE`` set and no caches, every cold import
would compile the sources and the figure would measure the compiler), then runs N fresh processes
and prints each one's cold figure and their median (wall and CPU time: under load the CPU time is
the steadier figure).
"""

from __future__ import annotations

import argparse
import compileall
import pathlib
import statistics
import subprocess
import sys
import time

START = time.perf_counter()
START_CPU = time.process_time()
from fprime_lite.deploy.fpp.loader import load_fpp  # noqa: E402 - its import is part of the cold time

IMPORTED = time.perf_counter() - START
ROOT = pathlib.Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--deployment", default="proves_ref")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--processes", type=int, default=0,
                        help="run this many fresh processes (after writing the bytecode caches) and summarise")
    args = parser.parse_args()
    if args.processes:
        compileall.compile_dir(str(ROOT / "src"), quiet=1)
        colds: list[float] = []
        cpus: list[float] = []
        for _ in range(args.processes):
            out = subprocess.run([sys.executable, __file__, "--deployment", args.deployment, "--repeat", "1"],
                                 check=True, capture_output=True, text=True).stdout
            print(out.strip())
            colds.append(float(out.split("cold ", 1)[1].split(" s", 1)[0]))
            cpus.append(float(out.split(" s, ", 1)[1].split(" s CPU", 1)[0]))
        print(f"{args.deployment}: cold over {args.processes} fresh processes: "
              f"median {statistics.median(colds):.2f} s, "
              f"min {min(colds):.2f} s, max {max(colds):.2f} s; CPU median {statistics.median(cpus):.2f} s")
        return
    folder = ROOT / "deployments" / args.deployment / "fpp"
    files = [folder / "components.fpp", folder / "topology.fpp"]
    start = time.perf_counter()
    model = load_fpp(files)
    first = time.perf_counter() - start
    cpu = time.process_time() - START_CPU
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        load_fpp(files)
        times.append(time.perf_counter() - start)
    print(f"{args.deployment}: {len(model.instances)} instances, {len(model.connections)} connections; "
          f"cold {IMPORTED + first:.2f} s, {cpu:.2f} s CPU "
          f"(loader import {IMPORTED:.2f} s + first load + bind {first:.2f} s), "
          f"then warm median {statistics.median(times):.2f} s over {args.repeat}")


if __name__ == "__main__":
    main()
