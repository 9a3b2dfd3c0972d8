#!/usr/bin/env python3
"""Regenerate the tables and figures of docs/studies/ and the README's figures (docs/img/), in one command.

    python tools/studies.py                    # every study, written into the docs (minutes to an hour)
    python tools/studies.py --only NAME ...    # some studies (--list names them)
    python tools/studies.py --quick            # every study's short version, into runs/studies-quick/
    python tools/studies.py --check            # staleness: do the docs hold what the committed results give?

A study's tables live in its markdown file between ``<!-- studies:BLOCK -->`` and
``<!-- /studies:BLOCK -->``; this script rewrites what is between the two lines and nothing else, so a
documented number in such a block is, by construction, what the code computes from the committed
campaign results (``docs/studies/<campaign>/results.parquet`` + ``manifest.json``) or from the runs the
study flies. Figures are drawn by the project's own plotters (a run's ``--plots``, the campaign's
``draw_plots``, the study scripts under ``campaigns/``); nothing here draws a figure of its own.

``--quick`` flies each study's short version (the runs a few hundred seconds long, the campaign tables
from the committed results) and writes everything under ``--out`` (default ``runs/studies-quick``),
never into the docs: it shows the whole chain works in minutes. ``--check`` writes nothing: it renders
every block from the committed results and compares it with the docs, checks that each committed
campaign folder belongs to its campaign file as it is now (same file hash, every run id still planned,
the same resolved configuration: the manifest's ``resolved``, a topology's default scenario and field
model; a manifest recording none is reported UNKNOWN, not stale), re-flies each campaign's cheap
probe runs and compares their metrics with the committed rows, and runs each study's own probe (a study script's
``probe``: a cheap piece of its committed JSON file recomputed or re-flown and compared to the float).
``tests/test_studies.py`` runs that check. Exit status: 0 done (or nothing stale), 1 stale, 2 usage.

``--confirm-resolution FOLDER ...``: for a committed campaign whose resolved configuration changed in a way
that cannot alter its flights (a parameter added at its former constant), re-fly its probe runs (else its
first run) and, if every metric agrees to the float, record today's configuration in its manifest
(``resolution_confirmed``), which ``--check`` compares against from then on; a disagreement records nothing.
A folder whose manifest records no configuration (``UNKNOWN``) is confirmed the same way, flying also its last
run and the cheapest run of each configuration its runs resolve to.

Campaign results are not re-run here (that is hours of CPU for some); each study names the command that
produces them, and ``--rerun-campaigns`` runs those (one worker, resuming what is already there).
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import hashlib
import importlib
import importlib.util
import json
import math
import pathlib
import re
import shutil
import sys
import tempfile
from typing import Callable

ROOT = pathlib.Path(__file__).resolve().parents[1]
STUDIES_DIR = ROOT / "docs" / "studies"
IMG_DIR = ROOT / "docs" / "img"

_BLOCK = re.compile(r"(<!-- studies:(?P<name>[\w.-]+) -->\n)(?P<body>.*?)(<!-- /studies:(?P=name) -->)", re.S)


class StudyError(Exception):
    """A study cannot be regenerated or checked as asked (missing results, a marker not found)."""


# --------------------------------------------------------------------------------------------- context


@dataclasses.dataclass
class Context:
    """Where a study writes: into the repository (``out`` None) or under a scratch folder (quick)."""

    quick: bool = False
    out: pathlib.Path | None = None
    reuse: bool = False
    written: list[str] = dataclasses.field(default_factory=list)

    @property
    def runs(self) -> pathlib.Path:
        """Where the studies' flights go (kept: ``--reuse-runs`` resumes from them)."""
        return (self.out / "flights") if self.out is not None else ROOT / "runs" / "studies"

    def path(self, repo_path: pathlib.Path) -> pathlib.Path:
        """Where ``repo_path`` (a file of the repository) goes in this context."""
        if self.out is None:
            return repo_path
        return self.out / repo_path.relative_to(ROOT)

    def write_bytes(self, repo_path: pathlib.Path, data: bytes) -> None:
        from fprime_lite.osal.atomic import atomic_write_bytes

        target = self.path(repo_path)
        target.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(target, data)
        self.written.append(str(target.relative_to(ROOT) if target.is_relative_to(ROOT) else target))

    def copy(self, source: pathlib.Path, repo_path: pathlib.Path) -> None:
        self.write_bytes(repo_path, source.read_bytes())

    def set_blocks(self, doc: pathlib.Path, blocks: dict[str, str]) -> None:
        """Rewrite the named blocks of ``doc`` (quick: into a copy of it under ``out``)."""
        source = self.path(doc) if self.path(doc).exists() else doc
        text = replace_blocks(source.read_text(encoding="utf-8"), blocks, doc)
        self.write_bytes(doc, text.encode("utf-8"))


def doc_blocks(text: str) -> dict[str, str]:
    """The ``studies:`` blocks of a markdown text, by name."""
    return {m.group("name"): m.group("body") for m in _BLOCK.finditer(text)}


def replace_blocks(text: str, blocks: dict[str, str], where: pathlib.Path | str = "the document") -> str:
    missing = sorted(set(blocks) - set(doc_blocks(text)))
    if missing:
        raise StudyError(f"{where}: no block {', '.join(missing)} (add '<!-- studies:NAME -->' and "
                         f"'<!-- /studies:NAME -->' lines around the place it goes)")

    def sub(m: re.Match) -> str:
        name = m.group("name")
        if name not in blocks:
            return m.group(0)
        body = blocks[name]
        return m.group(1) + (body if body.endswith("\n") else body + "\n") + m.group(4)

    return _BLOCK.sub(sub, text)


def _load_script(relative: str):
    """A study script under campaigns/ as a module (they are scripts, not a package)."""
    path = ROOT / relative
    name = "_studies_" + re.sub(r"\W", "_", relative)
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise StudyError(f"cannot load {relative}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def _fmt(x, digits: int = 0, none: str = "—") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return none
    return f"{x:,.{digits}f}"


def _float(x) -> float | None:
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


# ------------------------------------------------------------------------------------ committed campaigns


@dataclasses.dataclass(frozen=True)
class CommittedCampaign:
    """A campaign whose results folder is committed under docs/studies/."""

    folder: str            # under docs/studies/
    campaign_file: str     # repository-relative
    # the runs re-flown by --check and compared with their committed rows (cheap ones): a predicate on a task
    probe: Callable[[dict], bool] | None = None
    probe_rel_tol: float = 0.0

    @property
    def path(self) -> pathlib.Path:
        return STUDIES_DIR / self.folder

    @property
    def command(self) -> str:
        """The command that makes (or resumes) the committed folder; into ``runs/`` while nothing is committed."""
        out = f"docs/studies/{self.folder}" if self.path.exists() else f"runs/{pathlib.PurePath(self.folder).name}"
        return f"nice -n 10 fprime-lite campaign {self.campaign_file} --workers 1 --out {out}"

    def results(self):
        from fprime_lite.tools.campaign import read_results

        if not (self.path / "results.parquet").exists():
            raise StudyError(f"docs/studies/{self.folder}/results.parquet is not committed: run `{self.command}`")
        return read_results(self.path)

    def campaign(self):
        from fprime_lite.tools.campaign import load_campaign

        return load_campaign(ROOT / self.campaign_file)

    def campaign_file_changed(self) -> bool:
        """Whether the campaign file differs from the one the committed folder was made by (comments and
        layout aside: the manifest keeps the text, and equal YAML plans the same runs)."""
        manifest = json.loads((self.path / "manifest.json").read_text(encoding="utf-8"))
        text = (ROOT / self.campaign_file).read_bytes()
        if hashlib.sha256(text).hexdigest() == manifest.get("campaign_sha256"):
            return False
        return not _same_yaml(text.decode("utf-8"), manifest.get("campaign_text"))

    def problems(self, *, fly_probes: bool = True) -> list[str]:
        """Why the committed folder may no longer be what its campaign file gives (empty: none found)."""
        from fprime_lite.tools.campaign.plan import plan_runs

        out: list[str] = []
        if not (self.path / "results.parquet").exists():
            return out  # not committed: the study's block says so, and the block is compared on its own
        if self.campaign_file_changed():
            out.append(f"docs/studies/{self.folder}: {self.campaign_file} changed since these results were made "
                       f"(it says something else than the text in manifest.json): run `{self.command}` again")
        df = self.results()
        with tempfile.TemporaryDirectory() as scratch:
            tasks = plan_runs(self.campaign(), pathlib.Path(scratch))
            by_id = {t["run_id"]: t for t in tasks}
            missing = sorted(set(df["run_id"]) - set(by_id))
            if missing:
                out.append(f"docs/studies/{self.folder}: {len(missing)} committed run id(s) are no longer planned by "
                           f"{self.campaign_file} (e.g. {missing[0]}): the results are of another campaign")
            out += self.resolution_problems(tasks)
            if fly_probes and self.probe is not None:
                out += self._fly_probes(df, [t for t in tasks if t["run_id"] in set(df["run_id"]) and self.probe(t)],
                                        pathlib.Path(scratch))
        return out

    def _recorded_resolution(self) -> dict | None:
        """What the committed results stand for: the manifest's ``resolved`` (what the runs resolved their
        configuration from), or the latest ``resolution_confirmed`` entry's when a later configuration was
        confirmed to fly the same (:meth:`confirm_resolution`); None if it records none (a folder made
        before manifests did)."""
        manifest = json.loads((self.path / "manifest.json").read_text(encoding="utf-8"))
        confirmed = manifest.get("resolution_confirmed") or []
        return confirmed[-1]["resolved"] if confirmed else manifest.get("resolved")

    def confirmation_tasks(self, df, tasks: list[dict], *, unknown: bool = False) -> list[dict]:
        """The runs :meth:`confirm_resolution` re-flies: the probe runs, else the first committed run.

        ``unknown`` (the manifest records no resolution, so nothing says which of its configurations may have
        moved): besides those, the last committed run (another corner of the campaign's grid) and, for each run
        section (run kind and section configuration: a topology, a plant run's law, scenario and gains, what
        :func:`resolved_configuration` fingerprints once each) that no chosen run flies yet, its committed run
        cheapest in CPU-seconds (else wall-clock seconds): every section is flown at least once, so a changed
        default that only one law or topology reads is caught too."""
        committed = set(df["run_id"])
        runs = [t for t in tasks if t["run_id"] in committed]
        probed = [t for t in runs if self.probe is None or self.probe(t)]
        chosen = probed if self.probe is not None else probed[:1]
        if not unknown or not runs:
            return chosen
        chosen = chosen + [runs[-1]]
        cost = _committed_cost(df)
        keys = {t["run_id"]: json.dumps([t["kind"], t["config"], str(t.get("base_dir"))], sort_keys=True, default=str)
                for t in runs}  # a run section, as resolved_configuration tells them apart
        for key in dict.fromkeys(keys.values()):
            if not any(keys[t["run_id"]] == key for t in chosen):
                chosen.append(min((t for t in runs if keys[t["run_id"]] == key), key=lambda t: cost(t["run_id"])))
        order = {t["run_id"]: i for i, t in enumerate(runs)}
        return sorted({t["run_id"]: t for t in chosen}.values(), key=lambda t: order[t["run_id"]])

    def confirm_resolution(self) -> list[str]:
        """When what the campaign resolves to changed (e.g. a parameter added at the value that was a constant
        before), fly :meth:`confirmation_tasks` with today's configuration and compare each metric with its
        committed row to the float (``probe_rel_tol``); if all agree, append to the manifest a
        ``resolution_confirmed`` entry (today's resolution, the date, the code's commit, the runs compared),
        which :meth:`resolution_problems` then compares against. A manifest recording no resolution (made before
        manifests did, :meth:`resolution_unknown`) is confirmed the same way, with more runs flown
        (``confirmation_tasks(..., unknown=True)``) and an entry saying it had none before. Returns the
        disagreements (nothing is written then: the campaign must be re-flown), or an empty list."""
        from fprime_lite.osal.atomic import atomic_write_text
        from fprime_lite.tools.campaign.manifest import now_utc, resolved_configuration
        from fprime_lite.tools.campaign.plan import plan_runs

        df = self.results()
        unknown = self._recorded_resolution() is None
        with tempfile.TemporaryDirectory() as scratch:
            tasks = plan_runs(self.campaign(), pathlib.Path(scratch))
            if not unknown and not self.resolution_problems(tasks):
                return []
            chosen = self.confirmation_tasks(df, tasks, unknown=unknown)
            if not chosen:
                return [f"docs/studies/{self.folder}: no committed run to confirm with: re-fly it (`{self.command}`)"]
            problems = self._fly_probes(df, chosen, pathlib.Path(scratch))
            if problems:
                return problems
            manifest_path = self.path / "manifest.json"
            manifest = json.loads(manifest_path.read_text(encoding="utf-8"))
            manifest.setdefault("resolution_confirmed", []).append({
                "resolved": resolved_configuration(tasks), "date": now_utc(), "code": _code_revision(),
                "runs": [t["run_id"] for t in chosen],
                "how": ("the manifest recorded no resolved configuration before (made before manifests did); "
                        if unknown else "")
                       + "these runs flown again with this configuration gave their committed metrics to the float "
                       f"(relative tolerance {self.probe_rel_tol}): tools/studies.py --confirm-resolution"})
            atomic_write_text(manifest_path, json.dumps(manifest, indent=2) + "\n")  # the engine's layout
        return []

    def resolution_problems(self, tasks: list[dict]) -> list[str]:
        """Whether what the planned runs resolve to now (a topology's default scenario, its field model)
        differs from what the committed folder's manifest records; a manifest recording nothing is
        :meth:`resolution_unknown`'s business, not a problem."""
        from fprime_lite.tools.campaign.manifest import resolved_configuration

        then = self._recorded_resolution()
        if then is None:
            return []
        now = resolved_configuration(tasks)
        changes = [_resolution_change(key, then.get(key), now.get(key)) for key in sorted(set(then) | set(now))]
        changes = [c for c in changes if c]
        if not changes:
            return []
        return [f"docs/studies/{self.folder}: what {self.campaign_file} resolves to changed since these results "
                f"were made ({'; '.join(changes)}): re-fly it, `git rm -r -q docs/studies/{self.folder}` then "
                f"`nice -n 10 fprime-lite campaign {self.campaign_file} --workers 1 --out docs/studies/{self.folder}`; "
                f"or, when the change cannot alter its flights, `python tools/studies.py --confirm-resolution "
                f"{self.folder}` flies a run or two again and records the new configuration if they agree to the float"]

    def resolution_unknown(self) -> str | None:
        """A note (not a staleness) when the committed manifest records no resolved configuration."""
        if not (self.path / "manifest.json").exists() or self._recorded_resolution() is not None:
            return None
        return (f"docs/studies/{self.folder}: manifest.json records no resolved configuration (made before "
                f"manifests did): whether a topology default it flew (scenario, field model) changed since is "
                f"unknown; re-flying it records one, or `python tools/studies.py --confirm-resolution {self.folder}` "
                f"flies a few of its runs again and records today's if they agree to the float")

    def _fly_probes(self, df, tasks: list[dict], scratch: pathlib.Path) -> list[str]:
        from fprime_lite.tools.campaign.task import fly

        out = []
        for task in tasks:
            row = fly(task, scratch / task["run_id"])
            committed = df[df["run_id"] == task["run_id"]].iloc[0]
            if row["status"] != committed["status"]:
                out.append(f"{self.folder} run {task['run_id']}: status {row['status']} now, "
                           f"{committed['status']} committed ({row['error']})")
                continue
            for name, value in row["metrics"].items():
                old = _float(committed.get(name))
                new = _float(value)
                if (old is None) != (new is None) or (
                        old is not None and new is not None
                        and abs(new - old) > self.probe_rel_tol * max(abs(old), abs(new))):
                    out.append(f"{self.folder} run {task['run_id']} ({json.dumps(task['values'])}): {name} = "
                               f"{new} now, {old} committed: the code no longer computes the documented number "
                               f"(`{self.command}` then `python tools/studies.py`)")
        return out

    def redraw_plots(self, ctx: Context) -> None:
        """The campaign's own plots, redrawn from the committed results (its ``plots`` or the automatic ones)."""
        from fprime_lite.tools.campaign.plots import draw_plots

        with tempfile.TemporaryDirectory() as scratch:
            for png in draw_plots(self.results(), self.campaign(), pathlib.Path(scratch)):
                ctx.copy(png, self.path / png.name)

    def rerun(self) -> None:
        from fprime_lite.tools.campaign import run_campaign

        run_campaign(ROOT / self.campaign_file, workers=1, out=self.path, resume=True)


@functools.lru_cache(maxsize=1)
def _code_revision() -> str:
    """The work tree's commit, ``+dirty`` when it has uncommitted changes outside ``docs/`` (as campaign
    manifests say; the docs and committed results cannot change a flight); read once."""
    from fprime_lite.tools.campaign.manifest import git_state

    state = git_state(ROOT, ignore=("docs",))
    if state is None:
        return "unknown"
    return state["commit"][:7] + ("+dirty" if state["dirty"] else "")


def _committed_cost(df) -> Callable[[str], float]:
    """A committed run's cost by its run id: its ``cpu_s``, else its ``wall_s`` (seconds; infinite when the
    results record neither), for choosing the cheapest run to fly again."""
    for column in ("cpu_s", "wall_s"):
        if column in df.columns:
            costs = {run: _float(value) for run, value in zip(df["run_id"], df[column], strict=True)}
            return lambda run: math.inf if costs.get(run) is None else float(costs[run])
    return lambda run: math.inf


def _same_yaml(now: str, then: str | None) -> bool:
    """Whether two campaign texts say the same thing (they may differ in comments and layout only)."""
    import yaml

    if then is None:
        return False
    try:
        return yaml.safe_load(now) == yaml.safe_load(then)
    except yaml.YAMLError:
        return False


def _resolution_change(key: str, then: dict | None, now: dict | None) -> str | None:
    """One line saying how what ``key`` resolves to changed (None: it did not)."""
    if then == now:
        return None
    if then is None or now is None:
        return f"{key} {'is resolved now, not then' if then is None else 'is no longer resolved'}"
    if "error" in now:
        return f"{key} cannot be resolved now: {now['error']}"
    if then.get("sha256") == now.get("sha256"):
        return None
    parts = []
    if then.get("field_model") != now.get("field_model"):
        parts.append(f"field model {then.get('field_model')} → {now.get('field_model')}")
    before, after = then.get("sections") or {}, now.get("sections") or {}
    sections = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
    if sections:
        parts.append(f"scenario sections changed: {', '.join(sections)}")
    return f"{key} ({now.get('source', '?')}): {'; '.join(parts) or 'resolved values changed'}"


def _wheels_cheap(task: dict) -> bool:
    config, values = task["config"], task["values"]
    return config.get("law") == "wheels_pd" and float(values.get("scenario.dynamics_step_s", 0.0)) >= 0.01


def _ideal_variant_first_seed(task: dict) -> bool:
    """BDotDetumble with an ideal magnetometer, first seed: ≈ 570 simulated s, a couple of CPU-seconds."""
    values = task["values"]
    return (task["seed_index"] == 0 and str(values.get("topology", "")).endswith("topology_bdot_detumble.yaml")
            and values.get("scenario.sensors.magnetometer.noise_std_gauss") == 0
            and values.get("scenario.sensors.magnetometer.resolution_gauss") == 0)


CAMPAIGNS = {
    "coursework_convergence": CommittedCampaign("coursework_convergence", "campaigns/coursework/convergence.yaml",
                                                probe=_wheels_cheap),
    "spin_minor_axis": CommittedCampaign("spin_stabilisation_campaign/spin_minor_axis",
                                         "campaigns/adcs/spin_minor_axis.yaml"),
    "spin_major_axis": CommittedCampaign("spin_stabilisation_campaign/spin_major_axis",
                                         "campaigns/adcs/spin_major_axis.yaml"),
    "coursework_convergence_listing": CommittedCampaign("coursework_convergence_listing",
                                                        "campaigns/coursework/convergence_listing.yaml"),
    "coursework_convergence_switched": CommittedCampaign("coursework_convergence_switched",
                                                         "campaigns/coursework/convergence_switched.yaml"),
    "coursework_cross_product_sweep": CommittedCampaign("coursework_cross_product_sweep",
                                                        "campaigns/coursework/cross_product_sweep.yaml"),
    "coursework_beta_pd_grid": CommittedCampaign("coursework_beta_pd_grid", "campaigns/coursework/beta_pd_grid.yaml"),
    "coursework_beta_pd_grid_listing": CommittedCampaign("coursework_beta_pd_grid_listing",
                                                         "campaigns/coursework/beta_pd_grid_listing.yaml"),
    "coursework_wheels_pd_grid": CommittedCampaign("coursework_wheels_pd_grid",
                                                   "campaigns/coursework/wheels_pd_grid.yaml",
                                                   probe=lambda t: t["values"].get("scenario.control.wheels_pd.k_d")
                                                   == 9 and t["values"].get("scenario.control.wheels_pd.k_p") == 5),
    "coursework_noise": CommittedCampaign("coursework_noise", "campaigns/coursework/noise.yaml",
                                          probe=lambda t: t["config"].get("law") == "wheels_pd"
                                          and t["seed_index"] == 0),
    "attitude_knowledge": CommittedCampaign("attitude_knowledge", "campaigns/adcs/pointing_wheels.yaml"),
    "flight_detumble_campaign": CommittedCampaign("flight_detumble_campaign", "campaigns/proves_flight_detumble.yaml"),
    "flight_detumble_campaign_p95": CommittedCampaign("flight_detumble_campaign_p95",
                                                      "campaigns/proves_flight_detumble_p95.yaml"),
    "gain_sweep": CommittedCampaign("gain_sweep", "campaigns/proves_gain_sweep.yaml"),
    "flight_bdot_noise": CommittedCampaign("flight_bdot_noise", "campaigns/proves_bdot_noise.yaml",
                                           probe=lambda t: _ideal_variant_first_seed(t)),
    # one plant run of an orbit (~10 CPU-s) re-flown by --check
    "magnetic_pointing_hold_worst": CommittedCampaign("magnetic_pointing_hold_worst",
                                                      "campaigns/adcs/hold_magnetorquers_worst.yaml"),
    "magnetic_pointing_tumble": CommittedCampaign("magnetic_pointing_tumble",
                                                  "campaigns/adcs/pointing_magnetorquers.yaml"),
    # the 100-run hold flown again with today's code (IGRF-14): committed as far as it got, resumable
    "magnetic_pointing_hold_campaign": CommittedCampaign("magnetic_pointing_hold/campaign",
                                                         "campaigns/adcs/hold_magnetorquers.yaml"),
    "magnetorquer_hold_after_acquisition": CommittedCampaign("magnetorquer_hold_after_acquisition/campaign",
                                                             "campaigns/adcs/pointing_magnetorquers_plant.yaml",
                                                             probe=lambda t: t["seed_index"] == 0),
    # plant runs of 330 s (~1 CPU-s each): the first seed re-flown by --check
    "robust_rates_campaign": CommittedCampaign("robust_rates/campaign", "campaigns/adcs/robust_rates_plant.yaml",
                                               probe=lambda t: t["seed_index"] == 0),
    "robust_rates_window_campaign": CommittedCampaign("robust_rates/campaign_window",
                                                      "campaigns/adcs/robust_rates_plant_window.yaml",
                                                      probe=lambda t: t["seed_index"] == 0),
    "magnetorquer_hold_two_orbits": CommittedCampaign("magnetorquer_hold_after_acquisition/two_orbits",
                                                      "campaigns/adcs/pointing_magnetorquers_plant_2orbits.yaml"),
    "robust_rates_gate_campaign": CommittedCampaign("robust_rates/campaign_gate",
                                                    "campaigns/adcs/robust_rates_plant_gate.yaml",
                                                    probe=lambda t: t["seed_index"] == 0),
    "robust_rates_dipole_campaign": CommittedCampaign("robust_rates/campaign_dipole",
                                                      "campaigns/adcs/robust_rates_plant_dipole.yaml",
                                                      probe=lambda t: t["seed_index"] == 0),
    # issue 27's candidates on the first 100 and 10 draws (plant runs of an orbit, ~10 CPU-s each)
    "magnetorquer_hold_rho_schedule": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_rho_schedule",
        "campaigns/adcs/pointing_magnetorquers_plant_rho_schedule.yaml"),
    "magnetorquer_hold_no_mag_bias": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_no_mag_bias",
        "campaigns/adcs/pointing_magnetorquers_plant_no_mag_bias.yaml"),
    "magnetorquer_hold_field_model_lqr": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr.yaml"),
    "magnetorquer_hold_field_model_lqr_igrf14": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr_igrf14",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr_igrf14.yaml"),
    "magnetorquer_hold_field_model_lqr_below_40": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr_below_40",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr_below_40.yaml"),
    "magnetorquer_hold_field_model_lqr_below_40_igrf14": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr_below_40_igrf14",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr_below_40_igrf14.yaml"),
    "magnetorquer_hold_field_model_lqr_below_40_igrf14_degree13": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr_below_40_igrf14_degree13",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr_below_40_igrf14_degree13.yaml"),
    "magnetorquer_hold_field_model_lqr_below_50": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr_below_50",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr_below_50.yaml"),
    "magnetorquer_hold_field_model_lqr_below_50_igrf14": CommittedCampaign(
        "magnetorquer_hold_after_acquisition/campaign_field_model_lqr_below_50_igrf14",
        "campaigns/adcs/pointing_magnetorquers_plant_field_model_lqr_below_50_igrf14.yaml"),
}


