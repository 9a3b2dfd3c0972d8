"""Other projects' own integration suites, run unchanged through ``fprime-lite conformance``.

Marked ``upstream`` (minutes; excluded from the default ``python -m pytest``; ``.ci/run`` runs
``python -m pytest -m upstream`` after the default suite). The suites live in ``../shared/upstream``
seen from the project root (never copied into the project); the tests that run them skip, saying
so, where that folder is absent.

- F´'s reusable suites (``fprime_int``: PrmDb, EventManager, Health, CdhCore, FileHandling) on
  the reference deployment, with both framings: must pass (one racy test may fail, listed with its
  reason in ``upstream/fprime_int_expected_failures.txt``). Health runs with the fprime framing
  only (it sleeps about 4 minutes) and needs ``/tmp/1MiB.txt``, which F´'s CI makes, and no
  ``/tmp/2MiB.txt``: the fixture writes 1 MiB of random bytes to the first when it is missing and
  removes the second before and after.
- PROVES's suite (``proves_int``, 45 tests) needs Python >= 3.12: it runs with the interpreter
  ``$FPRIME_LITE_TEST_PYTHON`` names, else ``.venv-upstream/bin/python`` (``.ci/run`` builds it with
  ``pip install -e '.[upstream]'``), and skips, saying so, without one. It runs with ``--sim-plant``
  (the six manual tests through ``detumble.tools.pytest_plant``: none may be skipped) and the board at
  rest, and with ``upstream/proves_expected_failures.txt``: each listed test gives the reason it fails
  today; any other failure fails the job.
- The verb's own clean-up: SIGTERM during a run ends every process it started.
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
LISTS = pathlib.Path(__file__).parent / "upstream"
PROVES_PYTHON = os.environ.get("FPRIME_LITE_TEST_PYTHON") or str(ROOT / ".venv-upstream" / "bin" / "python")

pytestmark = pytest.mark.upstream
needs_upstream = pytest.mark.skipif(not UPSTREAM.is_dir(), reason=f"{UPSTREAM} is absent: the upstream suites are "
                                    f"kept in shared/upstream beside the project (see its README), not in the project")


def conformance(suite: pathlib.Path, out: pathlib.Path, *args: str, timeout: float = 1800) -> tuple[int, str]:
    """Run the verb in a subprocess; its exit status and output."""
    result = subprocess.run([sys.executable, "-m", "fprime_lite.tools.cli", "conformance", str(suite), "--topology",
                             str(TOPOLOGY), "--out", str(out), *args], capture_output=True, text=True, timeout=timeout,
                            stdin=subprocess.DEVNULL)
    return result.returncode, result.stdout + result.stderr


def outcomes(out: pathlib.Path) -> dict[str, int]:
    counts = {"passed": 0, "failed": 0, "errors": 0, "skipped": 0, "xfailed": 0}
    for c in read_junit(out / "junit.xml").values():
        for key in counts:
            counts[key] += getattr(c, key)
    return counts


@pytest.fixture
def health_files():
    """F´'s Health suite appends /tmp/1MiB.txt to /tmp/2MiB.txt, then /tmp/2MiB.txt to itself eight
    times (256 MiB) and removes it with a last command nobody waits for. F´'s CI makes the first file
    on a fresh machine, so do we when it is missing; the second must not exist beforehand (each run
    would start from the last one's size and double it: 64 GiB after one leftover of 256 MiB), so it
    is removed before and after, with the temporary files of an append the end of a run cut short."""
    one_mib, two_mib = pathlib.Path("/tmp/1MiB.txt"), pathlib.Path("/tmp/2MiB.txt")
    if not one_mib.exists():
        one_mib.write_bytes(os.urandom(1 << 20))

    def clean():
        two_mib.unlink(missing_ok=True)
        for part in pathlib.Path("/tmp").glob(".fprime-lite-tmp.*.2MiB.txt.*.part"):
            part.unlink(missing_ok=True)

    clean()
    yield one_mib
    clean()


@needs_upstream
@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_fprime_reusable_suites_pass(framing, tmp_path, health_files):
    suite = UPSTREAM / "fprime_int"
    extra = [] if framing == "fprime" else ["--", "--deselect", "Health/test_cmd_health.py::test_send_health_command"]
    status, output = conformance(suite, tmp_path / "work", "--framing", framing, "--expected-failures",
                                 str(LISTS / "fprime_int_expected_failures.txt"), *extra)
    counts = outcomes(tmp_path / "work")
    print(f"\nfprime_int, {framing} framing: {counts}")
    assert status == 0, output[-8000:]
    expected = 9 if framing == "fprime" else 8
    # the listed tests (fprime_int_expected_failures.txt) may fail: the racy CdhCore test, and Health's where
    # appends are quicker than a Health cycle
    assert counts["passed"] + counts["xfailed"] == expected and counts["xfailed"] <= 2, output[-4000:]


@needs_upstream
@pytest.mark.parametrize("framing", ["fprime", "ccsds"])
def test_proves_suite_fails_only_where_listed(framing, tmp_path):
    if not os.path.isfile(PROVES_PYTHON):
        pytest.skip(f"no Python >= 3.12 test-runner venv: {PROVES_PYTHON} is absent (set FPRIME_LITE_TEST_PYTHON, "
                    f"or build it as .ci/run does: python3.12 -m venv .venv-upstream && .venv-upstream/bin/python -m "
                    f"pip install -e '.[upstream]')")
    # the board on the bench (at rest: the detumbler idles, as on PROVES's CI board), the six manual
    # tests run through the plant-control plugin
    status, output = conformance(UPSTREAM / "proves_int", tmp_path / "work", "--framing", framing, "--python",
                                 PROVES_PYTHON, "--expected-failures", str(LISTS / "proves_expected_failures.txt"),
                                 "--sim-plant", "--run-arg=--set", "--run-arg=initial.rate.magnitude_deg_s=0")
    counts = outcomes(tmp_path / "work")
    print(f"\nproves_int, {framing} framing: {counts}")
    assert status == 0, output[-8000:]
    assert sum(counts.values()) == 45 and counts["skipped"] == 0, output[-4000:]


def test_sigterm_ends_every_process_the_verb_started(tmp_path):
    """A suite still running when the verb gets SIGTERM: pytest, the deployment (which still writes
    its outputs) and the GDS with its comm child all end, and the verb exits 128 + 15."""
    suite = tmp_path / "suite"
    suite.mkdir()
    (suite / "test_wait.py").write_text("import time\n\ndef test_wait(fprime_test_api):\n    time.sleep(600)\n")
    work = tmp_path / "work"
    verb = subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.cli", "conformance", str(suite), "--topology",
                             str(TOPOLOGY), "--framing", "fprime", "--out", str(work)], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, text=True)
    try:
        deadline = time.monotonic() + 300
        while not (work / "pytest.log").exists() or "test_wait.py" not in (work / "pytest.log").read_text():
            assert time.monotonic() < deadline and verb.poll() is None, verb.stdout.read() if verb.stdout else ""
            time.sleep(0.5)
        assert _processes_mentioning(str(work)), "nothing of the run was found to be running"
        verb.send_signal(signal.SIGTERM)
        output, _ = verb.communicate(timeout=120)
    finally:
        if verb.poll() is None:
            verb.kill()
    assert verb.returncode == 128 + signal.SIGTERM, output
    assert _processes_mentioning(str(work)) == [], output
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
