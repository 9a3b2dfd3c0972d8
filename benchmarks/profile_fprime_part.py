"""Where a deployment's F´ part goes: the deployment's tick against its plant-only counterpart, by module,
and each rate-group member's own CPU.

    python benchmarks/profile_fprime_part.py [TOPOLOGY] [--duration S] [--law LAW] [--top N]

Flies ``TOPOLOGY`` (default ``deployments/adcs_ref/topology.yaml``) for ``--duration`` simulated seconds
after 20 s of flight, under ``cProfile``, then the plant-only runner on the deployment's own scenario with
the matching law (``detumble.tools.bench.PLANT_ONLY_LAWS``, or ``--law``) for as long, and prints:

- Python calls a tick of the fastest rate group on each side (deterministic: the same on any machine);
- by module, the deployment's profiled time minus the counterpart's, and the calls a tick it adds
  (the profiler inflates every call alike, so read shares, not µs);
- each rate-group member's own CPU a tick (``time.thread_time_ns`` around each call, a second flight
  without the profiler), beside the plant step and the electrical and thermal models; a queued (async)
  member's figure is its enqueue, its handler runs when the scheduler drains the queue.

A measurement for reading, never asserted anywhere (docs/performance.md, issue 32's tick section).
"""

from __future__ import annotations

import argparse
import collections
import cProfile
import pathlib
import pstats
import sys
import time

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.rate_groups import RateGroupBase

from detumble.sim.runner import run as plant_only
from detumble.tools.bench import PLANT_ONLY_LAWS, tick_rate_group

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _by_module(profile: cProfile.Profile) -> tuple[collections.Counter, collections.Counter]:
    seconds: collections.Counter = collections.Counter()
    calls: collections.Counter = collections.Counter()
    for (filename, _, _), (_, ncalls, tottime, _, _) in pstats.Stats(profile).stats.items():  # type: ignore[attr-defined]
        key = filename.split("/src/", 1)[1] if "/src/" in filename else ("builtins" if filename == "~" else
                                                                          pathlib.Path(filename).name)
        seconds[key] += tottime
        calls[key] += ncalls
    return seconds, calls


def _fly(topology: pathlib.Path):
    loaded = load_topology(topology)
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(20.0)
    group, period_s = tick_rate_group(loaded)
    return loaded, deployment, group, period_s


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("topology", nargs="?", default=str(ROOT / "deployments/adcs_ref/topology.yaml"))
    parser.add_argument("--duration", type=float, default=100.0, help="simulated seconds profiled (default 100)")
    parser.add_argument("--law", help="the counterpart's plant-only law (default: by the scenario)")
    parser.add_argument("--top", type=int, default=25, help="modules listed (default 25)")
    args = parser.parse_args(argv)

    loaded, deployment, group, period_s = _fly(pathlib.Path(args.topology))
    scenario = loaded.resources["spacecraft"].scenario
    law = args.law or PLANT_ONLY_LAWS.get(scenario.name)
    if law is None:
        print(f"no plant-only law known for scenario {scenario.name!r}; give --law", file=sys.stderr)
        return 2
    c0 = group.cycles
    profile = cProfile.Profile()
    profile.enable()
    deployment.run_for(args.duration)
    profile.disable()
    ticks = group.cycles - c0
    dep_s, dep_n = _by_module(profile)
    profile = cProfile.Profile()
    profile.enable()
    plant_only(scenario, law=law, duration_s=args.duration)
    profile.disable()
    po_s, po_n = _by_module(profile)

    extra = sum(dep_s.values()) - sum(po_s.values())
    print(f"{pathlib.Path(args.topology).parent.name}: {sum(dep_n.values()) / ticks:.1f} Python calls a tick, "
          f"plant-only {law} {sum(po_n.values()) / ticks:.1f}")
    print("share of (deployment - plant-only) profiled time, and calls a tick added, by module:")
    rows = {k: (dep_s[k] - po_s[k], (dep_n[k] - po_n[k]) / ticks) for k in set(dep_s) | set(po_s)}
    for key, (s, n) in sorted(rows.items(), key=lambda kv: -abs(kv[1][0]))[:args.top]:
        print(f"  {s / extra * 100:6.1f} %  {n:+7.2f} calls/tick  {key}")

    # each member's own CPU, in a second flight without the profiler
    spent: collections.Counter = collections.Counter()
    clock = time.thread_time_ns

    def timed(label, fn):
        def call(*a):
            t = clock()
            try:
                return fn(*a)
            finally:
                spent[label] += clock() - t
        return call

    loaded, deployment, group, period_s = _fly(pathlib.Path(args.topology))
    for name, instance in loaded.topology.instances.items():
        rg = instance.component
        if isinstance(rg, RateGroupBase):
            port = rg.output_port("RateGroupMemberOut")
            members = []
            for i in range(rg.MAX_MEMBERS):
                target = port.targets[i]
                if target is not None:
                    label = f"{name.rsplit('.', 1)[-1]}[{i}] {target[0].component.name}.{target[0].name}"
                    members.append((i, timed(label, port.calls[i]), rg.contexts[i]))
            rg._members, rg._members_version = members, port.version
    spacecraft = loaded.resources["spacecraft"]
    spacecraft.plant.step_ns = timed("plant step", spacecraft.plant.step_ns)
    if spacecraft.power is not None:
        spacecraft.power.step = timed("power step", spacecraft.power.step)
        spacecraft.thermal.step = timed("thermal step", spacecraft.thermal.step)
    c0, t0 = group.cycles, clock()
    deployment.run_for(args.duration)
    ticks, total = group.cycles - c0, clock() - t0
    print(f"own CPU a tick (wrappers included; {total / ticks / 1000:.1f} µs a tick in all, this machine's load):")
    for label, ns in spent.most_common():
        print(f"  {ns / total * 100:6.1f} %  {label}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
