"""Interrupting `fprime-lite campaign` (issue 28): SIGINT / SIGTERM keep every row that came back,
write the manifest as interrupted, shut the embedded cluster down, say how to resume and exit
130 / 143 without a traceback; the resumes then finish the campaign with no row lost or doubled."""

from __future__ import annotations

import contextlib
import json
import os
import pathlib
import shlex
import signal
import subprocess
import sys
import time

import pytest

from fprime_lite.tools.campaign import read_results
from fprime_lite.tools.campaign.plan import plan_runs
from fprime_lite.tools.campaign.spec import load_campaign
from tests.fprime_lite.tools.campaign.conftest import REPO, TINY_PLANT

pytest.importorskip("distributed", reason="dask[distributed] is a dependency: pip install -e .[test]")

SRC = str(pathlib.Path(__import__("fprime_lite").__file__).resolve().parents[1])  # the code under test
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [SRC, str(REPO), os.environ.get("PYTHONPATH")])))

#: The tiny plant campaign at 120 runs of 120 simulated seconds (≈ 40 ms each on one worker): long
#: enough to be signalled after the first results part, short enough to finish in a few seconds.
CAMPAIGN = TINY_PLANT.replace("duration_s: 20", "duration_s: 120").replace("seeds: 2", "seeds: 60")
assert CAMPAIGN.count("120") == 1 and "seeds: 60" in CAMPAIGN


def _parts(out: pathlib.Path) -> list[pathlib.Path]:
    folder = out / "results.parts"
    return sorted(folder.glob("part-*.parquet")) if folder.is_dir() else []


def _signalled_campaign(argv: list[str], cwd: pathlib.Path, out: pathlib.Path, sig: signal.Signals, *,
                        group: bool) -> tuple[int, str, int]:
    """Start ``fprime-lite campaign ARGV`` in its own session, send ``sig`` once a results part more
    than it started with is on disk (to the whole process group, as a terminal's Ctrl-C does, or to the
    campaign process only, as ``kill PID`` does); ``(exit status, stderr, processes left in the group)``."""
    before = len(_parts(out))
    proc = subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.cli", "campaign", *argv], cwd=cwd, env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        deadline = time.monotonic() + 180
        while len(_parts(out)) <= before and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        assert proc.poll() is None, "the campaign ended before it could be signalled: make it longer"
        (os.killpg if group else os.kill)(proc.pid, sig)
        _, err = proc.communicate(timeout=120)
        deadline = time.monotonic() + 30
        left: list[str] = []
        while time.monotonic() < deadline:
            left = subprocess.run(["pgrep", "-g", str(proc.pid)], capture_output=True, text=True).stdout.split()
            if not left:
                break
            time.sleep(0.2)
        return proc.returncode, err, len(left)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)


def _resume_argv(err: str) -> list[str]:
    """The arguments of the command the interrupted campaign printed to continue it."""
    line = next(ln for ln in err.splitlines() if "continue with: " in ln)
    words = shlex.split(line.split("continue with: ", 1)[1])
    assert words[:2] == ["fprime-lite", "campaign"]
    return words[2:]


def _same_rows(before, after) -> None:
    """Every row of ``before`` is in ``after``, unchanged (timings and worker included: not flown again)."""
    kept = before.set_index("run_id")
    assert after.set_index("run_id").loc[kept.index].equals(kept)


def _manifest(out: pathlib.Path) -> dict:
    return json.loads((out / "manifest.json").read_text())


def test_sigint_then_sigterm_then_resume_to_completion(tmp_path):
    """CAMP-150: Ctrl-C (SIGINT to the whole group, workers included) after the first results exits
    130 with no traceback, keeps the rows that came back (the manifest says interrupted, with done /
    planned) and leaves no process behind; the printed resume command, killed with SIGTERM after its
    first new rows, exits 143 the same way; run once more it finishes:
    every planned run exactly once, the rows kept across both interruptions unchanged."""
    path = tmp_path / "c.yaml"
    path.write_text(CAMPAIGN, encoding="utf-8")
    out = tmp_path / "o"
    planned = {t["run_id"] for t in plan_runs(load_campaign(path), out / "runs", draw=False)}
    assert len(planned) == 120

    rc, err, left = _signalled_campaign([str(path), "--workers", "1", "--out", str(out), "--no-plots",
                                         "--no-progress"], tmp_path, out, signal.SIGINT, group=True)
    assert rc == 130, err
    assert "Traceback" not in err
    assert "interrupted by SIGINT after" in err
    assert left == 0  # the campaign and its worker's processes are gone
    first = read_results(out)
    m = _manifest(out)
    assert m["status"] == "interrupted"
    assert m["interrupted"] == {"signal": "SIGINT", "done": len(first), "planned": 120}
    assert 0 < len(first) < 120
    assert first["status"].eq("ok").all()  # a worker ended by the same Ctrl-C fails no run
    argv = _resume_argv(err)
    assert "--resume" in argv and argv[argv.index("--out") + 1] == str(out)

    rc, err, left = _signalled_campaign(argv, tmp_path, out, signal.SIGTERM, group=False)
    assert rc == 143, err
    assert "Traceback" not in err
    assert "interrupted by SIGTERM after" in err
    assert left == 0
    second = read_results(out)
    m = _manifest(out)
    assert m["status"] == "interrupted"
    assert m["interrupted"] == {"signal": "SIGTERM", "done": len(second), "planned": 120}
    assert len(first) < len(second) < 120
    _same_rows(first, second)

    r = subprocess.run([sys.executable, "-m", "fprime_lite.tools.cli", "campaign", *_resume_argv(err)],
                       cwd=tmp_path, env=ENV, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    final = read_results(out)
    assert len(final) == 120 and set(final["run_id"]) == planned  # none lost, none twice
    m = _manifest(out)
    assert m["status"] == "complete" and "interrupted" not in m
    assert [h["status"] for h in m["history"]] == ["interrupted", "interrupted", "complete"]
    assert sum(h["ran"] for h in m["history"]) == 120  # no run recorded twice across the sessions
    _same_rows(second, final)
