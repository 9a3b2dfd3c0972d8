"""Running campaigns on a LocalCluster: rows, read-back, failures and timeouts, determinism."""

from __future__ import annotations

import json

import numpy as np
import pytest

from fprime_lite.tools.campaign import CampaignError, read_results, run_campaign
from tests.fprime_lite.tools.campaign.conftest import TINY_PLANT, comparable, recorded

pd = pytest.importorskip("pandas", reason="pandas, dask and pyarrow are dependencies: pip install -e .[test]")
pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")


@pytest.fixture(scope="module")
def two_worker_result(tmp_path_factory):
    folder = tmp_path_factory.mktemp("camp")
    path = folder / "c.yaml"
    path.write_text(TINY_PLANT, encoding="utf-8")
    df = run_campaign(path, workers=2, out=folder / "out2", plots=True, summary=False)
    return path, folder, df


def test_local_cluster_of_two_runs_every_run(two_worker_result):
    """CAMP-030: a LocalCluster of 2 runs all 4 runs; one row each, status ok, both workers used,
    the parquet file equals the returned table, and manifest.json records the cluster."""
    path, folder, df = two_worker_result
    assert len(df) == 4 and set(df["status"]) == {"ok"}
    assert list(df[["point", "seed_index"]].itertuples(index=False, name=None)) == [(0, 0), (0, 1), (1, 0), (1, 1)]
    assert df["run_id"].is_unique
    pd.testing.assert_frame_equal(read_results(folder / "out2"), df)
    manifest = json.loads((folder / "out2" / "manifest.json").read_text())
    assert manifest["status"] == "complete" and manifest["cluster"]["type"] == "local"
    assert manifest["cluster"]["workers"] == 2 and manifest["counts"] == {"ok": 4}
    assert manifest["campaign_text"] == path.read_text() and manifest["versions"]["dask"]
    assert (folder / "out2" / "plots").is_dir() and list((folder / "out2" / "plots").glob("*.png"))


def test_the_manifest_records_what_the_runs_resolve_to(two_worker_result):
    """CAMP-094: manifest.json's ``resolved`` names the scenario the plant runs load (``default``, packaged: no
    file the campaign names) with its field model and the digest of its values, defaults filled in."""
    from detumble.sim.scenario import scenario_fingerprint

    _, folder, _ = two_worker_result
    manifest = json.loads((folder / "out2" / "manifest.json").read_text())
    assert manifest["resolved"] == {"scenario default": scenario_fingerprint("default")}
    assert manifest["resolved"]["scenario default"]["field_model"] == "dipole"


def test_dispersions_are_read_back_from_the_built_simulation(two_worker_result):
    """CAMP-031: the recorded initial rate is the plant's own |w(0)| and equals the summary's
    initial_rate_deg_s; the bias read from the plant's magnetometer equals the one requested."""
    _, _, df = two_worker_result
    for _, r in df.iterrows():
        asked = json.loads(r["requested"])
        key = "scenario.initial.rate.magnitude_deg_s"
        assert r[key] == pytest.approx(asked[key], rel=1e-12)
        assert r["scenario.initial.rate.magnitude_deg_s"] == pytest.approx(r["initial_rate_deg_s"], rel=1e-12)
        assert list(r["scenario.sensors.magnetometer.bias_gauss"]) == asked["scenario.sensors.magnetometer.bias_gauss"]
        assert r["gain"] == asked["gain"]
        assert r["coil_energy_j"] > 0 and np.isfinite(r["final_rate_deg_s"])


def test_one_worker_gives_the_same_table(two_worker_result):
    """CAMP-032: --workers 1 and --workers 2 give bit-identical tables (but for wall time and worker)."""
    path, folder, df2 = two_worker_result
    df1 = run_campaign(path, workers=1, out=folder / "out1", plots=False, summary=False)
    pd.testing.assert_frame_equal(comparable(df1), comparable(df2), check_exact=True)