# ------------------------------------------------------------------------------------------------- studies


@dataclasses.dataclass(frozen=True)
class Study:
    name: str
    summary: str
    regenerate: Callable[[Context], None]
    blocks: Callable[[], dict[str, str]] | None = None   # from committed results only (what --check compares)
    doc: pathlib.Path | None = None
    campaigns: tuple[str, ...] = ()
    # recomputes or re-flies a cheap piece of the committed source and compares it to the float (--check, unless
    # --no-probes): the problems found, empty when it agrees
    probe: Callable[[], list[str]] | None = None


# --- seed 004: convergence -------------------------------------------------------------------------------

_CONVERGENCE_DOC = STUDIES_DIR / "coursework_reproduction.md"
_RULE = 0.005  # spec/control.md: a figure is published where halving its step moves it by < 0.5 %


def _convergence_series(df) -> list[tuple[str, list[tuple[float, float, dict]]]]:
    """(label, [(step, period, metrics)]) per law variant, steps large to small; the runs that halve
    step and period together only."""
    series: dict[str, list] = {}
    for _, row in df.iterrows():
        # a run that failed read nothing back: its values are the requested ones
        r = {**row.to_dict(), **json.loads(row["requested"])} if row["status"] != "ok" else row
        law = r["law"]
        step, period = float(r["scenario.dynamics_step_s"]), float(r["scenario.control.period_s"])
        if law == "beta_pd":
            label = "`beta_pd`, " + ("eq. 23 *or* 24 (default)" if bool(r["scenario.control.beta_pd.switched"])
                                     else "both spin terms (listing)")
        elif law == "wheels_pd":
            kd = _float(r.get("scenario.control.wheels_pd.k_d"))  # NaN where the grid point does not set it
            error = r["scenario.control.wheels_pd.error"]
            label = f"`wheels_pd`, error `{error}`" + (f", K_d = {kd:g}" if kd is not None else "")
        else:
            label = "`cross_product`, k = 146"
        series.setdefault(label, []).append((step, period, {
            "status": r["status"], "error": r["error"],
            "overall": _float(r["settling_time_2pct_s"]),
            "axes": [_float(r[f"settling_time_2pct_{a}_s"]) for a in "xyz"],
            "attitude": _float(r.get("settling_time_2pct_attitude_s")),
        }))
    return [(label, sorted(rows, key=lambda x: (-x[1], -x[0]))) for label, rows in sorted(series.items())]


#: Below this observed order the last three halvings' differences barely shrink: no limit is extrapolated from them
#: (a Richardson step divides by 2^p − 1, which goes to 0 with p).
_MIN_ORDER = 0.5


def _richardson(values: list[float]) -> tuple[float | None, float | None]:
    """From the last three figures of a halving sequence: the observed order p and the extrapolated
    limit V(h→0) = V(h/4) + (V(h/4) − V(h/2)) / (2^p − 1); None when the differences do not shrink."""
    if len(values) < 3:
        return None, None
    a, b, c = values[-3:]
    d1, d2 = b - a, c - b
    if d1 == 0.0 or d2 == 0.0 or (d1 > 0) != (d2 > 0) or abs(d2) >= abs(d1):
        return None, None
    p = math.log2(d1 / d2)
    return p, c + d2 / (2.0 ** p - 1.0)


def _first_converged(figures: list[tuple[float, float | None]]) -> tuple[float, float] | None:
    """The published figure of a halving sequence ``[(step, figure)]`` (steps large to small), or None: the figure
    of the first halving from which that halving and every later one move it by less than the rule
    (spec/control.md: < 0.5 %), at that halving's step. A halving under the rule followed by one over it is not
    convergence: the sequence then has no published figure until a further halving meets the rule again."""
    changes = [None if a is None or b is None else abs(b - a) < _RULE * abs(a)
               for (_, a), (_, b) in zip(figures, figures[1:], strict=False)]
    for i, ok in enumerate(changes):
        if ok and all(changes[i:]):
            step, value = figures[i + 1]
            assert value is not None
            return step, value
    return None


#: The campaigns that continue the convergence campaign's β-PD halvings (the listing's form, the equations').
_CONVERGENCE_CONTINUED = ("coursework_convergence_listing", "coursework_convergence_switched")


def _convergence_made() -> list[CommittedCampaign]:
    """The convergence campaign and those of its continuations whose results are committed."""
    return [CAMPAIGNS["coursework_convergence"]] + [
        CAMPAIGNS[k] for k in _CONVERGENCE_CONTINUED if (CAMPAIGNS[k].path / "results.parquet").exists()]


def _convergence_results():
    """The convergence campaign's committed rows, with the β-PD's continuations where committed."""
    import pandas as pd

    return pd.concat([c.results() for c in _convergence_made()], ignore_index=True)


def _repeated_runs(rows: list) -> tuple[list, list[str]]:
    """``rows`` (step, period, metrics) with a point flown in two campaigns kept once, and one line per repeat:
    whether the second flight gave the same figures (a continuation re-flies its starting point)."""
    kept: dict[tuple[float, float], tuple] = {}
    notes = []
    for step, period, m in rows:
        first = kept.get((step, period))
        if first is None:
            kept[(step, period)] = (step, period, m)
            continue
        same = first[2]["overall"] == m["overall"] and first[2]["axes"] == m["axes"]
        notes.append(f"{step:g} s flown twice: " + ("the same figures both times" if same else
                     f"**different figures** ({_fmt(first[2]['overall'])} and {_fmt(m['overall'])} s); the "
                     f"first is shown"))
    return list(kept.values()), notes


def convergence_blocks() -> dict[str, str]:
    df = _convergence_results()
    lines = ["| law (report's gains) | step = period (s) | settling time, 2 % bands (s): overall (ω_x / ω_y / ω_z) | "
             "change on halving | converged (< 0.5 %)? |", "|---|---|---|---|---|"]
    fixed_period = []
    summary = []
    for label, rows in _convergence_series(df):
        rows, repeats = _repeated_runs(rows)
        summary += [f"- {label}: {note}." for note in repeats]
        together = [r for r in rows if r[0] == r[1]]
        fixed_period += [(label, r) for r in rows if r[0] != r[1]]
        previous = None
        for step, _, m in together:
            if m["status"] != "ok":
                lines.append(f"| {label} | {step:g} | not measured: run {m['status']} ({m['error']}) | | |")
                continue
            digits = 3 if label.startswith("`wheels") else 0
            axes = " / ".join(_fmt(a, digits) for a in m["axes"])
            if m["attitude"] is not None:
                axes += f"; attitude {_fmt(m['attitude'], digits)}"
            overall = m["overall"]
            change = ("" if previous is None or overall is None or previous is None
                      else f"{100.0 * (overall - previous) / previous:+.2f} %")
            converged = "" if not change else ("yes" if abs(overall - previous) < _RULE * abs(previous) else "**no**")
            lines.append(f"| {label} | {step:g} | **{_fmt(overall, digits)}** ({axes}) | {change} | {converged} |")
            previous = overall
        overalls = [m["overall"] for _, _, m in together if m["overall"] is not None]
        if together and not overalls and all(m["status"] == "ok" for _, _, m in together):
            slowest = [max(a for a in m["axes"] if a is not None) for _, _, m in together]
            summary.append(f"- {label}: overall — : the attitude does not settle within the run (this K_d over-damps "
                           f"it); the rate axes are settled by {', '.join(_fmt(x, 3) for x in slowest)} s.")
        # the β-PD's figures only: the wheel law's are read on the control period's grid (the page takes them at
        # 0.005 s for that reason) and the cross-product law has two steps
        flown = [(step, m["overall"]) for step, _, m in together if m["status"] == "ok"]
        if label.startswith("`beta_pd") and len(flown) >= 2:
            published = _first_converged(flown)
            (h_prev, v_prev), (h_last, v_last) = flown[-2], flown[-1]
            if published is not None:
                steps = [h for h, _ in flown]
                i = steps.index(published[0])
                moved = 100.0 * (published[1] - flown[i - 1][1]) / flown[i - 1][1]
                after = "" if i == len(steps) - 1 else ", and every halving after it by less than 0.5 %"
                summary.append(f"- {label}: converged by the rule: the halving to {published[0]:g} s moves it "
                               f"{moved:+.2f} %{after}; published figure **{_fmt(published[1])} s** at "
                               f"{published[0]:g} s.")
            elif v_prev is not None and v_last is not None:
                summary.append(f"- {label}: **not converged** over the steps flown: the last halving ({h_prev:g} → "
                               f"{h_last:g} s) moves it {100.0 * (v_last - v_prev) / v_prev:+.2f} %; the figure at "
                               f"the smallest step, {_fmt(v_last)} s, is given with its step.")
        p, limit = _richardson(overalls)
        if p is not None and len(overalls) >= 3 and p < _MIN_ORDER:
            summary.append(f"- {label}: observed order {p:.2f} from the last three halvings: the differences barely "
                           f"shrink, too little for an extrapolated limit.")
        elif p is not None and len(overalls) >= 3:
            summary.append(f"- {label}: observed order {p:.2f} from the last three halvings; "
                           f"extrapolated limit (step → 0) ≈ {_fmt(limit, 3 if label.startswith('`wheels') else 0)} s.")
    for label, (step, period, m) in fixed_period:
        summary.append(f"- {label}: control period held at {period:g} s, dynamics step {step:g} s: "
                       f"{_fmt(m['overall'])} s ({' / '.join(_fmt(a) for a in m['axes'])}).")
    made = _convergence_made()
    source = ("Generated by `python tools/studies.py --only coursework_convergence` from "
              + ", ".join(f"`docs/studies/{c.folder}/` (made by `{c.command}`{_state_note(c)})" for c in made) + ".")
    return {"coursework_convergence": "\n".join(lines) + "\n\n" + "\n".join(summary) + "\n\n" + source + "\n"}


def regenerate_convergence(ctx: Context) -> None:
    ctx.set_blocks(_CONVERGENCE_DOC, convergence_blocks())


def _state_note(campaign: CommittedCampaign) -> str:
    """'' for a complete committed campaign; else how far it got (a stopped campaign is committed as it is)."""
    manifest = json.loads((campaign.path / "manifest.json").read_text(encoding="utf-8"))
    if manifest.get("status") == "complete":
        return ""
    done = len(campaign.results())
    return (f"; **stopped after {done} of {manifest.get('runs')} runs** (a reduced run of the campaign, in its "
            f"planned order, seed-major), the rest by the same command with `--resume`")


def _committed(key: str):
    """(campaign, its results) or (campaign, None) when its folder is not committed."""
    campaign = CAMPAIGNS[key]
    if not (campaign.path / "results.parquet").exists():
        return campaign, None
    return campaign, campaign.results()


def _not_committed(campaign: CommittedCampaign) -> str:
    return f"Not committed yet: `{campaign.command}`.\n"


def _source(study: str, campaign: CommittedCampaign) -> str:
    return (f"Generated by `python tools/studies.py --only {study}` from `docs/studies/{campaign.folder}/` "
            f"(made by `{campaign.command}`{_state_note(campaign)}).")


def _ok(df):
    return df[df["status"] == "ok"]


def _cell(df, digits: int, **where) -> str:
    """The settling time of the one row matching ``where`` (— never settled, blank: not flown)."""
    rows = df
    for key, value in where.items():
        rows = rows[rows[key] == value]
    if len(rows) == 0:
        return "not flown"
    row = rows.iloc[0]
    if row["status"] != "ok":
        return f"{row['status']}"
    return _fmt(_float(row["settling_time_2pct_s"]), digits)


def cross_product_block() -> str:
    campaign, df = _committed("coursework_cross_product_sweep")
    if df is None:
        return _not_committed(campaign)
    gains = [float(g) for g in campaign.campaign().grids[0]["gain"]]
    head = "| k (A·m²/(rad/s·T)) | " + " | ".join(f"**{g:g}**" if g == 146 else f"{g:g}" for g in gains) + " |"
    lines = [head, "|---|" + "---|" * len(gains)]
    for label, metric, digits in (("settling, 2 % bands (s)", "settling_time_2pct_s", 0),
                                  ("\\|ω − ω_final\\| < 1 °/s (s)", "time_below_threshold_s", 0),
                                  ("\\|ω\\| at the end of the run (°/s)", "final_rate_deg_s", None)):
        cells = []
        for g in gains:
            rows = df[df["gain"].astype(float) == g]
            if len(rows) == 0:
                cells.append("not flown")
            elif rows.iloc[0]["status"] != "ok":
                cells.append(str(rows.iloc[0]["status"]))
            else:
                v = _float(rows.iloc[0][metric])
                cells.append("—" if v is None else (f"{v:.2g}" if digits is None else _fmt(v, digits)))
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    ok = _ok(df)
    settled = ok.dropna(subset=["settling_time_2pct_s"])
    notes = ["", "(— : not within the run; `not flown`: the campaign was stopped before this gain.)"]
    if len(settled):
        best = settled.loc[settled["settling_time_2pct_s"].astype(float).idxmin()]
        ref = settled[settled["gain"].astype(float) == 146]
        line = (f"- fastest gain flown: k = {float(best['gain']):g}, {_fmt(float(best['settling_time_2pct_s']))} s")
        if len(ref):
            line += (f" ({float(ref.iloc[0]['settling_time_2pct_s']) / float(best['settling_time_2pct_s']):.1f}× "
                     f"faster than k = 146's {_fmt(float(ref.iloc[0]['settling_time_2pct_s']))} s)")
        notes.append(line + ".")
    return "\n".join(lines + notes) + "\n\n" + _source("coursework_grids", campaign) + "\n"


def beta_pd_block(key: str = "coursework_beta_pd_grid",
                  form: str = "Equations' form (`switched: true`, the default), 0.01 s.") -> str:
    """The β-PD's (K_s, K_d) grid of the committed campaign ``key`` (settling time, s), ``form`` its closing line."""
    campaign, df = _committed(key)
    if df is None:
        return _not_committed(campaign)
    ks_key, kd_key = "scenario.control.beta_pd.k_s", "scenario.control.beta_pd.k_d"
    grids = campaign.campaign().grids
    kss, kds = [float(v) for v in grids[0][ks_key]], [float(v) for v in grids[0][kd_key]]
    lines = ["| K_s \\ K_d | " + " | ".join(f"{k:g}" for k in kds) + " |", "|---|" + "---|" * len(kds)]
    f = df.assign(**{ks_key: df[ks_key].astype(float), kd_key: df[kd_key].astype(float)})
    for ks in kss:
        cells = []
        for kd in kds:
            c = _cell(f, 0, **{ks_key: ks, kd_key: kd})
            cells.append(f"**{c}**" if (ks, kd) == (990.0, 0.06) else c)
        lines.append(f"| {ks:g} | " + " | ".join(cells) + " |")
    others = [float(v) for v in grids[1][ks_key]]
    at = [(ks, _cell(f, 0, **{ks_key: ks, kd_key: 0.06})) for ks in others]
    lines += ["", "At K_d = 0.06: " + ", ".join(f"K_s = {ks:g} → {c}" + ("" if c == "not flown" else " s")
                                                 for ks, c in at) + ".",
              "(— : not within the run; `not flown`: the campaign was stopped before this point.) " + form]
    return "\n".join(lines) + "\n\n" + _source("coursework_grids", campaign) + "\n"


def wheels_pd_block() -> str:
    campaign, df = _committed("coursework_wheels_pd_grid")
    if df is None:
        return _not_committed(campaign)
    kd_key, kp_key = "scenario.control.wheels_pd.k_d", "scenario.control.wheels_pd.k_p"
    err = "scenario.control.wheels_pd.error"
    f = df.assign(**{kd_key: df[kd_key].astype(float), kp_key: df[kp_key].astype(float)})
    kds, kps = sorted(f[kd_key].unique()), sorted(f[kp_key].unique())
    lines = ["| K_d \\ K_p | " + " | ".join(f"{k:g}" for k in kps) + " |", "|---|" + "---|" * len(kps)]
    for kd in kds:
        cells = [_cell(f, 2, **{kd_key: kd, kp_key: kp, err: "report"}) for kp in kps]
        if kd == 9:
            cells[kps.index(5.0)] = f"**{cells[kps.index(5.0)]}**"
        lines.append(f"| {kd:g} | " + " | ".join(cells) + " |")
    ok = _ok(f)
    pivot = ok.pivot_table(index=[kd_key, kp_key], columns=err, values="settling_time_2pct_s")
    notes = [""]
    if {"report", "shortest_path"} <= set(pivot.columns):
        diff = float((pivot["report"] - pivot["shortest_path"]).abs().max())
        notes.append(f"- `error: shortest_path` against `error: report` (the table), largest difference over the "
                     f"{len(pivot)} points: {diff:.3f} s.")
    rep = ok[ok[err] == "report"]
    if len(rep):
        best = rep.loc[rep["settling_time_2pct_s"].astype(float).idxmin()]
        notes.append(f"- fastest point of the grid: K_d = {best[kd_key]:g}, K_p = {best[kp_key]:g}: "
                     f"{float(best['settling_time_2pct_s']):.2f} s.")
    notes.append(f"- {len(ok)} of {len(f)} runs ok; 120 s each, 0.01 s.")
    return "\n".join(lines + notes) + "\n\n" + _source("coursework_grids", campaign) + "\n"


