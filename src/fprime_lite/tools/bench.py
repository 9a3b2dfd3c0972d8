"""``fprime-lite bench``: speed and memory of a deployment, as ratios measured in one run.

    fprime-lite bench [TOPOLOGY] [--duration S] [--json FILE] [--memory] [--only PIECE …]

Measures, in this order and in this one process:

1. a call through a connected output port vs a plain bound-method call (ns, ratio);
2. every installed bench piece (entry points ``fprime_lite.bench``, :mod:`fprime_lite.tools.plugins`)
   on the topology — the detumble application's piece flies the deployment against its plant-only
   twin and reports the per-tick cost ratio;
3. the peak resident memory of this process;
4. with ``--memory``: peak memory of separate ``fprime-lite run`` processes of 1 h and 24 h of
   simulated time (streaming outputs must keep memory flat).

Timings depend on the machine; compare the ratios. Nothing here is asserted by the test suite.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import resource
import subprocess
import sys
import tempfile
import time
import timeit

from fprime_lite.osal.atomic import atomic_write_text
from fprime_lite.tools.plugins import BenchPiece, PluginError, bench_pieces

__all__ = ["main", "measure_port_call"]


def measure_port_call(number: int = 2_000_000, repeat: int = 7) -> dict:
    """ns per call through a connected output port vs a plain bound-method call."""
    from fprime_lite.model.component import PassiveComponent
    from fprime_lite.model.ports import OutputPort, PortType, sync_input
    from fprime_lite.model.types import I8

    start_type = PortType("Bench.Start", returns=bool, level=I8)

    class Driver(PassiveComponent):
        @sync_input(start_type)
        def start(self, level):
            return True

    class Caller(PassiveComponent):
        startOut = OutputPort(start_type)

    caller, driver = Caller("caller"), Driver("driver")
    caller.output_port("startOut").connect(0, driver.input_port("start"))
    env = {"caller": caller, "driver": driver}
    plain_timer = timeit.Timer("driver.start(5)", globals=env)
    port_timer = timeit.Timer("caller.startOut[0](5)", globals=env)
    plain = port = math.inf
    for _ in range(repeat):  # interleaved, so both see the same load on a shared machine
        plain = min(plain, plain_timer.timeit(number) / number)
        port = min(port, port_timer.timeit(number) / number)
    return {"plain_ns": plain * 1e9, "port_ns": port * 1e9, "ratio": port / plain}


def _peak_rss_mb(who=resource.RUSAGE_SELF) -> float:
    return resource.getrusage(who).ru_maxrss / 1024.0  # Linux reports KiB


def _child_peak_memory(topology, seconds: float) -> dict:
    """Run ``fprime-lite run`` for ``seconds`` in a fresh process; return its peak RSS."""
    with tempfile.TemporaryDirectory() as out:
        code = ("import json, resource, sys; from fprime_lite.tools.cli import main; "
                f"rc = main(['run', {str(topology)!r}, '--duration', '{seconds}', '--out', {out + '/run'!r}, "
                "'--no-progress', '--no-plots']); "
                "print(json.dumps({'rc': rc, 'peak_rss_mb': resource.getrusage(resource.RUSAGE_SELF).ru_maxrss "
                "/ 1024}))")
        t0 = time.perf_counter()
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
    line = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else "{}"
    result = json.loads(line)
    result.update({"sim_seconds": seconds, "wall_s": wall})
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="fprime-lite bench", description=__doc__.splitlines()[0])
    parser.add_argument("topology", nargs="?", default="topology.yaml",
                        help="topology to measure (default: ./topology.yaml)")
    parser.add_argument("--topology", dest="topology_opt", metavar="TOPOLOGY", help="same as the positional argument")
    parser.add_argument("--only", action="append", metavar="PIECE", help="run only these bench pieces")
    parser.add_argument("--duration", type=float, help="simulated seconds (default: one orbit)")
    parser.add_argument("--json", metavar="FILE", default="bench.json", help="where to write the figures")
    parser.add_argument("--memory", action="store_true", help="also measure 1 h and 24 h runs' peak memory")
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0)
    args.topology = args.topology_opt or args.topology
    try:
        pieces = bench_pieces()
    except PluginError as exc:
        print(f"fprime-lite bench: {exc}", file=sys.stderr)
        return 2
    unknown = sorted(set(args.only or ()) - set(pieces))
    if unknown:
        print(f"fprime-lite bench: no bench piece {', '.join(unknown)}; installed: {', '.join(pieces) or 'none'}",
              file=sys.stderr)
        return 2
    if pieces and not pathlib.Path(args.topology).is_file():
        print(f"fprime-lite bench: {args.topology}: no such topology file — give the path of a topology YAML "
              f"file", file=sys.stderr)
        return 2

    results: dict = {"python": sys.version.split()[0]}
    results["port_call"] = measure_port_call()
    for name, piece in pieces.items():
        if not args.only or name in args.only:
            results[name] = piece.measure(args)
    results["peak_rss_mb"] = _peak_rss_mb()
    if args.memory:
        one_hour = _child_peak_memory(args.topology, 3600)
        one_day = _child_peak_memory(args.topology, 86400)
        results["memory"] = {"run_1h": one_hour, "run_24h": one_day,
                             "growth_ratio": one_day.get("peak_rss_mb", 0) / max(one_hour.get("peak_rss_mb", 1), 1e-9)}
    atomic_write_text(args.json, json.dumps(results, indent=2) + "\n")
    _print(results, pieces)
    print(f"figures written to {args.json}")
    return 0


def _print(r: dict, pieces: dict[str, BenchPiece]) -> None:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    p = r["port_call"]
    table = Table(title="fprime-lite bench (ratios are what to compare)", show_header=True)
    table.add_column("figure")
    table.add_column("value", justify="right")
    table.add_column("target", justify="right")
    table.add_row("port call / plain call", f"{p['port_ns']:.1f} ns / {p['plain_ns']:.1f} ns = {p['ratio']:.2f}",
                  "≤ 1.5")
    for name, piece in pieces.items():
        if name in r:
            for row in piece.rows(r[name]):  # a plug-in's text is shown as written ("pip install -e '.[bsk]'")
                table.add_row(*(escape(cell) for cell in row))
    table.add_row("peak RSS (this process)", f"{r['peak_rss_mb']:.0f} MB", "")
    if "memory" in r:
        m = r["memory"]
        table.add_row("peak RSS, 1 h run", f"{m['run_1h'].get('peak_rss_mb', float('nan')):.0f} MB", "")
        table.add_row("peak RSS, 24 h run", f"{m['run_24h'].get('peak_rss_mb', float('nan')):.0f} MB", "≤ 200 MB")
        table.add_row("24 h / 1 h", f"{m['growth_ratio']:.3f}", "≤ 1.10")
    Console().print(table)


if __name__ == "__main__":
    sys.exit(main())
