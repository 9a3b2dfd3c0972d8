"""Seeds and dispersed values come from run identity, never from the order of execution."""

from __future__ import annotations

import pathlib

from fprime_lite.tools.campaign import load_campaign
from fprime_lite.tools.campaign.plan import plan_runs
from tests.fprime_lite.tools.campaign.conftest import TINY_PLANT


def _by_point(tasks):
    return {(tuple(sorted((k, v) for k, v in t["values"].items() if k == "gain")), t["seed_index"]):
            (t["seed"], t["values"], t["run_id"]) for t in tasks}


def test_seeds_depend_on_the_point_not_its_position(write_campaign):
    """CAMP-010: reordering the grid (and adding a point) leaves every run's seed, draws and id unchanged."""
    a = plan_runs(load_campaign(write_campaign(TINY_PLANT, "a.yaml")), pathlib.Path("x"))
    b = plan_runs(load_campaign(write_campaign(TINY_PLANT.replace("[1.0, 3.0]", "[9.0, 3.0, 1.0]"), "b.yaml")),
                  pathlib.Path("x"))
    pa, pb = _by_point(a), _by_point(b)
    assert set(pa) < set(pb)
    for key, value in pa.items():
        assert pb[key] == value
    assert len({t["seed"] for t in b}) == len(b)  # distinct seeds per run
    assert len({t["run_id"] for t in b}) == len(b)


def test_master_seed_changes_every_draw(write_campaign):
    """CAMP-011: another master seed gives other seeds and other dispersed values."""
    a = plan_runs(load_campaign(write_campaign(TINY_PLANT, "a.yaml")), pathlib.Path("x"))
    b = plan_runs(load_campaign(write_campaign(TINY_PLANT.replace("master_seed: 7", "master_seed: 8"), "b.yaml")),
                  pathlib.Path("x"))
    for ta, tb in zip(a, b, strict=True):
        assert ta["seed"] != tb["seed"]
        key = "scenario.initial.rate.magnitude_deg_s"
        assert ta["values"][key] != tb["values"][key]


def test_adding_a_dispersion_keeps_the_others(write_campaign):
    """CAMP-012: each dispersed key draws from its own stream: adding one leaves the others' values."""
    extra = TINY_PLANT.replace("seeds: 2",
                               "  scenario.initial.rate.axis: {dist: random_vector, magnitude: 1}\nseeds: 2")
    a = plan_runs(load_campaign(write_campaign(TINY_PLANT, "a.yaml")), pathlib.Path("x"))
    b = plan_runs(load_campaign(write_campaign(extra, "b.yaml")), pathlib.Path("x"))
    for ta, tb in zip(a, b, strict=True):
        key = "scenario.sensors.magnetometer.bias_gauss"
        assert tb["values"][key] == ta["values"][key]
        assert ta["seed"] == tb["seed"]


def test_common_random_numbers_pair_the_points(write_campaign):
    """CAMP-013: with common_random_numbers every grid point meets the same draws and noise seed."""
    tasks = plan_runs(load_campaign(write_campaign("common_random_numbers: true\n" + TINY_PLANT)), pathlib.Path("x"))
    by_seed = {}
    for t in tasks:
        draw = {k: v for k, v in t["values"].items() if k != "gain"}
        by_seed.setdefault(t["seed_index"], []).append((t["seed"], draw))
    for runs in by_seed.values():
        assert all(r == runs[0] for r in runs) and len(runs) == 2
    assert len({t["run_id"] for t in tasks}) == len(tasks)
