"""Rewrite the golden dictionaries from the current code (run it only after checking that the
change adds members on purpose and moves no existing name, id or format; see
tests/fprime_lite/deploy/test_dictionary_golden.py). The framework's own members are left out.

    python tests/data/dictionary/regenerate.py
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).parent
ROOT = HERE.parents[2]
sys.path.insert(0, str(ROOT / "tests" / "fprime_lite" / "deploy"))

from test_dictionary_golden import CASES, FRAMEWORK, _member  # noqa: E402

from fprime_lite.tools.cli import main  # noqa: E402


def regenerate() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        for topology, flags, golden in CASES:
            out = Path(tmp) / golden
            if main(["dict", str(ROOT / topology), "-o", str(out), *flags]) != 0:
                raise SystemExit(f"fprime-lite dict failed for {topology}")
            dictionary = json.loads(out.read_text())
            for key, names in FRAMEWORK.items():
                dictionary[key] = [e for e in dictionary[key] if _member(e) not in names]
            (HERE / golden).write_text(json.dumps(dictionary, indent=2) + "\n")


if __name__ == "__main__":
    regenerate()
