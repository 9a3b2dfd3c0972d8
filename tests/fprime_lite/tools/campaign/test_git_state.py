"""The git state a campaign manifest (and tools/studies.py's confirmations) records."""

import pathlib
import subprocess

from fprime_lite.tools.campaign.manifest import git_state


def _git(repo: pathlib.Path, *args: str) -> None:
    subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True)


def test_ignored_paths_do_not_make_the_tree_dirty(tmp_path):
    """MANIFEST-GIT-001: a change to a tracked file makes the tree dirty unless it lies under an ``ignore``
    path (tools/studies.py --confirm-resolution ignores docs/, where it writes); outside a work tree: None."""
    assert git_state(tmp_path) is None
    _git(tmp_path, "init", "-q")
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "manifest.json").write_text("{}\n")
    (tmp_path / "code.py").write_text("x = 1\n")
    _git(tmp_path, "add", ".")
    _git(tmp_path, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "one")
    assert git_state(tmp_path)["dirty"] is False
    (tmp_path / "docs" / "manifest.json").write_text('{"a": 1}\n')
    assert git_state(tmp_path)["dirty"] is True
    assert git_state(tmp_path, ignore=("docs",))["dirty"] is False
    (tmp_path / "code.py").write_text("x = 2\n")
    state = git_state(tmp_path, ignore=("docs",))
    assert state["dirty"] is True and len(state["commit"]) == 40
