"""Mutation fuzzing of the topology loader (issue #16): whatever the bytes of a topology, an included
subtopology or a base it extends, loading either succeeds or raises TopologyError whose problems
all read ``file:line: what — what to do`` — never another exception, never a stall.

Two stages are fuzzed separately, because they cost very different amounts per input:

- ``check``: :func:`read_topology` — parsing, ``extends``, includes and the schema (everything that
  reads the bytes; nothing imported or constructed), about a millisecond an input;
- ``load``: :func:`load_topology` — the same plus importing the types, constructing resources and
  instances (the simulated spacecraft among them) and wiring, tens of milliseconds an input.

The default suite runs a bounded Hypothesis property of ``load`` and a bounded campaign of
``check``. The long mode (``pytest -m fuzz tests/fprime_lite/deploy/test_topology_fuzz.py -s``)
runs ``FPRIME_LITE_FUZZ_INPUTS`` inputs through ``check`` (default 1 000 000) and
``FPRIME_LITE_FUZZ_LOAD_INPUTS`` through ``load`` (default 20 000), seed ``FPRIME_LITE_FUZZ_SEED``;
figures go to stdout and, every 10 000 inputs (``check``) or 1 000 (``load``) and at the end, to
the JSON-lines file ``FPRIME_LITE_FUZZ_REPORT`` when it is set (docs/reliability.md records them);
crashing inputs are saved beside the test's temporary folder.
"""

from __future__ import annotations

import json
import os
import pathlib
import random
import re
import shutil
import signal
import tempfile
import time
import traceback

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from fprime_lite.deploy.topology_loader import TopologyError, load_topology, read_topology
from fprime_lite.deploy.topology_yaml.schema import TopologyConfig

ROOT = pathlib.Path(__file__).parents[3]
REF_DIR = ROOT / "deployments" / "proves_ref"
SUBTOPOLOGIES = ROOT / "src" / "fprime_lite" / "subtopologies"

#: (file mutated, file loaded): the topology, a variant that extends it, an included subtopology.
TARGETS = [("topology.yaml", "topology.yaml"),
           ("topology_bdot_detumble.yaml", "topology_bdot_detumble.yaml"),
           ("cdh_core.yaml", "local.yaml")]

HOSTILE = [
    "", "~", "null", "[]", "{}", "[1, 2]", "{a: 1}", "0", "-1", "1e400", ".nan", "-.inf", "0x100000000", "true",
    "9" * 5000, "0x" + "f" * 5000, "x" * 300, '"a\\0b"', '"\\x07"', "'$nope'", "$clock", "$spacecraft", "$topology_dir",
    "os.system", "subprocess.run", "antigravity.x", "detumble.sim.scenario.load_scenario",
    "fprime_lite.svc.health.Health", "fprime_lite.deploy.resources.topology_resource",
    "fprime_lite.svc.rate_groups.__class__", "!!python/name:os.system", "!!python/object/apply:os.system [id]",
    "!!binary aGVsbG8=", "!!set {a: null}", "!!omap [a: 1]", "&a [*a]", "*undefined", "&x {<<: *x}",
    "[" * 300 + "]" * 300, "{" * 70 + "}" * 70, "? [a, b]\n  : c", "{1: 2}", "{[a]: 1}", "2001-12-14",
    "/etc/passwd", "/dev/zero", "/proc/self/mem", "..", "fprime_lite:../../../../etc/passwd",
    "fprime_lite:subtopologies/cdh_core.yaml", "os:x", "topology.yaml", "local.yaml",
    "CdhCore.cmdDisp.compCmdSend[99999]", "CdhCore.cmdDisp.nope -> CdhCore.events.LogRecv",
    "ReferenceDeployment.rateGroup1Hz", "\t", "\ufeff", "é", "\x85", "- a\n- b",
]
OPS = ["flip", "delete", "insert", "value", "key", "dup_line", "drop_line", "swap_lines", "indent"]


