"""``fprime-lite run``: fly a loaded deployment for a while and write what it produced.

Outputs in the run folder, each streamed or written atomically:

- ``events.log`` and ``channels.csv`` — the downlink as the ground receives it (decoded packets of
  the event manager and the telemetry channelizer, at the telemetry rate group's tick);
- ``dictionary.json`` — the F´ JSON dictionary of the deployment;
- ``summary.json`` — the run's figures (below);
- whatever the topology's *report* resources add (the detumble report writes ``truth.csv`` and PNG
  plots).

The run's folder is also the root of every file service (FileUplink, FileDownlink, FileManager)
whose topology entry gives no ``root``: uplinked files land there, and only files there can be
downlinked, moved or removed (``file_root`` widens that for ``fprime-lite conformance``).

A report resource is any resource with some of these methods: ``begin(deployment, out_dir)``,
``on_event(decoded_event)``, ``progress() -> dict``, ``summary() -> dict``,
``finish(out_dir, plots=bool) -> [paths]``.
"""

from __future__ import annotations

import json
import os
import pathlib
import sys
import time
from typing import Mapping

from fprime_lite.osal.atomic import atomic_write_text
from fprime_lite.osal.confine import Confinement
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.resources import SimulationEnded
from fprime_lite.deploy.dictionary import write_dictionary
from fprime_lite.ground.downlink import DecodedEvent, GroundRecorder
from fprime_lite.ground.writer_process import OutputWriter, choose_writer
from fprime_lite.svc.cmd_sequencer import CmdSequencer
from fprime_lite.svc.file_downlink import FileDownlink
from fprime_lite.svc.file_manager import FileManager
from fprime_lite.svc.file_uplink import FileUplink
from fprime_lite.svc.rate_groups import RateGroupBase
from fprime_lite.deploy.topology_loader import LoadedDeployment
from fprime_lite.tools.interrupt import stop_on_signals
from fprime_lite.tools.stop_condition import CHECK_INTERVAL_S, StopCondition, holds_all, parse_stop_condition

__all__ = ["run_deployment", "use_board_as_flash", "run_duration", "file_root_problem", "DEFAULT_DURATION_S",
           "flight_problems", "PROGRESS_STEP_S", "WALL_CLOCK_SUMMARY_KEYS", "wall_clock_channels"]

#: Simulated seconds between progress updates (and between chunks of the run).
PROGRESS_STEP_S = 10.0

#: Simulated seconds of a run when neither the caller nor the topology's ``run.duration_s`` says.
DEFAULT_DURATION_S = 600.0


def file_root_problem(file_root) -> str | None:
    """What is wrong with ``file_root`` as a run's file-service root, or None: it must be an existing
    folder holding the working directory (relative paths given to the file services resolve against the
    working directory, as on F´'s ground; ``fprime-lite run --file-root``, ``run(file_root=...)``)."""
    if file_root is None:
        return None
    root = pathlib.Path(file_root)
    if not root.is_dir():
        return "not an existing folder"
    if not pathlib.Path.cwd().resolve().is_relative_to(root.resolve()):
        return (f"the working directory {pathlib.Path.cwd()} is not inside it — run from a folder inside "
                f"{file_root} (relative paths resolve against it)")
    return None


def run_duration(loaded: LoadedDeployment, requested: float | None) -> float:
    """``requested`` when given, else the topology's ``run.duration_s``, else :data:`DEFAULT_DURATION_S`."""
    if requested is not None:
        return float(requested)
    declared = loaded.config.run.duration_s if loaded.config is not None else None
    return declared if declared is not None else DEFAULT_DURATION_S


def _reports(loaded: LoadedDeployment) -> list:
    return [r for name, r in loaded.resources.items()
            if name not in ("clock", "scheduler", "topology_dir") and hasattr(r, "summary")]


def use_board_as_flash(loaded: LoadedDeployment, board_root) -> None:
    """Make ``board_root`` the simulated spacecraft's flash too (every resource with ``use_flash_dir``):
    on the board the flash is the one file system, so FsFormat's FORMAT erases the uplinked ``/seq``
    files with the flight state, and the state files lie at the board's ``/``."""
    for resource in loaded.resources.values():
        if callable(getattr(resource, "use_flash_dir", None)):
            resource.use_flash_dir(os.fspath(board_root))


