"""Time by the wall clock where a deployment's tick goes: each piece's µs a tick, calls a tick and µs a call.

    python benchmarks/time_tick_pieces.py TOPOLOGY PIECE [PIECE ...] [--after 20] [--duration 300] [--rate 50]

A PIECE is written as for ``count_tick_pieces.py``: ``module:Class.method`` (the class's function replaced
before the topology is loaded, so that ports and listeners bind the replacement) or
``@Instance.name:attr[.attr]`` (a topology instance's attribute, replaced after the uncounted seconds).
The deployment flies ``--after`` simulated seconds, then ``--duration`` seconds with nothing wrapped (the
plain tick), then ``--duration`` seconds with every piece inside a pair of ``time.perf_counter`` reads.
A tick is one of the fastest rate group's (``--rate``, Hz).

Why beside the callgrind counts: a piece marked for ``count_tick_pieces.py`` carries its marker's frames
(thousands of instructions a call), which swamps a piece that runs in a microsecond or two. The wrapper here
costs a fraction of a microsecond a call, and the script says how much: ``wrapper_us`` is one wrapped call
of an empty function less the bare call, timed in the same process, and the wrapped window's tick less the
plain one is what all the wrappers added. A piece's figure includes the pieces it calls and their
wrappers. Wall time moves with the machine's load: compare pieces of one run, not runs of different
sittings. Nothing is asserted: a measurement for reading (docs/performance.md, issue 32, "the tick by the
wall clock").
"""

from __future__ import annotations

import argparse
import collections
import pathlib
import sys
import time
from typing import Any, Callable

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

from count_tick_pieces import resolve  # noqa: E402 - the benchmarks folder is not a package

_clock = time.perf_counter


def timed(original: Callable, key: str, seconds: collections.Counter, calls: collections.Counter) -> Callable:
    """``original`` inside a pair of clock reads: ``seconds[key]`` and ``calls[key]`` grow at each call
    (also when it raises); arguments, keywords and the answer pass through unchanged."""
    def piece(*args: Any, **kwargs: Any) -> Any:
        t0 = _clock()
        try:
            return original(*args, **kwargs)
        finally:
            seconds[key] += _clock() - t0
            calls[key] += 1
    return piece


def wrapper_cost_us(n: int = 200_000) -> float:
    """One wrapped call of an empty function less one bare call, µs (the best of five loops of ``n``)."""
    def empty() -> None:
        return None

    wrapped = timed(empty, "", collections.Counter(), collections.Counter())

    def loop(f: Callable) -> float:
        t0 = _clock()
        for _ in range(n):
            f()
        return _clock() - t0

    bare = min(loop(empty) for _ in range(5))
    return (min(loop(wrapped) for _ in range(5)) - bare) / n * 1e6


def measure(topology: str, pieces: list[str], *, after_s: float = 20.0, duration_s: float = 300.0,
            rate_hz: float = 50.0) -> dict:
    """Fly ``topology`` and time ``pieces`` (see the module's docstring); returns the figures as a dict."""
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    seconds: collections.Counter = collections.Counter()
    calls: collections.Counter = collections.Counter()
    late = [spec for spec in pieces if spec.startswith("@")]
    for spec in pieces:
        if not spec.startswith("@"):
            owner, attr, original = resolve(spec)
            setattr(owner, attr, timed(original, spec, seconds, calls))
    loaded = load_topology(topology)
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(after_s)
    ticks = duration_s * rate_hz
    t0 = _clock()
    deployment.run_for(duration_s)
    plain_us = (_clock() - t0) / ticks * 1e6
    for spec in late:
        owner, attr, original = resolve(spec, deployment)
        setattr(owner, attr, timed(original, spec, seconds, calls))
    seconds.clear()
    calls.clear()
    t0 = _clock()
    deployment.run_for(duration_s)
    wrapped_us = (_clock() - t0) / ticks * 1e6
    rows = {spec: {"us_per_tick": seconds[spec] / ticks * 1e6, "calls_per_tick": calls[spec] / ticks,
                   "us_per_call": seconds[spec] / calls[spec] * 1e6 if calls[spec] else None} for spec in pieces}
    return {"plain_tick_us": plain_us, "wrapped_tick_us": wrapped_us, "wrapper_us": wrapper_cost_us(),
            "ticks": ticks, "pieces": rows}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("topology")
    parser.add_argument("pieces", nargs="+")
    parser.add_argument("--after", type=float, default=20.0, help="untimed simulated seconds first (default 20)")
    parser.add_argument("--duration", type=float, default=300.0,
                        help="simulated seconds of each timed window (default 300)")
    parser.add_argument("--rate", type=float, default=50.0, help="the fastest rate group's rate, Hz (default 50)")
    args = parser.parse_args(argv)
    if not args.duration > 0 or args.after < 0 or not args.rate > 0:
        parser.error("--duration and --rate must be positive, --after not negative")
    r = measure(args.topology, args.pieces, after_s=args.after, duration_s=args.duration, rate_hz=args.rate)
    print(f"tick: plain {r['plain_tick_us']:.2f} µs, wrapped {r['wrapped_tick_us']:.2f} µs "
          f"(a wrapper {r['wrapper_us']:.3f} µs a call)")
    for spec, row in sorted(r["pieces"].items(), key=lambda item: -item[1]["us_per_tick"]):
        per_call = "" if row["us_per_call"] is None else f"{row['us_per_call']:8.2f} µs a call"
        print(f"{row['us_per_tick']:7.2f} µs a tick  {row['calls_per_tick']:6.2f} calls a tick  {per_call}  {spec}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