def mutate(data: bytes, ops: list[tuple[str, int, int, str]]) -> bytes:
    """Apply ``ops`` (kind, position, size, payload) to ``data``."""
    for kind, pos, size, payload in ops:
        raw = payload.encode("utf-8", "surrogatepass")
        n = max(len(data), 1)
        at = pos % n
        lines = data.split(b"\n")
        k = pos % max(len(lines), 1)
        if kind == "flip":
            data = data[:at] + bytes([data[at] ^ (1 << (size % 8))]) + data[at + 1:] if data else raw
        elif kind == "delete":
            data = data[:at] + data[at + 1 + size % 64:]
        elif kind == "insert":
            data = data[:at] + raw + data[at:]
        elif kind in ("value", "key"):
            line = lines[k]
            head, sep, tail = line.partition(b": ")
            if sep:
                new_key = raw or b"x"  # a function replacement: the fuzzed bytes are not a template
                lines[k] = (head + sep + raw if kind == "value"
                            else re.sub(rb"\S+$", lambda m, key=new_key: key, head) + sep + tail)
            data = b"\n".join(lines)
        elif kind == "dup_line":
            data = b"\n".join(lines[:k + 1] + lines[k:])
        elif kind == "drop_line":
            data = b"\n".join(lines[:k] + lines[k + 1:])
        elif kind == "swap_lines":
            j = size % max(len(lines), 1)
            lines[k], lines[j] = lines[j], lines[k]
            data = b"\n".join(lines)
        elif kind == "indent":
            lines[k] = lines[k][2:] if size % 2 and lines[k].startswith(b"  ") else b"  " + lines[k]
            data = b"\n".join(lines)
    return data


class Corpus:
    """A folder holding the reference deployment, its variant and local copies of the includes."""

    def __init__(self, folder: pathlib.Path):
        self.folder = folder
        shutil.copytree(REF_DIR, folder, dirs_exist_ok=True)
        for sub in SUBTOPOLOGIES.glob("*.yaml"):
            shutil.copy(sub, folder / sub.name)
        text = (folder / "topology.yaml").read_text()
        (folder / "local.yaml").write_text(text.replace("fprime_lite:subtopologies/", ""))
        self.originals = {name: (folder / name).read_bytes() for name, _ in TARGETS}

    def run(self, stage: str, target: tuple[str, str], data: bytes) -> str:
        """Check or load (``stage``) with ``target``'s file replaced by ``data``: 'loaded' or
        'refused'; anything else raises."""
        mutated, entry = target
        (self.folder / mutated).write_bytes(data)
        try:
            if stage == "check":
                assert isinstance(read_topology(self.folder / entry), TopologyConfig)
            else:
                load_topology(self.folder / entry)
            return "loaded"
        except TopologyError as exc:
            for problem in exc.problems:
                assert re.match(r"^.+:\d+: .+ — .+", problem, re.S), f"not 'file:line: what — what to do': {problem!r}"
            return "refused"
        finally:
            (self.folder / mutated).write_bytes(self.originals[mutated])

    def load(self, target: tuple[str, str], data: bytes) -> str:
        return self.run("load", target, data)


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    return Corpus(tmp_path_factory.mktemp("corpus"))


def test_the_corpus_loads(corpus):
    """TOPO-FUZZ-000: every unmutated target loads and checks, so a refusal is the mutation's doing."""
    for target in TARGETS:
        assert corpus.load(target, corpus.originals[target[0]]) == "loaded"
        assert corpus.run("check", target, corpus.originals[target[0]]) == "loaded"


_op = st.tuples(st.sampled_from(OPS), st.integers(0, 10 ** 6), st.integers(0, 255),
                st.sampled_from(HOSTILE) | st.text(max_size=12))


