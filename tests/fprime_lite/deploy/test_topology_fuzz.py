"""Mutation fuzzing of the topology loader (issue #16): whatever the bytes of a topology, an included
subtopology or a base it extends, loading either succeeds or raises TopologyError whose problems
all read ``file:line: what — what to do`` — never another exception, never a stall.

The default suite runs a bounded Hypothesis property (a few seconds). The long mode is
``pytest -m fuzz tests/fprime_lite/deploy/test_topology_fuzz.py -s`` with
``FPRIME_LITE_FUZZ_INPUTS`` inputs (default 20000) and ``FPRIME_LITE_FUZZ_SEED``; it prints its
figures (recorded in docs/reliability.md) and saves any crashing input beside the report.
"""

from __future__ import annotations

import os
import pathlib
import random
import re
import shutil
import signal
import time
import traceback

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from fprime_lite.deploy.topology_loader import TopologyError, load_topology

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

    def load(self, target: tuple[str, str], data: bytes) -> str:
        """Load with ``target``'s file replaced by ``data``: 'loaded' or 'refused'; anything else raises."""
        mutated, entry = target
        (self.folder / mutated).write_bytes(data)
        try:
            load_topology(self.folder / entry)
            return "loaded"
        except TopologyError as exc:
            for problem in exc.problems:
                assert re.match(r"^.+:\d+: .+ — .+", problem, re.S), f"not 'file:line: what — what to do': {problem!r}"
            return "refused"
        finally:
            (self.folder / mutated).write_bytes(self.originals[mutated])


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    return Corpus(tmp_path_factory.mktemp("corpus"))


def test_the_corpus_loads(corpus):
    """TOPO-FUZZ-000: every unmutated target loads, so a refusal is the mutation's doing."""
    for target in TARGETS:
        assert corpus.load(target, corpus.originals[target[0]]) == "loaded"


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
    """Raised by the per-input alarm; a BaseException so that no ``except Exception`` swallows it."""


def _alarm(signum, frame):
    raise _Hang()


@pytest.mark.fuzz
def test_long_mutation_campaign(tmp_path, monkeypatch):
    """TOPO-FUZZ-002: the long campaign — N random mutations (1–4 ops) of the three targets; no
    crash, and no input runs into the 10 s alarm."""
    corpus = Corpus(tmp_path / "corpus")
    monkeypatch.chdir(corpus.folder)
    n = int(os.environ.get("FPRIME_LITE_FUZZ_INPUTS", "20000"))
    seed = int(os.environ.get("FPRIME_LITE_FUZZ_SEED", "1"))
    rng = random.Random(seed)
    outcomes = {"loaded": 0, "refused": 0, "crash": 0, "hang": 0}
    slowest, crashes = 0.0, []
    previous = signal.signal(signal.SIGALRM, _alarm)
    start = time.perf_counter()
    try:
        for i in range(n):
            target = rng.choice(TARGETS)
            ops = [(rng.choice(OPS), rng.randrange(10 ** 6), rng.randrange(256),
                    rng.choice(HOSTILE) if rng.random() < 0.8 else
                    "".join(chr(rng.randrange(1, 0x3000)) for _ in range(rng.randrange(8))))
                   for _ in range(rng.randint(1, 4))]
            data = mutate(corpus.originals[target[0]], ops)
            t0 = time.perf_counter()
            signal.setitimer(signal.ITIMER_REAL, 10.0)
            try:
                outcomes[corpus.load(target, data)] += 1
            except _Hang:
                outcomes["hang"] += 1
                crashes.append((i, target, data, "hang"))
            except (Exception, AssertionError):  # noqa: BLE001 - a crash is what this counts
                outcomes["crash"] += 1
                crashes.append((i, target, data, traceback.format_exc(limit=3)))
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0)
            slowest = max(slowest, time.perf_counter() - t0)
    finally:
        signal.signal(signal.SIGALRM, previous)
    elapsed = time.perf_counter() - start
    for i, target, data, why in crashes[:20]:
        (tmp_path / f"crash-{i}-{target[0]}").write_bytes(data)
        print(f"input {i} ({target[0]}): {why}")
    print(f"\ntopology loader fuzz: seed {seed}, {n} inputs in {elapsed:.0f} s, {outcomes['loaded']} loaded, "
          f"{outcomes['refused']} refused, {outcomes['crash']} crashes, {outcomes['hang']} hangs, "
          f"slowest input {slowest:.2f} s (saved crashes: {tmp_path})")
    assert outcomes["crash"] == 0 and outcomes["hang"] == 0, crashes[:3]
