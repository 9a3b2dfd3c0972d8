"""``manifest.json``: what produced a campaign folder (file, versions, commit, times, cluster)."""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import pathlib
import platform
import subprocess

from fprime_lite.osal.atomic import atomic_write_text

__all__ = ["write_manifest", "package_versions"]


def package_versions() -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for name in ("fprime-lite", "numpy", "dask", "distributed", "pandas", "pyarrow"):
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = "not installed"
    return out


def _git_commit(folder: pathlib.Path) -> str | None:
    try:
        r = subprocess.run(["git", "-C", str(folder), "rev-parse", "HEAD"], capture_output=True, text=True,
                           timeout=5)
    except (OSError, subprocess.TimeoutExpired):
        return None
    if r.returncode != 0:
        return None
    dirty = subprocess.run(["git", "-C", str(folder), "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True, timeout=5).stdout.strip()
    return r.stdout.strip() + ("+dirty" if dirty else "")


def now_utc() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def write_manifest(out_dir: pathlib.Path, campaign, *, started: str, ended: str | None, status: str,
                   cluster: dict | None, runs: int, counts: dict, resumed_from: int = 0, retried: int = 0) -> dict:
    """Write ``out_dir/manifest.json`` atomically and return it."""
    manifest = {
        "campaign": campaign.name,
        "description": campaign.description,
        "campaign_file": str(campaign.path),
        "campaign_sha256": hashlib.sha256(campaign.text.encode()).hexdigest(),
        "campaign_text": campaign.text,
        "kind": campaign.kind,
        "master_seed": campaign.master_seed,
        "runs": runs,
        "resumed_with": resumed_from,
        "retried": retried,
        "keep": campaign.keep.describe(),
        "counts": counts,
        "status": status,
        "started": started,
        "ended": ended,
        "cluster": cluster,
        "git_commit": _git_commit(campaign.base_dir),
        "versions": package_versions(),
    }
    atomic_write_text(pathlib.Path(out_dir) / "manifest.json", json.dumps(manifest, indent=2) + "\n")
    return manifest