def run_deployment(loaded: LoadedDeployment, out_dir, *, duration_s: float, parameter_file=None, sequence=None,
                   progress: bool = False, plots: bool = True, console=None, allow_warnings: bool = False,
                   stop_on_events=(), stop_when=(), quiet: bool = False, interruptible: bool = False,
                   file_root=None, board_root=None, writer: str = "inline") -> dict:
    """Start ``loaded``, run it for ``duration_s`` simulated seconds, write the outputs; return the summary.

    The summary's ``ok`` is False when the flight had handler faults, rate-group member faults,
    cycle slips or WARNING_HI/FATAL events, unless ``allow_warnings``; ``problems`` says which.
    ``stop_on_events``: full event names (``Module.inst.Event``) whose downlink ends the run early
    (a campaign stops at DetumbleCompleted). ``stop_when``: conditions (text ``KEY OP VALUE`` or
    :class:`~fprime_lite.tools.stop_condition.StopCondition`) on the reports' ``progress()`` values,
    checked once per simulated second; the run ends at the first check where all of them hold. The
    summary's ``stopped_by`` says what ended a run early (None when it ran its duration).
    ``quiet`` prints nothing (no summary table). ``interruptible``: SIGINT (Ctrl-C) and SIGTERM end the
    flight where it is, as an early stop does, and the outputs up to that instant are written as usual;
    the summary then says ``stopped_by: "interrupted"`` and ``signal`` (``"SIGINT"``/``"SIGTERM"``).
    Only the main thread can take signals; elsewhere the flag does nothing. ``file_root``: the file
    services without a root of their own are confined to this folder instead of ``out_dir`` and
    resolve relative paths against the working directory, which must lie inside it, and an uplinked
    or moved file replaces an existing one (an uplinked one in place), as F´'s services do (the F´
    integration tests need it: ``fprime-lite conformance``). ``board_root``: instead, this folder stands
    in for the board's ``/`` for the file services and the command sequencers: an absolute path such as
    ``/seq/a.bin`` names ``board_root/seq/a.bin``, a relative one resolves against it, nothing outside it
    is reachable, and files are replaced as with ``file_root`` (PROVES's suite uplinks to ``/seq``).
    ``writer``: ``"inline"`` writes every output in this process; ``"process"`` has a writer process
    format the telemetry files and the reports' row streams (``truth.csv``) on another core, the same
    bytes (:mod:`fprime_lite.ground.writer_process`; a failure there raises its ``OutputWriterError``);
    ``"auto"``: :func:`~fprime_lite.ground.writer_process.choose_writer`.
    """
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    deployment = Deployment(loaded)
    topo = deployment.topology
    cwd = os.getcwd()  # relative paths of a --file-root run, also after a restart

    def set_up_file_services() -> None:  # again after each software restart (it re-initialises them)
        for component in topo.components():  # file services without a root of their own use the run's folder
            if board_root is not None and isinstance(component, CmdSequencer):
                component.board_root = Confinement(board_root, board=True)
            if hasattr(component, "set_default_root"):
                if file_root is None and board_root is None:
                    component.set_default_root(out)
                    continue
                if board_root is not None:
                    component.set_default_root(board_root, board=True)
                else:
                    component.set_default_root(cwd, confine_to=file_root)
                if isinstance(component, (FileUplink, FileManager)):
                    component.overwrite = True  # F´'s services replace an existing file …
                if isinstance(component, FileUplink):
                    component.in_place = True  # … and FileUplink writes into it

    set_up_file_services()
    deployment.component_setup.append(set_up_file_services)
    reports = _reports(loaded)
    stop_names = frozenset(stop_on_events)
    conditions = [c if isinstance(c, StopCondition) else parse_stop_condition(c) for c in stop_when]
    stopped_by: list[str] = []

    def on_event(event: DecodedEvent) -> None:
        for r in reports:
            if hasattr(r, "on_event"):
                r.on_event(event)
        if event.name in stop_names:
            stopped_by.append(f"event {event.name}")
            deployment.scheduler.stop()

    output_writer: OutputWriter | None = None
    if choose_writer(writer) == "process" and loaded.clock is not None:
        for stream in (sys.stdout, sys.stderr):  # the child must not print what this process had buffered
            stream.flush()
        output_writer = OutputWriter(topo, out, loaded.clock.now().total_us, on_failure=deployment.scheduler.stop)
    deployment.output_writer = output_writer  # the reports' row streams go to it (open_row_stream)
    try:
        return _fly_and_write(deployment, loaded, out, output_writer, reports, on_event, stopped_by, conditions,
                              duration_s=duration_s, parameter_file=parameter_file, sequence=sequence,
                              progress=progress, plots=plots, console=console, allow_warnings=allow_warnings,
                              quiet=quiet, interruptible=interruptible)
    except BaseException:
        if output_writer is not None:
            output_writer.abandon()
        raise


