"""Count, under callgrind, the instructions of up to eight pieces of a deployment's tick (or of its plant-only
counterpart's) in one run, each piece inclusive of everything it calls.

    PYTHONHASHSEED=0 valgrind --tool=callgrind --collect-atstart=no --toggle-collect=starmap_next \\
        --callgrind-out-file=OUT python benchmarks/count_tick_pieces.py TOPOLOGY SIDE PIECE [PIECE ...]
    callgrind_annotate --inclusive=yes --threshold=100 OUT \\
        | grep -E "$(python benchmarks/count_tick_pieces.py --markers)"

SIDE ``deploy``: the deployment flies ``--after`` simulated seconds uncounted (default 20), then ``--duration``
seconds (default 20) inside ``itertools.starmap`` (the counted window). SIDE ``plant``: the plant-only
counterpart (``detumble.sim.runner.run`` on the topology's scenario with ``detumble.tools.bench.PLANT_ONLY_LAWS``'
law, as ``count_run_instructions.py``'s MODE ``plant``), counted whole for ``--after + --duration`` seconds.

A PIECE is ``module:Class.method`` (the class's function replaced before the topology is loaded, so that
ports and listeners bind the replacement) or, on the deploy side, ``@Instance.name:attr[.attr]`` (an attribute of a
topology instance, replaced after the uncounted seconds: a rate group's ``_cycle``, a channel's ``write``).
Each piece is called through its own C function of the standard library (``MARKERS``, in the order given),
which nothing in the flight calls, so callgrind's inclusive count of that function is the piece's count in
the window (its share of the wrappers' own work included: compare the same piece on both sides, or pieces
wrapped alike). Before the window every replacement calls the original directly. Divide by the window's
ticks (``--duration`` × the fastest group's rate) for a figure a tick. The stderr lines say which piece went
through which function and each piece's calls in the window. Nothing is asserted: a measurement for reading
(docs/performance.md, "Issue 32: the F´ part piece by piece (fpart2 lane)").
"""

from __future__ import annotations

import argparse
import collections
import contextvars
import functools
import gc
import importlib
import itertools
import sys
from typing import Any, Callable


