"""The Python entry point: fly a deployment from a script or a notebook, and load a finished run.

    from fprime_lite.tools import run, open_run

    result = run("topology.yaml", duration_s=600)          # quiet: prints nothing
    result.ok, result.problems                              # did the flight go well, and if not why
    result.summary["final_rate_deg_s"]                      # everything summary.json holds
    result.telemetry["ReferenceDeployment.detumbleManager.AngularVelocityMagnitude [deg/s]"].plot()
    result.events[result.events.severity == "WARNING_HI"]
    result.plot()                                           # the application's PNG plots

    again = open_run("runs/20260101-120000.000")            # the same object for a finished run

:func:`run` takes the options of ``fprime-lite run`` as keyword arguments, checks the parameter
file and the sequence before anything flies and raises :class:`RunSetupError` (one line naming the
mistake) for a mistake in the inputs. A flight that goes badly does not raise: ``ok`` is False and
``problems`` says why (handler faults, cycle slips, WARNING_HI/FATAL events).
"""
from __future__ import annotations

import datetime as _dt
import json
import math
import pathlib
import sys
from typing import Sequence

from fprime_lite.osal.atomic import clean_temporary_files
from fprime_lite.osal.folders import file_in_the_way, make_output_folder
from fprime_lite.tools.errors import RunSetupError

__all__ = ["run", "open_run", "load", "RunResult", "RunSetupError", "claim_run_folder", "plot_run_dir"]


def load(topology="topology.yaml", *, scenario: str | None = None, seed: int | None = None,
         settings: Sequence[str] = (), truth_interval_s: float | None = None, scheduler_factory=None):
    """Load ``topology`` (a path) with the simulation and report options passed to the resources
    holding those roles; return the :class:`~fprime_lite.deploy.topology_loader.LoadedDeployment`.

    The topology file's folder is importable while it loads, so a component module beside the
    topology (``type: thermostat.Thermostat`` for ``thermostat.py``) is found without setting
    ``PYTHONPATH``.
    """
    from fprime_lite.deploy.topology_loader import load_topology

    path = pathlib.Path(topology)
    if path.is_dir():
        raise RunSetupError(f"{topology}: is a folder — give the path of a topology YAML file")
    if not path.exists():
        raise RunSetupError(f"{topology}: no such topology file — give the path of a topology YAML file "
                            f"(the reference deployment is deployments/proves_ref/topology.yaml)")
    overrides: dict[str, dict] = {}
    simulation: dict = {}
    if scenario is not None:
        if pathlib.Path(scenario).is_dir():
            raise RunSetupError(f"scenario {scenario}: is a folder — give a packaged scenario name or a YAML file")
        simulation["scenario"] = scenario
    if settings:
        simulation["settings"] = list(settings)
    if seed is not None:
        simulation["seed"] = seed
    if simulation:
        overrides["simulation"] = simulation
    if truth_interval_s is not None:
        overrides["report"] = {"truth_interval_s": truth_interval_s}
    folder = str(path.resolve().parent)
    added = folder not in sys.path
    if added:
        sys.path.insert(0, folder)
    _forget_modules_shadowed_by(folder)
    try:
        return load_topology(path, scheduler_factory=scheduler_factory, role_overrides=overrides)
    finally:
        if added and folder in sys.path:
            sys.path.remove(folder)


def _forget_modules_shadowed_by(folder: str) -> None:
    """Drop from ``sys.modules`` every module a file or package in ``folder`` names that was imported
    from elsewhere, so this topology's ``counter.Counter`` is its own ``counter.py`` and not the one
    beside another topology loaded earlier in this process (two deployments with a module of the same
    name). What was built from the earlier module keeps it; only new imports look again."""
    base = pathlib.Path(folder)
    try:
        entries = list(base.iterdir())
    except OSError:
        return
    names = {p.stem for p in entries if p.suffix == ".py"} | \
        {p.name for p in entries if (p / "__init__.py").is_file()}
    for name in (names & set(sys.modules)) - sys.stdlib_module_names:
        origin = getattr(sys.modules[name], "__file__", None)
        if origin is None or pathlib.Path(origin).resolve().is_relative_to(base):
            continue
        for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
            del sys.modules[key]


