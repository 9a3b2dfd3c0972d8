"""The campaigns shipped in campaigns/: each validates and builds; smoke.yaml runs (the CI example)."""

from __future__ import annotations

import pathlib

import pytest

from fprime_lite.tools.campaign import load_campaign, read_results
from fprime_lite.tools.campaign.engine import preflight
from fprime_lite.tools.campaign.plan import plan_runs
from fprime_lite.tools.cli import main
from tests.fprime_lite.tools.campaign.conftest import REPO

SHIPPED = sorted((REPO / "campaigns").glob("*.yaml")) + sorted((REPO / "campaigns" / "adcs").glob("*.yaml"))


@pytest.mark.parametrize("path", SHIPPED, ids=[p.name for p in SHIPPED])
def test_shipped_campaign_validates_and_builds(path):
    """CAMP-080: every shipped campaign loads and its representative runs build (no key misspelt)."""
    campaign = load_campaign(path)
    tasks = plan_runs(campaign, pathlib.Path("unused"))
    preflight(campaign, tasks)
    assert len(tasks) >= 8


def test_smoke_campaign_runs_on_two_workers(tmp_path):
    """CAMP-081: `fprime-lite campaign campaigns/smoke.yaml --workers 2` gives 12 ok rows with the
    read-back initial rate equal to the summary's, and draws its plots."""
    out = tmp_path / "smoke"
    assert main(["campaign", str(REPO / "campaigns" / "smoke.yaml"), "--workers", "2", "--out", str(out)]) == 0
    df = read_results(out)
    assert len(df) == 12 and set(df["status"]) == {"ok"}
    assert (df["scenario.initial.rate.magnitude_deg_s"] - df["initial_rate_deg_s"]).abs().max() < 1e-9
    assert len(list((out / "plots").glob("*.png"))) == 5  # one heatmap per metric (gain × period)
