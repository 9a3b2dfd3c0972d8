"""Per-run files and plots (issues 31 and 28): plant runs keep their traces, `every: N`, `--rerun RUN_ID`,
no empty folders; line plots grouped by grid point with percentiles from the file; heatmaps that show
"never" cells and no colour bar without a value."""

from __future__ import annotations

import json

import numpy as np
import pytest

from fprime_lite.tools.campaign import run_campaign
from fprime_lite.tools.cli import main
from tests.fprime_lite.tools.campaign.conftest import recorded

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

PLANT = """\
campaign: plant_files
master_seed: 5
run: {kind: plant, scenario: default, law: bdot, duration_s: 10}
grid:
  gain: [1.0, 3.0]
seeds: 2
metrics: [final_rate_deg_s]
KEEP
"""


def test_plant_runs_keep_their_trace_and_every_n_keeps_a_sample(write_campaign, tmp_path):
    """CAMP-131: `keep: all` on plant runs keeps each run's summary.json and rate.csv (before: empty
    folders); `keep: {every: 2}` keeps exactly the runs at places 0 and 2 of the plan; `keep: {failed:
    true}` with every run ok leaves no folder at all."""
    df = run_campaign(write_campaign(PLANT.replace("KEEP", "keep: all")), workers=2, out=tmp_path / "all",
                      plots=False, summary=False)
    for run_id in df["run_id"]:
        folder = tmp_path / "all" / "runs" / run_id
        assert json.loads((folder / "summary.json").read_text())["gain"] in (1.0, 3.0)
        assert (folder / "rate.csv").read_text().startswith("time_s,omega_x_deg_s")
    df = run_campaign(write_campaign(PLANT.replace("KEEP", "keep: {every: 2}"), "e.yaml"), workers=2,
                      out=tmp_path / "every", plots=False, summary=False)
    expected = set(df[(df["point"] * 2 + df["seed_index"]) % 2 == 0]["run_id"])
    assert {p.name for p in (tmp_path / "every" / "runs").iterdir()} == expected and len(expected) == 2
    run_campaign(write_campaign(PLANT.replace("KEEP", "keep: {failed: true}"), "f.yaml"), workers=1,
                 out=tmp_path / "failed", plots=False, summary=False)
    runs = tmp_path / "failed" / "runs"
    assert not runs.exists() or not any(runs.iterdir())


def test_rerun_flies_one_run_again_with_its_files(write_campaign, tmp_path, capsys):
    """CAMP-132: `--rerun RUN_ID` flies that run again in-process (same seed and values), keeps its files in
    runs/RUN_ID, says it reproduced the journaled row, and leaves the journal alone; an unknown id is
    refused with a did-you-mean."""
    path = write_campaign(PLANT.replace("KEEP", ""))
    out = tmp_path / "o"
    assert main(["campaign", str(path), "--workers", "1", "--out", str(out), "--no-plots"]) == 0
    run_id = pd.read_parquet(out / "results.parquet")["run_id"][2]
    journal = recorded(out)
    assert journal
    capsys.readouterr()
    assert main(["campaign", str(path), "--out", str(out), "--rerun", run_id]) == 0
    said = capsys.readouterr().out
    assert f"run {run_id}: ok" in said and "every metric and read-back value as journaled" in said
    assert (out / "runs" / run_id / "rate.csv").is_file() and recorded(out) == journal
    assert main(["campaign", str(path), "--out", str(out), "--rerun", run_id[:-1] + "x"]) == 2
    assert f"did you mean {run_id}?" in capsys.readouterr().err


def _frame(values, metric="m"):
    rows = []
    for (x, y), v in values.items():
        rows += [{"x": x, "y": y, metric: v, "status": "ok", "point": 0, "seed_index": s} for s in range(3)]
    return pd.DataFrame(rows)


def test_heatmap_cells_that_never_settled_are_drawn_and_an_all_null_metric_has_no_colour_bar():
    """CAMP-133: a cell whose aggregate is never is hatched and labelled "never" in black (before: white
    text on a white, empty cell); the other labels contrast with their colour; a metric null in every run
    draws no colour bar and says so in the title (before: a meaningless bar)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fprime_lite.tools.campaign.plots import _heatmap

    fig, ax = plt.subplots()
    _heatmap(fig, ax, _frame({(1, 1): 3.0, (1, 2): np.nan, (2, 1): 5.0, (2, 2): 9.0}), "x", "y", "m", "median")
    never = [t for t in ax.texts if t.get_text() == "never"]
    assert len(never) == 1 and never[0].get_color() == "k" and never[0].get_position() == (0, 1)
    assert len(ax.patches) == 1 and ax.patches[0].get_hatch() == "//"
    assert len(fig.axes) == 2 and "(hatched: never)" in ax.get_title()
    plt.close(fig)
    fig, ax = plt.subplots()
    _heatmap(fig, ax, _frame({(1, 1): np.nan, (2, 1): np.nan}), "x", "y", "m", "p95")
    assert len(fig.axes) == 1 and "no value in any cell" in ax.get_title()
    assert [t.get_text() for t in ax.texts] == ["never", "never"]
    plt.close(fig)


def test_heatmap_titles_name_metric_and_aggregate_and_labels_stay_legible():
    """CAMP-151: the title names the aggregate and the metric, with values and with none; a "never" label
    sits on its own white box (the hatching does not cross it); a value from 1,000 up is written whole
    (before: "2.99e+03" for 2,989 s)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fprime_lite.tools.campaign.plots import _heatmap

    fig, ax = plt.subplots()
    _heatmap(fig, ax, _frame({(1, 1): 2989.4, (1, 2): np.nan, (2, 1): 5.25, (2, 2): 612.0}, "detumble_complete_s"),
             "x", "y", "detumble_complete_s", "p95")
    assert ax.get_title().startswith("p95 of detumble_complete_s")
    labels = {t.get_text(): t for t in ax.texts}
    assert set(labels) == {"2,989", "never", "5.25", "612"}
    box = labels["never"].get_bbox_patch()
    assert box is not None and box.get_facecolor()[:3] == (1.0, 1.0, 1.0)
    plt.close(fig)
    fig, ax = plt.subplots()
    _heatmap(fig, ax, _frame({(1, 1): np.nan, (2, 1): np.nan}, "coil_energy_j"), "x", "y", "coil_energy_j", "median")
    assert ax.get_title().startswith("median of coil_energy_j: no value")
    plt.close(fig)


def test_line_plots_group_by_grid_point_with_the_files_percentiles():
    """CAMP-134: a metric against x with a second grid key draws one median line per value of that key,
    labelled with it, and the band of the percentiles the plot asks for."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fprime_lite.tools.campaign.plots import _line

    rng = np.random.default_rng(1)
    df = pd.DataFrame([{"x": x, "mode": mode, "m": x * (2 if mode == "b" else 1) + rng.normal(), "point": 0}
                       for x in (1.0, 2.0, 4.0) for mode in ("a", "b") for _ in range(20)])
    fig, ax = plt.subplots()
    _line(ax, df, "x", "m", ["x", "mode"], (10, 90))
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "mode=a (median)" in labels and "mode=b (median)" in labels and "10–90 % over seeds" in labels
    medians = {line.get_label(): line.get_ydata() for line in ax.get_lines()}
    b = df[df["mode"] == "b"].groupby("x")["m"].median().to_numpy()
    assert np.allclose(medians["mode=b (median)"], b)
    plt.close(fig)
