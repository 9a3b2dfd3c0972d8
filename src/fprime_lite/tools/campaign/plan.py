"""A campaign's runs, in a fixed order: each grid point × each seed index, with its identity,
simulator seed and dispersed values (see :mod:`.seeding`)."""

from __future__ import annotations

import pathlib

from fprime_lite.tools.campaign.grid import grid_points
from fprime_lite.tools.campaign.seeding import key_generator, run_id, run_seed_sequence, simulator_seed

__all__ = ["plan_runs"]


def plan_runs(campaign, artifacts_dir: pathlib.Path) -> list[dict]:
    """The task of every run of ``campaign`` (plain data: it travels to the workers).

    With ``common_random_numbers`` the seed sequence is keyed by the seed index alone, so every grid
    point meets the same dispersed draws and noise seeds (paired comparisons between points).
    """
    from fprime_lite.tools.campaign.kinds import resolve_kind

    fields = resolve_kind(campaign.kind).fields
    identity = {"run": campaign.run, "dispersions": campaign.dispersion_specs, "metrics": campaign.metrics,
                "crn": campaign.common_random_numbers}
    tasks = []
    for index, point in enumerate(grid_points(campaign.grids)):
        for s in range(campaign.seeds):
            seq = run_seed_sequence(campaign.master_seed, {} if campaign.common_random_numbers else point, s)
            seed = simulator_seed(seq)
            values = dict(point)
            for key, dispersion in campaign.dispersions.items():
                values[key] = dispersion.sample(key_generator(seq, key))
            config = dict(campaign.run)
            config.update({k: v for k, v in point.items() if k in fields})
            tasks.append({
                "run_id": run_id(identity, point, seed), "point": index, "seed_index": s, "seed": seed,
                "kind": campaign.kind, "config": config, "values": values, "metrics": campaign.metrics,
                "timeout_s": campaign.timeout_s, "keep": campaign.keep.worker_mode, "artifacts_dir": str(artifacts_dir),
                "base_dir": str(campaign.base_dir),
            })
    return tasks