def noise_block() -> str:
    campaign, df = _committed("coursework_noise")
    if df is None:
        return _not_committed(campaign)
    conv = CAMPAIGNS["coursework_convergence"].results()
    at = conv[conv["scenario.dynamics_step_s"].astype(float) == 0.01]
    ideal_cross = at[at["law"] == "cross_product"]["settling_time_2pct_s"]
    ideal_wheels = at[(at["law"] == "wheels_pd") & (at["scenario.control.wheels_pd.error"] == "report")
                      & at["scenario.control.wheels_pd.k_d"].isna()]["settling_time_2pct_s"]
    momentum = "scenario.spacecraft.reaction_wheels.momentum_noise_std_nms"
    cases = [("`magnetorquer1`, k = 146, 40 nT (4e-4 G) Gaussian noise on the field it reads",
              df[df["law"] == "cross_product"], 2, ideal_cross)]
    wheels = df[df["law"] == "wheels_pd"]
    for level in sorted(wheels[momentum].dropna().astype(float).unique()):
        cases.append((f"`wheels` (error `report`), momentum-reading noise {level:g} N·m·s (1σ)",
                      wheels[wheels[momentum].astype(float) == level], 3, ideal_wheels))
    lines = ["| case | runs ok / flown | settling (2 % bands), min–max over the seeds (s) | ideal sensors (s) |",
             "|---|---|---|---|"]
    for label, rows, digits, ideal in cases:
        ok = _ok(rows)["settling_time_2pct_s"].dropna().astype(float)
        spread = "—" if not len(ok) else (f"{_fmt(ok.min(), digits)}–{_fmt(ok.max(), digits)}"
                                          if ok.min() != ok.max() else f"{_fmt(ok.min(), digits)} (all {len(ok)})")
        ideal_text = _fmt(float(ideal.iloc[0]), digits) if len(ideal) else "—"
        lines.append(f"| {label} | {len(_ok(rows))} / {len(rows)} | {spread} | {ideal_text} |")
    lines += ["", "(Ideal sensors: the convergence campaign's 0.01 s rows, `docs/studies/coursework_convergence/`.)"]
    return "\n".join(lines) + "\n\n" + _source("coursework_grids", campaign) + "\n"


def beta_pd_listing_block() -> str:
    return beta_pd_block("coursework_beta_pd_grid_listing",
                         "The listing's form (`switched: false`, both spin terms), 0.01 s.")


_GRID_BLOCKS = {"coursework_cross_product": cross_product_block, "coursework_beta_pd": beta_pd_block,
                "coursework_beta_pd_listing": beta_pd_listing_block,
                "coursework_wheels_pd": wheels_pd_block, "coursework_noise": noise_block}
_GRID_FIGURES = {"coursework_cross_product_sweep": "cross_product_settling.png",
                 "coursework_beta_pd_grid": "beta_pd_heatmap_settling.png",
                 "coursework_wheels_pd_grid": "wheels_pd_heatmap_settling.png"}


def grid_blocks() -> dict[str, str]:
    return {name: make() for name, make in _GRID_BLOCKS.items()}


def regenerate_grids(ctx: Context) -> None:
    """The seed-004 sweep tables (cross product, β-PD, wheels, noise) and figures, from committed results:
    each figure is the campaign's own first plot (the settling time), redrawn by ``draw_plots``."""
    from fprime_lite.tools.campaign.plots import draw_plots

    ctx.set_blocks(_CONVERGENCE_DOC, grid_blocks())
    for key, figure in _GRID_FIGURES.items():
        campaign, df = _committed(key)
        if df is None:
            continue
        with tempfile.TemporaryDirectory() as scratch:
            pngs = draw_plots(df, campaign.campaign(), pathlib.Path(scratch))
            settling = [p for p in pngs if p.name.endswith("_settling_time_2pct_s.png")]
            if settling:
                ctx.copy(settling[0], IMG_DIR / "coursework" / figure)


# --- seed 004: the report's model (SciPy) ----------------------------------------------------------------

_REPLICA_CASES = (
    # (file under docs/studies/coursework_replica/, label, report_replica.py arguments)
    ("magnetorquer2_ode45.json", "`magnetorquer2`, eq. 23 *or* 24, ode45 defaults", ["beta_pd", "--t-max", "9000"]),
    ("magnetorquer2_listing_ode45.json", "`magnetorquer2`, both spin terms (listing), ode45 defaults",
     ["beta_pd", "--listing", "--t-max", "9000"]),
    ("wheels_ode45.json", "`wheels`, K_p = 5, K_d = 9, ode45 defaults", ["wheels_pd", "--t-max", "30"]),
    ("wheels_tight.json", "`wheels`, K_p = 5, K_d = 9, RelTol 1e-8",
     ["wheels_pd", "--t-max", "30", "--rtol", "1e-8", "--atol", "1e-10"]),
    ("wheels_tight_steps.json", "`wheels`, same, read off its accepted steps only (`--sample 0`)",
     ["wheels_pd", "--t-max", "30", "--rtol", "1e-8", "--atol", "1e-10", "--sample", "0"]),
)


def _replica_run(name: str, args: list[str]) -> dict:
    """The committed JSON line of ``report_replica.py ARGS`` (docs/studies/coursework_replica/NAME)."""
    path = _MT1_DIR / name
    if not path.exists():
        raise StudyError(f"{_shown(path)} is not committed: make it with `python campaigns/coursework/"
                         f"report_replica.py {' '.join(args)} > docs/studies/coursework_replica/{name}`")
    return json.loads(path.read_text(encoding="utf-8"))


def replica_blocks() -> dict[str, str]:
    """The report's model of ``magnetorquer2`` and ``wheels`` under SciPy's RK45, from the committed JSON lines of
    ``report_replica.py`` (docs/studies/coursework_replica/; the runs themselves take CPU-minutes and need SciPy)."""
    lines = ["| case (`campaigns/coursework/report_replica.py ARGS`) | ARGS | settling, 2 % bands: overall "
             "(x / y / z) | solver steps |", "|---|---|---|---|"]
    for name, label, args in _REPLICA_CASES:
        out = _replica_run(name, args)
        digits = 3 if args[0] == "wheels_pd" else 0
        axes = " / ".join(_fmt(a, digits) for a in out["settling_axes_s"])
        lines.append(f"| {label} | `{' '.join(args)}` | **{_fmt(out['settling_overall_s'], digits)}** ({axes}) "
                     f"| {out['steps']} |")
    lines += ["", "Generated by `python tools/studies.py --only coursework_replica` from "
              "`docs/studies/coursework_replica/*.json` (each the JSON line of `python campaigns/coursework/"
              "report_replica.py ARGS > docs/studies/coursework_replica/FILE`: SciPy RK45, settling read off its "
              "dense output every 1 ms unless `--sample 0`; `--rerun-campaigns` flies them again)."]
    return {"coursework_replica": "\n".join(lines) + "\n"}


def regenerate_replica(ctx: Context) -> None:
    ctx.set_blocks(_CONVERGENCE_DOC, replica_blocks())


def fly_replica() -> None:
    """Fly the β-PD and wheel replica runs again into docs/studies/coursework_replica/ (CPU-minutes; needs scipy)."""
    _fly_replica_cases(_REPLICA_CASES)


_MT1_DIR = STUDIES_DIR / "coursework_replica"
_MT1_CASES = (
    # (file under docs/studies/coursework_replica/, label, report_replica.py arguments)
    ("magnetorquer1_ode45.json", "ode45 defaults (RelTol 1e-3, AbsTol 1e-6)",
     ["cross_product", "--gain", "146", "--t-max", "30000"]),
    ("magnetorquer1_tight.json", "RelTol 1e-8, AbsTol 1e-10",
     ["cross_product", "--gain", "146", "--t-max", "30000", "--rtol", "1e-8", "--atol", "1e-10"]),
    ("magnetorquer1_ode45_unnormalized.json", "ode45 defaults, eq. 11's DCM from the un-normalised quaternion",
     ["cross_product", "--gain", "146", "--t-max", "30000", "--no-normalize"]),
)


def magnetorquer1_blocks() -> dict[str, str]:
    """The report's model of ``magnetorquer1`` (30,000 s under RK45), read off the dense output every 1 ms,
    from the committed JSON lines of ``report_replica.py`` (docs/studies/coursework_replica/)."""
    lines = ["| `magnetorquer1`, k = 146, RK45 | settling, 2 % bands: overall (x / y / z) (s) | solver steps | "
             "‖q‖ at the end | command |", "|---|---|---|---|---|"]
    for name, label, args in _MT1_CASES:
        path = _MT1_DIR / name
        command = (f"`python campaigns/coursework/report_replica.py {' '.join(args)} "
                   f"> docs/studies/coursework_replica/{name}`")
        if not path.exists():  # the command without the file it would write (the docs name existing paths only)
            lines.append(f"| {label} | not committed yet | | | `python campaigns/coursework/report_replica.py "
                         f"{' '.join(args)}` |")
            continue
        out = json.loads(path.read_text(encoding="utf-8"))
        if out.get("sample_s", 0) <= 0:
            raise StudyError(f"{_shown(path)}: read off the solver's steps (--sample 0); the table is of "
                             f"the dense output")
        axes = " / ".join(_fmt(a, 1) for a in out["settling_axes_s"])
        lines.append(f"| {label} | **{_fmt(out['settling_overall_s'], 1)}** ({axes}) | {out['steps']} | "
                     f"{out['final_norm_q']:.3f} | {command} |")
    lines += ["", "Generated by `python tools/studies.py --only coursework_replica_magnetorquer1` from "
              "`docs/studies/coursework_replica/*.json` (each the JSON line of its command: SciPy RK45, settling "
              "read off the dense output every 1 ms; `--rerun-campaigns` flies them again)."]
    return {"coursework_replica_magnetorquer1": "\n".join(lines) + "\n"}


def regenerate_magnetorquer1(ctx: Context) -> None:
    ctx.set_blocks(_CONVERGENCE_DOC, magnetorquer1_blocks())


def fly_magnetorquer1() -> None:
    """Fly the three replica runs again into docs/studies/coursework_replica/ (CPU-minutes; needs scipy)."""
    _fly_replica_cases(_MT1_CASES)


def _fly_replica_cases(cases) -> None:
    """Each case's ``report_replica.py ARGS`` again, its JSON line into docs/studies/coursework_replica/FILE."""
    from fprime_lite.osal.atomic import atomic_write_bytes

    replica = _load_script("campaigns/coursework/report_replica.py")
    for name, _, args in cases:
        _MT1_DIR.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(_MT1_DIR / name, (json.dumps(replica.run(replica.parse_args(args))) + "\n").encode())


# --- seed 004: the page's summary tables (report, replica, plant side by side) -----------------------------

#: The report's own figures (seed 004, the coursework report: Table 1 and its text), constants of the report quoted
#: as it prints them, not measured here: overall settling per controller, and the β-PD's per-axis times of Table 1
#: (1.669 h, 0.023 h, 1.693 h).
_REPORT_OVERALL = {"cross_product": "20,442 s", "beta_pd": "6,094.5 s", "listing": "—",
                   "wheels_pd": "\"within seconds\""}
_REPORT_BETA_AXES = ("6,008", "83", "6,095", "6,094.5")
#: The summary's rows: (key, label, the convergence campaign's series, the replica's committed file)
_SUMMARY_ROWS = (
    ("cross_product", "`magnetorquer1`, k = 146", "`cross_product`, k = 146", "magnetorquer1_ode45.json"),
    ("beta_pd", "`magnetorquer2` (β-PD), K_s = 990, K_d = 0.06, eq. 23 *or* 24 (the default)",
     "`beta_pd`, eq. 23 *or* 24 (default)", "magnetorquer2_ode45.json"),
    ("listing", "`magnetorquer2`, both spin terms (the listing, `switched: false`)",
     "`beta_pd`, both spin terms (listing)", "magnetorquer2_listing_ode45.json"),
    ("wheels_pd", "`wheels`, K_p = 5, K_d = 9", "`wheels_pd`, error `report`", "wheels_ode45.json"),
)
#: the replica's run at RelTol 1e-8 quoted beside its ode45 figure, where one is committed
_SUMMARY_TIGHT = {"cross_product": "magnetorquer1_tight.json", "wheels_pd": "wheels_tight.json"}


def _summary_series() -> dict[str, list[tuple[float, dict]]]:
    """The convergence campaigns' step-halving series (step = period; a point flown twice kept once), by label."""
    out = {}
    for label, rows in _convergence_series(_convergence_results()):
        kept, _ = _repeated_runs(rows)
        out[label] = [(step, m) for step, period, m in kept if step == period and m["status"] == "ok"]
    return out


def _replica_file(name: str) -> dict:
    args = {n: a for n, _, a in (*_MT1_CASES, *_REPLICA_CASES)}[name]
    return _replica_run(name, args)


def _converged_cell(series: list[tuple[float, dict]], digits: int) -> str:
    """The published figure by the rule (< 0.5 % on halving), its step and the halvings around it."""
    flown = [(step, m["overall"]) for step, m in series]
    published = _first_converged(flown)
    if published is None:
        step, value = flown[-1]
        return f"not converged over the steps flown ({_fmt(value, digits)} s at {step:g} s)"
    steps = [h for h, _ in flown]
    i = steps.index(published[0])
    moves = [100.0 * (flown[j][1] - flown[j - 1][1]) / flown[j - 1][1] for j in range(i, len(flown))]
    text = f"**{_fmt(published[1], digits)} s** ({published[0]:g} s: the halving to it moves it {moves[0]:+.2f} %"
    if len(moves) > 1:
        text += (", the next " + ", ".join(f"{m:+.2f} %" for m in moves[1:]) + ", to "
                 + ", ".join(f"{_fmt(v, digits)} s" for _, v in flown[i + 1:]))
    return text + ")"


def coursework_summary_blocks() -> dict[str, str]:
    """coursework_reproduction.md's two summary tables: the figures side by side (the report's, its model under
    RK45 at ode45's defaults, the plant at 0.01 s and converged) and the β-PD's per-axis pattern, from the committed
    replica runs (docs/studies/coursework_replica/) and the convergence campaigns, with the report's own figures."""
    series = _summary_series()
    lines = ["| controller (report's gains) | report | report's model, RK45 at ode45 defaults | plant, 0.01 s | "
             "plant, converged (the spec's < 0.5 % on halving) | flight deployment |", "|---|---|---|---|---|---|"]
    for key, label, name, replica in _SUMMARY_ROWS:
        digits = 3 if key == "wheels_pd" else 0
        rk = _replica_file(replica)
        at = dict(series[name])
        plant = at[0.01]["overall"] if 0.01 in at else None
        flight = ("same law, same trajectory (CWD-001)" if key == "cross_product" else
                  "within 0.3 s of the plant (CWD-001)" if key == "wheels_pd" else "(CWD-001)")
        model = f"{_fmt(rk['settling_overall_s'], digits)} s"
        if key in _SUMMARY_TIGHT:
            tight = _replica_file(_SUMMARY_TIGHT[key])["settling_overall_s"]
            model += f" ({_fmt(tight, 1 if digits == 0 else digits)} s at RelTol 1e-8)"
        lines.append(f"| {label} | {_REPORT_OVERALL[key]} | {model} | "
                     f"{_fmt(plant, digits)} s | {_converged_cell(series[name], digits)} | {flight} |")
    lines += ["", "The report's column is its own figures (Table 1 and its text). The model's: "
              "`docs/studies/coursework_replica/` (the blocks below). The plant's: the convergence campaigns (the "
              "convergence section), `error: report` for the wheels; converged is the first step from which every "
              "halving moves the figure by < 0.5 %. The flight column names the test that compares the deployment "
              "with the plant (CWD-001: the same trajectory, settling within 0.3 s)."]
    summary = "\n".join(lines) + "\n\nGenerated by `python tools/studies.py --only coursework_summary`.\n"

    def pattern(x: float, y: float, z: float) -> str:
        return f"{'x before z' if x < z else 'z before x'}, y ≈ {y:.0f} s"

    rows = ["| β-PD, K_s = 990, K_d = 0.06 | ω_x (s) | ω_y (s) | ω_z (s) | overall (s) | pattern |",
            "|---|---|---|---|---|---|"]
    x, y, z, overall = (float(v.replace(",", "")) for v in _REPORT_BETA_AXES)
    rows.append(f"| the report, Table 1 | {' | '.join(_REPORT_BETA_AXES)} | {pattern(x, y, z)} |")
    for label, axes, total in (
            ("report's model at ode45 defaults, eq. 23 *or* 24", *(lambda r: (r["settling_axes_s"],
                                                                              r["settling_overall_s"]))(
                _replica_file("magnetorquer2_ode45.json"))),
            ("same, both spin terms (listing)", *(lambda r: (r["settling_axes_s"], r["settling_overall_s"]))(
                _replica_file("magnetorquer2_listing_ode45.json"))),
            ("plant at 0.01 s, eq. 23 *or* 24", dict(series["`beta_pd`, eq. 23 *or* 24 (default)"])[0.01]["axes"],
             dict(series["`beta_pd`, eq. 23 *or* 24 (default)"])[0.01]["overall"]),
            ("plant at 0.01 s, both spin terms", dict(series["`beta_pd`, both spin terms (listing)"])[0.01]["axes"],
             dict(series["`beta_pd`, both spin terms (listing)"])[0.01]["overall"])):
        rows.append(f"| {label} | {_fmt(axes[0])} | {_fmt(axes[1], 1)} | {_fmt(axes[2])} | {_fmt(total)} | "
                    f"{pattern(*axes)} |")
    rows += ["", "Generated by `python tools/studies.py --only coursework_summary` from "
             "`docs/studies/coursework_replica/magnetorquer2*.json` and the convergence campaigns' 0.01 s rows (the "
             "report's row: its Table 1)."]
    return {"coursework_summary": summary, "coursework_beta_pattern": "\n".join(rows) + "\n"}


def regenerate_coursework_summary(ctx: Context) -> None:
    ctx.set_blocks(_CONVERGENCE_DOC, coursework_summary_blocks())


#: "Beyond the report": the real 1U wheel's orbit, kept as the JSON file of campaigns/coursework/real_wheel.py
REAL_WHEEL = "coursework_real_wheel.json"
_REAL_WHEEL_SCRIPT = "campaigns/coursework/real_wheel.py"
#: the magnetic laws shown beside it (keys of _SUMMARY_ROWS)
_REAL_WHEEL_BESIDE = {"beta_pd": "report's `magnetorquer2` (β-PD, eq. 23 *or* 24)",
                      "cross_product": "report's `magnetorquer1` (k = 146)"}


def real_wheel_blocks() -> dict[str, str]:
    """The real 1U wheel with dumping (its committed JSON file) beside the report's magnetic laws at 0.01 s and
    converged (the convergence campaigns' rows: their settling time and time under 1 °/s)."""
    command = f"python {_REAL_WHEEL_SCRIPT} --json docs/studies/{REAL_WHEEL}"
    path = STUDIES_DIR / REAL_WHEEL
    if not path.exists():
        raise StudyError(f"{_shown(path)} is not committed: make it with `{command}`")
    table = json.loads(path.read_text(encoding="utf-8"))
    lines = ["| | settling (2 % bands) | \\|ω − ω_final\\| < 1 °/s | wheel momentum |", "|---|---|---|---|",
             _load_script(_REAL_WHEEL_SCRIPT).markdown(table)]
    df = _convergence_results()
    series = _summary_series()
    for key, _, name, _ in _SUMMARY_ROWS:
        if key not in _REAL_WHEEL_BESIDE:
            continue
        at = dict(series[name])
        law = df[(df["law"] == key) & (df["scenario.dynamics_step_s"].astype(float) == 0.01)]
        if key == "beta_pd":
            law = law[law["scenario.control.beta_pd.switched"].astype(bool)]
        row = law.iloc[0]
        below = _float(row["time_below_threshold_s"])
        below_text = (f"{_fmt(below)} s" if below is not None else
                      f"not within {_fmt(float(row['duration_s']))} s")
        lines.append(f"| {_REAL_WHEEL_BESIDE[key]} | {_fmt(at[0.01]['overall'])} s at 0.01 s; converged "
                     f"{_converged_cell(series[name], 0)} | {below_text} (0.01 s) | — |")
    lines += ["", f"Generated by `python tools/studies.py --only coursework_real_wheel` from "
              f"`docs/studies/{REAL_WHEEL}` (made by `{command}`) and the convergence campaigns (the magnetic "
              f"laws' rows)."]
    return {"coursework_real_wheel": "\n".join(lines) + "\n"}


