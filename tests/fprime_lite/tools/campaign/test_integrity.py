"""Campaigns you can trust (issue 31): duplicate points, names checked before flying, resume that
renumbers and refuses another campaign, the manifest, CPU-independent dispersions, exit status."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys
import textwrap

import pytest

from fprime_lite.tools.campaign import CampaignError, load_campaign, run_campaign
from tests.fprime_lite.tools.campaign.conftest import TOPOLOGY

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

PROBE = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"
SRC = str(pathlib.Path(__import__("fprime_lite").__file__).resolve().parents[1])  # the code under test


@pytest.fixture
def no_cluster(monkeypatch):
    """Any attempt to start or reach a Dask cluster fails the test: nothing may fly."""
    import fprime_lite.tools.campaign.cluster as cluster

    def refuse(*args, **kwargs):
        raise AssertionError("a run reached the cluster")
    monkeypatch.setattr(cluster, "dask_client", refuse)


def test_a_grid_point_listed_twice_flies_once(write_campaign, tmp_path):
    """CAMP-110: the flight defaults listed alone and again inside a sweep (as 1 and 1.0) are one point:
    two runs, not three, every one ok (before: duplicate run ids, 'FutureCancelledError' and the gain
    lost), and the manifest says which listed point was merged."""
    path = write_campaign(f"""\
        campaign: dup
        run: {{kind: "{PROBE}"}}
        grid:
          - {{x: [1]}}
          - {{x: [1.0, 2.0]}}
        metrics: [value]
        """)
    df = run_campaign(path, workers=1, out=tmp_path / "o", plots=False, summary=False)
    assert len(df) == 2 and set(df["status"]) == {"ok"} and list(df["value"]) == [2.0, 4.0]
    assert list(df["point"]) == [0, 1] and df["run_id"].is_unique
    manifest = json.loads((tmp_path / "o" / "manifest.json").read_text())
    assert manifest["merged_points"] == [{"listed": 1, "point": 0}]


def test_a_failed_run_never_exits_0(write_campaign, tmp_path, capsys):
    """CAMP-111: one failed run among ok ones makes `fprime-lite campaign` exit 1 and say how many."""
    from fprime_lite.tools.cli import main

    path = write_campaign(f"""\
        campaign: one_fails
        run: {{kind: "{PROBE}", mode: fail_if_marker}}
        grid:
          x: [1.0, 2.0]
        metrics: [value]
        """)
    (tmp_path / "marker").write_text("")
    assert main(["campaign", str(path), "--workers", "1", "--out", str(tmp_path / "o"), "--no-plots"]) == 1
    assert "2 of 2 runs did not finish ok" in capsys.readouterr().err
    (tmp_path / "marker").unlink()
    assert main(["campaign", str(path), "--workers", "1", "--out", str(tmp_path / "o"), "--retry-failed",
                 "--no-plots"]) == 0


def _refused(path, tmp_path) -> str:
    with pytest.raises(CampaignError) as info:
        run_campaign(path, workers=1, out=tmp_path / "never", plots=False, summary=False)
    assert not (tmp_path / "never").exists()
    return "\n".join(info.value.problems)


def test_a_misspelt_metric_is_refused_before_flying(write_campaign, tmp_path, no_cluster):
    """CAMP-112: a metric that is neither a named metric nor a key of the run summary is refused at the
    'metrics' line with a did-you-mean, before any run flies (before: a null column and exit 0)."""
    path = write_campaign("""\
        campaign: typo
        run: {kind: plant, scenario: default, law: bdot, duration_s: 20}
        metrics: [final_rate_deg_s, initial_rate_deg_ss]
        """)
    text = _refused(path, tmp_path)
    assert f"{path}:3: metric 'initial_rate_deg_ss' is neither a named metric nor a key of the run summary" in text
    assert "did you mean 'initial_rate_deg_s'?" in text


def test_misspelt_stop_on_events_and_stop_when_are_refused_before_flying(write_campaign, tmp_path, no_cluster):
    """CAMP-113: a stop_on_events name the topology does not declare and a stop_when key no report
    publishes are refused at their lines with a did-you-mean (before: every run flew its full horizon)."""
    base = f"""\
        campaign: stops
        run:
          kind: deployment
          topology: {TOPOLOGY}
          duration_s: 30
          STOP
        metrics: [final_rate_deg_s]
        """
    misspelt = "stop_on_events: [ReferenceDeployment.detumbleManager.DetumbleComplete]"
    path = write_campaign(base.replace("STOP", misspelt))
    text = _refused(path, tmp_path)
    assert f"{path}:6: stop_on_events: the topology has no event ReferenceDeployment.detumbleManager." \
           "DetumbleComplete — did you mean ReferenceDeployment.detumbleManager.DetumbleCompleted?" in text
    path = write_campaign(base.replace("STOP", "stop_when: ['rate_deg_z < 1']"), "b.yaml")
    text = _refused(path, tmp_path)
    assert "b.yaml:6: stop_when: no report of this topology publishes 'rate_deg_z' — did you mean 'rate_deg_s'?" in text


def test_plot_settings_are_checked_with_the_file(write_campaign):
    """CAMP-114: a heatmap agg that does not exist, a heatmap over a text axis, a percentile band out of
    range and an agg on a line plot are refused when the file is read (before: a crash after all runs)."""
    path = write_campaign(f"""\
        campaign: plots
        run: {{kind: "{PROBE}"}}
        grid:
          x: [1.0, 2.0]
          mode: [ok, fail_if_marker]
        metrics: [value]
        plots:
          - {{type: heatmap, x: x, y: mode, metric: value}}
          - {{type: heatmap, x: x, y: x, metric: value, agg: meen}}
          - {{type: line, x: x, metric: value, percentiles: [5, 105], agg: p90}}
          - {{type: heatmap, x: x, y: mode, metric: valeu, agg: p90}}
        """)
    with pytest.raises(CampaignError) as info:
        load_campaign(path)
    text = "\n".join(info.value.problems)
    assert f"{path}:8: plot y 'mode' takes the value 'ok', not a number" in text
    assert f"{path}:9: heatmap agg 'meen': use one of median, mean, p95, max, min or pNN" in text
    assert "did you mean 'mean'?" in text and f"{path}:9: a heatmap's x and y must be two different keys" in text
    assert f"{path}:10: 'percentiles' is [low, high] with 0 <= low < high <= 100, got [5, 105]" in text
    assert f"{path}:10: 'agg' is a heatmap's" in text
    assert f"{path}:11: plot metric 'valeu' is not in 'metrics' — did you mean 'value'?" in text


def test_every_grid_value_is_built_before_flying(write_campaign, tmp_path, no_cluster):
    """CAMP-115: a bad value anywhere on an axis (a control period of 0.55 s, not a whole number of
    0.1 s steps, second on its axis) stops the campaign at that axis's line (before: only its runs failed)."""
    path = write_campaign("""\
        campaign: bad_value
        run: {kind: plant, scenario: default, law: bdot, duration_s: 20}
        grid:
          gain: [1.0, 3.0]
          scenario.control.period_s: [0.5, 0.55]
        metrics: [final_rate_deg_s]
        """)
    text = _refused(path, tmp_path)
    assert f"{path}:5: " in text and "0.55" in text


