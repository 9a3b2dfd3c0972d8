"""``fprime-lite conformance``: run an fprime-gds integration suite against a flying deployment.

    fprime-lite conformance TESTS_DIR [--topology T] [--framing fprime|ccsds]
                            [--deployment-config JSON] [--python PY] [-- PYTEST_ARGS]

What a PROVES or F´ developer runs in CI instead of a board (docs/ground.md, "Conformance"):

1. writes the deployment's GDS dictionary (``fprime-lite dict --gds``) into a work folder;
2. starts the stock ``fprime-gds`` headless (``-n``) on 127.0.0.1, on a port free at start and ZMQ
   sockets of its own, so that two runs do not collide;
3. starts the deployment paced to the wall clock and connected to it (``fprime-lite run --gds``),
   from the work folder, with a copy of its parameter file there (``PrmDb.dat``: the suites save
   parameters, the shipped file is never written) and its file services confined to
   ``--file-root`` (default ``/tmp``, where F´'s suites put their files) — or, with
   ``--board-root DIR``, DIR standing in for the board's ``/`` for the file services and the
   sequencers (PROVES's suite names ``/seq/…``; the parameter copy then lies in DIR) — and waits
   until the deployment says its ground link is connected;
4. runs pytest on TESTS_DIR, with the interpreter ``--python`` names (the PROVES suite needs
   Python >= 3.12), with the options fprime-gds's pytest plugin (``fprime_test_api``) reads: the
   dictionary, the ZMQ sockets, the logs, the file store and ``--deployment-config`` (default:
   ``int_config.json`` beside the topology);
5. ends the deployment (SIGTERM: its outputs are written) and the GDS, each with its whole process
   group, also when the verb itself gets Ctrl-C or SIGTERM; killed by SIGKILL, its watchdog
   (``ProcessGroups(watchdog=True)``) ends them;
6. prints a table of passed / failed / errors / skipped per test file (read from pytest's JUnit
   XML) and exits with pytest's status (2 for a mistake in the verb's own options or a ground
   system or deployment that did not come up).

The work folder (``--out``, default a new ``fprime-lite-conformance-*`` folder in the file root) keeps
every log: ``gds.log``, ``deployment.log``, ``pytest.log``, ``junit.xml``, ``gds-logs/``,
``api-logs/``, the run's outputs in ``run/``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["main", "ConformanceError", "SuiteCounts", "read_junit", "format_table", "FRAMINGS"]

#: ``--framing`` → fprime-gds's ``--framing-selection``.
FRAMINGS = {"fprime": "fprime", "ccsds": "space-packet-space-data-link"}

#: The environment variable naming the default ``--python``.
PYTHON_ENV = "FPRIME_LITE_TEST_PYTHON"
#: The deployment's plant-control side channel and RTC choice (the application's contract: the PROVES reference
#: deployment's plant_control resource reads them; see docs/components/proves_suite_components.md).
PLANT_ENV = "FPRIME_LITE_PLANT_CONTROL"
RTC_ENV = "FPRIME_LITE_RTC"

EXIT_SETUP = 2

#: What ``fprime-lite run --gds`` prints once its ground link has connected.
CONNECTED = "ground link: connected to"


class ConformanceError(FprimeLiteError):
    """The run could not be set up: a bad option, a missing file, a GDS or deployment that did not start."""


@dataclasses.dataclass
class SuiteCounts:
    """Outcomes of the tests of one file (or of the whole suite)."""

    passed: int = 0
    failed: int = 0
    errors: int = 0
    skipped: int = 0
    xfailed: int = 0
    seconds: float = 0.0
    not_passed: list[str] = dataclasses.field(default_factory=list)  # "name: outcome"

    @property
    def total(self) -> int:
        return self.passed + self.failed + self.errors + self.skipped + self.xfailed

    def add(self, other: SuiteCounts) -> None:
        self.passed += other.passed
        self.failed += other.failed
        self.errors += other.errors
        self.skipped += other.skipped
        self.xfailed += other.xfailed
        self.seconds += other.seconds


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="fprime-lite conformance",
        description="Start the stock fprime-gds headless and the deployment paced to the wall clock and "
                    "connected to it, run an fprime-gds integration suite (pytest, fprime_test_api) on them, stop "
                    "everything, print a pass/fail table. Exit status: pytest's (2 when the run could not be set "
                    "up). Arguments after '--' go to pytest.",
        epilog="e.g. fprime-lite conformance ../shared/upstream/fprime_int --topology "
               "deployments/proves_ref/topology.yaml --framing fprime -- -k 'not health'")
    p.add_argument("tests", metavar="TESTS_DIR", help="the test folder or file pytest runs")
    p.add_argument("--topology", default="topology.yaml", metavar="T",
                   help="the deployment's topology (default: ./topology.yaml)")
    p.add_argument("--framing", choices=tuple(FRAMINGS), default="ccsds",
                   help="ground-link framing: ccsds = space-packet-space-data-link (the GDS's default, as PROVES "
                        "flies), fprime (default: ccsds)")
    p.add_argument("--deployment-config", metavar="JSON",
                   help="the fprime_test_api deployment config mapping F´ names (Svc.CommandDispatcher …) to this "
                        "deployment's instances (default: int_config.json beside the topology, if there is one)")
    p.add_argument("--python", metavar="PY",
                   help=f"the interpreter that runs pytest; it needs pytest and fprime-gds 4.4.1 (default: "
                        f"${PYTHON_ENV}, else this interpreter). The PROVES suite needs Python >= 3.12: "
                        f"'.ci/run' builds .venv-upstream for it")
    p.add_argument("--file-root", default="/tmp", metavar="DIR",
                   help="the folder the deployment's file services may reach; it holds the work folder "
                        "(default: /tmp, where F´'s suites write)")
    p.add_argument("--board-root", metavar="DIR",
                   help="a folder standing in for the board's / (run --board-root): absolute paths the suite names "
                        "(/seq/a.bin) are taken inside it, nothing outside it is reachable, and the deployment's "
                        "parameter file is copied there as PrmDb.dat; put in it beforehand the files the suite expects "
                        "on the board. For suites written for a board (PROVES's); F´'s FileHandling suite needs the "
                        "host's /tmp shared instead (the default, --file-root)")
    p.add_argument("--out", metavar="DIR", help="the work folder, kept with every log (absent or empty; inside "
                   "--file-root; default: a new fprime-lite-conformance-* folder in --file-root)")
    p.add_argument("--run-arg", action="append", default=[], metavar="ARG",
                   help="one more argument for 'fprime-lite run' (repeatable), e.g. --run-arg=--seq "
                        "--run-arg=idle.seq")
    p.add_argument("--expected-failures", metavar="FILE",
                   help="tests expected to fail, one a line: NODE_ID (relative to TESTS_DIR) then the reason; they "
                        "run as xfail and do not fail the run (needs fprime-lite in --python's environment)")
    p.add_argument("--sim-plant", action="store_true",
                   help="let the suite drive the simulated plant: the deployment listens for plant-control requests "
                        "on a free loopback port (FPRIME_LITE_PLANT_CONTROL) with its RTC at the wall clock's UTC "
                        "(FPRIME_LITE_RTC=wall), and pytest gets --sim-plant 127.0.0.1:PORT (the plugin that runs "
                        "PROVES's manual tests; needs fprime-lite in --python's environment)")
    p.add_argument("--startup-timeout", type=float, default=120.0, metavar="SECONDS",
                   help="how long to wait for the deployment to connect to the GDS (default: 120)")
    return p


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    pytest_args: list[str] = []
    if "--" in argv:
        cut = argv.index("--")
        argv, pytest_args = argv[:cut], argv[cut + 1:]
    args = build_parser().parse_args(argv)
    try:
        return run(args, pytest_args)
    except ConformanceError as exc:
        print(f"fprime-lite conformance: {exc}", file=sys.stderr)
        return EXIT_SETUP


# --- set-up ------------------------------------------------------------------------------------------


def _check_inputs(args) -> tuple[pathlib.Path, pathlib.Path, pathlib.Path | None, str, pathlib.Path]:
    tests = pathlib.Path(args.tests)
    if not tests.exists():
        raise ConformanceError(f"TESTS_DIR {args.tests}: no such folder or file")
    topology = pathlib.Path(args.topology)
    if not topology.is_file():
        raise ConformanceError(f"--topology {args.topology}: no such file — give the deployment's topology.yaml")
    config = pathlib.Path(args.deployment_config) if args.deployment_config else None
    if config is None and (topology.parent / "int_config.json").is_file():
        config = topology.parent / "int_config.json"
    if config is not None:
        try:
            data = json.loads(config.read_text(encoding="utf-8"))
        except OSError as exc:
            raise ConformanceError(f"--deployment-config {config}: cannot read it ({exc.strerror or exc})") from None
        except ValueError as exc:
            raise ConformanceError(f"--deployment-config {config}: not JSON ({exc})") from None
        if not isinstance(data, dict) or not all(isinstance(v, str) for v in data.values()):
            raise ConformanceError(f"--deployment-config {config}: expected a JSON object of strings, e.g. "
                                   f'{{"Svc.CommandDispatcher": "CdhCore.cmdDisp"}}')
    python = args.python or os.environ.get(PYTHON_ENV) or sys.executable
    # absolute (pytest runs from the work folder), but not resolved: a venv's python is a symbolic link
    python = os.path.abspath(python) if os.sep in python else (shutil.which(python) or python)
    modules = "sys, pytest, fprime_gds" + (", fprime_lite.testing.expected_failures" if args.expected_failures else "")
    probe = subprocess.run([python, "-c", f"import {modules}, importlib.metadata as m; print(m.version('fprime-gds'))"],
                           capture_output=True, text=True) if os.path.isfile(python) else None
    if probe is None or probe.returncode != 0:
        why = "not found" if probe is None else (probe.stderr.strip().splitlines() or ["failed"])[-1]
        raise ConformanceError(f"--python {python}: cannot import {modules} ({why}) — give an interpreter with "
                               f"pytest and fprime-gds==4.4.1 (and fprime-lite for --expected-failures) installed: "
                               f"pip install -e '.[upstream]' in its venv")
    if args.expected_failures and not pathlib.Path(args.expected_failures).is_file():
        raise ConformanceError(f"--expected-failures {args.expected_failures}: no such file")
    theirs, ours = probe.stdout.strip(), _gds_version()
    if theirs != ours:
        raise ConformanceError(f"--python {python}: has fprime-gds {theirs}, the ground system here is {ours} — the "
                               f"test API and the GDS must be the same release (pip install 'fprime-gds=={ours}')")
    root = pathlib.Path(args.file_root)
    if not root.is_dir():
        raise ConformanceError(f"--file-root {args.file_root}: not an existing folder")
    if args.board_root is not None and not pathlib.Path(args.board_root).is_dir():
        raise ConformanceError(f"--board-root {args.board_root}: not an existing folder — create it (with the files "
                               f"the suite expects on the board)")
    return tests.resolve(), topology.resolve(), config.resolve() if config else None, python, root.resolve()


def _work_folder(out: str | None, root: pathlib.Path, board: bool) -> pathlib.Path:
    if out is None:
        return pathlib.Path(tempfile.mkdtemp(prefix="fprime-lite-conformance-", dir=root))
    work = pathlib.Path(out).resolve()
    if not board and not work.is_relative_to(root):
        raise ConformanceError(f"--out {out}: not inside --file-root {root} — the deployment runs from it")
    if work.exists() and (not work.is_dir() or any(work.iterdir())):
        raise ConformanceError(f"--out {out}: exists and is not an empty folder — choose another or remove it")
    work.mkdir(parents=True, exist_ok=True)
    return work


def _write_dictionary(topology: pathlib.Path, work: pathlib.Path, files: pathlib.Path) -> pathlib.Path | None:
    """The GDS dictionary into ``work``; the deployment's parameter file, if any, as ``files/PrmDb.dat``
    (``files``: where the deployment's relative paths resolve: the work folder, or the board root)."""
    from fprime_lite.deploy.com_stack import add_ground_link
    from fprime_lite.deploy.dictionary import write_dictionary
    from fprime_lite.tools.api import load

    try:
        loaded = load(str(topology))
        add_ground_link(loaded.topology)
        write_dictionary(loaded.topology, work / "dictionary.json")
    except FprimeLiteError as exc:
        raise ConformanceError(f"--topology {topology}: {exc}") from None
    params = loaded.parameter_file
    if params is not None and pathlib.Path(params).is_file():
        shutil.copyfile(params, files / "PrmDb.dat")
        return files / "PrmDb.dat"
    return None


def _gds_version() -> str:
    import importlib.metadata

    try:
        return importlib.metadata.version("fprime-gds")
    except importlib.metadata.PackageNotFoundError:
        raise ConformanceError("fprime-gds is not installed beside fprime-lite — pip install -e .[test]") from None


def _gds_program() -> str:
    here = pathlib.Path(sys.executable).parent
    gds = shutil.which("fprime-gds", path=str(here)) or shutil.which("fprime-gds")
    if gds is None:
        raise ConformanceError("fprime-gds is not installed beside fprime-lite — pip install -e .[test]")
    return gds


def _wait_connected(groups, timeout_s: float) -> None:
    """Until the deployment says its ground link is connected; refuse a process that ended."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        for name, proc in groups.procs.items():
            if proc.poll() is not None:
                raise ConformanceError(f"the {name} ended during start-up (exit {proc.returncode}); its last "
                                       f"output ({groups.log_path(name)}):\n{groups.log(name, 3000)}")
        if CONNECTED in groups.log("deployment"):
            return
        time.sleep(0.2)
    raise ConformanceError(f"the deployment did not connect to the GDS within {timeout_s:g} s (--startup-timeout); "
                           f"deployment output:\n{groups.log('deployment', 2000)}\n"
                           f"GDS output:\n{groups.log('gds', 2000)}")


class _SignalError(FprimeLiteError):
    """SIGTERM or SIGINT received by the verb."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _raise_stop(signum, frame):
    raise _SignalError(signum)


# --- the run -----------------------------------------------------------------------------------------


def run(args, pytest_args: list[str]) -> int:
    from fprime_lite.tools.processes import ProcessGroups, free_port

    tests, topology, config, python, root = _check_inputs(args)
    gds = _gds_program()
    board = pathlib.Path(args.board_root).resolve() if args.board_root is not None else None
    work = _work_folder(args.out, root, board is not None)
    sockets = pathlib.Path(tempfile.mkdtemp(prefix="fl-cf-"))  # ZMQ ipc paths must stay short
    zmq = [f"ipc://{sockets}/in", f"ipc://{sockets}/out"]
    groups = ProcessGroups(work, watchdog=True)  # SIGKILL of the verb: the watchdog ends what it started
    previous = {sig: signal.signal(sig, _raise_stop) for sig in (signal.SIGTERM, signal.SIGINT)}
    started = time.monotonic()
    try:
        params = _write_dictionary(topology, work, board if board is not None else work)
        dictionary = work / "dictionary.json"
        files = work / "gds-files"
        port = free_port()
        print(f"conformance: {tests} against {topology} ({args.framing} framing, GDS on 127.0.0.1:{port}); "
              f"work folder {work}", flush=True)
        groups.start("gds", [gds, "-n", "--dictionary", str(dictionary), "--framing-selection",
                             FRAMINGS[args.framing], "--ip-address", "127.0.0.1", "--ip-port", str(port), "-g", "none",
                             "--zmq-transport", *zmq, "--logs", str(work / "gds-logs"), "--log-directly",
                             "--file-storage-directory", str(files)], cwd=work)
        deployment = [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(topology), "--gds",
                      f"127.0.0.1:{port}", "--framing", args.framing, "--duration", str(30 * 86400.0), "--out",
                      str(work / "run"), "--no-plots", "--allow-warnings"]
        deployment += ["--board-root", str(board)] if board is not None else ["--file-root", str(root)]
        if params is not None:
            deployment += ["--params", str(params)]
        deployment_env = dict(os.environ)
        if args.sim_plant:
            plant = f"127.0.0.1:{free_port()}"
            deployment_env.update({PLANT_ENV: plant, RTC_ENV: "wall"})
            pytest_args = ["--sim-plant", plant] + list(pytest_args)
        groups.start("deployment", deployment + list(args.run_arg), cwd=work, env=deployment_env)
        _wait_connected(groups, args.startup_timeout)
        print(f"conformance: deployment connected after {time.monotonic() - started:.1f} s; running pytest with "
              f"{python}", flush=True)
        (work / "pytest.ini").write_text("[pytest]\n")  # the suite's own rootdir settings, none of ours
        rootdir = tests if tests.is_dir() else tests.parent
        command = [python, "-m", "pytest", str(tests), "-c", str(work / "pytest.ini"), "--rootdir", str(rootdir),
                   "-p", "no:cacheprovider", "-rfEs", "-o", "junit_family=xunit1", "--junitxml",
                   str(work / "junit.xml"),
                   "--dictionary", str(dictionary), "--zmq-transport", *zmq, "--logs", str(work / "api-logs"),
                   "--log-directly", "--file-storage-directory", str(files),
                   "-p", "fprime_lite.testing.link_settle"]  # the API's first packets must not be dropped
        if config is not None:
            command += ["--deployment-config", str(config)]
        if args.expected_failures:
            command += ["-p", "fprime_lite.testing.expected_failures", "--fprime-lite-expected-failures",
                        str(pathlib.Path(args.expected_failures).resolve())]
        env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
        status = _run_pytest(groups, command + pytest_args, work, env)
    except _SignalError as stop:
        print(f"conformance: {stop}: stopping the ground system and the deployment", file=sys.stderr)
        return 128 + stop.signum
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not cut the clean-up short
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        _stop(groups)
        groups.close()
        shutil.rmtree(sockets, ignore_errors=True)
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    wall = time.monotonic() - started
    counts = read_junit(work / "junit.xml")
    print(format_table(counts))
    print(f"conformance: pytest exit status {status}; wall time {wall:.0f} s; logs in {work}")
    return status


def _run_pytest(groups, command: list[str], work: pathlib.Path, env: dict) -> int:
    """Run pytest in its own process group, echoing its output; on _SignalError, interrupt it first."""
    proc = groups.start("pytest", command, cwd=work, env=env)
    log = groups.log_path("pytest")
    shown = 0
    try:
        while proc.poll() is None:
            shown = _echo(log, shown)
            time.sleep(0.5)
    except _SignalError:
        groups.stop("pytest", grace_s=20, sig=signal.SIGINT)  # pytest writes its report on Ctrl-C
        _echo(log, shown)
        raise
    _echo(log, shown)
    return proc.returncode


def _echo(path: pathlib.Path, shown: int) -> int:
    try:
        with open(path, "rb") as f:
            f.seek(shown)
            chunk = f.read()
    except OSError:
        return shown
    if chunk:
        sys.stdout.write(chunk.decode(errors="replace"))
        sys.stdout.flush()
    return shown + len(chunk)


def _stop(groups) -> None:
    """The deployment first (SIGTERM: it writes its outputs), then the GDS, each with its whole group."""
    for name, grace in (("pytest", 5.0), ("deployment", 60.0), ("gds", 5.0)):
        if name in groups.procs:
            groups.stop(name, grace_s=grace)


# --- the report --------------------------------------------------------------------------------------


def read_junit(path: pathlib.Path) -> dict[str, SuiteCounts]:
    """Outcomes per test file from pytest's JUnit XML (``{}`` when pytest wrote none)."""
    try:
        tree = ET.parse(path)
    except (OSError, ET.ParseError):
        return {}
    files: dict[str, SuiteCounts] = {}
    for case in tree.iter("testcase"):
        key = case.get("file") or case.get("classname") or "?"  # xunit1 names the file
        counts = files.setdefault(key, SuiteCounts())
        counts.seconds += float(case.get("time") or 0.0)
        tags = {child.tag: child for child in case}
        test = case.get("name", "?")
        if "skipped" in tags and tags["skipped"].get("type") == "pytest.xfail":
            counts.xfailed += 1
            counts.not_passed.append(f"{test}: xfailed ({tags['skipped'].get('message', '')})")
        elif "failure" in tags:
            counts.failed += 1
            counts.not_passed.append(f"{test}: failed")
        elif "error" in tags:
            counts.errors += 1
            counts.not_passed.append(f"{test}: error")
        elif "skipped" in tags:
            counts.skipped += 1
            counts.not_passed.append(f"{test}: skipped")
        else:
            counts.passed += 1
    return files


def format_table(files: dict[str, SuiteCounts]) -> str:
    """A fixed-width table: one row per file, a total row, then the tests that did not pass."""
    if not files:
        return "no test results (pytest wrote no JUnit report)"
    width = max(len("total"), *(len(k) for k in files))
    head = (f"{'file':<{width}}  {'passed':>6}  {'failed':>6}  {'errors':>6}  {'skipped':>7}  {'xfailed':>7}  "
            f"{'seconds':>8}")
    lines = [head, "-" * len(head)]
    total = SuiteCounts()

    def row(name: str, c: SuiteCounts) -> str:
        return (f"{name:<{width}}  {c.passed:>6}  {c.failed:>6}  {c.errors:>6}  {c.skipped:>7}  {c.xfailed:>7}  "
                f"{c.seconds:>8.1f}")

    for name in sorted(files):
        total.add(files[name])
        lines.append(row(name, files[name]))
    lines.append("-" * len(head))
    lines.append(row("total", total))
    for name in sorted(files):
        for entry in files[name].not_passed:
            lines.append(f"  {name}::{entry}")
    return "\n".join(lines)
