"""Channel writes a tick of a deployment's fastest rate group, by component and by channel.

    python benchmarks/count_channel_writes.py [TOPOLOGY] [--after S] [--duration S] [--top N]

Flies ``TOPOLOGY`` (default ``deployments/adcs_ref/topology.yaml``) for ``--after`` simulated seconds (default 20),
then counts for ``--duration`` seconds (default 10) every write that reaches TlmChan's table (``tlmSend``'s latest
values: the generated writers' assignments and ``TlmRecv``'s alike), and prints the writes a tick by component and
the ``--top`` channels. Deterministic (simulated time); a measurement for reading (docs/performance.md, issue 32).
"""

from __future__ import annotations

import argparse
import collections
import pathlib
import sys

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.tlm_chan import TlmChan

from detumble.tools.bench import tick_rate_group

ROOT = pathlib.Path(__file__).resolve().parents[1]


class _CountingTable(dict):
    """TlmChan's ``_latest`` that counts every assignment by channel id."""

    def __init__(self, table: dict, counts: collections.Counter):
        super().__init__(table)
        self.counts = counts

    def __setitem__(self, chan_id, entry):
        self.counts[chan_id] += 1
        super().__setitem__(chan_id, entry)


def count_writes(topology: pathlib.Path, after_s: float, duration_s: float) -> tuple[dict[str, float], float]:
    """``({"component.channel": writes a tick}, ticks counted)`` over ``duration_s`` after ``after_s`` of flight."""
    loaded = load_topology(topology)
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(after_s)
    names = {}
    stores = []
    for component in loaded.topology.components():
        for name, channel in component.channels.items():
            names[channel.id] = f"{component.name}.{name}"
        if isinstance(component, TlmChan):
            stores.append(component)
    counts: collections.Counter = collections.Counter()
    for store in stores:
        store._latest = _CountingTable(store._latest, counts)
    deployment.run_for(duration_s)
    _, period_s = tick_rate_group(loaded)
    ticks = duration_s / period_s
    return {names.get(k, f"0x{k:X}"): v / ticks for k, v in counts.items()}, ticks


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("topology", nargs="?", type=pathlib.Path,
                        default=ROOT / "deployments" / "adcs_ref" / "topology.yaml")
    parser.add_argument("--after", type=float, default=20.0, help="simulated seconds flown before counting")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds counted")
    parser.add_argument("--top", type=int, default=20, help="channels listed")
    args = parser.parse_args(argv)
    per_channel, ticks = count_writes(args.topology, args.after, args.duration)
    by_component: collections.Counter = collections.Counter()
    for name, rate in per_channel.items():
        by_component[name.split(".")[0]] += rate
    print(f"{args.topology}: {sum(per_channel.values()):.2f} channel writes a tick ({ticks:.0f} ticks counted)")
    print("by component:")
    for name, rate in by_component.most_common():
        print(f"  {rate:6.2f}  {name}")
    print("by channel:")
    for name, rate in sorted(per_channel.items(), key=lambda kv: -kv[1])[:args.top]:
        print(f"  {rate:6.2f}  {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