def test_whether_a_campaign_starts_never_depends_on_the_master_seed(write_campaign):
    """CAMP-116: the pre-flight check builds dispersed keys at their nominal values: a dispersed inertia
    that often violates the triangle inequality passes the check under every master seed (its bad draws
    fail as runs); before, the first run's draw decided."""
    from fprime_lite.tools.campaign.engine import preflight
    from fprime_lite.tools.campaign.plan import plan_runs

    for master_seed in range(6):
        path = write_campaign(f"""\
            campaign: inertia
            master_seed: {master_seed}
            run: {{kind: plant, scenario: default, law: bdot, duration_s: 5}}
            dispersions:
              scenario.spacecraft.inertia_kg_m2: {{dist: inertia, nominal: [1.0e-3, 1.0e-3, 1.9e-3], moment_std: 0.3}}
            metrics: [final_rate_deg_s]
            """, f"c{master_seed}.yaml")
        c = load_campaign(path)
        preflight(c, plan_runs(c, path.parent / "runs", draw=False))


def test_resume_renumbers_points_and_refuses_another_campaign(write_campaign, tmp_path):
    """CAMP-117: after a point is inserted at the front of the grid, --resume gives the old rows their new
    point numbers (one configuration per point in the table); CAMP-118: resuming a different campaign in
    the folder is refused, naming both, unless force=True."""
    text = f"""\
        campaign: renumber
        run: {{kind: "{PROBE}"}}
        grid:
          x: AXIS
        metrics: [value]
        """
    path = write_campaign(text.replace("AXIS", "[1.0, 2.0]"))
    out = tmp_path / "o"
    run_campaign(path, workers=1, out=out, plots=False, summary=False)
    path.write_text(textwrap.dedent(text.replace("AXIS", "[0.5, 1.0, 2.0]")))
    df = run_campaign(path, workers=1, out=out, resume=True, plots=False, summary=False)
    assert list(df["point"]) == [0, 1, 2] and list(df["x"]) == [0.5, 1.0, 2.0]
    assert df.groupby("point")["x"].nunique().max() == 1

    other = write_campaign(text.replace("renumber", "another").replace("AXIS", "[7.0]"), "other.yaml")
    with pytest.raises(CampaignError, match=r"holds campaign 'renumber', not 'another'.*none of its 3 runs.*--force"):
        run_campaign(other, workers=1, out=out, resume=True, plots=False, summary=False)
    df = run_campaign(other, workers=1, out=out, resume=True, force=True, plots=False, summary=False)
    assert list(df["x"]) == [7.0]


