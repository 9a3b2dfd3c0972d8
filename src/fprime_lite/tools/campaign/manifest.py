"""``manifest.json``: what produced a campaign folder.

- the campaign file (text, SHA-256) and the SHA-256 of every input file it names (topology,
  parameter file, sequence, scenario file: any run-section or grid value that is a file);
- the software: the git commit of the installed fprime-lite source and whether its working tree
  had uncommitted changes (``dirty``), and the package versions — on the client and on each worker;
- the machines: host, CPU model and count, platform, of the client and of each worker;
- ``resolved``: what the runs resolve their configuration from beyond the named files (the run
  kind's ``fingerprint``: a topology's default scenario, a digest of its values and its field model),
  one entry per distinct thing resolved (:func:`resolved_configuration`);
- ``history``: one entry per session (the first run and each ``--resume``): start, end, status,
  cluster, workers, how many rows it started with and how many failed runs it retried. The top-level
  ``started`` is the first session's, ``ended``, ``status`` and ``cluster`` the latest's.
- a session ended by SIGINT/SIGTERM: ``status: "interrupted"`` and ``interrupted``: the signal, the
  rows recorded (``done``) and the runs planned (``planned``);
- a session ended by an error (a scheduler with no workers, a broken cluster): ``status: "failed"``
  and ``error``: its message.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import os
import pathlib
import platform
import socket
import subprocess
from typing import Any

from fprime_lite.model.errors import FprimeLiteError
from fprime_lite.osal.atomic import atomic_write_text

__all__ = ["ManifestWriter", "package_versions", "machine", "software", "input_files", "read_manifest", "now_utc",
           "resolved_configuration"]

PACKAGES = ("fprime-lite", "numpy", "dask", "distributed", "pandas", "pyarrow", "pyyaml", "matplotlib")


def package_versions() -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for name in PACKAGES:
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = "not installed"
    return out


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine() -> dict:
    """This machine: host, CPU model, logical CPUs, platform."""
    return {"host": socket.gethostname(), "cpu": _cpu_model(), "cpus": os.cpu_count(),
            "platform": platform.platform()}


def _git(folder: pathlib.Path, *args: str) -> str | None:
    try:
        r = subprocess.run(["git", "-C", str(folder), *args], capture_output=True, text=True, timeout=5)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return r.stdout.strip() if r.returncode == 0 else None


def git_state(folder: pathlib.Path, ignore: tuple[str, ...] = ()) -> dict | None:
    """``{"commit", "dirty"}`` of the git work tree holding ``folder``; None outside one. ``ignore``:
    paths (relative to ``folder``) whose uncommitted changes do not make it dirty."""
    commit = _git(folder, "rev-parse", "HEAD")
    if commit is None:
        return None
    excluded = ("--", ".", *(f":!{path}" for path in ignore)) if ignore else ()
    status = _git(folder, "status", "--porcelain", "--untracked-files=no", *excluded)
    return {"commit": commit, "dirty": bool(status)}


def software() -> dict:
    """The fprime-lite that runs: its version, source folder and that folder's git commit and dirty flag
    (``commit`` None for an installed release outside a git work tree)."""
    import fprime_lite

    source = pathlib.Path(fprime_lite.__file__).resolve().parent
    state = git_state(source) or {"commit": None, "dirty": None}
    return {"fprime_lite": package_versions()["fprime-lite"], "source": str(source), **state}


def _sha256(path: pathlib.Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def input_files(campaign) -> dict[str, str]:
    """SHA-256 of the campaign file and of every file its run section or grid names (relative paths
    from the campaign file's folder)."""
    found = {str(campaign.path): _sha256(campaign.path)}
    candidates: list = []
    for value in campaign.run.values():
        candidates += value if isinstance(value, list) else [value]
    for grid in campaign.grids:
        for axis in grid.values():
            candidates += axis
    for value in candidates:
        if not isinstance(value, str) or not value or "\n" in value or len(value) > 4096:
            continue
        p = pathlib.Path(value)
        p = p if p.is_absolute() else campaign.base_dir / p
        try:
            if p.is_file():
                found[str(p)] = _sha256(p)
        except OSError:
            continue
    return found


def resolved_configuration(tasks: list[dict]) -> dict:
    """What the planned ``tasks`` resolve their configuration from, by their run kind's
    ``fingerprint`` hook, once per distinct run section (a per-run value is the run id's business);
    a fingerprint that cannot be made is recorded as ``{"error": message}``."""
    from fprime_lite.tools.campaign.kinds import resolve_kind

    found: dict = {}
    seen: set[str] = set()
    for task in tasks:
        key = json.dumps([task["kind"], task["config"], str(task.get("base_dir"))], sort_keys=True, default=str)
        if key in seen:
            continue
        seen.add(key)
        try:
            hook = resolve_kind(task["kind"]).fingerprint
            if hook is not None:
                found.update(hook(task["config"], pathlib.Path(task.get("base_dir") or ".")))
        except (FprimeLiteError, LookupError, OSError, ImportError, ValueError) as exc:  # a topology or scenario
            # that cannot be read (a ScenarioError is a ValueError): recorded, and the manifest still written
            found[f"{task['kind']} {json.dumps(task['config'], default=str)}"] = {"error": str(exc)}
    return found


def now_utc() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def read_manifest(out_dir: pathlib.Path) -> dict | None:
    try:
        data = json.loads((pathlib.Path(out_dir) / "manifest.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


class ManifestWriter:
    """Writes ``out_dir/manifest.json`` atomically for one session, keeping the earlier sessions'
    history."""

    def __init__(self, out_dir: pathlib.Path, campaign, *, runs: int, resumed_with: int, retried: int,
                 merged_points: list | None = None, resolved: dict | None = None):
        self.path = pathlib.Path(out_dir) / "manifest.json"
        self.campaign = campaign
        previous = read_manifest(out_dir) or {}
        history = previous.get("history")
        if history is None and previous.get("started"):  # a folder written before the history was kept
            history = [{k: previous.get(k) for k in ("started", "ended", "status", "cluster", "resumed_with",
                                                      "retried")}]
        self.history: list[dict] = list(history or [])
        self.runs = runs
        self.merged_points = merged_points or []
        self.session: dict[str, Any] = {
            "started": now_utc(), "ended": None, "status": "running", "resumed_with": resumed_with,
            "retried": retried, "ran": 0, "cluster": None, "client": machine(), "software": software(),
                        "workers": None}
        self.inputs = input_files(campaign)
        self.resolved = resolved
        self.versions = package_versions()

    def write(self, *, status: str, counts: dict, cluster: dict | None = None, workers: list | None = None,
              ran: int | None = None, ended: bool = False, interrupted: dict | None = None,
              error: str | None = None) -> dict:
        s = self.session
        s["status"] = status
        if interrupted is not None:
            s["interrupted"] = interrupted
        if error is not None:
            s["error"] = error
        if cluster is not None:
            s["cluster"] = cluster
        if workers is not None:
            s["workers"] = workers
        if ran is not None:
            s["ran"] = ran
        if ended:
            s["ended"] = now_utc()
        history = self.history + [dict(s)]
        c = self.campaign
        sw = s["software"]
        manifest = {
            "campaign": c.name,
            "description": c.description,
            "campaign_file": str(c.path),
            "campaign_sha256": hashlib.sha256(c.text.encode()).hexdigest(),
            "campaign_text": c.text,
            "kind": c.kind,
            "master_seed": c.master_seed,
            "runs": self.runs,
            "merged_points": self.merged_points,
            "resumed_with": s["resumed_with"],
            "retried": s["retried"],
            "keep": c.keep.describe(),
            "counts": counts,
            "status": status,
            **({"interrupted": interrupted} if interrupted is not None else {}),
            **({"error": error} if error is not None else {}),
            "started": history[0]["started"],
            "ended": s["ended"],
            "cluster": s["cluster"],
            "software": sw,
            "git_commit": (sw["commit"] + ("+dirty" if sw["dirty"] else "")) if sw["commit"] else None,
            "campaign_folder_git": git_state(c.base_dir),
            "versions": self.versions,
            "client": s["client"],
            "workers": s["workers"],
            "inputs": self.inputs,
            **({"resolved": self.resolved} if self.resolved is not None else {}),
            "history": history,
        }
        atomic_write_text(self.path, json.dumps(manifest, indent=2) + "\n")
        return manifest
