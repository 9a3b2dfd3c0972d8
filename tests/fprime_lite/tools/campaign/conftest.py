"""Helpers for the campaign tests: small campaign files written into tmp_path."""

from __future__ import annotations

import contextlib
import os
import pathlib
import signal
import socket
import subprocess
import sys
import textwrap

import pytest

REPO = pathlib.Path(__file__).resolve().parents[4]
TOPOLOGY = REPO / "deployments" / "proves_ref" / "topology.yaml"
#: The venv's bin folder (dask scheduler / dask worker for the external-cluster tests).
BIN = pathlib.Path(sys.executable).parent


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(procs) -> None:
    for p in procs:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(p.pid, signal.SIGTERM)
    for p in procs:
        try:
            p.wait(timeout=15)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(p.pid, signal.SIGKILL)
            p.wait(timeout=5)


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


def recorded(out: pathlib.Path) -> dict[str, bytes]:
    """The bytes of every results part of the campaign folder ``out``, by file name."""
    parts = out / "results.parts"
    return {p.name: p.read_bytes() for p in sorted(parts.iterdir())} if parts.is_dir() else {}


def comparable(df):
    """The results table without what depends on where and how fast a run went."""
    return df.drop(columns=["wall_s", "cpu_s", "worker"]).reset_index(drop=True)
