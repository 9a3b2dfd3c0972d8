"""A campaign's runs, in a fixed order: each grid point × each seed index, with its identity,
simulator seed and (drawn only for the runs about to fly) dispersed values (see :mod:`.seeding`).

Grid points are identified by their values, not by where the file lists them: a point written
twice (the flight defaults alone and again inside a sweep, or ``3`` in one sub-grid and ``3.0`` in
another) is one point, flown once, numbered where it first appears; :func:`merged_points` says which.
"""

from __future__ import annotations

import pathlib

from fprime_lite.tools.campaign.errors import CampaignError
from fprime_lite.tools.campaign.grid import grid_points
from fprime_lite.tools.campaign.seeding import canonical, key_generator, run_id, run_seed_sequence, simulator_seed

__all__ = ["plan_runs", "draw_values", "unique_points", "point_identity", "write_plan_cache", "PLAN_CACHE"]

#: In a campaign folder: the run ids and simulator seeds of its plan, so that a resume of a large
#: campaign does not derive 100,000 seed sequences again (checked against a key of everything they
#: depend on; anything else is recomputed).
PLAN_CACHE = "plan-cache.json"


def _plan_key(campaign, identity_json: str, points: list[dict]) -> str:
    import hashlib

    text = canonical([identity_json, campaign.master_seed, campaign.common_random_numbers, campaign.seeds,
                      [canonical(p) for p in points], 1])
    return hashlib.sha256(text.encode()).hexdigest()


def _read_cache(path, key: str, n: int):
    import json

    if path is None:
        return None
    try:
        data = json.loads(pathlib.Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("key") != key or len(data.get("runs", ())) != n:
        return None
    return data["runs"]


def write_plan_cache(path, campaign, tasks: list[dict]) -> None:
    """Record the run ids and seeds of ``tasks`` (the whole plan of ``campaign``) at ``path``."""
    import json

    from fprime_lite.osal.atomic import atomic_write_text

    identity_json = canonical(_identity(campaign))
    points, _ = unique_points(campaign.grids)
    atomic_write_text(pathlib.Path(path), json.dumps({"key": _plan_key(campaign, identity_json, points),
                                                      "runs": [[t["run_id"], t["seed"]] for t in tasks]}))


def _identity(campaign) -> dict:
    return {"run": campaign.run, "dispersions": campaign.dispersion_specs, "metrics": campaign.metrics,
            "crn": campaign.common_random_numbers}


def point_identity(point: dict) -> str:
    """What makes two grid points the same run: their keys and values, numbers compared as floats."""
    def norm(v):
        if isinstance(v, bool) or v is None or isinstance(v, str):
            return v
        if isinstance(v, (int, float)):
            return float(v)
        if isinstance(v, (list, tuple)):
            return [norm(x) for x in v]
        if isinstance(v, dict):
            return {str(k): norm(x) for k, x in v.items()}
        return v
    return canonical(norm(point))


def unique_points(grids: list[dict[str, list]]) -> tuple[list[dict], list[tuple[int, int]]]:
    """The grid's distinct points in file order, and ``(listed position, point number)`` for each
    point listed again (merged into the first)."""
    points: list[dict] = []
    seen: dict[str, int] = {}
    merged = []
    for position, point in enumerate(grid_points(grids)):
        ident = point_identity(point)
        if ident in seen:
            merged.append((position, seen[ident]))
            continue
        seen[ident] = len(points)
        points.append(point)
    return points, merged


def plan_runs(campaign, artifacts_dir: pathlib.Path, *, draw: bool = True, cache=None) -> list[dict]:
    """The task of every run of ``campaign`` (plain data: it travels to the workers).

    With ``common_random_numbers`` the seed sequence is keyed by the seed index alone, so every grid
    point meets the same dispersed draws and noise seeds (paired comparisons between points).
    ``draw=False`` leaves the dispersed values out (``values`` holds the grid point only): a resume
    draws them with :func:`draw_values` for the runs it still has to fly. ``cache``: a
    :data:`PLAN_CACHE` file whose ids and seeds are used when its key matches this plan.
    """
    from fprime_lite.tools.campaign.kinds import resolve_kind

    fields = resolve_kind(campaign.kind).fields
    identity = _identity(campaign)
    points, _ = unique_points(campaign.grids)
    every = campaign.keep.every
    tasks: list[dict] = []
    ids: dict[str, int] = {}
    identity_json = canonical(identity)
    cached = _read_cache(cache, _plan_key(campaign, identity_json, points), len(points) * campaign.seeds) \
        if cache is not None else None
    base_dir, artifacts = str(campaign.base_dir), str(artifacts_dir)  # (resolved once, not per run)
    for index, point in enumerate(points):
        point_json = canonical(point)
        seq_json = canonical({}) if campaign.common_random_numbers else point_json
        config = dict(campaign.run)
        config.update({k: v for k, v in point.items() if k in fields})
        for s in range(campaign.seeds):
            order = len(tasks)
            if cached is not None:
                rid, seed = cached[order]
            else:
                seed = simulator_seed(run_seed_sequence(campaign.master_seed, point, s, point_json=seq_json))
                rid = run_id(identity, point, seed, run_json=identity_json, point_json=point_json)
            if rid in ids:  # two different points with one id: a hash collision or a bug — never fly either silently
                raise CampaignError([f"{campaign.path}: grid points {ids[rid]} and {index} give the same run id {rid}"])
            ids[rid] = index
            tasks.append({
                "run_id": rid, "point": index, "seed_index": s, "seed": seed, "order": order,
                "kind": campaign.kind, "config": config, "values": dict(point), "drawn": False,
                "metrics": campaign.metrics, "timeout_s": campaign.timeout_s,
                "keep": "all" if every and order % every == 0 else campaign.keep.worker_mode,
                "artifacts_dir": artifacts, "base_dir": base_dir,
            })
    if draw:
        for task in tasks:
            draw_values(task, campaign)
    return tasks


def draw_values(task: dict, campaign) -> dict:
    """Add the dispersed values of ``task`` (drawn from its own seed streams); returns the task."""
    if task.get("drawn") or not campaign.dispersions:
        task["drawn"] = True
        return task
    point = {k: v for k, v in task["values"].items() if k not in campaign.dispersions}
    seq = run_seed_sequence(campaign.master_seed, {} if campaign.common_random_numbers else point,
                            task["seed_index"])
    from fprime_lite.tools.campaign.kinds import resolve_kind

    fields = resolve_kind(campaign.kind).fields
    for key, dispersion in campaign.dispersions.items():
        task["values"][key] = dispersion.sample(key_generator(seq, key))
        if key in fields:  # a dispersed run-section field (a law drawn per run) goes into the run's config
            task["config"] = {**task["config"], key: task["values"][key]}
    task["drawn"] = True
    return task