def test_the_manifest_records_software_workers_inputs_and_each_session(write_campaign, tmp_path):
    """CAMP-119: manifest.json has the commit and dirty flag of the fprime-lite source that ran (not of
    the campaign file's folder), each worker's package versions and CPU, the SHA-256 of every input file,
    the client's CPU, and one history entry per session (a resume appends; the first start is kept)."""
    import hashlib

    import fprime_lite

    seq = tmp_path / "input.seq"
    seq.write_text("hello\n")
    path = write_campaign(f"""\
        campaign: manifest
        run: {{kind: "{PROBE}"}}
        grid:
          x: [1.0]
          mode: [{seq.name}]
        seeds: 1
        metrics: [value]
        """)
    out = tmp_path / "o"
    run_campaign(path, workers=1, out=out, plots=False, summary=False)
    first = json.loads((out / "manifest.json").read_text())
    source = pathlib.Path(fprime_lite.__file__).resolve().parent
    head = subprocess.run(["git", "-C", str(source), "rev-parse", "HEAD"], capture_output=True, text=True)
    assert first["software"]["commit"] == (head.stdout.strip() or None)
    assert isinstance(first["software"]["dirty"], bool) and first["software"]["source"] == str(source)
    (group,) = first["workers"]
    assert group["versions"]["numpy"] and group["cpu"] and len(group["workers"]) == 1
    assert first["client"]["cpu"] and first["client"]["cpus"] >= 1
    assert first["inputs"] == {str(path): hashlib.sha256(path.read_bytes()).hexdigest(),
                               str(seq): hashlib.sha256(b"hello\n").hexdigest()}
    assert len(first["history"]) == 1 and first["history"][0]["ran"] == 1
    path.write_text(path.read_text().replace("seeds: 1", "seeds: 2"))
    run_campaign(path, workers=1, out=out, resume=True, plots=False, summary=False)
    second = json.loads((out / "manifest.json").read_text())
    assert second["started"] == first["started"] and len(second["history"]) == 2
    assert [h["ran"] for h in second["history"]] == [1, 1] and second["history"][1]["resumed_with"] == 1


SAMPLER = """
import hashlib, json, sys
from fprime_lite.tools.campaign.dispersions import parse_dispersion
from fprime_lite.tools.campaign.seeding import key_generator, run_seed_sequence
specs = {
    "v": {"dist": "random_vector", "magnitude": {"dist": "uniform", "low": 1e-3, "high": 1e3}},
    "q": {"dist": "random_rotation"},
    "a": {"dist": "angle_about_random_axis", "angle_deg": 30, "nominal": [0.6, 0.8, 0.0, 0.0]},
    "j": {"dist": "inertia", "nominal": [[2.2e-3, 2e-5, -1.5e-5], [2e-5, 2.15e-3, 1e-5], [-1.5e-5, 1e-5, 2.05e-3]],
          "moment_std": 0.05, "axis_angle_deg": 10},
}
out = []
for key, spec in specs.items():
    d = parse_dispersion(spec, key)
    for i in range(400):
        out.append(d.sample(key_generator(run_seed_sequence(1, {"i": i}, 0), key)))
print(hashlib.sha256(json.dumps(out, default=float.hex).encode()).hexdigest())
"""


