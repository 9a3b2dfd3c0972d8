"""Count the instructions of the run recorder alone, on a fixed downlink (issue 32).

    python benchmarks/count_recorder_replay.py capture TOPOLOGY DURATION_S PACKETS.pickle
    PYTHONHASHSEED=0 valgrind --tool=callgrind --collect-atstart=no --toggle-collect=starmap_next \\
        python benchmarks/count_recorder_replay.py count PACKETS.pickle TOPOLOGY OUT_DIR

``capture`` flies ``fprime-lite run`` (plots off) for DURATION_S and keeps, instead of recording them,
every packet the run's :class:`~fprime_lite.ground.downlink.GroundRecorder` would receive, with its
reception time (µs of the deployment's clock). ``count`` replays them into a fresh recorder (the
run's: the report's ``on_event`` callback stands in as a list's ``append``, the clock is stepped to each
packet's reception) inside one ``itertools.starmap`` call, so only the recorder's work is counted,
and leaves its ``events.log``, ``channels.csv`` and ``channels_wide.csv`` in OUT_DIR.

Unlike ``count_run_instructions.py ... recorder``, every revision replays the same bytes (the rate
groups' ``RgMaxTime`` are wall-clock measurements, different in each flight): counts of two
revisions compare exactly, and their files can be compared byte for byte (``cmp``). It also runs in
about a minute under callgrind, the flight not being counted.
"""

from __future__ import annotations

import itertools
import pickle
import sys
import tempfile


def capture(topology: str, duration_s: float, path: str) -> int:
    from fprime_lite.deploy.topology_loader import load_topology
    from fprime_lite.ground.downlink import GroundRecorder
    from fprime_lite.tools.runner import run_deployment

    loaded = load_topology(topology)
    clock = loaded.clock
    packets: list[tuple[int, bytes]] = []

    def keep(self, data, context=0):
        packets.append((clock.now().total_us, bytes(data)))

    GroundRecorder.receive = keep  # type: ignore[method-assign]
    with tempfile.TemporaryDirectory() as out:
        run_deployment(loaded, out, duration_s=duration_s, plots=False, quiet=True)
    with open(path, "wb") as fh:
        pickle.dump(packets, fh)
    print(f"{len(packets)} packets")
    return 0


def count(path: str, topology: str, out: str) -> int:
    from fprime_lite.deploy.topology_loader import load_topology
    from fprime_lite.ground.downlink import GroundRecorder
    from fprime_lite.model.time import Time

    with open(path, "rb") as fh:
        packets: list[tuple[int, bytes]] = pickle.load(fh)
    loaded = load_topology(topology)
    base, context = loaded.clock.time_base, loaded.clock.context

    class Clock:
        us = packets[0][0] if packets else 0

        def now(self) -> Time:
            return Time.from_us(self.us, base, context)

    clock = Clock()
    events: list = []
    recorder = GroundRecorder(loaded.topology, out, clock=clock, on_event=events.append)

    def replay() -> None:
        for us, data in packets:
            clock.us = us
            recorder.receive(data)

    next(itertools.starmap(replay, ((),)))
    recorder.close()
    print(f"{len(packets)} packets, {recorder.channel_updates} channel updates, {len(events)} events")
    return 0


def main(argv: list[str]) -> int:
    if len(argv) == 4 and argv[0] == "capture":
        return capture(argv[1], float(argv[2]), argv[3])
    if len(argv) == 4 and argv[0] == "count":
        return count(argv[1], argv[2], argv[3])
    print(__doc__)
    return 2


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