def test_a_failing_and_a_timed_out_run_are_recorded_and_the_campaign_goes_on(write_campaign, tmp_path):
    """CAMP-033: a run whose dispersed inertia violates the triangle inequality fails with its error (the
    pre-flight check builds the nominal inertia, valid, whatever the master seed); a run past timeout_s
    is 'timeout' with null metrics and the reason; the others are ok."""
    path = write_campaign("""\
        campaign: mixed
        master_seed: 3
        run: {kind: plant, scenario: default, law: bdot, duration_s: 20}
        dispersions:
          scenario.spacecraft.inertia_kg_m2: {dist: inertia, nominal: [1.0e-3, 1.0e-3, 1.9e-3], moment_std: 0.3}
        seeds: 6
        metrics: [final_rate_deg_s]
        """)
    df = run_campaign(path, workers=2, out=tmp_path / "o", plots=False, summary=False)
    failed = df[df["status"] == "failed"]
    assert set(df["status"]) == {"ok", "failed"}, df[["status", "error"]]
    assert failed["error"].str.contains("triangle").all() and failed["final_rate_deg_s"].isna().all()
    slow = write_campaign("""\
        campaign: slow
        run: {kind: plant, scenario: default, law: bdot, duration_s: 100000}
        metrics: [final_rate_deg_s]
        timeout_s: 0.5
        """, "slow.yaml")
    df = run_campaign(slow, workers=1, out=tmp_path / "s", plots=False, summary=False)
    (row,) = df.to_dict("records")
    assert row["status"] == "timeout" and "timed out after 0.5 s" in row["error"]
    assert np.isnan(row["final_rate_deg_s"])
    assert "timed out" in json.loads(row["notes"])["final_rate_deg_s"]


def test_a_misspelt_dispersion_key_fails_before_the_campaign_starts(write_campaign, tmp_path):
    """CAMP-034: a dispersed scenario key that does not exist stops the campaign at its file:line
    before any run is submitted: no results are written."""
    path = write_campaign(TINY_PLANT.replace("magnetometer.bias_gauss", "magnetometer.bias_gaus"))
    with pytest.raises(CampaignError) as info:
        run_campaign(path, workers=1, out=tmp_path / "o", plots=False, summary=False)
    (problem,) = info.value.problems
    assert problem.startswith(f"{path}:8: ") and "has no key 'bias_gaus'" in problem
    assert not (tmp_path / "o").exists()


def test_existing_results_need_resume(two_worker_result):
    """CAMP-035: a folder with results is not overwritten: the error says to add --resume."""
    path, folder, _ = two_worker_result
    with pytest.raises(CampaignError, match="add --resume"):
        run_campaign(path, workers=1, out=folder / "out2", plots=False, summary=False)
    df = run_campaign(path, workers=1, out=folder / "out2", resume=True, plots=False, summary=False)
    assert len(df) == 4  # nothing left to run: the same rows


def test_an_out_that_is_a_file_or_cannot_be_made_is_refused_before_any_run(two_worker_result, tmp_path, monkeypatch):
    """CAMP-105: ``--out`` naming a file, or a folder that cannot be created, is a campaign problem that says
    so before the pre-flight check or any run flies; the file is left as it was."""
    import fprime_lite.tools.campaign.engine as engine

    path, _, _ = two_worker_result
    checked = []
    monkeypatch.setattr(engine, "preflight", lambda *a: checked.append(a))
    a_file = tmp_path / "a_file"
    a_file.write_text("keep me\n")
    with pytest.raises(CampaignError, match="is a file, not a folder"):
        run_campaign(path, workers=1, out=a_file, plots=False, summary=False)
    assert checked == []
    with pytest.raises(CampaignError, match=r"cannot create the folder \(Not a directory\)"):
        run_campaign(path, workers=1, out=a_file / "sub", plots=False, summary=False)
    assert a_file.read_text() == "keep me\n"


def test_one_process_writes_a_campaign_folder_at_a_time(two_worker_result, tmp_path):
    """CAMP-104: while a campaign process holds its folder, a second one (here a --resume) is refused before it
    reads or writes anything, with an error naming the holder; the rows are untouched; once the holder is gone
    the folder is free again (the kernel drops the lock with the process, so a killed campaign leaves none)."""
    import subprocess
    import sys
    import textwrap

    path, folder, _ = two_worker_result
    out = folder / "out2"
    before = recorded(out)
    assert before
    holder = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""
        import pathlib, sys, time
        from fprime_lite.tools.campaign.folder_lock import campaign_folder_lock
        with campaign_folder_lock(pathlib.Path({str(out)!r})):
            print("held", flush=True)
            sys.stdin.read()
        """)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        with pytest.raises(CampaignError, match=rf"already writing into this folder \(pid {holder.pid} on .*--resume"):
            run_campaign(path, workers=1, out=out, resume=True, plots=False, summary=False)
        assert recorded(out) == before
    finally:
        holder.communicate("")
    df = run_campaign(path, workers=1, out=out, resume=True, plots=False, summary=False)
    assert len(df) == 4
