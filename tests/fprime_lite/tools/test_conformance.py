"""``fprime-lite conformance``: its report, its refusals and the expected-failures plugin (fast; the
end-to-end runs against the stock fprime-gds are in tests/integration/test_upstream.py)."""

from __future__ import annotations

import pathlib
import subprocess
import sys
import textwrap

import pytest

from fprime_lite.tools.cli import main as fprime_lite
from fprime_lite.tools.conformance import format_table, read_junit

JUNIT = """<?xml version="1.0" encoding="utf-8"?>
<testsuites><testsuite name="pytest">
  <testcase classname="CdhCore.test_cdh_core" file="CdhCore/test_cdh_core.py" name="test_a" time="1.5"/>
  <testcase classname="CdhCore.test_cdh_core" file="CdhCore/test_cdh_core.py" name="test_b" time="0.5">
    <failure message="boom">trace</failure></testcase>
  <testcase classname="PrmDb.test_cmd_PrmDb" file="PrmDb/test_cmd_PrmDb.py" name="test_c" time="0.1">
    <error message="setup">trace</error></testcase>
  <testcase classname="PrmDb.test_cmd_PrmDb" file="PrmDb/test_cmd_PrmDb.py" name="test_d" time="0.0">
    <skipped type="pytest.skip" message="manual">skip</skipped></testcase>
  <testcase classname="PrmDb.test_cmd_PrmDb" file="PrmDb/test_cmd_PrmDb.py" name="test_e" time="0.2">
    <skipped type="pytest.xfail" message="no antenna">xfail</skipped></testcase>
</testsuite></testsuites>
"""


def test_the_table_counts_each_outcome_per_file(tmp_path):
    path = tmp_path / "junit.xml"
    path.write_text(JUNIT)
    files = read_junit(path)
    cdh, prm = files["CdhCore/test_cdh_core.py"], files["PrmDb/test_cmd_PrmDb.py"]
    assert (cdh.passed, cdh.failed, cdh.errors, cdh.skipped, cdh.xfailed) == (1, 1, 0, 0, 0)
    assert (prm.passed, prm.failed, prm.errors, prm.skipped, prm.xfailed) == (0, 0, 1, 1, 1)
    assert cdh.seconds == pytest.approx(2.0)
    table = format_table(files).splitlines()
    assert next(line for line in table if line.startswith("total")).split() == ["total", "1", "1", "1", "1", "1", "2.3"]
    assert "  CdhCore/test_cdh_core.py::test_b: failed" in table
    assert "  PrmDb/test_cmd_PrmDb.py::test_e: xfailed (no antenna)" in table
    assert read_junit(tmp_path / "missing.xml") == {}
    assert format_table({}) == "no test results (pytest wrote no JUnit report)"


@pytest.mark.parametrize("args, message", [
    (["NO_SUCH_DIR"], "TESTS_DIR NO_SUCH_DIR: no such folder or file"),
    (["TESTS", "--topology", "nope.yaml"], "--topology nope.yaml: no such file"),
    (["TESTS", "--topology", "TOPO", "--deployment-config", "BAD"], "not JSON"),
    (["TESTS", "--topology", "TOPO", "--deployment-config", "LIST"], "expected a JSON object of strings"),
    (["TESTS", "--topology", "TOPO", "--python", "/no/such/python"], "--python /no/such/python: cannot import"),
    (["TESTS", "--topology", "TOPO", "--expected-failures", "nope.txt"], "--expected-failures nope.txt: no such file"),
    (["TESTS", "--topology", "TOPO", "--file-root", "/no/such/root"], "--file-root /no/such/root: not an existing"),
])
def test_mistakes_are_refused_before_anything_starts(tmp_path, monkeypatch, capsys, args, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "suite").mkdir()
    (tmp_path / "topology.yaml").write_text("deployment: X\n")
    (tmp_path / "bad.json").write_text("{")
    (tmp_path / "list.json").write_text("[1]")
    names = {"TESTS": "suite", "TOPO": "topology.yaml", "BAD": "bad.json", "LIST": "list.json"}
    assert fprime_lite(["conformance", *[names.get(a, a) for a in args]]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fprime-lite conformance: ") and message in err
    assert not list(tmp_path.glob("fprime-lite-conformance-*"))  # no work folder was made


def _run_suite(tmp_path, listing: str | None) -> subprocess.CompletedProcess:
    (tmp_path / "test_suite.py").write_text(textwrap.dedent("""
        def test_fails():
            assert False
        def test_passes():
            pass
    """))
    argv = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
            "-p", "fprime_lite.testing.expected_failures", str(tmp_path / "test_suite.py"), "--rootdir", str(tmp_path),
            "-c", str(tmp_path / "pytest.ini")]
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    if listing is not None:
        (tmp_path / "expected.txt").write_text(listing)
        argv += ["--fprime-lite-expected-failures", str(tmp_path / "expected.txt")]
    return subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path)