def fly_real_wheel() -> None:
    """Fly the real wheel's orbit again into its committed JSON file (~15 CPU-s)."""
    if _load_script(_REAL_WHEEL_SCRIPT).main(["--json", str(STUDIES_DIR / REAL_WHEEL)]) != 0:
        raise StudyError(f"`python {_REAL_WHEEL_SCRIPT}` failed")


def regenerate_real_wheel(ctx: Context) -> None:
    ctx.set_blocks(_CONVERGENCE_DOC, real_wheel_blocks())


_RIPPLE_DIR = STUDIES_DIR / "coursework_settling_ripple"
#: The β-PD's halvings flown by campaigns/coursework/settling_ripple.py (step = control period, s), per form: the
#: listing's (file listing_STEP.json) and the equations' (switched_STEP.json, ``--switched``).
_RIPPLE_STEPS = {"listing": (0.01, 0.005, 0.0025, 0.00125, 0.000625), "switched": (0.0025, 0.00125, 0.000625)}
_RIPPLE_FORMS = {"listing": "both spin terms (listing)", "switched": "eq. 23 *or* 24 (default)"}


def _ripple_command(step: float, form: str = "listing") -> str:
    return f"python campaigns/coursework/settling_ripple.py --step {step:g}" + (
        " --switched" if form == "switched" else "")


def _ripple_file(form: str, step: float) -> pathlib.Path:
    return _RIPPLE_DIR / f"{form}_{step:g}.json"


def _slow_axis(out: dict) -> str:
    """The axis whose 2 % settling time is the run's overall figure."""
    return max("xyz", key=lambda a: out["axes"][a]["settling_s"] or -math.inf)


def ripple_blocks() -> dict[str, str]:
    """The β-PD's slow axis around its 2 % settling instant at each step: the ripple peaks either side of the band,
    their spacing, the body's turn, and the settling time read off the signal and off the peaks' envelope; from the
    committed JSON lines of ``settling_ripple.py`` (docs/studies/coursework_settling_ripple/)."""
    lines = ["| β-PD form, slow axis | step = period (s) | 2 % settling (s) | last peak above the band: t (s), "
             "height / band | next peak: t (s), height / band | peak spacing (s) | turn, 2π/\\|ω − ω_final\\| (s) | "
             "envelope settling (s) |", "|---|---|---|---|---|---|---|---|"]
    summary = []
    for form, steps in _RIPPLE_STEPS.items():
        flown = []
        for step in steps:
            path = _ripple_file(form, step)
            if not path.exists():
                lines.append(f"| {_RIPPLE_FORMS[form]} | {step:g} | not committed yet: `{_ripple_command(step, form)} "
                             f"> docs/studies/coursework_settling_ripple/{path.name}` | | | | | |")
                continue
            out = json.loads(path.read_text(encoding="utf-8"))
            if out["switched"] != (form == "switched") or out["step_s"] != step:
                raise StudyError(f"{_shown(path)} is not the {form} form at {step:g} s")
            axis = _slow_axis(out)
            a = out["axes"][axis]
            last, after = a["peaks"][-2], a["peaks"][-1]
            if not (last["height_over_band"] > 1.0 >= after["height_over_band"]):
                raise StudyError(f"{_shown(path)}: its last two peaks do not straddle the band")
            lines.append(f"| {_RIPPLE_FORMS[form]}, ω_{axis} | {step:g} | **{_fmt(a['settling_s'], 1)}** | "
                         f"{_fmt(last['t_s'], 1)}, {last['height_over_band']:.4f} | {_fmt(after['t_s'], 1)}, "
                         f"{after['height_over_band']:.4f} | {a['ripple_period_s']:.1f} | "
                         f"{a['rotation_period_s']:.1f} | **{_fmt(a['envelope_settling_s'], 1)}** |")
            flown.append((step, a["settling_s"], a["envelope_settling_s"], a["settling_s"] - last["t_s"]))
        if len(flown) < 2:
            continue
        name = _RIPPLE_FORMS[form]
        for i, what in ((1, "2 % settling time"), (2, "envelope settling time")):
            diffs = [b[i] - a[i] for a, b in zip(flown, flown[1:], strict=False)]
            moves = ", ".join(f"{100.0 * d / a[i]:+.2f} %" for d, a in zip(diffs, flown, strict=False))
            shrinking = all(abs(d2) < abs(d1) for d1, d2 in zip(diffs, diffs[1:], strict=False))
            same_sign = all(d > 0 for d in diffs) or all(d < 0 for d in diffs)
            shape = ("monotone, each halving moving it less than the one before" if same_sign and shrinking else
                     "monotone" if same_sign else "not monotone")
            summary.append(f"- {name}: {what}, halving by halving: {moves} ({shape}).")
        published = _first_converged([(h, v) for h, _, v, _ in flown])
        p, limit = _richardson([v for _, _, v, _ in flown])
        summary.append(f"- {name}: envelope figure by the rule (< 0.5 % on halving): " + (
            f"{_fmt(published[1])} s at {published[0]:g} s" if published is not None else "not met over these steps")
            + (f"; observed order {p:.2f} from the last three, extrapolated limit ≈ {_fmt(limit)} s"
               if p is not None and p >= _MIN_ORDER else "") + ".")
        summary.append(f"- {name}: time from the last peak above the band to the 2 % settling instant: "
                       + ", ".join(f"{d:.1f} s" for *_, d in flown) + " (the peak's height over the band sets it).")
    source = ("Generated by `python tools/studies.py --only coursework_settling_ripple` from "
              "`docs/studies/coursework_settling_ripple/{listing,switched}_STEP.json` (each the JSON line of "
              "`nice -n 10 python campaigns/coursework/settling_ripple.py --step STEP [--switched]`: 9000 s, "
              "the trace kept every 0.5 s, peaks refined by a parabola through three samples; the 2 % figures are the "
              "run's own, measured at every control period).")
    return {"coursework_settling_ripple": "\n".join(lines) + "\n\n" + "\n".join(summary) + "\n\n" + source + "\n"}


def regenerate_ripple(ctx: Context) -> None:
    ctx.set_blocks(_CONVERGENCE_DOC, ripple_blocks())


def fly_ripple() -> None:
    """Fly the ripple runs again into docs/studies/coursework_settling_ripple/ (9000 s each: CPU-minutes)."""
    import contextlib
    import io

    from fprime_lite.osal.atomic import atomic_write_bytes

    script = _load_script("campaigns/coursework/settling_ripple.py")
    _RIPPLE_DIR.mkdir(parents=True, exist_ok=True)
    for form, steps in _RIPPLE_STEPS.items():
        for step in steps:
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                if script.main(["--step", f"{step:g}", *(["--switched"] if form == "switched" else [])]) != 0:
                    raise StudyError(f"`{_ripple_command(step, form)}` failed")
            atomic_write_bytes(_ripple_file(form, step), out.getvalue().encode())


# --- spin stabilisation campaign ---------------------------------------------------------------------------

_SPIN_DOC = STUDIES_DIR / "spin_stabilisation_campaign.md"


_SPIN_KEYS = ("spin_minor_axis", "spin_major_axis")


def _spin_results(study) -> list[dict | None]:
    """Each spin campaign's analysis from its committed folder (None: not committed)."""
    return [study.analyse(str(CAMPAIGNS[key].path)) if (CAMPAIGNS[key].path / "results.parquet").exists() else None
            for key in _SPIN_KEYS]


def _campaign_state(key: str) -> str:
    manifest = json.loads((CAMPAIGNS[key].path / "manifest.json").read_text(encoding="utf-8"))
    status = manifest.get("status", "?")
    return "" if status == "complete" else f" ({status}: {manifest.get('runs', '?')} planned)"


def spin_campaign_blocks() -> dict[str, str]:
    study = _load_script("campaigns/adcs/report_spin_study.py")
    results = _spin_results(study)
    if all(r is None for r in results):
        raise StudyError("no spin campaign results are committed: run `" + CAMPAIGNS["spin_minor_axis"].command + "`")
    labels = ("default, +Z minor (I_zz 2.05e-3)", "variant, +Z major (I_zz 2.40e-3)")
    lines = ["| inertia | runs (ok) | spin settle time p50 / p95 / max (s) | settled ≤ 1 orbit | then stayed ≥ 240 s "
             "(min) | transitions: SPIN_STABLE, POINTING and nothing else | **meets the target** | 95 % lower bound "
             "(Wilson) | momentum to +Z over SPIN_STABLE, median of the runs' medians / p95 of their p95s (deg) | "
             "CPU (s) |", "|---|---|---|---|---|---|---|---|---|---|"]
    bands = []
    for key, label, r in zip(_SPIN_KEYS, labels, results, strict=True):
        if r is None:
            lines.append(f"| {label} | not run yet: `{CAMPAIGNS[key].command}` | | | | | | | | |")
            continue
        n = r["n"]
        dwell = r["df"]["spin_settled_dwell_s"].to_numpy(dtype=float)
        lines.append(f"| {label} | {n} ({r['ok']}){_campaign_state(key)} | **{_fmt(r['p50'])} / {_fmt(r['p95'])} / "
                     f"{_fmt(r['max'])}** | {r['settled']} / {n} | {r['dwelt']} / {n} ({_fmt(float(min(dwell)), 1)} s) "
                     f"| {r['qualified']} / {n} | **{100 * r['meets'] / n:.0f} %** | {100 * r['lower95']:.1f} % | "
                     f"{r['axis_median']:.2f} / {r['axis_p95_of_p95']:.2f} | {r['cpu_s']:.0f} |")
        axis = "minor" if key == "spin_minor_axis" else "major"
        parts = [f"{_fmt(study.percentile(s, 50))} / {_fmt(float(max(s)))} ({lo:g}–{hi:g} °/s, {len(s)} runs)"
                 for lo, hi, s in study.rate_bands(r)]
        bands.append(f"- {axis} axis, settle time p50 / max (s) by initial rate: " + ", ".join(parts) + ".")
        flown = r["df"]["sim_seconds"].to_numpy(dtype=float)
        bands.append(f"- {axis} axis: AUTO declared the spin stable (POINTING) in {r['qualified']} of {n} runs, at "
                     f"{_fmt(study.percentile(flown, 50))} s median ({_fmt(float(max(flown)))} s at most) after "
                     f"SPIN_STABLE began; with the early stop the mean run flew {float(flown.mean()):.0f} s.")
    if all(r is not None for r in results) and (paired := study.paired(*results)) is not None:
        bands.append(f"- paired (the same draws): the major-axis body settles sooner in {paired['sooner']} of "
                     f"{paired['pairs']} pairs (median {paired['median_gain_s']:.1f} s sooner).")
    made = " and ".join(f"`{CAMPAIGNS[key].command}`"
                        for key, r in zip(_SPIN_KEYS, results, strict=True) if r is not None)
    source = ("Generated by `python tools/studies.py --only spin_stabilisation_campaign` from "
              f"`docs/studies/spin_stabilisation_campaign/` (made by {made}).")
    return {"spin_campaign": "\n".join(lines) + "\n\n" + "\n".join(bands) + "\n\n" + source + "\n"}


def regenerate_spin_campaign(ctx: Context) -> None:
    study = _load_script("campaigns/adcs/report_spin_study.py")
    ctx.set_blocks(_SPIN_DOC, spin_campaign_blocks())
    results = [r for r in _spin_results(study) if r is not None]
    with tempfile.TemporaryDirectory() as scratch:
        study._plot(results, pathlib.Path(scratch))
        ctx.copy(pathlib.Path(scratch) / "spin_settle.png", IMG_DIR / "spin_stabilisation" / "spin_settle.png")
    for key in _SPIN_KEYS:
        if (CAMPAIGNS[key].path / "results.parquet").exists():
            CAMPAIGNS[key].redraw_plots(ctx)


# --- campaign plots of the other committed campaigns ---------------------------------------------------------




# --- campaign tables of attitude_knowledge.md and flight_detumble_campaign.md -------------------------------------

_KNOWLEDGE_DOC = STUDIES_DIR / "attitude_knowledge.md"
_FLIGHT_DOC = STUDIES_DIR / "flight_detumble_campaign.md"
# (metric, label, digits, scale, unit, target text, test of one run's value)
_KNOWLEDGE_ROWS = (
    ("slew_settle_s", "90° slew settled below 0.1° (s)", 1, 1.0, "", "≤ 30 s", lambda v: v <= 30.0),
    ("pointing_steady_median_deg", "steady median (°)", 4, 1.0, "", "≤ 0.01°", lambda v: v <= 0.01),
    ("pointing_steady_p95_deg", "steady p95 (°)", 4, 1.0, "", "≤ 0.05°", lambda v: v <= 0.05),
    ("wheel_momentum_max_fraction", "largest \\|h_i\\|/h_max", 1, 100.0, " %", "< 50 %", lambda v: v < 0.5),
    ("wheel_limit_events", "wheel limit events", 0, 1.0, "", "never", lambda v: v == 0),
)


def knowledge_blocks() -> dict[str, str]:
    """The 100-run pointing campaign's table (docs/studies/attitude_knowledge/), per-run metrics' spread."""
    import numpy as np

    campaign, df = _committed("attitude_knowledge")
    if df is None:
        return {"attitude_knowledge_campaign": _not_committed(campaign)}
    ok = _ok(df)
    lines = ["| metric (per run) | min | median | p95 | max | target | runs meeting it |",
             "|---|---|---|---|---|---|---|"]
    for metric, label, digits, scale, unit, target, meets in _KNOWLEDGE_ROWS:
        values = ok[metric].dropna().to_numpy(dtype=float)
        if not len(values):
            lines.append(f"| {label} | — | — | — | — | {target} | 0 / {len(df)} |")
            continue
        stats = [float(np.min(values)), float(np.percentile(values, 50)), float(np.percentile(values, 95)),
                 float(np.max(values))]
        cells = [f"{_fmt(scale * s, digits)}{unit}" for s in stats]
        meeting = sum(1 for v in values if meets(v))
        lines.append(f"| {label} | " + " | ".join(cells) + f" | {target} | **{meeting} / {len(df)}** |")
    cpu = float(df["cpu_s"].sum()) if "cpu_s" in df else math.nan
    lines += ["", f"{len(ok)} of {len(df)} runs ok; {cpu:,.0f} CPU-s in the runs. Statistics over the runs' own "
              "figures (numpy's linear percentile)."]
    return {"attitude_knowledge_campaign": "\n".join(lines) + "\n\n" + _source("attitude_knowledge", campaign) + "\n"}


def knowledge_verdict_blocks() -> dict[str, str]:
    """attitude_knowledge.md's verdict on issue 13's targets, from the 100-run campaign's committed results and the
    orbit runs' committed JSON (docs/studies/attitude_knowledge/orbit_runs.json)."""
    import numpy as np

    campaign, df = _committed("attitude_knowledge")
    orbit_path = STUDIES_DIR / "attitude_knowledge" / "orbit_runs.json"
    if df is None or not orbit_path.exists():
        raise StudyError(f"the verdict needs docs/studies/{campaign.folder}/ and {_shown(orbit_path)} committed")
    runs = json.loads(orbit_path.read_text(encoding="utf-8"))["runs"]
    orbit, no_dump, shipped = runs["orbit"], runs["orbit_no_dumping"], runs["shipped"]
    ok, n = _ok(df), len(df)

    def column(metric: str) -> list[float]:
        return [float(v) for v in ok[metric].dropna()]

    def verdict(met: bool) -> str:
        return "**met**" if met else "**not met**"

    slew, med, p95 = column("slew_settle_s"), column("pointing_steady_median_deg"), column("pointing_steady_p95_deg")
    events, peak = column("wheel_limit_events"), column("wheel_momentum_max_fraction")
    med_ok, p95_ok, slew_ok = (sum(v <= 0.01 for v in med), sum(v <= 0.05 for v in p95),
                               sum(v <= 30.0 for v in slew))
    orbit_events = sum(r["limit_events"] for r in runs.values())
    ratio = orbit["h_after_slew_mean_nms"] / no_dump["h_after_slew_mean_nms"]
    lines = [
        "| target (issue 13, wheels + star tracker 10″) | verdict | evidence |", "|---|---|---|",
        f"| 90° slew settled below 0.1° in ≤ 30 s | {verdict(slew_ok == n)}: {slew_ok} / {n} runs, "
        f"{_fmt(min(slew), 1)}–{_fmt(max(slew), 1)} s | campaign; the orbit run "
        f"({_fmt(orbit['slew_settle_s'], 1)} s) |",
        f"| steady-state median ≤ 0.01° | {verdict(float(np.median(med)) <= 0.01)} as a statistic (median of per-run "
        f"medians {float(np.median(med)):.4f}°, p95 {float(np.percentile(med, 95)):.4f}°) and in {med_ok} / {n} runs "
        f"individually (largest {max(med):.4f}°) | campaign; the shipped run ({shipped['steady_median_deg']:.4f}°) |",
        f"| steady-state p95 ≤ 0.05° | {verdict(p95_ok == n)}: {p95_ok} / {n}, largest {max(p95):.3f}° | campaign; "
        f"the shipped run ({shipped['steady_p95_deg']:.4f}°) |",
        f"| torque and momentum limits never exceeded | {verdict(sum(events) == 0 and orbit_events == 0)}: "
        f"{sum(events):.0f} events in {len(events)} runs and {orbit_events} in the {len(runs)} orbit-table runs | no "
        f"limit event in any run |",
        f"| wheel momentum < 50 % of capacity by magnetic dumping over an orbit | "
        f"{'met' if orbit['wheel_momentum_max_fraction'] < 0.5 else '**not met**'} (one orbit, one run): peak "
        f"{100 * orbit['wheel_momentum_max_fraction']:.1f} %, set by the slew; after it dumping holds \\|h\\| to "
        f"{ratio:.2f} of what it averages without | orbit runs; the campaign's runs peak at {100 * max(peak):.1f} % |",
    ]
    source = (f"Generated by `python tools/studies.py --only attitude_knowledge_verdict` from "
              f"`docs/studies/{campaign.folder}/` (made by `{campaign.command}`) and `{_shown(orbit_path)}`.")
    return {"attitude_knowledge_verdict": "\n".join(lines) + "\n\n" + source + "\n"}


def regenerate_knowledge_verdict(ctx: Context) -> None:
    ctx.set_blocks(_KNOWLEDGE_DOC, knowledge_verdict_blocks())


def regenerate_knowledge(ctx: Context) -> None:
    ctx.set_blocks(_KNOWLEDGE_DOC, knowledge_blocks())
    CAMPAIGNS["attitude_knowledge"].redraw_plots(ctx)


def _flight_table(key: str) -> str:
    """``campaigns/report_flight_study.py``'s tables of one committed campaign folder (its stdout)."""
    import contextlib
    import io

    campaign, df = _committed(key)
    if df is None:
        return _not_committed(campaign)
    report = _load_script("campaigns/report_flight_study.py")
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        report.main([str(campaign.path)])
    lines = buffer.getvalue().rstrip("\n").split("\n")
    first = next(i for i, line in enumerate(lines) if line.startswith("|"))
    last = max(i for i, line in enumerate(lines) if line.startswith("|"))
    after = [line for line in lines[last + 1:] if line.strip()]
    text = ("; ".join(lines[:first]) + ".\n\n" + "\n".join(lines[first:last + 1]) + "\n\n"
            + "\n".join(f"- {line}" for line in after if not line.startswith(" ")))
    return (text + "\n\n" + _source("flight_detumble_campaign", campaign)
            + f" The table is `python campaigns/report_flight_study.py docs/studies/{campaign.folder}`.\n")


def flight_blocks() -> dict[str, str]:
    return {"flight_detumble_p95": _flight_table("flight_detumble_campaign_p95"),
            "flight_detumble_orbit": _flight_table("flight_detumble_campaign")}


def regenerate_flight(ctx: Context) -> None:
    ctx.set_blocks(_FLIGHT_DOC, flight_blocks())
    for key in ("flight_detumble_campaign", "flight_detumble_campaign_p95"):
        CAMPAIGNS[key].redraw_plots(ctx)


# --- the flight B-dot against BDotDetumble: gain_sweep.md and flight_bdot_noise.md ------------------------------

_GAIN_DOC = STUDIES_DIR / "gain_sweep.md"
_NOISE_DOC = STUDIES_DIR / "flight_bdot_noise.md"
_FLIGHT_GAIN = "params.ReferenceDeployment.detumbleManager.GAIN"
_VARIANT_GAIN = "params.ReferenceDeployment.bdotDetumble.Gain"
_COMPLETE = "detumble_complete_s"


