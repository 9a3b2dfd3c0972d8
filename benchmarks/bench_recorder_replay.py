"""CPU per telemetry packet and per channel update of the run recorder, TlmChan's packets against
TlmPacketizer's (docs/performance.md "The recorder and packetized telemetry").

Flies each topology for ``--duration`` simulated seconds, keeps every packet its telemetry service
sent, then replays them ``--rounds`` times into a fresh :class:`~fprime_lite.ground.downlink.GroundRecorder`
(the run's own clock stepped to each packet's reception) and prints the best round's CPU time per
packet and per channel update written to ``channels.csv``.

    python benchmarks/bench_recorder_replay.py --duration 300 --rounds 5
    python benchmarks/bench_recorder_replay.py --level 6      # every packet of the set goes down
"""

from __future__ import annotations

import argparse
import pathlib
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _downlink(topology: pathlib.Path, seconds: float, level: int | None) -> tuple[object, list[tuple[int, bytes]]]:
    """(the loaded deployment, [(reception µs, packet)] of its telemetry service's downlink)."""
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.tools.api import load

    loaded = load(str(topology))
    topo = loaded.topology
    service = topo.instance(topo.patterns["telemetry"]).component
    if level is not None and hasattr(service, "start_level"):
        service.start_level = level
    packets: list[tuple[int, bytes]] = []
    deployment = Deployment(loaded)
    clock = loaded.clock
    service.output_port("PktSend").connect_callable(
        0, lambda data, context=0: packets.append((clock.now().total_us, bytes(data))), "bench")
    deployment.start()
    deployment.run_for(seconds)
    return loaded, packets


def _replay(loaded, packets: list[tuple[int, bytes]], rounds: int) -> tuple[float, int]:
    """(best CPU seconds of one replay, channel updates written)."""
    from fprime_lite.ground.downlink import GroundRecorder
    from fprime_lite.model.time import Time

    class _Clock:
        def __init__(self) -> None:
            self.us = packets[0][0] if packets else 0

        def now(self) -> Time:
            return Time.from_us(self.us)

    best, updates = float("inf"), 0
    for _ in range(rounds):
        with tempfile.TemporaryDirectory() as folder:
            clock = _Clock()
            recorder = GroundRecorder(loaded.topology, folder, clock=clock)
            start = time.process_time()
            for us, data in packets:
                clock.us = us
                recorder.receive(data)
            best = min(best, time.process_time() - start)
            updates = recorder.channel_updates
            recorder.close()
    return best, updates


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=300.0, help="simulated seconds flown (default 300)")
    parser.add_argument("--rounds", type=int, default=5, help="replays; the best is printed (default 5)")
    parser.add_argument("--level", type=int, default=None, help="the packetizer's send level (default: the topology's)")
    args = parser.parse_args(argv)
    for name in ("topology.yaml", "topology_packetized.yaml"):
        loaded, packets = _downlink(ROOT / "deployments" / "proves_ref" / name, args.duration, args.level)
        cpu, updates = _replay(loaded, packets, args.rounds)
        print(f"{name}: {len(packets)} packets, {updates} channel updates; best of {args.rounds}: "
              f"{cpu * 1e3:.1f} ms CPU, {cpu / max(len(packets), 1) * 1e6:.1f} µs/packet, "
              f"{cpu / max(updates, 1) * 1e6:.2f} µs/update")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
