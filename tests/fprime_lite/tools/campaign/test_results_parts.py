"""results.parts/: rows recorded as parquet parts, never rewritten; a SIGKILL loses at most the batch
being written and never damages a committed part; a resume reads the parts and keeps each run id's
last record."""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from fprime_lite.tools.campaign import CampaignError
from fprime_lite.tools.campaign.results import ResultStore, read_results
from tests.fprime_lite.tools.campaign.conftest import REPO

pytest.importorskip("pyarrow", reason="pyarrow is a dependency: pip install -e .[test]")


def _row(i: int, status: str = "ok") -> dict:
    return {"run_id": f"r{i:05d}", "point": i % 7, "seed_index": i // 7, "seed": i, "status": status,
            "error": None if status == "ok" else "boom", "values": {"x": float(i)},
            "metrics": {"m": 2.0 * i if status == "ok" else None}, "notes": "{}", "requested": "{}",
            "wall_s": 1e-4, "cpu_s": 1e-4, "worker": "w", "worker_address": None}


def _valid(df) -> None:
    """Every row is one that was added, whole, once."""
    assert df["run_id"].is_unique
    assert (df["m"] == 2.0 * df["x"]).all() and (df["run_id"] == [f"r{int(x):05d}" for x in df["x"]]).all()


CHILD = textwrap.dedent("""\
    import sys, time
    sys.path.insert(0, {repo!r})
    from tests.fprime_lite.tools.campaign.test_results_parts import _row
    from fprime_lite.tools.campaign.results import ResultStore
    import fprime_lite.osal.atomic as atomic
    out, n, mode = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    if mode == "hang_in_third_part":  # the third part: half written, then the process stops before its rename
        real, calls = atomic.os.replace, []
        def replace(src, dst):
            calls.append(dst)
            if len(calls) == 3:
                with open(src, "r+b") as fh:
                    fh.truncate(fh.seek(0, 2) // 2)
                print("writing", flush=True)
                time.sleep(600)
            real(src, dst)
        atomic.os.replace = replace
    store = ResultStore(out, ["x"], ["m"], flush_s=0.01 if mode == "stream" else 3600, batch_rows=10)
    done = store.done_ids()
    print("started", len(done), flush=True)
    for i in range(n):
        if f"r{{i:05d}}" not in done:
            store.add(_row(i))
            if mode == "stream":
                time.sleep(0.002)
    store.close()
    print("closed", flush=True)
    """).format(repo=str(REPO))


def _child(tmp_path, out, n: int, mode: str) -> subprocess.Popen:
    script = tmp_path / "child.py"
    script.write_text(CHILD)
    return subprocess.Popen([sys.executable, str(script), str(out), str(n), mode], stdout=subprocess.PIPE, text=True)