def _completion(rows) -> list[float | None]:
    """``detumble_complete_s`` of ``rows`` in seed order (None: not reached within the run, or not ok)."""
    rows = rows.sort_values("seed_index")
    return [_float(r[_COMPLETE]) if r["status"] == "ok" else None for _, r in rows.iterrows()]


def _seconds(values: list[float | None]) -> str:
    return " / ".join(_fmt(v, none="never") for v in values) + " s"


def gain_sweep_blocks() -> dict[str, str]:
    """The gain table of docs/studies/gain_sweep.md: time to DetumbleCompleted per gain and noise seed."""
    from fractions import Fraction

    import numpy as np

    campaign, df = _committed("gain_sweep")
    if df is None:
        return {"gain_sweep": _not_committed(campaign)}
    flight = df[df[_FLIGHT_GAIN].notna()]
    variant = df[df[_VARIANT_GAIN].notna()]
    gains = sorted(float(g) for g in flight[_FLIGHT_GAIN].unique())
    variant_gains = sorted(float(g) for g in variant[_VARIANT_GAIN].unique())
    if len(gains) != len(variant_gains):
        raise StudyError(f"{campaign.campaign_file}: the two sub-grids should scale the gains by the same factors")
    seeds = int(df["seed_index"].nunique())
    lines = [f"| × default | flight `GAIN` | flight: complete at (seed {' / '.join(str(i) for i in range(seeds))}) "
             f"| median | BDotDetumble `Gain` | BDotDetumble: complete at | median |", "|---|---|---|---|---|---|---|"]

    def median(values: list[float | None]) -> str:
        return "never" if not values or None in values else f"{_fmt(float(np.median(values)))} s"

    for g, v in zip(gains, variant_gains, strict=True):
        factor = Fraction(g / 3.0).limit_denominator(12)
        f_values = _completion(flight[flight[_FLIGHT_GAIN] == g])
        v_values = _completion(variant[variant[_VARIANT_GAIN] == v])
        cells = [str(factor), f"{g:g}", _seconds(f_values), median(f_values), f"{v:.3g}", _seconds(v_values),
                 median(v_values)]
        if factor == 1:
            cells = [f"**{c}**" for c in cells]
        lines.append("| " + " | ".join(cells) + " |")

    def spread(rows) -> str:
        values = [x for x in _completion(rows) if x is not None]
        return f"{_fmt(min(values))}–{_fmt(max(values))} s" if values else "never"

    at_default = _completion(flight[flight[_FLIGHT_GAIN] == 3.0])
    gap = (max(at_default) - min(at_default)) if at_default and None not in at_default else None
    upper = spread(variant[variant[_VARIANT_GAIN] >= 1.0])
    lines += ["", f"Flight B-dot over every gain and seed: {spread(flight)} (at the default gain the seeds differ by "
              f"{_fmt(gap)} s); BDotDetumble: {spread(variant)}, of which {upper} at its default gain and above. "
              f"{len(_ok(df))} of {len(df)} runs ok."]
    return {"gain_sweep": "\n".join(lines) + "\n\n" + _source("gain_sweep", campaign) + "\n"}


_NOISE_ROWS = (  # (noise σ G, quantisation step G, label)
    (0.003, 0.0015, "as in the scenario (σ 3 mG, 1.5 mG steps)"),
    (0.0, 0.0015, "no noise (`noise_std_gauss=0`)"),
    (0.003, 0.0, "no quantisation (`resolution_gauss=0`)"),
    (0.0, 0.0, "neither"),
)


def noise_blocks() -> dict[str, str]:
    """The magnetometer table of docs/studies/flight_bdot_noise.md: median (range) over the noise seeds."""
    import numpy as np

    campaign, df = _committed("flight_bdot_noise")
    if df is None:
        return {"flight_bdot_noise": _not_committed(campaign)}
    noise, step = "scenario.sensors.magnetometer.noise_std_gauss", "scenario.sensors.magnetometer.resolution_gauss"
    seeds = int(df["seed_index"].nunique())
    lines = ["| magnetometer | flight B-dot (`topology.yaml`) | BDotDetumble (`topology_bdot_detumble.yaml`) |",
             "|---|---|---|"]
    for sigma, q, label in _NOISE_ROWS:
        cells = []
        for topology in ("topology.yaml", "topology_bdot_detumble.yaml"):
            rows = df[df["topology"].str.endswith("/" + topology) & (df[noise] == sigma) & (df[step] == q)]
            values = _completion(rows)
            if not values:
                cells.append("not flown")
                continue
            reached = [x for x in values if x is not None]
            if len(reached) < len(values):
                cells.append(_seconds(values))
                continue
            cells.append(f"**{_fmt(float(np.median(reached)))} s** ({_fmt(min(reached))}–{_fmt(max(reached))})")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lines += ["", f"Median (min–max) over {seeds} magnetometer noise seeds, the same seeds in every cell; "
              f"{len(_ok(df))} of {len(df)} runs ok."]
    return {"flight_bdot_noise": "\n".join(lines) + "\n\n" + _source("flight_bdot_noise", campaign) + "\n"}


# No campaign plots for these two: their grids mix two topologies, each with its own keys, and the automatic
# heatmap would pool them (the tables are the result).
def regenerate_gain_sweep(ctx: Context) -> None:
    ctx.set_blocks(_GAIN_DOC, gain_sweep_blocks())


def regenerate_noise(ctx: Context) -> None:
    ctx.set_blocks(_NOISE_DOC, noise_blocks())


# --- docs/performance.md: the detumble it times, against the committed campaigns' draws --------------------------

_PERF_DOC = ROOT / "docs" / "performance.md"


def performance_detumble_blocks() -> dict[str, str]:
    """The sentence of docs/performance.md that places its timed detumble (the default scenario's noise seed 1)
    among the committed campaigns' flight B-dot runs at the default GAIN and the scenario's magnetometer."""
    import numpy as np

    gain_campaign, gain = _committed("gain_sweep")
    noise_campaign, noise = _committed("flight_bdot_noise")
    if gain is None or noise is None:
        raise StudyError("docs/studies/gain_sweep/ and docs/studies/flight_bdot_noise/ must be committed")
    sweep = _completion(gain[gain[_FLIGHT_GAIN] == 3.0])
    as_flown = noise[noise["topology"].str.endswith("/topology.yaml")
                     & (noise["scenario.sensors.magnetometer.noise_std_gauss"] == 0.003)
                     & (noise["scenario.sensors.magnetometer.resolution_gauss"] == 0.0015)]
    drawn = _completion(as_flown)
    every = sweep + drawn
    if not sweep or not drawn or None in every:
        raise StudyError("a flight B-dot run at the default gain did not complete its detumble: the range is undefined")
    text = (f"The committed campaigns' {len(every)} noise draws at the default gain give "
            f"{_fmt(min(every))}–{_fmt(max(every))} s "
            f"({len(sweep)} seeds in\n[gain_sweep.md](studies/gain_sweep.md): {_seconds(sweep)}; {len(drawn)} in\n"
            f"[flight_bdot_noise.md](studies/flight_bdot_noise.md): {_fmt(min(drawn))}–{_fmt(max(drawn))} s, median "
            f"{_fmt(float(np.median(drawn)))} s). It is a\nworkload for the wall-clock figure, not a detumble "
            f"performance figure: those are the studies'.\n\nGenerated by `python tools/studies.py --only "
            f"performance_detumble` from `docs/studies/gain_sweep/` and\n`docs/studies/flight_bdot_noise/`.\n")
    return {"performance_detumble": text}


def regenerate_performance_detumble(ctx: Context) -> None:
    ctx.set_blocks(_PERF_DOC, performance_detumble_blocks())


# --- single-run tables of study scripts, from the JSON file each script writes (--json) ------------------------------


#: the margin screen's weight sets on the linearised hold, 'θ scale deg/rate scale rad/s/r/α 1/s' (the kept one first)
MARGIN_WEIGHT_SETS = ("30/0.03/1/0.002,30/0.02/1/0.002,30/0.025/1/0.002,30/0.03/1/0.001,30/0.03/1/0.003,"
                      "30/0.03/1/0.004,30/0.03/0.5/0.002,30/0.03/2/0.002,20/0.03/1/0.002,25/0.03/1/0.002,"
                      "30/0.02/1/0.003,15/0.03/1/0.002,20/0.03/1/0.003,20/0.02/0.5/0.002")


@dataclasses.dataclass(frozen=True)
class ScriptTable:
    """A table that a script under campaigns/ (or a module's ``main``) prints from its own flights (minutes: too
    long for ``--check``), kept as the JSON file its ``--json`` writes and rendered by its ``markdown()``."""

    name: str              # the study's (--only NAME)
    summary: str
    block: str
    script: str            # relative to the repository, or the module run with python -m
    results: str           # relative to docs/studies/
    doc: pathlib.Path
    args: tuple[str, ...] = ()   # the script's arguments before --json
    module: bool = False   # script names a module (python -m SCRIPT), not a file
    render: str = "markdown"   # the script's function that renders the table from the JSON file
    # the script's function ``probe(committed) -> list[str]``: recompute a cheap piece of the JSON file (the study's
    # --check probe); empty: none
    probe: str = ""

    @property
    def path(self) -> pathlib.Path:
        return STUDIES_DIR / self.results

    def run_probe(self) -> list[str]:
        """The script's probe against the committed JSON file (its problems, each naming the command to re-fly)."""
        if not self.probe:
            return []
        if not self.path.exists():
            return [f"{_shown(self.path)} is not committed: make it with `{self.command}`"]
        committed = json.loads(self.path.read_text(encoding="utf-8"))
        found = getattr(self.code(), self.probe)(committed)
        return [f"{_shown(self.path)}: {p}: the code no longer computes the documented figures (`{self.command}` "
                f"then `python tools/studies.py --only {self.name}`)" for p in found]

    @property
    def command(self) -> str:
        run = f"python -m {self.script}" if self.module else f"python {self.script}"
        return " ".join([run, *self.args, "--json", f"docs/studies/{self.results}"])

    def code(self):
        return importlib.import_module(self.script) if self.module else _load_script(self.script)

    def blocks(self) -> dict[str, str]:
        if not self.path.exists():
            raise StudyError(f"{_shown(self.path)} is not committed: make it with `{self.command}`")
        table = json.loads(self.path.read_text(encoding="utf-8"))
        if table.get("quick"):
            raise StudyError(f"{_shown(self.path)} holds a --quick run's figures: make it with `{self.command}`")
        try:
            body = getattr(self.code(), self.render)(table)
        except ValueError as exc:  # the renderer refuses a file not made as the table says (its reason)
            raise StudyError(f"{_shown(self.path)}: {exc} (`{self.command}`)") from exc
        return {self.block: f"{body}\nGenerated by `python tools/studies.py --only {self.name}` from "
                            f"`docs/studies/{self.results}` (made by `{self.command}`).\n"}

    def regenerate(self, ctx: Context) -> None:
        ctx.set_blocks(self.doc, self.blocks())

    def study(self) -> Study:
        return Study(self.name, self.summary, self.regenerate, self.blocks, self.doc,
                     probe=self.run_probe if self.probe else None)

    def fly(self) -> None:
        """Fly the script again into its committed JSON file (minutes)."""
        if self.code().main([*self.args, "--json", str(self.path)]) != 0:
            raise StudyError(f"`{self.command}` failed")


SCRIPT_TABLES = {t.name: t for t in (
    ScriptTable("robust_rates", "issue 27's slew with the plant's inertia off the model: 12 plant-only runs "
                "(committed JSON)", "robust_rates_single_runs", "campaigns/adcs/robust_rates_table.py",
                "robust_rates/table.json", STUDIES_DIR / "robust_rates.md"),
    ScriptTable("robust_rates_tail", "where the robust-rates campaign's p95 comes from: its 100 draws, the integral's "
                "window at 1° and 0.1°, 400 plant runs (committed JSON)", "robust_rates_tail",
                "campaigns/adcs/robust_rates_tail.py", "robust_rates/tail.json", STUDIES_DIR / "robust_rates.md"),
    ScriptTable("pointing_targets", "issue 27's moving targets on the wheels: 9 plant-only runs (committed JSON)",
                "pointing_targets", "campaigns/adcs/targets_study.py", "pointing_targets/table.json",
                STUDIES_DIR / "pointing_targets.md"),
    ScriptTable("environment_torques", "when AUTO reaches POINTING in the dipole and IGRF-14: 12 plant-only runs "
                "(committed JSON)", "environment_torques_field_auto", "campaigns/adcs/field_auto_study.py",
                "environment_torques/field_auto.json", STUDIES_DIR / "environment_torques.md"),
    ScriptTable("environment_feed_forward", "the wheel law's gyroscopic and gravity-gradient feed-forward, and drag "
                "and solar pressure, in a nadir hold: 5 plant-only runs (committed JSON)",
                "environment_torques_feed_forward", "campaigns/adcs/wheel_runs_study.py",
                "environment_torques/feed_forward.json", STUDIES_DIR / "environment_torques.md",
                ("--part", "feed_forward")),
    ScriptTable("environment_four_wheels", "a fourth wheel's null-space momentum management: 2 plant-only runs "
                "(committed JSON)", "environment_torques_four_wheels", "campaigns/adcs/wheel_runs_study.py",
                "environment_torques/four_wheels.json", STUDIES_DIR / "environment_torques.md",
                ("--part", "four_wheels")),
    ScriptTable("pointing_gyroscopic", "the gyroscopic feed-forward over a ground-station pass: 2 plant-only runs "
                "(committed JSON)", "pointing_targets_gyroscopic", "campaigns/adcs/wheel_runs_study.py",
                "pointing_targets/gyroscopic.json", STUDIES_DIR / "pointing_targets.md", ("--part", "gyroscopic")),
    ScriptTable("attitude_modes_sensors", "seed 003's pointing on the wheels with noiseless sensors: four 300 s "
                "adcs_ref runs (committed JSON)", "attitude_modes_sensors", "campaigns/adcs/wheels_sensor_table.py",
                "attitude_modes/sensors.json", STUDIES_DIR / "attitude_modes.md"),
    ScriptTable("attitude_knowledge_orbit_runs", "issue 13's pointing on the wheels over an orbit and the shipped "
                "sequence: three adcs_ref runs, ~3 CPU-minutes (committed JSON)", "attitude_knowledge_orbit_runs",
                "campaigns/adcs/wheels_orbit_table.py", "attitude_knowledge/orbit_runs.json",
                STUDIES_DIR / "attitude_knowledge.md"),
    ScriptTable("magnetic_pointing_residual_ab", "magnetorquer hold: the residual-dipole compensation on and off, "
                "same start and noise seed, present and previous gains: four one-orbit adcs_ref runs (committed "
                "JSON; the probe re-flies 300 s of one)", "magnetic_pointing_residual_ab",
                "campaigns/adcs/magnetic_pointing_runs.py", "magnetic_pointing/residual_ab.json",
                STUDIES_DIR / "magnetic_pointing.md",
                ("--only", "ab_present_on", "ab_present_off", "ab_previous_on", "ab_previous_off"),
                render="residual_ab_markdown", probe="ab_probe"),
    ScriptTable("attitude_knowledge_mekf", "issue 13's MEKF: the figures of the flights its unit tests assert on "
                "(tests/detumble/control/test_mekf.py's harness; committed JSON, a few CPU-s, re-flown by the probe)",
                "attitude_knowledge_mekf", "campaigns/adcs/mekf_evidence.py", "attitude_knowledge/mekf_evidence.json",
                STUDIES_DIR / "attitude_knowledge.md", probe="probe"),
    ScriptTable("magnetorquer_hold_lqr_bound", "issue 27's coil hold: how fast a periodic LQR (any linear coil law "
                "with B(t) known) makes the linearised hold fall from 30°, at what dipole (committed JSON, "
                "~4 CPU-minutes; the probe recomputes one weight)", "magnetorquer_hold_lqr_bound",
                "campaigns/adcs/magnetic_lqr_bound.py", "magnetorquer_hold_after_acquisition/lqr_bound.json",
                STUDIES_DIR / "magnetorquer_hold_after_acquisition.md", probe="probe"),
    ScriptTable("magnetorquer_hold_margin", "issue 27's 40° coil hold: a screen of candidates for margin under the "
                "p95 goal, 28 plant draws a candidate (committed JSON, ~15 CPU-minutes a candidate)",
                "magnetorquer_hold_margin", "campaigns/adcs/magnetorquer_hold_candidates.py",
                "magnetorquer_hold_after_acquisition/margin.json",
                STUDIES_DIR / "magnetorquer_hold_after_acquisition.md", args=("--part", "margin"),
                render="margin_markdown"),
    ScriptTable("magnetorquer_hold_lqr_weights_screen", "issue 27's 40° coil hold: weight sets near the kept one on "
                "the linearised hold, the margin screen's first step (committed JSON, ~1 CPU-minute a set)",
                "magnetorquer_hold_lqr_weights_screen", "campaigns/adcs/magnetorquer_hold_lqr_weights.py",
                "magnetorquer_hold_after_acquisition/lqr_weights.json",
                STUDIES_DIR / "magnetorquer_hold_after_acquisition.md", args=("--sets", MARGIN_WEIGHT_SETS)),
)}


_SUN_SAFE_DOC = STUDIES_DIR / "sun_safe.md"
_SUN_SAFE_SUMMARY = ("issue 27's Sun-safe on the light sensors: 96 plant-only seed flights and 36 adcs_ref flights "
                     "(committed JSON)")
#: sun_safe.md's plant-only tables: (block and JSON file name, the module's arguments)
SUN_SAFE_TABLES = tuple(
    ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, f"sun_safe_{key}", "detumble.sim.sun_safe_check", f"sun_safe/{key}.json",
                _SUN_SAFE_DOC, tuple(args.split()), module=True)
    for key, args in (("wheels", "--seeds 5"), ("magnetorquers", "--seeds 3 --actuator MAGNETORQUERS"),
                      ("albedo_wheels", "--seeds 3 --albedo 0.3 --penumbra"),
                      ("albedo_magnetorquers", "--seeds 3 --albedo 0.3 --penumbra --actuator MAGNETORQUERS"),
                      ("albedo_model_wheels", "--seeds 3 --albedo 0.3 --penumbra --albedo-model 0.3"),
                      ("albedo_model_magnetorquers",
                       "--seeds 3 --albedo 0.3 --penumbra --albedo-model 0.3 --actuator MAGNETORQUERS"))) + (
    # the F´ side: the ADCS component's raw and corrected vector over adcs_ref's AUTO flight (3 deployment runs)
    ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, "sun_safe_albedo_deployment", "campaigns/adcs/sun_albedo_deployment.py",
                "sun_safe/albedo_deployment.json", _SUN_SAFE_DOC),
    # the coils through adcs_ref (21 deployment runs): by ground command, the operator procedure, the hand-back,
    # the hand-back with the hold spin at 1.9 °/s (the candidate fix for the eclipse the hold costs) and from a
    # 2 °/s tumble (why the tracker-loss kinds fly 1.9 °/s); the last two with a --check probe (120 s of seed 1)
    *(ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, f"sun_safe_coil_{kind}", "campaigns/adcs/sun_safe_coil_runs.py",
                  f"sun_safe/coil_{kind}.json", _SUN_SAFE_DOC, (kind,),
                  probe="coil_probe" if kind in ("hand_back_hold_1_9", "hand_back_2_deg_s") else "")
      for kind in ("command", "operator", "hand_back", "hand_back_hold_1_9", "hand_back_2_deg_s")),
    # where along the orbit the field lets the coils lower the spin (no flight: one pass over the orbit, ~1 s)
    ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, "sun_safe_spin_down_geometry", "detumble.sim.spin_down_geometry",
                "sun_safe/spin_down_geometry.json", _SUN_SAFE_DOC, module=True),
    # the coils' automatic spin-down, plant-only (5 seed flights; seed 1's first sunlit part re-flown by the probe)
    ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, "sun_safe_spin_down", "detumble.sim.sun_safe_check",
                "sun_safe/spin_down.json", _SUN_SAFE_DOC, ("--spin-down", "--seeds", "5"), module=True,
                render="spin_down_markdown", probe="spin_down_probe"),
    # ... and with its parameters changed (one JSON file, four tables: 51 plant-only flights)
    *(ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, f"sun_safe_spin_down_{part}",
                  "campaigns/adcs/sun_spin_down_variants.py", "sun_safe/spin_down_variants.json", _SUN_SAFE_DOC,
                  render=f"{part}_markdown")
      for part in ("gate", "tip", "hold_rate", "spin_rate")),
    # the single flights the page's prose quotes (one JSON file, six blocks: 11 plant-only flights, 11 short adcs_ref
    # runs and one of an orbit; the probe, on the first only, recomputes the t = 0 figures and re-flies two parts)
    *(ScriptTable("sun_safe", _SUN_SAFE_SUMMARY, f"sun_safe_single_{part}",
                  "campaigns/adcs/sun_safe_single_flights.py", "sun_safe/single_flights.json", _SUN_SAFE_DOC,
                  render=f"{part}_markdown", probe="probe" if part == "bias" else "")
      for part in ("bias", "lit", "coil_gains", "tracker_limit", "bounce", "albedo_flight")),)
