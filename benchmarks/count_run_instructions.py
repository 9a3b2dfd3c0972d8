"""Count the instructions of a ``fprime-lite run`` (or of its truth row) under callgrind.

    PYTHONHASHSEED=0 valgrind --tool=callgrind --collect-atstart=no --toggle-collect=starmap_next \\
        python benchmarks/count_run_instructions.py TOPOLOGY DURATION_S MODE OUT_DIR

Only what runs inside ``itertools.starmap`` is counted. MODE ``run``: ``run_deployment`` after the
topology's load (every output written, plots off: what ``fprime-lite run --no-plots`` does after the
load). MODE ``deploy``: the same flight without any output (``Deployment(loaded)``, ``start()`` and
``run_for(DURATION_S)``: the benchmark's ``fprime_lite_deployment_50hz`` kind, its start included),
so that ``run`` - ``deploy`` is what the outputs, the reports and the dictionary cost. MODE ``runproc``:
``run`` with ``writer="process"`` (the default of ``fprime-lite run`` on two cores): the telemetry files
and the truth rows are formatted by a forked writer process, which callgrind counts in a file of its own
(``callgrind.out.PID`` of the child); the flight's process's count is what stays on the flight's core.
MODE ``runproc-without-row``, ``runproc-without-report-clock``, ``runproc-without-packets``: ``runproc``
with one piece of what stays in the flight's process left out, so that its difference from ``runproc`` is
that piece's count: the truth rows (the trace sampled once, at its start), the detumble report's time
listener (called at every tick to credit the manager's states), the hand-over of the telemetry packets
to the writer process (``OutputWriter.packet`` does nothing: the child records no telemetry).
MODE ``plant``: the deployment's plant-only counterpart instead (``detumble.sim.runner.run`` on the
topology's scenario with ``detumble.tools.bench.PLANT_ONLY_LAWS``' law, as ``measure_deployment`` times it; the
fresh ``Plant`` built outside the count; OUT_DIR unused), so that ``deploy`` - ``plant`` is the F´ part.
MODE ``row``:
the flight runs uncounted except ``SimulatedSpacecraft.truth`` and the truth-trace callbacks (the
run reports' sampled rows). MODE ``recorder``: uncounted except the ground recorder's handling of
each downlinked packet (``GroundRecorder.receive``: decoding, ``events.log``, ``channels.csv``, the
wide table, the reports' event callbacks). The total is callgrind's ``summary`` line
(``callgrind_annotate`` breaks it down by C function). Instruction counts do not depend on the
machine's load (docs/performance.md, "Issue 32: the 1 Hz truth/report row").
"""

from __future__ import annotations

import itertools
import sys

from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.tools.runner import run_deployment


def _count_row_only() -> None:
    from detumble.drivers.spacecraft import SimulatedSpacecraft

    truth, set_trace = SimulatedSpacecraft.truth, SimulatedSpacecraft.set_trace

    def counted_truth(self):
        return next(itertools.starmap(truth, ((self,),)))

    def counted_set_trace(self, callback, interval_us=1_000_000):
        if callback is None:
            return set_trace(self, None)
        return set_trace(self, lambda s: next(itertools.starmap(callback, ((s,),))), interval_us)

    SimulatedSpacecraft.truth = counted_truth  # type: ignore[method-assign]
    SimulatedSpacecraft.set_trace = counted_set_trace  # type: ignore[method-assign]


def _count_recorder_only() -> None:
    from fprime_lite.ground.downlink import GroundRecorder

    receive = GroundRecorder.receive

    def counted_receive(self, data, context=0):
        return next(itertools.starmap(receive, ((self, data, context),)))

    GroundRecorder.receive = counted_receive  # type: ignore[method-assign]


def _leave_out(piece: str) -> None:
    """``runproc`` without ``piece`` (see the MODEs ``runproc-without-…``)."""
    if piece == "row":
        from detumble.drivers.spacecraft import SimulatedSpacecraft

        set_trace = SimulatedSpacecraft.set_trace

        def once(self, callback, interval_us=1_000_000):
            return set_trace(self, callback, 10**15 if callback is not None else interval_us)

        SimulatedSpacecraft.set_trace = once  # type: ignore[method-assign]
    elif piece == "report-clock":
        from detumble.reports.detumble_report import DetumbleRunReport
        from fprime_lite.deploy.scheduler import Scheduler

        add = Scheduler.add_time_listener

        def add_but_the_report(self, listener):
            if getattr(listener, "__func__", None) is not DetumbleRunReport._on_time:
                add(self, listener)

        Scheduler.add_time_listener = add_but_the_report  # type: ignore[method-assign]
    elif piece == "packets":
        from fprime_lite.ground.writer_process import OutputWriter

        OutputWriter.packet = lambda self, data, reception_us: None  # type: ignore[method-assign]


_WITHOUT = ("runproc-without-row", "runproc-without-report-clock", "runproc-without-packets")


def main(argv: list[str]) -> int:
    if len(argv) != 4 or argv[2] not in ("run", "runproc", "row", "deploy", "plant", "recorder", *_WITHOUT):
        print(__doc__)
        return 2
    topology, duration_s, mode, out = argv[0], float(argv[1]), argv[2], argv[3]
    if mode in _WITHOUT:
        _leave_out(mode.removeprefix("runproc-without-"))
        mode = "runproc"
    if mode == "row":
        _count_row_only()
    elif mode == "recorder":
        _count_recorder_only()
    loaded = load_topology(topology)

    def fly() -> None:
        run_deployment(loaded, out, duration_s=duration_s, plots=False, quiet=True,
                       writer="process" if mode == "runproc" else "inline")

    def fly_without_outputs() -> None:
        from fprime_lite.deploy.deployment import Deployment

        deployment = Deployment(loaded)
        deployment.start()
        deployment.run_for(duration_s)

    def fly_plant_only() -> None:
        from detumble.sim.plant import Plant
        from detumble.sim.runner import run as plant_only
        from detumble.tools.bench import PLANT_ONLY_LAWS

        scenario = loaded.resources["spacecraft"].scenario
        law = PLANT_ONLY_LAWS.get(scenario.name, scenario.control.law)
        fresh = Plant(scenario)
        next(itertools.starmap(lambda: plant_only(scenario, law=law, duration_s=duration_s, plant=fresh), ((),)))

    if mode == "deploy":
        next(itertools.starmap(fly_without_outputs, ((),)))
    elif mode == "plant":
        fly_plant_only()
    elif mode in ("run", "runproc"):
        next(itertools.starmap(fly, ((),)))
    else:
        fly()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
