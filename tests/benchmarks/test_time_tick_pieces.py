"""benchmarks/time_tick_pieces.py: its wrapper passes every call through and counts it, and a short flight
reports each piece's calls a tick as the rate groups make them (the times themselves are not judged)."""

import collections
import pathlib

import pytest

import time_tick_pieces as tool

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("answer", [None, 0, "", (1.5, -2.0)])
def test_the_wrapper_passes_calls_through_and_counts_them(answer):
    """BENCH-036: a wrapped function gets the arguments and keywords given, its answer (falsy ones included)
    comes back, and each call counts once with a non-negative time; a call that raises propagates its
    exception and still counts."""
    seconds, calls, seen = collections.Counter(), collections.Counter(), []

    def piece(*args, **kwargs):
        seen.append((args, kwargs))
        if kwargs.get("fail"):
            raise ValueError("from the piece")
        return answer

    wrapped = tool.timed(piece, "p", seconds, calls)
    assert wrapped(3, "x", k=1) == answer
    assert seen == [((3, "x"), {"k": 1})] and calls["p"] == 1 and seconds["p"] >= 0.0
    with pytest.raises(ValueError, match="from the piece"):
        wrapped(fail=True)
    assert calls["p"] == 2


def test_a_short_flight_counts_each_piece_at_its_rate(monkeypatch):
    """BENCH-037: proves_ref, 1 s timed after 1 s: the plant's advance runs once a 50 Hz tick, the 1 Hz group's
    cycle once in 50 ticks (an instance piece, wrapped after the untimed second), the manager's run once a tick;
    every figure is a positive time."""
    from detumble.components.detumble_manager import DetumbleManager
    from detumble.drivers.spacecraft import SimulatedSpacecraft

    monkeypatch.setattr(SimulatedSpacecraft, "advance_to_us", SimulatedSpacecraft.__dict__["advance_to_us"])
    monkeypatch.setattr(DetumbleManager, "run", DetumbleManager.__dict__["run"])
    specs = ["detumble.drivers.spacecraft:SimulatedSpacecraft.advance_to_us",
             "detumble.components.detumble_manager:DetumbleManager.run",
             "@ReferenceDeployment.rateGroup1Hz:_cycle"]
    r = tool.measure(str(ROOT / "deployments/proves_ref/topology.yaml"), specs, after_s=1.0, duration_s=1.0)
    rows = r["pieces"]
    assert r["ticks"] == 50
    assert rows[specs[0]]["calls_per_tick"] == 1.0
    assert rows[specs[1]]["calls_per_tick"] == 1.0
    assert rows[specs[2]]["calls_per_tick"] == 1 / 50
    assert all(row["us_per_tick"] > 0 and row["us_per_call"] > 0 for row in rows.values())
    assert r["plain_tick_us"] > 0 and r["wrapped_tick_us"] > 0 and r["wrapper_us"] > 0