def _takewhile(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        next(itertools.takewhile(lambda _: box.append(f(*a)) or True, (None,)), None)
        return box[0]
    return call


def _dropwhile(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        next(itertools.dropwhile(lambda _: box.append(f(*a)), (None,)), None)
        return box[0]
    return call


def _filterfalse(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        next(itertools.filterfalse(lambda _: box.append(f(*a)), (None,)), None)
        return box[0]
    return call


def _groupby(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        next(itertools.groupby((None,), lambda _: box.append(f(*a))), None)
        return box[0]
    return call


def _calliter(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        next(iter(lambda: box.append(f(*a)) or 1, 0))
        return box[0]
    return call


def _context(f: Callable) -> Callable:
    run = contextvars.copy_context().run
    return lambda *a: run(f, *a)


def _reduce(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        functools.reduce(lambda _x, _y: box.append(f(*a)), (None, None))
        return box[0]
    return call


def _defaultdict(f: Callable) -> Callable:
    def call(*a: Any) -> Any:
        box: list = []
        collections.defaultdict(lambda: box.append(f(*a)))[0]
        return box[0]
    return call


#: (callgrind's name of the C function a piece is called through, the wrapper that calls it so), in order.
MARKERS = (("takewhile_next", _takewhile), ("dropwhile_next", _dropwhile), ("filterfalse_next", _filterfalse),
           ("groupby_next", _groupby), ("calliter_iternext", _calliter), ("context_run", _context),
           ("functools_reduce", _reduce), ("defdict_missing", _defaultdict))


def _switched(original: Callable, mark: Callable, on: list) -> Callable:
    """``original`` while ``on[0]`` is False, then ``original`` through ``mark``'s C function, counted there
    (``on[1][wrapper]``: the calls that went through the marker)."""
    def counted(*a: Any) -> Any:
        on[1][piece] += 1
        return original(*a)

    marked = mark(counted)

    def piece(*a: Any) -> Any:
        return marked(*a) if on[0] else original(*a)
    return piece


def resolve(spec: str, deployment: Any = None) -> tuple[Any, str, Callable]:
    """``(owner, attribute, original)`` of a PIECE: a class's function (``module:Class.method``, from the class's
    own ``__dict__``) or, with ``deployment``, a topology instance's attribute (``@Instance.name:attr[.attr]``)."""
    if deployment is not None:
        instance, path = spec[1:].split(":")
        owner = deployment.topology.instance(instance).component
        *parents, attr = path.split(".")
        for parent in parents:
            owner = getattr(owner, parent)
        return owner, attr, getattr(owner, attr)
    module, qualname = spec.split(":")
    owner_path, attr = qualname.rsplit(".", 1)
    owner = importlib.import_module(module)
    for part in owner_path.split("."):
        owner = getattr(owner, part)
    return owner, attr, owner.__dict__[attr]


def install(specs: list[str], deployment: Any = None, on: list | None = None) -> tuple[list, list]:
    """Replace each class piece of ``specs`` (or, with ``deployment``, each instance piece) by its marked
    wrapper; returns ``(on, [(marker name, spec, wrapper), ...])``: set ``on[0]`` True to route calls through
    the markers, ``on[1]`` counts each wrapper's calls from then on."""
    if len(specs) > len(MARKERS):
        raise SystemExit(f"at most {len(MARKERS)} pieces, got {len(specs)}")
    on = on if on is not None else [False, collections.Counter()]
    done = []
    for (name, mark), spec in zip(MARKERS, specs, strict=False):  # fewer pieces than markers
        if spec.startswith("@") != (deployment is not None):
            continue
        owner, attr, original = resolve(spec, deployment)
        wrapper = _switched(original, mark, on)
        setattr(owner, attr, wrapper)
        done.append((name, spec, wrapper))
    return on, done


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("topology", nargs="?")
    parser.add_argument("side", nargs="?", choices=("deploy", "plant"))
    parser.add_argument("pieces", nargs="*")
    parser.add_argument("--after", type=float, default=20.0, help="uncounted simulated seconds first (default 20)")
    parser.add_argument("--duration", type=float, default=20.0, help="counted simulated seconds (default 20)")
    parser.add_argument("--markers", action="store_true", help="print the marker functions' names as one regex")
    args = parser.parse_args(argv)
    if args.markers:
        print("|".join(name for name, _ in MARKERS) + "|starmap_next")
        return 0
    if not args.topology or not args.side or not args.pieces:
        parser.error("give TOPOLOGY, SIDE and at least one PIECE")
    gc.disable()  # counts of one tree then agree to about 0.1 % (docs/performance.md, the fpart lane)
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    on, done = install(args.pieces, None)  # before the topology's load: its instances bind their ports then
    loaded = load_topology(args.topology)
    if args.side == "plant":
        if len(done) != len(args.pieces):
            raise SystemExit("the plant side takes module:Class.method pieces only")
        from detumble.sim.plant import Plant
        from detumble.sim.runner import run as plant_only
        from detumble.tools.bench import PLANT_ONLY_LAWS

        scenario = loaded.resources["spacecraft"].scenario
        fresh = Plant(scenario)
        on[0] = True
        next(itertools.starmap(lambda: plant_only(scenario, law=PLANT_ONLY_LAWS[scenario.name],
                                                   duration_s=args.after + args.duration, plant=fresh), ((),)))
    else:
        deployment = Deployment(loaded)
        deployment.start()
        deployment.run_for(args.after)
        _, more = install(args.pieces, deployment, on)
        done += more
        on[0] = True
        next(itertools.starmap(deployment.run_for, ((args.duration,),)))
    for name, spec, wrapper in done:
        print(f"{name:18s} {spec}: {on[1][wrapper]} calls", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
