"""Campaign files: validation with file:line errors, unknown keys refused, grid axes."""

from __future__ import annotations

import pytest

from fprime_lite.tools.campaign import CampaignError, load_campaign
from fprime_lite.tools.campaign.grid import axis_values, grid_points


def _problems(path) -> list[str]:
    with pytest.raises(CampaignError) as info:
        load_campaign(path)
    return info.value.problems


def test_valid_file_loads(write_campaign):
    """CAMP-001: a valid campaign file loads with its grid, dispersions, seeds and metrics."""
    from tests.fprime_lite.tools.campaign.conftest import TINY_PLANT

    c = load_campaign(write_campaign(TINY_PLANT))
    assert c.name == "tiny" and c.kind == "plant" and c.seeds == 2 and c.master_seed == 7
    assert c.grids == [{"gain": [1.0, 3.0]}]
    assert c.varied_keys == ["gain", "scenario.initial.rate.magnitude_deg_s",
                             "scenario.sensors.magnetometer.bias_gauss"]


def test_unknown_keys_are_refused_with_file_and_line(write_campaign):
    """CAMP-002: unknown keys at the top, in the run section, in a dispersion and in a plot are each
    reported at their own file:line, all at once, with a did-you-mean."""
    path = write_campaign("""\
        campaign: bad
        run: {kind: plant, scenario: default, durration_s: 20}
        seed: 3
        dispersions:
          scenario.initial.rate.magnitude_deg_s: {dist: uniform, low: 1, hihg: 2}
        metrics: [final_rate_deg_s]
        plots:
          - {type: cdf, metric: final_rate_deg_s, colour: red}
        """)
    problems = _problems(path)
    text = "\n".join(problems)
    assert f"{path}:2: unknown key 'durration_s' in the 'plant' run section — did you mean 'duration_s'?" in text
    assert f"{path}:3: unknown key 'seed' in the campaign file — did you mean 'seeds'?" in text
    assert f"{path}:5: dispersion 'scenario.initial.rate.magnitude_deg_s': unknown field hihg" in text
    assert f"{path}:8: unknown key 'colour' in a plot" in text
    assert len(problems) == 4


def test_bad_values_are_reported_at_their_lines(write_campaign):
    """CAMP-003: a bad run kind, a bad axis, a bad dist name and a non-varied plot key are refused."""
    path = write_campaign("""\
        campaign: bad
        run: {kind: plantt}
        grid:
          gain: {range: [1, 0, 1]}
        dispersions:
          gain2: {dist: gaussian, mean: 0, std: 1}
        seeds: 0
        """)
    text = "\n".join(_problems(path))
    assert f"{path}:2: unknown run kind 'plantt' — did you mean 'plant'?" in text
    assert f"{path}:4: grid axis 'gain': range [1, 0, 1]: the step never reaches stop" in text
    assert f"{path}:6: dispersion 'gain2': unknown dist 'gaussian'" in text
    assert f"{path}:7: 'seeds' must be a whole number >= 1" in text


def test_varied_keys_are_checked_by_the_run_kind(write_campaign):
    """CAMP-004: a key the run kind cannot vary is refused at its line, naming what it can vary."""
    path = write_campaign("""\
        campaign: bad
        run: {kind: deployment, topology: t.yaml, duration_s: 5}
        grid:
          GAIN: [1, 2]
        """)
    (problem,) = _problems(path)
    assert problem.startswith(f"{path}:4: 'GAIN' cannot be varied: a deployment run varies topology")


def test_axis_forms():
    """CAMP-005: lists, ranges (stop included when on the grid), linspace and logrange."""
    assert axis_values([3, "a"]) == [3, "a"]
    assert axis_values({"range": [0, 1, 0.25]}) == [0, 0.25, 0.5, 0.75, 1]
    assert axis_values({"range": [0, 0.9, 0.3]}) == [0, 0.3, 0.6, 0.9]  # 0.30000000000000004 cleaned
    assert axis_values({"linspace": [1, 2, 3]}) == [1, 1.5, 2]
    assert axis_values({"logrange": [1e-3, 1e-1, 3]}) == [0.001, 0.01, 0.1]
    with pytest.raises(ValueError, match="start and stop must be > 0"):
        axis_values({"logrange": [0, 1, 3]})
    with pytest.raises(ValueError, match="exactly one of"):
        axis_values({"range": [0, 1, 1], "linspace": [0, 1, 2]})


