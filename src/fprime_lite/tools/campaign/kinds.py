"""Run kinds and named metrics: the plug-in interface of the campaign engine.

The framework provides the ``deployment`` run kind; an application adds its own kinds and metrics
through entry points (``pyproject.toml``)::

    [project.entry-points."fprime_lite.campaign_runs"]
    plant = "detumble.reports.campaign:PLANT_RUN"          # a RunKind

    [project.entry-points."fprime_lite.campaign_metrics"]
    detumble = "detumble.reports.campaign:METRICS"         # a Metric, or a tuple of Metrics

A kind turns a :class:`RunRequest` into a :class:`Prepared` run: the simulation built but not yet
flown. The engine reads the varied values back from it (``readback``), lets metrics attach probes to
``simulation``, then flies it (``execute``).
"""

from __future__ import annotations

import functools
import pathlib
from dataclasses import dataclass, field
from typing import Any, Callable

__all__ = ["RunKind", "RunRequest", "Prepared", "RunOutput", "Metric", "run_kinds", "resolve_kind", "metrics",
           "RUNS_GROUP", "METRICS_GROUP"]

RUNS_GROUP = "fprime_lite.campaign_runs"
METRICS_GROUP = "fprime_lite.campaign_metrics"


@dataclass
class RunRequest:
    """One run to build: the campaign's ``run`` section with this run's values applied.

    ``config`` holds the run-section fields (a varied field already replaced); ``values`` every
    varied key (grid and dispersions) with the value requested; ``seed`` the simulator seed;
    ``base_dir`` the campaign file's folder (relative paths start there);
    ``out_dir`` a folder for the run's files; ``should_stop()`` turns true when the run's time
    is up (kinds check it at least once per simulated second); ``write_files``: whether the run's
    files may be kept (``keep``), so a kind that writes nothing it needs writes its trace and
    summary only then.
    """

    config: dict
    values: dict
    seed: int
    out_dir: pathlib.Path
    base_dir: pathlib.Path = pathlib.Path(".")
    should_stop: Callable[[], bool] = lambda: False
    write_files: bool = False


@dataclass
class RunOutput:
    """What a flown run gives the metrics: its summary, an optional trace of named numpy arrays
    (``t_s`` first), and the folder of its files."""

    summary: dict
    trace: dict | None = None
    out_dir: pathlib.Path | None = None
    stopped_early: bool = False


@dataclass
class Prepared:
    """A run built and ready: ``readback(key)`` gives a varied value as the built simulation holds
    it; ``execute()`` flies it and returns a :class:`RunOutput`."""

    simulation: Any
    readback: Callable[[str], Any]
    execute: Callable[[], RunOutput]


@dataclass(frozen=True)
class RunKind:
    """A kind of run. ``fields``: the keys of its ``run`` section (``required`` among them);
    ``check_key(key)``: None when ``key`` may be varied, else what is wrong with it;
    ``prepare(request)`` builds the run (raise :class:`~.errors.RunSetupError` for bad input);
    ``fingerprint(config, base_dir)`` (optional) says, without building the run, what a run of the
    run-section ``config`` resolves its configuration from beyond the files the campaign names (a
    topology's default scenario and the field model it flies): a JSON-able dict, keyed by what
    resolves, that the manifest records (``resolved``) and ``tools/studies.py --check`` compares."""

    name: str
    fields: frozenset
    required: frozenset
    check_key: Callable[[str], str | None]
    prepare: Callable[[RunRequest], Prepared]
    description: str = ""
    fingerprint: Callable[[dict, pathlib.Path], dict] | None = None


@dataclass(frozen=True)
class Metric:
    """A named metric. ``compute(output, probe)`` returns a number or raises
    :class:`~.errors.MetricUnavailable` with the reason; ``instrument(simulation)`` (optional) is
    called before the run flies and its result is passed as ``probe``."""

    name: str
    unit: str
    description: str
    compute: Callable[[RunOutput, Any], float | None]
    instrument: Callable[[Any], Any] | None = field(default=None)


@functools.lru_cache(maxsize=None)
def _entry_point_objects(group: str) -> tuple:
    """The objects of ``group``'s entry points, loaded once per process (each worker's first run)."""
    from importlib.metadata import entry_points

    from fprime_lite.tools.campaign.errors import CampaignError

    found = []
    for ep in sorted(entry_points(group=group), key=lambda e: e.name):
        try:
            obj = ep.load()
        except Exception as exc:  # noqa: BLE001 - a broken plug-in is reported, not raised through
            raise CampaignError([f"plug-in {ep.name!r} ({ep.value}) of {group} cannot be loaded: {exc} "
                                 f"— reinstall the package that provides it"]) from None
        found += list(obj) if isinstance(obj, (tuple, list)) else [obj]
    return tuple(found)


def run_kinds() -> dict[str, RunKind]:
    """The framework's run kinds and the installed ones, by name."""
    from fprime_lite.tools.campaign.deployment_kind import DEPLOYMENT_RUN

    kinds = {DEPLOYMENT_RUN.name: DEPLOYMENT_RUN}
    for obj in _entry_point_objects(RUNS_GROUP):
        if isinstance(obj, RunKind):
            kinds[obj.name] = obj
    return kinds


def resolve_kind(name: str) -> RunKind:
    """The run kind called ``name``: an installed one, or ``package.module:NAME`` — a
    :class:`RunKind` object imported from a module on the path (a kind not packaged as a plug-in,
    e.g. a test's). Raises ``LookupError`` saying what is wrong."""
    kinds = run_kinds()
    if name in kinds:
        return kinds[name]
    if not isinstance(name, str) or ":" not in name:
        raise LookupError(f"unknown run kind {name!r} (installed kinds: {', '.join(sorted(kinds))})")
    import importlib

    module, _, attr = name.partition(":")
    try:
        obj = getattr(importlib.import_module(module), attr)
    except (ImportError, AttributeError) as exc:
        raise LookupError(f"run kind {name!r} cannot be imported: {exc}") from None
    if not isinstance(obj, RunKind):
        raise LookupError(f"run kind {name!r} is a {type(obj).__name__}, not a RunKind")
    return obj


def metrics() -> dict[str, Metric]:
    """The installed named metrics, by name (a copy: the caller may change it)."""
    return dict(_metrics_by_name())


@functools.lru_cache(maxsize=None)
def _metrics_by_name() -> dict[str, Metric]:
    return {m.name: m for m in _entry_point_objects(METRICS_GROUP) if isinstance(m, Metric)}