def _kill_when(proc: subprocess.Popen, ready, after_s: float = 0.0) -> None:
    """SIGKILL ``proc`` once ``ready()`` has returned and ``after_s`` more seconds have passed (unless it ended)."""
    try:
        assert proc.stdout.readline().startswith("started")
        ready()
        try:
            proc.wait(timeout=after_s) if after_s else None
        except subprocess.TimeoutExpired:
            pass
        if proc.poll() is None:
            proc.send_signal(signal.SIGKILL)
            proc.wait(timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.stdout.close()


def test_a_kill_while_a_part_is_written_loses_only_that_batch(tmp_path):
    """CAMP-140: SIGKILL while the third part is half written: the two committed parts (20 rows) read back
    whole, the torn temporary file is removed by the next writer (not by a reader, who may be on another
    host than a live writer), and a resume records the rest: 40 rows, each once."""
    out = tmp_path / "o"
    proc = _child(tmp_path, out, 40, "hang_in_third_part")

    def writing() -> None:
        assert proc.stdout.readline().strip() == "writing"
    _kill_when(proc, writing)
    parts = out / "results.parts"
    leftovers = [p.name for p in parts.iterdir() if not p.name.startswith("part-")]
    assert len(leftovers) == 1  # the torn part, never renamed
    assert len(read_results(out)) == 20 and (parts / leftovers[0]).exists()  # a reader removes nothing
    store = ResultStore(out, ["x"], ["m"])
    assert sorted(store.done_ids()) == [f"r{i:05d}" for i in range(20)]
    assert sorted(p.name for p in parts.iterdir()) == ["part-00000000.parquet", "part-00000001.parquet"]
    _valid(read_results(out))
    for i in range(40):
        if i >= 20:
            store.add(_row(i))
    df = store.close()
    assert len(df) == 40
    _valid(df)
    assert [p.name for p in parts.iterdir()] == ["part-00000003.parquet"]  # part 2 at close, then the compaction


def _wait_for_a_part(out) -> None:
    deadline = time.monotonic() + 60
    while not list(out.glob("results.parts/part-*.parquet")) and time.monotonic() < deadline:
        time.sleep(0.01)


def test_repeated_kills_never_damage_what_is_recorded(tmp_path):
    """CAMP-141: a writer flushing every 10 ms is SIGKILLed at random moments, twice; after each kill the
    folder reads back (no damaged part), every row whole and once, never fewer than before; a last,
    uninterrupted resume ends with all 300 rows."""
    out = tmp_path / "o"
    rnd = random.Random(31)
    seen = 0
    for _ in range(2):
        _kill_when(_child(tmp_path, out, 300, "stream"), lambda: _wait_for_a_part(out), rnd.uniform(0.05, 0.3))
        df = read_results(out)
        _valid(df)
        assert len(df) >= seen
        seen = len(df)
    proc = _child(tmp_path, out, 300, "stream")
    assert proc.wait(timeout=120) == 0
    proc.stdout.close()
    df = read_results(out)
    assert len(df) == 300
    _valid(df)


def test_a_resume_keeps_each_run_ids_last_record(tmp_path):
    """CAMP-142: a run recorded failed, then ok in a later part (a retry), counts once, as ok, also after
    compaction; the results.parquet written at close says which part it includes."""
    store = ResultStore(tmp_path, ["x"], ["m"])
    store.add(_row(1, "failed"))
    store.add(_row(2))
    store.close()
    store = ResultStore(tmp_path, ["x"], ["m"])
    assert store.done_ids(ok_only=True) == {"r00002"}
    store.add(_row(1))
    df = store.close()
    assert list(df["status"]) == ["ok", "ok"] and list(df["run_id"]) == ["r00001", "r00002"]
    again = ResultStore(tmp_path, ["x"], ["m"])
    assert again.row("r00001")["metrics"] == {"m": 2.0} and len(again) == 2


def test_an_older_folders_journal_is_still_read(tmp_path):
    """CAMP-143: a folder written by the JSON-journal version (rows.jsonl, its last line cut short by a
    kill) resumes: its rows count, the cut line is ignored, later parts override it; at close its rows
    move into the compacted part and the journal is renamed, not read again."""
    lines = [json.dumps(_row(i, "failed" if i == 3 else "ok")) for i in range(5)]
    (tmp_path / "rows.jsonl").write_text("\n".join(lines) + "\n" + lines[0][:20])
    store = ResultStore(tmp_path, ["x"], ["m"])
    assert store.done_ids() == {f"r{i:05d}" for i in range(5)} and store.done_ids(ok_only=True) == \
        {f"r{i:05d}" for i in range(5) if i != 3}
    store.add(_row(3))
    df = store.close()
    assert len(df) == 5 and set(df["status"]) == {"ok"}
    _valid(df)
    assert not (tmp_path / "rows.jsonl").exists() and (tmp_path / "rows.jsonl.migrated").exists()
    again = ResultStore(tmp_path, ["x"], ["m"])  # from the compacted part alone
    assert again.done_ids(ok_only=True) == {f"r{i:05d}" for i in range(5)} and len(again) == 5


def test_a_damaged_part_is_named_not_skipped(tmp_path):
    """CAMP-144: a committed part damaged by something else is refused with its path and what to do."""
    store = ResultStore(tmp_path, ["x"], ["m"])
    store.add(_row(1))
    store.close()
    part = next((tmp_path / "results.parts").iterdir())
    part.write_bytes(part.read_bytes()[:40])
    with pytest.raises(CampaignError, match=rf"{part.name}: this results part cannot be read .* --resume"):
        ResultStore(tmp_path, ["x"], ["m"])
    assert os.path.exists(part)


def test_a_running_campaign_with_no_part_yet_reads_as_an_empty_table(tmp_path):
    """CAMP-145: between the parts folder's creation and the first flush a reader (a user polling, or
    CAMP-051's kill loop) gets an empty table with the result columns, not a FileNotFoundError for a
    results.parquet that only a finished session writes."""
    (tmp_path / "results.parts").mkdir()
    table = read_results(tmp_path)
    assert len(table) == 0 and "run_id" in table.columns and "status" in table.columns


def test_a_folder_without_its_parts_resumes_from_its_table(tmp_path):
    """CAMP-153: a folder holding only results.parquet (committed or copied without results.parts/) resumes from
    that table: its runs count as done, and a session stopped early keeps them in the table it writes (it used
    to fly every run again and write a table of only the new rows over the old one)."""
    import shutil

    from fprime_lite.tools.campaign.results import has_results

    store = ResultStore(tmp_path, ["x"], ["m"])
    for i in range(6):
        store.add(_row(i, "failed" if i == 4 else "ok"))
    store.close()
    shutil.rmtree(tmp_path / "results.parts")
    assert has_results(tmp_path)  # a campaign without --resume is refused this folder
    store = ResultStore(tmp_path, ["x"], ["m"])
    assert store.done_ids() == {f"r{i:05d}" for i in range(6)}
    assert store.done_ids(ok_only=True) == {f"r{i:05d}" for i in range(6) if i != 4}
    store.add(_row(6))
    df = store.close()
    assert len(df) == 7 and df["run_id"].is_unique
    _valid(df[df["status"] == "ok"])
    assert (df.set_index("run_id").loc["r00004", "status"]) == "failed"
    assert read_results(tmp_path).equals(df)
    again = ResultStore(tmp_path, ["x"], ["m"])  # the columns' split (varied | metrics) survived the round trip
    assert again.varied == ["x"] and again.metric_names == ["m"] and len(again) == 7


def test_a_table_that_is_not_a_campaigns_is_refused_and_left(tmp_path):
    """CAMP-154: a results.parquet without a run_id column (not a campaign's table) is refused with its path
    and left as it was."""
    import pandas as pd

    pd.DataFrame({"a": [1.0]}).to_parquet(tmp_path / "results.parquet")
    before = (tmp_path / "results.parquet").read_bytes()
    with pytest.raises(CampaignError, match=r"results.parquet: not a campaign's results table"):
        ResultStore(tmp_path, ["x"], ["m"])
    assert (tmp_path / "results.parquet").read_bytes() == before
