"""benchmarks/count_run_instructions.py's ``plant`` mode (issue 32, telem lane): the deployment's plant-only
counterpart, counted inside ``itertools.starmap`` (callgrind's ``--toggle-collect=starmap_next`` window) so that
``deploy`` - ``plant`` is the F´ part. No instructions are counted here: what is flown, and where."""

from __future__ import annotations

import itertools
import pathlib

import count_run_instructions

REFERENCE = pathlib.Path(__file__).resolve().parents[2] / "deployments"


def test_plant_mode_flies_the_counterpart_law_inside_the_counted_window(monkeypatch):
    """BENCH-030: ``plant`` flies ``detumble.sim.runner.run`` on the topology's own scenario with the law
    ``measure_deployment`` pairs it with (adcs_ref: ``adcs``; proves_ref: its scenario's B-dot), for the duration
    asked, on a fresh plant built before the counted window, and the run happens inside ``itertools.starmap``."""
    import detumble.sim.runner as runner

    inside = []
    flown = []
    starmap = itertools.starmap

    def watched_starmap(function, iterable):  # the counted window: what starmap calls
        def counted(*args):
            inside.append(True)
            try:
                return function(*args)
            finally:
                inside.pop()
        return starmap(counted, iterable)

    def fake_run(scenario, law=None, gain=None, duration_s=None, seed=None, *, plant=None, **_):
        flown.append((scenario.name, law, duration_s, plant is not None and plant.t_ns == 0, bool(inside)))

    monkeypatch.setattr(count_run_instructions.itertools, "starmap", watched_starmap)
    monkeypatch.setattr(runner, "run", fake_run)
    for name in ("adcs_ref", "proves_ref"):
        topology = REFERENCE / name / "topology.yaml"
        assert count_run_instructions.main([str(topology), "7.5", "plant", "unused"]) == 0
    # (scenario, law, duration, fresh plant, inside starmap): the pairs measure_deployment flies
    assert flown == [("adcs", "adcs", 7.5, True, True), ("default", "bdot", 7.5, True, True)]