#: sun_safe.md's albedo-mismatch table (wheels, model a = 0.3): (albedo in the sensors, its JSON file under
#: docs/studies/, what the row is called); the 0.3 row is the albedo_model_wheels table's file
SUN_SAFE_MISMATCH = ((0.0, "sun_safe/albedo_model_truth_00.json", "0 (the model subtracts light that is not there)"),
                     (0.2, "sun_safe/albedo_model_truth_02.json", "0.2"),
                     (0.3, "sun_safe/albedo_model_wheels.json", "0.3 (the model's)"),
                     (0.4, "sun_safe/albedo_model_truth_04.json", "0.4"))


def _mismatch_command(albedo: float, results: str) -> str:
    return (f"python -m detumble.sim.sun_safe_check --seeds 3 --albedo {albedo:g} --penumbra --albedo-model 0.3 "
            f"--json docs/studies/{results}")


def sun_safe_mismatch_block() -> dict[str, str]:
    """The model against a different Earth: one row per albedo in the sensors, from each file's per-seed Sun vector
    figures (its options checked: 3 seeds, wheels, penumbra, model 0.3, that albedo)."""
    lines = ["| albedo in the sensors | Sun vector median (deg, per seed) | p95 (deg, per seed) | max (deg, all) | "
             "sunlit readings ≤ 5° | acquisition ≤ 10° (s, per seed) |", "|---|---|---|---|---|---|"]
    for albedo, results, label in SUN_SAFE_MISMATCH:
        path = STUDIES_DIR / results
        if not path.exists():
            raise StudyError(f"{_shown(path)} is not committed: make it with `{_mismatch_command(albedo, results)}`")
        data = json.loads(path.read_text(encoding="utf-8"))
        opts = data.get("options", {})
        wanted = {"seeds": 3, "actuator": "ANY", "albedo": albedo, "albedo_model": 0.3, "penumbra": True}
        if any(opts.get(k) != v for k, v in wanted.items()):
            raise StudyError(f"{_shown(path)} was not made by `{_mismatch_command(albedo, results)}`")
        medians = " / ".join(f"{r['vector_deg']['median']:.2f}" for r in data["rows"])
        p95s = " / ".join(f"{r['vector_deg']['p95']:.2f}" for r in data["rows"])
        within = " / ".join(f"{100 * r['vector_within']:.1f}" for r in data["rows"])
        acquired = " / ".join("never" if r["acquisition_s"] is None else f"{r['acquisition_s']:.0f}"
                              for r in data["rows"])
        lines.append(f"| {label} | {medians} | {p95s} | {data['pooled_vector_deg']['max']:.2f} | {within} % | "
                     f"{acquired} |")
    made = "; ".join(f"`{_mismatch_command(a, r)}`" for a, r, _ in SUN_SAFE_MISMATCH)
    return {"sun_safe_albedo_mismatch": "\n".join(lines) + f"\n\nGenerated by `python tools/studies.py --only "
            f"sun_safe` from the files made by {made}.\n"}


def fly_sun_safe_mismatch() -> None:
    """Fly the mismatch table's files again (the 0.3 row is albedo_model_wheels, flown with SUN_SAFE_TABLES)."""
    from detumble.sim import sun_safe_check

    for albedo, results, _ in SUN_SAFE_MISMATCH:
        if results != "sun_safe/albedo_model_wheels.json" and sun_safe_check.main(
                _mismatch_command(albedo, results).split()[3:-1] + [str(STUDIES_DIR / results)]) != 0:
            raise StudyError(f"`{_mismatch_command(albedo, results)}` failed")


_MAG_PLANT_SUMMARY = "magnetorquer pointing: Floquet maps and plant-only checks (committed JSON, ~6 CPU-minutes)"
_MAG_RUNS_SUMMARY = ("magnetorquer pointing: eleven one-orbit adcs_ref runs and their error-vs-time figure (committed "
                     "JSON, ~4 CPU-minutes; the probe re-flies 300 s of one)")
#: magnetic_pointing.md's plant-only tables (campaigns/adcs/magnetic_pointing_tables.py) and single deployment runs
#: (campaigns/adcs/magnetic_pointing_runs.py: one JSON file, two tables)
MAG_POINTING_TABLES = (
    *(ScriptTable("magnetic_pointing", _MAG_PLANT_SUMMARY, f"magnetic_pointing_{key}",
                  "campaigns/adcs/magnetic_pointing_tables.py", f"magnetic_pointing/{key}.json", STUDIES_DIR /
                  "magnetic_pointing.md", tuple(args.split()))
      for key, args in (("floquet", "floquet"), ("checks", "checks"), ("corner_dipole", "corner --field dipole"),
                        ("corner_igrf14", "corner --field igrf14"), ("floquet_convergence", "convergence"))),
    # the gravity-gradient floor: its closed form re-computed by --check (a CPU-second)
    ScriptTable("magnetic_pointing", _MAG_PLANT_SUMMARY, "magnetic_pointing_floor",
                "campaigns/adcs/magnetic_pointing_tables.py", "magnetic_pointing/floor.json",
                STUDIES_DIR / "magnetic_pointing.md", ("floor",), probe="floor_probe"),
    *(ScriptTable("magnetic_pointing_runs", _MAG_RUNS_SUMMARY, f"magnetic_pointing_{start}_runs",
                  "campaigns/adcs/magnetic_pointing_runs.py", "magnetic_pointing/deployment.json",
                  STUDIES_DIR / "magnetic_pointing.md", render=f"{start}_markdown")
      for start in ("tumble", "hold", "corner")),
    # the figures quoted from the error-vs-time figure (drawn from the same JSON file's error series); the probe
    # re-flies the first 300 s of the present defaults' tumble
    ScriptTable("magnetic_pointing_runs", _MAG_RUNS_SUMMARY, "magnetic_pointing_error_figure",
                "campaigns/adcs/magnetic_pointing_runs.py", "magnetic_pointing/deployment.json",
                STUDIES_DIR / "magnetic_pointing.md", render="error_runs_markdown", probe="probe"),
)


#: attitude_knowledge.md's two single-run tables (campaigns/adcs/pointing_single_table.py: one JSON file, 15 runs)
KNOWLEDGE_SINGLE_TABLES = tuple(
    ScriptTable("attitude_knowledge_single_runs", "issue 13's estimator and D-term design, one 400 s adcs_ref run "
                "per row: 15 runs (committed JSON)", f"attitude_knowledge_{part}",
                "campaigns/adcs/pointing_single_table.py",
                "attitude_knowledge/single_runs.json", STUDIES_DIR / "attitude_knowledge.md",
                render=f"{part}_markdown", probe="probe" if part == "design" else "")
    for part in ("design", "sensors"))
#: environment_torques.md's closed-form figures and the magnetorquer hold's bias margin (no flight: a CPU-second)
ENV_CLOSED_FORM_TABLES = tuple(
    ScriptTable("environment_closed_form", "environment torques in closed form and the coil law's Floquet margin to "
                "the magnetometer bias (committed JSON, about 8 CPU-s)", f"environment_torques_{part}",
                "campaigns/adcs/environment_closed_form.py", "environment_torques/closed_form.json",
                STUDIES_DIR / "environment_torques.md", render=f"{part}_markdown",
                probe="probe" if part == "nadir" else "")
    for part in ("nadir", "surfaces", "floquet_bias", "igrf_table"))


#: magnetic_pointing.md's Floquet figure: the maps kept as JSON (campaigns/adcs/magnetic_pointing_figures.py), the
#: figures the page quotes from them rendered into a block, the figure drawn from them by the script's draw_floquet
FLOQUET_MAPS = ScriptTable("magnetic_pointing_floquet_figure", "magnetorquer pointing: the Floquet maps' figure and "
                           "the figures quoted from them (committed JSON, ~60 CPU-s)", "magnetic_pointing_floquet_maps",
                           "campaigns/adcs/magnetic_pointing_figures.py", "magnetic_pointing/floquet_maps.json",
                           STUDIES_DIR / "magnetic_pointing.md", ("floquet",), render="maps_markdown", probe="probe")


def regenerate_floquet_figure(ctx: Context) -> None:
    """The block from the committed maps, and docs/img/magnetic_pointing/floquet.png drawn from them."""
    FLOQUET_MAPS.regenerate(ctx)
    maps = json.loads(FLOQUET_MAPS.path.read_text(encoding="utf-8"))
    with tempfile.TemporaryDirectory() as scratch:
        png = FLOQUET_MAPS.code().draw_floquet(maps, pathlib.Path(scratch))
        ctx.copy(png, IMG_DIR / "magnetic_pointing" / "floquet.png")


def _grouped_study(tables: tuple[ScriptTable, ...]) -> Study:
    """One study of several tables of one script (one JSON file, one page, blocks rendered by their own functions)."""
    doc = tables[0].doc

    def blocks() -> dict[str, str]:
        return {block: body for t in tables for block, body in t.blocks().items()}

    def regenerate(ctx: Context) -> None:
        ctx.set_blocks(doc, blocks())

    def probe() -> list[str]:
        return [p for t in tables for p in t.run_probe()]

    return Study(tables[0].name, tables[0].summary, regenerate, blocks, doc, probe=probe)


def _mag_blocks(name: str) -> dict[str, str]:
    return {block: body for t in MAG_POINTING_TABLES if t.name == name for block, body in t.blocks().items()}


def magnetic_pointing_blocks() -> dict[str, str]:
    return _mag_blocks("magnetic_pointing")


def magnetic_pointing_runs_blocks() -> dict[str, str]:
    return _mag_blocks("magnetic_pointing_runs")


def regenerate_magnetic_pointing(ctx: Context) -> None:
    ctx.set_blocks(STUDIES_DIR / "magnetic_pointing.md", magnetic_pointing_blocks())


def regenerate_magnetic_pointing_runs(ctx: Context) -> None:
    """The runs' blocks, and docs/img/magnetic_pointing/pointing_error_runs.png drawn from their error series."""
    ctx.set_blocks(STUDIES_DIR / "magnetic_pointing.md", magnetic_pointing_runs_blocks())
    table = next(t for t in MAG_POINTING_TABLES if t.name == "magnetic_pointing_runs")
    with tempfile.TemporaryDirectory() as scratch:
        png = table.code().draw_errors(json.loads(table.path.read_text(encoding="utf-8")), pathlib.Path(scratch))
        ctx.copy(png, IMG_DIR / "magnetic_pointing" / "pointing_error_runs.png")


def sun_safe_blocks() -> dict[str, str]:
    blocks = {block: body for t in SUN_SAFE_TABLES for block, body in t.blocks().items()}
    blocks.update(sun_safe_mismatch_block())
    return blocks


def regenerate_sun_safe(ctx: Context) -> None:
    ctx.set_blocks(_SUN_SAFE_DOC, sun_safe_blocks())


# --- magnetic_pointing.md: the 100-run magnetorquer hold campaign, from its committed per-run figures -------------

_MAG_DOC = STUDIES_DIR / "magnetic_pointing.md"
_MAG_RUNS = STUDIES_DIR / "magnetic_pointing_hold" / "runs_2026-12-02.csv"
_MAG_TARGETS = (("pointing_median_deg", 5.0), ("pointing_p95_deg", 15.0))


def _per_run_spread(df, window: str = "after the first 10 % of POINTING") -> list[str]:
    """The per-run spread of a magnetorquer campaign's pointing figures, the runs meeting issue 13's targets (95 %
    Wilson lower bound) and the time above 5° and 15° pooled over the runs (markdown lines)."""
    import numpy as np

    from detumble.analysis.pooled_stats import per_run_share

    ok = df[df["status"] == "ok"]
    lines = [f"| per-run statistic ({window}) | min | median | p95 | max |",
             "|---|---|---|---|---|"]
    for column, label in (("pointing_median_deg", "pointing error median"), ("pointing_p95_deg", "pointing error p95"),
                          ("pointing_max_deg", "pointing error max")):
        v = ok[column].to_numpy(dtype=float)
        cells = [np.min(v), np.median(v), np.percentile(v, 95), np.max(v)]
        lines.append(f"| {label} | " + " | ".join(f"{_fmt(float(c), 2)}°" for c in cells) + " |")
    lines.append("")
    hits = [ok[column] <= bound for column, bound in _MAG_TARGETS]
    for (column, bound), flags in zip(_MAG_TARGETS + (("both", None),), hits + [hits[0] & hits[1]], strict=True):
        share = per_run_share(flags)
        what = "median ≤ 5° and p95 ≤ 15°" if bound is None else f"{column.split('_')[1]} ≤ {bound:g}°"
        lines.append(f"- runs with {what}: **{share.successes} / {share.n}** (95 % Wilson lower bound "
                     f"{100 * share.lower95:.1f} %)")
    window = float(ok["pointing_error_deg.window_s"].sum())
    above = {x: float(ok[f"pointing_error_deg.time_above_s.{x}"].sum()) for x in (5, 15)}
    lines.append(f"- pooled over the runs' {window:,.0f} s of POINTING: time above 5° {100 * above[5] / window:.2f} %, "
                 f"above 15° **{100 * above[15] / window:.2f} %** (exact, from each run's time above)")
    lines.append(f"- {len(ok)} of {len(df)} runs ok; {float(df['cpu_s'].sum()) / 60:,.0f} CPU-minutes in the runs")
    return lines


def magnetic_hold_blocks() -> dict[str, str]:
    """The hold campaign's per-run spread, the runs meeting issue 13's targets (95 % Wilson lower bound) and
    the time above 5° and 15° pooled over the runs, from ``magnetic_pointing_hold/runs_2026-12-02.csv`` (one
    row per run of ``campaigns/adcs/hold_magnetorquers.yaml``; its results folder is not committed)."""
    import pandas as pd

    if not _MAG_RUNS.exists():
        raise StudyError(f"{_shown(_MAG_RUNS)} is not committed")
    lines = _per_run_spread(pd.read_csv(_MAG_RUNS))
    lines += ["", f"Generated by `python tools/studies.py --only magnetic_pointing_hold` from "
              f"`{_MAG_RUNS.relative_to(STUDIES_DIR)}` (numpy's linear percentile over the runs)."]
    return {"magnetic_pointing_hold": "\n".join(lines) + "\n"}


def regenerate_magnetic_hold(ctx: Context) -> None:
    ctx.set_blocks(_MAG_DOC, magnetic_hold_blocks())


def magnetic_tumble_blocks() -> dict[str, str]:
    """Dispersed tumbling starts on the deployment (campaigns/adcs/pointing_magnetorquers.yaml: 0–0.5 °/s about
    random axes from the identity, 45° from the target), from its committed results folder (complete or stopped)."""
    campaign, df = _committed("magnetic_pointing_tumble")
    if df is None:
        return {"magnetic_pointing_tumble": _not_committed(campaign)}
    lines = _per_run_spread(df, "the run summary's window: after the error stays below 30°")
    lines += _tumble_misses_by_rate(df)
    lines += ["", _source("magnetic_pointing_tumble", campaign)]
    return {"magnetic_pointing_tumble": "\n".join(lines) + "\n"}


#: the initial-rate bins (deg/s, lower bound included, upper excluded but the last) of the tumble campaign's misses
_TUMBLE_RATE_BINS = ((0.0, 0.1), (0.1, 0.3), (0.3, 0.5))


def _tumble_misses_by_rate(df) -> list[str]:
    """Which tumbles miss p95 ≤ 15°: the misses' p95 and initial-rate spans, and the runs meeting it per initial-rate
    bin (markdown lines)."""
    ok = df[df["status"] == "ok"]
    rate = ok["scenario.initial.rate.magnitude_deg_s"].astype(float)
    p95 = ok["pointing_p95_deg"].astype(float)
    miss = p95 > _MAG_TARGETS[1][1]
    lines = []
    if miss.any():
        lines.append(f"- the {int(miss.sum())} p95 misses: p95 {_fmt(float(p95[miss].min()), 1)}–"
                     f"{_fmt(float(p95[miss].max()), 1)}°, initial rate {_fmt(float(rate[miss].min()), 2)}–"
                     f"{_fmt(float(rate[miss].max()), 2)} °/s")
    cells = []
    for i, (low, high) in enumerate(_TUMBLE_RATE_BINS):
        last = i == len(_TUMBLE_RATE_BINS) - 1
        inside = (rate >= low) & ((rate <= high) if last else (rate < high))
        cells.append(f"{int((inside & ~miss).sum())}/{int(inside.sum())} at {low:g}–{high:g} °/s")
    lines.append("- runs with p95 ≤ 15° by initial rate: " + ", ".join(cells))
    return lines


def _pooled_lines(df) -> list[str]:
    """The pointing error pooled over the ok runs' windows (time-weighted, from each run's histogram): p50 and p95
    with their histogram brackets (markdown lines; none when the results have no pooling columns)."""
    from detumble.analysis.pooled_stats import POINTING_THRESHOLDS_DEG, pooled_percentile, runs_from_columns

    try:
        runs = runs_from_columns(_ok(df), "pointing_error_deg", POINTING_THRESHOLDS_DEG)
    except KeyError:
        return []
    if not runs:
        return []
    cells = []
    for p in (0.5, 0.95):
        q = pooled_percentile(runs, p)
        cells.append(f"p{100 * p:g} **{q.estimate_deg:.2f}°** (histogram bracket {q.lower_deg:.2f}–{q.upper_deg:.2f}°)")
    return [f"- pooled over the runs (time-weighted, from each run's error histogram): {', '.join(cells)}"]


def magnetic_hold_campaign_blocks() -> dict[str, str]:
    """The 100-run hold (campaigns/adcs/hold_magnetorquers.yaml) flown again with today's code, from its committed
    results folder (complete or stopped: the block says how many runs): per-run spread, targets, pooled figures."""
    campaign, df = _committed("magnetic_pointing_hold_campaign")
    if df is None:
        return {"magnetic_pointing_hold_campaign": _not_committed(campaign)}
    lines = _per_run_spread(df, "the run summary's window: after the error stays below 30°")
    lines[-1:-1] = _pooled_lines(df)
    lines += ["", _source("magnetic_pointing_hold_campaign", campaign)]
    return {"magnetic_pointing_hold_campaign": "\n".join(lines) + "\n"}


def regenerate_magnetic_hold_campaign(ctx: Context) -> None:
    ctx.set_blocks(_MAG_DOC, magnetic_hold_campaign_blocks())


def regenerate_magnetic_tumble(ctx: Context) -> None:
    ctx.set_blocks(_MAG_DOC, magnetic_tumble_blocks())


def magnetic_hold_worst_blocks() -> dict[str, str]:
    """The deployment's worst corner of the hold (campaigns/adcs/hold_magnetorquers_worst.yaml: 10 runs 20° off at
    0.05 °/s), run by run, from its committed results folder."""
    campaign, df = _committed("magnetic_pointing_hold_worst")
    if df is None:
        return {"magnetic_pointing_hold_worst": _not_committed(campaign)}
    from detumble.analysis.pooled_stats import per_run_share

    ok = _ok(df).sort_values("seed") if "seed" in df else _ok(df)
    lines = ["| run | median | p95 | max | final rate (°/s) |", "|---|---|---|---|---|"]
    for i, (_, row) in enumerate(ok.iterrows()):
        lines.append(f"| {i} | {_fmt(_float(row['pointing_median_deg']), 2)}° | "
                     f"{_fmt(_float(row['pointing_p95_deg']), 2)}° | {_fmt(_float(row['pointing_max_deg']), 2)}° | "
                     f"{_fmt(_float(row['final_rate_deg_s']), 4)} |")
    both = (ok["pointing_median_deg"] <= 5.0) & (ok["pointing_p95_deg"] <= 15.0)
    share = per_run_share(both)
    lines += ["", f"- runs with median ≤ 5° and p95 ≤ 15°: **{share.successes} / {share.n}** (95 % Wilson lower bound "
              f"{100 * share.lower95:.1f} %); {len(ok)} of {len(df)} runs ok",
              "", _source("magnetic_pointing_hold_worst", campaign)]
    return {"magnetic_pointing_hold_worst": "\n".join(lines) + "\n"}


def regenerate_magnetic_hold_worst(ctx: Context) -> None:
    ctx.set_blocks(_MAG_DOC, magnetic_hold_worst_blocks())


# --- issue 27's magnetorquer-only hold after acquisition (plant-only campaign) -------------------------------------

_HOLD_DOC = STUDIES_DIR / "magnetorquer_hold_after_acquisition.md"


def hold_after_acquisition_blocks() -> dict[str, str]:
    """The 100-run table of docs/studies/magnetorquer_hold_after_acquisition.md: campaigns/adcs/report_pointing_plant.py
    on the committed results."""
    campaign, df = _committed("magnetorquer_hold_after_acquisition")
    if df is None:
        return {"magnetorquer_hold_campaign": _not_committed(campaign)}
    report = _load_script("campaigns/adcs/report_pointing_plant.py")
    body = report.markdown(report.analyse(df))
    blocks = {"magnetorquer_hold_campaign": body + "\n" + _source("magnetorquer_hold_after_acquisition", campaign)
              + "\n"}
    two, df_two = _committed("magnetorquer_hold_two_orbits")
    blocks["magnetorquer_hold_two_orbits"] = _not_committed(two) if df_two is None else (
        report.paired_markdown(report.paired(df, df_two)) + "\n"
        + _source("magnetorquer_hold_after_acquisition", two) + "\n")
    return blocks