def claim_run_folder(out=None, runs_dir="runs") -> pathlib.Path:
    """Create and return the output folder of a run: ``out`` (absent or empty), or a new
    ``runs/<date>-<time>.<ms>`` with ``-2``, ``-3`` … appended when that name is taken. Claiming a
    folder under ``runs`` first removes the temporary files that killed runs left in ``runs``."""
    if out is not None:
        out = pathlib.Path(out)
        problem = file_in_the_way(out)
        if problem is None and out.is_dir() and any(out.iterdir()):
            problem = "the folder exists and is not empty — choose another or remove it"
        problem = problem or make_output_folder(out)
        if problem is not None:
            raise RunSetupError(f"--out {out}: {problem}")
        return out
    stamp = _dt.datetime.now().strftime("%Y%m%d-%H%M%S.%f")[:-3]
    runs = pathlib.Path(runs_dir)
    try:
        runs.mkdir(exist_ok=True)
    except OSError as exc:
        raise RunSetupError(f"cannot create {runs.resolve()} ({exc.strerror}) — run from a folder you can "
                            f"write or give --out DIR") from None
    clean_temporary_files(runs, recursive=True)  # what killed runs left half-written in their folders
    for n in range(1, 1000):
        folder = runs / (stamp if n == 1 else f"{stamp}-{n}")
        try:
            folder.mkdir()
            return folder
        except FileExistsError:
            continue
        except OSError as exc:
            raise RunSetupError(f"cannot create {folder} ({exc.strerror}) — give --out DIR") from None
    raise RunSetupError(f"{runs}: 999 run folders named {stamp}* already exist — give --out DIR")


def run(topology="topology.yaml", *, duration_s: float | None = None, out=None, scenario: str | None = None,
        seed: int | None = None, settings: Sequence[str] = (), params=None, seq=None,
        truth_interval_s: float | None = None, plots: bool = False, progress: bool = False,
        quiet: bool = True, force: bool = False, board_root=None, file_root=None) -> "RunResult":
    """Fly ``topology`` for ``duration_s`` simulated seconds (default: the topology's ``run.duration_s``,
    else 600); return its :class:`RunResult`.

    Outputs go to ``out`` (absent or empty) or a new ``runs/<timestamp>``. ``plots`` draws the PNGs
    as the run ends (``result.plot()`` does it later); ``progress`` shows the progress bar;
    ``quiet=False`` prints the summary table.

    A run longer than :data:`~fprime_lite.tools.disk_estimate.CHECK_ABOVE_S` is first estimated (a
    60 s probe flight scaled to ``duration_s``) and refused with :class:`RunSetupError` when its
    outputs would not fit the disk or exceed 10 GB, as ``fprime-lite run`` does; ``force=True`` flies
    it anyway.

    ``board_root`` (an existing folder; ``fprime-lite run --board-root``) stands in for the board's
    ``/`` for the file services and the command sequencers (``/seq/a.bin`` is ``board_root/seq/a.bin``,
    nothing outside it is reachable, files are replaced as F´'s services replace them) and is the
    simulated spacecraft's flash too.

    ``file_root`` (``fprime-lite run --file-root``; an existing folder holding the working directory)
    gives the file services without a root of their own F´'s behaviour: confined to ``file_root``,
    relative paths from the working directory, existing files replaced, uploads written in place.
    Give ``board_root`` or ``file_root``, not both.
    """
    from fprime_lite.deploy.preflight import check_run_files
    from fprime_lite.tools import disk_estimate
    from fprime_lite.tools.runner import file_root_problem, run_deployment, run_duration, use_board_as_flash

    if duration_s is not None and not (isinstance(duration_s, (int, float)) and not isinstance(duration_s, bool)
                                       and 0 < duration_s < math.inf):
        raise RunSetupError(f"duration_s must be a positive, finite number of seconds, got {duration_s!r}")
    for what, value in (("parameter file", params), ("sequence", seq)):
        if value is not None and not pathlib.Path(value).is_file():
            kind = "is a folder" if pathlib.Path(value).is_dir() else "no such file"
            raise RunSetupError(f"{what} {value}: {kind}")
    if board_root is not None and not pathlib.Path(board_root).is_dir():
        raise RunSetupError(f"board_root {board_root}: not an existing folder — create it (it stands in for the "
                            f"board's /)")
    if board_root is not None and file_root is not None:
        raise RunSetupError("board_root and file_root: give one (a board root is the file services' whole root)")
    problem = file_root_problem(file_root)
    if problem is not None:
        raise RunSetupError(f"file_root {file_root}: {problem}")
    loaded = load(topology, scenario=scenario, seed=seed, settings=settings, truth_interval_s=truth_interval_s)
    check_run_files(loaded, parameter_file=params, sequence=seq)
    duration_s = run_duration(loaded, duration_s)
    if duration_s > disk_estimate.CHECK_ABOVE_S and not force:
        def fly(probe_folder: pathlib.Path, seconds: float) -> None:
            probe = load(topology, scenario=scenario, seed=seed, settings=settings, truth_interval_s=truth_interval_s)
            run_deployment(probe, probe_folder, duration_s=seconds, parameter_file=params, sequence=seq,
                           plots=False, quiet=True)
        disk_estimate.check_disk(disk_estimate.estimate_output_bytes(fly), duration_s,
                                 pathlib.Path(out if out is not None else "runs"), spelling="api")
    if board_root is not None:
        use_board_as_flash(loaded, board_root)
    folder = claim_run_folder(out)
    run_deployment(loaded, folder, duration_s=duration_s, parameter_file=params, sequence=seq,
                   progress=progress, plots=plots, quiet=quiet, board_root=board_root,
                   file_root=file_root)
    return RunResult(folder)


