"""Fixtures shared by tests in several folders."""

import pathlib
import subprocess
import sys

import pytest


@pytest.fixture
def killed_leftover():
    """``make(folder, name)``: write, in ``folder``, the temporary file a process killed while
    writing ``name`` there would have left (named as ``fprime_lite.osal.atomic`` names them, with
    the pid of a process that has exited); returns its path."""
    done = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True, check=True)
    pid = int(done.stdout)

    def make(folder: pathlib.Path, name: str) -> pathlib.Path:
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f".fprime-lite-tmp.{pid}.{name}.k1ll3d.part"
        path.write_bytes(b"half")
        return path

    return make


def hidden_names(folder: pathlib.Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


@pytest.fixture
def hidden():
    """``hidden(folder)``: the sorted names of the hidden files in ``folder``."""
    return hidden_names
