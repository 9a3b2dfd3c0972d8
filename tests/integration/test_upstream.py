"""Other projects' own integration suites, run unchanged through ``fprime-lite conformance``.

Marked ``upstream`` (minutes; excluded from the default ``python -m pytest``; ``.ci/run`` runs
``python -m pytest -m upstream`` after the default suite). The suites live in ``../shared/upstream``
seen from the project root (never copied into the project); the tests that run them skip, saying
so, where that folder is absent.

- F´'s reusable suites (``fprime_int``: PrmDb, EventManager, Health, CdhCore, FileHandling) on
  the reference deployment flying ``Svc.TlmPacketizer`` as F´'s Ref does
  (``deployments/proves_ref/topology_packetized.yaml``), with both framings: every test must pass
  (``upstream/fprime_int_expected_failures.txt`` lists none now). All but FileHandling run on board roots
  of the run's own (``--board-root``), Health alone on one made with the ``/tmp/1MiB.txt`` it appends
  (F´'s CI makes it), so two runs at once share no file; FileHandling then runs alone with the host's
  ``/tmp`` shared, as it requires.
- PROVES's suite (``proves_int``, 45 tests) needs Python >= 3.12: it runs with the interpreter
  ``$FPRIME_LITE_TEST_PYTHON`` names, else ``.venv-upstream/bin/python`` (``.ci/run`` builds it with
  ``pip install -e '.[upstream]'``), and skips, saying so, without one. It runs with ``--sim-plant``
  (the six manual tests through ``detumble.tools.pytest_plant``: none may be skipped), on a board root
  of its own with no start-up sequence (the board as PROVES's CI formats it; the default tumble), and
  with ``upstream/proves_expected_failures.txt``: each listed test gives the reason it fails today;
  any other failure fails the job.
- The verb's own clean-up: SIGTERM during a run ends every process it started, and so does its
  watchdog when the verb is killed outright (SIGKILL).
"""

from __future__ import annotations

import os
import pathlib
import signal
import subprocess
import sys
import time

import pytest

from fprime_lite.tools.conformance import read_junit

ROOT = pathlib.Path(__file__).parents[2]
UPSTREAM = ROOT.parent / "shared" / "upstream"
TOPOLOGY = ROOT / "deployments" / "proves_ref" / "topology.yaml"
#: proves_ref with Svc.TlmPacketizer, as F´'s Ref (the home of F´'s suites) flies (docs/ground.md)
PACKETIZED = ROOT / "deployments" / "proves_ref" / "topology_packetized.yaml"
LISTS = pathlib.Path(__file__).parent / "upstream"
PROVES_PYTHON = os.environ.get("FPRIME_LITE_TEST_PYTHON") or str(ROOT / ".venv-upstream" / "bin" / "python")

pytestmark = pytest.mark.upstream
needs_upstream = pytest.mark.skipif(not UPSTREAM.is_dir(), reason=f"{UPSTREAM} is absent: the upstream suites are "
                                    f"kept in shared/upstream beside the project (see its README), not in the project")


def conformance(suite: pathlib.Path, out: pathlib.Path, *args: str, timeout: float = 1800,
                topology: pathlib.Path = TOPOLOGY) -> tuple[int, str]:
    """Run the verb in a subprocess; its exit status and output."""
    result = subprocess.run([sys.executable, "-m", "fprime_lite.tools.cli", "conformance", str(suite), "--topology",
                             str(topology), "--out", str(out), *args], capture_output=True, text=True, timeout=timeout,
                            stdin=subprocess.DEVNULL)
    return result.returncode, result.stdout + result.stderr


def outcomes(out: pathlib.Path) -> dict[str, int]:
    counts = {"passed": 0, "failed": 0, "errors": 0, "skipped": 0, "xfailed": 0}
    for c in read_junit(out / "junit.xml").values():
        for key in counts:
            counts[key] += getattr(c, key)
    return counts


def board_with_health_files(board: pathlib.Path) -> pathlib.Path:
    """A fresh board file system for F´'s suites: Health appends ``/tmp/1MiB.txt`` (which F´'s CI makes)
    to ``/tmp/2MiB.txt``, then that file to itself eight times (256 MiB); on a board root both lie in
    the run's own folder, so two runs never share them and no leftover doubles."""
    (board / "tmp").mkdir(parents=True)
    (board / "tmp" / "1MiB.txt").write_bytes(os.urandom(1 << 20))
    return board