def open_run(run_dir) -> "RunResult":
    """The :class:`RunResult` of a finished run folder."""
    folder = pathlib.Path(run_dir)
    if not (folder / "summary.json").is_file():
        raise RunSetupError(f"{run_dir}: not a run folder (no summary.json) — give a folder "
                            f"'fprime-lite run' wrote")
    return RunResult(folder)


def plot_run_dir(run_dir, out_dir=None) -> list[pathlib.Path]:
    """Draw the plots of a finished run with every installed run plotter that applies to it."""
    from fprime_lite.tools.plugins import run_plotters

    folder = pathlib.Path(run_dir)
    if not folder.is_dir():
        raise RunSetupError(f"{run_dir}: no such run folder")
    target = pathlib.Path(out_dir) if out_dir is not None else folder
    if not target.is_dir():
        raise RunSetupError(f"{target}: no such folder — create it first")
    plotters = run_plotters()
    chosen = [p for p in plotters.values() if p.applies(folder)]
    if not chosen:
        installed = ", ".join(plotters) or "none installed"
        raise RunSetupError(f"{run_dir}: no run plotter recognises this run (plotters: {installed}); "
                            f"an application adds one through the fprime_lite.plots entry points")
    written: list[pathlib.Path] = []
    for plotter in chosen:
        written += plotter.plot(folder, target)
    return written


class RunResult:
    """A finished run: its folder, summary and outputs as pandas DataFrames (read when first used).

    ``events`` — events.log: ``time`` (UTC, or seconds for other time bases), ``name``,
    ``severity``, ``text``; ``channels`` — channels.csv as received (``time`` s, ``channel``,
    ``value`` text); ``telemetry`` — channels_wide.csv, one column per channel scalar (units in the
    heading), indexed by ``t_s``; ``truth`` — the application's truth.csv if the run wrote one
    (indexed by ``t_s``), else None.
    """

    def __init__(self, out_dir):
        self.out_dir = pathlib.Path(out_dir)
        self.summary: dict = json.loads((self.out_dir / "summary.json").read_text(encoding="utf-8"))
        self._frames: dict = {}

    @property
    def ok(self) -> bool:
        return bool(self.summary.get("ok", not self.problems))

    @property
    def problems(self) -> list[str]:
        return list(self.summary.get("problems", []))

    def _frame(self, key, make):
        if key not in self._frames:
            self._frames[key] = make()
        return self._frames[key]

    @property
    def events(self):
        import pandas as pd

        def make():
            rows = []
            with open(self.out_dir / "events.log", encoding="utf-8") as f:
                for line in f:
                    time, name, severity, text = (line.rstrip("\n").split(" ", 3) + ["", "", ""])[:4]
                    rows.append((time, name, severity, text))
            frame = pd.DataFrame(rows, columns=["time", "name", "severity", "text"])
            if len(frame) and frame["time"].str.endswith("Z").all():
                frame["time"] = pd.to_datetime(frame["time"], utc=True)
            return frame

        return self._frame("events", make)

    @property
    def channels(self):
        import pandas as pd

        return self._frame("channels", lambda: pd.read_csv(self.out_dir / "channels.csv", dtype={"value": str}))

    @property
    def telemetry(self):
        import pandas as pd

        return self._frame("telemetry", lambda: pd.read_csv(self.out_dir / "channels_wide.csv", index_col="t_s"))

    @property
    def truth(self):
        import pandas as pd

        path = self.out_dir / "truth.csv"
        return self._frame("truth", lambda: pd.read_csv(path, index_col="t_s") if path.exists() else None)

    def plot(self, out_dir=None) -> list[pathlib.Path]:
        """Draw the run's plots (the installed run plotters); return the PNG files written."""
        return plot_run_dir(self.out_dir, out_dir)

    def __repr__(self) -> str:
        verdict = "ok" if self.ok else "problems: " + "; ".join(self.problems)
        sim = self.summary.get("sim_seconds")
        sim_text = f", {sim:,.0f} s simulated" if isinstance(sim, (int, float)) else ""
        return f"RunResult({str(self.out_dir)!r}{sim_text}, {verdict})"
