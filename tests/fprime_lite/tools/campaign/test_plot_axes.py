"""Which grid keys the automatic plots take as axes (tools/campaign/plots.py)."""

from types import SimpleNamespace

import numpy as np
import pytest

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")

from fprime_lite.tools.campaign.plots import auto_plots  # noqa: E402 - after the dependency check, as its siblings


def test_a_list_valued_grid_key_is_not_an_axis_and_does_not_stop_the_plots():
    """CAMP-152: coursework/noise.yaml grids a vector setting (bias_gauss: [[0, 0, 0]]); its column holds arrays,
    which pandas cannot hash. The automatic plots skip it and draw against the numeric key (the campaign ended in
    a traceback after its last run before)."""
    df = pd.DataFrame({
        "point": [0, 0, 1, 1],
        "scenario.sensors.magnetometer.bias_gauss": [np.zeros(3), np.zeros(3), None, None],
        "scenario.spacecraft.reaction_wheels.momentum_noise_std_nms": [None, None, 1e-5, 1e-4],
        "settling_time_2pct_s": [20400.0, 20450.0, 80.0, 81.0],
    })
    noise = "scenario.spacecraft.reaction_wheels.momentum_noise_std_nms"
    campaign = SimpleNamespace(grid_keys=["scenario.sensors.magnetometer.bias_gauss", noise],
                               metrics=["settling_time_2pct_s"])
    assert auto_plots(df, campaign) == [{"type": "line", "x": noise, "metric": "settling_time_2pct_s"}]