@settings(max_examples=50, deadline=None, database=None, phases=[Phase.explicit, Phase.generate],
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(target=st.sampled_from(TARGETS), ops=st.lists(_op, min_size=1, max_size=3))
def test_mutated_topologies_load_or_are_refused_with_located_messages(corpus, monkeypatch, target, ops):
    """TOPO-FUZZ-001: a mutated topology, variant or include loads or gives located problems only."""
    monkeypatch.chdir(corpus.folder)
    corpus.load(target, mutate(corpus.originals[target[0]], ops))


class _Hang(BaseException):
    """Raised by the per-input CPU timer; a BaseException so that no ``except Exception`` swallows it."""


def _on_timer(signum, frame):
    # re-armed first: if the exception is raised where Python swallows it (a gc callback runs
    # Python code too), the timer fires again instead of leaving the input running for ever
    signal.setitimer(signal.ITIMER_VIRTUAL, 0.05)
    raise _Hang()


def random_input(rng: random.Random, corpus: Corpus) -> tuple[tuple[str, str], bytes]:
    """One input: a target and its file with 1–4 random mutations (80 % hostile payloads)."""
    target = rng.choice(TARGETS)
    ops = [(rng.choice(OPS), rng.randrange(10 ** 6), rng.randrange(256),
            rng.choice(HOSTILE) if rng.random() < 0.8 else
            "".join(chr(rng.randrange(1, 0x3000)) for _ in range(rng.randrange(8))))
           for _ in range(rng.randint(1, 4))]
    return target, mutate(corpus.originals[target[0]], ops)


def campaign(corpus: Corpus, stage: str, inputs: int, seed: int, hang_cpu_s: float, report=None,
             run=None, report_every: int = 10_000) -> dict:
    """``inputs`` random inputs through ``stage`` ('check' or 'load'); the figures.

    An input that raises anything but a located TopologyError is a crash; one that uses more than
    ``hang_cpu_s`` of CPU time (``ITIMER_VIRTUAL``, so a busy shared machine does not count) a hang.
    ``report(figures)`` is called every ``report_every`` inputs; ``run`` replaces ``corpus.run`` (tests).
    """
    run = run or corpus.run
    rng = random.Random(seed)
    outcomes = {"loaded": 0, "refused": 0, "crash": 0, "hang": 0}
    slowest_cpu, found = 0.0, []
    previous = signal.signal(signal.SIGVTALRM, _on_timer)
    start, cpu_start = time.perf_counter(), time.process_time()

    def figures(done: int) -> dict:
        wall = time.perf_counter() - start
        return {"stage": stage, "seed": seed, "inputs": done, **outcomes, "wall_s": round(wall, 1),
                "cpu_s": round(time.process_time() - cpu_start, 1),
                "inputs_per_s": round(done / wall, 1) if wall else None,
                "slowest_input_cpu_ms": round(slowest_cpu * 1e3, 2),
                "first_findings": [(i, t[0], why[-600:]) for i, t, _, why in found[:5]]}

    try:
        for i in range(inputs):
            target, data = random_input(rng, corpus)
            t0 = time.process_time()
            signal.setitimer(signal.ITIMER_VIRTUAL, hang_cpu_s)
            try:
                outcomes[run(stage, target, data)] += 1
            except _Hang:
                outcomes["hang"] += 1
                found.append((i, target, data, "hang"))
            except (Exception, AssertionError):  # noqa: BLE001 - a crash is what this counts
                outcomes["crash"] += 1
                found.append((i, target, data, traceback.format_exc(limit=4)))
            finally:
                signal.setitimer(signal.ITIMER_VIRTUAL, 0)
            slowest_cpu = max(slowest_cpu, time.process_time() - t0)
            if report is not None and (i + 1) % report_every == 0:
                report(figures(i + 1))
    finally:
        signal.signal(signal.SIGVTALRM, previous)
    result = figures(inputs)
    result["found"] = found
    return result


def test_bounded_check_campaign(corpus, monkeypatch):
    """TOPO-FUZZ-003: 1 000 mutated inputs (fixed seed) through parsing and the schema: no crash,
    no hang, and the mutations reach both outcomes."""
    monkeypatch.chdir(corpus.folder)
    result = campaign(corpus, "check", 1000, seed=3, hang_cpu_s=2.0)
    assert result["crash"] == 0 and result["hang"] == 0, result["first_findings"]
    assert result["loaded"] > 0 and result["refused"] > 0


def test_the_campaign_finds_a_planted_crash_and_hang(corpus, monkeypatch):
    """TOPO-FUZZ-004: the campaign is not blind: a stage that raises KeyError on inputs holding a
    '!!python' tag and loops forever on inputs of some lengths (bugs planted for this test) is
    reported as crashing and as hanging, with the input that did it."""
    monkeypatch.chdir(corpus.folder)

    def planted(stage, target, data):
        if len(data) % 97 == 0:
            while True:
                pass
        if b"!!python" in data:
            raise KeyError("planted")
        return corpus.run(stage, target, data)

    # 0.5 s: ten times the slowest legitimate input measured (a check is ~5 ms, but a full garbage
    # collection landing inside one input has cost it 57-69 ms on this machine); a planted loop never ends
    result = campaign(corpus, "check", 600, seed=5, hang_cpu_s=0.5, run=planted)
    crashes = [(data, why) for _, _, data, why in result["found"] if why != "hang"]
    hangs = [data for _, _, data, why in result["found"] if why == "hang"]
    assert result["crash"] == len(crashes) > 0 and all(b"!!python" in d and "planted" in w for d, w in crashes)
    assert result["hang"] == len(hangs) > 0 and all(len(d) % 97 == 0 for d in hangs)


def _scratch_folder(tmp_path: pathlib.Path) -> pathlib.Path:
    """A folder in memory (tmpfs) when the machine has one: rewriting a file on some disk file
    systems costs milliseconds, more than checking it."""
    shm = pathlib.Path("/dev/shm")
    if shm.is_dir() and os.access(shm, os.W_OK):
        return pathlib.Path(tempfile.mkdtemp(prefix="fprime-lite-topo-fuzz-", dir=shm))
    return tmp_path / "corpus"


def _long_campaign(tmp_path, monkeypatch, stage: str, inputs: int, hang_cpu_s: float, report_every: int) -> None:
    folder = _scratch_folder(tmp_path)
    try:
        corpus = Corpus(folder)
        monkeypatch.chdir(corpus.folder)
        seed = int(os.environ.get("FPRIME_LITE_FUZZ_SEED", "1"))
        report_path = os.environ.get("FPRIME_LITE_FUZZ_REPORT")

        def report(figures: dict) -> None:
            print(json.dumps(figures), flush=True)
            if report_path:
                with open(report_path, "a", encoding="utf-8") as f:
                    f.write(json.dumps({"parser": f"topology_{stage}", **figures}) + "\n")

        result = campaign(corpus, stage, inputs, seed, hang_cpu_s, report=report, report_every=report_every)
        found = result.pop("found")
        report(result)
    finally:
        if folder.parent == pathlib.Path("/dev/shm"):
            shutil.rmtree(folder, ignore_errors=True)
    for i, target, data, why in found[:20]:
        (tmp_path / f"{stage}-{i}-{target[0]}").write_bytes(data)
        print(f"input {i} ({target[0]}): {why}")
    print(f"\ntopology {stage} fuzz: seed {seed}, {inputs} inputs in {result['wall_s']} s "
          f"({result['inputs_per_s']}/s), {result['loaded']} loaded, {result['refused']} refused, "
          f"{result['crash']} crashes, {result['hang']} hangs, slowest input {result['slowest_input_cpu_ms']} ms "
          f"CPU (saved crashes: {tmp_path})")
    assert result["crash"] == 0 and result["hang"] == 0, found[:3]


@pytest.mark.fuzz
def test_long_check_campaign(tmp_path, monkeypatch):
    """TOPO-FUZZ-005: the long campaign of parsing and the schema — FPRIME_LITE_FUZZ_INPUTS
    (default 1 M) mutations of the three targets; no crash, no input past 2 s of CPU time."""
    _long_campaign(tmp_path, monkeypatch, "check", int(os.environ.get("FPRIME_LITE_FUZZ_INPUTS", "1000000")), 2.0,
                   10_000)


@pytest.mark.fuzz
def test_long_mutation_campaign(tmp_path, monkeypatch):
    """TOPO-FUZZ-002: the long campaign of full loads (parse, schema, build, wire) —
    FPRIME_LITE_FUZZ_LOAD_INPUTS (default 20 000) mutations; no crash, no input past 10 s of CPU."""
    _long_campaign(tmp_path, monkeypatch, "load", int(os.environ.get("FPRIME_LITE_FUZZ_LOAD_INPUTS", "20000")),
                   10.0, 1_000)