def _fly_and_write(deployment: Deployment, loaded: LoadedDeployment, out: pathlib.Path,
                   output_writer: OutputWriter | None, reports, on_event, stopped_by: list[str], conditions, *,
                   duration_s: float, parameter_file, sequence, progress: bool, plots: bool, console,
                   allow_warnings: bool, quiet: bool, interruptible: bool) -> dict:
    """:func:`run_deployment` from the recorder on."""
    topo = deployment.topology
    recorder = GroundRecorder(topo, out, on_event=on_event, clock=loaded.clock,
                              telemetry_sink=output_writer.packet if output_writer is not None else None)
    recorder.attach(topo, topo.patterns.get("event"), topo.patterns.get("telemetry"))
    for instance in topo.instances.values():
        if isinstance(instance.component, FileDownlink):
            recorder.attach_file_downlink(topo, instance.qualified_name)
    if output_writer is not None:  # the child builds and writes it while the flight starts
        output_writer.write_dictionary(out / "dictionary.json")
    else:
        write_dictionary(topo, out / "dictionary.json")
    for r in reports:
        if hasattr(r, "begin"):
            r.begin(deployment, out)

    wall0 = time.perf_counter()
    deployment.start(parameter_file=parameter_file, sequence=sequence)
    start_us = deployment.scheduler.now_us
    if conditions:
        _watch_conditions(deployment.scheduler, reports, conditions, stopped_by)
    end_us = start_us + round(duration_s * 1_000_000)
    signals: list[str] = []
    ended: SimulationEnded | None = None
    with stop_on_signals(deployment.scheduler.stop, signals, enabled=interruptible):
        try:
            if progress:
                _run_with_progress(deployment, end_us, reports, console)
            else:
                deployment.scheduler.run(until_us=end_us)  # stop() (an early-stop event) ends it sooner
        except SimulationEnded as exc:  # the simulated world cannot go on: keep what flew up to here
            ended = exc
            stopped_by.insert(0, exc.kind)
    wall = time.perf_counter() - wall0
    if signals:
        stopped_by.insert(0, "interrupted")

    recorder.close()
    written: list[pathlib.Path] = []
    for r in reports:
        if hasattr(r, "finish"):
            written += r.finish(out, plots=plots) or []
    if output_writer is not None:  # the child's files finished and renamed, its counters
        counts = output_writer.close()
        recorder.undecodable += counts["undecodable"]
        recorder.channel_updates += counts["channel_updates"]
    sim_s = (deployment.scheduler.now_us - start_us) / 1e6  # less than duration_s when stopped early
    summary = _summary(deployment, recorder, reports, sim_s, wall)
    summary["stopped_by"] = stopped_by[0] if stopped_by and sim_s < duration_s - 1e-9 else None
    if summary["stopped_by"] == "interrupted":
        summary["signal"] = signals[0]
    if ended is not None:
        summary["stop_reason"] = ended.message
    summary["problems"] = ([ended.message] if ended is not None else []) + \
        flight_problems(summary, recorder.event_names_by_severity)
    summary["ok"] = ended is None and (allow_warnings or not summary["problems"])
    atomic_write_text(out / "summary.json", json.dumps(summary, indent=2) + "\n")
    if not quiet:
        _print_summary(summary, console)
    return summary


#: Event severities that make a run fail (``fprime-lite run`` exits 1 unless --allow-warnings).
FAILING_SEVERITIES = ("WARNING_HI", "FATAL")


#: How many event names a problem lists before "and N more".
PROBLEM_NAMES = 3


def flight_problems(summary: dict, event_names: Mapping[str, Mapping[str, int]] | None = None) -> list[str]:
    """What went wrong in a flight, one short phrase each (empty when nothing did). ``event_names``:
    severity → {event name: count}, which the phrases of WARNING_HI and FATAL events name (the most
    frequent first)."""
    problems = []
    for key, what in (("handler_faults", "handler fault(s)"), ("member_faults", "rate-group member fault(s)"),
                      ("cycle_slips", "cycle slip(s)")):
        if summary.get(key):
            problems.append(f"{summary[key]} {what}")
    for severity in FAILING_SEVERITIES:
        n = summary.get("events_by_severity", {}).get(severity, 0)
        if n:
            problems.append(f"{n} {severity} event(s){_named((event_names or {}).get(severity, {}))} (see events.log)")
    return problems


def _named(counts: Mapping[str, int]) -> str:
    """``: A.b.C ×2, D.e.F`` — the names, most frequent first (then alphabetical), at most PROBLEM_NAMES."""
    if not counts:
        return ""
    ranked = sorted(counts.items(), key=lambda item: (-item[1], item[0]))
    shown = [f"{name} ×{n}" if n > 1 else name for name, n in ranked[:PROBLEM_NAMES]]
    more = f" and {len(ranked) - PROBLEM_NAMES} more" if len(ranked) > PROBLEM_NAMES else ""
    return ": " + ", ".join(shown) + more


