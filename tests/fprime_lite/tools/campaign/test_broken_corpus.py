"""The corpus of broken campaign files (tests/data/campaign_broken/, issue 31 target: none reaches a
worker). Each file's first line says what the refusal must say: ``# expect: TEXT``."""

from __future__ import annotations

import pathlib

import pytest

from fprime_lite.tools.campaign import CampaignError, run_campaign

CORPUS = pathlib.Path(__file__).resolve().parents[3] / "data" / "campaign_broken"
FILES = sorted(CORPUS.glob("*.yaml"))


def test_the_corpus_has_at_least_35_files():
    """CAMP-140: the corpus holds 35 or more distinct broken campaigns."""
    assert len(FILES) >= 35


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_a_broken_campaign_never_reaches_a_worker(path, tmp_path, monkeypatch):
    """CAMP-141: each broken file is refused with its expected message (file:line and what to do) before a
    cluster is started or a run submitted; no campaign folder is created."""
    import fprime_lite.tools.campaign.cluster as cluster

    def reached(*args, **kwargs):
        raise AssertionError(f"{path.name} reached the cluster")
    monkeypatch.setattr(cluster, "dask_client", reached)
    expect = path.read_text().splitlines()[0].removeprefix("# expect:").strip()
    with pytest.raises(CampaignError) as info:
        run_campaign(path, workers=1, out=tmp_path / "o", plots=False, summary=False)
    assert expect in str(info.value), str(info.value)
    assert all(str(path) in p or path.name in p for p in info.value.problems), info.value.problems
    assert not (tmp_path / "o").exists()