def test_listed_failures_run_as_expected_failures(tmp_path):
    plain = _run_suite(tmp_path, None)
    assert plain.returncode == 1 and "1 failed, 1 passed" in plain.stdout
    listed = _run_suite(tmp_path, "# why each fails\n\ntest_suite.py::test_fails  no such component yet\n"
                                  "test_suite.py::test_gone  a test the suite no longer has\n")
    assert listed.returncode == 0, listed.stdout
    assert "1 passed, 1 xfailed" in listed.stdout
    assert "1 listed test(s) not collected: test_suite.py::test_gone" in listed.stdout


def test_a_listed_test_without_a_reason_is_refused(tmp_path):
    result = _run_suite(tmp_path, "test_suite.py::test_fails\n")
    assert result.returncode == 4  # pytest's usage error
    assert "expected.txt:1: 'test_suite.py::test_fails' has no reason" in result.stderr


def test_a_run_with_a_file_root_gives_the_file_services_fprimes_behaviour(tmp_path, monkeypatch):
    """run --file-root (what conformance passes): the services without a root of their own are
    confined to it, take relative paths from the working directory, replace existing files, and
    FileUplink writes in place; a plain run keeps them in the run folder with overwrite off."""
    from fprime_lite.tools.api import load
    from fprime_lite.tools.runner import run_deployment

    topology = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    for file_root in (None, tmp_path):
        loaded = load(str(topology))
        out = tmp_path / f"run-{file_root is not None}"
        run_deployment(loaded, out, duration_s=0.1, plots=False, quiet=True, file_root=file_root)
        manager = loaded.topology.instance("FileHandling.fileManager").component
        uplink = loaded.topology.instance("FileHandling.fileUplink").component
        if file_root is None:
            assert manager.root_path == manager.confinement_root == str(out.resolve())
            assert (manager.overwrite, uplink.overwrite, uplink.in_place) == (False, False, False)
        else:
            assert (manager.root_path, manager.confinement_root) == (str(work.resolve()), str(tmp_path.resolve()))
            assert (manager.overwrite, uplink.overwrite, uplink.in_place) == (True, True, True)


