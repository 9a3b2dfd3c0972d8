"""benchmarks/count_channel_writes.py (issue 32, ctltlm lane): the channel writes a tick it reports."""

from __future__ import annotations

import pathlib

import pytest

import count_channel_writes

ADCS_REF = pathlib.Path(__file__).resolve().parents[2] / "deployments" / "adcs_ref" / "topology.yaml"


def test_counts_each_write_that_reaches_tlm_chan_per_tick_of_the_fastest_group():
    """BENCH-031: on adcs_ref (2 s after 3 s of flight, 100 ticks of the 50 Hz group) every rate group's RgMaxTime,
    written once a cycle, counts 1, 0.2 and 0.02 a tick; the star tracker's attitude channel, written by its 1 Hz
    run, 0.02; the controller's channels, written by its 1 Hz tlmRun, at most 0.02 each and 0.3 or less in all."""
    rates, ticks = count_channel_writes.count_writes(ADCS_REF, 3.0, 2.0)
    assert ticks == pytest.approx(100)
    assert rates["rateGroup50Hz.RgMaxTime"] == pytest.approx(1.0)
    assert rates["rateGroup10Hz.RgMaxTime"] == pytest.approx(0.2)
    assert rates["rateGroup1Hz.RgMaxTime"] == pytest.approx(0.02)
    assert rates["starTracker.Attitude"] == pytest.approx(0.02)
    ours = {k: v for k, v in rates.items() if k.startswith("attitudeController.")}
    assert len(ours) >= 13 and max(ours.values()) == pytest.approx(0.02) and sum(ours.values()) <= 0.3 + 1e-9