def regenerate_hold_after_acquisition(ctx: Context) -> None:
    ctx.set_blocks(_HOLD_DOC, hold_after_acquisition_blocks())
    for key in ("magnetorquer_hold_after_acquisition", "magnetorquer_hold_two_orbits"):
        if (CAMPAIGNS[key].path / "results.parquet").exists():
            CAMPAIGNS[key].redraw_plots(ctx)


#: issue 27's candidates for a faster fall from 30°: Floquet maps and re-flown draws (campaigns/adcs/...candidates.py)
HOLD_CANDIDATE_TABLES = tuple(
    ScriptTable("magnetorquer_hold_candidates", "issue 27's coil hold: Floquet maps of the candidates and 161 re-flown "
                "plant draws (committed JSON, ~5 CPU-minutes)", f"magnetorquer_hold_candidates_{part}",
                "campaigns/adcs/magnetorquer_hold_candidates.py", "magnetorquer_hold_after_acquisition/candidates.json",
                _HOLD_DOC, render=f"{part}_markdown")
    for part in ("floquet", "draws"))
#: (campaign key, block, how the page names the candidate)
_HOLD_CANDIDATE_CAMPAIGNS = (("magnetorquer_hold_rho_schedule", "magnetorquer_hold_rho_schedule_campaign",
                              "ρ scheduled (4 from 20°)"),
                             ("magnetorquer_hold_no_mag_bias", "magnetorquer_hold_no_mag_bias_campaign",
                              "no magnetometer bias"),
                             ("magnetorquer_hold_field_model_lqr", "magnetorquer_hold_field_model_lqr_campaign",
                              "the hold scheduled on the field model"),
                             ("magnetorquer_hold_field_model_lqr_igrf14",
                              "magnetorquer_hold_field_model_lqr_igrf14_campaign",
                              "IGRF-14 plant, the hold on IGRF-14 of degree 6"),
                             ("magnetorquer_hold_field_model_lqr_below_40",
                              "magnetorquer_hold_field_model_lqr_below_40_campaign",
                              "the scheduled hold below 40°, field steering above"),
                             ("magnetorquer_hold_field_model_lqr_below_40_igrf14",
                              "magnetorquer_hold_field_model_lqr_below_40_igrf14_campaign",
                              "IGRF-14 plant, the hold below 40° on IGRF-14 of degree 6"),
                             ("magnetorquer_hold_field_model_lqr_below_40_igrf14_degree13",
                              "magnetorquer_hold_field_model_lqr_below_40_igrf14_degree13_campaign",
                              "IGRF-14 plant, the hold below 40° on IGRF-14 of degree 13"),
                             ("magnetorquer_hold_field_model_lqr_below_50",
                              "magnetorquer_hold_field_model_lqr_below_50_campaign",
                              "the scheduled hold below 50°, field steering above"),
                             ("magnetorquer_hold_field_model_lqr_below_50_igrf14",
                              "magnetorquer_hold_field_model_lqr_below_50_igrf14_campaign",
                              "IGRF-14 plant, the hold below 50° on IGRF-14 of degree 6"))


def hold_candidate_campaign_blocks() -> dict[str, str]:
    """Each candidate's campaign on the first draws against the committed 100-run campaign's same draws."""
    _, base = _committed("magnetorquer_hold_after_acquisition")
    script = _load_script(HOLD_CANDIDATE_TABLES[0].script)
    blocks = {}
    for key, block, label in _HOLD_CANDIDATE_CAMPAIGNS:
        campaign, df = _committed(key)
        if df is None or base is None:
            blocks[block] = _not_committed(campaign if df is None else CAMPAIGNS["magnetorquer_hold_after_acquisition"])
            continue
        try:
            body = script.campaign_markdown(base, df, label)
        except ValueError as exc:
            raise StudyError(f"{key}: {exc}") from None
        blocks[block] = (body + "\n"
                         + _source("magnetorquer_hold_candidate_campaigns", campaign) + "\n")
    return blocks


def regenerate_hold_candidate_campaigns(ctx: Context) -> None:
    ctx.set_blocks(_HOLD_DOC, hold_candidate_campaign_blocks())


# --- robust_rates.md: the 100-run campaign with the plant's inertia dispersed around the model ------------------

_ROBUST_DOC = STUDIES_DIR / "robust_rates.md"
#: (metric, what the page calls it, unit, digits, goal: at most this)
_ROBUST_METRICS = (("slew_settle_s", "slew settle below 0.1°", "s", 1, 30.0),
                   ("pointing_median_deg", "steady median (after each acquisition below 0.1°)", "deg", 4, 0.01),
                   ("pointing_p95_deg", "steady p95 (after each acquisition below 0.1°)", "deg", 4, 0.05),
                   ("steady_after_slew_median_deg", "steady median (from 60 s after the slew)", "deg", 4, 0.01),
                   ("steady_after_slew_p95_deg", "steady p95 (from 60 s after the slew)", "deg", 4, 0.05))


def _largest_moment_deviation(requested: dict, nominal) -> float:
    """The largest relative deviation of a run's drawn principal moments from the nominal's, each drawn moment
    paired with the nominal principal axis its own axis is nearest (the draw turns the axes by at most 20°)."""
    import numpy as np

    moments, axes = np.linalg.eigh(np.asarray(nominal, dtype=float))
    drawn, drawn_axes = np.linalg.eigh(np.asarray(requested["scenario.spacecraft.inertia_kg_m2"], dtype=float))
    pairing = np.abs(axes.T @ drawn_axes).argmax(axis=1)
    if len(set(pairing.tolist())) != 3:
        raise StudyError("a drawn inertia's principal axes do not pair with the nominal's")
    return float(np.max(np.abs(drawn[pairing] / moments - 1.0)))


def robust_rates_campaign_blocks() -> dict[str, str]:
    """robust_rates.md's campaign table: the per-run figures' spread over the runs and the goals met."""
    return {"robust_rates_campaign": _robust_campaign_table("robust_rates_campaign")}


def _paired_campaigns(key: str, base_key: str, draws: str):
    """Committed campaign ``key`` and ``base_key``'s ``ok`` runs by seed index and the indices of both, or the block
    saying which is not committed; StudyError when they do not fly the same draws (``draws`` names the base's)."""
    campaign, df = _committed(key)
    base, base_df = _committed(base_key)
    if df is None or base_df is None:
        return _not_committed(campaign if df is None else base)
    new, old = _ok(df).set_index("seed_index"), _ok(base_df).set_index("seed_index")
    both = new.index.intersection(old.index)
    if len(both) != len(new) or set(df["seed"]) != set(base_df["seed"]):
        raise StudyError(f"{campaign.folder} does not fly {draws}")
    return new, old, both


def robust_rates_window_campaign_blocks() -> dict[str, str]:
    """robust_rates.md's table of the same draws with INTEGRAL_WINDOW 0.1°, and its run-by-run comparison with the
    ungated 1° campaign (INTEGRAL_RATE_GATE 0, the former default; honest-window p95, settle time, after-slew p95)."""
    key = "robust_rates_window_campaign"
    paired = _paired_campaigns(key, "robust_rates_campaign", "the default campaign's draws")
    if isinstance(paired, str):
        return {key: paired}
    new, old, both = paired
    parts = []
    for metric, label, unit, digits in (("pointing_p95_deg", "the honest-window p95", "°", 4),
                                        ("slew_settle_s", "the settle time", " s", 1),
                                        ("steady_after_slew_p95_deg", "the after-slew p95", "°", 4)):
        change = new.loc[both, metric].astype(float) - old.loc[both, metric].astype(float)
        parts.append(f"{label} is lower in {int((change < 0).sum())} runs and higher in {int((change > 0).sum())} "
                     f"(by at most {max(change.max(), 0.0):.{digits}f}{unit})")
    p95_new, p95_old = new.loc[both, "pointing_p95_deg"], old.loc[both, "pointing_p95_deg"]
    higher = p95_new.index[p95_new > p95_old]
    earlier = new.loc[higher, "slew_settle_s"] < old.loc[higher, "slew_settle_s"]
    compare = (f"Run by run against the ungated campaign above (the same draws): {'; '.join(parts)}; the honest-window "
               f"p95 ≤ 0.05° in {int((p95_old <= 0.05).sum())} → {int((p95_new <= 0.05).sum())} of {len(both)}. Of "
               f"the {len(higher)} runs whose honest-window p95 is higher, {int(earlier.sum())} settle earlier.")
    table = _robust_campaign_table(key)
    return {key: table.replace("\n\nGenerated by", f"\n\n{compare}\n\nGenerated by", 1)}


def robust_rates_gate_campaign_blocks() -> dict[str, str]:
    """robust_rates.md's table of the same draws with the integral's rate gate (INTEGRAL_RATE_GATE 0.05 °/s, window
    1°: the default), and its run-by-run comparison with the ungated 1° campaign (INTEGRAL_RATE_GATE 0) and with the
    0.1° window's (STUDY-120)."""
    key = "robust_rates_gate_campaign"
    campaign, df = _committed(key)
    if df is None:
        return {key: _not_committed(campaign)}
    new = _ok(df).set_index("seed_index")
    sentences = []
    for base_key, name in (("robust_rates_campaign", "the ungated 1° campaign"),
                           ("robust_rates_window_campaign", "the 0.1° window's")):
        base, base_df = _committed(base_key)
        if base_df is None:
            return {key: _not_committed(base)}
        old = _ok(base_df).set_index("seed_index")
        both = new.index.intersection(old.index)
        if len(both) != len(new) or set(df["seed"]) != set(base_df["seed"]):
            raise StudyError(f"robust_rates/campaign_gate does not fly the draws of {base.folder}")
        change = new.loc[both, "pointing_p95_deg"].astype(float) - old.loc[both, "pointing_p95_deg"].astype(float)
        settle = new.loc[both, "slew_settle_s"].astype(float) - old.loc[both, "slew_settle_s"].astype(float)
        counts = " → ".join(str(int((frame.loc[both, "pointing_p95_deg"] <= 0.05).sum())) for frame in (old, new))
        sentences.append(f"against {name} (the same draws) the honest-window p95 is lower in "
                         f"{int((change < 0).sum())} runs, equal in {int((change == 0).sum())} and higher in "
                         f"{int((change > 0).sum())} (by at most {max(change.max(), 0.0):.4f}°), the settle time "
                         f"later in {int((settle > 0).sum())} (by at most {max(settle.max(), 0.0):.1f} s); "
                         f"p95 ≤ 0.05° in {counts} of {len(both)}")
    compare = "Run by run: " + "; ".join(sentences) + "."
    table = _robust_campaign_table(key)
    return {key: table.replace("\n\nGenerated by", f"\n\n{compare}\n\nGenerated by", 1)}


def robust_rates_dipole_campaign_blocks() -> dict[str, str]:
    """robust_rates.md's table of the same draws with the rate observer's residual-dipole estimate
    (RATE_OBSERVER_DIPOLE_TIME 20 s, the default since issue 27, and the default gate), and its run-by-run comparison
    with the gate campaign (the default before the estimate: it pins RATE_OBSERVER_DIPOLE_TIME 0): the honest-window
    p95 and median, the after-slew p95, the runs the gate campaign misses (STUDY-170)."""
    key = "robust_rates_dipole_campaign"
    paired = _paired_campaigns(key, "robust_rates_gate_campaign", "the draws of robust_rates/campaign_gate")
    if isinstance(paired, str):
        return {key: paired}
    new, old, both = paired
    p95_old, p95_new = old["pointing_p95_deg"].astype(float), new["pointing_p95_deg"].astype(float)
    missed = old.index[p95_old > 0.05]
    parts = []
    for metric, label, goal in (("pointing_p95_deg", "the honest-window p95", 0.05),
                                ("pointing_median_deg", "the honest-window median", 0.01),
                                ("steady_after_slew_p95_deg", "the after-slew p95", 0.05)):
        a, b = old.loc[both, metric].astype(float), new.loc[both, metric].astype(float)
        change = b - a
        parts.append(f"{label} is lower in {int((change < 0).sum())} runs, equal in {int((change == 0).sum())} and "
                     f"higher in {int((change > 0).sum())} (by at most {max(change.max(), 0.0):.4f}°; ≤ {goal:g}° in "
                     f"{int((a <= goal).sum())} → {int((b <= goal).sum())} of {len(both)})")
    cells = ", ".join(f"{i}: {p95_old[i]:.4f}° → {p95_new[i]:.4f}°" for i in missed)
    compare = (f"Run by run against the gate campaign (the default before the estimate, the same draws): "
               f"{'; '.join(parts)}. The runs the gate campaign misses (seed index: honest-window p95): "
               f"{cells or 'none'}.")
    table = _robust_campaign_table(key)
    return {key: table.replace("\n\nGenerated by", f"\n\n{compare}\n\nGenerated by", 1)}


def _robust_campaign_table(key: str) -> str:
    """The committed campaign ``key``'s table (robust_rates.md): the drawn inertias, then each metric's spread."""
    import numpy as np

    campaign, df = _committed(key)
    if df is None:
        return _not_committed(campaign)
    ok = _ok(df)
    import yaml

    manifest = json.loads((campaign.path / "manifest.json").read_text(encoding="utf-8"))
    nominal = yaml.safe_load(manifest["campaign_text"])["dispersions"]["scenario.spacecraft.inertia_kg_m2"]["nominal"]
    deviation = 100.0 * np.array([_largest_moment_deviation(json.loads(r), nominal) for r in ok["requested"]])
    lines = [f"{len(df)} runs, {len(ok)} `ok`. The largest principal-moment deviation of a run's drawn inertia from "
             f"the model's: median {np.median(deviation):.1f} %, max {deviation.max():.1f} %, "
             f"{int((deviation > 10.0).sum())} runs beyond 10 %. Per-run figures, then their spread over the `ok` "
             "runs (p95: linear interpolation between order statistics):", "",
             "| per run | min | median | p95 | max | goal met |", "|---|---|---|---|---|---|"]
    for metric, label, unit, digits, goal in _ROBUST_METRICS:
        values = ok[metric].astype(float).dropna().to_numpy()
        met = int((values <= goal).sum())
        mark = "**" if met == len(ok) else ""
        lines.append(f"| {label} ({unit}) | {values.min():.{digits}f} | {np.median(values):.{digits}f} | "
                     f"{np.percentile(values, 95):.{digits}f} | {values.max():.{digits}f} | "
                     f"≤ {goal:g}{' s' if unit == 's' else '°'}: {mark}{met}/{len(ok)}{mark} |")
    return "\n".join(lines) + "\n\n" + _source(key, campaign) + "\n"


def regenerate_robust_rates_campaign(ctx: Context) -> None:
    ctx.set_blocks(_ROBUST_DOC, robust_rates_campaign_blocks())
    if (CAMPAIGNS["robust_rates_campaign"].path / "results.parquet").exists():
        CAMPAIGNS["robust_rates_campaign"].redraw_plots(ctx)


def regenerate_robust_rates_window_campaign(ctx: Context) -> None:
    ctx.set_blocks(_ROBUST_DOC, robust_rates_window_campaign_blocks())
    if (CAMPAIGNS["robust_rates_window_campaign"].path / "results.parquet").exists():
        CAMPAIGNS["robust_rates_window_campaign"].redraw_plots(ctx)


def regenerate_robust_rates_gate_campaign(ctx: Context) -> None:
    ctx.set_blocks(_ROBUST_DOC, robust_rates_gate_campaign_blocks())
    if (CAMPAIGNS["robust_rates_gate_campaign"].path / "results.parquet").exists():
        CAMPAIGNS["robust_rates_gate_campaign"].redraw_plots(ctx)


def regenerate_robust_rates_dipole_campaign(ctx: Context) -> None:
    ctx.set_blocks(_ROBUST_DOC, robust_rates_dipole_campaign_blocks())
    if (CAMPAIGNS["robust_rates_dipole_campaign"].path / "results.parquet").exists():
        CAMPAIGNS["robust_rates_dipole_campaign"].redraw_plots(ctx)


# --- flights: the README's figures and the attitude-modes study ------------------------------------------------


def _fly(ctx: Context, topology: pathlib.Path, duration_s: float, name: str, *, seq: str | None = None,
         sets: dict | None = None):
    """One deployment run with its plots (the project's own plotters), as ``fprime-lite run`` flies it,
    into ``runs/studies/NAME`` (quick: under ``--out``). With ``--reuse-runs`` a finished run of the same
    request there is used again (a long regeneration can then be resumed after an interruption)."""
    from fprime_lite.tools import open_run, run

    out = ctx.runs / name
    request = {"topology": str(topology.relative_to(ROOT)), "duration_s": duration_s, "seq": seq, "sets": sets or {}}
    stamp = ctx.runs / f"{name}.request.json"
    if ctx.reuse and (out / "summary.json").exists() and stamp.exists() and json.loads(stamp.read_text()) == request:
        return open_run(out)
    shutil.rmtree(out, ignore_errors=True)
    stamp.unlink(missing_ok=True)
    out.parent.mkdir(parents=True, exist_ok=True)
    sequence = None
    if seq is not None:
        sequence = ctx.runs / f"{name}.seq"
        sequence.write_text(seq, encoding="utf-8")
    result = run(topology, duration_s=duration_s, out=out, plots=True, seq=sequence,
                 settings=[f"{key}={value}" for key, value in (sets or {}).items()])
    stamp.write_text(json.dumps(request), encoding="utf-8")
    return result


def regenerate_readme_figures(ctx: Context) -> None:
    """docs/img/reference_run_<kind>.png: one full detumble of the reference deployment (3100 s)."""
    result = _fly(ctx, ROOT / "deployments" / "proves_ref" / "topology.yaml", 300.0 if ctx.quick else 3100.0,
                  "readme_reference_run")
    for png in sorted(result.out_dir.glob("*.png")):
        ctx.copy(png, IMG_DIR / f"reference_run_{png.name}")


_ATTITUDE_DOC = STUDIES_DIR / "attitude_modes.md"
_C = "ReferenceDeployment.attitudeController"
_MAJOR = "[[2.05e-3,2.0e-5,-1.5e-5],[2.0e-5,2.15e-3,1.0e-5],[-1.5e-5,1.0e-5,2.40e-3]]"
_SPIN_RUNS = (
    # (law, inertia label, extra --set)
    ("RATE_REGULATOR (default)", "default, ẑ minor", "RATE_REGULATOR", {}),
    ("RATE_REGULATOR", "ẑ major (I_zz 2.40e-3)", "RATE_REGULATOR", {"spacecraft.inertia_kg_m2": _MAJOR}),
    ("SEED_KANE_DAMPER (seed 003 as written)", "default", "SEED_KANE_DAMPER", {}),
    ("VIRTUAL_DAMPER (classical 3-axis)", "default", "VIRTUAL_DAMPER", {}),
)


def _spin_row(summary: dict, csv_path: pathlib.Path) -> tuple[str, str, str]:
    """(settled, at the end: momentum to +Z and rate about +Z, SPIN_STABLE spin-axis error median / p95),
    from the run's ``summary.json`` and the last row of its ``attitude.csv``."""
    import pandas as pd

    settled = summary.get("spin_settled_s")
    last = pd.read_csv(csv_path).iloc[-1]
    axis, about_z, rate = (float(last[c]) for c in ("spin_axis_error_deg", "spin_rate_deg_s", "rate_deg_s"))
    end = f"{axis:.2f}°, {about_z:.3f} °/s about +Z"
    if abs(about_z) < 0.9 * rate:
        end += f" (\\|ω\\| {rate:.2f} °/s)"
    stats = summary.get("spin_axis_error_deg") or {}
    return (_fmt(settled) + " s" if settled is not None else "never", end,
            f"{_fmt(stats.get('median'), 2)}° / {_fmt(stats.get('p95'), 2)}°")


_ADCS = ROOT / "deployments" / "adcs_ref" / "topology.yaml"


