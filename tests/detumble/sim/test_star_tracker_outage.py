"""STAR-OUT-001/002: the star tracker's outage window (``sensors.star_tracker.outage_s``): a tracker lost and
recovered, the Sun-safe entry on star-tracker loss and the exit when knowledge is back (issue 27)."""

from __future__ import annotations

import pytest

from detumble.sim.plant import Plant
from detumble.sim.scenario import ScenarioError, load_scenario


def test_no_solution_inside_the_outage_window():
    """STAR-OUT-001: the adcs scenario at rest with ``outage_s = [2, 4]``: solutions before 2 s, none from 2 s to
    4 s (the held attitude, counted as dropouts), solutions again from 4 s; without the key, none is lost."""
    sc = load_scenario("adcs", seed=1,
                       settings=["initial.rate.magnitude_deg_s=0", "sensors.star_tracker.outage_s=[2,4]"])
    plant = Plant(sc, 1)
    seen = []
    for _ in range(60):
        plant.step(0.1)
        seen.append((round(plant.t, 1), plant.star_tracker_reading()[4]))
    assert all(valid for t, valid in seen if t < 2.0)
    assert not any(valid for t, valid in seen if 2.0 <= t < 4.0)
    assert all(valid for t, valid in seen if t >= 4.0)
    assert plant.star_tracker.dropouts == 10  # 5 Hz for 2 s
    plain = Plant(load_scenario("adcs", seed=1, settings=["initial.rate.magnitude_deg_s=0"]), 1)
    plain.step(6.0)
    assert plain.star_tracker.dropouts == 0


@pytest.mark.parametrize("value, words", [("[5]", "expected [start, end]"), ("[4,2]", "must end after it starts"),
                                          ("[-1,2]", "outage_s")])
def test_a_bad_outage_is_refused(value, words):
    """STAR-OUT-002: an outage that is not ``[start, end]`` with 0 ≤ start < end is refused by name."""
    with pytest.raises(ScenarioError, match=words.replace("[", r"\[")):
        load_scenario("adcs", settings=[f"sensors.star_tracker.outage_s={value}"])