def test_run_refuses_a_file_root_that_does_not_hold_the_working_directory(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    topology = str(pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml")
    assert fprime_lite(["run", topology, "--file-root", str(tmp_path / "nope")]) == 2
    assert "--file-root" in capsys.readouterr().err
    (tmp_path / "elsewhere").mkdir()
    assert fprime_lite(["run", topology, "--file-root", str(tmp_path / "elsewhere")]) == 2
    assert "is not inside it" in capsys.readouterr().err
    assert not (tmp_path / "runs").exists()  # refused before a run folder was made


def test_a_run_with_a_board_root_maps_the_boards_paths_into_it(tmp_path, monkeypatch):
    """run --board-root (what conformance --board-root passes; PROVES's rtc_test uplinks to /seq): the
    file services and both sequencers take /seq/x.bin as BOARD/seq/x.bin, a CS_RUN of a board path
    reads the file there, nothing outside the board is reachable, and files are replaced as F´ does."""
    from fprime_lite.svc.cmd_sequencer import CmdSequencer
    from fprime_lite.tools.api import load
    from fprime_lite.tools.runner import run_deployment

    topology = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"
    board = tmp_path / "board"
    (board / "seq").mkdir(parents=True)
    monkeypatch.chdir(tmp_path)
    loaded = load(str(topology))
    run_deployment(loaded, tmp_path / "run", duration_s=0.1, plots=False, quiet=True, board_root=board)
    topo = loaded.topology
    manager = topo.instance("FileHandling.fileManager").component
    uplink = topo.instance("FileHandling.fileUplink").component
    assert manager.resolve("/seq/no_op.bin") == str(board.resolve() / "seq" / "no_op.bin")
    assert (manager.overwrite, uplink.overwrite, uplink.in_place) == (True, True, True)
    sequencers = [i.component for i in topo.instances.values() if isinstance(i.component, CmdSequencer)]
    assert {s.name for s in sequencers} >= {"cmdSeq", "payloadSeq"}
    for sequencer in sequencers:
        assert sequencer._resolve("/seq/no_op.bin") == board.resolve() / "seq" / "no_op.bin"
        with pytest.raises(PermissionError):
            sequencer._resolve("/../outside.bin")
    # CS_RUN of a board path: the file is looked for on the board (found: loaded; absent: not found)
    cmd_seq = topo.instance("ReferenceDeployment.cmdSeq").component
    (board / "seq" / "bad.bin").write_bytes(b"\0")
    events = []
    cmd_seq.CS_FileNotFound = lambda name: events.append(("not found", name))
    cmd_seq.CS_FileInvalid = lambda name, stage, error: events.append(("invalid", name))
    cmd_seq._load("/seq/missing.bin")
    cmd_seq._load("/seq/bad.bin")
    assert events == [("not found", "/seq/missing.bin"), ("invalid", "/seq/bad.bin")]
    # a software restart (PROVES's reset tests) re-initialises each component, then runs the deployment's
    # component_setup again: the board root comes back
    deployment = loaded.resources["spacecraft"].reset_handler.__self__
    for name in ("FileHandling.fileManager", "ReferenceDeployment.payloadSeq"):
        instance = topo.instance(name)
        type(instance.component).__init__(instance.component, instance.component.name, **instance.init_kwargs)
    with pytest.raises(PermissionError):
        manager.resolve("/seq/no_op.bin")
    for setup in deployment.component_setup:
        setup()
    assert manager.resolve("/seq/no_op.bin") == str(board.resolve() / "seq" / "no_op.bin")
    assert manager.overwrite and topo.instance("ReferenceDeployment.payloadSeq").component.board_root is not None


def test_run_refuses_board_root_with_file_root_and_no_startup_with_seq(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    topology = str(pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml")
    assert fprime_lite(["run", topology, "--board-root", str(tmp_path / "nope")]) == 2
    assert "--board-root" in capsys.readouterr().err
    assert fprime_lite(["run", topology, "--board-root", str(tmp_path), "--file-root", str(tmp_path)]) == 2
    assert "give one" in capsys.readouterr().err
    seq = pathlib.Path(topology).parent / "startup.seq"
    assert fprime_lite(["run", topology, "--no-startup", "--seq", str(seq)]) == 2
    assert "--no-startup and --seq" in capsys.readouterr().err
    assert not (tmp_path / "runs").exists()


def test_no_startup_flies_without_the_topologys_start_up_sequence(tmp_path, monkeypatch):
    """run --no-startup (PROVES's suite: a board whose file system holds no start-up sequence): the
    sequence that enables detumbling is not run, so the tumbling board's DetumbleManager stays DISABLED;
    without the flag it runs and detumbling starts within the first second."""
    monkeypatch.chdir(tmp_path)
    topology = str(pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml")
    for flag, expected in (([], True), (["--no-startup"], False)):
        out = tmp_path / f"run{len(flag)}"
        assert fprime_lite(["run", topology, "--duration", "1", "--out", str(out), "--no-plots", "--no-progress",
                            "--allow-warnings", *flag]) == 0
        events = (out / "events.log").read_text()
        assert ("CS_SequenceComplete" in events, "DetumbleStarted" in events) == (expected, expected)


def test_the_board_root_is_the_simulated_flash(tmp_path, monkeypatch):
    """CONF-FLASH-001: run --board-root makes the board root the spacecraft's flash as well (one file
    system, as on the board): the boot count lands at the board's /boot_count.bin, and fsFormat's FORMAT
    erases the uplinked /seq files with it."""
    from fprime_lite.tools.api import load
    from fprime_lite.tools.runner import use_board_as_flash
    from fprime_lite.tools.runner import run_deployment

    topology = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"
    monkeypatch.chdir(tmp_path)
    board = tmp_path / "board"
    board.mkdir()
    assert fprime_lite(["run", str(topology), "--board-root", str(board), "--duration", "0.1", "--no-plots",
                        "--no-startup", "--out", str(tmp_path / "cli-run")]) == 0
    assert (board / "boot_count.bin").is_file()

    board = tmp_path / "board2"
    (board / "seq").mkdir(parents=True)
    (board / "seq" / "uplinked.bin").write_bytes(b"\0" * 8)
    loaded = load(str(topology))
    use_board_as_flash(loaded, board)
    run_deployment(loaded, tmp_path / "run", duration_s=0.1, plots=False, quiet=True, board_root=board)
    assert loaded.resources["spacecraft"].flash_dir == str(board)
    assert (board / "boot_count.bin").is_file()
    fs_format = loaded.topology.instance("ReferenceDeployment.fsFormat").component
    formatted = []
    fs_format.FileSystemFormatted = lambda: formatted.append(True)
    fs_format.FORMAT()
    assert formatted and list(board.iterdir()) == []


def test_the_python_api_takes_a_board_root(tmp_path, monkeypatch):
    """CONF-API-001: ``fprime_lite.tools.run(..., board_root=DIR)`` is ``run --board-root DIR``: the
    board root is the file services' / and the spacecraft's flash (the boot count lands at its
    /boot_count.bin, not in the run folder); a folder that does not exist is refused before a run
    folder is made."""
    from fprime_lite.tools.api import RunSetupError, run

    topology = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"
    monkeypatch.chdir(tmp_path)
    with pytest.raises(RunSetupError, match="board_root .*nope: not an existing folder"):
        run(str(topology), duration_s=0.1, out=tmp_path / "refused", board_root=tmp_path / "nope")
    assert not (tmp_path / "refused").exists()
    board = tmp_path / "board"
    board.mkdir()
    result = run(str(topology), duration_s=0.1, out=tmp_path / "run", board_root=board)
    assert (board / "boot_count.bin").is_file()
    assert not list(result.out_dir.rglob("boot_count.bin"))


def test_the_python_api_takes_a_file_root(tmp_path, monkeypatch):
    """CONF-API-002: ``fprime_lite.tools.run(..., file_root=DIR)`` is ``run --file-root DIR``: the file
    services without a root of their own are confined to DIR, take relative paths from the working
    directory and replace files; a root that does not hold the working directory, or one given with a
    board root, is refused before a run folder is made."""
    from fprime_lite.tools.api import RunSetupError, run

    topology = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"
    work = tmp_path / "work"
    work.mkdir()
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(work)
    with pytest.raises(RunSetupError, match="file_root .*elsewhere: the working directory .* is not inside it"):
        run(str(topology), duration_s=0.1, out=tmp_path / "refused", file_root=tmp_path / "elsewhere")
    with pytest.raises(RunSetupError, match="board_root and file_root: give one"):
        run(str(topology), duration_s=0.1, out=tmp_path / "refused", file_root=tmp_path, board_root=tmp_path)
    assert not (tmp_path / "refused").exists()

    seen = {}
    from fprime_lite.tools import runner

    real = runner.run_deployment

    def spy(loaded, out_dir, **kwargs):
        summary = real(loaded, out_dir, **kwargs)
        manager = loaded.topology.instance("FileHandling.fileManager").component
        seen.update(root=manager.root_path, confined=manager.confinement_root, overwrite=manager.overwrite)
        return summary

    monkeypatch.setattr(runner, "run_deployment", spy)
    run(str(topology), duration_s=0.1, out=tmp_path / "run", file_root=tmp_path)
    assert seen == {"root": str(work.resolve()), "confined": str(tmp_path.resolve()), "overwrite": True}


def test_the_first_test_waits_for_the_api_link_to_settle(tmp_path):
    """CONF-LINK-001: conformance's link_settle plugin waits, once, between the test API's creation and the
    first test (fprime-gds's PUB socket drops what is sent before the ground system's subscription reaches
    it: F´'s FileHandling suite lost its first uplink packets so); a second test does not wait again."""
    (tmp_path / "conftest.py").write_text(textwrap.dedent("""
        import time, pytest
        @pytest.fixture(scope="session")
        def fprime_test_api_session():
            with open("times.txt", "a") as fh:
                fh.write(f"api {time.monotonic()}\\n")
            return object()
        @pytest.fixture
        def fprime_test_api(fprime_test_api_session):
            return fprime_test_api_session
    """))
    (tmp_path / "test_suite.py").write_text(textwrap.dedent("""
        import time
        def test_first(fprime_test_api):
            with open("times.txt", "a") as fh:
                fh.write(f"test {time.monotonic()}\\n")
        def test_second(fprime_test_api):
            with open("times.txt", "a") as fh:
                fh.write(f"test {time.monotonic()}\\n")
    """))
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    argv = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "fprime_lite.testing.link_settle",
            "--fprime-lite-link-settle", "0.6", str(tmp_path / "test_suite.py"), "--rootdir", str(tmp_path),
            "-c", str(tmp_path / "pytest.ini")]
    result = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    times = [line.split() for line in (tmp_path / "times.txt").read_text().splitlines()]
    assert [name for name, _ in times] == ["api", "test", "test"]
    api, first, second = (float(t) for _, t in times)
    assert first - api >= 0.6
    assert second - first < 0.6