#: Summary keys measured on the wall clock; every other key is a function of the inputs.
WALL_CLOCK_SUMMARY_KEYS = frozenset({"wall_seconds", "real_time_factor"})


def wall_clock_channels(topology) -> set[str]:
    """Qualified names of the channels declared ``wall_clock=True`` (their values are measured)."""
    return {f"{i.qualified_name}.{c.name}" for i in topology.instances.values()
            for c in i.component.spec.channels if c.wall_clock}


def _summary(deployment: Deployment, recorder: GroundRecorder, reports, sim_s: float, wall_s: float) -> dict:
    topo = deployment.topology
    timer = deployment.loaded.timer
    rate_groups = [c for c in topo.components() if isinstance(c, RateGroupBase)]
    summary = {
        "deployment": topo.deployment,
        "sim_seconds": sim_s,
        "wall_seconds": wall_s,
        "real_time_factor": sim_s / wall_s if wall_s > 0 else None,
        "ticks": timer.driver.tick if timer is not None else deployment.scheduler.events_run,
        "rate_group_cycles": {g.name: g.cycles for g in rate_groups},
        "events_by_severity": dict(sorted(recorder.events_by_severity.items())),
        "command_errors": recorder.events_by_name.get(f"{topo.patterns.get('command')}.OpCodeError", 0),
        "cycle_slips": sum(g.slips for g in rate_groups),
        "member_faults": sum(g.member_faults for g in rate_groups),
        "handler_faults": sum(c.handler_faults for c in topo.components()),
        "undecodable_packets": recorder.undecodable,
        "files_downlinked": [{"destination": f.destination, "path": str(f.path), "bytes": f.received_bytes,
                              "status": f.status} for f in recorder.files.files],
    }
    for r in reports:
        summary.update(r.summary())
    return summary


def _watch_conditions(scheduler, reports, conditions, stopped_by: list) -> None:
    """Stop ``scheduler`` at the first whole simulated second at which every condition holds."""
    step_us = round(CHECK_INTERVAL_S * 1_000_000)
    next_us = [scheduler.now_us + step_us]

    def check(time_us: int) -> None:
        if time_us < next_us[0] or stopped_by:
            return
        next_us[0] = time_us + step_us
        values: dict = {}
        for r in reports:
            if hasattr(r, "progress"):
                values.update(r.progress())
        if holds_all(conditions, values):
            stopped_by.append("stop_when " + " and ".join(c.text for c in conditions))
            scheduler.stop()
    scheduler.add_time_listener(check)


def _run_with_progress(deployment: Deployment, end_us: int, reports, console) -> None:
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    scheduler = deployment.scheduler
    start_us = scheduler.now_us
    step_us = round(PROGRESS_STEP_S * 1_000_000)
    with Progress(TextColumn("[bold]{task.description}"), BarColumn(),
                  TextColumn("{task.fields[sim]}"), TextColumn("{task.fields[extra]}"),
                  TimeElapsedColumn(), console=console, transient=False) as bar:
        task = bar.add_task("running", total=end_us - start_us, sim="", extra="")
        wall0 = time.perf_counter()
        while scheduler.now_us < end_us:
            scheduler.run(until_us=min(end_us, scheduler.now_us + step_us))
            if scheduler.stopped:  # an early-stop event or condition
                break
            sim_s = (scheduler.now_us - start_us) / 1e6
            wall = time.perf_counter() - wall0
            extra = []
            for r in reports:
                if hasattr(r, "progress"):
                    for key, value in r.progress().items():
                        extra.append(f"{key} {value:.2f}" if isinstance(value, float) else f"{key} {value}")
            bar.update(task, completed=scheduler.now_us - start_us,
                       sim=f"t={sim_s:,.0f} s ({sim_s / wall if wall > 0 else 0:,.0f}× real time)",
                       extra="  ".join(extra))


def _print_summary(summary: dict, console) -> None:
    from rich.console import Console
    from rich.table import Table

    console = console or Console(stderr=False)
    table = Table(title=f"Run summary — {summary['deployment']}", show_header=False)
    table.add_column("figure")
    table.add_column("value", justify="right")
    for key, value in summary.items():
        if key in ("deployment", "rate_group_cycles"):
            continue
        if isinstance(value, float):
            text = f"{value:,.3f}"
        elif isinstance(value, dict):
            text = ", ".join(f"{k} {v}" for k, v in value.items()) or "none"
        elif key == "problems":
            text = "; ".join(value) or "none"
        elif key == "files_downlinked":
            text = ", ".join(f"{f['destination']} ({f['status']})" for f in value) or "none"
        else:
            text = "—" if value is None else str(value)
        table.add_row(key, text)
    console.print(table)
