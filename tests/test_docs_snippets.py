"""Every code block of README.md and docs/ runs as printed, unless it is marked as not meant to run.

A fenced block is classified by an HTML comment on the line just before it (docs/architecture.md):

- ``<!-- snippet: file NAME -->`` — the block is the file NAME, written into the page's scratch
  folder (later blocks of the page use it);
- ``<!-- snippet: run -->`` — a shell block: its lines run with bash (``set -e``) in the folder;
- ``<!-- snippet: python -->`` — a Python block run as a script in the folder;
- ``<!-- snippet: not run: REASON -->`` — not run; the reason is required.

A block without a marker fails the test, so a new block is either run or says why it is not. The
scratch folder starts empty but for links to the repository's ``deployments/`` and ``examples/``,
so repository-relative paths work and nothing is written into the checkout.
"""
from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
_FENCE = re.compile(r"^(?:<!-- snippet: (?P<marker>.*?) -->\n)?```(?P<lang>[^\n]*)\n(?P<body>.*?)^```\s*$",
                    re.M | re.S)


def blocks(page: pathlib.Path) -> list[tuple[int, str | None, str, str]]:
    """(line, marker, language, body) of every fenced block of ``page``."""
    text = page.read_text(encoding="utf-8")
    return [(text[:m.start()].count("\n") + 1 + (1 if m.group("marker") else 0), m.group("marker"),
             m.group("lang").strip(), m.group("body")) for m in _FENCE.finditer(text)]


def _env() -> dict:
    env = dict(os.environ)
    env["PATH"] = f"{pathlib.Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env.pop("PYTHONPATH", None)
    env["MPLBACKEND"] = "Agg"
    return env


def _check(done: subprocess.CompletedProcess, where: str) -> None:
    assert done.returncode == 0, f"{where} failed (exit {done.returncode}):\n{done.stdout}\n{done.stderr}"


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_every_block_runs_as_printed_or_says_why_not(page, tmp_path):
    """FH-005: README.md's and docs/'s code blocks run exactly as printed, each in order in one
    scratch folder per page; a block not meant to run is marked with its reason."""
    for name in ("deployments", "examples"):
        (tmp_path / name).symlink_to(ROOT / name, target_is_directory=True)
    rel = page.relative_to(ROOT)
    for n, (line, marker, lang, body) in enumerate(blocks(page)):
        where = f"{rel}:{line} ({lang or 'plain'} block)"
        assert marker is not None, (f"{where} has no snippet marker: put <!-- snippet: file NAME | run | python "
                                    f"| not run: REASON --> on the line before it")
        kind, _, arg = marker.partition(":") if marker.startswith("not run") else marker.partition(" ")
        if kind == "not run":
            assert arg.strip(), f"{where}: 'not run' needs a reason"
        elif kind == "file":
            assert arg.strip(), f"{where}: 'file' needs a file name"
            (tmp_path / arg.strip()).write_text(body, encoding="utf-8")
        elif kind == "run":
            _check(subprocess.run(["bash", "-e", "-o", "pipefail", "-c", body], cwd=tmp_path, env=_env(),
                                  capture_output=True, text=True, timeout=600), where)
        elif kind == "python":
            script = tmp_path / f"_snippet_{n}.py"
            script.write_text(body, encoding="utf-8")
            _check(subprocess.run([sys.executable, script.name], cwd=tmp_path, env=_env(),
                                  capture_output=True, text=True, timeout=600), where)
        else:
            pytest.fail(f"{where}: unknown snippet marker {marker!r}")


def test_the_readme_runs_its_component_test_and_topology():
    """FH-005: the README's component, harness test and topology are files the suite runs, with
    the commands that use them (so its first example cannot silently stop working)."""
    markers = [m for _, m, _, _ in blocks(ROOT / "README.md")]
    assert {"file thermostat.py", "file test_thermostat.py", "file topology.yaml", "run", "python"} <= set(markers)