def attitude_modes_magnetorquer_blocks() -> dict[str, str]:
    """attitude_modes.md's magnetorquer table: the single runs of magnetic_pointing/deployment.json and the hold
    campaign's per-run figures (magnetic_pointing_hold/runs_2026-12-02.csv)."""
    import pandas as pd

    from detumble.analysis.pooled_stats import per_run_share

    runs_table = next(t for t in MAG_POINTING_TABLES if t.name == "magnetic_pointing_runs")
    if not runs_table.path.exists():
        raise StudyError(f"{_shown(runs_table.path)} is not committed: make it with `{runs_table.command}`")
    if not _MAG_RUNS.exists():
        raise StudyError(f"{_shown(_MAG_RUNS)} is not committed")
    runs = json.loads(runs_table.path.read_text(encoding="utf-8"))["runs"]

    def stats(name: str) -> str:
        r = runs.get(name)
        return "not flown" if r is None else f"{_fmt(r['median_deg'], 2)}° / {_fmt(r['p95_deg'], 2)}°"

    df = pd.read_csv(_MAG_RUNS)
    ok = df[df["status"] == "ok"]
    med, p95 = (per_run_share(ok[c] <= b) for c, b in _MAG_TARGETS)
    above = 100 * float(ok["pointing_error_deg.time_above_s.15"].sum()) / float(ok["pointing_error_deg.window_s"].sum())
    rows = ["| figure | value | target |", "|---|---|---|",
            f"| attitude hold (at rest on the target, POINTING at 5 s), median / p95 | **{stats('hold')}** "
            f"(first-pass parameters: {stats('hold_first')}) | median ≤ 5°, p95 ≤ 15° |",
            f"| hold campaign, {med.n} runs 0–20° off at 0–0.05 °/s (tilted dipole, 2026-12-02) | per run: median ≤ 5° "
            f"in **{med.successes}/{med.n}**, p95 ≤ 15° in **{p95.successes}/{p95.n}**; time above 15°: "
            f"{above:.2f} % | median ≤ 5°, p95 ≤ 15° |",
            f"| from a 0.5 °/s tumble (`mag.seq` above), median / p95 | **{stats('tumble')}** (first-pass "
            f"parameters: {stats('tumble_first')}; seed 003's projected PD {stats('tumble_seed_pd')}) | "
            "median ≤ 5°, p95 ≤ 15° |",
            "", "Generated by `python tools/studies.py --only attitude_modes_magnetorquers` from "
            f"`docs/studies/{runs_table.results}` (made by `{runs_table.command}`; statistics over POINTING after "
            "its first 10 %, the present defaults in IGRF-14 with field steering on the raw reading pinned: "
            f"MAG_BIAS_TIME 0, MAG_LQR_ANGLE 0) and `{_MAG_RUNS.relative_to(STUDIES_DIR)}`."]
    return {"attitude_modes_magnetorquers": "\n".join(rows) + "\n"}


def regenerate_attitude_modes_magnetorquers(ctx: Context) -> None:
    ctx.set_blocks(_ATTITUDE_DOC, attitude_modes_magnetorquer_blocks())


def regenerate_attitude_modes_spin(ctx: Context) -> None:
    """The spin table of docs/studies/attitude_modes.md: one orbit per law from a 1 °/s tumble."""
    topology = _ADCS
    orbit = 300.0 if ctx.quick else 5580.0
    rows = ["| law | inertia | settled (5°, 5 %) | at the end of the orbit: momentum to +Z, rate | SPIN_STABLE "
            "spin-axis error median / p95 |", "|---|---|---|---|---|"]
    for i, (law, inertia, member, sets) in enumerate(_SPIN_RUNS):
        seq = f"R00:00:00 {_C}.SPIN_LAW_PRM_SET {member}\nR00:00:00 {_C}.FORCE_MODE SPIN_STABLE\n"
        result = _fly(ctx, topology, orbit, f"attitude_modes_spin{i}", seq=seq,
                      sets={"initial.rate.magnitude_deg_s": "1.0", **sets})
        summary = json.loads((result.out_dir / "summary.json").read_text(encoding="utf-8"))
        settled, end, stats = _spin_row(summary, result.out_dir / "attitude.csv")
        rows.append(f"| {law} | {inertia} | **{settled}** | {end} | {stats} |")
    rows += ["", f"Generated by `python tools/studies.py --only attitude_modes_spin` ({orbit:g} s each): "
             "`fprime-lite run deployments/adcs_ref/topology.yaml --duration 5580 --seq spin.seq --set "
             "initial.rate.magnitude_deg_s=1.0` with spin.seq as above (and the --set of the major axis)."]
    ctx.set_blocks(_ATTITUDE_DOC, {"attitude_modes_spin": "\n".join(rows) + "\n"})


#: attitude_modes.md's shipped-sequence and wheel-orbit tables and figures: one JSON file of two adcs_ref flights
#: (campaigns/adcs/attitude_modes_runs.py) and their traces beside it; each flight's first 30 s re-flown by --check
ATTITUDE_RUNS_TABLES = tuple(
    ScriptTable(name, summary, block, "campaigns/adcs/attitude_modes_runs.py", "attitude_modes/runs.json",
                _ATTITUDE_DOC, render=f"{flight}_markdown", probe=f"{flight}_probe")
    for name, summary, block, flight in (
        ("attitude_modes_pointing", "seed 003's whole sequence as shipped: its table and figures (committed JSON and "
         "trace of one 6000 s run)", "attitude_modes_shipped", "shipped"),
        ("attitude_modes_orbit", "seed 003's pointing on the wheels for one orbit: table and figures (committed JSON "
         "and trace of one run)", "attitude_modes_orbit", "orbit")))
#: each flight's figures the page shows: (file the script draws, its name under docs/img/attitude_modes/)
_ATTITUDE_FIGURES = {"shipped": (("attitude_mode", "attitude_mode"), ("pointing_error", "pointing_error"),
                                 ("wheel_momentum", "wheel_momentum"), ("dipole", "dipole")),
                     "orbit": (("pointing_error", "pointing_error_orbit"), ("wheel_momentum", "wheel_momentum_orbit"))}


def _attitude_runs_regenerate(table: ScriptTable, flight: str):
    def regenerate(ctx: Context) -> None:
        """The block from the committed JSON file, and the flight's figures drawn from it and its trace."""
        table.regenerate(ctx)
        committed = json.loads(table.path.read_text(encoding="utf-8"))
        with tempfile.TemporaryDirectory() as scratch:
            drawn = {p.stem: p for p in table.code().draw(committed, table.path, flight, pathlib.Path(scratch))}
            for stem, name in _ATTITUDE_FIGURES[flight]:
                ctx.copy(drawn[stem], IMG_DIR / "attitude_modes" / f"{name}.png")
    return regenerate


STUDIES = {s.name: s for s in (
    Study("coursework_convergence", "seed 004: every plant figure against the step (committed campaign)",
          regenerate_convergence, convergence_blocks, _CONVERGENCE_DOC,
          ("coursework_convergence", *_CONVERGENCE_CONTINUED)),
    Study("coursework_settling_ripple", "seed 004: the listing β-PD's ripple at its settling instant (committed "
          "plant runs)", regenerate_ripple, ripple_blocks, _CONVERGENCE_DOC),
    Study("coursework_grids", "seed 004: the gain sweeps and the noise study (committed campaigns)",
          regenerate_grids, grid_blocks, _CONVERGENCE_DOC,
          ("coursework_cross_product_sweep", "coursework_beta_pd_grid", "coursework_wheels_pd_grid",
           "coursework_noise", "coursework_beta_pd_grid_listing")),
    Study("coursework_replica_magnetorquer1", "seed 004: magnetorquer1 in the report's own model (committed RK45 runs)",
          regenerate_magnetorquer1, magnetorquer1_blocks, _CONVERGENCE_DOC),
    Study("coursework_replica", "seed 004: the report's own model under SciPy's RK45 (committed RK45 runs)",
          regenerate_replica, replica_blocks, _CONVERGENCE_DOC),
    Study("coursework_summary", "seed 004: the report, its model and the plant side by side, and the β-PD's "
          "per-axis pattern (committed RK45 runs and campaigns)", regenerate_coursework_summary,
          coursework_summary_blocks, _CONVERGENCE_DOC, ("coursework_convergence", *_CONVERGENCE_CONTINUED)),
    Study("coursework_real_wheel", "seed 004's tumble under a real 1U wheel with dumping, beside the magnetic laws "
          "(committed JSON of one orbit and the convergence campaigns)", regenerate_real_wheel, real_wheel_blocks,
          _CONVERGENCE_DOC),
    Study("spin_stabilisation_campaign", "issue 13's spin target over 2 × 100 deployment runs (committed campaigns)",
          regenerate_spin_campaign, spin_campaign_blocks, _SPIN_DOC, ("spin_minor_axis", "spin_major_axis")),
    Study("attitude_knowledge", "issue 13's pointing on the wheels over 100 deployment runs (committed campaign)",
          regenerate_knowledge, knowledge_blocks, _KNOWLEDGE_DOC, ("attitude_knowledge",)),
    Study("attitude_knowledge_verdict", "issue 13's targets: the verdict from the 100-run campaign and the orbit runs "
          "(committed campaign and JSON)", regenerate_knowledge_verdict, knowledge_verdict_blocks, _KNOWLEDGE_DOC),
    Study("flight_detumble_campaign", "the PROVES flight detumble configurations (two committed campaigns)",
          regenerate_flight, flight_blocks, _FLIGHT_DOC, ("flight_detumble_campaign", "flight_detumble_campaign_p95")),
    Study("gain_sweep", "the flight B-dot and BDotDetumble against their gains (committed campaign)",
          regenerate_gain_sweep, gain_sweep_blocks, _GAIN_DOC, ("gain_sweep",)),
    Study("flight_bdot_noise", "the flight B-dot and BDotDetumble against magnetometer noise (committed campaign)",
          regenerate_noise, noise_blocks, _NOISE_DOC, ("flight_bdot_noise",)),
    Study("performance_detumble", "docs/performance.md's timed detumble among the campaigns' draws (committed "
          "campaigns)", regenerate_performance_detumble, performance_detumble_blocks, _PERF_DOC),
    *(t.study() for t in SCRIPT_TABLES.values()),
    Study("sun_safe", _SUN_SAFE_SUMMARY, regenerate_sun_safe, sun_safe_blocks, _SUN_SAFE_DOC,
          probe=lambda: [p for t in SUN_SAFE_TABLES for p in t.run_probe()]),
    Study("robust_rates_campaign", "issue 27's slew with the plant's inertia dispersed: 100 plant runs (committed "
          "campaign)", regenerate_robust_rates_campaign, robust_rates_campaign_blocks, _ROBUST_DOC,
          ("robust_rates_campaign",)),
    Study("robust_rates_window_campaign", "issue 27's slew, the same 100 draws with the integral's window at 0.1° "
          "(committed campaign)", regenerate_robust_rates_window_campaign, robust_rates_window_campaign_blocks,
          _ROBUST_DOC, ("robust_rates_window_campaign",)),
    Study("robust_rates_gate_campaign", "issue 27's slew, the same 100 draws with the integral's rate gate at "
          "0.05 °/s (committed campaign)", regenerate_robust_rates_gate_campaign, robust_rates_gate_campaign_blocks,
          _ROBUST_DOC, ("robust_rates_gate_campaign",)),
    Study("robust_rates_dipole_campaign", "issue 27's slew, the same 100 draws with the rate observer's "
          "residual-dipole estimate (committed campaign)", regenerate_robust_rates_dipole_campaign,
          robust_rates_dipole_campaign_blocks, _ROBUST_DOC, ("robust_rates_dipole_campaign",)),
    Study("magnetic_pointing", _MAG_PLANT_SUMMARY, regenerate_magnetic_pointing, magnetic_pointing_blocks,
          STUDIES_DIR / "magnetic_pointing.md",
          probe=lambda: [p for t in MAG_POINTING_TABLES if t.name == "magnetic_pointing" for p in t.run_probe()]),
    _grouped_study(KNOWLEDGE_SINGLE_TABLES),
    Study(FLOQUET_MAPS.name, FLOQUET_MAPS.summary, regenerate_floquet_figure, FLOQUET_MAPS.blocks, FLOQUET_MAPS.doc,
          probe=FLOQUET_MAPS.run_probe),
    _grouped_study(ENV_CLOSED_FORM_TABLES),
    Study("magnetic_pointing_runs", _MAG_RUNS_SUMMARY, regenerate_magnetic_pointing_runs,
          magnetic_pointing_runs_blocks, STUDIES_DIR / "magnetic_pointing.md",
          probe=lambda: [p for t in MAG_POINTING_TABLES if t.name == "magnetic_pointing_runs" for p in t.run_probe()]),
    Study("magnetic_pointing_hold_worst", "magnetorquer-only hold at its worst corner: 10 deployment runs "
          "(committed campaign)", regenerate_magnetic_hold_worst, magnetic_hold_worst_blocks, _MAG_DOC,
          ("magnetic_pointing_hold_worst",)),
    Study("magnetic_pointing_tumble", "magnetorquer-only pointing from dispersed tumbles: up to 100 deployment runs "
          "(committed campaign)", regenerate_magnetic_tumble, magnetic_tumble_blocks, _MAG_DOC,
          ("magnetic_pointing_tumble",)),
    Study("magnetic_pointing_hold_campaign", "magnetorquer-only hold, 100 deployment runs flown again with today's "
          "code (committed campaign; the block says how many were flown)", regenerate_magnetic_hold_campaign,
          magnetic_hold_campaign_blocks, _MAG_DOC, ("magnetic_pointing_hold_campaign",)),
    Study("magnetic_pointing_hold", "magnetorquer-only hold over 100 deployment runs (committed per-run table)",
          regenerate_magnetic_hold, magnetic_hold_blocks, _MAG_DOC),
    _grouped_study(HOLD_CANDIDATE_TABLES),
    Study("magnetorquer_hold_candidate_campaigns", "issue 27's coil hold: the candidates on the campaign's first 100 "
          "and 10 draws (committed campaigns)", regenerate_hold_candidate_campaigns, hold_candidate_campaign_blocks,
          _HOLD_DOC, tuple(key for key, _, _ in _HOLD_CANDIDATE_CAMPAIGNS)),
    Study("magnetorquer_hold_after_acquisition", "issue 27's coil-only hold after acquisition over 100 plant runs "
          "(committed campaign)", regenerate_hold_after_acquisition, hold_after_acquisition_blocks, _HOLD_DOC,
          ("magnetorquer_hold_after_acquisition", "magnetorquer_hold_two_orbits")),
    Study("attitude_modes_spin", "seed 003's spin stabilisation: one orbit per law (four deployment runs)",
          regenerate_attitude_modes_spin, None, _ATTITUDE_DOC),
    *(Study(t.name, t.summary, _attitude_runs_regenerate(t, flight), t.blocks, t.doc, probe=t.run_probe)
      for t, flight in zip(ATTITUDE_RUNS_TABLES, ("shipped", "orbit"), strict=True)),
    Study("attitude_modes_magnetorquers", "seed 003's magnetorquer-only pointing: the page's table (committed JSON "
          "and per-run CSV)", regenerate_attitude_modes_magnetorquers, attitude_modes_magnetorquer_blocks,
          _ATTITUDE_DOC),
    Study("readme_figures", "the README's figures: one detumble of the reference deployment (3100 s)",
          regenerate_readme_figures, None, None),
)}


# ------------------------------------------------------------------------------------------------ commands


def _shown(path: pathlib.Path) -> str:
    return str(path.relative_to(ROOT)) if path.is_relative_to(ROOT) else str(path)


def check(names: list[str], *, fly_probes: bool = True) -> list[str]:
    """Every way the docs and the committed results of ``names`` may be stale (empty: none)."""
    problems = []
    for name in names:
        study = STUDIES[name]
        if study.blocks is not None and study.doc is not None:
            try:
                expected = study.blocks()
            except StudyError as exc:
                problems.append(f"{name}: {exc}")
                continue
            present = doc_blocks(study.doc.read_text(encoding="utf-8"))
            for block, body in expected.items():
                if block not in present:
                    problems.append(f"{_shown(study.doc)}: no block '{block}'")
                elif present[block].rstrip("\n") != body.rstrip("\n"):
                    problems.append(f"{_shown(study.doc)}: block '{block}' is not what the committed "
                                    f"results give: run `python tools/studies.py --only {name}`")
        if fly_probes and study.probe is not None:
            try:
                problems += study.probe()
            except StudyError as exc:
                problems.append(f"{name}: {exc}")
        for key in study.campaigns:
            try:
                problems += CAMPAIGNS[key].problems(fly_probes=fly_probes)
            except StudyError as exc:
                problems.append(f"{name}: {exc}")
    return problems


def unknown_resolutions(names: list[str]) -> list[str]:
    """Notes for the committed campaign folders of ``names`` whose manifests record no resolved
    configuration (reported by ``--check``, not counted stale)."""
    keys = dict.fromkeys(key for name in names for key in STUDIES[name].campaigns)
    return [note for key in keys if (note := CAMPAIGNS[key].resolution_unknown()) is not None]


def confirm_resolutions(folders: list[str]) -> int:
    """``--confirm-resolution``: :meth:`CommittedCampaign.confirm_resolution` for each named folder."""
    by_folder = {c.folder: c for c in CAMPAIGNS.values()}
    _code_revision()  # the tree as it is before any manifest changes
    failed = 0
    for name in folders:
        campaign = CAMPAIGNS.get(name) or by_folder.get(name.removeprefix("docs/studies/").rstrip("/"))
        if campaign is None:
            print(f"studies: {name}: no committed campaign of that folder or key; known folders: "
                  f"{', '.join(sorted(by_folder))}", file=sys.stderr)
            return 2
        problems = campaign.confirm_resolution()
        for problem in problems:
            print(f"NOT CONFIRMED: {problem}")
        print(f"docs/studies/{campaign.folder}: " + ("not confirmed: re-fly it" if problems else "agrees"))
        failed += bool(problems)
    return 1 if failed else 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", nargs="+", metavar="NAME", help="these studies only (--list names them)")
    ap.add_argument("--quick", action="store_true", help="each study's short version, written under --out")
    ap.add_argument("--out", type=pathlib.Path, help="where --quick writes (default runs/studies-quick)")
    ap.add_argument("--check", action="store_true", help="write nothing; report what is stale (exit 1 if any)")
    ap.add_argument("--no-probes", action="store_true", help="with --check: do not re-fly the probe runs")
    ap.add_argument("--rerun-campaigns", action="store_true",
                    help="run the studies' campaigns first (one worker, resuming the committed folders: hours)")
    ap.add_argument("--reuse-runs", action="store_true",
                    help="use again a finished flight of the same request in runs/studies/ (resume a long run)")
    ap.add_argument("--list", action="store_true", help="name every study and stop")
    ap.add_argument("--confirm-resolution", nargs="+", metavar="FOLDER",
                    help="committed campaign folders (under docs/studies/, or their study's campaign key) whose "
                         "resolved configuration changed or is unknown: fly their probe runs (else the first run; "
                         "when unknown, also the last and the cheapest of each configuration) again and, if "
                         "every metric agrees to the float, record today's configuration in their manifest")
    args = ap.parse_args(argv)
    if args.confirm_resolution:
        return confirm_resolutions(args.confirm_resolution)
    if args.list:
        for study in STUDIES.values():
            print(f"{study.name:30s} {study.summary}")
        return 0
    names = args.only or list(STUDIES)
    unknown = [n for n in names if n not in STUDIES]
    if unknown:
        import difflib

        hints = [f"{n} (did you mean {', '.join(difflib.get_close_matches(n, STUDIES, 1)) or 'one of --list'}?)"
                 for n in unknown]
        print(f"studies: unknown study {'; '.join(hints)}; known: {', '.join(STUDIES)}", file=sys.stderr)
        return 2
    if args.check:
        problems = check(names, fly_probes=not args.no_probes)
        for note in unknown_resolutions(names):
            print(f"UNKNOWN: {note}")
        for p in problems:
            print(f"STALE: {p}")
        print("nothing stale" if not problems else f"{len(problems)} stale item(s)")
        return 1 if problems else 0
    if args.out is not None and not args.quick:
        print("studies: --out is where --quick writes; without --quick the studies write into the docs",
              file=sys.stderr)
        return 2
    ctx = Context(quick=args.quick, out=(args.out or ROOT / "runs" / "studies-quick") if args.quick else None,
                  reuse=args.reuse_runs)
    failed = []
    for name in names:
        study = STUDIES[name]
        if args.rerun_campaigns:
            for key in study.campaigns:
                CAMPAIGNS[key].rerun()
            if name == "coursework_replica_magnetorquer1":
                fly_magnetorquer1()
            if name == "coursework_replica":
                fly_replica()
            if name == "coursework_real_wheel":
                fly_real_wheel()
            if name == "coursework_settling_ripple":
                fly_ripple()
            if name == "sun_safe":
                fly_sun_safe_mismatch()
            flown = set()
            for table in (*SUN_SAFE_TABLES, *SCRIPT_TABLES.values(), *MAG_POINTING_TABLES, *KNOWLEDGE_SINGLE_TABLES,
                          *ENV_CLOSED_FORM_TABLES, FLOQUET_MAPS, *ATTITUDE_RUNS_TABLES,
                          *HOLD_CANDIDATE_TABLES):
                if table.name == name and table.command not in flown:  # two tables may share one JSON file
                    table.fly()
                    flown.add(table.command)
        print(f"{name}: {study.summary}", flush=True)
        try:
            before = len(ctx.written)
            study.regenerate(ctx)
            for path in ctx.written[before:]:
                print(f"  wrote {path}")
        except StudyError as exc:
            failed.append(name)
            print(f"  not regenerated: {exc}", file=sys.stderr)
    if failed:
        print(f"studies: {len(failed)} not regenerated: {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