@needs_upstream
@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_fprime_reusable_suites_pass(framing, tmp_path):
    """F´'s suites in three runs: those that only command the flight software on a board root of the
    run's own; Health alone on another (its appends keep the board's FileManager busy for minutes at the
    modelled SD-card rate, which is what makes its ping late, so a suite after it would wait); then
    FileHandling, which needs the host's /tmp shared with the flight software."""
    suite = UPSTREAM / "fprime_int"
    deselect = ["--deselect", "Health/test_cmd_health.py::test_send_health_command",
                "--deselect", "FileHandling/test_file_handling.py::test_uplink_file",
                "--deselect", "FileHandling/test_file_handling.py::test_downlink_file"]
    (tmp_path / "board" / "tmp").mkdir(parents=True)  # F´'s Ref runs on Linux: PrmDb moves its file to /tmp
    status, output = conformance(suite, tmp_path / "work", "--framing", framing, "--expected-failures",
                                 str(LISTS / "fprime_int_expected_failures.txt"), "--board-root",
                                 str(tmp_path / "board"), "--", *deselect, topology=PACKETIZED)
    counts = outcomes(tmp_path / "work")
    print(f"\nfprime_int on a board root, {framing} framing: {counts}")
    assert status == 0, output[-8000:]
    # CdhCore's test_telemetry_update included: the packetizer's Health packet comes down every tick
    assert counts["passed"] == 6 and counts["xfailed"] == 0, output[-4000:]

    board = board_with_health_files(tmp_path / "health-board")
    try:
        status, output = conformance(suite / "Health", tmp_path / "work-health", "--framing", framing,
                                     "--board-root", str(board), topology=PACKETIZED)
    finally:
        (board / "tmp" / "2MiB.txt").unlink(missing_ok=True)  # up to 256 MiB
    counts = outcomes(tmp_path / "work-health")
    print(f"fprime_int/Health, {framing} framing: {counts}")
    assert status == 0 and counts["passed"] == 1, output[-8000:]

    status, output = conformance(suite / "FileHandling", tmp_path / "work-files", "--framing", framing,
                                 topology=PACKETIZED)
    counts = outcomes(tmp_path / "work-files")
    print(f"fprime_int/FileHandling, {framing} framing: {counts}")
    assert status == 0 and counts["passed"] == 2, output[-8000:]


@needs_upstream
@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_proves_suite_fails_only_where_listed(framing, tmp_path):
    if not os.path.isfile(PROVES_PYTHON):
        pytest.skip(f"no Python >= 3.12 test-runner venv: {PROVES_PYTHON} is absent (set FPRIME_LITE_TEST_PYTHON, "
                    f"or build it as .ci/run does: python3.12 -m venv .venv-upstream && .venv-upstream/bin/python -m "
                    f"pip install -e '.[upstream]')")
    # the board as on PROVES's CI: its file system formatted (a board root of the run's own, no start-up
    # sequence on it, so the DetumbleManager stays DISABLED), the default tumble; the six manual tests run
    # through the plant-control plugin
    board = tmp_path / "board"
    board.mkdir()
    status, output = conformance(UPSTREAM / "proves_int", tmp_path / "work", "--framing", framing, "--python",
                                 PROVES_PYTHON, "--expected-failures", str(LISTS / "proves_expected_failures.txt"),
                                 "--sim-plant", "--board-root", str(board), "--run-arg=--no-startup")
    counts = outcomes(tmp_path / "work")
    print(f"\nproves_int, {framing} framing: {counts}")
    assert status == 0, output[-8000:]
    assert sum(counts.values()) == 45 and counts["skipped"] == 0, output[-4000:]


def _start_waiting_run(tmp_path: pathlib.Path) -> tuple[subprocess.Popen, pathlib.Path]:
    """The verb running a suite whose one test waits ten minutes; returned once that test runs."""
    suite = tmp_path / "suite"
    suite.mkdir()
    (suite / "test_wait.py").write_text("import time\n\ndef test_wait(fprime_test_api):\n    time.sleep(600)\n")
    work = tmp_path / "work"
    verb = subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.cli", "conformance", str(suite), "--topology",
                             str(TOPOLOGY), "--framing", "fprime", "--out", str(work)], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, text=True)
    deadline = time.monotonic() + 300
    while not (work / "pytest.log").exists() or "test_wait.py" not in (work / "pytest.log").read_text():
        if time.monotonic() > deadline or verb.poll() is not None:
            verb.kill()
            raise AssertionError(verb.communicate()[0])
        time.sleep(0.5)
    assert _processes_mentioning(str(work)), "nothing of the run was found to be running"
    return verb, work


def test_sigterm_ends_every_process_the_verb_started(tmp_path):
    """A suite still running when the verb gets SIGTERM: pytest, the deployment (which still writes
    its outputs) and the GDS with its comm child all end, and the verb exits 128 + 15."""
    verb, work = _start_waiting_run(tmp_path)
    try:
        verb.send_signal(signal.SIGTERM)
        output, _ = verb.communicate(timeout=120)
    finally:
        if verb.poll() is None:
            verb.kill()
    assert verb.returncode == 128 + signal.SIGTERM, output
    assert _processes_mentioning(str(work)) == [], output
    assert list((work / "run").glob("summary.json")), "the deployment did not write its outputs"


def test_sigkill_leaves_no_process_behind(tmp_path):
    """The verb killed outright (SIGKILL: no clean-up of its own): its watchdog ends pytest, the
    deployment and the GDS with its comm child within the grace time, and the deployment, sent SIGTERM
    first, still writes its outputs."""
    from fprime_lite.tools.processes import WATCHDOG_GRACE_S

    verb, work = _start_waiting_run(tmp_path)
    verb.kill()
    verb.communicate(timeout=30)
    deadline = time.monotonic() + WATCHDOG_GRACE_S + 30
    while _processes_mentioning(str(work)) and time.monotonic() < deadline:
        time.sleep(0.5)
    assert _processes_mentioning(str(work)) == []
    assert list((work / "run").glob("summary.json")), "the deployment did not write its outputs"


def _processes_mentioning(text: str) -> list[str]:
    """Command lines of the running processes that mention ``text`` (the run's work folder)."""
    found = []
    for proc in pathlib.Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            cmdline = (proc / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if text in cmdline:
            found.append(f"{proc.name}: {cmdline[:200]}")
    return found