def test_grid_is_a_union_of_products():
    """CAMP-006: a list of grids is the union of their products in file order, last key fastest."""
    pts = grid_points([{"a": [1, 2], "b": ["x", "y"]}, {"c": [0]}])
    assert pts == [{"a": 1, "b": "x"}, {"a": 1, "b": "y"}, {"a": 2, "b": "x"}, {"a": 2, "b": "y"}, {"c": 0}]


def test_percentile_with_never():
    """CAMP-007: percentiles where inf means "never": numpy's linear rule, inf only when reached."""
    import math

    import numpy as np

    from fprime_lite.tools.campaign.report import percentile

    assert percentile(np.array([3923.0, 2989.0, math.inf]), 50) == 3923.0  # numpy: nan (inf·0)
    assert percentile(np.array([3923.0, 2989.0, math.inf]), 95) == math.inf
    assert percentile(np.arange(11.0), 95) == np.percentile(np.arange(11.0), 95)
    xs = [1.0, 2.0, 4.0, 8.0]
    assert percentile(np.array(xs), 40) == pytest.approx(np.percentile(xs, 40), rel=1e-15)


def test_a_run_kind_by_import_path_is_checked_at_its_line(write_campaign):
    """CAMP-008: kind: module:NAME loads a RunKind from an importable module (its fields checked);
    a module or name that cannot be imported, or an object that is not a RunKind, is refused at the kind line."""
    probe = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"
    good = load_campaign(write_campaign(f'campaign: k\nrun: {{kind: "{probe}", mode: ok}}\n'))
    assert good.kind.endswith(":PROBE_RUN") and good.run["mode"] == "ok"
    for kind, message in (("no_such_module_xyz:K", "cannot be imported"),
                          ("tests.fprime_lite.tools.campaign.probe_kinds:NOPE", "cannot be imported"),
                          ("tests.fprime_lite.tools.campaign.probe_kinds:os", "is a module, not a RunKind")):
        path = write_campaign(f'campaign: k\nrun:\n  kind: "{kind}"\n', "bad.yaml")
        (problem,) = _problems(path)
        assert problem.startswith(f"{path}:3: run kind '{kind}'") and message in problem, problem


def _registry(names):
    from fprime_lite.tools.campaign.kinds import Metric

    return {n: Metric(name=n, unit="s", description=n, compute=lambda output, probe: 0.0) for n in names}


def test_metric_group_expands_to_its_named_metrics_in_order(write_campaign, monkeypatch):
    """CAMP-093: 'PREFIX.*' in 'metrics' stands for every installed named metric 'PREFIX.…' in
    registration order; a group that matches nothing is refused at the 'metrics' line, naming the
    groups there are; the terminal summary gives the group one line, not one row per member."""
    import io

    import pandas as pd
    from rich.console import Console

    from fprime_lite.tools.campaign import kinds
    from fprime_lite.tools.campaign.report import print_summary
    from tests.fprime_lite.tools.campaign.conftest import TINY_PLANT

    names = ["err.window_s", "err.bin.1", "err.bin.0", "errx.other", "rate"]
    monkeypatch.setattr(kinds, "metrics", lambda: _registry(names))
    listed = "metrics: [final_rate_deg_s, coil_energy_j, initial_rate_deg_s]"
    c = load_campaign(write_campaign(TINY_PLANT.replace(listed, "metrics: [final_rate_deg_s, err.*]")))
    assert c.metrics == ["final_rate_deg_s", "err.window_s", "err.bin.1", "err.bin.0"]
    assert c.metric_groups == {"err.*": ["err.window_s", "err.bin.1", "err.bin.0"]}

    df = pd.DataFrame([{"status": "ok", "point": 0, "final_rate_deg_s": 1.0, "err.window_s": 5.0,
                        "err.bin.1": 2.0, "err.bin.0": 3.0}])
    out = io.StringIO()
    print_summary(df, c, console=Console(file=out, width=200))
    text = out.getvalue()
    assert "final_rate_deg_s" in text and "err.*: 3 columns in results.parquet" in text
    assert "err.bin.1" not in text

    bad = write_campaign(TINY_PLANT.replace(listed, "metrics: [final_rate_deg_s, nope.*]"), name="bad.yaml")
    problems = _problems(bad)
    assert len(problems) == 1 and "bad.yaml:10" in problems[0]
    assert "'nope.*' matches no installed named metric" in problems[0] and "err.*" in problems[0]
