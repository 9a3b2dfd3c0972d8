"""Confinement of file-service paths to a root (issue #16 finding 6)."""

import os

import pytest

from fprime_lite.osal.confine import Confinement, PathRefused


@pytest.fixture
def tree(tmp_path):
    root = tmp_path / "root"
    (root / "sub").mkdir(parents=True)
    (tmp_path / "secret").write_text("s")
    (root / "out_link").symlink_to(tmp_path)
    (root / "in_link").symlink_to(root / "sub")
    (root / "file_link").symlink_to(tmp_path / "secret")
    return tmp_path, root, Confinement(root)


@pytest.mark.parametrize("path", ["a.txt", "sub/a.txt", "sub/../a.txt", "in_link/a.txt", "./sub", "ROOT/sub/a.txt"])
def test_paths_inside_the_root_resolve_inside_it(tree, path):
    """CONFINE-1: relative paths, ``..`` that stays inside, links inside and absolute paths inside."""
    _, root, c = tree
    path = path.replace("ROOT", str(root))
    for resolved in (c.contents(path), c.entry(path)):
        assert resolved.startswith(str(root) + os.sep)


@pytest.mark.parametrize("path", ["../secret", "sub/../../secret", "/etc/passwd", "out_link/secret",
                                  "out_link/root/../secret", "TMP/secret"])
def test_paths_leaving_the_root_are_refused(tree, path):
    """CONFINE-2: ``..`` above the root, absolute paths elsewhere, links pointing outside."""
    tmp, _, c = tree
    path = path.replace("TMP", str(tmp))
    with pytest.raises(PathRefused) as refused:
        c.contents(path)
    assert refused.value.reason == "outside the root"
    with pytest.raises(PathRefused):
        c.entry(path)


def test_a_final_link_is_followed_for_contents_and_not_for_the_entry(tree):
    """CONFINE-3: ``file_link`` -> outside: reading it is refused; removing or replacing the link
    itself (the entry) is allowed and names the link."""
    _, root, c = tree
    with pytest.raises(PathRefused):
        c.contents("file_link")
    assert c.entry("file_link") == str(root / "file_link")


def test_the_root_itself_is_not_an_entry(tree):
    """CONFINE-4: removing or renaming the root is refused; a NUL byte is the OS's ValueError."""
    _, root, c = tree
    with pytest.raises(PathRefused):
        c.entry(".")
    with pytest.raises(ValueError):
        c.contents("a\0b")


def test_a_base_inside_a_wider_root_takes_relative_paths(tmp_path):
    """CONFINE-5: ``base`` (run --file-root: the working directory) resolves relative paths; absolute
    paths anywhere in the wider root are allowed; outside it they are still refused."""
    root = tmp_path / "root"
    base = root / "work"
    c = Confinement(root, base=base)
    assert c.contents("PrmDb.dat") == str(base.resolve() / "PrmDb.dat")
    assert c.entry(str(root / "other.txt")) == str(root.resolve() / "other.txt")
    with pytest.raises(PathRefused, match="outside the root"):
        c.contents(str(tmp_path / "elsewhere.txt"))
    with pytest.raises(ValueError, match="not inside the root"):
        Confinement(base, base=tmp_path)


def test_a_board_root_stands_in_for_the_boards_slash(tree):
    """CONFINE-6: on a board root (run --board-root) an absolute path names a file inside the root,
    a relative one resolves against it; ``/..``, links pointing outside and NUL bytes are refused as
    anywhere else; a board root resolves relative paths against itself only."""
    tmp, root, _ = tree
    c = Confinement(root, board=True)
    real = str(root.resolve())
    assert c.contents("/seq/no_op.bin") == real + "/seq/no_op.bin"
    assert c.entry("/seq") == real + "/seq"
    assert c.contents("seq/no_op.bin") == real + "/seq/no_op.bin"
    assert c.contents("/") == real
    for leaving in ("/../secret", "/sub/../../secret", "/out_link/secret", "/file_link"):
        with pytest.raises(PathRefused, match="outside the root"):
            c.contents(leaving)
    with pytest.raises(PathRefused):
        c.entry("/")
    assert Confinement(root).contents(str(root / "x")) == real + "/x"  # not a board: absolute stays absolute
    with pytest.raises(PathRefused):
        Confinement(root).contents("/seq/no_op.bin")
    with pytest.raises(ValueError, match="board root"):
        Confinement(root, base=root / "sub", board=True)
