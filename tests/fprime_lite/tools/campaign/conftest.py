"""Helpers for the campaign tests: small campaign files written into tmp_path."""

from __future__ import annotations

import pathlib
import textwrap

import pytest

REPO = pathlib.Path(__file__).resolve().parents[4]
TOPOLOGY = REPO / "deployments" / "proves_ref" / "topology.yaml"

TINY_PLANT = """\
campaign: tiny
master_seed: 7
run: {kind: plant, scenario: default, law: bdot, duration_s: 20}
grid:
  gain: [1.0, 3.0]
dispersions:
  scenario.initial.rate.magnitude_deg_s: {dist: uniform, low: 10, high: 30}
  scenario.sensors.magnetometer.bias_gauss: {dist: normal, mean: [0, 0, 0], std: 0.005}
seeds: 2
metrics: [final_rate_deg_s, coil_energy_j, initial_rate_deg_s]
"""


@pytest.fixture
def write_campaign(tmp_path):
    def write(text: str, name: str = "c.yaml") -> pathlib.Path:
        path = tmp_path / name
        path.write_text(textwrap.dedent(text), encoding="utf-8")
        return path
    return write


def comparable(df):
    """The results table without what depends on where and how fast a run went."""
    return df.drop(columns=["wall_s", "cpu_s", "worker"]).reset_index(drop=True)