def test_dispersions_are_bit_identical_whatever_blas_kernel_the_cpu_selects(tmp_path):
    """CAMP-120: the dispersed values (vectors, rotations, inertias) drawn under OpenBLAS's generic kernels
    (OPENBLAS_CORETYPE=Prescott) and its Haswell and SkylakeX kernels are bit-identical: no draw goes
    through BLAS (np.linalg.norm and @ gave 35 different last bits across CPUs)."""
    script = tmp_path / "sample.py"
    script.write_text(SAMPLER)
    digests = set()
    for core in ("Prescott", "Haswell", "SkylakeX"):
        env = dict(os.environ, OPENBLAS_CORETYPE=core, PYTHONPATH=SRC)
        r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=120)
        assert r.returncode == 0, r.stderr
        digests.add(r.stdout.strip())
    assert len(digests) == 1


def test_dispersions_call_no_blas(monkeypatch):
    """CAMP-121: with numpy's BLAS/LAPACK entry points made to raise, every distribution still draws,
    and a random vector's direction is the pure-Python normalised normal draw, bit for bit."""
    import math

    import numpy as np

    from fprime_lite.tools.campaign.dispersions import parse_dispersion

    def boom(*args, **kwargs):
        raise AssertionError("BLAS called")
    for name in ("norm", "eigh", "eig", "svd", "qr"):
        monkeypatch.setattr(np.linalg, name, boom)
    monkeypatch.setattr(np, "dot", boom)
    for spec in ({"dist": "random_vector", "magnitude": 2.0}, {"dist": "random_rotation"},
                 {"dist": "angle_about_random_axis", "angle_deg": 5},
                 {"dist": "inertia", "nominal": [[2.2e-3, 2e-5, 0], [2e-5, 2.1e-3, 0], [0, 0, 2e-3]],
                  "moment_std": 0.1}):
        parse_dispersion(spec, "k").sample(np.random.default_rng(5))
    v = parse_dispersion({"dist": "random_vector", "magnitude": 1.0}, "k").sample(np.random.default_rng(9))
    g = [float(x) for x in np.random.default_rng(9).standard_normal(3)]
    n = math.sqrt(math.fsum(x * x for x in g))
    assert v == [x / n for x in g] or v == [x / math.hypot(*g) for x in g]


def test_the_plan_cache_gives_the_same_plan_and_follows_every_input(write_campaign, tmp_path):
    """CAMP-142: the run ids and seeds a campaign folder caches (plan-cache.json, so a 100k-run resume does
    not derive every seed sequence again) equal a fresh plan's; a changed master seed, grid or seed count
    ignores the cache."""
    from fprime_lite.tools.campaign.plan import plan_runs, write_plan_cache

    text = f"""\
        campaign: cache
        master_seed: MS
        run: {{kind: "{PROBE}"}}
        grid:
          x: [1.0, 2.0]
        seeds: 3
        metrics: [value]
        """
    path = write_campaign(text.replace("MS", "1"))
    c = load_campaign(path)
    cache = tmp_path / "plan-cache.json"
    fresh = plan_runs(c, tmp_path, draw=False)
    write_plan_cache(cache, c, fresh)
    data = json.loads(cache.read_text())
    data["runs"][0][1] += 1  # a seed the cache alone holds: visible when the cache is used
    cache.write_text(json.dumps(data))
    assert plan_runs(c, tmp_path, draw=False, cache=cache)[0]["seed"] == fresh[0]["seed"] + 1
    for edit in (text.replace("MS", "2"), text.replace("MS", "1").replace("[1.0, 2.0]", "[1.0, 3.0]"),
                 text.replace("MS", "1").replace("seeds: 3", "seeds: 2")):
        changed = load_campaign(write_campaign(edit, "e.yaml"))
        expected = [(t["run_id"], t["seed"]) for t in plan_runs(changed, tmp_path, draw=False)]
        assert [(t["run_id"], t["seed"]) for t in plan_runs(changed, tmp_path, draw=False, cache=cache)] == expected
